//! Merge (section 5.1): repeatedly replace the pair of neighbouring spheres whose union is
//! covered most tightly by one sphere.

use std::cmp::{Ordering, Reverse};

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};

use super::seeded_ball::{SeededBall, seeded_enclosing_ball};
use super::{FittedSphere, ReductionInput, center_depth, eq2_error};
use crate::SphereTreeError;

/// Once the set is this many times the target, every pair may merge, not only
/// neighbours (the paper: "2 or 3 times the target").
const ALL_PAIRS_FACTOR: usize = 3;

/// A live sphere of the merge.
#[derive(Debug, Clone)]
struct Live {
    sphere: Sphere,
    error: f64,
    depth: f64,
    inside: bool,
    covers: Vec<u32>,
    /// The support points of the minimum enclosing ball of the covered points: the seed
    /// of the enclosing balls of its unions.
    support: Vec<DVec3>,
    version: u32,
}

/// A candidate merge in the queue (smallest key first). The key is the merged sphere's
/// error when `exact`, else a lower bound on it: the surface queries of the minimum
/// enclosing ball's centre wait until the pair reaches the front of the queue.
#[derive(Debug, Clone, Copy)]
struct PairMerge {
    key: f64,
    exact: bool,
    a: u32,
    b: u32,
    version_a: u32,
    version_b: u32,
}

impl Priority for PairMerge {
    type Key = (Reverse<TotalF64>, bool, Reverse<u32>, Reverse<u32>);

    /// The smallest key first (ties: exact first, then the smallest ids).
    fn priority(&self) -> Self::Key {
        (
            Reverse(TotalF64(self.key)),
            self.exact,
            Reverse(self.a),
            Reverse(self.b),
        )
    }
}

/// Reduces the candidates to at most `target` spheres by merging: each step replaces the
/// pair whose merged sphere has the smallest error. The merged sphere is the tightest of
/// three: the first sphere grown (same centre) to cover both sets of points, the second
/// grown likewise, and the minimum enclosing ball of the union — so a sphere stays on the
/// medial axis unless moving it pays. Pairs start as neighbours: spheres that cover a
/// common point (Voronoi neighbours share three forming points, which both cover); once
/// the set is at most three times the target, every pair is considered.
///
/// # Performance
///
/// A pair's queue key needs the minimum enclosing ball of the union of its points; it is
/// solved from the two parts' support points, which usually takes one or two passes over
/// the points instead of dozens. Surface queries wait until a pair reaches the front of
/// the queue.
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] for `target == 0`,
/// [`SphereTreeError::UncoveredPoint`] for a point no candidate covers,
/// [`SphereTreeError::CoverOutOfRange`] for a candidate listing a point that does not
/// exist, [`SphereTreeError::InvalidSphere`] for a NaN or negative candidate.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, Sphere, shapes};
/// use sphaera_query::Surface;
/// use sphaera_spheretree::reduce::{Candidate, ReductionInput, merge};
///
/// let mesh = shapes::capsule(0.5, 2.0, 12)?;
/// let surface = Surface::new(&mesh)?;
/// // Points along the capsule's axis, each covered by a small sphere.
/// let points: Vec<DVec3> = (0..20).map(|i| DVec3::new(0.0, 0.0, -0.9 + 0.09 * f64::from(i))).collect();
/// let candidates: Vec<Candidate> = (0..20)
///     .map(|i| Candidate { sphere: Sphere::new(points[i], 0.1), covers: vec![i as u32] })
///     .collect();
/// let input = ReductionInput { surface: &surface, points: &points, candidates: &candidates };
/// let merged = merge(&input, 3)?;
/// assert!(merged.len() <= 3);
/// // Every point is still covered, by a sphere that lists it.
/// for (i, p) in points.iter().enumerate() {
///     assert!(merged.iter().any(|s| s.covers.contains(&(i as u32))
///         && s.sphere.contains_point(*p, 1e-9)));
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn merge(
    input: &ReductionInput<'_>,
    target: usize,
) -> Result<Vec<FittedSphere>, SphereTreeError> {
    if target == 0 {
        return Err(SphereTreeError::InvalidParameter {
            name: "target",
            value: 0.0,
            requirement: "at least 1",
        });
    }
    input.validate()?;
    let mut live: Vec<Option<Live>> = input
        .candidates
        .iter()
        .map(|c| {
            let (depth, inside) = center_depth(input.surface, c.sphere.center);
            let support = seeded_enclosing_ball(|| points_of(input, &c.covers), &[])
                .map(|b| b.support)
                .unwrap_or_default();
            Some(Live {
                sphere: c.sphere,
                error: eq2_error(c.sphere.radius, depth, inside),
                depth,
                inside,
                covers: c.covers.clone(),
                support,
                version: 0,
            })
        })
        .collect();
    let mut count = live.len();
    let mut heap = MaxHeap::new();
    let mut all_pairs = count <= ALL_PAIRS_FACTOR * target;
    let pairs: Vec<(usize, usize)> = (0..live.len())
        .flat_map(|a| (a + 1..live.len()).map(move |b| (a, b)))
        .filter(|&(a, b)| all_pairs || neighbours(&live, a, b))
        .collect();
    heap.extend(bound_pairs(input, &live, &pairs));
    while count > target {
        let Some(best) = heap.pop() else {
            // No pair left (only possible before switching to all pairs): switch now.
            all_pairs = true;
            push_all_pairs(input, &live, &mut heap);
            if heap.is_empty() {
                break;
            }
            continue;
        };
        let (a, b) = (best.a as usize, best.b as usize);
        let current = |i: usize, v: u32| live[i].as_ref().is_some_and(|l| l.version == v);
        if !current(a, best.version_a) || !current(b, best.version_b) {
            continue;
        }
        let merged = match (&live[a], &live[b]) {
            (Some(x), Some(y)) => best_merge(input, x, y),
            _ => continue,
        };
        if !best.exact {
            // Its key was a lower bound: queue it again with its exact error.
            heap.push(PairMerge {
                key: merged.error,
                exact: true,
                ..best
            });
            continue;
        }
        live[b] = None;
        if let Some(slot) = live[a].as_mut() {
            let version = slot.version + 1;
            *slot = Live { version, ..merged };
        }
        count -= 1;
        if !all_pairs && count <= ALL_PAIRS_FACTOR * target {
            all_pairs = true;
            push_all_pairs(input, &live, &mut heap);
        } else {
            let pairs: Vec<(usize, usize)> = (0..live.len())
                .filter(|&other| {
                    other != a
                        && live[other].is_some()
                        && (all_pairs || neighbours(&live, a, other))
                })
                .map(|other| (a.min(other), a.max(other)))
                .collect();
            heap.extend(bound_pairs(input, &live, &pairs));
        }
    }
    Ok(live
        .into_iter()
        .flatten()
        .map(|l| FittedSphere {
            sphere: l.sphere,
            error: l.error,
            covers: l.covers,
        })
        .collect())
}

