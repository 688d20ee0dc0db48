//! Geometric primitives every Sphaera crate needs.

mod circumsphere;
mod closest_point;
mod enclosing_ball;
mod triangle;

pub use circumsphere::{ball_through_two_points, circumball_of_triangle, circumsphere};
pub use closest_point::{
    Feature, SegmentClosestPoint, SegmentFeature, TriangleClosestPoint, closest_point_on_segment,
    closest_point_on_triangle, point_triangle_distance_squared,
};
pub use enclosing_ball::{
    EnclosingBall, minimum_enclosing_ball, minimum_enclosing_ball_with_support,
};
pub use triangle::Triangle;
