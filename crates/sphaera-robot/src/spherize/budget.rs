//! Dividing the sphere budget among the links, and passing on the spheres a link cannot
//! use.

use super::link::spheres_text;
use super::{LinkSpheres, MAX_SPHERES_PER_LINK, SphereBudget, SpherizeOptions, spherize_links};
use crate::RobotError;
use crate::geometry::LinkGeometry;
use crate::primitive::Shape;
/// Rounds of [`pass_on_unused`] at most.
const PASSES: usize = 3;

/// A total honoured where links cannot use their share: the spheres a link leaves
/// unused (a sphere primitive, a box whose tightest layout is smaller) go to the links
/// that use all theirs, have no count of their own and are not spheres alone, in
/// proportion to their weights, and those links are spherized again; the giving links'
/// budgets become what they use (their shortfall says where the rest went).
pub(super) fn pass_on_unused(
    with: &[LinkGeometry],
    targets: &mut [Target],
    links: &mut [LinkSpheres],
    options: &SpherizeOptions,
) -> Result<(), RobotError> {
    for _ in 0..PASSES {
        let unused: usize = links
            .iter()
            .map(|l| l.report.budget.unwrap_or(0).saturating_sub(l.spheres.len()))
            .sum();
        // A link of spheres alone never uses more than one sphere each.
        let may_use_more = |g: &LinkGeometry| {
            g.mesh.is_some()
                || g.primitives
                    .iter()
                    .any(|p| !matches!(p.shape, Shape::Sphere { .. }))
        };
        let takers: Vec<usize> = (0..links.len())
            .filter(|&i| {
                links[i].report.shortfall.is_none()
                    && !options.per_link.contains_key(&with[i].link)
                    && may_use_more(&with[i])
            })
            .collect();
        if unused == 0 || takers.is_empty() {
            return Ok(());
        }
        let weights: Vec<f64> = takers.iter().map(|&i| weight(&with[i])).collect();
        let extra = proportional(unused, &weights, 0);
        for link in links.iter_mut() {
            let r = &mut link.report;
            let given = r.budget.unwrap_or(0);
            if given > link.spheres.len() {
                let passed = given - link.spheres.len();
                r.budget = Some(link.spheres.len());
                if let Some(why) = &mut r.shortfall {
                    why.push_str(&format!(
                        " ({} passed to other links)",
                        spheres_text(passed)
                    ));
                }
            }
        }
        let again: Vec<usize> = takers
            .iter()
            .zip(&extra)
            .filter(|&(_, &e)| e > 0)
            .map(|(&i, _)| i)
            .collect();
        for (&i, &e) in takers.iter().zip(&extra) {
            if let Target::Count(n) = targets[i] {
                targets[i] = Target::Count((n + e).min(MAX_SPHERES_PER_LINK));
            }
        }
        let geometry: Vec<LinkGeometry> = again.iter().map(|&i| with[i].clone()).collect();
        let goals: Vec<Target> = again.iter().map(|&i| targets[i]).collect();
        let redone = spherize_links(&geometry, &goals, options, &|_| {})?;
        for (&i, link) in again.iter().zip(redone) {
            links[i] = link;
        }
    }
    Ok(())
}

/// What one link is spherized to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Target {
    Count(usize),
    Tolerance(f64),
}

/// The budget of every link with geometry, in order.
pub(super) fn allocate(
    links: &[LinkGeometry],
    options: &SpherizeOptions,
) -> Result<Vec<Target>, RobotError> {
    let fixed = |g: &LinkGeometry| options.per_link.get(&g.link).copied();
    Ok(match options.budget {
        SphereBudget::PerLink(n) => links
            .iter()
            .map(|g| Target::Count(fixed(g).unwrap_or(n)))
            .collect(),
        SphereBudget::Tolerance(length) => links
            .iter()
            .map(|g| match fixed(g) {
                Some(n) => Target::Count(n),
                None => Target::Tolerance(length.resolve(g.diagonal())),
            })
            .collect(),
        SphereBudget::Total(total) => {
            let taken: usize = links.iter().filter_map(fixed).sum();
            let free: Vec<usize> = (0..links.len())
                .filter(|&i| fixed(&links[i]).is_none())
                .collect();
            if free.is_empty() && taken != total {
                return Err(RobotError::Budget {
                    message: format!(
                        "every link has its own count, and they sum to {taken}, not the total of {total}"
                    ),
                });
            }
            if total < taken + free.len() {
                return Err(RobotError::Budget {
                    message: format!(
                        "a total of {total} spheres cannot give each of the {} links with geometry one{}",
                        links.len(),
                        if taken > 0 {
                            format!(" (the per-link counts take {taken})")
                        } else {
                            String::new()
                        }
                    ),
                });
            }
            let weights: Vec<f64> = free.iter().map(|&i| weight(&links[i])).collect();
            let shares = divide(total - taken, &weights);
            let mut targets: Vec<Target> = links
                .iter()
                .map(|g| Target::Count(fixed(g).unwrap_or(1)))
                .collect();
            for (&i, share) in free.iter().zip(shares) {
                if share > MAX_SPHERES_PER_LINK {
                    return Err(RobotError::Budget {
                        message: format!(
                            "a total of {total} spheres would give link \"{}\" {share}, more than the 10,000 allowed per link",
                            links[i].link
                        ),
                    });
                }
                targets[i] = Target::Count(share);
            }
            targets
        }
    })
}

/// A link's share of a total: its area times a complexity factor.
fn weight(link: &LinkGeometry) -> f64 {
    let complexity = 1.0 + 0.25 * (link.triangles().max(12) as f64 / 12.0).log2();
    link.area().max(f64::MIN_POSITIVE) * complexity
}

/// `total` split in proportion to `weights`, at least 1 each, by largest remainders
/// (`total` at least the number of weights: then the shares sum to it exactly).
pub(super) fn divide(total: usize, weights: &[f64]) -> Vec<usize> {
    proportional(total, weights, 1)
}

/// `total` split in proportion to `weights`, at least `least` each, by largest
/// remainders: the shares sum to `total` when it is at least `least` per weight.
fn proportional(total: usize, weights: &[f64], least: usize) -> Vec<usize> {
    let n = weights.len();
    if n == 0 {
        return Vec::new();
    }
    if total <= least * n {
        return vec![least; n];
    }
    let spare = (total - least * n) as f64;
    let sum: f64 = weights.iter().sum();
    let exact: Vec<f64> = weights
        .iter()
        .map(|w| {
            if sum > 0.0 {
                spare * w / sum
            } else {
                spare / n as f64
            }
        })
        .collect();
    let mut shares: Vec<usize> = exact.iter().map(|e| least + e.floor() as usize).collect();
    // Rounding may give a floor one too many; take back from the smallest remainders.
    while shares.iter().sum::<usize>() > total {
        if let Some(i) = (0..n).filter(|&i| shares[i] > least).min_by(|&a, &b| {
            (exact[a] - exact[a].floor()).total_cmp(&(exact[b] - exact[b].floor()))
        }) {
            shares[i] -= 1;
        } else {
            break;
        }
    }
    let mut left = total.saturating_sub(shares.iter().sum::<usize>());
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        (exact[b] - exact[b].floor())
            .total_cmp(&(exact[a] - exact[a].floor()))
            .then(a.cmp(&b))
    });
    for &i in order.iter().cycle() {
        if left == 0 {
            break;
        }
        shares[i] += 1;
        left -= 1;
    }
    shares
}
