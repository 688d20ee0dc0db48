//! The boundary of a mesh (its holes) and the bound it gives on how fast the generalized
//! winding number varies away from the mesh.
//!
//! # The boundary chain
//!
//! Each triangle `(a, b, c)` contributes its three directed edges `a → b`, `b → c`,
//! `c → a`. Keyed by their corners' positions (so that duplicated vertices weld), the
//! directed edges of one segment add up to a net **multiplicity** `m_e` (traversals one
//! way less traversals the other way). The edges with `m_e ≠ 0` form the boundary chain
//! `∂M`: empty for a closed, consistently oriented mesh (every edge traversed once each
//! way), the rims of the holes of a scan.
//!
//! # The gradient bound
//!
//! Off the mesh, the winding number `w(x) = Σ_t Ω_t(x) / 4π` is smooth, and the gradient
//! of the solid angle `Ω_t` a triangle subtends is the Biot–Savart field of its rim: the
//! magnetic scalar potential of a current loop is proportional to the solid angle it
//! subtends (Jackson, *Classical Electrodynamics*, 3rd ed., §5.6),
//! `∇Ω_t(x) = ∮_{∂t} (y − x) × dy / |y − x|³` up to the sign of the orientation. Summed over
//! the triangles, each edge's line integral appears with its net multiplicity, so the
//! interior edges cancel and only the boundary chain remains:
//!
//! ```text
//! |∇w(x)| ≤ (1/4π) Σ_e |m_e| ∫_e |dy| / |y − x|² ≤ (1/4π) Σ_e |m_e| · |e| / dist(x, e)².
//! ```
//!
//! So on a segment `[p, x]` that meets no triangle, `|w(x) − w(p)| ≤ |x − p| · G` for any
//! `G` bounding `|∇w|` on the segment: the winding number changes by jumps of ±1 across
//! triangles, and otherwise only as fast as the holes let it. On a closed mesh `G = 0` and
//! this is the familiar statement that `w` is constant between crossings.
//! [`WindingBoundary::gradient_bound`] gives such a `G` over a ball, from a bounding-volume
//! hierarchy over the boundary edges (a cluster of edges of total weighted length `Λ`
//! within radius `r` of its centre `k` is bounded at once by `Λ / (|x − k| − r)²` when far).
//!
//! # The caps: the winding number near a hole, exactly and cheaply
//!
//! Each connected component of the chain (a hole's rim) is coned off from an apex (the
//! mean of its vertices): the edge `a → b` of net multiplicity `m` gives the cap triangle
//! `(o, b, a)` with multiplicity `m`. The cone's boundary is minus the chain (the spokes
//! `o → v` cancel, since a chain that bounds has as much multiplicity into each vertex as
//! out of it), so the mesh and its caps form a cycle, whose winding number
//! `w_M + w_C` is an **integer** off both. Hence `w_M = k − w_C` with `k` the integer
//! nearest to any estimate of `w_M + w_C` within `½`: the certified traversal's estimate of
//! `w_M` (far coarser than what deciding `w_M > ½` near a hole's span takes) plus the
//! exact solid angles of the few cap triangles
//! ([`WindingBoundary::cap_solid_angle`]). A cap triangle's computed solid angle may be
//! off by `4π` where it is discontinuous (on the triangle): that is an integer in `w`,
//! which `k` absorbs, so only the error modulo `4π` counts, and that is bounded per
//! triangle from the conditioning of the `atan2` it takes.

use std::collections::HashMap;
use std::f64::consts::PI;

use glam::DVec3;

use super::CertifiedSide;
use sphaera_mesh::TriMesh;
use sphaera_mesh::geometry::{Triangle, closest_point_on_segment, point_triangle_distance_squared};
use sphaera_mesh::topology::{EdgeTable, halfedge_vertices};

/// Most boundary edges in a leaf of the hierarchy.
const LEAF_EDGES: usize = 4;

/// A cluster is bounded at once when its distance to the query ball is at least this
/// many times its radius (the bound is then at most `(1 + 1/FAR)²` times that of its
/// edges one by one).
const FAR: f64 = 4.0;

