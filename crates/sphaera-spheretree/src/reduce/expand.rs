//! Expand and select (section 5.3): expand every candidate to a common standoff `e` from
//! the surface, greedily select a subset covering every point, and search the smallest
//! standoff whose selection fits the target count.

use sphaera_mesh::Sphere;

use super::window_bits::{WindowBits, all_of, morton_positions};
use super::{FittedSphere, ReductionInput, center_depth};
use crate::SphereTreeError;

/// Bisection steps of the standoff search at most.
const SEARCH_STEPS: usize = 40;

/// The standoff search stops when its bracket is narrower than this fraction of the
/// mesh's diagonal (0.01 %: below the two decimals errors are reported with, in % of the
/// diagonal); each halving costs a full greedy selection.
const SEARCH_RESOLUTION: f64 = 1e-4;

/// The greedy ranking of the selection.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Selection {
    /// Pick the sphere that makes the most remaining candidates redundant (the paper's
    /// choice: it takes complicated areas first and grows from chosen spheres, leaving
    /// fewer gaps to fill).
    #[default]
    MaxElim,
    /// Pick the sphere covering the most uncovered points.
    MaxCover,
}

/// What [`expand_select`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpandOutcome {
    /// The selected spheres, all with error [`ExpandOutcome::standoff`].
    pub spheres: Vec<FittedSphere>,
    /// The standoff `e`: every sphere reaches at most `e` beyond the surface (eq. 2;
    /// exact for convex parts, an over-estimate for concave ones).
    pub standoff: f64,
    /// Whether the count equals the target. When the selection jumps over it (the
    /// paper's "25 or 55" case), this is `false` and the set is the largest one found
    /// below the target.
    pub exact: bool,
    /// The smallest count above the target seen during the search, if any: what a
    /// slightly smaller standoff gives.
    pub next_count_above: Option<usize>,
}

/// One candidate, expanded.
struct Expandable {
    center: glam::DVec3,
    depth: f64,
    inside: bool,
    /// Every point's distance from the centre, in point order.
    distances: Vec<f64>,
    /// The largest of them.
    farthest: f64,
}

impl Expandable {
    /// The radius at standoff `e` (`None` when the sphere would vanish).
    fn radius(&self, e: f64) -> Option<f64> {
        let r = if self.inside {
            e + self.depth
        } else {
            e - self.depth
        };
        (r > 0.0).then_some(r)
    }

    /// The standoff at which it starts to cover a point `d` from its centre.
    fn standoff_at(&self, d: f64) -> f64 {
        if self.inside {
            d - self.depth
        } else {
            d + self.depth
        }
    }
}

/// Expands the candidates to the smallest common standoff at which the greedy selection
/// covers every point with at most `target` spheres.
///
/// # Errors
///
/// As [`super::merge`].
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, Sphere, shapes};
/// use sphaera_query::Surface;
/// use sphaera_spheretree::reduce::{Candidate, ReductionInput, Selection, expand_select};
///
/// let mesh = shapes::capsule(0.5, 2.0, 12)?;
/// let surface = Surface::new(&mesh)?;
/// let points: Vec<DVec3> = (0..20).map(|i| DVec3::new(0.0, 0.5, -0.9 + 0.09 * f64::from(i))).collect();
/// let candidates: Vec<Candidate> = (0..20)
///     .map(|i| Candidate {
///         sphere: Sphere::new(DVec3::new(0.0, 0.0, points[i].z), 0.5),
///         covers: vec![i as u32],
///     })
///     .collect();
/// let input = ReductionInput { surface: &surface, points: &points, candidates: &candidates };
/// let outcome = expand_select(&input, 4, Selection::MaxElim)?;
/// assert!(outcome.spheres.len() <= 4);
/// for s in &outcome.spheres {
///     assert_eq!(s.error, outcome.standoff);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn expand_select(
    input: &ReductionInput<'_>,
    target: usize,
    selection: Selection,
) -> Result<ExpandOutcome, SphereTreeError> {
    if target == 0 {
        return Err(SphereTreeError::InvalidParameter {
            name: "target",
            value: 0.0,
            requirement: "at least 1",
        });
    }
    input.validate()?;
    let expandable: Vec<Expandable> = input
        .candidates
        .iter()
        .map(|c| {
            let (depth, inside) = center_depth(input.surface, c.sphere.center);
            let distances: Vec<f64> = input
                .points
                .iter()
                .map(|p| p.distance(c.sphere.center))
                .collect();
            let farthest = distances.iter().copied().fold(0.0, f64::max);
            Expandable {
                center: c.sphere.center,
                depth,
                inside,
                distances,
                farthest,
            }
        })
        .collect();
    // Below `low` some point is covered by no expanded candidate; at `high` one covers
    // them all. Both from the sorted distances: no distance is computed twice.
    let mut cheapest = vec![f64::INFINITY; input.points.len()];
    for x in &expandable {
        for (slot, &d) in cheapest.iter_mut().zip(&x.distances) {
            *slot = slot.min(x.standoff_at(d));
        }
    }
    let low = cheapest.iter().copied().fold(0.0_f64, f64::max);
    // At `high`, the candidate needing the smallest standoff to reach every point covers
    // them all alone: the search's feasible end.
    let (single, high) = expandable
        .iter()
        .enumerate()
        .map(|(i, x)| (i, x.standoff_at(x.farthest).max(0.0)))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map_or((0, low), |(i, e)| (i, e.max(low)));
    let positions = morton_positions(input.points);
    let mut best = vec![single];
    let mut best_e = high;
    let mut next_above: Option<usize> = None;
    // Bisection on the standoff for the smallest one whose selection fits the target; a
    // standoff where rounding leaves a point uncoverable counts as too small.
    let (mut lo, mut hi) = (low, high);
    let mut probe = low;
    let resolution = SEARCH_RESOLUTION * input.surface.diagonal();
    for _ in 0..SEARCH_STEPS {
        match select(input, &expandable, &positions, probe, selection) {
            Some(chosen) if chosen.len() <= target => {
                hi = probe;
                best = chosen;
                best_e = probe;
            }
            Some(chosen) => {
                lo = probe;
                next_above = Some(next_above.map_or(chosen.len(), |n| n.min(chosen.len())));
            }
            None => lo = probe,
        }
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi || hi - lo <= resolution {
            break;
        }
        probe = mid;
    }
    let spheres = best
        .iter()
        .filter_map(|&i| {
            let x = expandable.get(i)?;
            let radius = x.radius(best_e)?;
            let sphere = Sphere::new(x.center, radius);
            Some(FittedSphere {
                sphere,
                error: best_e,
                covers: super::points_within(input.points, &sphere),
            })
        })
        .collect::<Vec<_>>();
    Ok(ExpandOutcome {
        exact: spheres.len() == target,
        spheres,
        standoff: best_e,
        next_count_above: next_above,
    })
}

