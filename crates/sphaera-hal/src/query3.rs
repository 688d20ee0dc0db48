//! Point inclusion for 3D HAL trees: the crossing parity of an axis-aligned ray from the
//! point, moved symbolically off every edge and vertex, counting only the faces of patches
//! whose bounding box and volume the ray may meet, with exact predicates; and its
//! brute-force reference.
//!
//! The paper's section 5.1 goes further: it replaces a patch by its approximating
//! triangle when the point is outside the patch's bounding volume. That is exact only
//! when the triangles kept form a closed polyhedron whose sides follow the same edge
//! paths as the patches' boundaries, and the paper's own construction breaks that: it
//! discards the triangles whose paths coalesce, which opens holes in the levels. Keeping
//! them instead (as "folds", split along with their neighbours) closes every level, but
//! they swamp the tree on `spot.obj` (most nodes are folds, a coarse level has more
//! triangles than the mesh, and some folds never resolve; the counts are in the section
//! *HAL trees (`sphaera-hal`, issue 17)*, paragraph *Watertight levels*, of
//! `docs/benchmarks.md` in the repository). The closed meshes of [`HalTree3::level`] fill
//! the holes with fans, which is right for a picture and gives no inclusion guarantee. So
//! here the bounding volumes only cull, and the answer is always the exact one.

use glam::DVec3;
use sphaera_mesh::{Aabb, TriMesh};

use crate::{Containment, HalTree3};

fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// The ray of a query: from the point along coordinate axis `axis` (0, 1, 2 for x, y, z),
/// toward `+∞` when `positive`, else toward `−∞`.
///
/// The point is moved symbolically (Simulation of Simplicity) by `(ε, ε²)` along the next
/// two axes in cyclic order, `u = axis + 1` and `v = axis + 2` (mod 3), for an infinitely
/// small `ε > 0`: the moved ray is parallel to no face it could cross and passes through
/// no edge and no vertex, so its crossing parity is the answer for every point off the
/// surface, whatever the mesh (lattice-aligned CAD parts included). Only signs of exact
/// determinants and comparisons of coordinates decide it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct AxisRay {
    pub(crate) axis: usize,
    pub(crate) positive: bool,
}

impl AxisRay {
    /// The axis-aligned ray from `x` (inside the closed box `bounds`) with the shortest way
    /// out of the box (the lowest axis, then `+`, on ties): the tree and the brute force
    /// shoot the same one.
    pub(crate) fn shortest(bounds: &Aabb, x: DVec3) -> Self {
        let mut best = (
            f64::INFINITY,
            Self {
                axis: 0,
                positive: true,
            },
        );
        for axis in 0..3 {
            for positive in [true, false] {
                let way = if positive {
                    bounds.max[axis] - x[axis]
                } else {
                    x[axis] - bounds.min[axis]
                };
                if way < best.0 {
                    best = (way, Self { axis, positive });
                }
            }
        }
        best.1
    }

    /// The two axes across the ray, `(axis + 1, axis + 2)` mod 3 (the projection plane,
    /// oriented so that its orientation is the normal's component along the ray's axis).
    pub(crate) fn across(self) -> (usize, usize) {
        ((self.axis + 1) % 3, (self.axis + 2) % 3)
    }
}

/// The point of a query lies on the surface (on a closed face).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct OnSurface;

/// The sign of `orient2d(a, b, q)` for the query point `q` moved to `q + (ε, ε²)`: the
/// exact sign when it is not zero, else the sign of the perturbation's first non-zero
/// term (`a.y − b.y` for `ε`, `b.x − a.x` for `ε²`; the determinant is linear in `q`).
/// Zero only for an edge that projects to a point (parallel to the ray).
fn perturbed_sign(d: f64, a: robust::Coord<f64>, b: robust::Coord<f64>) -> i8 {
    let sign = |v: f64| {
        if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        }
    };
    match sign(d) {
        0 => match sign(a.y - b.y) {
            0 => sign(b.x - a.x),
            s => s,
        },
        s => s,
    }
}