/// Relative allowance for the rounding of a distance (far above the few operations).
const ROUNDING: f64 = 1e-12;

/// A boundary edge: a segment and its weight `|m_e| · |e|`.
#[derive(Clone, Copy, Debug)]
struct Edge {
    start: DVec3,
    end: DVec3,
    weight: f64,
}

/// A cap triangle `(apex, end, start)` of a boundary edge `start → end`, with the edge's
/// net multiplicity (signed).
#[derive(Clone, Copy, Debug)]
struct Cap {
    apex: DVec3,
    start: DVec3,
    end: DVec3,
    multiplicity: f64,
}

/// The caps of one component of the chain: a fan of triangles about an apex.
#[derive(Clone, Debug)]
struct Fan {
    apex: DVec3,
    /// The radius of a ball about the apex containing the fan.
    radius: f64,
    /// Its triangles in `caps` and its edges in `fan_edges` (the same range).
    caps: std::ops::Range<usize>,
    /// Its vertices in `fan_vertices`.
    vertices: std::ops::Range<usize>,
}

/// Relative forward error bound of the numerator and denominator of the solid-angle
/// formula, in units of `|a| |b| |c|` and of the machine epsilon (a few dozen operations
/// on terms bounded by that product; far above their worst case).
const SOLID_ANGLE_ERROR: f64 = 64.0 * f64::EPSILON;

/// A node of the hierarchy over the boundary edges.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// The centre of a ball containing the node's edges.
    center: DVec3,
    /// Its radius.
    radius: f64,
    /// The sum of the node's edges' weights.
    weight: f64,
    /// The first edge of a leaf; the second child of an inner node (the first child
    /// follows the node itself).
    first: u32,
    /// The number of edges of a leaf; 0 for an inner node.
    count: u32,
}

/// The boundary chain of a mesh (the rims of its holes, see the
/// notes of the `winding::boundary` source module) and the bound it gives on the gradient of the generalized
/// winding number.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh, shapes};
/// use sphaera_query::winding::WindingBoundary;
///
/// let cube = shapes::cube(2.0, 1)?; // [-1, 1]³, closed
/// assert!(WindingBoundary::new(&cube).is_empty());
/// assert_eq!(WindingBoundary::new(&cube).gradient_bound(DVec3::ZERO, 0.5), 0.0);
/// // Without its first triangle it has a hole: three edges of length 2, 2 and 2√2.
/// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
/// let boundary = WindingBoundary::new(&open);
/// assert_eq!(boundary.edge_count(), 3);
/// assert!((boundary.length() - (4.0 + 8f64.sqrt())).abs() < 1e-12);
/// // Far from the hole the winding number hardly varies; a ball touching it, unbounded.
/// assert!(boundary.gradient_bound(DVec3::splat(50.0), 1.0) < 1e-3);
/// assert_eq!(boundary.gradient_bound(DVec3::ZERO, 2.0), f64::INFINITY);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct WindingBoundary {
    edges: Vec<Edge>,
    nodes: Vec<Node>,
    /// The cap triangles (see the notes of the `winding::boundary` source module), grouped by component.
    caps: Vec<Cap>,
    /// The components' caps (fans about their apexes).
    fans: Vec<Fan>,
    /// The fans' rim vertices, by fan.
    fan_vertices: Vec<DVec3>,
    /// The fans' edges: their start and end among their fan's vertices (offsets from the
    /// fan's first) and multiplicities, in the order of `caps`.
    fan_edges: Vec<(u32, u32, f64)>,
    length: f64,
    /// The largest coordinate magnitude of the boundary (the scale of rounding).
    scale: f64,
}

