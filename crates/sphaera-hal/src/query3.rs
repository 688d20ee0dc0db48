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

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::DVec3;
use sphaera_mesh::geometry::{Triangle, closest_point_on_triangle};
use sphaera_mesh::heap::TotalF64;
use sphaera_mesh::{Aabb, TriMesh};

use crate::tree3::FlatNode;
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
    match (ray.axis, ray.positive) {
        (0, true) => crossing_along::<0, true>(&t, x),
        (0, false) => crossing_along::<0, false>(&t, x),
        (1, true) => crossing_along::<1, true>(&t, x),
        (1, false) => crossing_along::<1, false>(&t, x),
        (_, true) => crossing_along::<2, true>(&t, x),
        (_, false) => crossing_along::<2, false>(&t, x),
    }
}

/// [`crossing`] for the ray along `AXIS`, toward `+∞` when `POSITIVE`.
#[inline]
fn crossing_along<const AXIS: usize, const POSITIVE: bool>(
    t: &[DVec3; 3],
    x: DVec3,
) -> Result<bool, OnSurface> {
    let (u, v) = ((AXIS + 1) % 3, (AXIS + 2) % 3);
    let flat = |p: DVec3| robust::Coord { x: p[u], y: p[v] };
    let [a, b, c] = t.map(flat);
    let q = flat(x);
    let d0 = robust::orient2d(a, b, q);
    let d1 = robust::orient2d(b, c, q);
    // Mixed strict signs: across the ray, `x` is outside the closed projected triangle,
    // so the (moved) ray misses it and `x` is not on it.
    if (d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0) {
        return Ok(false);
    }
    let d2 = robust::orient2d(c, a, q);
    let d = [d0, d1, d2];
    if d.iter().any(|&s| s > 0.0) && d.iter().any(|&s| s < 0.0) {
        return Ok(false);
    }
    let s = [
        perturbed_sign(d0, a, b),
        perturbed_sign(d1, b, c),
        perturbed_sign(d2, c, a),
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
        let facing = (s[0] > 0) == POSITIVE;
        return Ok((o > 0.0) == facing);
    }
    // `x` projects onto the projection's boundary (or the projection is flat): it may lie
    // on an edge, or on a face parallel to the ray.
    if d.contains(&0.0) && on_triangle(*t, x) {
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
    let (u, v) = ray.across();
    let mut inside = false;
    for t in mesh.triangles() {
        let corners = t.map(|v| mesh.positions()[v as usize]);
        // The ray misses the triangle's box (coordinates compared, exact): it misses the
        // triangle, and `x` is not on it.
        let (lo, hi) = (
            corners[0].min(corners[1]).min(corners[2]),
            corners[0].max(corners[1]).max(corners[2]),
        );
        let behind = if ray.positive {
            hi[ray.axis] < x[ray.axis]
        } else {
            lo[ray.axis] > x[ray.axis]
        };
        if behind || x[u] < lo[u] || x[u] > hi[u] || x[v] < lo[v] || x[v] > hi[v] {
            continue;
        }
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
    /// surface, with one ray, whatever the mesh), with exact orientation tests on the
    /// faces of the patches whose bounding box and bounding volume the ray may meet.
    /// Points exactly on a face are [`Containment::Boundary`] (decided exactly). Equal to
    /// [`contains3_brute`] on every input.
    ///
    /// # Performance
    ///
    /// The nodes are laid out flat, children next to each other, each with its patch's
    /// bounding box; an axis-aligned ray meets a box when the point lies within the box's
    /// two ranges across the ray and before its far side along it, five comparisons, so a
    /// child is pushed only when its box is met, and the paper's volume (two balls or
    /// half-spaces) is tested when it is popped. The leaves keep their triangles by value.
    /// No allocation per query (the stack is the thread's).
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
        // The stack is the thread's, kept from query to query (no allocation per query).
        let mut stack = STACK.with(|s| std::mem::take(&mut *s.borrow_mut()));
        let answer = match AxisRay::shortest(&bounds, x) {
            AxisRay {
                axis: 0,
                positive: true,
            } => self.cross::<0, true>(&mut stack, x, slack),
            AxisRay {
                axis: 0,
                positive: false,
            } => self.cross::<0, false>(&mut stack, x, slack),
            AxisRay {
                axis: 1,
                positive: true,
            } => self.cross::<1, true>(&mut stack, x, slack),
            AxisRay {
                axis: 1,
                positive: false,
            } => self.cross::<1, false>(&mut stack, x, slack),
            AxisRay { positive: true, .. } => self.cross::<2, true>(&mut stack, x, slack),
            AxisRay {
                positive: false, ..
            } => self.cross::<2, false>(&mut stack, x, slack),
        };
        STACK.with(|s| *s.borrow_mut() = stack);
        match answer {
            Ok(true) => Containment::Inside,
            Ok(false) => Containment::Outside,
            Err(OnSurface) => Containment::Boundary,
        }
    }

    /// The crossing parity of the moved ray from `x` along `AXIS` (toward `+∞` when
    /// `POSITIVE`) with the faces whose patches' boxes and volumes it may meet; `Err` when
    /// `x` is on a face. A child is pushed only when the ray meets its box (closed
    /// comparisons of coordinates: exact, and conservative for the moved ray); its volume
    /// is tested when it is popped.
    fn cross<const AXIS: usize, const POSITIVE: bool>(
        &self,
        stack: &mut Vec<u32>,
        x: DVec3,
        slack: f64,
    ) -> Result<bool, OnSurface> {
        let layout = self.layout();
        let (nodes, regions, triangles) = (&layout.nodes, &layout.regions, &layout.triangles);
        let (u, v) = ((AXIS + 1) % 3, (AXIS + 2) % 3);
        let p = x.to_array();
        let hits = |n: &FlatNode| {
            n.lo[u] <= p[u]
                && p[u] <= n.hi[u]
                && n.lo[v] <= p[v]
                && p[v] <= n.hi[v]
                && if POSITIVE {
                    p[AXIS] <= n.hi[AXIS]
                } else {
                    n.lo[AXIS] <= p[AXIS]
                }
        };
        stack.clear();
        stack.extend((0..layout.root_count).filter(|&r| hits(&nodes[r as usize])));
        let mut inside = false;
        while let Some(n) = stack.pop() {
            let node = &nodes[n as usize];
            if node.count == 0 {
                inside ^= crossing_along::<AXIS, POSITIVE>(&triangles[node.first as usize], x)?;
                continue;
            }
            let [r0, r1] = regions[n as usize];
            if !(r0.meets_axis_ray::<AXIS, POSITIVE>(x, slack)
                && r1.meets_axis_ray::<AXIS, POSITIVE>(x, slack))
            {
                continue;
            }
            for c in node.first..node.first + node.count {
                if hits(&nodes[c as usize]) {
                    stack.push(c);
                }
            }
        }
        Ok(inside)
    }
}

/// The face of a [`HalTree3`]'s mesh nearest to a point, as [`HalTree3::nearest_face`]
/// finds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestFace {
    /// The face: an index into the mesh's triangles.
    pub face: usize,
    /// The distance from the point to the face.
    pub distance: f64,
    /// The point of the face nearest to the point.
    pub point: DVec3,
}

