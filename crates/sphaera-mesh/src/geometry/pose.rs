//! A mesh's canonical pose: a frame that moves, turns and scales with the mesh, so that
//! an algorithm run in it gives the same answer however the mesh is placed.
//!
//! An algorithm that breaks ties by coordinates, or that works on degenerate input (flat
//! faces, cospherical points), decides by rounding noise, and rounding noise changes when
//! the mesh is moved, turned or rescaled. Run in the canonical pose, it sees the same
//! numbers whatever similarity transform the user applied: the frame is built from
//! features that move with the mesh (its vertex centroid, its farthest vertex, the vertex
//! farthest from that axis, ties within [`TIE_TOLERANCE`] broken by the lowest vertex
//! index, which no transform changes), and the canonical coordinates are snapped to a
//! grid of power-of-two step, coarse enough to swallow the rounding noise of the
//! transform and fine enough to leave every triangle's shape alone.

use glam::DVec3;

use crate::{MeshError, Sphere, TriMesh};

/// Two candidate features (vertex distances) within this fraction of the largest count
/// as tied; the lowest vertex index wins. Far above the rounding noise of a moved mesh
/// (about 10⁻⁹ for a mesh 10⁶ of its own sizes from the origin), far below any real
/// difference worth keeping.
pub const TIE_TOLERANCE: f64 = 1e-6;

/// The coarsest snapping grid: a step of `2^-COARSEST_GRID_BITS` of the pose's size.
pub const COARSEST_GRID_BITS: i32 = 16;

/// The finest snapping grid (for meshes with triangles thinner than `2^-32` of their
/// size): a step of `2^-FINEST_GRID_BITS` of the pose's size.
pub const FINEST_GRID_BITS: i32 = 44;

/// The grid step is at most the thinnest triangle's height (relative to the pose's size)
/// divided by `2^GRID_MARGIN_BITS`, so snapping moves no vertex by more than 1/512 of any
/// triangle's height.
pub const GRID_MARGIN_BITS: i32 = 8;

/// A mesh's canonical pose: origin at its vertex centroid, axes from its farthest
/// vertices, unit the largest distance of a vertex from the centroid.
///
/// [`CanonicalPose::of`] a mesh moved, turned and scaled by any similarity (proper
/// rotation) is that similarity composed with the pose of the original, up to rounding;
/// [`CanonicalPose::canonical_mesh`] snaps the coordinates, so the canonical meshes of
/// the two are identical unless a coordinate lies within the rounding noise of a grid
/// cell's boundary. Scaling by a power of two changes nothing in the canonical mesh, bit
/// for bit, and [`CanonicalPose::point_from_canonical`] scales exactly.
///
/// # Examples
///
/// ```
/// use glam::DQuat;
/// use sphaera_mesh::{DVec3, TriMesh, geometry::CanonicalPose, shapes};
///
/// let mesh = shapes::capsule(0.5, 2.0, 8)?;
/// let turned = TriMesh::new(
///     mesh.positions()
///         .iter()
///         .map(|&p| DQuat::from_rotation_y(0.7) * p * 3.0 + DVec3::new(10.0, -4.0, 2.0))
///         .collect(),
///     mesh.triangles().to_vec(),
/// )?;
/// let (a, b) = (CanonicalPose::of(&mesh), CanonicalPose::of(&turned));
/// assert_eq!(a.canonical_mesh(&mesh)?.positions(), b.canonical_mesh(&turned)?.positions());
/// // Back to the mesh's own coordinates.
/// let p = b.point_from_canonical(b.point_to_canonical(turned.positions()[5]));
/// assert!(p.distance(turned.positions()[5]) <= b.size() * b.grid_step());
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CanonicalPose {
    origin: DVec3,
    axes: [DVec3; 3],
    size: f64,
    grid_bits: i32,
}

impl CanonicalPose {
    /// The canonical pose of `mesh` (of all its positions; the triangles set the grid).
    ///
    /// Degenerate meshes still get a pose: when every vertex sits at the centroid, the
    /// axes are the coordinate axes and the unit is 1; when every vertex lies on one line
    /// through it, the second axis is any direction perpendicular to the first.
    #[must_use]
    pub fn of(mesh: &TriMesh) -> Self {
        let positions = mesh.positions();
        let count = positions.len().max(1) as f64;
        let origin = positions.iter().fold(DVec3::ZERO, |sum, &p| sum + p) / count;
        let Some(first) = farthest(positions, |p| (p - origin).length()) else {
            return Self::unit(origin);
        };
        let size = (positions[first] - origin).length();
        if size.is_nan() || size <= 0.0 || size.is_infinite() {
            return Self::unit(origin);
        }
        let x = (positions[first] - origin) / size;
        let off_axis = |p: DVec3| {
            let v = p - origin;
            v - x * v.dot(x)
        };
        let y = farthest(positions, |p| off_axis(p).length())
            .map(|second| off_axis(positions[second]))
            .filter(|v| v.length() > TIE_TOLERANCE * size)
            .map_or_else(|| x.any_orthonormal_vector(), DVec3::normalize);
        let z = x.cross(y);
        let grid_bits = grid_bits(mesh, size);
        Self {
            origin,
            axes: [x, y, z],
            size,
            grid_bits,
        }
    }

