//! Sphere-tree construction (Algorithm 1 of the paper).

use glam::DVec3;
use sphaera_medial::{MedialApproximation, MedialParams, RegionGoal, Surface};
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_mesh::{TriMesh, sampling};

use crate::SphereTreeError;
use crate::reduce::{
    Candidate, FittedSphere, Reducer, ReductionInput, centre_depth, eq2_error, reduce,
};
use crate::segment::divide;
use crate::tree::{SphereTree, TreeNode};

/// Improvement steps allowed per node, per requested medial sphere.
const REFINE_STEPS_PER_SPHERE: usize = 4;

/// Parameters of [`build`], with the paper's defaults.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct Params {
    /// Children per node at most (default 8).
    pub branch: usize,
    /// Levels below the root (default 3).
    pub depth: usize,
    /// Surface samples standing for the surface (default 10,000; the paper used
    /// 5,000–10,000).
    pub samples: usize,
    /// Spheres of the initial medial approximation (default 500; the paper: 500–1,000).
    pub initial_spheres: usize,
    /// Medial spheres a node's region is refined to before reduction (default 100; the
    /// paper: 100–200).
    pub min_spheres_per_node: usize,
    /// The region's medial spheres must have at most this fraction of the parent's
    /// error (default ½; the paper: ½ to ¼).
    pub error_fraction: f64,
    /// The reducer (default [`Reducer::Combined`]).
    pub reducer: Reducer,
    /// Balance the division of a region between children by moving the dividing planes
    /// (default on).
    pub balance_regions: bool,
    /// Seed of the surface sampling.
    pub seed: u64,
    /// Certify that every level covers the whole surface, not only the samples, growing
    /// spheres where needed ([`crate::cover`]; default on).
    pub certify_coverage: bool,
    /// The certification's resolution, as a fraction of the mesh's bounding-box
    /// diagonal (default 10⁻³): triangle pieces are split down to this size before a
    /// sphere is grown to contain one, so a sphere grows by about this much at most
    /// where two spheres barely overlap, and by the gap's size where a gap was.
    pub coverage_resolution: f64,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            branch: 8,
            depth: 3,
            samples: 10_000,
            initial_spheres: 500,
            min_spheres_per_node: 100,
            error_fraction: 0.5,
            reducer: Reducer::Combined,
            balance_regions: true,
            seed: 1,
            certify_coverage: true,
            coverage_resolution: 1e-3,
        }
    }
}

impl Params {
    /// With `branch` children per node at most.
    #[must_use]
    pub fn branch(mut self, branch: usize) -> Self {
        self.branch = branch;
        self
    }

    /// With `depth` levels below the root.
    #[must_use]
    pub fn depth(mut self, depth: usize) -> Self {
        self.depth = depth;
        self
    }

    /// With `samples` surface samples.
    #[must_use]
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// With `n` spheres in the initial medial approximation.
    #[must_use]
    pub fn initial_spheres(mut self, n: usize) -> Self {
        self.initial_spheres = n;
        self
    }

    /// With at least `n` medial spheres per node's region before reduction.
    #[must_use]
    pub fn min_spheres_per_node(mut self, n: usize) -> Self {
        self.min_spheres_per_node = n;
        self
    }

    /// With a node's medial spheres refined to at most `fraction` of the parent's error
    /// (in (0, 1]; checked by [`build`]).
    #[must_use]
    pub fn error_fraction(mut self, fraction: f64) -> Self {
        self.error_fraction = fraction;
        self
    }

    /// With the given reducer.
    #[must_use]
    pub fn reducer(mut self, reducer: Reducer) -> Self {
        self.reducer = reducer;
        self
    }

    /// With surface-coverage certification on or off.
    #[must_use]
    pub fn certify_coverage(mut self, on: bool) -> Self {
        self.certify_coverage = on;
        self
    }

    /// With the given sampling seed.
    #[must_use]
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    fn validate(&self) -> Result<(), SphereTreeError> {
        let bad = |what: String| Err(SphereTreeError::InvalidParameter(what));
        if self.branch == 0 {
            return bad("branch must be at least 1".into());
        }
        if self.samples < 4 {
            return bad(format!("samples {} must be at least 4", self.samples));
        }
        if !(self.coverage_resolution > 0.0 && self.coverage_resolution.is_finite()) {
            return bad(format!(
                "coverage_resolution {} must be positive and finite",
                self.coverage_resolution
            ));
        }
        if !(self.error_fraction > 0.0 && self.error_fraction <= 1.0) {
            return bad(format!(
                "error_fraction {} must be in (0, 1]",
                self.error_fraction
            ));
        }
        Ok(())
    }
}

/// Progress of [`build_with_progress`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuildProgress {
    /// The level being built (1 for the root's children).
    pub level: usize,
    /// Nodes of that level's parents done.
    pub done: usize,
    /// Parents of that level.
    pub total: usize,
}

/// Builds the sphere-tree of `mesh`.
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] for bad parameters,
/// [`SphereTreeError::Mesh`] for an empty mesh or one with no area (a single degenerate
/// triangle), [`SphereTreeError::Medial`] for a mesh without a meaningful inside (a
/// single triangle, a flat sheet).
pub fn build(mesh: &TriMesh, params: &Params) -> Result<SphereTree, SphereTreeError> {
    build_with_progress(mesh, params, &|_| {})
}

