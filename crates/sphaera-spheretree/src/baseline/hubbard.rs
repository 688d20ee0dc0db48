//! Hubbard's medial-axis sphere-tree (the paper's reference method): a static medial
//! approximation, reduced per node by merging pairs into approximate bounding spheres.

use std::cmp::Reverse;

use glam::DVec3;
use sphaera_medial::{CoverCriterion, MedialApproximation, Surface};
use sphaera_mesh::Sphere;
use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};

use super::{Child, Start, assemble};
use crate::options::{SphereTreeOptions, SphereTreeProgress};
use crate::reduce::{center_depth, eq2_error};
use crate::segment::divide;
use crate::{SphereTree, SphereTreeError};

/// Once a node's set is this many times the branching factor, every pair may merge, not
/// only intersecting ones (as [`merge`](crate::reduce::merge)).
const ALL_PAIRS_FACTOR: usize = 3;

/// Nearest spheres each medial sphere may first merge with.
const NEIGHBOURS: usize = 8;

/// Builds Hubbard's sphere-tree of `mesh`, as the paper describes it.
///
/// 1. A **static** medial approximation
///    ([`MedialApproximation::build_static`]): the Voronoi diagram of
///    [`SphereTreeOptions::forming_points`] samples, its internal spheres, never refined.
///    Unlike Hubbard, coverage of the samples is completed (with the smallest-error cover
///    spheres), because every level of a [`SphereTree`] must cover its parent's region.
/// 2. Per node, the medial spheres covering a sample of its region are **merged** in
///    pairs until at most `branch` remain, the pair whose merged sphere has the smallest
///    eq. 2 error first. The merged sphere is Hubbard's *approximate bounding sphere*:
///    the smallest sphere enclosing the two spheres (not their points), so it covers
///    whatever they covered. Pairs start as neighbours — each sphere's 8 nearest centres,
///    standing in for Hubbard's Voronoi neighbours; a merged sphere inherits both
///    lists — and once the set is at most three times `branch`, every pair.
/// 3. The region is divided between the merged spheres with
///    [`segment::divide`](crate::segment::divide) (balanced), and each sphere is grown
///    by rounding's worth if needed to contain its part.
pub(crate) fn hubbard(
    start: &Start<'_>,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    let medial = MedialApproximation::build_static(
        start.surface,
        &start.samples,
        options.forming_points.min(start.samples.len()),
        Some(CoverCriterion::SmallestError),
    )?;
    let medial_spheres = medial.spheres();
    let spheres: Vec<Sphere> = medial_spheres
        .iter()
        .map(|m| Sphere::new(m.center, m.radius))
        .collect();
    // Per sample, the medial spheres covering it.
    let mut covering: Vec<Vec<u32>> = vec![Vec::new(); start.samples.len()];
    for (i, m) in medial_spheres.iter().enumerate() {
        for &s in &m.covers {
            if let Some(list) = covering.get_mut(s as usize) {
                list.push(i as u32);
            }
        }
    }
    let samples = &start.samples;
    let surface = start.surface;
    assemble(
        start,
        options.depth,
        options.branch,
        progress,
        |_, _, region| {
            let mut members: Vec<u32> = region
                .iter()
                .flat_map(|&s| covering[s as usize].iter().copied())
                .collect();
            members.sort_unstable();
            members.dedup();
            let set: Vec<Sphere> = members.iter().map(|&i| spheres[i as usize]).collect();
            let merged = merge_bounding(surface, &set, options.branch);
            let points: Vec<DVec3> = region.iter().map(|&s| samples[s as usize]).collect();
            let groups = divide(&points, &merged, true);
            Ok(merged
                .iter()
                .zip(groups)
                .map(|(sphere, group)| {
                    let radius = group
                        .iter()
                        .map(|&g| points[g as usize].distance(sphere.center))
                        .fold(sphere.radius, f64::max);
                    Child {
                        sphere: Sphere::new(sphere.center, radius),
                        region: group.iter().map(|&g| region[g as usize]).collect(),
                    }
                })
                .collect())
        },
    )
}

/// The smallest sphere enclosing spheres `a` and `b`.
fn enclose(a: &Sphere, b: &Sphere) -> Sphere {
    let d = a.center.distance(b.center);
    if d + b.radius <= a.radius {
        return *a;
    }
    if d + a.radius <= b.radius {
        return *b;
    }
    let radius = 0.5 * (d + a.radius + b.radius);
    // d > 0 here: otherwise one sphere contains the other.
    let center = a.center + (b.center - a.center) * ((radius - a.radius) / d);
    // A hair larger, so that both spheres stay inside despite rounding.
    Sphere::new(center, radius * (1.0 + 1e-12))
}

/// A queued merge (smallest error first, then the smallest ids).
#[derive(Debug, Clone, Copy)]
struct Pair {
    error: f64,
    a: u32,
    b: u32,
    version_a: u32,
    version_b: u32,
}

