//! Sphere-tree construction (Algorithm 1 of the paper).

use glam::DVec3;
use sphaera_medial::{MedialApproximation, MedialOptions, RegionOptions, Surface};
use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::{CanonicalPose, minimum_enclosing_ball};
use sphaera_query::sampling;

use crate::SphereTreeError;
use crate::baseline;
use crate::evaluate::{EvaluationOptions, sphere_error};
use crate::minimax::minimax_tree;
use crate::options::{Effort, Method, SphereTreeOptions, SphereTreeProgress};
use crate::reduce::{
    Candidate, FittedSphere, Reducer, ReductionInput, center_depth, eq2_error, reduce,
};
use crate::segment::divide;
use crate::tree::{SphereTree, TreeNode};

/// Improvement steps allowed per node, per requested medial sphere.
const REFINE_STEPS_PER_SPHERE: usize = 4;

/// Builds the sphere-tree of `surface` with `options.method`.
///
/// The medial methods work in the mesh's canonical pose
/// ([`CanonicalPose`]), so that the tree of a turned, rescaled or moved mesh is the same
/// tree, mapped; relative lengths in the options refer to the diagonal of the mesh's
/// bounding box in that pose. The baselines work in the mesh's own axes, as their papers
/// define them.
///
/// The surface is prepared once by the caller ([`Surface::new`]) and can be used again
/// to evaluate the tree ([`evaluate_set`](crate::evaluate_set)) or to build with other
/// options.
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::{Method, SphereTreeOptions, build};
///
/// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
/// let options = SphereTreeOptions::default().with_depth(2).with_samples(1_000);
/// let octree = build(&surface, &options.clone().with_method(Method::Octree))?;
/// assert_eq!(octree.level_count(), 3);
/// assert!(octree.level(2).len() > octree.level(1).len());
/// // The baselines' coverage is measured, not certified; the medial methods certify it.
/// assert!(octree.coverage().is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] for options the method cannot use,
/// [`SphereTreeError::Mesh`] for a mesh without area to sample (a single degenerate
/// triangle), [`SphereTreeError::Medial`] when the medial approximation cannot start
/// (too few distinct samples).
pub fn build(
    surface: &Surface,
    options: &SphereTreeOptions,
) -> Result<SphereTree, SphereTreeError> {
    build_with_progress(surface, options, &|_| {})
}

/// [`build`], reporting progress per parent node (from the calling thread).
///
/// # Examples
///
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::{SphereTreeOptions, SphereTreeProgress, build_with_progress};
///
/// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 8)?)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(2)
///     .with_branch(4)
///     .with_samples(600)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let deepest = AtomicUsize::new(0);
/// let report = |p: &SphereTreeProgress| {
///     assert!(p.done < p.total);
///     deepest.fetch_max(p.level, Ordering::Relaxed);
/// };
/// let tree = build_with_progress(&surface, &options, &report)?;
/// assert_eq!(deepest.into_inner(), 2);
/// assert_eq!(tree.level_count(), 3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`build`].
pub fn build_with_progress(
    surface: &Surface,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    options.validate()?;
    if !surface.has_inside() && options.method.resolved() != Method::Minimax {
        return Err(SphereTreeError::NeedsInside {
            method: options.method.name(),
        });
    }
    let medial = |reducer| {
        posed_tree(surface, options, &|canonical, tolerance| {
            let _ = tolerance;
            medial_tree(canonical, options, reducer, progress)
        })
    };
    match options.method.resolved() {
        Method::Merge => medial(Reducer::Merge),
        Method::Burst => medial(Reducer::Burst),
        Method::Expand => medial(Reducer::Expand),
        Method::Combined => medial(Reducer::Combined),
        Method::Octree => baseline::octree(surface, options, progress),
        Method::Grid => baseline::grid(surface, options, progress),
        Method::Hubbard => baseline::hubbard(surface, options, progress),
        Method::Minimax | Method::Auto => {
            let minimax = |options: &SphereTreeOptions| {
                posed_tree(surface, options, &|canonical, tolerance| {
                    minimax_tree(canonical, options, tolerance, progress)
                })
            };
            let tree = minimax(options)?;
            if options.effort != Effort::Thorough {
                return Ok(tree);
            }
            // A thorough tree is never looser than the default's.
            let default = minimax(&options.clone().with_effort(Effort::Default))?;
            Ok(if tighter(&default, &tree, options.tolerance.is_some()) {
                default
            } else {
                tree
            })
        }
    }
}