/// [`build`], reporting progress per parent node.
///
/// # Errors
///
/// As [`build`].
pub fn build_with_progress(
    mesh: &TriMesh,
    params: &Params,
    progress: &dyn Fn(&BuildProgress),
) -> Result<SphereTree, SphereTreeError> {
    params.validate()?;
    let surface = Surface::new(mesh)?;
    let samples: Vec<DVec3> = sampling::poisson_disk(mesh, params.samples, params.seed)?
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    let root_ball = minimum_enclosing_ball(mesh.positions())?;
    let (depth, inside) = centre_depth(&surface, root_ball.center);
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
    if params.depth == 0 {
        return Ok(finish(
            mesh,
            &surface,
            params,
            SphereTree {
                branch: params.branch,
                nodes,
                level_starts,
                coverage: Vec::new(),
            },
        ));
    }
    let medial_params = MedialParams::default().spheres(params.initial_spheres);
    let mut medial = MedialApproximation::build(&surface, &samples, &medial_params)?;
    for level in 1..=params.depth {
        let parents = level_starts[level - 1]..level_starts[level];
        let total = parents.len();
        // Refine each parent's region in turn (the medial set is shared), then reduce.
        let mut problems = Vec::with_capacity(total);
        for (done, parent) in parents.clone().enumerate() {
            progress(&BuildProgress { level, done, total });
            let region = &regions[parent];
            if region.is_empty() {
                problems.push(None);
                continue;
            }
            // Far more medial spheres than the region has samples cannot help (each is
            // fixed by four samples) and would spend the refinement cap for nothing.
            let wanted = params.min_spheres_per_node.min(2 * region.len());
            let mut goal = RegionGoal::new(wanted, params.error_fraction * nodes[parent].error);
            // The error goal may be out of reach (a part the samples already resolve
            // fully): cap the work per node.
            goal.max_iterations = REFINE_STEPS_PER_SPHERE * wanted.max(1);
            let outcome = medial.refine_region(region, goal)?;
            problems.push(Some(candidates(region, &outcome.spheres)));
        }
        let reduced = reduce_all(
            &surface,
            &samples,
            &regions,
            parents.clone(),
            &problems,
            params,
        )?;
        let divisions = divide_all(&samples, &regions, parents.clone(), &reduced, params);
        for ((parent, fitted), groups) in parents.clone().zip(reduced).zip(divisions) {
            let first = nodes.len() as u32;
            let region = regions[parent].clone();
            for (f, group) in fitted.iter().zip(groups) {
                // A child left without points is redundant: its siblings cover its part.
                if group.is_empty() {
                    continue;
                }
                nodes.push(TreeNode {
                    sphere: f.sphere,
                    error: f.error,
                    level: level as u32,
                    parent: Some(parent as u32),
                    children: 0..0,
                    region_samples: group.len() as u32,
                });
                regions.push(group.iter().map(|&g| region[g as usize]).collect());
            }
            nodes[parent].children = first..nodes.len() as u32;
        }
        level_starts.push(nodes.len());
    }
    Ok(finish(
        mesh,
        &surface,
        params,
        SphereTree {
            branch: params.branch,
            nodes,
            level_starts,
            coverage: Vec::new(),
        },
    ))
}

/// Certifies the tree's coverage of the surface when asked to.
fn finish(mesh: &TriMesh, surface: &Surface, params: &Params, mut tree: SphereTree) -> SphereTree {
    if params.certify_coverage {
        let resolution = params.coverage_resolution * mesh.bounding_box_diagonal();
        crate::cover::certify_tree(mesh, surface, &mut tree, resolution);
    }
    tree
}

/// The medial spheres of a region as reducer candidates, their covers restricted to the
/// region (indices local to it).
fn candidates(region: &[u32], spheres: &[sphaera_medial::MedialSphere]) -> Vec<Candidate> {
    // Region sample id → local index.
    let local = |s: u32| region.binary_search(&s).ok().map(|i| i as u32);
    spheres
        .iter()
        .map(|m| Candidate {
            sphere: sphaera_mesh::Sphere::new(m.centre, m.radius),
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
    params: &Params,
) -> Vec<Vec<Vec<u32>>> {
    let one = |(parent, fitted): (usize, &Vec<FittedSphere>)| {
        let points: Vec<DVec3> = regions[parent]
            .iter()
            .map(|&i| samples[i as usize])
            .collect();
        let spheres: Vec<_> = fitted.iter().map(|f| f.sphere).collect();
        divide(&points, &spheres, params.balance_regions)
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

/// Reduces every parent's candidates (in parallel with the `parallel` feature; each
/// reduction is independent, so the result is the same).
fn reduce_all(
    surface: &Surface,
    samples: &[DVec3],
    regions: &[Vec<u32>],
    parents: std::ops::Range<usize>,
    problems: &[Option<Vec<Candidate>>],
    params: &Params,
) -> Result<Vec<Vec<FittedSphere>>, SphereTreeError> {
    let one = |(parent, problem): (usize, &Option<Vec<Candidate>>)| {
        let Some(candidates) = problem else {
            return Ok(Vec::new());
        };
        let points: Vec<DVec3> = regions[parent]
            .iter()
            .map(|&i| samples[i as usize])
            .collect();
        let input = ReductionInput {
            surface,
            points: &points,
            candidates,
        };
        reduce(params.reducer, &input, params.branch)
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
