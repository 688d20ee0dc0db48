//! Object segmentation (section 3.1): a parent's region (its surface points) is divided
//! between its children so that each point is covered by exactly one child set, with as
//! little duplication as possible.
//!
//! A point covered by several children goes to the one of smallest *power*
//! `‖p − c‖² − r² − w`: with all weights `w` zero the boundary between two children is
//! the plane through the circle where their spheres intersect (the paper's dividing
//! plane); the weights move those planes. A Nelder–Mead simplex search over the weights
//! balances the division, minimizing the largest child region's enclosing-ball radius,
//! so that no child inherits a region much larger than its siblings'.

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::minimum_enclosing_ball;

/// Simplex iterations of the balancing search.
const BALANCE_ITERATIONS: usize = 80;

/// The simplex search stops when its values agree to this relative spread.
const CONVERGED: f64 = 1e-9;

/// For each point, the index of the sphere it is assigned to: among the spheres that
/// contain it (with a relative tolerance), the one of smallest weighted power; a point no
/// sphere contains goes to the sphere whose surface is nearest.
#[must_use]
pub fn assign(points: &[DVec3], spheres: &[Sphere], weights: &[f64]) -> Vec<usize> {
    points
        .iter()
        .map(|&p| {
            let mut best: Option<(usize, f64)> = None;
            for (i, s) in spheres.iter().enumerate() {
                let tolerance = 1e-9 * s.radius.max(1e-300);
                if !s.contains_point(p, tolerance) {
                    continue;
                }
                let w = weights.get(i).copied().unwrap_or(0.0);
                let power = p.distance_squared(s.center) - s.radius * s.radius - w;
                if best.is_none_or(|(_, b)| power < b) {
                    best = Some((i, power));
                }
            }
            best.map_or_else(
                || {
                    (0..spheres.len())
                        .min_by(|&a, &b| {
                            spheres[a]
                                .signed_distance(p)
                                .total_cmp(&spheres[b].signed_distance(p))
                        })
                        .unwrap_or(0)
                },
                |(i, _)| i,
            )
        })
        .collect()
}

/// Divides `points` between `spheres`: the groups of point indices (ascending), one per
/// sphere (possibly empty), balanced by the simplex search when `balance` is set.
#[must_use]
pub fn divide(points: &[DVec3], spheres: &[Sphere], balance: bool) -> Vec<Vec<u32>> {
    let k = spheres.len();
    let mut weights = vec![0.0; k];
    if balance && k > 1 && points.len() > k {
        let scale = spheres.iter().map(|s| s.radius * s.radius).sum::<f64>() / k as f64;
        weights = nelder_mead(
            |w| largest_region(points, spheres, w),
            &weights,
            0.1 * scale,
            BALANCE_ITERATIONS,
        );
        // Keep the unweighted division unless balancing strictly helps.
        if largest_region(points, spheres, &weights)
            >= largest_region(points, spheres, &vec![0.0; k])
        {
            weights = vec![0.0; k];
        }
    }
    groups(&assign(points, spheres, &weights), k)
}

fn groups(assignment: &[usize], k: usize) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new(); k];
    for (p, &s) in assignment.iter().enumerate() {
        if let Some(group) = out.get_mut(s) {
            group.push(p as u32);
        }
    }
    out
}

/// Regions with at least this many points measure their groups' enclosing balls in
/// parallel (with the `parallel` feature).
#[cfg(feature = "parallel")]
const PARALLEL_POINTS: usize = 2_000;

/// The largest enclosing-ball radius among the groups of a weighted division.
fn largest_region(points: &[DVec3], spheres: &[Sphere], weights: &[f64]) -> f64 {
    let radius = |g: &Vec<u32>| {
        let pts: Vec<DVec3> = g.iter().map(|&i| points[i as usize]).collect();
        minimum_enclosing_ball(&pts).map_or(0.0, |b| b.radius)
    };
    let groups = groups(&assign(points, spheres, weights), spheres.len());
    #[cfg(feature = "parallel")]
    if points.len() >= PARALLEL_POINTS {
        use rayon::prelude::*;
        return groups.par_iter().map(radius).reduce(|| 0.0, f64::max);
    }
    groups.iter().map(radius).fold(0.0, f64::max)
}

/// Minimizes `f` from `start` with the Nelder–Mead simplex method (reflection 1,
/// expansion 2, contraction ½, shrink ½), initial steps `step` along each axis;
/// deterministic.
fn nelder_mead(f: impl Fn(&[f64]) -> f64, start: &[f64], step: f64, iterations: usize) -> Vec<f64> {
    let n = start.len();
    let mut simplex: Vec<(Vec<f64>, f64)> = (0..=n)
        .map(|i| {
            let mut x = start.to_vec();
            if i > 0 {
                x[i - 1] += step;
            }
            let v = f(&x);
            (x, v)
        })
        .collect();
    let combine = |a: &[f64], b: &[f64], t: f64| -> Vec<f64> {
        a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect()
    };
    for _ in 0..iterations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        // Converged (the objective is piecewise constant: a flat simplex stays flat).
        if simplex[n].1 - simplex[0].1 <= CONVERGED * simplex[0].1.abs() {
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|j| simplex[..n].iter().map(|(x, _)| x[j]).sum::<f64>() / n as f64)
            .collect();
        let (worst, worst_value) = simplex[n].clone();
        let reflected = combine(&centroid, &worst, -1.0);
        let reflected_value = f(&reflected);
        if reflected_value < simplex[0].1 {
            let expanded = combine(&centroid, &worst, -2.0);
            let expanded_value = f(&expanded);
            simplex[n] = if expanded_value < reflected_value {
                (expanded, expanded_value)
            } else {
                (reflected, reflected_value)
            };
        } else if reflected_value < simplex[n - 1].1 {
            simplex[n] = (reflected, reflected_value);
        } else {
            let contracted = combine(&centroid, &worst, 0.5);
            let contracted_value = f(&contracted);
            if contracted_value < worst_value {
                simplex[n] = (contracted, contracted_value);
            } else {
                let best = simplex[0].0.clone();
                for entry in simplex.iter_mut().skip(1) {
                    let x = combine(&best, &entry.0, 0.5);
                    let v = f(&x);
                    *entry = (x, v);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex.swap_remove(0).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nelder_mead_finds_a_quadratic_minimum() {
        let x = nelder_mead(
            |v| (v[0] - 1.0).powi(2) + (v[1] + 2.0).powi(2),
            &[0.0, 0.0],
            0.5,
            200,
        );
        assert!(
            (x[0] - 1.0).abs() < 1e-3 && (x[1] + 2.0).abs() < 1e-3,
            "{x:?}"
        );
    }

    #[test]
    fn overlapping_points_go_to_one_side_of_the_radical_plane() {
        let spheres = [Sphere::new(DVec3::ZERO, 1.0), Sphere::new(DVec3::X, 1.0)];
        let points = [
            DVec3::new(0.4, 0.0, 0.0),
            DVec3::new(0.6, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
        ];
        // The third point is in neither: it goes to the nearer sphere.
        assert_eq!(assign(&points, &spheres, &[0.0, 0.0]), vec![0, 1, 1]);
        let groups = divide(&points, &spheres, true);
        assert_eq!(groups.iter().map(Vec::len).sum::<usize>(), 3);
    }
}