/// Whether tree `a` is strictly tighter than `b`: with a tolerance (both meet it), by
/// fewer spheres in its cut of leaves; built to a depth, by a smaller product of its
/// levels' worst errors (every level counts alike, whatever its scale).
fn tighter(a: &SphereTree, b: &SphereTree, tolerance: bool) -> bool {
    if tolerance {
        return a.leaves().len() < b.leaves().len();
    }
    let score = |tree: &SphereTree| -> f64 {
        (1..tree.level_count())
            .map(|level| {
                let worst = tree
                    .level(level)
                    .iter()
                    .map(|n| n.error)
                    .fold(0.0, f64::max);
                worst.max(f64::MIN_POSITIVE).ln()
            })
            .sum()
    };
    a.level_count() == b.level_count() && score(a) < score(b)
}

/// The fraction of a tolerance kept free for the coverage certificate's growth.
const CERTIFICATE_ROOM: f64 = 1e-6;

/// A construction in a (canonical) surface, given the tolerance in its units.
type Construction<'a> = dyn Fn(&Surface, Option<f64>) -> Result<SphereTree, SphereTreeError> + 'a;

/// A construction run in the mesh's canonical pose and brought back: a tree that moves,
/// turns and scales with the mesh.
///
/// Sampling, the medial axis, the searches and the reducers decide by comparing numbers,
/// and on degenerate input (flat faces, cospherical samples, symmetric parts) rounding
/// noise decides; that noise changes when the mesh is moved, turned or rescaled. In the
/// canonical pose ([`CanonicalPose`]: a frame built from the mesh's own vertices, the
/// coordinates snapped to a grid far coarser than rounding and far finer than any
/// triangle) a mesh and any similarity transform of it are almost always the same
/// numbers, so the same tree comes out, mapped. Every relative length (the medial
/// tolerances, the coverage resolution) is taken relative to the canonical mesh's
/// diagonal, which does not turn with the mesh.
///
/// `construct` builds in the canonical surface (a solid or a shell, as `surface` is),
/// given the tolerance in canonical units less twice the snapping's displacement. Each
/// sphere is brought back grown by that displacement (so that it covers on the mesh what
/// it covered on the canonical mesh) and its eq. 2 error by twice it (the growth, and the
/// distance from its centre to the surface, which changes by at most that much); the
/// coverage certificate is then computed on the mesh itself.
fn posed_tree(
    surface: &Surface,
    options: &SphereTreeOptions,
    construct: &Construction<'_>,
) -> Result<SphereTree, SphereTreeError> {
    let mesh = surface.mesh();
    let pose = CanonicalPose::of(mesh);
    let canonical_mesh = pose.canonical_mesh(mesh)?;
    let canonical = if surface.has_inside() {
        Surface::solid_or_shell(&canonical_mesh)?
    } else {
        Surface::shell(&canonical_mesh)?
    };
    let slack = pose.displacement(mesh);
    let tolerance = match options.tolerance {
        Some(t) => {
            let wanted = t.resolve(surface.diagonal());
            // The coverage certificate may grow a sphere by the rounding of the way back
            // (the construction covers every piece exactly): keep room for it.
            let room = wanted - 2.0 * slack - CERTIFICATE_ROOM * wanted;
            if room.is_nan() || room <= 0.0 {
                return Err(SphereTreeError::InvalidParameter {
                    name: "tolerance",
                    value: wanted,
                    requirement: "larger than the rounding of the mesh's coordinates",
                });
            }
            Some(room / pose.size())
        }
        None => None,
    };
    let mut tree = construct(&canonical, tolerance).map_err(|e| match e {
        // Back to the mesh's units: the tolerance as asked, the worst leaf as placed.
        SphereTreeError::ToleranceUnreachable {
            worst,
            spheres,
            levels,
            limit,
            depth,
            ..
        } => SphereTreeError::ToleranceUnreachable {
            tolerance: options
                .tolerance
                .map_or(0.0, |t| t.resolve(surface.diagonal())),
            worst: pose.length_from_canonical(worst) + slack,
            spheres,
            levels,
            limit,
            depth,
        },
        other => other,
    })?;
    for node in &mut tree.nodes {
        // The mesh lies within `slack` of the canonical mesh mapped back: a sphere grown by
        // it covers on the mesh what it covered there, and reaches at most `slack` farther
        // from the mesh, plus the growth.
        let mut sphere = pose.sphere_from_canonical(&node.sphere);
        sphere.radius += slack;
        node.sphere = sphere;
        node.error = pose.length_from_canonical(node.error) + 2.0 * slack;
    }
    if !options.certify_coverage {
        // Not recorded (the minimax spheres cover the surface all the same).
    } else if options.method.resolved() == Method::Minimax {
        // Every node's sphere contains the corners of the pieces tiling its region, so
        // every cut covers the surface by construction (see `crate::minimax`).
        tree.coverage = crate::cover::by_construction(&tree);
    } else {
        let diagonal = pose.length_from_canonical(canonical.diagonal());
        let resolution = options.coverage_resolution.resolve(diagonal);
        crate::cover::certify_tree(surface, &mut tree, resolution);
    }
    Ok(tree)
}