impl WindingBoundary {
    /// The boundary chain of `mesh`, its edges keyed by their corners' positions.
    ///
    /// # Performance
    ///
    /// Linear in the triangles (a hash of the vertex positions, then the edge matching
    /// of [`topology`](sphaera_mesh::topology)).
    #[must_use]
    pub fn new(mesh: &TriMesh) -> Self {
        // Weld by position: the canonical vertex of each position is its first index.
        let positions = mesh.positions();
        let mut first: HashMap<[u64; 3], u32> = HashMap::with_capacity(positions.len());
        let canonical: Vec<u32> = positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                *first
                    .entry(p.to_array().map(f64::to_bits))
                    .or_insert(i as u32)
            })
            .collect();
        let triangles: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .map(|t| t.map(|v| canonical[v as usize]))
            .collect();
        let table = EdgeTable::new(&triangles, positions.len());
        let mut edges = Vec::new();
        // The chain's edges by canonical vertices, with their signed multiplicities.
        let mut chain: Vec<(u32, u32, i64)> = Vec::new();
        for e in 0..table.edge_count() {
            let halfedges = table.edge(e);
            let Some(&any) = halfedges.first() else {
                continue;
            };
            let (a, b) = halfedge_vertices(&triangles, any);
            let (low, high) = (a.min(b), a.max(b));
            if low == high {
                continue; // a collapsed edge: a point, no length
            }
            let net: i64 = halfedges
                .iter()
                .map(|&h| {
                    if halfedge_vertices(&triangles, h).0 == low {
                        1
                    } else {
                        -1
                    }
                })
                .sum();
            if net != 0 {
                chain.push((low, high, net));
                let (start, end) = (positions[low as usize], positions[high as usize]);
                edges.push(Edge {
                    start,
                    end,
                    weight: net.unsigned_abs() as f64 * start.distance(end),
                });
            }
        }
        let length = edges.iter().map(|e| e.weight).sum();
        let scale = edges
            .iter()
            .map(|e| e.start.abs().max(e.end.abs()).max_element())
            .fold(0.0, f64::max);
        let (caps, fans, fan_vertices, fan_edges) = cone_off(positions, &chain);
        let mut boundary = Self {
            edges,
            nodes: Vec::new(),
            caps,
            fans,
            fan_vertices,
            fan_edges,
            length,
            scale,
        };
        if !boundary.edges.is_empty() {
            let count = boundary.edges.len();
            boundary.build(0, count);
        }
        boundary
    }

    /// Whether the chain is empty: every edge is traversed as often one way as the other
    /// (a closed mesh), and the winding number is an integer off the mesh.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// The number of boundary edges (segments with a non-zero net multiplicity).
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The total length of the boundary, each edge counted `|m_e|` times.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The number of cap triangles (one per boundary edge).
    #[must_use]
    pub fn cap_count(&self) -> usize {
        self.caps.len()
    }

    /// The solid angle `Ω_C` the caps subtend at `p` (each cap triangle counted with its
    /// multiplicity; see the notes of the `winding::boundary` source module) and a bound of its error
    /// **modulo `4π`**: the exact value lies within the bound of the returned one plus an
    /// integer multiple of `4π`. The bound is large only within a tiny distance of a cap
    /// triangle's edge (its solid angle is ill-conditioned there); `None` for a
    /// non-finite `p`. 0 (and 0) for an empty boundary.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh, shapes};
    /// use sphaera_query::winding::{WindingBoundary, winding_number_brute};
    ///
    /// let cube = shapes::cube(2.0, 1)?;
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// let boundary = WindingBoundary::new(&open);
    /// // The mesh and its caps are closed: the winding numbers add up to an integer.
    /// for p in [DVec3::ZERO, DVec3::new(0.9, -0.9, 0.95), DVec3::splat(3.0)] {
    ///     let (omega, error) = boundary.cap_solid_angle(p).expect("finite");
    ///     let total = winding_number_brute(&open, p) + omega / (4.0 * std::f64::consts::PI);
    ///     assert!((total - total.round()).abs() < 1e-9 && error < 1e-9);
    /// }
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// One solid angle per boundary edge.
    #[must_use]
    pub fn cap_solid_angle(&self, p: DVec3) -> Option<(f64, f64)> {
        if !p.is_finite() {
            return None;
        }
        let mut omega = 0.0;
        let mut error = 0.0;
        let mut magnitude = 0.0;
        let size = self.scale + p.abs().max_element();
        let perturbation = 2.0 * f64::EPSILON * size;
        // Per vertex of a fan: the corner relative to `p`, its length and its dot product
        // with the apex's (shared by the two cap triangles of the vertex's two edges).
        let mut corners: Vec<(DVec3, f64, f64)> = Vec::new();
        for fan in &self.fans {
            let a = fan.apex - p;
            let la = a.length();
            corners.clear();
            corners.extend(
                self.fan_vertices
                    .get(fan.vertices.clone())
                    .unwrap_or(&[])
                    .iter()
                    .map(|&v| {
                        let r = v - p;
                        (r, r.length(), a.dot(r))
                    }),
            );
            for &(start, end, multiplicity) in self.fan_edges.get(fan.caps.clone()).unwrap_or(&[]) {
                // The triangle (apex, end, start): a, b, c.
                let (Some(&(b, lb, ab)), Some(&(c, lc, ca))) =
                    (corners.get(end as usize), corners.get(start as usize))
                else {
                    continue; // invariant: fan edges index their fan's vertices; never taken
                };
                let numerator = a.dot(b.cross(c));
                let denominator = la * lb * lc + ab * lc + b.dot(c) * la + ca * lb;
                let term = 2.0 * numerator.atan2(denominator);
                // atan2(y, x) moves by at most (|dy| + |dx|) / hypot(x, y) ≤ (|dy| + |dx|)
                // / max(|x|, |y|) (its gradient has norm 1 / hypot). The numerator and the
                // denominator are off by at most SOLID_ANGLE_ERROR |a| |b| |c| from their
                // operations, and by what the rounding of the differences `corner − p`
                // (each coordinate within an ulp of the larger of the two, at most `size`)
                // moves them: a perturbation `e` of one corner changes each trilinear term
                // by at most `|e|` times the product of the other two lengths, and the
                // formula has six of them (the denominator's four, the triple product
                // counted twice over). Doubled for `2 atan2`; an ulp or two of `2π` for the
                // atan2 itself.
                let larger = numerator.abs().max(denominator.abs());
                let moved = SOLID_ANGLE_ERROR * la * lb * lc
                    + 8.0 * perturbation * (la * lb + lb * lc + lc * la);
                let conditioning = if larger > 0.0 {
                    2.0 * moved / larger
                } else {
                    f64::INFINITY
                };
                omega += multiplicity * term;
                magnitude += (multiplicity * term).abs();
                error += multiplicity.abs() * (conditioning + 8.0 * f64::EPSILON * 2.0 * PI);
            }
        }
        // The sum's own rounding: an ulp of the running magnitude per addition.
        let count = self.caps.len() as f64;
        error += (count + 16.0) * 2.0 * f64::EPSILON * magnitude;
        Some((omega, error))
    }

    /// The side of `p` and a certified margin `|w − ½|` of the mesh's winding number,
    /// given `closed`, the (integer) winding number at `p` of the mesh closed by its caps
    /// ([`WindingNumber::capped_side`](super::WindingNumber::capped_side) gives it; it is
    /// constant along any path that meets neither the mesh nor the caps,
    /// [`WindingBoundary::caps_avoid_segment`]): `w = closed − Ω_C / 4π`, exactly up to the
    /// caps' rounding, which the margin takes off. `None` where that rounding leaves no
    /// margin (on the winding number's `½` level set, or within a tiny distance of a cap
    /// triangle's edge) or for non-finite input.
    #[must_use]
    pub fn side_given_closed(&self, p: DVec3, closed: f64) -> Option<CertifiedSide> {
        let (cap, cap_error) = self.cap_solid_angle(p)?;
        side_from(closed, cap, cap_error)
    }

    /// Whether the segment `[a, b]` certainly meets no cap triangle (so that the winding
    /// number of the mesh closed by its caps is the same at both ends when the segment
    /// meets no triangle of the mesh either). Conservative: `false` when the ball on the
    /// segment comes within rounding of a cap triangle.
    #[must_use]
    pub fn caps_avoid_segment(&self, a: DVec3, b: DVec3) -> bool {
        let middle = 0.5 * (a + b);
        let half = 0.5 * a.distance(b);
        if !middle.is_finite() || !half.is_finite() {
            return false;
        }
        let slack = ROUNDING * (half + self.scale + middle.abs().max_element());
        let reach = half + slack;
        for fan in &self.fans {
            if fan.apex.distance(middle) > fan.radius + reach {
                continue;
            }
            for cap in self.caps.get(fan.caps.clone()).unwrap_or(&[]) {
                let triangle = Triangle::new(cap.apex, cap.end, cap.start);
                let squared = point_triangle_distance_squared(middle, &triangle);
                if squared <= reach * reach {
                    return false;
                }
            }
        }
        true
    }

    /// An upper bound of `|∇w|` at every point of the ball of `radius` about `center` that
    /// is not on the mesh (see the notes of the `winding::boundary` source module): 0 for an empty
    /// boundary, `f64::INFINITY` when the ball reaches the boundary (or for non-finite
    /// input).
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// A descent of the hierarchy over the boundary edges: clusters at least four of
    /// their radii away from the ball are bounded at once.
    #[must_use]
    pub fn gradient_bound(&self, center: DVec3, radius: f64) -> f64 {
        if self.edges.is_empty() {
            return 0.0;
        }
        if !center.is_finite() || !radius.is_finite() {
            return f64::INFINITY;
        }
        let radius = radius.max(0.0);
        let slack = |d: f64| ROUNDING * (d + radius + self.scale + center.abs().max_element());
        let mut sum = 0.0;
        let mut stack: Vec<u32> = vec![0];
        while let Some(index) = stack.pop() {
            let Some(node) = self.nodes.get(index as usize) else {
                continue; // invariant: child indices are in range; never taken
            };
            let to_center = center.distance(node.center);
            let gap = to_center - node.radius - radius;
            if gap >= FAR * node.radius {
                let gap = gap - slack(to_center);
                sum += node.weight / (gap * gap);
                continue;
            }
            if node.count == 0 {
                stack.push(node.first);
                stack.push(index + 1);
                continue;
            }
            let start = node.first as usize;
            let end = start + node.count as usize;
            for edge in self.edges.get(start..end).unwrap_or(&[]) {
                let distance = closest_point_on_segment(center, edge.start, edge.end)
                    .distance_squared
                    .sqrt();
                let gap = distance - radius - slack(distance);
                if gap <= 0.0 {
                    return f64::INFINITY;
                }
                sum += edge.weight / (gap * gap);
            }
        }
        sum / (4.0 * PI) * (1.0 + 1e-9)
    }

    /// Builds the node of `edges[start..end]` at the end of `nodes` (its children after
    /// it), sorting the edges by their midpoints along the longest axis (ties by the
    /// current order: deterministic).
    fn build(&mut self, start: usize, end: usize) -> usize {
        let slice = &self.edges[start..end];
        let (mut low, mut high) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for e in slice {
            low = low.min(e.start.min(e.end));
            high = high.max(e.start.max(e.end));
        }
        let center = 0.5 * (low + high);
        let radius = slice
            .iter()
            .map(|e| center.distance(e.start).max(center.distance(e.end)))
            .fold(0.0, f64::max)
            * (1.0 + ROUNDING);
        let weight = slice.iter().map(|e| e.weight).sum();
        let index = self.nodes.len();
        self.nodes.push(Node {
            center,
            radius,
            weight,
            first: start as u32,
            count: (end - start) as u32,
        });
        if end - start <= LEAF_EDGES {
            return index;
        }
        let extent = high - low;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let key = |e: &Edge| (e.start + e.end)[axis];
        self.edges[start..end].sort_by(|a, b| key(a).total_cmp(&key(b)));
        let middle = start + (end - start) / 2;
        self.build(start, middle);
        let second = self.build(middle, end);
        self.nodes[index].count = 0;
        self.nodes[index].first = second as u32;
        index
    }
}

