//! Whether inside/outside is meaningful for a mesh: [`WindingNumber::solidity`] and
//! [`WindingNumber::check_solid`].

use glam::DVec3;

use super::WindingNumber;
use crate::QueryError;

/// Most probe triangles [`WindingNumber::solidity`] examines.
const MAX_PROBES: usize = 64;

/// [`WindingNumber::check_solid`] fails when no probe reaches this `|w|`.
pub const SOLID_THRESHOLD: f64 = 0.75;

/// [`WindingNumber::check_solid`] reports an inward orientation when the median winding
/// number just behind the triangles is below this.
pub const INWARD_THRESHOLD: f64 = 0.25;

/// What [`WindingNumber::solidity`] measured next to the surface.
///
/// Probe points sit just behind and just in front of sample triangles (at
/// `centroid ∓ δ · normal`, `δ = 10⁻³ √area`). Crossing any surface changes the winding
/// number by one, so the two probes of a triangle read:
///
/// | mesh | behind (`− normal`) | in front (`+ normal`) |
/// |---|---|---|
/// | closed, outward oriented (a solid) | 1 | 0 |
/// | closed, inward oriented | 0 | −1 |
/// | a lone open sheet | ½ | −½ |
/// | a solid with small holes (a scan) | ≈ 1 | ≈ 0 |
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::TriMesh;
/// use sphaera_query::winding::WindingNumber;
///
/// let tetrahedron = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// let report = WindingNumber::new(&tetrahedron)?.solidity();
/// assert_eq!(report.probes, 4);
/// assert!((report.max_abs_winding - 1.0).abs() < 1e-3);
/// assert!((report.median_inner_winding - 1.0).abs() < 1e-3);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidityReport {
    /// Number of probe triangles (non-degenerate triangles evenly spaced in the tree's
    /// triangle order, at most 64).
    pub probes: usize,
    /// The largest `|w|` over all probe points: about 1 when the mesh encloses a volume,
    /// at most about ½ for a lone open sheet.
    pub max_abs_winding: f64,
    /// The median over the probe triangles of `w` just behind them: about 1 for an
    /// outward-oriented solid, 0 for an inward-oriented one, ½ for a sheet.
    pub median_inner_winding: f64,
}

impl WindingNumber {
    /// Measures how much the mesh encloses a volume; see [`SolidityReport`] for what the
    /// numbers mean and [`WindingNumber::check_solid`] for the verdict.
    ///
    /// # Examples
    ///
    /// See [`SolidityReport`].
    ///
    /// # Panics
    ///
    /// Never. A mesh whose triangles are all degenerate gives zero probes and zero
    /// windings.
    ///
    /// # Performance
    ///
    /// 128 winding-number queries.
    pub fn solidity(&self) -> SolidityReport {
        let corners = &self.tree.corners;
        let candidates: Vec<(DVec3, DVec3, f64)> = corners
            .iter()
            .filter_map(|&[a, b, c]| {
                let scaled = (b - a).cross(c - a);
                let normal = scaled.try_normalize()?;
                let area = 0.5 * scaled.length();
                Some(((a + b + c) / 3.0, normal, area))
            })
            .collect();
        let step = candidates.len().div_ceil(MAX_PROBES).max(1);
        let mut inner = Vec::new();
        let mut max_abs_winding: f64 = 0.0;
        for &(centroid, normal, area) in candidates.iter().step_by(step) {
            let offset = 1e-3 * area.sqrt();
            let behind = self.winding_number(centroid - offset * normal);
            let in_front = self.winding_number(centroid + offset * normal);
            max_abs_winding = max_abs_winding.max(behind.abs()).max(in_front.abs());
            inner.push(behind);
        }
        inner.sort_by(f64::total_cmp);
        let median_inner_winding = inner.get(inner.len() / 2).copied().unwrap_or(0.0);
        SolidityReport {
            probes: inner.len(),
            max_abs_winding,
            median_inner_winding,
        }
    }

