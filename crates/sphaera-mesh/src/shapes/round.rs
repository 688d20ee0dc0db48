//! Surfaces of revolution: sphere, ellipsoid, capsule, cylinder, cone, torus, thick tube.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::{DVec2, DVec3};

use super::loft::{Profile, pieces};
use super::{
    check_less, check_non_negative, check_positive, check_resolution, check_vertex_budget,
};
use crate::{MeshError, TriMesh};

const AT_LEAST_3: &str = "at least 3";

/// Checks `resolution ≥ 3` and that `resolution` circles of `profile_points` points fit
/// the vertex budget (both as `f64`, before anything is allocated).
fn check_round(
    shape: &'static str,
    resolution: usize,
    profile_points: f64,
) -> Result<(), MeshError> {
    check_resolution(resolution, 3, AT_LEAST_3)?;
    check_vertex_budget(shape, profile_points * resolution as f64)
}

/// A UV sphere of `radius` centred at the origin, poles on the z axis.
///
/// `resolution` segments around the equator (at least 3) and `resolution / 2` (at least
/// 2) between the poles. Each pole is one vertex with a fan of triangles, so there are no
/// degenerate pole triangles. `resolution` 32 gives 2·32·15 = 960 triangles.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::sphere(2.0, 32)?;
/// assert_eq!(mesh.triangle_count(), 960);
/// assert!(mesh.positions().iter().all(|p| (p.length() - 2.0).abs() < 1e-12));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `radius` is not finite and positive or
/// `resolution < 3`; [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
///
/// # Panics
///
/// Never.
pub fn sphere(radius: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("radius", radius)?;
    check_round("sphere", resolution, resolution as f64 / 2.0 + 2.0)?;
    let rings = (resolution / 2).max(2);
    let mut profile = Profile::start(DVec2::new(0.0, -radius));
    profile.arc(DVec2::ZERO, radius, -FRAC_PI_2, FRAC_PI_2, rings);
    // The arc ends at ρ = r cos(π/2) ≈ 6e-17 r: `revolve` snaps it to an exact pole.
    profile.revolve("sphere", false, resolution)
}

/// An ellipsoid with the given semi-axes along x, y and z, centred at the origin.
///
/// The [`sphere`] of radius 1 with the same `resolution`, scaled per axis.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// let mesh = sphaera_mesh::shapes::ellipsoid(DVec3::new(2.0, 1.0, 0.5), 32)?;
/// let b = mesh.bounding_box();
/// assert!((b.max.x - 2.0).abs() < 1e-12 && (b.max.z - 0.5).abs() < 1e-12);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// As [`sphere`], for each semi-axis (`semi_axes.x`, `.y`, `.z`).
///
/// # Panics
///
/// Never.
pub fn ellipsoid(semi_axes: DVec3, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("semi_axes.x", semi_axes.x)?;
    check_positive("semi_axes.y", semi_axes.y)?;
    check_positive("semi_axes.z", semi_axes.z)?;
    let unit = sphere(1.0, resolution)?;
    let (positions, triangles) = unit.into_parts();
    // A scale by positive factors keeps the orientation.
    TriMesh::new(
        positions.into_iter().map(|p| p * semi_axes).collect(),
        triangles,
    )
}

/// A capsule: a cylinder of `radius` and `length` along z with hemispherical ends,
/// centred at the origin (total height `length + 2·radius`).
///
/// `resolution` segments around the axis (at least 3); edges along the axis are about as
/// long. `length` 0 gives a sphere.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 24)?;
/// let b = mesh.bounding_box();
/// assert!((b.max.z - 1.5).abs() < 1e-12);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `radius` is not finite and positive, `length` not
/// finite and non-negative, or `resolution < 3`; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn capsule(radius: f64, length: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("radius", radius)?;
    check_non_negative("length", length)?;
    let spacing = TAU * radius / resolution.max(1) as f64;
    check_round(
        "capsule",
        resolution,
        (PI * radius + length) / spacing + 4.0,
    )?;
    let half = 0.5 * length;
    let quarter = pieces(FRAC_PI_2 * radius, spacing);
    let mut profile = Profile::start(DVec2::new(0.0, -half - radius));
    profile.arc(DVec2::new(0.0, -half), radius, -FRAC_PI_2, 0.0, quarter);
    if length > 0.0 {
        profile.line_to(DVec2::new(radius, half), pieces(length, spacing));
    }
    profile.arc(DVec2::new(0.0, half), radius, 0.0, FRAC_PI_2, quarter);
    profile.revolve("capsule", false, resolution)
}

/// A closed cylinder of `radius` and `height` along z, centred at the origin, with flat
/// caps.
///
/// `resolution` segments around the axis (at least 3). The caps are concentric rings
/// around a single centre vertex, with edges about as long as around the rim.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::cylinder(1.0, 2.0, 16)?;
/// let b = mesh.bounding_box();
/// assert!((b.min.z + 1.0).abs() < 1e-12 && (b.max.z - 1.0).abs() < 1e-12);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `radius` or `height` is not finite and positive or
/// `resolution < 3`; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn cylinder(radius: f64, height: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    let spacing = TAU * radius / resolution.max(1) as f64;
    check_round(
        "cylinder",
        resolution,
        (2.0 * radius + height) / spacing + 4.0,
    )?;
    let (cap, side) = (pieces(radius, spacing), pieces(height, spacing));
    let h = 0.5 * height;
    let mut profile = Profile::start(DVec2::new(0.0, -h));
    profile.line_to(DVec2::new(radius, -h), cap);
    profile.line_to(DVec2::new(radius, h), side);
    profile.line_to(DVec2::new(0.0, h), cap);
    profile.revolve("cylinder", false, resolution)
}

