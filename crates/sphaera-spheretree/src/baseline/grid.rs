//! The grid sphere-tree: per level, a regular grid of cubic cells.

use std::collections::HashSet;

use glam::DVec3;

use super::{CellGrid, Child, Start, assemble, group_by_cell};
use crate::options::{SphereTreeOptions, SphereTreeProgress};
use crate::{SphereTree, SphereTreeError};

/// Bisection steps of the cell-size search.
const SIZE_STEPS: usize = 48;

/// Builds the grid sphere-tree of `mesh`.
///
/// **Rule.** Level `l` uses a regular grid of cubic cells anchored at the bounding box's
/// minimum corner, whose edge is the smallest (found by bisection, to 2⁻⁴⁸ of the box)
/// for which at most `branch^l` cells hold a surface sample (capped at the sample
/// count). A node of level `l` is a pair (parent, cell): the parent's region samples
/// falling in the cell, and the cell's **circumscribed sphere**, as for
/// [`octree`](super::octree) (it covers the whole surface in the cell). Unlike the
/// octree, consecutive grids are not nested: a cell straddling two parents' regions
/// yields a child of each (the same sphere twice), so a level may have somewhat more
/// nodes than occupied cells and a node more than `branch` children;
/// [`SphereTree::branch`] reports the most children any node has (at least `branch`).
pub(crate) fn grid(
    start: &Start<'_>,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    let bounds = start.surface.mesh().bounding_box();
    let extent = bounds.extent();
    let longest = extent.x.max(extent.y).max(extent.z).max(f64::MIN_POSITIVE);
    let samples = &start.samples;
    let grids: Vec<CellGrid> = (1..=options.depth)
        .map(|level| {
            let target = (options.branch as u64)
                .checked_pow(level as u32)
                .unwrap_or(u64::MAX)
                .min(samples.len() as u64);
            level_grid(samples, bounds.min, longest, target)
        })
        .collect();
    assemble(
        start,
        options.depth,
        options.branch,
        progress,
        |level, _, region| {
            let Some(grid) = grids.get(level - 1) else {
                return Ok(Vec::new());
            };
            Ok(group_by_cell(grid, samples, region)
                .into_iter()
                .map(|(cell, ids)| Child {
                    sphere: grid.cell_sphere(cell),
                    region: ids,
                })
                .collect())
        },
    )
}

/// The grid of the smallest cell edge with at most `target` occupied cells.
fn level_grid(samples: &[DVec3], origin: DVec3, longest: f64, target: u64) -> CellGrid {
    let make = |cell: f64| CellGrid {
        origin,
        cell,
        // Enough cells to reach past the box on every axis (bounded: the edge is at
        // least 2⁻⁴⁸ of the box).
        cells: (longest / cell).ceil() as u64 + 1,
    };
    let occupied = |g: &CellGrid| {
        samples
            .iter()
            .map(|&p| g.cell_of(p))
            .collect::<HashSet<[u64; 3]>>()
            .len() as u64
    };
    // One cell as large as the box (plus a hair) is always feasible.
    let (mut feasible, mut infeasible) = (longest * (1.0 + 1e-9), 0.0);
    for _ in 0..SIZE_STEPS {
        let mid = 0.5 * (feasible + infeasible);
        if mid <= 0.0 {
            break;
        }
        if occupied(&make(mid)) <= target {
            feasible = mid;
        } else {
            infeasible = mid;
        }
    }
    make(feasible)
}
