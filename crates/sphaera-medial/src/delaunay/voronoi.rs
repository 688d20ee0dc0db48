//! The Voronoi dual: a Voronoi vertex per finite tetrahedron (its circumcentre), Voronoi
//! edges between neighbouring tetrahedra, and the cell of each input point.

use glam::DVec3;

use super::{Delaunay, INFINITE, NONE, TetId};

/// The Voronoi cell of one point: the finite tetrahedra around it (their circumcentres are
/// the cell's vertices), and whether the cell is unbounded (the point is on the hull).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct VoronoiCell {
    /// Finite tetrahedra incident to the point, in discovery order.
    pub tetrahedra: Vec<TetId>,
    /// Whether the point is on the convex hull (its cell extends to infinity).
    pub unbounded: bool,
}

impl Delaunay {
    /// The circumcentre and circumradius of finite tetrahedron `t` (the Voronoi vertex it
    /// stands for, and its distance to the four forming points), or `None` for a ghost or
    /// a removed id.
    ///
    /// The centre is computed in `f64` relative to a corner; for a nearly flat tetrahedron
    /// it is far away and approximate, like the true one.
    #[must_use]
    pub fn circumsphere(&self, t: TetId) -> Option<(DVec3, f64)> {
        if !self.is_finite(t) {
            return None;
        }
        let [a, b, c, d] = self.corners(self.tets[t as usize]);
        Some(circumsphere(a, b, c, d))
    }

    /// The Voronoi cell of vertex `v`; `None` if `v` is a duplicate or not a vertex id.
    #[must_use]
    pub fn voronoi_cell(&self, v: u32) -> Option<VoronoiCell> {
        let mut cell = VoronoiCell::default();
        self.voronoi_cell_into(v, &mut cell).then_some(cell)
    }

    /// [`Delaunay::voronoi_cell`] into a reused buffer; returns `false` (and leaves `cell`
    /// empty) for a duplicate or an invalid id.
    pub fn voronoi_cell_into(&self, v: u32, cell: &mut VoronoiCell) -> bool {
        cell.tetrahedra.clear();
        cell.unbounded = false;
        let Some(&start) = self.vertex_tet.get(v as usize) else {
            return false;
        };
        if start == NONE {
            return false;
        }
        self.around_vertex(start, v, |t, vertices| {
            if vertices.contains(&INFINITE) {
                cell.unbounded = true;
            } else {
                cell.tetrahedra.push(t);
            }
        });
        true
    }

    /// Appends to `out` the vertices joined to `v` by an edge (its Delaunay neighbours,
    /// whose Voronoi cells share a face with `v`'s); nothing for a duplicate or an
    /// invalid id.
    pub fn vertex_neighbors_into(&self, v: u32, out: &mut Vec<u32>) {
        let start = out.len();
        let Some(&first) = self.vertex_tet.get(v as usize) else {
            return;
        };
        if first == NONE {
            return;
        }
        self.around_vertex(first, v, |_, vertices| {
            for u in vertices {
                if u != v && u != INFINITE && !out[start..].contains(&u) {
                    out.push(u);
                }
            }
        });
    }

    /// Calls `visit` on every live tetrahedron incident to `v` (finite and ghost), found
    /// by a depth-first search from `first` through the faces that contain `v`.
    fn around_vertex(&self, first: TetId, v: u32, mut visit: impl FnMut(TetId, [u32; 4])) {
        let mut seen: Vec<TetId> = vec![first];
        let mut stack = vec![first];
        while let Some(t) = stack.pop() {
            let vertices = self.tets[t as usize];
            visit(t, vertices);
            for (i, &u) in vertices.iter().enumerate() {
                if u == v {
                    continue;
                }
                let n = self.adjacent[t as usize][i];
                if !seen.contains(&n) {
                    seen.push(n);
                    stack.push(n);
                }
            }
        }
    }

    /// The vertex nearest to `p` (Euclidean; ties to the first found), by a greedy walk
    /// on the Delaunay graph from vertex `start` (which is exact: a vertex that is not the
    /// nearest always has a nearer neighbour). `None` only for an invalid or duplicate
    /// `start`.
    #[must_use]
    pub fn nearest_vertex(&self, p: DVec3, start: u32) -> Option<u32> {
        if self
            .vertex_tet
            .get(start as usize)
            .is_none_or(|&t| t == NONE)
        {
            return None;
        }
        let mut current = start;
        let mut best = (self.points[current as usize] - p).length_squared();
        let mut neighbours = Vec::new();
        loop {
            neighbours.clear();
            self.vertex_neighbors_into(current, &mut neighbours);
            let mut next = current;
            for &u in &neighbours {
                let d = (self.points[u as usize] - p).length_squared();
                if d < best {
                    best = d;
                    next = u;
                }
            }
            if next == current {
                return Some(current);
            }
            current = next;
        }
    }

    /// Whether vertex `v` is on the convex hull.
    #[must_use]
    pub fn is_hull_vertex(&self, v: u32) -> bool {
        self.voronoi_cell(v).is_some_and(|c| c.unbounded)
    }
}

/// The sphere through four points, unchecked: the corners of a Delaunay tetrahedron are
/// never coplanar, and the radius is the distance to `a`. The checked, covering version
/// for arbitrary input is `sphaera_mesh::geometry::circumsphere`.
pub(crate) fn circumsphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> (DVec3, f64) {
    let (ab, ac, ad) = (b - a, c - a, d - a);
    let (bc, cd) = (ac.cross(ad), ad.cross(ab));
    let db = ab.cross(ac);
    let denominator = 2.0 * ab.dot(bc);
    let offset = (ab.length_squared() * bc + ac.length_squared() * cd + ad.length_squared() * db)
        / denominator;
    (a + offset, offset.length())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circumsphere_passes_through_the_four_points() {
        let p = [
            DVec3::new(0.3, -1.0, 2.0),
            DVec3::new(1.5, 0.2, -0.4),
            DVec3::new(-0.7, 0.9, 0.1),
            DVec3::new(0.2, 0.4, 1.3),
        ];
        let (center, radius) = circumsphere(p[0], p[1], p[2], p[3]);
        for q in p {
            assert!(((q - center).length() - radius).abs() < 1e-12);
        }
    }
}
