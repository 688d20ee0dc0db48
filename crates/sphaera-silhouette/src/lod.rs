//! Level of detail guided by labels (section 3.3): the contour region gets the allowed
//! error `e · f`, the rest `e`. Which triangles are in it is a [`ContourRegion`]: the
//! paper's rule (a corner at most `threshold` cells from the silhouette) or the
//! certified one (the part of the original a triangle stands for may come that close).
//! (Counting a coarse corner with the smallest label of the input vertices collapsed
//! into it was tried: it puts most coarse triangles in the region and spends more
//! triangles for the same outline.) Extracted view by view from `sphaera-simplify`'s
//! progressive hierarchy, with the error-sphere bound of each region; or, for one mesh
//! that keeps the silhouettes of many views, as per-vertex tolerance weights for the
//! static simplifier.

use glam::DVec3;
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_simplify::{Hierarchy, Placement, Refinement, Simplified};

use crate::SilhouetteError;
use crate::labels::{Interpolation, Labels};
use crate::views::Projection;

/// Which triangles of an extraction are in the contour region (all in cells of the
/// labels' images, at the scale of the frame's nearest point).
///
/// Measured on meshes nobody tuned it for (`sphaera-eval`'s `silhouette_vs_simplify`):
/// [`ContourRegion::Widened`] keeps the outline best for its triangles; the paper's rule
/// misses coarse triangles whose error region reaches the outline (on a small mesh such
/// as `eight.off` most of the gain); [`ContourRegion::Certified`] spends triangles well
/// inside the outline for little more.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContourRegion {
    /// The paper's rule: a triangle with a corner whose label is at most `threshold`.
    /// A coarse triangle whose corners lie farther inside but which stands for a part
    /// of the original that reaches the outline is left out, and keeps the error allowed
    /// elsewhere.
    Corners,
    /// A triangle with a corner whose label, less the triangle's error bound, is at most
    /// `threshold`: the part of the original the triangle stands for lies within its
    /// bound of it, so the region holds every triangle that stands for a silhouette
    /// point near a corner, however coarse.
    #[default]
    Widened,
    /// Certified: a triangle whose error region may come within `threshold` of the
    /// silhouette anywhere. Labels are distances, so no point of the triangle's image is
    /// nearer the silhouette than a corner's label less that corner's distance to the
    /// farthest other corner (an edge length, which projection does not lengthen); the
    /// triangle is left out only when that, less its error bound, exceeds the threshold
    /// for some corner, and [`ContourRegion::Widened`] leaves it out too (labels
    /// interpolated between views need not be distances). Each rule's region holds the
    /// one before.
    Certified,
}

impl ContourRegion {
    /// The name users type and reports show (`"corners"`, `"widened"`, `"certified"`), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads
    /// it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Corners => "corners",
            Self::Widened => "widened",
            Self::Certified => "certified",
        }
    }
}

impl std::fmt::Display for ContourRegion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ContourRegion {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "corners" => Ok(Self::Corners),
            "widened" => Ok(Self::Widened),
            "certified" => Ok(Self::Certified),
            _ => Err(sphaera_mesh::ParseNameError::new(
                "contour region",
                s,
                "corners, widened or certified",
            )),
        }
    }
}

/// Decides which triangles are in the contour region for one view's labels.
struct Membership<'a> {
    region: ContourRegion,
    /// Per input vertex, its label (cells).
    labels: &'a [f32],
    threshold: f32,
    /// Cells per unit of length at the image's nearest point.
    cells_per_unit: f64,
}

