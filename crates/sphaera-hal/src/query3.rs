//! Point inclusion for 3D HAL trees: the crossing number of a segment from the point to
//! beyond the root ball, counting only the faces of patches whose bounding volume the
//! segment may meet, with exact predicates; and its brute-force reference.
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

/// Directions (and their opposites) tried from the shortest way out of the bounding box:
/// a segment through an edge or a vertex (a zero orientation) is shot again along the
/// next. Irrational-looking, far from the axes.
const DIRECTIONS: [[f64; 3]; 4] = [
    [0.573_849_2, 0.618_033_9, 0.537_617_1],
    [-0.414_213_6, 0.732_050_8, 0.541_381_3],
    [0.300_000_7, -0.812_403_8, 0.500_057_3],
    [-0.661_043_2, -0.329_513_7, -0.674_020_9],
];

fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// What one triangle says about the segment `x → y` (`y` far outside the mesh):
/// `Err(true)` when `x` lies on it, `Err(false)` when the segment passes through an edge,
/// a vertex or along the plane (shoot again), else whether it crosses the interior.
fn crossing(t: [DVec3; 3], x: DVec3, y: DVec3) -> Result<bool, bool> {
    // The boxes of the segment and the triangle apart (coordinates compared, no
    // arithmetic, so exact): the segment misses the triangle and its edges, and `x` is not
    // on it.
    let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    if x.min(y).cmpgt(hi).any() || x.max(y).cmplt(lo).any() {
        return Ok(false);
    }
    let [a, b, c] = t.map(coord);
    let (cx, cy) = (coord(x), coord(y));
    let sx = robust::orient3d(a, b, c, cx);
    let sy = robust::orient3d(a, b, c, cy);
    if sx == 0.0 {
        if on_triangle(t, x) {
            return Err(true);
        }
        // Starting in the plane off the triangle: along the plane is degenerate, leaving
        // it misses.
        return if sy == 0.0 { Err(false) } else { Ok(false) };
    }
    // Ending in the plane (far from the triangle), or staying on one side: no crossing.
    if sy == 0.0 || (sx > 0.0) == (sy > 0.0) {
        return Ok(false);
    }
    let e = [
        robust::orient3d(cx, cy, a, b),
        robust::orient3d(cx, cy, b, c),
        robust::orient3d(cx, cy, c, a),
    ];
    let positive = e.iter().all(|&v| v >= 0.0);
    let negative = e.iter().all(|&v| v <= 0.0);
    if !(positive || negative) {
        return Ok(false);
    }
    if e.contains(&0.0) {
        // Through an edge or a vertex.
        return Err(false);
    }
    Ok(true)
}

/// Whether `x`, in the plane of `t`, lies on the triangle (exact, in the projection that
/// drops the normal's largest axis).
fn on_triangle(t: [DVec3; 3], x: DVec3) -> bool {
    let normal = (t[1] - t[0]).cross(t[2] - t[0]).abs();
    let drop = if normal.x >= normal.y && normal.x >= normal.z {
        0
    } else if normal.y >= normal.z {
        1
    } else {
        2
    };
    let flat = |p: DVec3| {
        let (u, v) = match drop {
            0 => (p.y, p.z),
            1 => (p.z, p.x),
            _ => (p.x, p.y),
        };
        robust::Coord { x: u, y: v }
    };
    let [a, b, c] = t.map(flat);
    let q = flat(x);
    let (d1, d2, d3) = (
        robust::orient2d(a, b, q),
        robust::orient2d(b, c, q),
        robust::orient2d(c, a, q),
    );
    (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0)
}

/// The far ends of the segments shot from `x`, a point in the closed box `bounds` (the
/// mesh's bounding box): along each of the eight directions ([`DIRECTIONS`] and their
/// opposites), just beyond where the direction leaves the box, the shortest first (the
/// lowest index on ties). The tree and the brute force shoot the same segments.
fn far_ends(bounds: &Aabb, x: DVec3) -> [DVec3; 8] {
    let margin = 1e-9 * bounds.diagonal();
    let mut ends: [(f64, usize, DVec3); 8] = [(0.0, 0, DVec3::ZERO); 8];
    for (i, slot) in ends.iter_mut().enumerate() {
        let sign = if i < 4 { 1.0 } else { -1.0 };
        let d = DVec3::from_array(DIRECTIONS[i % 4]) * sign;
        let exit = (0..3)
            .filter(|&axis| d[axis] != 0.0)
            .map(|axis| {
                let wall = if d[axis] > 0.0 {
                    bounds.max[axis]
                } else {
                    bounds.min[axis]
                };
                ((wall - x[axis]) / d[axis]).max(0.0)
            })
            .fold(f64::INFINITY, f64::min);
        let reach = exit * (1.0 + 1e-6) + margin;
        *slot = (reach, i, x + d * reach);
    }
    ends.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    ends.map(|(_, _, y)| y)
}

