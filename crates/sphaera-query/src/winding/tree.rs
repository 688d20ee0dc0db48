//! The bounding-volume hierarchy of [`WindingNumber`](super::WindingNumber): a binary tree
//! over the triangles with, per node, the far-field expansion of its triangles' area-weighted
//! normals.

use glam::{DMat3, DVec3};

use crate::QueryError;
use crate::bvh::BoxTree;
use sphaera_mesh::TriMesh;

/// Most triangles in a leaf.
pub(crate) const LEAF_SIZE: usize = 8;

/// One node of the tree. Nodes are stored depth-first: the left child of an inner node is
/// the next node, the right child is at `first`.
#[derive(Clone, Debug)]
pub(crate) struct Node {
    /// Expansion centre: the area-weighted mean of the triangle centroids (their plain mean
    /// when the area is zero).
    pub(crate) center: DVec3,
    /// Largest distance from `center` to a corner of the node's triangles.
    pub(crate) radius: f64,
    /// Total area of the node's triangles.
    pub(crate) area: f64,
    /// `Σ area_t · n_t`: the dipole moment.
    pub(crate) normal_sum: DVec3,
    /// `Σ_t (centroid_t − center) ⊗ N_t` with `N_t = area_t · n_t` (entry `(j, k)` is
    /// `d_j N_k`): the moment of the second-order term.
    pub(crate) moment: DMat3,
    /// `Q[i] = Σ_t N_t,i ∫_t (p − center)(p − center)ᵀ dA / area_t`: the moments of the
    /// third-order term (each matrix symmetric).
    pub(crate) quadratic_moment: [DMat3; 3],
    /// `2 u + v` with `u_k = Σ_i Q[i]_(i,k)` and `v_i = trace Q[i]`: the contractions of
    /// `quadratic_moment` the third-order term needs.
    pub(crate) quadratic_contraction: DVec3,
    /// Leaf: index of the first triangle in the reordered triangle array. Inner node: index
    /// of the right child.
    pub(crate) first: u32,
    /// Leaf: number of triangles (at least one). Inner node: zero.
    pub(crate) count: u32,
}

/// The tree and the triangle corners, reordered so that each leaf's triangles are
/// contiguous.
#[derive(Clone, Debug)]
pub(crate) struct Tree {
    pub(crate) nodes: Vec<Node>,
    pub(crate) corners: Vec<[DVec3; 3]>,
}

/// Per-triangle data used during the build.
struct Item {
    centroid: DVec3,
    /// `area · unit normal`, that is half the scaled normal.
    area_normal: DVec3,
    area: f64,
    /// `∫_t (p − centroid)(p − centroid)ᵀ dA / area`, which is
    /// `(1/12) Σ_corners (v − centroid)(v − centroid)ᵀ`.
    covariance: DMat3,
    corners: [DVec3; 3],
}

impl Tree {
    /// Builds the tree: the workspace's [`BoxTree`] over the triangles (median splits of
    /// the centroids, at most [`LEAF_SIZE`] per leaf), then each node's expansion over its
    /// triangles in tree order. `mesh` must have at least one triangle and
    /// fewer than `u32::MAX` (the caller checks both).
    pub(crate) fn build(mesh: &TriMesh) -> Result<Self, QueryError> {
        let boxes = BoxTree::build(&crate::closest::triangle_boxes(mesh), LEAF_SIZE)?;
        Ok(Self::with_boxes(mesh, &boxes))
    }