impl Priority for Pair {
    type Key = (Reverse<TotalF64>, Reverse<u32>, Reverse<u32>);

    fn priority(&self) -> Self::Key {
        (
            Reverse(TotalF64(self.error)),
            Reverse(self.a),
            Reverse(self.b),
        )
    }
}

/// Merges `set` into at most `target` spheres with approximate bounding spheres.
///
/// Neighbours stand in for Hubbard's Voronoi neighbours: each sphere starts with its
/// [`NEIGHBOURS`] nearest centres (symmetrised); a merged sphere inherits both lists.
fn merge_bounding(surface: &Surface, set: &[Sphere], target: usize) -> Vec<Sphere> {
    let n = set.len();
    if n <= target {
        return set.to_vec();
    }
    let mut live: Vec<Option<(Sphere, u32)>> = set.iter().map(|&s| Some((s, 0))).collect();
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for a in 0..n {
        let mut near: Vec<(f64, u32)> = (0..n)
            .filter(|&b| b != a)
            .map(|b| (set[a].center.distance_squared(set[b].center), b as u32))
            .collect();
        let k = NEIGHBOURS.min(near.len());
        if k > 0 && k < near.len() {
            near.select_nth_unstable_by(k - 1, |x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        }
        for &(_, b) in &near[..k] {
            neighbours[a].push(b);
            neighbours[b as usize].push(a as u32);
        }
    }
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
    }
    let mut count = n;
    let error = |s: &Sphere| {
        let (d, inside) = center_depth(surface, s.center);
        eq2_error(s.radius, d, inside)
    };
    let push = |live: &[Option<(Sphere, u32)>], a: usize, b: usize, heap: &mut MaxHeap<Pair>| {
        let (a, b) = (a.min(b), a.max(b));
        if let (Some((x, va)), Some((y, vb))) = (live[a], live[b]) {
            heap.push(Pair {
                error: error(&enclose(&x, &y)),
                a: a as u32,
                b: b as u32,
                version_a: va,
                version_b: vb,
            });
        }
    };
    let all_pairs_heap = |live: &[Option<(Sphere, u32)>]| {
        let mut heap = MaxHeap::new();
        for a in 0..live.len() {
            for b in a + 1..live.len() {
                push(live, a, b, &mut heap);
            }
        }
        heap
    };
    let mut all_pairs = count <= ALL_PAIRS_FACTOR * target;
    let mut heap = if all_pairs {
        all_pairs_heap(&live)
    } else {
        let mut heap = MaxHeap::new();
        for (a, list) in neighbours.iter().enumerate() {
            for &b in list {
                if a < b as usize {
                    push(&live, a, b as usize, &mut heap);
                }
            }
        }
        heap
    };
    while count > target {
        let Some(best) = heap.pop() else {
            if all_pairs {
                break;
            }
            // Disconnected groups remain: every pair may merge now.
            all_pairs = true;
            heap = all_pairs_heap(&live);
            continue;
        };
        let (a, b) = (best.a as usize, best.b as usize);
        let (Some((x, va)), Some((y, vb))) = (live[a], live[b]) else {
            continue;
        };
        if va != best.version_a || vb != best.version_b {
            continue;
        }
        live[b] = None;
        live[a] = Some((enclose(&x, &y), va + 1));
        count -= 1;
        let mut joined = std::mem::take(&mut neighbours[a]);
        joined.extend(std::mem::take(&mut neighbours[b]));
        joined.sort_unstable();
        joined.dedup();
        joined.retain(|&o| o as usize != a && live[o as usize].is_some());
        for &o in &joined {
            let list = &mut neighbours[o as usize];
            if let Err(at) = list.binary_search(&(a as u32)) {
                list.insert(at, a as u32);
            }
        }
        if !all_pairs && count <= ALL_PAIRS_FACTOR * target {
            all_pairs = true;
            heap = all_pairs_heap(&live);
        } else if all_pairs {
            for other in 0..live.len() {
                if other != a {
                    push(&live, a, other, &mut heap);
                }
            }
        } else {
            for &o in &joined {
                push(&live, a, o as usize, &mut heap);
            }
        }
        neighbours[a] = joined;
    }
    live.into_iter().flatten().map(|(s, _)| s).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enclosing_sphere_contains_both() {
        let a = Sphere::new(DVec3::ZERO, 1.0);
        let b = Sphere::new(DVec3::new(3.0, 0.0, 0.0), 0.5);
        let e = enclose(&a, &b);
        assert!(e.contains_sphere(&a, 1e-12) && e.contains_sphere(&b, 1e-12));
        assert!((e.radius - 2.25).abs() < 1e-9);
        let inner = Sphere::new(DVec3::new(0.2, 0.0, 0.0), 0.3);
        assert_eq!(enclose(&a, &inner), a);
    }
}