    /// Checks that inside/outside is meaningful: the mesh encloses a volume
    /// ([`SolidityReport::max_abs_winding`] at least [`SOLID_THRESHOLD`] = 0.75) and is
    /// oriented outward ([`SolidityReport::median_inner_winding`] at least
    /// [`INWARD_THRESHOLD`] = 0.25). Open scans with small holes pass; lone sheets, loose
    /// open patches and inward-oriented meshes fail. The criterion is deliberately simple:
    /// a surface that wraps around a region enough for `|w|` to reach 0.75 somewhere passes
    /// (a hemispherical bowl reaches about 0.85 near its pole, so it passes, and its
    /// "inside" is the part of the ball where `w > ½`).
    ///
    /// # Errors
    ///
    /// - [`QueryError::NotSolid`] if no probe sees `|w|` of at least 0.75 (for example a
    ///   flat sheet, where `|w| ≤ ½`);
    /// - [`QueryError::InwardOrientation`] if the interior lies in front of the triangles
    ///   (flip every triangle to fix it).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_query::QueryError;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let tetrahedron = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// assert!(WindingNumber::new(&tetrahedron)?.check_solid().is_ok());
    ///
    /// let square = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let err = WindingNumber::new(&square)?.check_solid().unwrap_err();
    /// assert!(matches!(err, QueryError::NotSolid { .. }));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Performance
    ///
    /// As [`WindingNumber::solidity`].
    pub fn check_solid(&self) -> Result<SolidityReport, QueryError> {
        let report = self.solidity();
        if report.max_abs_winding.is_nan() || report.max_abs_winding < SOLID_THRESHOLD {
            return Err(QueryError::NotSolid {
                max_abs_winding: report.max_abs_winding,
                threshold: SOLID_THRESHOLD,
            });
        }
        if report.median_inner_winding < INWARD_THRESHOLD {
            return Err(QueryError::InwardOrientation {
                median_inner_winding: report.median_inner_winding,
            });
        }
        Ok(report)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::TriMesh;
    use sphaera_mesh::{shapes, shapes::fixtures};

    #[test]
    fn closed_shapes_are_solid() {
        for (name, mesh) in fixtures::closed_shapes() {
            let report = WindingNumber::new(&mesh).unwrap().check_solid();
            let report = report.unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!((report.median_inner_winding - 1.0).abs() < 1e-2, "{name}");
        }
    }

    #[test]
    fn flat_sheet_is_not_solid() {
        let sheet = fixtures::unit_sheet(20);
        let err = WindingNumber::new(&sheet)
            .unwrap()
            .check_solid()
            .unwrap_err();
        let QueryError::NotSolid {
            max_abs_winding, ..
        } = err
        else {
            panic!("{err}");
        };
        assert!(max_abs_winding <= 0.5 + 1e-3, "{max_abs_winding}");
    }

    #[test]
    fn inward_oriented_sphere_is_reported() {
        let (positions, triangles) = shapes::sphere(1.0, 20).unwrap().into_parts();
        let flipped = triangles.into_iter().map(|[a, b, c]| [a, c, b]).collect();
        let mesh = TriMesh::new(positions, flipped).unwrap();
        let err = WindingNumber::new(&mesh)
            .unwrap()
            .check_solid()
            .unwrap_err();
        assert!(matches!(err, QueryError::InwardOrientation { .. }), "{err}");
    }

    #[test]
    fn sphere_with_a_hole_is_still_solid() {
        let mesh = fixtures::sphere_with_hole(48, 22.5);
        let report = WindingNumber::new(&mesh).unwrap().check_solid().unwrap();
        assert!(report.median_inner_winding > 0.9, "{report:?}");
    }

    #[test]
    fn hemisphere_bowl_passes_and_its_numbers_are_as_documented() {
        let bowl = fixtures::sphere_with_hole(32, 90.0);
        let report = WindingNumber::new(&bowl).unwrap().check_solid().unwrap();
        assert!(
            report.max_abs_winding > 0.8 && report.max_abs_winding < 0.95,
            "{report:?}"
        );
    }

    #[test]
    fn not_solid_message_says_what_is_wrong() {
        let sheet = fixtures::unit_sheet(2);
        let err = WindingNumber::new(&sheet)
            .unwrap()
            .check_solid()
            .unwrap_err();
        let message = err.to_string();
        assert!(
            message.starts_with("the mesh does not enclose a volume"),
            "{message}"
        );
        assert!(message.contains("below 0.75"), "{message}");
    }

    #[test]
    fn degenerate_only_mesh_is_not_solid() {
        let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X], vec![[0, 1, 1]]).unwrap();
        let err = WindingNumber::new(&mesh)
            .unwrap()
            .check_solid()
            .unwrap_err();
        assert!(matches!(err, QueryError::NotSolid { .. }), "{err}");
    }
}