/// Whether `x` lies outside the closed box (so outside the mesh it bounds).
fn outside_box(bounds: &Aabb, x: DVec3) -> bool {
    x.cmplt(bounds.min).any() || x.cmpgt(bounds.max).any()
}

/// The crossing-number answer over every face: the reference for [`HalTree3::contains`]
/// (the same segments and exact predicates). `mesh` must be closed.
#[must_use]
pub fn contains3_brute(mesh: &TriMesh, x: DVec3) -> Containment {
    let bounds = mesh.bounding_box();
    if outside_box(&bounds, x) {
        return Containment::Outside;
    }
    'directions: for y in far_ends(&bounds, x) {
        let mut inside = false;
        for t in mesh.triangles() {
            let corners = t.map(|v| mesh.positions()[v as usize]);
            match crossing(corners, x, y) {
                Ok(crossed) => inside ^= crossed,
                Err(true) => return Containment::Boundary,
                Err(false) => continue 'directions,
            }
        }
        return if inside {
            Containment::Inside
        } else {
            Containment::Outside
        };
    }
    Containment::Boundary
}

impl HalTree3 {
    /// Point inclusion: the crossing number of the shortest of eight fixed segments from
    /// `x` out of the mesh's bounding box, visiting only the patches whose bounding volume the segment may meet (each node
    /// with the part of the segment inside its ancestors' volumes, clipped by its own), with exact
    /// orientation tests; a segment through an edge or a vertex is shot again along
    /// another direction. Equal to [`contains3_brute`] on every input. Points exactly on a
    /// face are [`Containment::Boundary`].
    ///
    /// The paper's section 5.1 would also replace a patch by its triangle when `x` is
    /// outside the patch's bounding volume. That needs levels that are closed polyhedra
    /// whose sides follow the patches' boundary paths, and discarding coalesced triangles
    /// (as the paper does) opens holes. Keeping them as folds split with their neighbours
    /// closes the levels, but was measured to swamp the tree (on `spot.obj` most nodes are
    /// folds, a coarse level has more triangles than the mesh, and some folds never
    /// resolve; see the section *HAL trees (`sphaera-hal`, issue 17)* of
    /// `docs/benchmarks.md` in the repository), so the bounds only cull here.
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
        for y in far_ends(&bounds, x) {
            let d = y - x;
            // Each node is visited with the part of the segment inside all its ancestors'
            // volumes, clipped further by its own. The stack is the thread's, kept from
            // query to query (no allocation per query).
            let mut stack = STACK.with(|s| std::mem::take(&mut *s.borrow_mut()));
            stack.clear();
            stack.extend(self.roots().iter().map(|&r| (r, (0.0, 1.0))));
            let answer = self.cross(&mut stack, x, y, d, slack);
            STACK.with(|s| *s.borrow_mut() = stack);
            match answer {
                Ok(inside) => {
                    return if inside {
                        Containment::Inside
                    } else {
                        Containment::Outside
                    };
                }
                Err(true) => return Containment::Boundary,
                Err(false) => {}
            }
        }
        Containment::Boundary
    }

    /// The crossing parity of the segment `x → y` (`d = y − x`) with the faces under the
    /// nodes on `stack`: `Err(true)` when `x` is on a face, `Err(false)` when the segment
    /// passes through an edge or a vertex (shoot another).
    fn cross(
        &self,
        stack: &mut Vec<(u32, (f64, f64))>,
        x: DVec3,
        y: DVec3,
        d: DVec3,
        slack: f64,
    ) -> Result<bool, bool> {
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
                    inside ^= crossing(t, x, y)?;
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