/// The adaptive medial construction (Algorithm 1 of the paper) with `reducer`, in the
/// surface's own coordinates, without the coverage certificate.
fn medial_tree(
    surface: &Surface,
    options: &SphereTreeOptions,
    reducer: Reducer,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    let mesh = surface.mesh();

    let sampled = sampling::poisson_disk(mesh, options.samples, options.seed)?;
    let samples: Vec<DVec3> = sampled.samples.iter().map(|s| s.position).collect();
    // Each sample stands for the surface within half the sample spacing of it.
    let owned = 0.5 * sampled.ideal_spacing;
    let root_ball = minimum_enclosing_ball(mesh.positions())?;
    let (depth, inside) = center_depth(surface, root_ball.center);
    let mut nodes = vec![TreeNode {
        sphere: root_ball,
        error: eq2_error(root_ball.radius, depth, inside),
        level: 0,
        parent: None,
        children: 0..0,
        region_samples: samples.len() as u32,
    }];
    let mut regions: Vec<Vec<u32>> = vec![(0..samples.len() as u32).collect()];
    let mut level_starts = vec![0, 1];
    if options.depth == 0 {
        return Ok(SphereTree {
            branch: options.branch,
            nodes,
            level_starts,
            coverage: Vec::new(),
        });
    }
    let medial_params = MedialOptions::default().with_target_spheres(options.initial_spheres);
    let mut medial = MedialApproximation::build(surface, &samples, &medial_params)?;
    for level in 1..=options.depth {
        let parents = level_starts[level - 1]..level_starts[level];
        let total = parents.len();
        // Refine each parent's region in turn (the medial set is shared), then reduce.
        let mut problems = Vec::with_capacity(total);
        for (done, parent) in parents.clone().enumerate() {
            progress(&SphereTreeProgress { level, done, total });
            let region = &regions[parent];
            if region.is_empty() {
                problems.push(None);
                continue;
            }
            // Far more medial spheres than the region has samples cannot help (each is
            // fixed by four samples) and would spend the refinement cap for nothing.
            let wanted = options.min_spheres_per_node.min(2 * region.len());
            // The error goal may be out of reach (a part the samples already resolve
            // fully): cap the work per node.
            let goal = RegionOptions::default()
                .with_min_spheres(wanted)
                .with_max_error(options.error_fraction * nodes[parent].error)
                .with_max_iterations(REFINE_STEPS_PER_SPHERE * wanted.max(1));
            let outcome = medial.refine_region(region, &goal)?;
            problems.push(Some(candidates(region, &outcome.spheres)));
        }
        let reduced = reduce_all(
            surface,
            &samples,
            &regions,
            parents.clone(),
            &problems,
            reducer,
            options.branch,
        )?;
        let limits = certified_lower_bounds(surface, &nodes[parents.clone()], &reduced)?;
        let divisions = divide_all(&samples, &regions, parents.clone(), &reduced, options);
        for (((parent, fitted), groups), limit) in
            parents.clone().zip(reduced).zip(divisions).zip(limits)
        {
            let first = nodes.len() as u32;
            let region = regions[parent].clone();
            let family = Family {
                region: &region,
                fitted: &fitted,
                owned,
                parent: (nodes[parent].sphere, nodes[parent].error),
                limit,
            };
            let children = children_of(surface, &samples, &family, groups);
            for (sphere, error, group) in children {
                nodes.push(TreeNode {
                    sphere,
                    error,
                    level: level as u32,
                    parent: Some(parent as u32),
                    children: 0..0,
                    region_samples: group.len() as u32,
                });
                regions.push(group);
            }
            nodes[parent].children = first..nodes.len() as u32;
        }
        level_starts.push(nodes.len());
    }
    Ok(SphereTree {
        branch: options.branch,
        nodes,
        level_starts,
        coverage: Vec::new(),
    })
}