/// What triangle `t` says about the symbolically moved ray `ray` from `x`: `Err` when `x`
/// lies on the closed triangle, else whether the moved ray crosses it (exact; see
/// [`AxisRay`]).
pub(crate) fn crossing(t: [DVec3; 3], x: DVec3, ray: AxisRay) -> Result<bool, OnSurface> {
    let (u, v) = ray.across();
    let flat = |p: DVec3| robust::Coord { x: p[u], y: p[v] };
    let [a, b, c] = t.map(flat);
    let q = flat(x);
    let d = [
        robust::orient2d(a, b, q),
        robust::orient2d(b, c, q),
        robust::orient2d(c, a, q),
    ];
    if d.iter().any(|&s| s > 0.0) && d.iter().any(|&s| s < 0.0) {
        // Across the ray, `x` is outside the closed projected triangle: the (moved) ray
        // misses it and `x` is not on it.
        return Ok(false);
    }
    let s = [
        perturbed_sign(d[0], a, b),
        perturbed_sign(d[1], b, c),
        perturbed_sign(d[2], c, a),
    ];
    if s[0] != 0 && s[0] == s[1] && s[1] == s[2] {
        // The moved ray passes through the interior of the projection, whose orientation
        // (the normal's component along the ray, `s[0]`) is then not zero: it crosses the
        // plane ahead of `x` when `x` is on the side the ray leaves. On the plane, `x` is
        // on the triangle (the projection is one-to-one on the plane).
        let o = robust::orient3d(coord(t[0]), coord(t[1]), coord(t[2]), coord(x));
        if o == 0.0 {
            return Err(OnSurface);
        }
        // robust's orient3d is `−n·(x − t₀)` for `n = (t₁ − t₀) × (t₂ − t₀)`: positive
        // behind the plane as seen along `n`.
        let facing = (s[0] > 0) == ray.positive;
        return Ok((o > 0.0) == facing);
    }
    // `x` projects onto the projection's boundary (or the projection is flat): it may lie
    // on an edge, or on a face parallel to the ray.
    if d.contains(&0.0) && on_triangle(t, x) {
        return Err(OnSurface);
    }
    Ok(false)
}

/// Whether `x` lies on the closed triangle `t`, exactly: on its plane, within its
/// bounding box, and inside it in each of the three coordinate projections (on the plane,
/// the projection along the normal's largest axis is one-to-one; for a degenerate
/// triangle, the three together place `x` on its segment).
pub(crate) fn on_triangle(t: [DVec3; 3], x: DVec3) -> bool {
    let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    if x.cmplt(lo).any() || x.cmpgt(hi).any() {
        return false;
    }
    if robust::orient3d(coord(t[0]), coord(t[1]), coord(t[2]), coord(x)) != 0.0 {
        return false;
    }
    (0..3).all(|axis| {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let flat = |p: DVec3| robust::Coord { x: p[u], y: p[v] };
        let [a, b, c] = t.map(flat);
        let q = flat(x);
        let d = [
            robust::orient2d(a, b, q),
            robust::orient2d(b, c, q),
            robust::orient2d(c, a, q),
        ];
        !(d.iter().any(|&s| s > 0.0) && d.iter().any(|&s| s < 0.0))
    })
}

/// Whether `x` lies outside the closed box (so outside the mesh it bounds).
fn outside_box(bounds: &Aabb, x: DVec3) -> bool {
    x.cmplt(bounds.min).any() || x.cmpgt(bounds.max).any()
}

