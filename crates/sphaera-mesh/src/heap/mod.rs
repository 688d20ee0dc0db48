//! Priority queues, with one ordering convention: an item's [`Priority`] is a key with a
//! total order, and the **highest priority pops first**.
//!
//! - [`MaxHeap`]: the standard binary heap (`std`'s `BinaryHeap`) of items ordered by
//!   their priority alone, for queues where stale entries are skipped when popped
//!   (branch and bound, pair merges).
//! - [`IndexedHeap`]: at most one item per id, replaced or removed in place, for
//!   priority processes that re-evaluate items constantly.
//!
//! Distances and errors are `f64`: [`TotalF64`] orders them by [`f64::total_cmp`], and
//! `std::cmp::Reverse` turns "smallest first" into a priority. Ties are broken inside the
//! key (a tuple compares field by field), so a queue built from the same input pops in
//! the same order on every run.
//!
//! # Examples
//!
//! ```
//! use std::cmp::Reverse;
//! use sphaera_mesh::heap::{HeapItem, IndexedHeap, MaxHeap, Priority, TotalF64};
//!
//! /// A job: the cheapest first, ties by the smaller id.
//! #[derive(Clone, Copy, Debug, PartialEq)]
//! struct Job { cost: f64, id: u32 }
//!
//! impl Priority for Job {
//!     type Key = (Reverse<TotalF64>, Reverse<u32>);
//!     fn priority(&self) -> Self::Key {
//!         (Reverse(TotalF64(self.cost)), Reverse(self.id))
//!     }
//! }
//!
//! impl HeapItem for Job {
//!     fn id(&self) -> u32 { self.id }
//! }
//!
//! let mut heap = IndexedHeap::new(10);
//! heap.set(Job { cost: 3.0, id: 1 });
//! heap.set(Job { cost: 1.0, id: 7 });
//! heap.set(Job { cost: 0.5, id: 1 }); // replaces id 1's item
//! assert_eq!(heap.len(), 2);
//! assert_eq!(heap.pop(), Some(Job { cost: 0.5, id: 1 }));
//! assert_eq!(heap.remove(7), Some(Job { cost: 1.0, id: 7 }));
//! assert!(heap.is_empty());
//!
//! let mut queue = MaxHeap::new();
//! queue.push(Job { cost: 2.0, id: 3 });
//! queue.push(Job { cost: 2.0, id: 1 });
//! queue.push(Job { cost: 9.0, id: 0 });
//! assert_eq!(queue.pop().map(|j| j.id), Some(1)); // cheapest, then smallest id
//! assert_eq!(queue.peek().map(|j| j.id), Some(3));
//! ```

mod indexed;
mod max_heap;

use std::cmp::Ordering;

pub use indexed::{HeapItem, IndexedHeap};
pub use max_heap::MaxHeap;

/// How an item is ordered in a queue: the item with the greatest key pops first.
pub trait Priority {
    /// The key, compared by its total order (a tuple compares field by field, so ties
    /// are broken by the later fields).
    type Key: Ord;

    /// The item's key.
    fn priority(&self) -> Self::Key;
}

/// An `f64` with the total order of [`f64::total_cmp`] (`-0.0 < 0.0`, NaNs at the ends),
/// to use distances and errors as priorities.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::heap::TotalF64;
///
/// assert!(TotalF64(-0.0) < TotalF64(0.0));
/// assert!(TotalF64(1.0) < TotalF64(f64::INFINITY));
/// assert_eq!(TotalF64(2.5).max(TotalF64(1.0)), TotalF64(2.5));
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct TotalF64(pub f64);

impl PartialEq for TotalF64 {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for TotalF64 {}

impl PartialOrd for TotalF64 {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for TotalF64 {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}