/// One parent's reduction, as [`children_of`] turns it into children.
struct Family<'a> {
    /// The parent's region (sample ids, ascending).
    region: &'a [u32],
    /// The reduced spheres.
    fitted: &'a [FittedSphere],
    /// The surface each sample stands for (half the sample spacing).
    owned: f64,
    /// The parent's sphere and eq. 2 error.
    parent: (Sphere, f64),
    /// A lower bound on the parent's certified error: a child whose eq. 2 error (an
    /// upper bound on its certified error) is at most this is no looser than the parent.
    limit: f64,
}

/// The children of one parent: per reduced sphere with a non-empty group, its sphere,
/// eq. 2 error and region (sample ids, ascending).
///
/// Three rules keep every child worth its sphere:
/// - a child whose sphere lies inside a sibling's has nothing left to cover: its samples
///   go to that sibling (the first such, in order) and it spends no sphere;
/// - a sphere smaller than the surface its samples stand for (a one-sample region gets a
///   sphere of radius 0 from the reducers, which only see points) is replaced by the
///   smallest ball around its samples grown by `owned`, so that it has a positive radius
///   covering its part of the surface;
/// - a child must be no looser than its parent. Its eq. 2 error bounds its certified
///   error from above (for a centre inside, the segment from the centre to a point of the
///   sphere outside the object crosses the surface at least the centre's depth from the
///   centre; outside, the triangle inequality). When it exceeds `limit`, the tightest of
///   the sphere shrunk to its samples and their smallest enclosing ball is taken if it
///   fits under `limit`, else the parent's own sphere (each such child keeps its own
///   samples, so the next level still refines them apart): refining a region never makes
///   it looser.
fn children_of(
    surface: &Surface,
    samples: &[DVec3],
    family: &Family<'_>,
    mut groups: Vec<Vec<u32>>,
) -> Vec<(Sphere, f64, Vec<u32>)> {
    let fitted = family.fitted;
    let inside = |a: &Sphere, b: &Sphere| a.center.distance(b.center) + a.radius <= b.radius;
    let mut spent = vec![true; fitted.len()];
    for i in 0..fitted.len() {
        if groups[i].is_empty() {
            spent[i] = false;
            continue;
        }
        let host = (0..fitted.len())
            .find(|&j| j != i && spent[j] && inside(&fitted[i].sphere, &fitted[j].sphere));
        if let Some(j) = host {
            let moved = std::mem::take(&mut groups[i]);
            groups[j].extend(moved);
            groups[j].sort_unstable();
            spent[i] = false;
        }
    }
    let eq2 = |sphere: Sphere| {
        let (depth, inside) = center_depth(surface, sphere.center);
        (sphere, eq2_error(sphere.radius, depth, inside))
    };
    let children: Vec<(Sphere, f64, Vec<u32>)> = fitted
        .iter()
        .zip(groups)
        .zip(spent)
        .filter(|&(_, spent)| spent)
        .map(|((f, group), _)| {
            // A group holds local indices into the parent's region (the division's output).
            let ids: Vec<u32> = group.iter().map(|&g| family.region[g as usize]).collect();
            let points = samples_of(samples, &ids);
            let mut best = (f.sphere, f.error);
            if f.sphere.radius < family.owned {
                best = minimum_enclosing_ball(&points).map_or(best, |ball| {
                    eq2(Sphere::new(ball.center, ball.radius + family.owned))
                });
            }
            if best.1 <= family.limit {
                return (best.0, best.1, ids);
            }
            let reach = points
                .iter()
                .map(|p| p.distance(best.0.center))
                .fold(family.owned, f64::max);
            let shrunk = eq2(Sphere::new(best.0.center, reach.min(best.0.radius)));
            let ball = minimum_enclosing_ball(&points)
                .map(|b| eq2(Sphere::new(b.center, b.radius.max(family.owned))));
            for candidate in [Some(shrunk), ball.ok()].into_iter().flatten() {
                if candidate.1 < best.1 {
                    best = candidate;
                }
            }
            if best.1 > family.limit {
                best = family.parent;
            }
            (best.0, best.1, ids)
        })
        .collect();
    children
}

/// Per parent node, a lower bound on its certified error, tight enough to judge its
/// reduced children: the error at one probe point of its sphere (the point farthest out
/// past the surface point nearest the centre) when every child's eq. 2 error is below
/// it, else the certified evaluation's lower bound (in parallel with the `parallel`
/// feature).
fn certified_lower_bounds(
    surface: &Surface,
    parents: &[TreeNode],
    reduced: &[Vec<FittedSphere>],
) -> Result<Vec<f64>, SphereTreeError> {
    let one = |(parent, fitted): (&TreeNode, &Vec<FittedSphere>)| {
        let quick = probe_error(surface, &parent.sphere);
        if crate::reduce::worst(fitted) <= quick {
            return Ok(quick);
        }
        let fit = sphere_error(surface, &parent.sphere, &EvaluationOptions::default())?;
        Ok(fit.lower.max(quick))
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        parents
            .par_iter()
            .zip(reduced.par_iter())
            .map(one)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        parents.iter().zip(reduced.iter()).map(one).collect()
    }
}

