//! One level of a built tree evaluated: the cut at that level (its nodes and the leaves
//! above it), with the construction errors as certified upper bounds and the certified
//! evaluation tightening them. What the CLI, the viewer, Python and the experiments
//! report per level.

use sphaera_mesh::Sphere;
use sphaera_query::Surface;

use super::{EvaluationOptions, SetEvaluation, evaluate_set_bounded};
use crate::{SphereTree, SphereTreeError};

/// The cut of a tree at one level, evaluated on the surface the tree was built on.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::{EvaluationOptions, SphereTreeOptions, Surface, build, evaluate_level};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let surface = Surface::new(&mesh)?;
/// let tree = build(&surface, &SphereTreeOptions::default().with_depth(2).with_branch(4))?;
/// let level = evaluate_level(&surface, &tree, 1, &EvaluationOptions::level_report())?;
/// assert_eq!(level.spheres.len(), tree.cut_at(1).len());
/// assert!(level.worst_lower <= level.worst_upper);
/// assert!(level.worst_upper <= level.construction_error);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LevelEvaluation {
    /// The level.
    pub level: usize,
    /// The spheres of the cut, in node order: the level's nodes and the leaves above it.
    pub spheres: Vec<Sphere>,
    /// How many of them are leaves above the level (0 in a tree built to a depth).
    pub leaves_above: usize,
    /// The largest construction error of the cut (each node's error is a certified upper
    /// bound of its sphere's).
    pub construction_error: f64,
    /// Per sphere, the tightest certified upper bound of its error: the smaller of the
    /// evaluation's upper bound and the construction error.
    pub uppers: Vec<f64>,
    /// The certified worst error lies in `[worst_lower, worst_upper]`; `worst_upper` is the
    /// largest of [`uppers`](Self::uppers).
    pub worst_lower: f64,
    /// See [`worst_lower`](Self::worst_lower).
    pub worst_upper: f64,
    /// The mean of [`uppers`](Self::uppers) (conservative: a sphere that cannot be the
    /// worst is not evaluated to the tolerance).
    pub mean_upper: f64,
    /// The population variance of [`uppers`](Self::uppers).
    pub upper_variance: f64,
    /// The evaluation of the cut's spheres, with the node errors as bounds.
    pub evaluation: SetEvaluation,
}

/// Evaluates the cut of `tree` at `level` on `surface` (the surface it was built on): the
/// node errors settle what they can and the evaluation spends nothing on spheres that
/// cannot be the worst ([`evaluate_set_bounded`]).
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] for `level` beyond the tree's levels or invalid
/// `options`; as [`evaluate_set_bounded`].
pub fn evaluate_level(
    surface: &Surface,
    tree: &SphereTree,
    level: usize,
    options: &EvaluationOptions,
) -> Result<LevelEvaluation, SphereTreeError> {
    if level >= tree.level_count() {
        return Err(SphereTreeError::InvalidParameter {
            name: "level",
            value: level as f64,
            requirement: "below the tree's number of levels",
        });
    }
    let cut = tree.cut_at(level);
    let spheres: Vec<Sphere> = cut.iter().map(|&i| tree.nodes()[i].sphere).collect();
    let errors: Vec<f64> = cut.iter().map(|&i| tree.nodes()[i].error).collect();
    let evaluation = evaluate_set_bounded(surface, &spheres, &errors, options)?;
    // Both bounds are certified upper bounds of a sphere's error: the smaller is tighter.
    let uppers: Vec<f64> = evaluation
        .fits
        .iter()
        .zip(&errors)
        .map(|(fit, &error)| fit.upper.min(error))
        .collect();
    let (mean_upper, upper_variance) = mean_and_variance(&uppers);
    Ok(LevelEvaluation {
        level,
        leaves_above: cut.len() - tree.level(level).len(),
        construction_error: errors.iter().copied().fold(0.0, f64::max),
        worst_lower: evaluation.worst_lower,
        worst_upper: uppers.iter().copied().fold(0.0, f64::max),
        mean_upper,
        upper_variance,
        uppers,
        spheres,
        evaluation,
    })
}

/// The mean and the population variance of `values` (0 and 0 for none).
fn mean_and_variance(values: &[f64]) -> (f64, f64) {
    if values.is_empty() {
        return (0.0, 0.0);
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, variance)
}

#[cfg(test)]
mod tests {
    use super::mean_and_variance;

    #[test]
    fn mean_and_variance_of_a_few_values() {
        assert_eq!(mean_and_variance(&[]), (0.0, 0.0));
        let (mean, variance) = mean_and_variance(&[1.0, 3.0]);
        assert!((mean - 2.0).abs() < 1e-15 && (variance - 1.0).abs() < 1e-15);
    }
}