impl Membership<'_> {
    /// Whether the triangle with the input vertices `inputs`, the positions `p` and the
    /// error bound `bound` is in the region.
    fn contains(&self, inputs: [u32; 3], p: [DVec3; 3], bound: f64) -> bool {
        self.region_contains(self.region, inputs, p, bound)
    }

    /// [`Membership::contains`] by the rule `region`.
    fn region_contains(
        &self,
        region: ContourRegion,
        inputs: [u32; 3],
        p: [DVec3; 3],
        bound: f64,
    ) -> bool {
        let label = |k: usize| self.labels[inputs[k] as usize];
        match region {
            ContourRegion::Corners => (0..3).any(|k| label(k) <= self.threshold),
            ContourRegion::Widened => {
                let nearest = (0..3).map(label).fold(f32::INFINITY, f32::min);
                f64::from(nearest) - bound * self.cells_per_unit <= f64::from(self.threshold)
            }
            ContourRegion::Certified => {
                if self.region_contains(ContourRegion::Widened, inputs, p, bound) {
                    return true;
                }
                let scale = self.cells_per_unit;
                let edge = [
                    p[0].distance(p[1]),
                    p[1].distance(p[2]),
                    p[2].distance(p[0]),
                ];
                let reach = [
                    edge[0].max(edge[2]),
                    edge[0].max(edge[1]),
                    edge[1].max(edge[2]),
                ];
                let nearest = (0..3)
                    .map(|k| f64::from(label(k)) - reach[k] * scale)
                    .fold(f64::NEG_INFINITY, f64::max)
                    - bound * scale;
                nearest <= f64::from(self.threshold)
            }
        }
    }
}

/// Per-vertex tolerance weights for [`sphaera_simplify::SimplifyOptions::with_weights`]:
/// `factor` for a vertex whose label is at most `threshold` cells in any of `views` (every
/// view when `views` is empty), 1 elsewhere. With `factor = 0` the contour of every chosen
/// view is kept exactly (the simplifier refuses weights that are all zero: a mesh that is
/// all contour cannot be simplified with `factor = 0`).
///
/// # Errors
///
/// [`SilhouetteError::InvalidParameter`] for a negative or non-finite `factor`, a NaN
/// `threshold`, or a view the labels do not have (an index past the last).
pub fn contour_weights(
    labels: &Labels,
    views: &[usize],
    threshold: f32,
    factor: f64,
) -> Result<Vec<f64>, SilhouetteError> {
    check("factor", factor)?;
    if threshold.is_nan() {
        return Err(SilhouetteError::InvalidParameter {
            name: "threshold",
            value: f64::from(threshold),
            requirement: "a number",
        });
    }
    let count = labels.views().len();
    if let Some(&k) = views.iter().find(|&&k| k >= count) {
        return Err(SilhouetteError::InvalidParameter {
            name: "view",
            value: k as f64,
            requirement: "the index of one of the labels' views",
        });
    }
    let chosen: Vec<usize> = if views.is_empty() {
        (0..count).collect()
    } else {
        views.to_vec()
    };
    let mut nearest = vec![f32::INFINITY; labels.vertex_count()];
    for k in chosen {
        for (n, l) in nearest.iter_mut().zip(labels.view(k)) {
            *n = n.min(l);
        }
    }
    Ok(nearest
        .into_iter()
        .map(|l| if l <= threshold { factor } else { 1.0 })
        .collect())
}

fn check(name: &'static str, value: f64) -> Result<(), SilhouetteError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(SilhouetteError::InvalidParameter {
            name,
            value,
            requirement: "finite and non-negative",
        })
    }
}

/// What a view-dependent extraction asks for: the error `e` away from the contour, and
/// in the contour region the smaller of `e · factor` and `cells` cells of the view.
///
/// The cap in cells is what keeps an outline in place in the image: an error sphere of a
/// quarter of a cell moves the outline by at most that. Measured on meshes nobody tuned
/// it for, at equal triangle counts, a quarter of a cell with the default region has at
/// most half the plain simplifier's wrong silhouette pixels at `e` ≤ 1 % of the diagonal,
/// where `e · factor` alone (the paper's rule, `cells` infinite) does not
/// (`silhouette_vs_simplify` in `docs/benchmarks.md`).
///
/// # Examples
///
/// ```
/// use sphaera_silhouette::ContourTolerance;
///
/// let tolerance = ContourTolerance::new(0.01);
/// assert_eq!((tolerance.factor, tolerance.threshold, tolerance.cells), (0.25, 2.0, 0.25));
/// let paper = tolerance.with_factor(0.1).with_cells(f64::INFINITY);
/// assert_eq!(paper.cells, f64::INFINITY);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContourTolerance {
    /// The allowed error `e` away from the contour (a length).
    pub error: f64,
    /// The factor `f` on `e` in the contour region (`0`: no error there).
    pub factor: f64,
    /// The contour region: triangles that come within this many cells of the silhouette
    /// (how it is decided: [`ContourRegion`]).
    pub threshold: f32,
    /// The contour region's allowance is also at most this many cells of the view's image
    /// (at the frame's nearest point); `f64::INFINITY` leaves `e · f` alone.
    pub cells: f64,
}

