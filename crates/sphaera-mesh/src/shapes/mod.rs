//! Procedural closed test shapes with a resolution parameter.
//!
//! Every builder returns a closed, consistently outward-oriented, 2-manifold [`TriMesh`](crate::TriMesh)
//! without degenerate or duplicate triangles and without unreferenced vertices, centred
//! near the origin. The set is the one the sphere-tree paper (Bradshaw and O'Sullivan,
//! "Adaptive medial-axis approximation for sphere-tree construction", 2004) evaluates on —
//! cube, ellipsoid, cylinder, torus, cone, an "S" swept tube and an "L" block — plus a
//! sphere, a capsule and a thick-walled tube (the thin-tube case where expand-select fails).
//!
//! | builder | genus | `resolution` means | analytic volume |
//! |---|---|---|---|
//! | [`cube`] | 0 | subdivisions per edge (≥ 1) | `size³` (exact) |
//! | [`sphere`] | 0 | segments around the equator (≥ 3) | `4/3 π r³` |
//! | [`ellipsoid`] | 0 | segments around the equator (≥ 3) | `4/3 π a b c` |
//! | [`capsule`] | 0 | segments around the axis (≥ 3) | `π r² l + 4/3 π r³` |
//! | [`cylinder`] | 0 | segments around the axis (≥ 3) | `π r² h` |
//! | [`cone`] | 0 | segments around the axis (≥ 3) | `π r² h / 3` |
//! | [`torus`] | 1 | segments around the axis (≥ 3) | `2 π² R r²` |
//! | [`thick_tube`] | 1 | segments around the axis (≥ 3) | `π (R² − r²) h` |
//! | [`s_tube`] | 0 | segments around the tube (≥ 3) | `π r² · 2π R` |
//! | [`l_block`] | 0 | subdivisions across the arm (≥ 1) | `(2 l − w) w d` (exact) |
//!
//! Two open builders stand apart: [`square_sheet`] and [`ring_sheet`] (a disc, or a
//! sheet with a hole) are flat sheets of zero thickness, with no inside, for
//! `sphaera_query::Surface::shell` and the methods that cover sheets.
//!
//! In every direction other than the one `resolution` counts, the builders pick the number
//! of pieces so that edges are about as long as around the main circle, so triangles stay
//! well shaped (the cone's apex and the caps' centres are single vertices with fans of
//! triangles — never degenerate slivers). Round shapes are inscribed polygonal
//! approximations: their volume is below the analytic one and converges as
//! `O(1/resolution²)` (see [`Shape::volume`] for the bound the tests check).
//!
//! [`Shape`] names each shape with its parameters, and [`DEFAULT_SHAPES`] lists one of each
//! with sensible proportions, for tests that want to run over all of them.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::shapes::{self, DEFAULT_SHAPES};
//!
//! let torus = shapes::torus(1.0, 0.25, 32)?;
//! let v = torus.vertex_count() as i64;
//! let f = torus.triangle_count() as i64;
//! // A closed triangle mesh has 3F/2 edges; Euler characteristic V − E + F = 2 − 2·genus.
//! assert_eq!(v - 3 * f / 2 + f, 0);
//! assert!(torus.surface_area() > 0.0);
//!
//! for shape in &DEFAULT_SHAPES {
//!     let mesh = shape.build(16)?;
//!     assert!(mesh.triangle_count() > 0, "{}", shape.name());
//! }
//!
//! // Bad parameters are errors, never panics.
//! assert!(shapes::torus(1.0, 2.0, 32).is_err());
//! assert!(shapes::sphere(f64::NAN, 32).is_err());
//! assert!(shapes::sphere(1.0, 2).is_err());
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! # Errors
//!
//! [`MeshError::InvalidParameter`] for a NaN, infinite, zero or negative size, a
//! resolution below the minimum, or proportions that would make the surface intersect
//! itself (a torus's minor radius not below its major radius, ...);
//! [`MeshError::ShapeTooLarge`] when the resolution and proportions would need more than
//! [`MAX_VERTICES`] vertices.
//!
//! # Performance
//!
//! Linear in the output: a round shape at resolution `r` has about `r²/2` to `r²`
//! vertices times its proportions (`torus(1.0, 0.3, 340)` has 69,360 triangles). The
//! builders are single-threaded and deterministic.

mod block;
mod catalog;
#[cfg(any(test, feature = "fixtures"))]
pub mod fixtures;
mod loft;
mod round;
mod sheet;
mod swept;
#[cfg(test)]
mod tests;

pub use block::{cube, l_block};
pub use catalog::{DEFAULT_SHAPES, Shape};
pub use round::{capsule, cone, cylinder, ellipsoid, sphere, thick_tube, torus};
pub use sheet::{ring_sheet, square_sheet};
pub use swept::s_tube;

use crate::MeshError;

/// The largest number of vertices a shape builder produces (2²⁶ ≈ 67 million, about
/// 1.6 GB of positions): a guard against a typo in `resolution` exhausting memory.
pub const MAX_VERTICES: usize = 1 << 26;

/// `Ok` if `value` is finite and positive.
fn check_positive(name: &'static str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(MeshError::InvalidParameter {
            name,
            value,
            requirement: "finite and positive",
        })
    }
}

/// `Ok` if `value` is finite and not negative.
fn check_non_negative(name: &'static str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(MeshError::InvalidParameter {
            name,
            value,
            requirement: "finite and not negative",
        })
    }
}

/// `Ok` if `resolution` is at least `minimum` (`requirement` says so in words).
fn check_resolution(
    resolution: usize,
    minimum: usize,
    requirement: &'static str,
) -> Result<(), MeshError> {
    if resolution >= minimum {
        Ok(())
    } else {
        Err(MeshError::InvalidParameter {
            name: "resolution",
            value: resolution as f64,
            requirement,
        })
    }
}

/// `Ok` if `smaller < larger`; the error names `smaller_name` with `requirement`.
fn check_less(
    smaller_name: &'static str,
    smaller: f64,
    larger: f64,
    requirement: &'static str,
) -> Result<(), MeshError> {
    if smaller < larger {
        Ok(())
    } else {
        Err(MeshError::InvalidParameter {
            name: smaller_name,
            value: smaller,
            requirement,
        })
    }
}

/// `Ok` if an estimated vertex count is within [`MAX_VERTICES`].
fn check_vertex_budget(shape: &'static str, vertices: f64) -> Result<(), MeshError> {
    if vertices.is_finite() && vertices <= MAX_VERTICES as f64 {
        Ok(())
    } else {
        Err(MeshError::ShapeTooLarge {
            shape,
            vertices,
            limit: MAX_VERTICES,
        })
    }
}
