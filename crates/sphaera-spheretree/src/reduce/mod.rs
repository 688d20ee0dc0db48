//! Sphere reducers (section 5 of the paper): from many medial spheres covering a set of
//! surface points, a few spheres covering the same points as tightly as possible.
//!
//! Every reducer takes a [`ReductionInput`] — the points to cover and candidate spheres,
//! each with the points it covers, whose union covers them all — and returns at most the
//! target number of [`FittedSphere`]s covering every point. Each fitted sphere's error is
//! the paper's eq. 2 measure: for a centre inside the object, `r − d` (d the distance
//! from the centre to the surface), a bound on how far the sphere reaches beyond the
//! surface that is exact for convex parts; for a centre outside, `r + d`. The certified
//! per-sphere error of a finished tree comes from [`crate::evaluate`].
//!
//! - [`merge`]: combine Voronoi-neighbour pairs, tightest result first.
//! - [`burst`]: remove spheres one at a time, growing their neighbours over the gap.
//! - [`expand_select`]: expand every candidate to a common standoff and greedily select a
//!   covering subset (`MaxElim` or `MaxCover`), searching the standoff that meets the count.
//! - [`combined`]: both, keeping the tighter set.

mod burst;
mod expand;
mod merge;
mod seeded_ball;
mod window_bits;

pub use burst::burst;
pub use expand::{ExpandOutcome, Selection, expand_select};
pub use merge::merge;

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_query::Surface;

use crate::SphereTreeError;

/// A candidate sphere and the indices (into [`ReductionInput::points`]) of the points it
/// covers.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The sphere.
    pub sphere: Sphere,
    /// Indices of the points it covers, ascending.
    pub covers: Vec<u32>,
}

/// A sphere chosen by a reducer, with its eq. 2 error and the points it covers.
#[derive(Debug, Clone, PartialEq)]
pub struct FittedSphere {
    /// The sphere.
    pub sphere: Sphere,
    /// Its error (eq. 2 of the paper; see the module docs).
    pub error: f64,
    /// Indices of the points it covers, ascending.
    pub covers: Vec<u32>,
}

/// The problem every reducer solves.
#[derive(Debug, Clone, Copy)]
pub struct ReductionInput<'a> {
    /// The object (inside test and distances).
    pub surface: &'a Surface,
    /// The points to cover.
    pub points: &'a [DVec3],
    /// Candidate spheres whose covers together contain every point.
    pub candidates: &'a [Candidate],
}

impl ReductionInput<'_> {
    /// Checks the input: valid spheres, covers in range, every point covered.
    pub(crate) fn validate(&self) -> Result<(), SphereTreeError> {
        let mut covered = vec![false; self.points.len()];
        for (index, c) in self.candidates.iter().enumerate() {
            if !c.sphere.is_valid() {
                return Err(SphereTreeError::InvalidSphere { index });
            }
            for &p in &c.covers {
                match covered.get_mut(p as usize) {
                    Some(slot) => *slot = true,
                    None => {
                        return Err(SphereTreeError::CoverOutOfRange {
                            candidate: index,
                            point: p,
                            points: self.points.len(),
                        });
                    }
                }
            }
        }
        if let Some(p) = covered.iter().position(|&c| !c) {
            return Err(SphereTreeError::UncoveredPoint { point: p });
        }
        Ok(())
    }
}

/// Distance from `center` to the surface and whether it is inside (certified).
pub(crate) fn center_depth(surface: &Surface, center: DVec3) -> (f64, bool) {
    // The certified side: eq. 2 is an upper bound of a sphere's error only for a centre
    // truly inside.
    surface
        .signed_closest(center)
        .map_or((f64::INFINITY, false), |s| (s.closest.distance, s.inside))
}

/// The eq. 2 error of a sphere of radius `radius` whose centre is `depth` from the
/// surface, inside or not (the medial crate's, the one formula).
pub(crate) use sphaera_medial::eq2_error;

/// Indices (ascending) of `points` within `sphere` (with a relative tolerance for
/// rounding).
pub(crate) fn points_within(points: &[DVec3], sphere: &Sphere) -> Vec<u32> {
    let tolerance = 1e-12 * sphere.radius.max(1.0);
    (0..points.len() as u32)
        .filter(|&i| sphere.contains_point(points[i as usize], tolerance))
        .collect()
}

/// Which reducer a medial [`Method`](crate::Method) runs per node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Reducer {
    /// [`merge`].
    Merge,
    /// [`burst`].
    Burst,
    /// [`expand_select`] with `MaxElim`.
    Expand,
    /// Both, keeping the set with the smaller worst error ([`combined`]).
    #[default]
    Combined,
}

/// Runs both [`merge`] and [`expand_select`] (`MaxElim`) and keeps the set with the smaller
/// worst error (ties: merge), the paper's fallback for shapes where expand-select fails,
/// such as a thick tube whose medial spheres sit in its wall.
///
/// # Errors
///
/// As [`merge`].
pub fn combined(
    input: &ReductionInput<'_>,
    target: usize,
) -> Result<Vec<FittedSphere>, SphereTreeError> {
    // Independent: run side by side with the `parallel` feature (same result).
    #[cfg(feature = "parallel")]
    let (merged, expanded) = rayon::join(
        || merge(input, target),
        || expand_select(input, target, Selection::MaxElim),
    );
    #[cfg(not(feature = "parallel"))]
    let (merged, expanded) = (
        merge(input, target),
        expand_select(input, target, Selection::MaxElim),
    );
    let (merged, expanded) = (merged?, expanded?.spheres);
    if worst(&expanded) < worst(&merged) {
        Ok(expanded)
    } else {
        Ok(merged)
    }
}

/// Runs the chosen reducer.
///
/// # Errors
///
/// As [`merge`].
pub(crate) fn reduce(
    reducer: Reducer,
    input: &ReductionInput<'_>,
    target: usize,
) -> Result<Vec<FittedSphere>, SphereTreeError> {
    match reducer {
        Reducer::Merge => merge(input, target),
        Reducer::Burst => burst(input, target),
        Reducer::Expand => Ok(expand_select(input, target, Selection::MaxElim)?.spheres),
        Reducer::Combined => combined(input, target),
    }
}

/// The largest error of a set (0 when empty).
pub fn worst(spheres: &[FittedSphere]) -> f64 {
    spheres.iter().map(|s| s.error).fold(0.0, f64::max)
}