impl ContourTolerance {
    /// The defaults around an error `e`: factor ¼, a region of 2 cells, at most ¼ cell
    /// in it.
    #[must_use]
    pub fn new(error: f64) -> Self {
        Self {
            error,
            factor: 0.25,
            threshold: 2.0,
            cells: 0.25,
        }
    }

    /// With the factor `f` on `e` in the contour region.
    #[must_use]
    pub fn with_factor(mut self, factor: f64) -> Self {
        self.factor = factor;
        self
    }

    /// With a contour region of `threshold` cells.
    #[must_use]
    pub fn with_threshold(mut self, threshold: f32) -> Self {
        self.threshold = threshold;
        self
    }

    /// With the contour region's allowance capped at `cells` cells.
    #[must_use]
    pub fn with_cells(mut self, cells: f64) -> Self {
        self.cells = cells;
        self
    }
}

/// One extracted mesh and its certified errors per region.
#[derive(Clone, Debug)]
pub struct Extraction {
    /// The mesh (Subset placement: every vertex an input vertex), its radii and input
    /// vertices.
    pub simplified: Simplified,
    /// The largest error bound of a contour triangle (the largest radius of its corners:
    /// no point of the original it stands for is farther, both ways).
    pub contour_error: f64,
    /// The error allowed in the contour region: the smaller of `e · f` and the cap in
    /// cells, as a length.
    pub contour_allowance: f64,
    /// The largest error bound of the other triangles.
    pub other_error: f64,
    /// Triangles in the contour region.
    pub contour_triangles: usize,
    /// Per triangle of the mesh: whether it is in the contour region.
    pub in_contour: Vec<bool>,
}

/// View-dependent extraction from a progressive hierarchy with labels computed on the
/// hierarchy's input mesh.
///
/// Extraction runs in two phases. The first refines the hierarchy until every vertex
/// radius is within the error `e` allowed away from the contour: it depends on `e` alone,
/// so it is computed once and kept. The second refines, from there, the triangles of the
/// view's contour region down to `e · f`. Moving to another view with the same `e` undoes
/// only the previous view's second phase and redoes it for the new contour: the work is
/// proportional to the contour, not to the mesh. The result never depends on the views
/// extracted before.
pub struct ViewDependent<'h> {
    hierarchy: &'h Hierarchy,
    labels: &'h Labels,
    refinement: Refinement<'h>,
    /// Per hierarchy vertex, its input vertex.
    input: Vec<u32>,
    /// Which triangles are in the contour region.
    region: ContourRegion,
    /// Cells of the labels' images per unit of length, at the nearest point of the frame.
    cells_per_unit: f64,
    /// The labels' frame: the smallest ball of the input.
    center: DVec3,
    radius: f64,
    /// The first phase for the last error asked for.
    prefix: Option<Prefix>,
    /// Reused lists of the second phase.
    work: Vec<u32>,
    added: Vec<u32>,
    undone: Vec<u32>,
}

/// The refinement to an error `e` that every view shares.
struct Prefix {
    /// The error (compared bit for bit).
    error: f64,
    /// Collapses undone to reach it.
    undone: usize,
    /// Its live triangles with their corners, in increasing id order.
    triangles: Vec<(u32, [u32; 3])>,
}

