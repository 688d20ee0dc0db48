//! An indexed 4-ary heap: at most one item per id, replaced or removed in place.

use super::Priority;

/// No heap slot.
const ABSENT: u32 = u32::MAX;

/// Children per node.
const ARITY: usize = 4;

/// An item of an [`IndexedHeap`]: its id (below the heap's id bound) and its
/// [`Priority`]. Items of different ids must never have equal priorities (break ties by
/// id), so the pop order is deterministic.
pub trait HeapItem: Priority + Copy {
    /// The id the item is filed under (one item per id).
    fn id(&self) -> u32;
}

/// Whether `a` pops before `b`.
fn before<E: Priority>(a: &E, b: &E) -> bool {
    a.priority() > b.priority()
}

/// A 4-ary heap (shallower than a binary one, so fewer cache misses on large heaps)
/// holding at most one item per id in `0..ids`, the highest
/// [`Priority`] first (see the [module docs](super)).
///
/// Priority processes re-evaluate items constantly (the simplifier's collapse candidates,
/// Meshsweeper's triangle intervals, sample elimination's weights). A lazy-deletion heap
/// grows with every re-evaluation; this one keeps one slot per id and moves the item to
/// its new place, so it stays as large as the set of current items and `remove` is
/// `O(log n)`.
#[derive(Clone, Debug)]
pub struct IndexedHeap<E> {
    heap: Vec<E>,
    /// Heap slot of each id, or [`ABSENT`].
    slot: Vec<u32>,
}

impl<E> Default for IndexedHeap<E> {
    /// An empty heap that holds no id.
    fn default() -> Self {
        Self {
            heap: Vec::new(),
            slot: Vec::new(),
        }
    }
}

impl<E: HeapItem> IndexedHeap<E> {
    /// An empty heap for ids below `ids`.
    pub fn new(ids: usize) -> Self {
        Self {
            heap: Vec::new(),
            slot: vec![ABSENT; ids],
        }
    }

    /// A heap of `items` (ids below `ids`; items with a larger id are dropped, and of
    /// items with the same id the last is kept), built in `O(n)`.
    pub fn from_items(ids: usize, items: impl IntoIterator<Item = E>) -> Self {
        let mut heap = Self::new(ids);
        for item in items {
            let Some(&s) = heap.slot.get(item.id() as usize) else {
                continue;
            };
            if s == ABSENT {
                heap.slot[item.id() as usize] = heap.heap.len() as u32;
                heap.heap.push(item);
            } else {
                heap.heap[s as usize] = item;
            }
        }
        for i in (0..heap.heap.len().div_ceil(ARITY)).rev() {
            heap.sift_down(i);
        }
        heap
    }

