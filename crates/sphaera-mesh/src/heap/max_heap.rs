//! A binary max-heap of items ordered by their priority alone.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::Priority;

/// A binary heap (`std`'s `BinaryHeap`) of items, the highest [`Priority`] first; fields
/// outside the priority ride along and are never compared. See the
/// [module docs](super) for an example.
#[derive(Clone, Debug)]
pub struct MaxHeap<T: Priority> {
    heap: BinaryHeap<ByPriority<T>>,
}

impl<T: Priority> Default for MaxHeap<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Priority> MaxHeap<T> {
    /// An empty heap.
    #[must_use]
    pub fn new() -> Self {
        Self {
            heap: BinaryHeap::new(),
        }
    }

    /// Adds `item`.
    pub fn push(&mut self, item: T) {
        self.heap.push(ByPriority(item));
    }

    /// Removes and returns the item of highest priority.
    pub fn pop(&mut self) -> Option<T> {
        self.heap.pop().map(|ByPriority(item)| item)
    }

    /// The item of highest priority.
    #[must_use]
    pub fn peek(&self) -> Option<&T> {
        self.heap.peek().map(|ByPriority(item)| item)
    }

    /// Removes every item.
    pub fn clear(&mut self) {
        self.heap.clear();
    }

    /// Every item, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = &T> {
        self.heap.iter().map(|ByPriority(item)| item)
    }

    /// Items held.
    #[must_use]
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether no item is held.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }
}

impl<T: Priority> Extend<T> for MaxHeap<T> {
    fn extend<I: IntoIterator<Item = T>>(&mut self, items: I) {
        self.heap.extend(items.into_iter().map(ByPriority));
    }
}

impl<T: Priority> FromIterator<T> for MaxHeap<T> {
    fn from_iter<I: IntoIterator<Item = T>>(items: I) -> Self {
        Self {
            heap: items.into_iter().map(ByPriority).collect(),
        }
    }
}

/// An item ordered by its priority.
#[derive(Clone, Debug)]
struct ByPriority<T>(T);

impl<T: Priority> PartialEq for ByPriority<T> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<T: Priority> Eq for ByPriority<T> {}

impl<T: Priority> PartialOrd for ByPriority<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<T: Priority> Ord for ByPriority<T> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.priority().cmp(&other.0.priority())
    }
}
