//! Baseline sphere-tree constructions the paper compares against (sections 2 and 7):
//! [`octree`], [`grid`] and Hubbard's static medial method ([`hubbard`]).
//!
//! Each returns a [`SphereTree`] with the same structure as [`build`](crate::build):
//! the root is the minimum enclosing ball of the mesh's vertices, the surface is
//! represented by the same Poisson-disk samples (count and seed from [`BaselineParams`]),
//! every node's region (its samples) is partitioned between its children, and every
//! sample of a node's region lies inside one of its children. Node errors are the
//! paper's eq. 2 (see [`TreeNode::error`]), computed as [`build`](crate::build) does; the
//! certified error of a level comes from [`evaluate_set`](crate::evaluate_set).
//!
//! ```
//! use sphaera_mesh::shapes;
//! use sphaera_spheretree::baseline::{BaselineParams, octree};
//!
//! let mesh = shapes::capsule(0.5, 2.0, 12)?;
//! let tree = octree(&mesh, &BaselineParams::default().depth(2).samples(1_000))?;
//! assert_eq!(tree.level_count(), 3);
//! assert!(tree.level(2).len() > tree.level(1).len());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod grid;
mod hubbard;
mod octree;

pub use grid::grid;
pub use hubbard::hubbard;
pub use octree::octree;

use glam::DVec3;
use sphaera_medial::Surface;
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_mesh::{Sphere, TriMesh, sampling};

use crate::SphereTreeError;
use crate::reduce::{centre_depth, eq2_error};
use crate::tree::{SphereTree, TreeNode};

/// The deepest tree a baseline builds: an octree cell at depth 20 is a millionth of the
/// bounding cube's edge, far below any sample spacing, and deeper trees only repeat
/// one-sample leaves.
pub const MAX_DEPTH: usize = 20;

/// The most surface samples a baseline accepts (each costs about 100 bytes per level).
pub const MAX_SAMPLES: usize = 10_000_000;

/// Parameters of the baseline constructions.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct BaselineParams {
    /// Levels below the root (default 3; at most [`MAX_DEPTH`]).
    pub depth: usize,
    /// Children per node for [`hubbard`], and the growth of the cell count per level
    /// for [`grid`] (default 8; the octree always splits a cell in 8).
    pub branch: usize,
    /// Surface samples standing for the surface (default 10,000).
    pub samples: usize,
    /// Seed of the surface sampling (default 1).
    pub seed: u64,
    /// Forming points of [`hubbard`]'s static Voronoi diagram (default 600, which gives
    /// about 2,500 medial spheres on the low-res bunny, the size the paper used for
    /// Hubbard's method there).
    pub forming_points: usize,
}

impl Default for BaselineParams {
    fn default() -> Self {
        Self {
            depth: 3,
            branch: 8,
            samples: 10_000,
            seed: 1,
            forming_points: 600,
        }
    }
}

impl BaselineParams {
    /// With `depth` levels below the root.
    #[must_use]
    pub fn depth(mut self, depth: usize) -> Self {
        self.depth = depth;
        self
    }

    /// With branching factor `branch`.
    #[must_use]
    pub fn branch(mut self, branch: usize) -> Self {
        self.branch = branch;
        self
    }

    /// With `samples` surface samples.
    #[must_use]
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// With the given sampling seed.
    #[must_use]
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// With `n` forming points for [`hubbard`]'s static diagram.
    #[must_use]
    pub fn forming_points(mut self, n: usize) -> Self {
        self.forming_points = n;
        self
    }

    fn validate(&self) -> Result<(), SphereTreeError> {
        let bad = |what: String| Err(SphereTreeError::InvalidParameter(what));
        if self.depth > MAX_DEPTH {
            return bad(format!(
                "depth {} exceeds the baselines' maximum of {MAX_DEPTH}",
                self.depth
            ));
        }
        if self.branch == 0 {
            return bad("branch must be at least 1".into());
        }
        if !(4..=MAX_SAMPLES).contains(&self.samples) {
            return bad(format!(
                "samples {} must be between 4 and {MAX_SAMPLES}",
                self.samples
            ));
        }
        if self.forming_points < 4 {
            return bad(format!(
                "forming_points {} must be at least 4",
                self.forming_points
            ));
        }
        Ok(())
    }
}

/// The start every baseline shares: the surface, its samples and the root.
pub(crate) struct Start {
    pub(crate) surface: Surface,
    pub(crate) samples: Vec<DVec3>,
    pub(crate) root: Sphere,
}

