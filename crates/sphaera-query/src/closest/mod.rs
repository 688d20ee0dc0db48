//! Exact closest points on a mesh: what an answer is ([`ClosestPoint`], with the
//! [`Feature`] of the mesh it lies on) and the [`TriangleTree`] that finds it for
//! independent queries.
//!
//! `sphaera-sweep`'s Meshsweeper sessions answer with the same [`ClosestPoint`]; they
//! are the engine for coherent queries (a point that moves a little each step) and
//! anytime bounds, where this tree is the engine for unrelated exact questions asked from
//! many threads (the medial approximation's Voronoi vertices, sampled Hausdorff
//! distances).
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_query::closest::{Feature, TriangleTree};
//!
//! let cube = shapes::cube(2.0, 1)?; // the cube [-1, 1]³, two triangles per face
//! let tree = TriangleTree::new(&cube)?;
//! let corner = tree.closest(DVec3::splat(3.0))?;
//! assert_eq!(corner.point, DVec3::ONE);
//! assert!(matches!(corner.feature, Feature::Vertex(_)));
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```

mod triangle_tree;

use glam::DVec3;

pub use triangle_tree::{ApproxClosest, TreeCursor, TriangleTree};
pub(crate) use triangle_tree::{LEAF_SIZE, triangle_boxes};

/// The feature of a mesh a closest point lies on (defined beside the closest point on a
/// triangle, in `sphaera-mesh`'s geometry).
pub use sphaera_mesh::geometry::Feature;

/// An exact closest point on a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    /// The closest point.
    pub point: DVec3,
    /// Its distance to the query point.
    pub distance: f64,
    /// The triangle it lies on (its index in the mesh queried; for a Meshsweeper
    /// session, in the mesh given to the simplifier).
    pub triangle: u32,
    /// The feature of that triangle it lies on.
    pub feature: Feature,
}