    /// The pose of a mesh without extent: coordinate axes, unit 1, the coarsest grid.
    fn unit(origin: DVec3) -> Self {
        Self {
            origin,
            axes: [DVec3::X, DVec3::Y, DVec3::Z],
            size: 1.0,
            grid_bits: COARSEST_GRID_BITS,
        }
    }

    /// The unit of the canonical coordinates: the largest distance of a vertex from the
    /// centroid, in the mesh's units (1 for a mesh without extent).
    #[must_use]
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The origin: the vertex centroid, in the mesh's coordinates.
    #[must_use]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The step of the snapping grid, in canonical units (a power of two between
    /// `2^-FINEST_GRID_BITS` and `2^-COARSEST_GRID_BITS`).
    #[must_use]
    pub fn grid_step(&self) -> f64 {
        (-f64::from(self.grid_bits)).exp2()
    }

    /// `p` (in the mesh's coordinates) in canonical coordinates, snapped to the grid.
    #[must_use]
    pub fn point_to_canonical(&self, p: DVec3) -> DVec3 {
        let v = p - self.origin;
        let [x, y, z] = self.axes;
        let scale = f64::from(self.grid_bits).exp2();
        let snap = |c: f64| (c / self.size * scale).round() / scale + 0.0;
        DVec3::new(snap(v.dot(x)), snap(v.dot(y)), snap(v.dot(z)))
    }

    /// `c` (in canonical coordinates) in the mesh's coordinates.
    #[must_use]
    pub fn point_from_canonical(&self, c: DVec3) -> DVec3 {
        let [x, y, z] = self.axes;
        self.origin + (x * c.x + y * c.y + z * c.z) * self.size
    }

    /// A length in canonical units, in the mesh's units.
    #[must_use]
    pub fn length_from_canonical(&self, length: f64) -> f64 {
        length * self.size
    }

    /// A sphere in canonical coordinates, in the mesh's coordinates.
    #[must_use]
    pub fn sphere_from_canonical(&self, sphere: &Sphere) -> Sphere {
        Sphere::new(
            self.point_from_canonical(sphere.center),
            self.length_from_canonical(sphere.radius),
        )
    }

    /// `mesh` in canonical coordinates (every position snapped), the same triangles.
    ///
    /// # Errors
    ///
    /// As [`TriMesh::new`]; cannot fail for the mesh the pose was made of.
    pub fn canonical_mesh(&self, mesh: &TriMesh) -> Result<TriMesh, MeshError> {
        let positions = mesh
            .positions()
            .iter()
            .map(|&p| self.point_to_canonical(p))
            .collect();
        TriMesh::new(positions, mesh.triangles().to_vec())
    }

    /// The largest distance snapping moved a vertex of `mesh`, in the mesh's units,
    /// rounding of the way back included: every point of the mesh's surface lies within
    /// this of the same point (same triangle, same barycentric coordinates) of the
    /// canonical mesh mapped back.
    #[must_use]
    pub fn displacement(&self, mesh: &TriMesh) -> f64 {
        let moved = mesh
            .positions()
            .iter()
            .map(|&p| p.distance(self.point_from_canonical(self.point_to_canonical(p))))
            .fold(0.0, f64::max);
        // The computed distances are themselves rounded: add a few units of the
        // coordinates' last place.
        let reach = mesh
            .positions()
            .iter()
            .map(|p| p.abs().max_element())
            .fold(self.size, f64::max);
        moved + 16.0 * f64::EPSILON * reach
    }
}

/// The lowest index among the positions whose `measure` is within [`TIE_TOLERANCE`] of
/// the largest (none for an empty set or a largest of 0).
fn farthest(positions: &[DVec3], measure: impl Fn(DVec3) -> f64) -> Option<usize> {
    let largest = positions.iter().map(|&p| measure(p)).fold(0.0, f64::max);
    if largest.is_nan() || largest <= 0.0 {
        return None;
    }
    let threshold = largest * (1.0 - TIE_TOLERANCE);
    positions.iter().position(|&p| measure(p) >= threshold)
}

