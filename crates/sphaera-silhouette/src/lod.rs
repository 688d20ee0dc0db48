//! Level of detail guided by labels (section 3.3): the contour region (triangles with a
//! corner at most `threshold` cells from the silhouette, the paper's rule) gets the
//! allowed error `e · f`, the rest `e`. (Counting a coarse corner with the smallest label
//! of the input vertices collapsed into it was tried: it puts most coarse triangles in
//! the region and spends more triangles for the same outline.) Extracted view by view
//! from `sphaera-simplify`'s progressive hierarchy, with the error-sphere bound of each
//! region; or, for one mesh that keeps the silhouettes of many views, as per-vertex
//! tolerance weights for the static simplifier.

use glam::DVec3;
use sphaera_simplify::{Hierarchy, Placement, Refinement, Simplified};

use crate::SilhouetteError;
use crate::labels::{Interpolation, Labels};

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

/// What a view-dependent extraction asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContourTolerance {
    /// The allowed error `e` away from the contour (a length).
    pub error: f64,
    /// The factor `f` on `e` in the contour region (`0`: no error there).
    pub factor: f64,
    /// The contour region: triangles with a vertex at most this many cells from the
    /// silhouette.
    pub threshold: f32,
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
        Ok(Self {
            hierarchy,
            labels,
            refinement: hierarchy.refinement(),
            input,
            prefix: None,
            work: Vec::new(),
            added: Vec::new(),
            undone: Vec::new(),
        })
    }

    /// Refines the hierarchy until every triangle's error bound (the largest radius of its
    /// corners) is within its allowance: `tolerance.error · tolerance.factor` in the
    /// contour region of the view from `direction` (labels by `interpolation`),
    /// `tolerance.error` elsewhere.
    ///
    /// The first call with an error refines the whole mesh to it (a scan of the
    /// hierarchy); later calls with the same error start from there and redo only the
    /// contour region (see [`ViewDependent`]). The result is the same either way.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidParameter`] for a negative or non-finite error, a factor
    /// outside `[0, 1]`, or a NaN threshold; as [`Labels::for_view`].
    pub fn extract(
        &mut self,
        direction: DVec3,
        interpolation: Interpolation,
        tolerance: ContourTolerance,
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
        let labels = self.labels.for_view(direction, interpolation)?;
        let prefix = self.prefix_for(tolerance.error);
        let input = &self.input;
        // The paper's rule: a triangle is in the contour region when one of its corners
        // is (Subset placement: a corner is an input vertex and keeps its label).
        let in_contour = |corners: [u32; 3]| {
            corners
                .iter()
                .any(|&v| labels[input[v as usize] as usize] <= tolerance.threshold)
        };
        let contour_allowance = tolerance.error * tolerance.factor;
        let refinement = &mut self.refinement;
        let hierarchy = self.hierarchy;
        // Away from the contour every triangle meets `error` after the first phase, so
        // only contour triangles can need more.
        let work = &mut self.work;
        work.clear();
        work.extend(prefix.triangles.iter().filter_map(|&(t, corners)| {
            (in_contour(corners) && triangle_bound(refinement, corners) > contour_allowance)
                .then_some(t)
        }));
        let (added, undone) = (&mut self.added, &mut self.undone);
        added.clear();
        while let Some(t) = work.pop() {
            let Some(corners) = refinement.corners(t) else {
                continue;
            };
            let allowed = if in_contour(corners) {
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
            let contour = inputs
                .iter()
                .any(|&i| labels[i as usize] <= tolerance.threshold);
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