fn neighbours(live: &[Option<Live>], a: usize, b: usize) -> bool {
    match (&live[a], &live[b]) {
        (Some(x), Some(y)) => share_a_point(&x.covers, &y.covers),
        _ => false,
    }
}

/// Whether two ascending lists have an element in common.
fn share_a_point(a: &[u32], b: &[u32]) -> bool {
    let (mut i, mut j) = (0, 0);
    while let (Some(&x), Some(&y)) = (a.get(i), b.get(j)) {
        match x.cmp(&y) {
            Ordering::Equal => return true,
            Ordering::Less => i += 1,
            Ordering::Greater => j += 1,
        }
    }
    false
}

fn push_all_pairs(
    input: &ReductionInput<'_>,
    live: &[Option<Live>],
    heap: &mut MaxHeap<PairMerge>,
) {
    heap.clear();
    let pairs: Vec<(usize, usize)> = (0..live.len())
        .flat_map(|a| (a + 1..live.len()).map(move |b| (a, b)))
        .filter(|&(a, b)| live[a].is_some() && live[b].is_some())
        .collect();
    heap.extend(bound_pairs(input, live, &pairs));
}

/// Pairs bounded in one batch at least before the work is split between threads.
#[cfg(feature = "parallel")]
const PARALLEL_PAIRS: usize = 64;

/// The queue entries of `pairs` (both live), in the order given (computed in parallel
/// with the `parallel` feature; each is a pure function of the pair, so the result is the
/// same).
fn bound_pairs(
    input: &ReductionInput<'_>,
    live: &[Option<Live>],
    pairs: &[(usize, usize)],
) -> Vec<PairMerge> {
    let one = |&(a, b): &(usize, usize)| {
        let (Some(x), Some(y)) = (&live[a], &live[b]) else {
            return None;
        };
        let (key, exact) = merge_bound(input, x, y);
        Some(PairMerge {
            key,
            exact,
            a: a as u32,
            b: b as u32,
            version_a: x.version,
            version_b: y.version,
        })
    };
    #[cfg(feature = "parallel")]
    if pairs.len() >= PARALLEL_PAIRS {
        use rayon::prelude::*;
        return pairs
            .par_iter()
            .with_min_len(PARALLEL_PAIRS / 2)
            .filter_map(one)
            .collect();
    }
    pairs.iter().filter_map(one).collect()
}