impl<'h> ViewDependent<'h> {
    /// Pairs a hierarchy with the labels of its input mesh.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::NotSubset`] for a hierarchy that moves vertices;
    /// [`SilhouetteError::MeshMismatch`] when the labels are for another vertex count.
    pub fn new(hierarchy: &'h Hierarchy, labels: &'h Labels) -> Result<Self, SilhouetteError> {
        if hierarchy.placement() != Placement::Subset {
            return Err(SilhouetteError::NotSubset);
        }
        if hierarchy.input_vertex_count() != labels.vertex_count() {
            return Err(SilhouetteError::MeshMismatch {
                labels: labels.vertex_count(),
                hierarchy: hierarchy.input_vertex_count(),
            });
        }
        let input = (0..hierarchy.vertex_count() as u32)
            .map(|v| hierarchy.original_vertex(v).unwrap_or(v))
            .collect();
        // The labels' frame: the smallest ball of the input (copies of non-manifold
        // vertices add no point), as `Labels::compute` frames its views.
        let ball = minimum_enclosing_ball(hierarchy.positions())
            .map_err(|_| SilhouetteError::EmptyMesh)?;
        let radius = if ball.radius > 0.0 { ball.radius } else { 1.0 };
        let half = labels.resolution() as f64 / 2.0;
        let cells_per_unit = match labels.views().projection() {
            Projection::Orthographic => half / radius,
            // The image scale `√(D² − 1) / depth` is largest at the ball's nearest point,
            // at depth `(D − 1) · radius`.
            Projection::Perspective { distance } => {
                half * (distance * distance - 1.0).sqrt() / ((distance - 1.0) * radius)
            }
        };
        Ok(Self {
            hierarchy,
            labels,
            refinement: hierarchy.refinement(),
            input,
            region: ContourRegion::default(),
            cells_per_unit,
            center: ball.center,
            radius,
            prefix: None,
            work: Vec::new(),
            added: Vec::new(),
            undone: Vec::new(),
        })
    }

    /// With the contour region decided by `region` (default [`ContourRegion::Certified`]).
    #[must_use]
    pub fn with_region(mut self, region: ContourRegion) -> Self {
        self.region = region;
        self.prefix = None;
        self
    }

    /// How the contour region is decided.
    #[must_use]
    pub fn region(&self) -> ContourRegion {
        self.region
    }

    /// Refines the hierarchy until every triangle's error bound (the largest radius of its
    /// corners) is within its allowance: the smaller of `tolerance.error ·
    /// tolerance.factor` and `tolerance.cells` cells in the contour region of the view from `direction` (labels by `interpolation`),
    /// `tolerance.error` elsewhere.
    ///
    /// The first call with an error refines the whole mesh to it (a scan of the
    /// hierarchy); later calls with the same error start from there and redo only the
    /// contour region (see [`ViewDependent`]). The result is the same either way.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidParameter`] for a negative or non-finite error, a factor
    /// outside `[0, 1]`, a NaN threshold, or a negative or NaN cap in cells; as
    /// [`Labels::for_view`].
    pub fn extract(
        &mut self,
        direction: DVec3,
        interpolation: Interpolation,
        tolerance: ContourTolerance,
    ) -> Result<Extraction, SilhouetteError> {
        self.extract_scaled(direction, interpolation, tolerance, self.cells_per_unit)
    }