/// The snapping grid's bits: at least [`COARSEST_GRID_BITS`], enough that a step is at
/// most the thinnest non-degenerate triangle's height over `2^GRID_MARGIN_BITS`, at most
/// [`FINEST_GRID_BITS`].
fn grid_bits(mesh: &TriMesh, size: f64) -> i32 {
    let positions = mesh.positions();
    let thinnest = mesh
        .triangles()
        .iter()
        .filter_map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let doubled_area = (b - a).cross(c - a).length();
            let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
            (doubled_area > 0.0 && longest > 0.0).then(|| doubled_area / longest)
        })
        .fold(f64::INFINITY, f64::min);
    if !thinnest.is_finite() {
        return COARSEST_GRID_BITS;
    }
    let needed = (size / thinnest).log2().ceil() + f64::from(GRID_MARGIN_BITS);
    // Saturating float-to-int conversion, then clamped.
    (needed as i32).clamp(COARSEST_GRID_BITS, FINEST_GRID_BITS)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)]

    use glam::DQuat;

    use super::*;
    use crate::shapes;

    fn mapped(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec3) -> TriMesh {
        TriMesh::new(
            mesh.positions().iter().map(|&p| f(p)).collect(),
            mesh.triangles().to_vec(),
        )
        .unwrap()
    }

    #[test]
    fn a_turned_scaled_and_moved_cube_has_the_same_canonical_mesh() {
        // The cube is the hard case: every corner ties for farthest, every face is flat.
        let cube = shapes::cube(1.0, 4).unwrap();
        let reference = CanonicalPose::of(&cube).canonical_mesh(&cube).unwrap();
        for (k, scale) in [0.001, 0.37, 3.0, 1e3].into_iter().enumerate() {
            let rotation = DQuat::from_euler(glam::EulerRot::XYZ, 0.3 * k as f64, 1.1, -0.4);
            let shift = DVec3::new(1e3, -2e2, 7.0) * scale;
            let moved = mapped(&cube, |p| rotation * p * scale + shift);
            let pose = CanonicalPose::of(&moved);
            assert_eq!(
                pose.canonical_mesh(&moved).unwrap().positions(),
                reference.positions(),
                "scale {scale}"
            );
        }
    }

    #[test]
    fn scaling_by_a_power_of_two_changes_no_bit() {
        let mesh = shapes::capsule(0.4, 1.3, 9).unwrap();
        let pose = CanonicalPose::of(&mesh);
        let canonical = pose.canonical_mesh(&mesh).unwrap();
        for factor in [0.125, 4.0, 2f64.powi(40), 2f64.powi(-40)] {
            let scaled = mapped(&mesh, |p| p * factor);
            let scaled_pose = CanonicalPose::of(&scaled);
            assert_eq!(
                scaled_pose.canonical_mesh(&scaled).unwrap().positions(),
                canonical.positions()
            );
            let c = DVec3::new(0.3, -0.2, 0.9);
            assert_eq!(
                scaled_pose.point_from_canonical(c),
                pose.point_from_canonical(c) * factor
            );
            assert_eq!(scaled_pose.size(), pose.size() * factor);
        }
    }

    #[test]
    fn the_round_trip_moves_points_by_at_most_the_displacement() {
        let mesh = mapped(&shapes::torus(2.0, 0.5, 24).unwrap(), |p| {
            DQuat::from_rotation_x(0.4) * p * 1e-3 + DVec3::splat(5.0)
        });
        let pose = CanonicalPose::of(&mesh);
        let bound = pose.displacement(&mesh);
        assert!(bound > 0.0);
        assert!(bound <= pose.size() * pose.grid_step());
        for &p in mesh.positions() {
            let back = pose.point_from_canonical(pose.point_to_canonical(p));
            assert!(p.distance(back) <= bound);
        }
    }

    #[test]
    fn thin_triangles_get_a_finer_grid() {
        let coarse = CanonicalPose::of(&shapes::cube(1.0, 2).unwrap());
        assert_eq!(coarse.grid_step(), (-f64::from(COARSEST_GRID_BITS)).exp2());
        // A sliver 10⁻⁹ high beside an ordinary triangle.
        let flat = TriMesh::new(
            vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(0.5, 1e-9, 0.0),
                DVec3::new(0.5, -0.8, 0.0),
            ],
            vec![[0, 1, 2], [1, 0, 3]],
        )
        .unwrap();
        let fine = CanonicalPose::of(&flat);
        assert!(fine.grid_step() * fine.size() <= 1e-9 / 256.0);
    }

    #[test]
    fn meshes_without_extent_get_the_unit_pose() {
        let point = TriMesh::new(vec![DVec3::ONE; 3], vec![[0, 1, 2]]).unwrap();
        let pose = CanonicalPose::of(&point);
        assert_eq!(pose.size(), 1.0);
        assert_eq!(pose.point_to_canonical(DVec3::ONE), DVec3::ZERO);
        let line =
            TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0], vec![[0, 1, 2]]).unwrap();
        let pose = CanonicalPose::of(&line);
        let back = pose.point_from_canonical(pose.point_to_canonical(DVec3::X * 2.0));
        assert!(back.distance(DVec3::X * 2.0) < 1e-12);
    }
}