/// The error of [`best_merge`] of `x` and `y` without surface queries: exact (`true`)
/// when a grown sphere is known to win, else a lower bound (`false`).
fn merge_bound(input: &ReductionInput<'_>, x: &Live, y: &Live) -> (f64, bool) {
    // Points covered by both appear twice: harmless for distances and enclosing balls.
    let pts = || points_of(input, &x.covers).chain(points_of(input, &y.covers));
    let (grown_x, grown_y) = grown_radii(pts(), x, y);
    let best = eq2_error(grown_x, x.depth, x.inside).min(eq2_error(grown_y, y.depth, y.inside));
    match union_ball(pts, x, y) {
        // The centre is at most the nearest point's distance from the surface, so the
        // error is at least `radius − nearest`, inside or not.
        Some(ball) if ball.sphere.radius - ball.nearest < best => {
            (ball.sphere.radius - ball.nearest, false)
        }
        _ => (best, true),
    }
}

/// The radii `x` and `y` grow to (same centres) to contain `pts`.
fn grown_radii(pts: impl Iterator<Item = DVec3>, x: &Live, y: &Live) -> (f64, f64) {
    let (cx, cy) = (x.sphere.center, y.sphere.center);
    pts.fold((0.0, 0.0), |(rx, ry): (f64, f64), p| {
        (rx.max(p.distance(cx)), ry.max(p.distance(cy)))
    })
}

/// The points of `covers`.
fn points_of<'a>(
    input: &'a ReductionInput<'_>,
    covers: &'a [u32],
) -> impl Iterator<Item = DVec3> + 'a {
    covers.iter().map(|&i| input.points[i as usize])
}

/// The minimum enclosing ball of the points `pts` yields (those of `x` and `y`), seeded
/// with both spheres' supports.
fn union_ball<I: Iterator<Item = DVec3>>(
    pts: impl Fn() -> I,
    x: &Live,
    y: &Live,
) -> Option<SeededBall> {
    let seed: Vec<DVec3> = x.support.iter().chain(&y.support).copied().collect();
    seeded_enclosing_ball(pts, &seed)
}

/// The tightest of the three merged spheres of `x` and `y` (version 0).
fn best_merge(input: &ReductionInput<'_>, x: &Live, y: &Live) -> Live {
    let covers = union(&x.covers, &y.covers);
    let pts = || points_of(input, &covers);
    let ball = union_ball(pts, x, y);
    let (grown_x, grown_y) = grown_radii(pts(), x, y);
    let grown = |l: &Live, radius: f64| Live {
        sphere: Sphere::new(l.sphere.center, radius),
        error: eq2_error(radius, l.depth, l.inside),
        depth: l.depth,
        inside: l.inside,
        covers: Vec::new(),
        support: Vec::new(),
        version: 0,
    };
    let mut best = grown(x, grown_x);
    let other = grown(y, grown_y);
    if other.error < best.error {
        best = other;
    }
    let mut support = Vec::new();
    if let Some(ball) = ball {
        // Skip the surface queries when the lower bound cannot beat the grown spheres.
        if ball.sphere.radius - ball.nearest < best.error {
            let (depth, inside) = center_depth(input.surface, ball.sphere.center);
            let error = eq2_error(ball.sphere.radius, depth, inside);
            if error < best.error {
                best = Live {
                    sphere: ball.sphere,
                    error,
                    depth,
                    inside,
                    covers: Vec::new(),
                    support: Vec::new(),
                    version: 0,
                };
            }
        }
        support = ball.support;
    }
    best.covers = covers;
    best.support = support;
    best
}

/// The sorted union of two ascending lists.
fn union(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let next = match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) if x == y => {
                i += 1;
                j += 1;
                x
            }
            (Some(&x), Some(&y)) if x < y => {
                i += 1;
                x
            }
            (Some(_), Some(&y)) | (None, Some(&y)) => {
                j += 1;
                y
            }
            (Some(&x), None) => {
                i += 1;
                x
            }
            (None, None) => break,
        };
        out.push(next);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::union;

    #[test]
    fn union_is_sorted_and_deduplicated() {
        assert_eq!(union(&[1, 3, 5], &[2, 3, 9]), vec![1, 2, 3, 5, 9]);
        assert_eq!(union(&[], &[4]), vec![4]);
        assert_eq!(union(&[7], &[]), vec![7]);
    }
}
