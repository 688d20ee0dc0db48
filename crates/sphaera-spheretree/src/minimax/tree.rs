//! The tree, top down: every node to split is divided between at most `branch` children,
//! level by level (the nodes of a level on every core with the `parallel` feature), either
//! to a fixed depth or, with a tolerance, only where a node's certified error exceeds it,
//! as deep as needed.

use sphaera_mesh::Surface;
use sphaera_mesh::geometry::minimum_enclosing_ball;

use super::candidates::signed_depth;
use super::node::{Child, Goal, Plan, divide};
use super::pieces::{Piece, area, mesh_pieces, refine};
use crate::evaluate::{EvaluationOptions, sphere_error};
use crate::options::{SphereTreeOptions, SphereTreeProgress};
use crate::tree::{SphereTree, TreeNode};
use crate::{MAX_MEDIAL_DEPTH, SphereTreeError};

/// The most nodes a tree may have (each holds its region's pieces while its level is
/// built): a tolerance needing more is refused.
pub const MAX_TREE_NODES: usize = 1 << 21;

/// The most pieces the nodes of one level hold together (about 1.2 GB): a level of many
/// nodes tiles each more coarsely.
const LEVEL_PIECES: usize = 1 << 24;

/// The fewest pieces a node is tiled with before it is divided: a tolerance tree whose
/// level would need more nodes than [`LEVEL_PIECES`] allows at this is refused.
const MIN_PIECES_PER_NODE: usize = 256;

/// Parents divided between two progress reports (in parallel within a batch).
const PROGRESS_BATCH: usize = 8;

/// The certified evaluation of a node whose eq. 2 error exceeds the tolerance is run to
/// this fraction of the tolerance.
const CERTIFY_FRACTION: f64 = 0.02;

/// Builds the tree of `surface` in its own coordinates: to `options.depth`, or with
/// `tolerance` (in the surface's units) until every leaf's certified error meets it.
pub(crate) fn minimax_tree(
    surface: &Surface,
    options: &SphereTreeOptions,
    tolerance: Option<f64>,
    progress: &(dyn Fn(&SphereTreeProgress) + Sync),
) -> Result<SphereTree, SphereTreeError> {
    let mesh = surface.mesh();
    let root_ball = minimum_enclosing_ball(mesh.positions())?;
    let root_depth = signed_depth(surface, root_ball.center)?;
    let mut nodes = vec![TreeNode {
        sphere: root_ball,
        error: super::eq2(root_ball.radius, root_depth),
        level: 0,
        parent: None,
        children: 0..0,
        region_samples: mesh.triangle_count() as u32,
    }];
    let mut regions: Vec<Vec<Piece>> = vec![mesh_pieces(mesh)];
    // The signed depth of every node's centre.
    let mut depths = vec![root_depth];
    let mut level_starts = vec![0, 1];
    let branch = options.branch;
    let max_depth = match tolerance {
        Some(_) => MAX_MEDIAL_DEPTH,
        None => options.depth,
    };
    for level in 1..=max_depth {
        let above = level_starts[level - 1]..level_starts[level];
        let parents: Vec<usize> = above
            .filter(|&p| match tolerance {
                Some(t) => nodes[p].error > t,
                None => true,
            })
            .collect();
        if parents.is_empty() {
            break;
        }
        let total = parents.len();
        if nodes.len().saturating_add(total.saturating_mul(branch)) > MAX_TREE_NODES {
            return Err(unreachable(tolerance, &nodes, level - 1));
        }
        let last = tolerance.is_none() && level == max_depth;
        let mut effort = Plan::for_level(options.effort, total, branch, last);
        // The level's pieces together stay within LEVEL_PIECES: many nodes get fewer.
        effort.pieces = effort.pieces.min(LEVEL_PIECES / total);
        if effort.pieces < MIN_PIECES_PER_NODE {
            return Err(unreachable(tolerance, &nodes, level - 1));
        }
        let goal = match tolerance {
            Some(t) => Goal::Within {
                tolerance: t,
                most: branch,
            },
            None => Goal::Count(branch),
        };
        let divided = divide_all(
            surface,
            &nodes,
            &depths,
            &regions,
            &parents,
            goal,
            effort,
            &|done| {
                progress(&SphereTreeProgress { level, done, total });
            },
        )?;
        let mut added = 0_usize;
        for (&parent, (pieces, children)) in parents.iter().zip(divided) {
            let first = nodes.len() as u32;
            added += children.len();
            if nodes.len() + children.len() > MAX_TREE_NODES {
                return Err(unreachable(tolerance, &nodes, level));
            }
            for child in children {
                let region: Vec<Piece> =
                    child.members.iter().map(|&m| pieces[m as usize]).collect();
                nodes.push(TreeNode {
                    sphere: child.sphere,
                    error: child.error,
                    level: level as u32,
                    parent: Some(parent as u32),
                    children: 0..0,
                    region_samples: region.len() as u32,
                });
                regions.push(region);
                depths.push(child.depth);
            }
            nodes[parent].children = first..nodes.len() as u32;
            // The parent's pieces live on in its children's regions.
            regions[parent] = Vec::new();
        }
        if added == 0 {
            break;
        }
        level_starts.push(nodes.len());
        if let Some(t) = tolerance {
            let start = level_starts[level];
            certify_level(surface, &mut nodes[start..], t)?;
            // Leaves are never divided: their pieces go.
            for (node, region) in nodes[start..].iter().zip(&mut regions[start..]) {
                if node.error <= t {
                    *region = Vec::new();
                }
            }
        }
    }
    drop(regions);
    if let Some(t) = tolerance {
        let deepest = level_starts.len().saturating_sub(2);
        let last = level_starts[deepest]..nodes.len();
        if nodes[last].iter().any(|n| n.error > t) {
            return Err(unreachable(tolerance, &nodes, deepest));
        }
    }
    Ok(SphereTree {
        branch,
        nodes,
        level_starts,
        coverage: Vec::new(),
    })
}