    /// [`ViewDependent::extract`] for a pinhole camera at `eye` (a point in the mesh's
    /// frame, outside the smallest ball around the mesh): the labels of the views nearest
    /// the direction from the ball's centre to the eye, and the cap in cells taken at the
    /// finer of two scales, the labels' images' and the camera's own image of the same
    /// resolution whose field of view just holds the ball (a camera nearer than the
    /// labels' cameras sees the outline larger, so its contour gets less error).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_silhouette::{ContourTolerance, Interpolation, LabelOptions, Labels, ViewDependent, ViewSet};
    /// use sphaera_simplify::{Hierarchy, SimplifyOptions};
    ///
    /// let mesh = shapes::torus(1.0, 0.3, 32)?;
    /// let labels = Labels::compute(&mesh, &ViewSet::regular(30.0)?, &LabelOptions::default().with_resolution(64))?;
    /// let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default())?;
    /// let mut lod = ViewDependent::new(&hierarchy, &labels)?;
    /// let tolerance = ContourTolerance::new(0.02 * mesh.bounding_box_diagonal());
    /// let near = lod.extract_at(DVec3::new(0.0, 0.0, 2.0), Interpolation::Nearest, tolerance)?;
    /// let far = lod.extract_at(DVec3::new(0.0, 0.0, 100.0), Interpolation::Nearest, tolerance)?;
    /// assert!(near.contour_allowance < far.contour_allowance);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::CameraInside`] for an eye inside the ball or not finite; as
    /// [`ViewDependent::extract`].
    pub fn extract_at(
        &mut self,
        eye: DVec3,
        interpolation: Interpolation,
        tolerance: ContourTolerance,
    ) -> Result<Extraction, SilhouetteError> {
        let offset = eye - self.center;
        let distance = offset.length() / self.radius;
        if !(distance.is_finite() && distance > 1.0) {
            return Err(SilhouetteError::CameraInside { distance });
        }
        // As for perspective labels: the scale `√(D² − 1) / depth` at the ball's nearest
        // point, at depth `(D − 1) · radius`.
        let half = self.labels.resolution() as f64 / 2.0;
        let camera = half * (distance * distance - 1.0).sqrt() / ((distance - 1.0) * self.radius);
        self.extract_scaled(
            offset,
            interpolation,
            tolerance,
            self.cells_per_unit.max(camera),
        )
    }

    /// [`ViewDependent::extract`] with `cells_per_unit` cells per unit of length for the
    /// cap in cells and the region's widening.
    fn extract_scaled(
        &mut self,
        direction: DVec3,
        interpolation: Interpolation,
        tolerance: ContourTolerance,
        cells_per_unit: f64,
    ) -> Result<Extraction, SilhouetteError> {
        check("error", tolerance.error)?;
        check("factor", tolerance.factor)?;
        if tolerance.factor > 1.0 {
            return Err(SilhouetteError::InvalidParameter {
                name: "factor",
                value: tolerance.factor,
                requirement: "at most 1 (the contour is allowed no more error than elsewhere)",
            });
        }
        if tolerance.threshold.is_nan() {
            return Err(SilhouetteError::InvalidParameter {
                name: "threshold",
                value: f64::NAN,
                requirement: "a number",
            });
        }
        if tolerance.cells.is_nan() || tolerance.cells < 0.0 {
            return Err(SilhouetteError::InvalidParameter {
                name: "cells",
                value: tolerance.cells,
                requirement: "non-negative (infinite for no cap)",
            });
        }
        let labels = self.labels.for_view(direction, interpolation)?;
        let prefix = self.prefix_for(tolerance.error);
        let input = &self.input;
        let membership = Membership {
            region: self.region,
            labels: &labels,
            threshold: tolerance.threshold,
            cells_per_unit,
        };
        // Subset placement: a corner is an input vertex and keeps its label.
        let in_contour = |refinement: &Refinement<'_>, corners: [u32; 3]| {
            membership.contains(
                corners.map(|v| input[v as usize]),
                corners.map(|v| refinement.position(v)),
                triangle_bound(refinement, corners),
            )
        };
        let contour_allowance =
            (tolerance.error * tolerance.factor).min(tolerance.cells / cells_per_unit);
        let refinement = &mut self.refinement;
        let hierarchy = self.hierarchy;
        // Away from the contour every triangle meets `error` after the first phase, so
        // only contour triangles can need more.
        let work = &mut self.work;
        work.clear();
        work.extend(prefix.triangles.iter().filter_map(|&(t, corners)| {
            (triangle_bound(refinement, corners) > contour_allowance
                && in_contour(refinement, corners))
            .then_some(t)
        }));
        let (added, undone) = (&mut self.added, &mut self.undone);
        added.clear();
        while let Some(t) = work.pop() {
            let Some(corners) = refinement.corners(t) else {
                continue;
            };
            let allowed = if in_contour(refinement, corners) {
                contour_allowance
            } else {
                tolerance.error
            };
            if triangle_bound(refinement, corners) <= allowed {
                continue;
            }
            let Some(&v) =
                corners
                    .iter()
                    .filter(|&&v| refinement.can_split(v))
                    .max_by(|&&a, &&b| {
                        refinement
                            .radius(a)
                            .total_cmp(&refinement.radius(b))
                            .then(b.cmp(&a))
                    })
            else {
                continue;
            };
            undone.clear();
            refinement.split_vertex_into(v, undone)?;
            for &c in undone.iter() {
                added.extend_from_slice(hierarchy.triangles_added_by_split(c));
                work.extend_from_slice(hierarchy.triangles_added_by_split(c));
                work.extend_from_slice(hierarchy.triangles_affected_by_split(c));
            }
            work.push(t);
        }
        added.extend(prefix.triangles.iter().map(|&(t, _)| t));
        let simplified = refinement.simplified_of(added);
        let (mut contour_error, mut other_error, mut contour_triangles) = (0.0_f64, 0.0_f64, 0);
        let mut region = Vec::with_capacity(simplified.mesh.triangle_count());
        for corners in simplified.mesh.triangles() {
            let inputs = corners.map(|x| simplified.original_vertex[x as usize]);
            let bound = corners
                .iter()
                .map(|&x| simplified.vertex_radii[x as usize])
                .fold(0.0, f64::max);
            let contour = membership.contains(
                inputs,
                corners.map(|x| simplified.mesh.positions()[x as usize]),
                bound,
            );
            region.push(contour);
            if contour {
                contour_error = contour_error.max(bound);
                contour_triangles += 1;
            } else {
                other_error = other_error.max(bound);
            }
        }
        self.prefix = Some(prefix);
        Ok(Extraction {
            simplified,
            contour_error,
            contour_allowance,
            other_error,
            contour_triangles,
            in_contour: region,
        })
    }

    /// The first phase for `error`: kept from the last call when the error is the same
    /// (the refinement is taken back to it), computed from the base mesh otherwise.
    fn prefix_for(&mut self, error: f64) -> Prefix {
        match self.prefix.take() {
            Some(prefix) if prefix.error.to_bits() == error.to_bits() => {
                self.refinement.reset_to(prefix.undone);
                prefix
            }
            _ => {
                let refinement = &mut self.refinement;
                refinement.reset();
                refinement.refine_to_error(error);
                let triangles = refinement
                    .live_triangles()
                    .filter_map(|t| refinement.corners(t).map(|corners| (t, corners)))
                    .collect();
                Prefix {
                    error,
                    undone: refinement.undone_count(),
                    triangles,
                }
            }
        }
    }
}

