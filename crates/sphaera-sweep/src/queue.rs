//! The priority queue of triangles: an indexed binary min-heap keyed by the lower end of
//! each triangle's distance interval, with at most one entry per triangle.
//!
//! Keys are stored *shifted* so that moving the query point never reorders the heap
//! (paper section 5.1): an entry computed when the total motion was `G₀` stores
//! `key = (d − ε) + G₀`; with the total motion now `G`, its interval's lower end is
//! `key − G`. Every interval widens by the same amount, so the order is unchanged.

use std::cmp::Reverse;

use sphaera_mesh::heap::{HeapItem, IndexedHeap, Priority, TotalF64};

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

impl Priority for Entry {
    type Key = (Reverse<TotalF64>, Reverse<u32>);

    /// The queue order: the lowest key first, then the lowest triangle (total and
    /// deterministic).
    fn priority(&self) -> Self::Key {
        (Reverse(TotalF64(self.key)), Reverse(self.triangle))
    }
}

impl HeapItem for Entry {
    fn id(&self) -> u32 {
        self.triangle
    }
}

/// The queue, at most one entry per triangle.
#[derive(Clone, Debug, Default)]
pub(crate) struct Queue {
    heap: IndexedHeap<Entry>,
}

impl Queue {
    /// An empty queue for triangle ids below `triangles`.
    pub(crate) fn new(triangles: usize) -> Self {
        Self {
            heap: IndexedHeap::new(triangles),
        }
    }

    /// Number of queued triangles.
    pub(crate) fn len(&self) -> usize {
        self.heap.len()
    }

    /// Removes every entry (`O(len)`).
    pub(crate) fn clear(&mut self) {
        self.heap.clear();
    }

    /// Whether `id` is queued.
    pub(crate) fn contains(&self, id: u32) -> bool {
        self.heap.contains(id)
    }

    /// The first entry.
    pub(crate) fn first(&self) -> Option<Entry> {
        self.heap.first().copied()
    }

    /// The smaller key of the first entry's two children: a lower bound on every entry
    /// but the first.
    pub(crate) fn second_key(&self) -> Option<f64> {
        self.heap.runners_up().map(|e| e.key).reduce(f64::min)
    }

    /// Inserts or replaces the entry of `entry.triangle`.
    pub(crate) fn set(&mut self, entry: Entry) {
        self.heap.set(entry);
    }

    /// Removes the entry of `triangle`, if queued.
    pub(crate) fn remove(&mut self, triangle: u32) -> Option<Entry> {
        self.heap.remove(triangle)
    }

    /// Bytes held (heap capacity and slots).
    pub(crate) fn bytes(&self) -> usize {
        self.heap.bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_tests::random::Lcg64;

    #[test]
    fn first_is_the_smallest_current_entry() {
        let n = 300_u32;
        let mut queue = Queue::new(n as usize);
        let mut model: Vec<Option<f64>> = vec![None; n as usize];
        let mut rng = Lcg64::new(11);
        for step in 0..5000 {
            let r = rng.next_high31();
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