    /// The tree of `mesh` (at least one triangle, fewer than `u32::MAX`) on `boxes`, the
    /// box tree over [`triangle_boxes`](crate::closest::triangle_boxes) with [`LEAF_SIZE`]
    /// (built, or refined from a coarser build).
    pub(crate) fn with_boxes(mesh: &TriMesh, boxes: &BoxTree) -> Self {
        let items: Vec<Item> = mesh
            .triangle_iter()
            .map(|t| {
                let area_normal = 0.5 * t.scaled_normal();
                let centroid = t.centroid();
                let covariance = t
                    .corners()
                    .iter()
                    .map(|&v| outer(v - centroid, v - centroid))
                    .fold(DMat3::ZERO, |acc, m| acc + m)
                    * (1.0 / 12.0);
                Item {
                    centroid,
                    area_normal,
                    area: area_normal.length(),
                    covariance,
                    corners: t.corners(),
                }
            })
            .collect();
        // The items in tree order, so that every node's triangles are one contiguous run
        // of them (read in the same order as through `order`: the same sums).
        let mut slots: Vec<Option<Item>> = items.into_iter().map(Some).collect();
        let items: Vec<Item> = boxes
            .order()
            .iter()
            .filter_map(|&i| slots[i as usize].take())
            .collect();
        drop(slots);
        // Each node's expansion sums over its triangles in tree order: independent per
        // node, so computed side by side with `parallel`, with the same sums either way.
        let expand = |shape: &crate::bvh::BoxNode| {
            let mut node = expansion_of(&items[shape.items()]);
            // Lossless: the caller checked that the triangle count fits a u32.
            (node.first, node.count) = match shape.right() {
                Some(right) => (right as u32, 0),
                None => (shape.items().start as u32, shape.items().len() as u32),
            };
            node
        };
        #[cfg(feature = "parallel")]
        let nodes: Vec<Node> = {
            use rayon::prelude::*;
            boxes.nodes().par_iter().map(expand).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let nodes: Vec<Node> = boxes.nodes().iter().map(expand).collect();
        let corners = items.iter().map(|item| item.corners).collect();
        Self { nodes, corners }
    }
}

/// The expansion (centre, radius, moments) of the triangles `items`.
fn expansion_of(items: &[Item]) -> Node {
    let mut area = 0.0;
    let mut weighted = DVec3::ZERO;
    let mut plain = DVec3::ZERO;
    let mut normal_sum = DVec3::ZERO;
    for item in items {
        area += item.area;
        weighted += item.area * item.centroid;
        plain += item.centroid;
        normal_sum += item.area_normal;
    }
    // `items` is never empty (the median split leaves at least LEAF_SIZE / 2 on each side).
    let count = items.len().max(1) as f64;
    let center = if area > 0.0 && (weighted / area).is_finite() {
        weighted / area
    } else {
        plain / count
    };
    let mut moment = DMat3::ZERO;
    let mut quadratic_moment = [DMat3::ZERO; 3];
    let mut radius_squared: f64 = 0.0;
    for item in items {
        let d = item.centroid - center;
        let n = item.area_normal;
        moment += outer(d, n);
        let second = item.covariance + outer(d, d);
        for (q, n_i) in quadratic_moment.iter_mut().zip(n.to_array()) {
            *q += second * n_i;
        }
        for corner in item.corners {
            radius_squared = radius_squared.max(corner.distance_squared(center));
        }
    }
    let [q0, q1, q2] = quadratic_moment;
    let u = DVec3::new(q0.x_axis.x, q0.y_axis.x, q0.z_axis.x)
        + DVec3::new(q1.x_axis.y, q1.y_axis.y, q1.z_axis.y)
        + DVec3::new(q2.x_axis.z, q2.y_axis.z, q2.z_axis.z);
    let v = DVec3::new(trace(&q0), trace(&q1), trace(&q2));
    Node {
        center,
        radius: radius_squared.sqrt(),
        area,
        normal_sum,
        moment,
        quadratic_moment,
        quadratic_contraction: 2.0 * u + v,
        first: 0,
        count: 0,
    }
}

/// The outer product `a bᵀ` (entry `(j, k)` is `a_j b_k`).
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The trace of `m`.
pub(crate) fn trace(m: &DMat3) -> f64 {
    m.x_axis.x + m.y_axis.y + m.z_axis.z
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::shapes;

    #[test]
    fn leaves_partition_the_triangles_and_radii_cover_them() {
        let mesh = shapes::torus(1.0, 0.35, 20).unwrap();
        let tree = Tree::build(&mesh).unwrap();
        assert_eq!(tree.corners.len(), mesh.triangle_count());
        let mut covered = vec![false; tree.corners.len()];
        for (index, node) in tree.nodes.iter().enumerate() {
            if node.count == 0 {
                assert!(node.first as usize > index + 1);
                continue;
            }
            assert!(node.count as usize <= LEAF_SIZE);
            let range = node.first as usize..(node.first + node.count) as usize;
            for t in range {
                assert!(!covered[t]);
                covered[t] = true;
                for corner in tree.corners[t] {
                    assert!(corner.distance(node.center) <= node.radius * (1.0 + 1e-12));
                }
            }
        }
        assert!(covered.iter().all(|&c| c));
        // The root's dipole moment of a closed surface vanishes.
        assert!(tree.nodes[0].normal_sum.length() < 1e-12);
    }

    #[test]
    fn build_is_deterministic() {
        let mesh = shapes::sphere(1.0, 24).unwrap();
        let (a, b) = (Tree::build(&mesh).unwrap(), Tree::build(&mesh).unwrap());
        assert_eq!(a.corners, b.corners);
        assert_eq!(a.nodes.len(), b.nodes.len());
    }
}