/// The side and margin of `w = closed − cap / 4π`, with `cap` within `cap_error` of the
/// caps' exact solid angle modulo `4π` (see [`WindingBoundary::side_given_closed`]).
pub(crate) fn side_from(closed: f64, cap: f64, cap_error: f64) -> Option<CertifiedSide> {
    let full = 4.0 * PI;
    let w = closed - cap / full;
    let rounding = 8.0 * f64::EPSILON * (closed.abs() + cap.abs() / full + 1.0);
    let margin = (w - 0.5).abs() - cap_error / full - rounding;
    (margin > 0.0 && w.is_finite()).then_some(CertifiedSide {
        inside: w > 0.5,
        margin,
    })
}

/// The cap triangles of a boundary chain (edges by canonical vertices, with their signed
/// multiplicities): every connected component coned off from the mean of its vertices
/// (see the notes of the `winding::boundary` source module).
#[allow(clippy::type_complexity)]
fn cone_off(
    positions: &[DVec3],
    chain: &[(u32, u32, i64)],
) -> (Vec<Cap>, Vec<Fan>, Vec<DVec3>, Vec<(u32, u32, f64)>) {
    // Connected components of the chain's vertices (union by index, deterministic).
    let mut parent: HashMap<u32, u32> = HashMap::with_capacity(2 * chain.len());
    fn root(parent: &mut HashMap<u32, u32>, v: u32) -> u32 {
        let mut r = v;
        while let Some(&up) = parent.get(&r) {
            if up == r {
                break;
            }
            r = up;
        }
        // Path compression.
        let mut x = v;
        while x != r {
            let up = parent.get(&x).copied().unwrap_or(r);
            parent.insert(x, r);
            x = up;
        }
        r
    }
    for &(a, b, _) in chain {
        parent.entry(a).or_insert(a);
        parent.entry(b).or_insert(b);
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        if ra != rb {
            parent.insert(ra.max(rb), ra.min(rb));
        }
    }
    // The apex of each component: the mean of its distinct vertices.
    let mut vertices: Vec<u32> = parent.keys().copied().collect();
    vertices.sort_unstable();
    let mut sums: HashMap<u32, (DVec3, f64)> = HashMap::new();
    for &v in &vertices {
        let r = root(&mut parent, v);
        let entry = sums.entry(r).or_insert((DVec3::ZERO, 0.0));
        entry.0 += positions[v as usize];
        entry.1 += 1.0;
    }
    // The caps by component (components in the order of their roots, edges in the
    // chain's order within each), with a ball about the apex containing them.
    let mut by_component: Vec<(u32, u32, u32, Cap)> = chain
        .iter()
        .map(|&(a, b, net)| {
            let r = root(&mut parent, a);
            let (sum, count) = sums
                .get(&r)
                .copied()
                .unwrap_or((positions[a as usize], 1.0));
            let cap = Cap {
                apex: sum / count,
                start: positions[a as usize],
                end: positions[b as usize],
                multiplicity: net as f64,
            };
            (r, a, b, cap)
        })
        .collect();
    by_component.sort_by_key(|&(r, ..)| r);
    let caps: Vec<Cap> = by_component.iter().map(|&(.., cap)| cap).collect();
    let mut fans = Vec::new();
    let mut fan_vertices = Vec::new();
    let mut fan_edges = Vec::with_capacity(caps.len());
    let mut start = 0;
    while start < by_component.len() {
        let r = by_component[start].0;
        let end = start
            + by_component[start..]
                .iter()
                .take_while(|c| c.0 == r)
                .count();
        let apex = caps[start].apex;
        let radius = caps[start..end]
            .iter()
            .map(|c| apex.distance(c.start).max(apex.distance(c.end)))
            .fold(0.0, f64::max)
            * (1.0 + ROUNDING);
        // The fan's distinct vertices, in the order they are first met.
        let first_vertex = fan_vertices.len();
        let mut local: HashMap<u32, u32> = HashMap::new();
        for &(_, a, b, cap) in &by_component[start..end] {
            let mut index = |v: u32| {
                let next = local.len() as u32;
                *local.entry(v).or_insert_with(|| {
                    fan_vertices.push(positions[v as usize]);
                    next
                })
            };
            let (ia, ib) = (index(a), index(b));
            fan_edges.push((ia, ib, cap.multiplicity));
        }
        fans.push(Fan {
            apex,
            radius,
            caps: start..end,
            vertices: first_vertex..fan_vertices.len(),
        });
        start = end;
    }
    (caps, fans, fan_vertices, fan_edges)
}
