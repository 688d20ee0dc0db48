//! The candidate queue: an indexed binary min-heap holding at most one candidate per
//! vertex, updated in place when a vertex is re-evaluated.
//!
//! It pops candidates in exactly the order of a lazy-deletion heap keyed by
//! `(cost, vertex, half-edge)` that skips superseded entries: each vertex has one current
//! candidate, and candidates of different vertices never compare equal. Keeping one entry
//! per vertex keeps the heap small (one entry per vertex) instead of growing with every
//! re-evaluation.

use std::cmp::Reverse;

use sphaera_mesh::heap::{HeapItem, IndexedHeap, Priority, TotalF64};
use sphaera_mesh::topology::HalfEdgeId;

/// A vertex's cheapest collapse when it was evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Entry {
    /// The queue key: the radius over the vertex's tolerance weight.
    pub key: f64,
    /// The radius the kept vertex gets.
    pub radius: f64,
    /// The collapse.
    pub halfedge: HalfEdgeId,
    /// Whether its topology was checked when it was evaluated (see
    /// [`Topology`](super::Topology)).
    pub checked: bool,
}

/// A queued candidate: the cheapest collapse out of `vertex` when it was evaluated (its
/// key and half-edge; the rest of its [`Entry`] is kept beside the heap, so that heap
/// entries stay 16 bytes).
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub key: f64,
    pub vertex: u32,
    pub halfedge: u32,
}

impl Priority for Candidate {
    type Key = (Reverse<TotalF64>, Reverse<u32>, Reverse<u32>);

    /// The queue order: the lowest key first, then the lowest vertex (total and
    /// deterministic; the half-edge never decides, as vertices are unique).
    fn priority(&self) -> Self::Key {
        (
            Reverse(TotalF64(self.key)),
            Reverse(self.vertex),
            Reverse(self.halfedge),
        )
    }
}

impl HeapItem for Candidate {
    fn id(&self) -> u32 {
        self.vertex
    }
}

/// The queue of current candidates, at most one per vertex.
#[derive(Debug)]
pub(super) struct Queue {
    heap: IndexedHeap<Candidate>,
    /// Per vertex, the radius and topology flag of its queued candidate.
    rest: Vec<(f64, bool)>,
}

impl Queue {
    /// The queue holding `initial[u]` for every vertex `u`.
    pub(super) fn new(initial: &[Option<Entry>]) -> Self {
        let rest = initial
            .iter()
            .map(|e| e.map_or((0.0, false), |e| (e.radius, e.checked)))
            .collect();
        let items = initial.iter().enumerate().filter_map(|(u, c)| {
            c.map(|entry| Candidate {
                key: entry.key,
                vertex: u as u32,
                halfedge: entry.halfedge.0,
            })
        });
        Self {
            heap: IndexedHeap::from_items(initial.len(), items),
            rest,
        }
    }

    /// The entry of a candidate of this queue.
    fn entry(&self, c: &Candidate) -> Entry {
        let (radius, checked) = self
            .rest
            .get(c.vertex as usize)
            .copied()
            .unwrap_or_default();
        Entry {
            key: c.key,
            radius,
            halfedge: HalfEdgeId(c.halfedge),
            checked,
        }
    }

    /// The current candidate of vertex `u`.
    #[cfg(test)]
    pub(super) fn get(&self, u: u32) -> Option<Entry> {
        self.heap.get(u).map(|c| self.entry(c))
    }

    /// The key of vertex `u`'s current candidate (without reading the rest of its entry).
    pub(super) fn key(&self, u: u32) -> Option<f64> {
        self.heap.get(u).map(|c| c.key)
    }

    /// The first candidate's vertex and key, left in place.
    pub(super) fn first(&self) -> Option<(u32, f64)> {
        self.heap.first().map(|c| (c.vertex, c.key))
    }

    /// Removes and returns the first candidate: its vertex and entry.
    pub(super) fn pop(&mut self) -> Option<(u32, Entry)> {
        let c = self.heap.pop()?;
        Some((c.vertex, self.entry(&c)))
    }

    /// Makes `entry` the current candidate of vertex `u` (`None` removes it).
    pub(super) fn set(&mut self, u: u32, entry: Option<Entry>) {
        match entry {
            None => {
                self.heap.remove(u);
            }
            Some(entry) => {
                if let Some(r) = self.rest.get_mut(u as usize) {
                    *r = (entry.radius, entry.checked);
                }
                self.heap.set(Candidate {
                    key: entry.key,
                    vertex: u,
                    halfedge: entry.halfedge.0,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_tests::random::Lcg64;

    #[test]
    fn pops_like_a_sorted_list_of_current_candidates() {
        let n = 200_u32;
        let mut rng = Lcg64::new(7);
        let entry = |key: f64, h: u64| Entry {
            key,
            radius: key,
            halfedge: HalfEdgeId(h as u32),
            checked: true,
        };
        let initial: Vec<Option<Entry>> = (0..n)
            .map(|_| {
                let r = rng.next_high31();
                (!r.is_multiple_of(5)).then_some(entry((r % 17) as f64, r % 1000))
            })
            .collect();
        let mut queue = Queue::new(&initial);
        let mut model = initial.clone();
        for step in 0..3000 {
            let r = rng.next_high31();
            let u = (r % u64::from(n)) as u32;
            if step % 3 == 0 {
                let expected = model
                    .iter()
                    .enumerate()
                    .filter_map(|(v, c)| c.map(|e| (e.key, v as u32, e.halfedge.0)))
                    .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let got = queue.pop().map(|(v, e)| (e.key, v, e.halfedge.0));
                assert_eq!(got, expected);
                if let Some((_, v, _)) = expected {
                    model[v as usize] = None;
                }
            } else {
                let c = (!r.is_multiple_of(4)).then_some(entry((r % 13) as f64, r % 77));
                queue.set(u, c);
                model[u as usize] = c;
            }
            for v in 0..n {
                assert_eq!(queue.get(v), model[v as usize]);
            }
        }
    }
}