/// The error of `sphere` at one point (a true value, so a lower bound on its certified
/// error): the point of the sphere farthest out past the surface point nearest its centre,
/// its distance to the surface when it lies outside the object (by the certified inside
/// test: the fast one may err within its error bound of ½), else 0. The centre's side
/// only chooses the direction, and any direction gives a true value.
pub(crate) fn probe_error(surface: &Surface, sphere: &Sphere) -> f64 {
    let Ok(nearest) = surface.closest(sphere.center) else {
        return 0.0;
    };
    let inside = surface.is_inside(sphere.center);
    let towards = if inside {
        nearest.point - sphere.center
    } else {
        sphere.center - nearest.point
    };
    let Some(direction) = towards.try_normalize() else {
        return 0.0;
    };
    let probe = sphere.center + direction * sphere.radius;
    if surface.is_inside_certified(probe) {
        return 0.0;
    }
    surface.closest(probe).map_or(0.0, |c| c.distance)
}

/// The medial spheres of a region as reducer candidates, their covers restricted to the
/// region (indices local to it).
fn candidates(region: &[u32], spheres: &[sphaera_medial::MedialSphere]) -> Vec<Candidate> {
    // Region sample id → local index.
    let local = |s: u32| region.binary_search(&s).ok().map(|i| i as u32);
    spheres
        .iter()
        .map(|m| Candidate {
            sphere: Sphere::new(m.center, m.radius),
            covers: m.covers.iter().filter_map(|&s| local(s)).collect(),
        })
        .filter(|c| !c.covers.is_empty())
        .collect()
}

/// Divides every parent's region between its reduced spheres (in parallel with the
/// `parallel` feature; each division is independent, so the result is the same): per
/// parent, the groups of local region indices, one per sphere.
fn divide_all(
    samples: &[DVec3],
    regions: &[Vec<u32>],
    parents: std::ops::Range<usize>,
    reduced: &[Vec<FittedSphere>],
    options: &SphereTreeOptions,
) -> Vec<Vec<Vec<u32>>> {
    let one = |(parent, fitted): (usize, &Vec<FittedSphere>)| {
        let points = samples_of(samples, &regions[parent]);
        let spheres: Vec<_> = fitted.iter().map(|f| f.sphere).collect();
        divide(&points, &spheres, options.balance_regions)
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        parents
            .into_par_iter()
            .zip(reduced.par_iter())
            .map(one)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        parents.zip(reduced.iter()).map(one).collect()
    }
}

/// The positions of the samples `region` names.
fn samples_of(samples: &[DVec3], region: &[u32]) -> Vec<DVec3> {
    // Regions hold ids of `samples` only: the root's are `0..samples.len()`, and every
    // child's are a subset of its parent's.
    region.iter().map(|&i| samples[i as usize]).collect()
}

/// Reduces one region's candidates to at most `branch` spheres with `reducer`.
fn reduce_region(
    surface: &Surface,
    points: &[DVec3],
    candidates: &[Candidate],
    reducer: Reducer,
    branch: usize,
) -> Result<Vec<FittedSphere>, SphereTreeError> {
    let input = ReductionInput {
        surface,
        points,
        candidates,
    };
    reduce(reducer, &input, branch)
}

/// Reduces every parent's candidates (in parallel with the `parallel` feature; each
/// reduction is independent, so the result is the same).
fn reduce_all(
    surface: &Surface,
    samples: &[DVec3],
    regions: &[Vec<u32>],
    parents: std::ops::Range<usize>,
    problems: &[Option<Vec<Candidate>>],
    reducer: Reducer,
    branch: usize,
) -> Result<Vec<Vec<FittedSphere>>, SphereTreeError> {
    let one = |(parent, problem): (usize, &Option<Vec<Candidate>>)| match problem {
        Some(candidates) => reduce_region(
            surface,
            &samples_of(samples, &regions[parent]),
            candidates,
            reducer,
            branch,
        ),
        None => Ok(Vec::new()),
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        parents
            .into_par_iter()
            .zip(problems.par_iter())
            .map(one)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        parents.zip(problems.iter()).map(one).collect()
    }
}