/// The crossing-number answer over every face: the reference for [`HalTree3::contains`]
/// (the same ray and exact predicates, so exact on every input). `mesh` must be closed.
///
/// # Examples
///
/// ```
/// use sphaera_hal::{Containment, contains3_brute};
/// use sphaera_mesh::{DVec3, shapes};
///
/// let cube = shapes::cube(2.0, 1)?;
/// // From the centre every axis-aligned ray runs into an edge (a face's diagonal): still
/// // exact.
/// assert_eq!(contains3_brute(&cube, DVec3::ZERO), Containment::Inside);
/// assert_eq!(contains3_brute(&cube, DVec3::new(1.0, 0.0, 0.0)), Containment::Boundary);
/// assert_eq!(contains3_brute(&cube, DVec3::splat(1.5)), Containment::Outside);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[must_use]
pub fn contains3_brute(mesh: &TriMesh, x: DVec3) -> Containment {
    let bounds = mesh.bounding_box();
    if outside_box(&bounds, x) {
        return Containment::Outside;
    }
    let ray = AxisRay::shortest(&bounds, x);
    let mut inside = false;
    for t in mesh.triangles() {
        let corners = t.map(|v| mesh.positions()[v as usize]);
        match crossing(corners, x, ray) {
            Ok(crossed) => inside ^= crossed,
            Err(OnSurface) => return Containment::Boundary,
        }
    }
    if inside {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

impl HalTree3 {
    /// Point inclusion: the crossing parity of an axis-aligned ray from `x` (the one with
    /// the shortest way out of the mesh's bounding box), moved symbolically off every edge
    /// and vertex (Simulation of Simplicity: the parity is exact for every point off the
    /// surface, with one ray, whatever the mesh), visiting only the patches whose bounding
    /// box and bounding volume the ray may meet (each node with the part of the ray inside
    /// its ancestors' volumes, clipped by its own), with exact orientation tests. Points
    /// exactly on a face are [`Containment::Boundary`] (decided exactly). Equal to
    /// [`contains3_brute`] on every input.
    ///
    /// The paper's section 5.1 would also replace a patch by its triangle when `x` is
    /// outside the patch's bounding volume. That needs levels that are closed polyhedra
    /// whose sides follow the patches' boundary paths, and discarding coalesced triangles
    /// (as the paper does) opens holes. Keeping them as folds split with their neighbours
    /// closes the levels, but was measured to swamp the tree (on `spot.obj` most nodes are
    /// folds, a coarse level has more triangles than the mesh, and some folds never
    /// resolve; see the section *HAL trees (`sphaera-hal`, issue 17)* of
    /// `docs/benchmarks.md` in the repository), so the bounds only cull here.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::{Containment, HalTree3};
    /// use sphaera_mesh::{DVec3, shapes};
    ///
    /// let tree = HalTree3::build(&shapes::cube(2.0, 2)?)?;
    /// // Every axis-aligned ray from the centre runs through a vertex: still exact.
    /// assert_eq!(tree.contains(DVec3::ZERO), Containment::Inside);
    /// assert_eq!(tree.contains(DVec3::new(0.0, 1.0, 0.5)), Containment::Boundary);
    /// assert_eq!(tree.contains(DVec3::new(0.0, 1.5, 0.0)), Containment::Outside);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn contains(&self, x: DVec3) -> Containment {
        let root = self.root_ball();
        let slack = 1e-12 * (root.radius + root.center.abs().max_element());
        if x.distance(root.center) > root.radius + slack {
            return Containment::Outside;
        }
        let bounds = self.bounding_box();
        if outside_box(&bounds, x) {
            return Containment::Outside;
        }
        let slack = 1e-9 * (bounds.diagonal() + x.abs().max_element());
        let ray = AxisRay::shortest(&bounds, x);
        let mut y = x;
        y[ray.axis] = if ray.positive {
            bounds.max[ray.axis] + slack
        } else {
            bounds.min[ray.axis] - slack
        };
        let d = y - x;
        // Each node is visited with the part of the ray inside all its ancestors'
        // volumes, clipped further by its own. The stack is the thread's, kept from
        // query to query (no allocation per query).
        let mut stack = STACK.with(|s| std::mem::take(&mut *s.borrow_mut()));
        stack.clear();
        stack.extend(self.roots().iter().map(|&r| (r, (0.0, 1.0))));
        let answer = self.cross(&mut stack, x, d, ray, slack);
        STACK.with(|s| *s.borrow_mut() = stack);
        match answer {
            Ok(true) => Containment::Inside,
            Ok(false) => Containment::Outside,
            Err(OnSurface) => Containment::Boundary,
        }
    }

    /// The crossing parity of the moved ray `ray` from `x` (reaching beyond the mesh at
    /// `x + d`) with the faces under the nodes on `stack`; `Err` when `x` is on a face.
    fn cross(
        &self,
        stack: &mut Vec<(u32, (f64, f64))>,
        x: DVec3,
        d: DVec3,
        ray: AxisRay,
        slack: f64,
    ) -> Result<bool, OnSurface> {
        let mesh = self.mesh();
        let positions = mesh.positions();
        let mut inside = false;
        while let Some((n, span)) = stack.pop() {
            let node = &self.nodes()[n as usize];
            let mut span = clip_to_box(self.node_box(n), x, d, span, slack);
            for region in self.node_regions(n) {
                span = span.and_then(|s| region.clip(x, d, s, slack));
            }
            let Some(span) = span else { continue };
            if node.children.is_empty() {
                for &f in &node.faces {
                    let t = mesh.triangles()[f as usize].map(|v| positions[v as usize]);
                    inside ^= crossing(t, x, ray)?;
                }
            } else {
                stack.extend(node.children.iter().map(|&c| (c, span)));
            }
        }
        Ok(inside)
    }
}

/// The part `(t0, t1)` of `span` where `x + t·d` lies in `bounds` grown by `slack`
/// (the slab method), or `None` when it does not.
fn clip_to_box(
    bounds: &Aabb,
    x: DVec3,
    d: DVec3,
    span: (f64, f64),
    slack: f64,
) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = span;
    for axis in 0..3 {
        let (lo, hi) = (bounds.min[axis] - slack, bounds.max[axis] + slack);
        if d[axis] == 0.0 {
            if x[axis] < lo || x[axis] > hi {
                return None;
            }
            continue;
        }
        let (a, b) = ((lo - x[axis]) / d[axis], (hi - x[axis]) / d[axis]);
        let (enter, exit) = if a <= b { (a, b) } else { (b, a) };
        t0 = t0.max(enter);
        t1 = t1.min(exit);
        if t0 > t1 {
            return None;
        }
    }
    Some((t0, t1))
}

