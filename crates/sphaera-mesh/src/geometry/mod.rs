//! Geometric primitives every Sphaera crate needs.
//!
//! | concept | items |
//! |---|---|
//! | a triangle's own geometry | [`Triangle`] |
//! | closest point on a triangle or segment | [`closest_point_on_triangle`] (with the [`TriangleFeature`] hit), [`point_triangle_distance_squared`] (fast path), [`closest_point_on_segment`] |
//! | closest points between segments | [`closest_points_between_segments`] |
//! | balls through given points | [`ball_through_two_points`], [`circumball_of_triangle`], [`circumsphere`] |
//! | minimum enclosing balls | [`minimum_enclosing_ball`] (points), [`minimum_enclosing_ball_of_balls`], with the support: [`minimum_enclosing_ball_with_support`], [`minimum_enclosing_ball_of_balls_with_support`] |
//! | ray casting | [`ray_triangle_intersection`] |
//! | a frame that moves with the mesh (for answers independent of placement) | [`CanonicalPose`] |
//! | placing a mesh or spheres in a scene | [`Similarity`] (rotation or mirror, uniform scale, translation; [`Similarity::rigid`] for rigid motions) |
//!
//! Everything works in `f64` and is robust for degenerate input: zero-area, needle and
//! point triangles, zero-length segments, duplicate, collinear, coplanar and cospherical
//! points never produce NaN, and the closest-point and enclosing-ball answers are always
//! realised by actual points (a returned closest point lies on the triangle; every input
//! point lies inside a returned enclosing ball in floating point). Each function is tested
//! against brute force with proptest.
//!
//! # Examples
//!
//! ```
//! use glam::DVec3;
//! use sphaera_mesh::geometry::{
//!     Triangle, TriangleFeature, closest_point_on_triangle, minimum_enclosing_ball,
//! };
//!
//! let triangle = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
//! let hit = closest_point_on_triangle(DVec3::new(2.0, 2.0, 0.0), &triangle);
//! assert_eq!(hit.feature, TriangleFeature::Edge(1)); // edge 1 runs from b to c
//! assert!((hit.point - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
//!
//! let ball = minimum_enclosing_ball(&triangle.corners())?;
//! assert!((ball.center - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
//! assert!(triangle.corners().iter().all(|&p| ball.contains_point(p, 0.0)));
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```

mod circumsphere;
mod closest_point;
mod enclosing_ball;
mod enclosing_ball_core;
mod enclosing_ball_of_balls;
mod pose;
mod ray;
mod segment_segment;
mod similarity;
mod triangle;

pub use circumsphere::{ball_through_two_points, circumball_of_triangle, circumsphere};
pub use closest_point::{
    Feature, SegmentClosestPoint, SegmentFeature, TriangleClosestPoint, TriangleFeature,
    closest_point_on_segment, closest_point_on_triangle, point_triangle_distance_squared,
};
pub use enclosing_ball::{
    EnclosingBall, minimum_enclosing_ball, minimum_enclosing_ball_with_support,
};
pub use enclosing_ball_of_balls::{
    minimum_enclosing_ball_of_balls, minimum_enclosing_ball_of_balls_with_support,
};
pub use pose::{
    COARSEST_GRID_BITS, CanonicalPose, FINEST_GRID_BITS, GRID_MARGIN_BITS, TIE_TOLERANCE,
};
pub use ray::{RayTriangleHit, ray_triangle_intersection};
pub use segment_segment::{SegmentPairClosestPoints, closest_points_between_segments};
pub use similarity::{SIMILARITY_TOLERANCE, Similarity, TransformDefect};
pub use triangle::Triangle;
