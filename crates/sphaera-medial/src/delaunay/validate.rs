//! A full consistency check of the data structure and the Delaunay property, used by the
//! tests and available to callers who want proof.

use super::predicates::orient;
use super::{DEAD, Delaunay, INFINITE, NONE, TetId};
use crate::{DelaunayError, Violation};

impl Delaunay {
    /// Checks every invariant: each live tetrahedron has four distinct vertices (at most
    /// one of them [`INFINITE`]); finite ones are positively oriented
    /// (no flat tetrahedra); neighbourhood is symmetric and neighbours share exactly the
    /// face between them; each non-duplicate vertex knows an incident tetrahedron; and every
    /// face is locally Delaunay under the perturbation (the fourth vertex of each neighbour
    /// is not in conflict), which implies the whole tetrahedralization is Delaunay and the
    /// hull convex.
    ///
    /// # Errors
    ///
    /// [`DelaunayError::Invalid`] naming the first violation.
    ///
    /// # Performance
    ///
    /// `O(n)` predicates: a few times the cost of building.
    pub fn validate(&self) -> Result<(), DelaunayError> {
        let fail = |violation: Violation| Err(DelaunayError::Invalid(violation));
        for (t, &vertices) in self.tets.iter().enumerate() {
            if vertices[0] == DEAD {
                continue;
            }
            let t = t as TetId;
            let infinite = vertices.iter().filter(|&&v| v == INFINITE).count();
            let mut sorted = vertices;
            sorted.sort_unstable();
            if infinite > 1 || sorted.windows(2).any(|w| w[0] == w[1]) {
                return fail(Violation::BadVertices {
                    tetrahedron: t,
                    vertices,
                });
            }
            if infinite == 0 {
                let [a, b, c, d] = self.corners(vertices);
                if orient(a, b, c, d) <= 0.0 {
                    return fail(Violation::NotPositive {
                        tetrahedron: t,
                        vertices,
                    });
                }
            }
            for i in 0..4 {
                let n = self.adjacent[t as usize][i];
                if n == NONE || !self.is_live(n) {
                    return fail(Violation::MissingNeighbour {
                        tetrahedron: t,
                        face: i,
                    });
                }
                let backs = self.adjacent[n as usize]
                    .iter()
                    .filter(|&&x| x == t)
                    .count();
                if backs != 1 {
                    return fail(Violation::AsymmetricNeighbours {
                        tetrahedron: t,
                        neighbour: n,
                    });
                }
                let Some(back) = self.adjacent[n as usize].iter().position(|&x| x == t) else {
                    continue;
                };
                let mut ours: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| vertices[k]).collect();
                let theirs_all = self.tets[n as usize];
                let mut theirs: Vec<u32> = (0..4)
                    .filter(|&k| k != back)
                    .map(|k| theirs_all[k])
                    .collect();
                ours.sort_unstable();
                theirs.sort_unstable();
                if ours != theirs {
                    return fail(Violation::NoSharedFace {
                        tetrahedron: t,
                        neighbour: n,
                    });
                }
                let apex = theirs_all[back];
                if apex != INFINITE && self.conflicts(t, self.points[apex as usize]) {
                    return fail(Violation::NotLocallyDelaunay {
                        tetrahedron: t,
                        neighbour: n,
                        apex,
                    });
                }
            }
        }
        for (v, &t) in self.vertex_tet.iter().enumerate() {
            let duplicate = self.duplicate_of[v] != NONE;
            if duplicate != (t == NONE) {
                return fail(Violation::DuplicateIncidence { vertex: v });
            }
            if !duplicate && (!self.is_live(t) || !self.tets[t as usize].contains(&(v as u32))) {
                return fail(Violation::WrongIncidence {
                    vertex: v,
                    tetrahedron: t,
                });
            }
        }
        Ok(())
    }
}
