//! The octree sphere-tree (the classic method of Palmer and Grimsdale, Hubbard, and
//! O'Sullivan and Dingliana; section 2 of the paper).

use glam::DVec3;

use super::{CellGrid, Child, Start, assemble, group_by_cell};
use crate::options::{SphereTreeOptions, SphereTreeProgress};
use crate::{SphereTree, SphereTreeError};

/// Builds the octree sphere-tree of `mesh`: the bounding cube of the mesh is subdivided
/// recursively into 8 cubes; every cube holding surface samples becomes a node whose
/// sphere is the cube's **circumscribed sphere**, and whose region is the samples in it.
///
/// The circumscribed sphere is the classic method's choice, kept here for two reasons:
/// it contains the whole cube, so it covers every part of the surface inside the cube,
/// not only the samples (a tight ball of the samples would need a margin, and a margin
/// certified for the surface between samples is what the circumscribed sphere already
/// is); and it makes the figures comparable with the classic toolkit's octree. A cube
/// the surface crosses without a sample is covered by its neighbours' spheres, which
/// reach 0.37 of a cell edge beyond their faces: more than the sample spacing whenever a
/// cell is larger than about three sample spacings.
///
/// Each node has at most 8 children ([`SphereTree::branch`] is 8 whatever
/// `branch` says). Only `depth`, `samples` and `seed` are used.
pub(crate) fn octree(
    start: &Start<'_>,
    options: &SphereTreeOptions,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    let bounds = start.surface.mesh().bounding_box();
    let extent = bounds.extent();
    // A hair larger than the box, so that no sample sits on the far faces.
    let edge = extent.x.max(extent.y).max(extent.z).max(f64::MIN_POSITIVE) * (1.0 + 1e-9);
    let origin = bounds.center() - DVec3::splat(0.5 * edge);
    let samples = &start.samples;
    assemble(start, options.depth, 8, progress, |level, _, region| {
        let cells = 1u64 << level;
        let grid = CellGrid {
            origin,
            cell: edge / cells as f64,
            cells,
        };
        Ok(group_by_cell(&grid, samples, region)
            .into_iter()
            .map(|(cell, ids)| Child {
                sphere: grid.cell_sphere(cell),
                region: ids,
            })
            .collect())
    })
}
