//! An indexed binary max-heap over items `0..m` keyed by an external weight array, with
//! "weight decreased" updates (what sample elimination needs; a lazy `BinaryHeap` with
//! stale entries is several times slower there).

use std::cmp::Ordering;

/// Max-heap of item indices ordered by `(weights[i], i)`.
#[derive(Debug)]
pub(super) struct IndexedMaxHeap {
    /// Heap array of items.
    heap: Vec<u32>,
    /// `position[i]` = where item `i` sits in `heap` (`u32::MAX` once popped).
    position: Vec<u32>,
}

/// Heap order: heavier first, then higher index (any fixed order keeps it deterministic).
fn above(weights: &[f64], a: u32, b: u32) -> bool {
    weights[a as usize]
        .total_cmp(&weights[b as usize])
        .then(a.cmp(&b))
        == Ordering::Greater
}

impl IndexedMaxHeap {
    /// A heap of all items `0..weights.len()` (which must fit a `u32`).
    pub fn new(weights: &[f64]) -> Self {
        let m = weights.len();
        let mut heap = Self {
            heap: (0..m as u32).collect(),
            position: (0..m as u32).collect(),
        };
        for p in (0..m / 2).rev() {
            heap.sift_down(weights, p);
        }
        heap
    }

    /// Removes and returns the heaviest item.
    pub fn pop(&mut self, weights: &[f64]) -> Option<usize> {
        let top = *self.heap.first()?;
        let last = self.heap.pop()?;
        if !self.heap.is_empty() {
            self.heap[0] = last;
            self.position[last as usize] = 0;
            self.sift_down(weights, 0);
        }
        self.position[top as usize] = u32::MAX;
        Some(top as usize)
    }

    /// Restores the order after `weights[item]` decreased (no-op for a popped item).
    pub fn decreased(&mut self, weights: &[f64], item: usize) {
        match self.position.get(item) {
            Some(&p) if p != u32::MAX => self.sift_down(weights, p as usize),
            _ => {}
        }
    }

    fn sift_down(&mut self, weights: &[f64], mut p: usize) {
        let n = self.heap.len();
        loop {
            let (l, r) = (2 * p + 1, 2 * p + 2);
            let mut best = p;
            if l < n && above(weights, self.heap[l], self.heap[best]) {
                best = l;
            }
            if r < n && above(weights, self.heap[r], self.heap[best]) {
                best = r;
            }
            if best == p {
                return;
            }
            self.heap.swap(p, best);
            self.position[self.heap[p] as usize] = p as u32;
            self.position[self.heap[best] as usize] = best as u32;
            p = best;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_in_weight_order_with_decreases() {
        let mut weights = vec![3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0];
        let mut heap = IndexedMaxHeap::new(&weights);
        assert_eq!(heap.pop(&weights), Some(5));
        weights[4] = 0.5;
        heap.decreased(&weights, 4);
        weights[7] = 1.0;
        heap.decreased(&weights, 7);
        let mut order = Vec::new();
        while let Some(i) = heap.pop(&weights) {
            order.push(i);
            heap.decreased(&weights, i); // no-op on a popped item
        }
        // 4.0 (2), 3.0 (0), 2.0 (6), then the 1.0 ties by higher index, then 0.5.
        assert_eq!(order, vec![2, 0, 6, 7, 3, 1, 4]);
    }
}
