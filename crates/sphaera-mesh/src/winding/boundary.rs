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

use std::collections::HashMap;
use std::f64::consts::PI;

use glam::DVec3;

use crate::TriMesh;
use crate::geometry::closest_point_on_segment;
use crate::topology::edge_table::{EdgeTable, halfedge_vertices};

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
/// [module documentation](self)) and the bound it gives on the gradient of the generalized
/// winding number.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh, shapes, winding::WindingBoundary};
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
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct WindingBoundary {
    edges: Vec<Edge>,
    nodes: Vec<Node>,
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
    /// of [`topology`](crate::topology)); about 0.1 s for the 871k-triangle dragon.
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
        let mut boundary = Self {
            edges,
            nodes: Vec::new(),
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

    /// An upper bound of `|∇w|` at every point of the ball of `radius` about `center` that
    /// is not on the mesh (see the [module documentation](self)): 0 for an empty
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