/// The greedy selection at standoff `e`: indices of the chosen candidates (`None` when
/// some point cannot be covered), with spheres that cover nothing uniquely dropped at the
/// end. `positions` numbers the points in space-filling order (the bit of each point).
fn select(
    input: &ReductionInput<'_>,
    expandable: &[Expandable],
    positions: &[u32],
    e: f64,
    selection: Selection,
) -> Option<Vec<usize>> {
    let n = input.points.len();
    let covers: Vec<Option<WindowBits>> = expandable
        .iter()
        .map(|x| {
            let reach = x.radius(e)? * (1.0 + 1e-12);
            let members: Vec<u32> = x
                .distances
                .iter()
                .zip(positions)
                .filter(|&(&d, _)| d <= reach)
                .map(|(_, &p)| p)
                .collect();
            (!members.is_empty()).then(|| WindowBits::new(&members))
        })
        .collect();
    let mut uncovered = all_of(n);
    let mut remaining: Vec<usize> = (0..covers.len()).filter(|&i| covers[i].is_some()).collect();
    let mut chosen = Vec::new();
    while uncovered.iter().any(|&w| w != 0) {
        // Each candidate's uncovered points and their count (its gain), by gain.
        let mut open: Vec<(usize, u32, WindowBits)> = remaining
            .iter()
            .filter_map(|&j| {
                let open = covers[j].as_ref()?.masked(&uncovered)?;
                Some((j, open.count(), open))
            })
            .collect();
        remaining = open.iter().map(|&(j, _, _)| j).collect();
        open.sort_by_key(|&(j, gain, _)| (gain, j));
        // The open sets by their first word: a subset of `i`'s cover lies within its
        // words, so only that range of this order can be one (the same count as testing
        // every candidate, far fewer tests).
        let mut by_first: Vec<usize> = Vec::new();
        if selection == Selection::MaxElim {
            by_first = (0..open.len()).collect();
            by_first.sort_by_key(|&k| (open[k].2.first_word(), k));
        }
        let best = open.iter().map(|&(i, gain, _)| {
            let rank = match selection {
                Selection::MaxCover => gain,
                // Candidates whose uncovered points `i` covers too; only those with no
                // larger gain can be (the gains are sorted).
                Selection::MaxElim => {
                    let end = open.partition_point(|&(_, g, _)| g <= gain);
                    covers[i].as_ref().map_or(0, |ci| {
                        let lo =
                            by_first.partition_point(|&k| open[k].2.first_word() < ci.first_word());
                        let hi =
                            by_first.partition_point(|&k| open[k].2.first_word() < ci.end_word());
                        by_first[lo..hi]
                            .iter()
                            .filter(|&&k| {
                                let (j, _, oj) = &open[k];
                                k < end
                                    && *j != i
                                    && oj.end_word() <= ci.end_word()
                                    && oj.is_subset_of(ci)
                            })
                            .count() as u32
                    })
                }
            };
            (rank, gain, std::cmp::Reverse(i))
        });
        let (_, _, std::cmp::Reverse(best)) = best.max()?;
        if let Some(c) = covers[best].as_ref() {
            c.remove_from(&mut uncovered);
        }
        chosen.push(best);
        remaining.retain(|&j| j != best);
    }
    // Drop spheres that cover nothing uniquely, latest first.
    let mut k = chosen.len();
    while k > 0 {
        k -= 1;
        let mut others = vec![0; n.div_ceil(64)];
        for (m, &j) in chosen.iter().enumerate() {
            if m != k
                && let Some(c) = covers[j].as_ref()
            {
                c.add_to(&mut others);
            }
        }
        let others = WindowBits::from_full(&others);
        if covers[chosen[k]]
            .as_ref()
            .is_some_and(|c| c.is_subset_of(&others))
        {
            chosen.remove(k);
        }
    }
    Some(chosen)
}