    /// Items held.
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether no item is held.
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }

    /// Removes every item (`O(len)`).
    pub fn clear(&mut self) {
        for item in &self.heap {
            if let Some(s) = self.slot.get_mut(item.id() as usize) {
                *s = ABSENT;
            }
        }
        self.heap.clear();
    }

    /// Whether an item is filed under `id`.
    pub fn contains(&self, id: u32) -> bool {
        self.slot.get(id as usize).is_some_and(|&s| s != ABSENT)
    }

    /// The item filed under `id`.
    pub fn get(&self, id: u32) -> Option<&E> {
        let s = *self.slot.get(id as usize)?;
        self.heap.get(s as usize)
    }

    /// The first item.
    pub fn first(&self) -> Option<&E> {
        self.heap.first()
    }

    /// The first item's children (the candidates for second place): every item but the
    /// first comes no earlier than the earlier of them.
    pub fn runners_up(&self) -> impl Iterator<Item = &E> {
        self.heap
            .get(1..(ARITY + 1).min(self.heap.len()))
            .unwrap_or(&[])
            .iter()
    }

    /// Removes and returns the first item.
    pub fn pop(&mut self) -> Option<E> {
        let top = *self.heap.first()?;
        self.remove_at(0);
        Some(top)
    }

    /// Inserts `item`, replacing the item of the same id; ignored if its id is out of
    /// range.
    pub fn set(&mut self, item: E) {
        let Some(&s) = self.slot.get(item.id() as usize) else {
            return;
        };
        let i = if s == ABSENT {
            self.heap.push(item);
            self.heap.len() - 1
        } else {
            self.heap[s as usize] = item;
            s as usize
        };
        self.slot[item.id() as usize] = i as u32;
        let i = self.sift_up(i);
        self.sift_down(i);
    }

    /// Removes and returns the item filed under `id`.
    pub fn remove(&mut self, id: u32) -> Option<E> {
        let s = *self.slot.get(id as usize)?;
        let item = *self.heap.get(s as usize)?;
        self.remove_at(s as usize);
        Some(item)
    }

    /// Bytes held (item capacity and slots).
    pub fn bytes(&self) -> usize {
        self.heap.capacity() * size_of::<E>() + self.slot.capacity() * size_of::<u32>()
    }

    /// Removes the item in heap slot `i` (`i < len`).
    fn remove_at(&mut self, i: usize) {
        let last = self.heap.len() - 1;
        self.heap.swap(i, last);
        if let Some(gone) = self.heap.pop() {
            self.slot[gone.id() as usize] = ABSENT;
        }
        if i < self.heap.len() {
            self.slot[self.heap[i].id() as usize] = i as u32;
            let i = self.sift_up(i);
            self.sift_down(i);
        }
    }

    /// Moves the item in slot `i` up to its place; returns its new slot.
    fn sift_up(&mut self, mut i: usize) -> usize {
        let item = self.heap[i];
        while i > 0 {
            let parent = (i - 1) / ARITY;
            if !before(&item, &self.heap[parent]) {
                break;
            }
            self.heap[i] = self.heap[parent];
            self.slot[self.heap[i].id() as usize] = i as u32;
            i = parent;
        }
        self.heap[i] = item;
        self.slot[item.id() as usize] = i as u32;
        i
    }

    /// Moves the item in slot `i` down to its place.
    fn sift_down(&mut self, mut i: usize) {
        let item = self.heap[i];
        let n = self.heap.len();
        loop {
            let first = ARITY * i + 1;
            if first >= n {
                break;
            }
            let mut child = first;
            for c in first + 1..(first + ARITY).min(n) {
                if before(&self.heap[c], &self.heap[child]) {
                    child = c;
                }
            }
            if !before(&self.heap[child], &item) {
                break;
            }
            self.heap[i] = self.heap[child];
            self.slot[self.heap[i].id() as usize] = i as u32;
            i = child;
        }
        self.heap[i] = item;
        self.slot[item.id() as usize] = i as u32;
    }
}

#[cfg(test)]
mod tests {
    use std::cmp::Reverse;

    use super::super::TotalF64;
    use super::*;
    use sphaera_tests::random::Lcg64;

    #[derive(Clone, Copy, Debug, PartialEq)]
    struct Item {
        key: f64,
        id: u32,
    }

    impl Priority for Item {
        type Key = (Reverse<TotalF64>, Reverse<u32>);
        fn priority(&self) -> Self::Key {
            (Reverse(TotalF64(self.key)), Reverse(self.id))
        }
    }

    impl HeapItem for Item {
        fn id(&self) -> u32 {
            self.id
        }
    }

    #[test]
    fn behaves_like_a_sorted_list_of_current_items() {
        let n = 300_u32;
        let initial = (0..n).step_by(3).map(|id| Item {
            key: f64::from(id % 17),
            id,
        });
        let mut heap = IndexedHeap::from_items(n as usize, initial.clone());
        let mut model: Vec<Option<f64>> = vec![None; n as usize];
        for item in initial {
            model[item.id as usize] = Some(item.key);
        }
        let mut rng = Lcg64::new(11);
        for step in 0..6000 {
            let r = rng.next_high31();
            let id = (r % u64::from(n)) as u32;
            match step % 5 {
                0 => {
                    assert_eq!(heap.remove(id).map(|e| e.key), model[id as usize]);
                    model[id as usize] = None;
                }
                1 => {
                    let popped = heap.pop();
                    if let Some(p) = popped {
                        model[p.id as usize] = None;
                    }
                }
                _ => {
                    let key = (r % 97) as f64;
                    heap.set(Item { key, id });
                    model[id as usize] = Some(key);
                }
            }
            let mut current: Vec<(f64, u32)> = model
                .iter()
                .enumerate()
                .filter_map(|(id, k)| k.map(|k| (k, id as u32)))
                .collect();
            current.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            assert_eq!(
                heap.first().map(|e| (e.key, e.id)),
                current.first().copied()
            );
            if let Some(second) = current.get(1) {
                let runner = heap
                    .runners_up()
                    .map(|e| e.key)
                    .fold(f64::INFINITY, f64::min);
                assert!(runner <= second.0);
            }
            assert_eq!(heap.len(), current.len());
            assert_eq!(heap.get(id).map(|e| e.key), model[id as usize]);
            assert_eq!(heap.contains(id), model[id as usize].is_some());
        }
        heap.set(Item { key: 1.0, id: n });
        assert!(!heap.contains(n));
        heap.clear();
        assert!(heap.is_empty() && heap.first().is_none());
    }
}