/// Validates the parameters and the mesh, samples the surface and finds the root ball.
pub(crate) fn start(mesh: &TriMesh, params: &BaselineParams) -> Result<Start, SphereTreeError> {
    params.validate()?;
    let surface = Surface::new(mesh)?;
    let samples: Vec<DVec3> = sampling::poisson_disk(mesh, params.samples, params.seed)?
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    let root = minimum_enclosing_ball(mesh.positions())?;
    Ok(Start {
        surface,
        samples,
        root,
    })
}

/// A child proposed by a baseline: its sphere and its region (sample ids, ascending, a
/// part of the parent's region, every one inside the sphere).
pub(crate) struct Child {
    pub(crate) sphere: Sphere,
    pub(crate) region: Vec<u32>,
}

/// Assembles a tree level by level: `split(level, parent, region)` proposes the children
/// of a node of `level − 1` (its index among all nodes and its region); children with
/// an empty region are dropped. The tree's branching factor is the larger of `branch`
/// and the most children any node got.
pub(crate) fn assemble(
    start: &Start,
    depth: usize,
    branch: usize,
    mut split: impl FnMut(usize, usize, &[u32]) -> Result<Vec<Child>, SphereTreeError>,
) -> Result<SphereTree, SphereTreeError> {
    let error = |sphere: &Sphere| {
        let (d, inside) = centre_depth(&start.surface, sphere.center);
        eq2_error(sphere.radius, d, inside)
    };
    let mut nodes = vec![TreeNode {
        sphere: start.root,
        error: error(&start.root),
        level: 0,
        parent: None,
        children: 0..0,
        region_samples: start.samples.len() as u32,
    }];
    let mut regions: Vec<Vec<u32>> = vec![(0..start.samples.len() as u32).collect()];
    let mut level_starts = vec![0, 1];
    let mut widest = branch;
    for level in 1..=depth {
        let parents = level_starts[level - 1]..level_starts[level];
        for parent in parents {
            let first = nodes.len() as u32;
            let children = split(level, parent, &regions[parent])?;
            for child in children {
                if child.region.is_empty() {
                    continue;
                }
                nodes.push(TreeNode {
                    sphere: child.sphere,
                    error: error(&child.sphere),
                    level: level as u32,
                    parent: Some(parent as u32),
                    children: 0..0,
                    region_samples: child.region.len() as u32,
                });
                regions.push(child.region);
            }
            nodes[parent].children = first..nodes.len() as u32;
            widest = widest.max(nodes.len() - first as usize);
        }
        level_starts.push(nodes.len());
    }
    // The baselines are the classic methods as published: their coverage is measured
    // (`evaluate::coverage`), not certified.
    Ok(SphereTree {
        branch: widest,
        nodes,
        level_starts,
        coverage: Vec::new(),
    })
}

/// An axis-aligned grid of cubic cells of edge `cell` anchored at `origin`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CellGrid {
    pub(crate) origin: DVec3,
    pub(crate) cell: f64,
    /// Cells per axis.
    pub(crate) cells: u64,
}

impl CellGrid {
    /// The cell of `p` (clamped to the grid), as integer coordinates.
    pub(crate) fn cell_of(&self, p: DVec3) -> [u64; 3] {
        let max = self.cells.saturating_sub(1) as f64;
        let axis = |v: f64, o: f64| ((v - o) / self.cell).floor().clamp(0.0, max) as u64;
        [
            axis(p.x, self.origin.x),
            axis(p.y, self.origin.y),
            axis(p.z, self.origin.z),
        ]
    }

    /// The circumscribed sphere of a cell: it contains the whole cell, so every part of
    /// the surface inside the cell, not only the samples there.
    pub(crate) fn cell_sphere(&self, c: [u64; 3]) -> Sphere {
        let corner = self.origin + DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * self.cell;
        let centre = corner + DVec3::splat(0.5 * self.cell);
        // A hair more than half the diagonal, so that corners survive rounding.
        Sphere::new(centre, 0.5 * self.cell * 3f64.sqrt() * (1.0 + 1e-12))
    }
}

/// Groups `region` (sample ids) by cell, cells in lexicographic order, ids ascending.
pub(crate) fn group_by_cell(
    grid: &CellGrid,
    samples: &[DVec3],
    region: &[u32],
) -> Vec<([u64; 3], Vec<u32>)> {
    let mut keyed: Vec<([u64; 3], u32)> = region
        .iter()
        .map(|&s| (grid.cell_of(samples[s as usize]), s))
        .collect();
    keyed.sort_unstable();
    let mut out: Vec<([u64; 3], Vec<u32>)> = Vec::new();
    for (cell, s) in keyed {
        match out.last_mut() {
            Some((c, ids)) if *c == cell => ids.push(s),
            _ => out.push((cell, vec![s])),
        }
    }
    out
}