/// A closed cone of base `radius` and `height` along z: base disc at `z = −height/2`,
/// apex at `z = height/2`.
///
/// `resolution` segments around the axis (at least 3). The apex is a single vertex (a fan
/// of `resolution` triangles), and so is the base centre.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// let mesh = sphaera_mesh::shapes::cone(1.0, 2.0, 16)?;
/// let apex = DVec3::new(0.0, 0.0, 1.0);
/// assert_eq!(mesh.positions().iter().filter(|&&p| p == apex).count(), 1);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `radius` or `height` is not finite and positive or
/// `resolution < 3`; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn cone(radius: f64, height: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    let spacing = TAU * radius / resolution.max(1) as f64;
    let slant = radius.hypot(height);
    check_round("cone", resolution, (radius + slant) / spacing + 4.0)?;
    let h = 0.5 * height;
    let mut profile = Profile::start(DVec2::new(0.0, -h));
    profile.line_to(DVec2::new(radius, -h), pieces(radius, spacing));
    profile.line_to(DVec2::new(0.0, h), pieces(slant, spacing));
    profile.revolve("cone", false, resolution)
}

/// A torus around the z axis: the circle of `minor_radius` in the xz-plane centred at
/// distance `major_radius` from the axis, revolved. Genus 1.
///
/// `resolution` segments around the z axis (at least 3); the minor circle gets
/// `resolution · minor_radius / major_radius` segments (at least 3).
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::torus(1.0, 0.25, 32)?;
/// // 32 rings of 8 vertices.
/// assert_eq!(mesh.vertex_count(), 256);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if a radius is not finite and positive,
/// `minor_radius ≥ major_radius` (the surface would intersect itself) or
/// `resolution < 3`; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn torus(
    major_radius: f64,
    minor_radius: f64,
    resolution: usize,
) -> Result<TriMesh, MeshError> {
    check_positive("major_radius", major_radius)?;
    check_positive("minor_radius", minor_radius)?;
    check_less(
        "minor_radius",
        minor_radius,
        major_radius,
        "less than `major_radius`",
    )?;
    let spacing = TAU * major_radius / resolution.max(1) as f64;
    check_round("torus", resolution, TAU * minor_radius / spacing + 4.0)?;
    let minor = pieces(TAU * minor_radius, spacing).max(3);
    let center = DVec2::new(major_radius, 0.0);
    let mut profile = Profile::start(center + DVec2::new(minor_radius, 0.0));
    // The arc's end repeats the start; the closed loft joins the last ring to the first.
    profile.arc(center, minor_radius, 0.0, TAU, minor);
    profile.points.pop();
    profile.revolve("torus", true, resolution)
}

/// A thick-walled tube: the annulus `inner_radius ≤ ρ ≤ outer_radius` extruded to
/// `height` along z, centred at the origin. Genus 1, with an inner and an outer wall and
/// flat annular ends — the thin-tube case where the sphere-tree paper's expand-select
/// reducer fails.
///
/// `resolution` segments around the axis (at least 3); edges along the profile are about
/// as long as around the outer circle.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::thick_tube(0.8, 1.0, 2.0, 32)?;
/// let inner = mesh.positions().iter().filter(|p| (p.truncate().length() - 0.8).abs() < 1e-12);
/// assert!(inner.count() > 0);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if a size is not finite and positive,
/// `inner_radius ≥ outer_radius` or `resolution < 3`; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn thick_tube(
    inner_radius: f64,
    outer_radius: f64,
    height: f64,
    resolution: usize,
) -> Result<TriMesh, MeshError> {
    check_positive("inner_radius", inner_radius)?;
    check_positive("outer_radius", outer_radius)?;
    check_positive("height", height)?;
    check_less(
        "inner_radius",
        inner_radius,
        outer_radius,
        "less than `outer_radius`",
    )?;
    let spacing = TAU * outer_radius / resolution.max(1) as f64;
    let wall = outer_radius - inner_radius;
    check_round(
        "thick_tube",
        resolution,
        2.0 * (wall + height) / spacing + 4.0,
    )?;
    let (across, along) = (pieces(wall, spacing), pieces(height, spacing));
    let h = 0.5 * height;
    // Counter-clockwise in the (ρ, z) half-plane: up the outer wall, in across the top,
    // down the inner wall, out across the bottom (the closing edge returns to the start).
    let mut profile = Profile::start(DVec2::new(outer_radius, -h));
    profile.line_to(DVec2::new(outer_radius, h), along);
    profile.line_to(DVec2::new(inner_radius, h), across);
    profile.line_to(DVec2::new(inner_radius, -h), along);
    profile.line_to(DVec2::new(outer_radius, -h), across);
    profile.points.pop();
    profile.revolve("thick_tube", true, resolution)
}