/// A triangle's error bound in a refinement: the largest radius of its corners.
fn triangle_bound(refinement: &Refinement<'_>, corners: [u32; 3]) -> f64 {
    corners
        .iter()
        .map(|&v| refinement.radius(v))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_holds_the_region_of_the_one_before() {
        let labels = [0.0, 1.5, 3.0, 7.0, 40.0, 400.0];
        let corners = [
            [DVec3::ZERO, DVec3::X, DVec3::Y],
            [DVec3::ZERO, DVec3::X * 30.0, DVec3::Y * 0.1],
            [DVec3::ZERO, DVec3::X * 1e-3, DVec3::Y * 1e-3],
        ];
        let mut checked = 0;
        for threshold in [0.0, 2.0, 5.0] {
            for bound in [0.0, 0.5, 4.0, 100.0] {
                for a in 0..labels.len() {
                    for b in 0..labels.len() {
                        for c in 0..labels.len() {
                            for p in corners {
                                let rule = |region| {
                                    Membership {
                                        region,
                                        labels: &labels,
                                        threshold,
                                        cells_per_unit: 2.0,
                                    }
                                    .contains(
                                        [a, b, c].map(|i| i as u32),
                                        p,
                                        bound,
                                    )
                                };
                                let [corners, widened, certified] = [
                                    ContourRegion::Corners,
                                    ContourRegion::Widened,
                                    ContourRegion::Certified,
                                ]
                                .map(rule);
                                assert!(!corners || widened, "{a} {b} {c} {bound} {threshold}");
                                assert!(!widened || certified, "{a} {b} {c} {bound} {threshold}");
                                checked += usize::from(certified && !corners);
                            }
                        }
                    }
                }
            }
        }
        // The wider rules do take in more.
        assert!(checked > 100, "{checked}");
    }
}