impl HalTree3 {
    /// The face nearest to `x` (the lowest index among equally near ones), its distance
    /// and its point nearest to `x`: branch and bound over the tree, best first. A node's
    /// lower bound is the largest of the distances from `x` to its patch's bounding box
    /// and to each of its two regions (balls or half-spaces: the patch lies in each, so
    /// in their intersection), less a slack for rounding relative to the coordinates'
    /// magnitude; a node is dropped once its bound exceeds the nearest distance found.
    /// Distances to faces are [`closest_point_on_triangle`]'s, so the answer is exactly
    /// the brute force's minimum of (squared distance, face index) over every face.
    /// `None` when `x` is not finite.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::HalTree3;
    /// use sphaera_mesh::{DVec3, shapes};
    ///
    /// let tree = HalTree3::build(&shapes::cube(2.0, 2)?)?;
    /// let nearest = tree.nearest_face(DVec3::new(3.0, 0.25, 0.5)).expect("a finite point");
    /// assert_eq!(nearest.distance, 2.0);
    /// assert_eq!(nearest.point, DVec3::new(1.0, 0.25, 0.5));
    /// // The face lies on the side x = 1.
    /// let face = tree.mesh().triangles()[nearest.face];
    /// assert!(face.iter().all(|&v| tree.mesh().positions()[v as usize].x == 1.0));
    /// assert!(tree.nearest_face(DVec3::NAN).is_none());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// Visits the nodes whose lower bound is below the nearest distance found: few near
    /// the surface, more far from it, where many patches are nearly as near. No
    /// allocation per query (the heap is the thread's).
    #[must_use]
    pub fn nearest_face(&self, x: DVec3) -> Option<NearestFace> {
        if !x.is_finite() {
            return None;
        }
        let layout = self.layout();
        let slack = 1e-9 * (self.bounding_box().diagonal() + x.abs().max_element());
        // The best so far: squared distance, face, point.
        let mut best: Option<(f64, u32, DVec3)> = None;
        let beyond = |best: &Option<(f64, u32, DVec3)>, lower: f64| {
            lower > 0.0 && best.is_some_and(|(d2, _, _)| lower * lower > d2)
        };
        // A node's lower bound, `None` when it cannot beat `best`: the box first, the
        // volume only when the box does not decide.
        let bound = |n: u32, best: &Option<(f64, u32, DVec3)>| {
            let node = &layout.nodes[n as usize];
            let (lo, hi) = (DVec3::from_array(node.lo), DVec3::from_array(node.hi));
            let mut lower = x.distance(x.clamp(lo, hi)) - slack;
            if beyond(best, lower) {
                return None;
            }
            for region in layout.regions[n as usize] {
                lower = lower.max(region.distance_outside(x) - slack);
            }
            (!beyond(best, lower)).then_some(lower.max(0.0))
        };
        let mut heap = HEAP.with(|h| std::mem::take(&mut *h.borrow_mut()));
        heap.clear();
        // Leaves are measured as soon as their parent is expanded, nodes wait in the heap.
        let visit = |n: u32, best: &mut Option<(f64, u32, DVec3)>, heap: &mut BinaryHeap<_>| {
            let node = &layout.nodes[n as usize];
            if node.count > 0 {
                if let Some(lower) = bound(n, best) {
                    heap.push(Reverse((TotalF64(lower), n)));
                }
                return;
            }
            let slot = node.first as usize;
            let [a, b, c] = layout.triangles[slot];
            let face = layout.faces[slot];
            let (lo, hi) = (DVec3::from_array(node.lo), DVec3::from_array(node.hi));
            if beyond(best, x.distance(x.clamp(lo, hi)) - slack) {
                return;
            }
            let hit = closest_point_on_triangle(x, &Triangle::new(a, b, c));
            let better = best.is_none_or(|(d2, f, _)| {
                hit.distance_squared
                    .total_cmp(&d2)
                    .then(face.cmp(&f))
                    .is_lt()
            });
            if better {
                *best = Some((hit.distance_squared, face, hit.point));
            }
        };
        for r in 0..layout.root_count {
            visit(r, &mut best, &mut heap);
        }
        while let Some(Reverse((TotalF64(lower), n))) = heap.pop() {
            if beyond(&best, lower) {
                // Best first: every node left is at least as far.
                break;
            }
            let node = &layout.nodes[n as usize];
            for c in node.first..node.first + node.count {
                visit(c, &mut best, &mut heap);
            }
        }
        HEAP.with(|h| *h.borrow_mut() = heap);
        best.map(|(d2, face, point)| NearestFace {
            face: face as usize,
            distance: d2.sqrt(),
            point,
        })
    }
}

thread_local! {
    /// The node stack of [`HalTree3::contains`], one per thread.
    static STACK: std::cell::RefCell<Vec<u32>> =
        const { std::cell::RefCell::new(Vec::new()) };
    /// The node heap of [`HalTree3::nearest_face`], one per thread.
    static HEAP: std::cell::RefCell<BinaryHeap<Reverse<(TotalF64, u32)>>> =
        const { std::cell::RefCell::new(BinaryHeap::new()) };
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
        let octahedron = shapes::fixtures::octahedron();
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
