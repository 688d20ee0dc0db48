//! The candidate queue: an indexed binary min-heap holding at most one candidate per
//! vertex, updated in place when a vertex is re-evaluated.
//!
//! It pops candidates in exactly the order of a lazy-deletion heap keyed by
//! `(cost, vertex, half-edge)` that skips superseded entries: each vertex has one current
//! candidate, and candidates of different vertices never compare equal. Keeping one entry
//! per vertex keeps the heap small (a few hundred kilobytes for a 70k-triangle mesh)
//! instead of growing with every re-evaluation.

use std::cmp::Reverse;

use sphaera_mesh::heap::{HeapItem, IndexedHeap, Priority, TotalF64};
use sphaera_mesh::topology::HalfEdgeId;

/// A queued candidate: the cheapest collapse out of `vertex` when it was evaluated.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub cost: f64,
    pub vertex: u32,
    pub halfedge: u32,
}

impl Priority for Candidate {
    type Key = (Reverse<TotalF64>, Reverse<u32>, Reverse<u32>);

    /// The queue order: the lowest cost first, then the lowest vertex (total and
    /// deterministic; the half-edge never decides, as vertices are unique).
    fn priority(&self) -> Self::Key {
        (
            Reverse(TotalF64(self.cost)),
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
}

impl Queue {
    /// The queue holding `initial[u]` for every vertex `u`.
    pub(super) fn new(initial: &[Option<(f64, HalfEdgeId)>]) -> Self {
        let items = initial.iter().enumerate().filter_map(|(u, c)| {
            c.map(|(cost, h)| Candidate {
                cost,
                vertex: u as u32,
                halfedge: h.0,
            })
        });
        Self {
            heap: IndexedHeap::from_items(initial.len(), items),
        }
    }

    /// The current candidate of vertex `u`.
    pub(super) fn get(&self, u: u32) -> Option<(f64, HalfEdgeId)> {
        self.heap.get(u).map(|c| (c.cost, HalfEdgeId(c.halfedge)))
    }

    /// Removes and returns the first candidate.
    pub(super) fn pop(&mut self) -> Option<Candidate> {
        self.heap.pop()
    }

    /// Makes `candidate` the current candidate of vertex `u` (`None` removes it).
    pub(super) fn set(&mut self, u: u32, candidate: Option<(f64, HalfEdgeId)>) {
        match candidate {
            None => {
                self.heap.remove(u);
            }
            Some((cost, h)) => self.heap.set(Candidate {
                cost,
                vertex: u,
                halfedge: h.0,
            }),
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
        let initial: Vec<Option<(f64, HalfEdgeId)>> = (0..n)
            .map(|_| {
                let r = rng.next_high31();
                (!r.is_multiple_of(5)).then_some(((r % 17) as f64, HalfEdgeId((r % 1000) as u32)))
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
                    .filter_map(|(v, c)| c.map(|(cost, h)| (cost, v as u32, h.0)))
                    .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let got = queue.pop().map(|c| (c.cost, c.vertex, c.halfedge));
                assert_eq!(got, expected);
                if let Some((_, v, _)) = expected {
                    model[v as usize] = None;
                }
            } else {
                let c = (!r.is_multiple_of(4))
                    .then_some(((r % 13) as f64, HalfEdgeId((r % 77) as u32)));
                queue.set(u, c);
                model[u as usize] = c;
            }
            for v in 0..n {
                assert_eq!(queue.get(v), model[v as usize]);
            }
        }
    }
}