/// The error of a tolerance that cannot be met, from the tree as it stands.
fn unreachable(tolerance: Option<f64>, nodes: &[TreeNode], levels: usize) -> SphereTreeError {
    let tolerance = tolerance.unwrap_or(0.0);
    let worst = nodes
        .iter()
        .filter(|n| n.children.is_empty())
        .map(|n| n.error)
        .fold(0.0, f64::max);
    SphereTreeError::ToleranceUnreachable {
        tolerance,
        worst,
        spheres: nodes.len(),
        levels,
        limit: MAX_TREE_NODES,
        depth: MAX_MEDIAL_DEPTH,
    }
}

/// A parent's region as divided (its pieces) and its children.
type Division = (Vec<Piece>, Vec<Child>);

/// Divides every parent's region (in batches, each on every core with the `parallel`
/// feature; each division is independent, so the result is the same): per parent, its
/// pieces as divided and the children. `done(n)` is called from the calling thread after
/// each batch.
#[allow(clippy::too_many_arguments)]
fn divide_all(
    surface: &Surface,
    nodes: &[TreeNode],
    depths: &[f64],
    regions: &[Vec<Piece>],
    parents: &[usize],
    goal: Goal,
    effort: Plan,
    done: &dyn Fn(usize),
) -> Result<Vec<Division>, SphereTreeError> {
    let most = match goal {
        Goal::Count(k) => k,
        Goal::Within { most, .. } => most,
    };
    let one = |&parent: &usize| -> Result<Division, SphereTreeError> {
        let region = &regions[parent];
        let pieces = refine(region, piece_size(region, most, &effort))?;
        let node = &nodes[parent];
        let children = divide(
            surface,
            &pieces,
            goal,
            (node.sphere, depths[parent]),
            effort,
        )?;
        Ok((pieces, children))
    };
    let mut out = Vec::with_capacity(parents.len());
    for (batch, chunk) in parents.chunks(PROGRESS_BATCH).enumerate() {
        done(batch * PROGRESS_BATCH);
        #[cfg(feature = "parallel")]
        let divided: Result<Vec<_>, SphereTreeError> = {
            use rayon::prelude::*;
            chunk.par_iter().map(one).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let divided: Result<Vec<_>, SphereTreeError> = chunk.iter().map(one).collect();
        out.extend(divided?);
    }
    Ok(out)
}

/// The longest edge a region's pieces are split to before it is divided into `most`
/// children: about the plan's pieces per node (or per child) over the region's area, and
/// never so fine that the region exceeds the pieces cap (checked by `refine`).
fn piece_size(region: &[Piece], most: usize, plan: &Plan) -> f64 {
    let total: f64 = region.iter().map(area).sum();
    let wanted = plan.pieces.max(plan.pieces_per_child.saturating_mul(most)) as f64;
    // A piece split to longest edge h has area about h²/4.
    let h = (4.0 * total / wanted).sqrt();
    if h > 0.0 && h.is_finite() {
        h
    } else {
        f64::INFINITY
    }
}

/// In a tolerance tree: the certified error of every node of a new level whose eq. 2
/// error exceeds the tolerance; a node whose certified error meets it keeps that as its
/// error (it is then a leaf).
fn certify_level(
    surface: &Surface,
    level: &mut [TreeNode],
    tolerance: f64,
) -> Result<(), SphereTreeError> {
    let options = EvaluationOptions::default().with_tolerance(sphaera_mesh::Length::Absolute(
        (CERTIFY_FRACTION * tolerance).max(f64::MIN_POSITIVE),
    ));
    let one = |node: &TreeNode| -> Result<f64, SphereTreeError> {
        if node.error <= tolerance {
            return Ok(node.error);
        }
        let fit = sphere_error(surface, &node.sphere, &options)?;
        Ok(node.error.min(fit.upper))
    };
    #[cfg(feature = "parallel")]
    let errors: Result<Vec<f64>, SphereTreeError> = {
        use rayon::prelude::*;
        level.par_iter().map(one).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let errors: Result<Vec<f64>, SphereTreeError> = level.iter().map(one).collect();
    for (node, error) in level.iter_mut().zip(errors?) {
        node.error = error;
    }
    Ok(())
}
