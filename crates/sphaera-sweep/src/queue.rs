//! The priority queue of triangles: an indexed binary min-heap keyed by the lower end of
//! each triangle's distance interval, with at most one entry per triangle.
//!
//! Keys are stored *shifted* so that moving the query point never reorders the heap
//! (paper section 5.1): an entry computed when the total motion was `G₀` stores
//! `key = (d − ε) + G₀`; with the total motion now `G`, its interval's lower end is
//! `key − G`. Every interval widens by the same amount, so the order is unchanged.

use std::cmp::Ordering;

/// No heap slot.
const ABSENT: u32 = u32::MAX;

/// A queued triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Entry {
    /// Shifted lower bound (see the module docs).
    pub key: f64,
    /// Hierarchy triangle id.
    pub triangle: u32,
    /// The motion generation the distance was computed at (older: "dirty").
    pub stamp: u32,
}

impl Entry {
    /// The queue order: the lowest key first, then the lowest triangle (total and
    /// deterministic).
    fn before(&self, other: &Self) -> bool {
        self.key
            .total_cmp(&other.key)
            .then(self.triangle.cmp(&other.triangle))
            == Ordering::Less
    }
}

/// The queue, at most one entry per triangle.
#[derive(Clone, Debug, Default)]
pub(crate) struct Queue {
    heap: Vec<Entry>,
    /// Heap slot of each triangle, or [`ABSENT`].
    slot: Vec<u32>,
}

impl Queue {
    /// An empty queue for triangle ids below `triangles`.
    pub(crate) fn new(triangles: usize) -> Self {
        Self {
            heap: Vec::new(),
            slot: vec![ABSENT; triangles],
        }
    }

    /// Number of queued triangles.
    pub(crate) fn len(&self) -> usize {
        self.heap.len()
    }

    /// Removes every entry (`O(len)`).
    pub(crate) fn clear(&mut self) {
        for e in &self.heap {
            if let Some(s) = self.slot.get_mut(e.triangle as usize) {
                *s = ABSENT;
            }
        }
        self.heap.clear();
    }

    /// Whether `id` is queued.
    pub(crate) fn contains(&self, id: u32) -> bool {
        self.slot.get(id as usize).is_some_and(|&s| s != ABSENT)
    }

    /// The first entry.
    pub(crate) fn first(&self) -> Option<Entry> {
        self.heap.first().copied()
    }

    /// The smaller key of the first entry's two children: a lower bound on every entry
    /// but the first.
    pub(crate) fn second_key(&self) -> Option<f64> {
        match (self.heap.get(1), self.heap.get(2)) {
            (Some(a), Some(b)) => Some(a.key.min(b.key)),
            (Some(a), None) => Some(a.key),
            _ => None,
        }
    }

    /// Inserts or replaces the entry of `entry.triangle`.
    pub(crate) fn set(&mut self, entry: Entry) {
        let Some(&i) = self.slot.get(entry.triangle as usize) else {
            return;
        };
        let i = if i == ABSENT {
            self.heap.push(entry);
            self.heap.len() - 1
        } else {
            self.heap[i as usize] = entry;
            i as usize
        };
        self.slot[entry.triangle as usize] = i as u32;
        let i = self.sift_up(i);
        self.sift_down(i);
    }

    /// Removes the entry of `triangle`, if queued.
    pub(crate) fn remove(&mut self, triangle: u32) -> Option<Entry> {
        let i = *self.slot.get(triangle as usize)?;
        if i == ABSENT {
            return None;
        }
        let entry = self.heap[i as usize];
        self.remove_at(i as usize);
        Some(entry)
    }

    /// Removes the entry in heap slot `i`.
    fn remove_at(&mut self, i: usize) {
        let last = self.heap.len() - 1;
        self.heap.swap(i, last);
        if let Some(gone) = self.heap.pop() {
            self.slot[gone.triangle as usize] = ABSENT;
        }
        if i < self.heap.len() {
            self.slot[self.heap[i].triangle as usize] = i as u32;
            let i = self.sift_up(i);
            self.sift_down(i);
        }
    }

    /// Moves the entry in slot `i` up to its place; returns its new slot.
    fn sift_up(&mut self, mut i: usize) -> usize {
        let e = self.heap[i];
        while i > 0 {
            let parent = (i - 1) / 2;
            if !e.before(&self.heap[parent]) {
                break;
            }
            self.heap[i] = self.heap[parent];
            self.slot[self.heap[i].triangle as usize] = i as u32;
            i = parent;
        }
        self.heap[i] = e;
        self.slot[e.triangle as usize] = i as u32;
        i
    }

    /// Moves the entry in slot `i` down to its place.
    fn sift_down(&mut self, mut i: usize) {
        let e = self.heap[i];
        let n = self.heap.len();
        loop {
            let left = 2 * i + 1;
            if left >= n {
                break;
            }
            let right = left + 1;
            let child = if right < n && self.heap[right].before(&self.heap[left]) {
                right
            } else {
                left
            };
            if !self.heap[child].before(&e) {
                break;
            }
            self.heap[i] = self.heap[child];
            self.slot[self.heap[i].triangle as usize] = i as u32;
            i = child;
        }
        self.heap[i] = e;
        self.slot[e.triangle as usize] = i as u32;
    }

    /// Bytes held (heap capacity and slots).
    pub(crate) fn bytes(&self) -> usize {
        self.heap.capacity() * size_of::<Entry>() + self.slot.capacity() * size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic pseudo-random sequence.
    fn lcg(state: &mut u64) -> u64 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        *state >> 33
    }

    #[test]
    fn first_is_the_smallest_current_entry() {
        let n = 300_u32;
        let mut queue = Queue::new(n as usize);
        let mut model: Vec<Option<f64>> = vec![None; n as usize];
        let mut state = 11;
        for step in 0..5000 {
            let r = lcg(&mut state);
            let t = (r % u64::from(n)) as u32;
            if step % 4 == 0 {
                assert_eq!(queue.remove(t).map(|e| e.key), model[t as usize]);
                model[t as usize] = None;
            } else {
                let key = (r % 97) as f64;
                queue.set(Entry {
                    key,
                    triangle: t,
                    stamp: 0,
                });
                model[t as usize] = Some(key);
            }
            let expected = model
                .iter()
                .enumerate()
                .filter_map(|(t, k)| k.map(|k| (k, t as u32)))
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            assert_eq!(queue.first().map(|e| (e.key, e.triangle)), expected);
            let mut keys: Vec<f64> = model.iter().flatten().copied().collect();
            keys.sort_by(f64::total_cmp);
            if keys.len() >= 2 {
                assert!(queue.second_key().is_some_and(|k| k <= keys[1]));
            }
            assert_eq!(queue.len(), keys.len());
        }
        queue.clear();
        assert_eq!(queue.len(), 0);
        assert!(queue.first().is_none());
    }
}
