//! The classic sphere-tree constructions the paper compares against (sections 2 and 7),
//! reached through [`build`](crate::build) with [`Method::Octree`], [`Method::Grid`] or
//! [`Method::Hubbard`] (see each variant's docs for its rule).

mod grid;
mod hubbard;
mod octree;

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_query::Surface;
use sphaera_query::sampling;

use crate::SphereTreeError;
use crate::options::{SphereTreeOptions, SphereTreeProgress};
use crate::reduce::{center_depth, eq2_error};
use crate::tree::{SphereTree, TreeNode};

/// The octree tree of `surface` (`options` validated).
pub(crate) fn octree(
    surface: &Surface,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    octree::octree(&start(surface, options)?, options, progress)
}

/// The grid tree of `surface` (`options` validated).
pub(crate) fn grid(
    surface: &Surface,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    grid::grid(&start(surface, options)?, options, progress)
}

/// Hubbard's tree of `surface` (`options` validated).
pub(crate) fn hubbard(
    surface: &Surface,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    hubbard::hubbard(&start(surface, options)?, options, progress)
}

/// The start every baseline shares: the surface, its samples and the root.
pub(crate) struct Start<'s> {
    pub(crate) surface: &'s Surface,
    pub(crate) samples: Vec<DVec3>,
    pub(crate) root: Sphere,
}

/// Samples the surface and finds the root ball.
fn start<'s>(
    surface: &'s Surface,
    options: &SphereTreeOptions,
) -> Result<Start<'s>, SphereTreeError> {
    let mesh = surface.mesh();
    let samples: Vec<DVec3> = sampling::poisson_disk(mesh, options.samples, options.seed)?
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
    start: &Start<'_>,
    depth: usize,
    branch: usize,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
    mut split: impl FnMut(usize, usize, &[u32]) -> Result<Vec<Child>, SphereTreeError>,
) -> Result<SphereTree, SphereTreeError> {
    let error = |sphere: &Sphere| {
        let (d, inside) = center_depth(start.surface, sphere.center);
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
        let total = parents.len();
        for (done, parent) in parents.enumerate() {
            progress(&SphereTreeProgress { level, done, total });
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
        let center = corner + DVec3::splat(0.5 * self.cell);
        // A hair more than half the diagonal, so that corners survive rounding.
        Sphere::new(center, 0.5 * self.cell * 3f64.sqrt() * (1.0 + 1e-12))
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