thread_local! {
    /// The node stack of [`HalTree3::contains`], one per thread.
    static STACK: std::cell::RefCell<Vec<(u32, (f64, f64))>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::shapes;

    /// The faces a moved ray crosses, counted.
    fn crossings(mesh: &TriMesh, x: DVec3, ray: AxisRay) -> usize {
        mesh.triangles()
            .iter()
            .filter(|t| {
                crossing(t.map(|v| mesh.positions()[v as usize]), x, ray)
                    .expect("x off the surface")
            })
            .count()
    }

    /// From the centre of a cube of two triangles per side, every axis-aligned ray runs
    /// into a side's diagonal (an edge shared by two faces); from the centre of an
    /// octahedron, into a corner shared by four. The moved ray crosses exactly one face.
    #[test]
    fn a_ray_through_an_edge_or_a_vertex_crosses_one_face() {
        let cube = shapes::cube(2.0, 1).expect("a cube");
        let octahedron = TriMesh::new(
            vec![
                DVec3::X,
                -DVec3::X,
                DVec3::Y,
                -DVec3::Y,
                DVec3::Z,
                -DVec3::Z,
            ],
            vec![
                [0, 2, 4],
                [2, 1, 4],
                [1, 3, 4],
                [3, 0, 4],
                [2, 0, 5],
                [1, 2, 5],
                [3, 1, 5],
                [0, 3, 5],
            ],
        )
        .expect("an octahedron");
        for mesh in [&cube, &octahedron] {
            for axis in 0..3 {
                for positive in [true, false] {
                    let ray = AxisRay { axis, positive };
                    // The ray grazes: some face has x on an edge's line across the ray.
                    let (u, v) = ray.across();
                    let grazes = mesh.triangles().iter().any(|t| {
                        let [a, b, c] = t.map(|i| {
                            let p = mesh.positions()[i as usize];
                            robust::Coord { x: p[u], y: p[v] }
                        });
                        let q = robust::Coord { x: 0.0, y: 0.0 };
                        [(a, b), (b, c), (c, a)]
                            .iter()
                            .any(|&(s, e)| robust::orient2d(s, e, q) == 0.0)
                    });
                    assert!(grazes, "{ray:?}");
                    assert_eq!(crossings(mesh, DVec3::ZERO, ray), 1, "{ray:?}");
                    // Outside, beyond a corner or an edge along the ray: none or two.
                    let mut far = DVec3::ZERO;
                    far[axis] = if positive { -3.0 } else { 3.0 };
                    assert_eq!(crossings(mesh, far, ray) % 2, 0, "{ray:?}");
                }
            }
        }
    }

    /// On a face, an edge or a vertex, whichever ray: the surface.
    #[test]
    fn points_on_faces_edges_and_vertices_are_on_the_surface() {
        let cube = shapes::cube(2.0, 1).expect("a cube");
        for x in [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.25, -1.0, 0.5),
        ] {
            for axis in 0..3 {
                for positive in [true, false] {
                    let ray = AxisRay { axis, positive };
                    let on = cube.triangles().iter().any(|t| {
                        crossing(t.map(|v| cube.positions()[v as usize]), x, ray).is_err()
                    });
                    assert!(on, "{x} {ray:?}");
                }
            }
            assert_eq!(contains3_brute(&cube, x), Containment::Boundary, "{x}");
        }
    }
}
