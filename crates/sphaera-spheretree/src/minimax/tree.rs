//! The tree, top down: every node to split is divided between at most `branch` children,
//! level by level (the nodes of a level on every core with the `parallel` feature), either
//! to a fixed depth or, with a tolerance, only where a node's certified error exceeds it,
//! as deep as needed.

use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_query::Surface;

use super::candidates::signed_depth;
use super::node::{Child, Goal, Plan, divide};
use super::pieces::{Piece, area, mesh_pieces, refine, refined_count};
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
    let eq2_bounds = eq2_bounds(surface);
    certify_level(surface, &mut nodes, &[false], tolerance, eq2_bounds)?;
    let mut regions: Vec<Vec<Piece>> = vec![mesh_pieces(mesh)];
    // The signed depth of every node's centre.
    let mut depths = vec![root_depth];
    // Whether each node was divided around the surface itself ([`on_the_surface`]); its
    // depth is then measured on the shell, and its eq. 2 error bounds its protrusion.
    let mut surface_centred = vec![false];
    // The surface taken as a shell, built when a node first needs it.
    let mut shell: Option<Surface> = None;
    let mut level_starts = vec![0, 1];
    let branch = options.branch;
    let max_depth = match tolerance {
        Some(_) => MAX_MEDIAL_DEPTH,
        None => options.depth,
    };
    // A tolerance tree stops at the budget asked for.
    let max_nodes = match tolerance {
        Some(_) => options.max_nodes.min(MAX_TREE_NODES),
        None => MAX_TREE_NODES,
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
        // Never more nodes than asked for (each node divided gets a child at least), nor
        // than a tree may hold (each may get `branch`).
        if nodes.len().saturating_add(total) > max_nodes
            || nodes.len().saturating_add(total.saturating_mul(branch)) > MAX_TREE_NODES
        {
            return Err(unreachable(tolerance, &nodes, level - 1, max_nodes));
        }
        let last = tolerance.is_none() && level == max_depth;
        let mut effort = Plan::for_level(options.effort, total, branch, last);
        // The level's pieces together stay within LEVEL_PIECES: many nodes get fewer.
        effort.pieces = effort.pieces.min(LEVEL_PIECES / total);
        if effort.pieces < MIN_PIECES_PER_NODE {
            return Err(unreachable(tolerance, &nodes, level - 1, max_nodes));
        }
        let goal = match tolerance {
            Some(t) => Goal::Within {
                tolerance: t,
                most: branch,
            },
            None => Goal::Count(branch),
        };
        let on_surface: Vec<bool> = parents
            .iter()
            .map(|&p| {
                let parent = nodes[p].parent.map(|q| &nodes[q as usize]);
                surface_centred[p]
                    || (!eq2_bounds
                        && tolerance.is_some()
                        && on_the_surface(&nodes[p], depths[p], parent))
            })
            .collect();
        if shell.is_none() && on_surface.contains(&true) {
            shell = Some(Surface::shell(mesh)?);
        }
        let surfaces = Surfaces {
            solid: surface,
            shell: shell.as_ref(),
        };
        let divided = divide_all(
            &surfaces,
            &nodes,
            &depths,
            &regions,
            &parents,
            &on_surface,
            goal,
            effort,
            &|done| {
                progress(&SphereTreeProgress { level, done, total });
            },
        )?;
        let start = nodes.len();
        {
            let mut built = Level {
                nodes: &mut nodes,
                regions: &mut regions,
                depths: &mut depths,
                surface_centred: &mut surface_centred,
                level: level as u32,
                max_nodes,
                tolerance,
            };
            for ((&parent, (pieces, children)), &centred) in
                parents.iter().zip(divided).zip(&on_surface)
            {
                built.push(parent, children_of(&pieces, children, centred))?;
            }
            if built.nodes.len() == start {
                break;
            }
            certify_level(
                surface,
                &mut built.nodes[start..],
                &built.surface_centred[start..],
                tolerance,
                eq2_bounds,
            )?;
            if !eq2_bounds {
                let failed = through_a_hole(built.nodes, built.depths, &parents, &on_surface);
                if !failed.is_empty() {
                    let shell = match &mut shell {
                        Some(shell) => &*shell,
                        none => none.insert(Surface::shell(mesh)?),
                    };
                    let retry = (goal, effort);
                    redivide_on_the_shell(
                        surface, shell, &failed, &parents, start, retry, &mut built,
                    )?;
                }
                if tolerance.is_none() {
                    keep_the_parent_where_looser(
                        built.nodes,
                        built.depths,
                        built.surface_centred,
                        start,
                    );
                }
            }
        }
        // The parents' pieces live on in their children's regions.
        for &parent in &parents {
            regions[parent] = Vec::new();
        }
        level_starts.push(nodes.len());
        if let Some(t) = tolerance {
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
            return Err(unreachable(tolerance, &nodes, deepest, max_nodes));
        }
    }
    Ok(SphereTree {
        branch,
        nodes,
        level_starts,
        coverage: Vec::new(),
    })
}

/// A new child, before it joins the tree: the node, its region, its centre's signed depth
/// and whether it was divided around the surface itself.
type NewChild = (TreeNode, Vec<Piece>, f64, bool);

/// A division's children as new nodes (their errors as the division found them, before
/// certification).
fn children_of(pieces: &[Piece], children: Vec<Child>, centred: bool) -> Vec<NewChild> {
    children
        .into_iter()
        .map(|child| {
            let region: Vec<Piece> = child.members.iter().map(|&m| pieces[m as usize]).collect();
            let node = TreeNode {
                sphere: child.sphere,
                error: child.error,
                level: 0,
                parent: None,
                children: 0..0,
                region_samples: region.len() as u32,
            };
            (node, region, child.depth, centred)
        })
        .collect()
}

/// The tree's per-node arrays while a level is added to them.
struct Level<'a> {
    nodes: &'a mut Vec<TreeNode>,
    regions: &'a mut Vec<Vec<Piece>>,
    depths: &'a mut Vec<f64>,
    surface_centred: &'a mut Vec<bool>,
    level: u32,
    max_nodes: usize,
    tolerance: Option<f64>,
}

impl Level<'_> {
    /// Appends `parent`'s children, refused past the node budget.
    fn push(&mut self, parent: usize, children: Vec<NewChild>) -> Result<(), SphereTreeError> {
        if self.nodes.len() + children.len() > self.max_nodes {
            let level = self.level as usize - 1;
            return Err(unreachable(
                self.tolerance,
                self.nodes,
                level,
                self.max_nodes,
            ));
        }
        let first = self.nodes.len() as u32;
        for (mut node, region, depth, centred) in children {
            node.level = self.level;
            node.parent = Some(parent as u32);
            self.nodes.push(node);
            self.regions.push(region);
            self.depths.push(depth);
            self.surface_centred.push(centred);
        }
        self.nodes[parent].children = first..self.nodes.len() as u32;
        Ok(())
    }
}

/// The parents (of those divided on the solid) one of whose children reaches farther
/// than the parent by its certified error: on an open mesh taken as a solid, a child
/// centred beside a hole pokes out through it (see [`on_the_surface`]).
fn through_a_hole(
    nodes: &[TreeNode],
    depths: &[f64],
    parents: &[usize],
    on_surface: &[bool],
) -> Vec<usize> {
    parents
        .iter()
        .zip(on_surface)
        .filter(|&(&p, &centred)| {
            let parent = &nodes[p];
            !centred
                && nodes[parent.children.start as usize..parent.children.end as usize]
                    .iter()
                    .zip(&depths[parent.children.start as usize..parent.children.end as usize])
                    .any(|(child, &depth)| {
                        child.error > parent.error
                            || child.error
                                > THROUGH_A_HOLE * super::eq2(child.sphere.radius, depth).max(0.0)
                    })
        })
        .map(|(&p, _)| p)
        .collect()
}

/// Divides the `failed` parents of the level that starts at `start` again, around the
/// surface itself (on the shell), and keeps for each the division whose worst certified
/// child is tighter; the level is rebuilt in its parents' order.
fn redivide_on_the_shell(
    solid: &Surface,
    shell: &Surface,
    failed: &[usize],
    parents: &[usize],
    start: usize,
    (goal, effort): (Goal, Plan),
    level: &mut Level<'_>,
) -> Result<(), SphereTreeError> {
    let surfaces = Surfaces {
        solid,
        shell: Some(shell),
    };
    let centred = vec![true; failed.len()];
    let divided = divide_all(
        &surfaces,
        level.nodes,
        level.depths,
        level.regions,
        failed,
        &centred,
        goal,
        effort,
        &|_| {},
    )?;
    let mut retried: Vec<Vec<NewChild>> = divided
        .into_iter()
        .map(|(pieces, children)| children_of(&pieces, children, true))
        .collect();
    // Every retried child certified at once (on every core), its error then its own.
    let mut new: Vec<TreeNode> = retried.iter().flatten().map(|c| c.0.clone()).collect();
    let all_centred = vec![true; new.len()];
    certify_level(solid, &mut new, &all_centred, level.tolerance, false)?;
    for (child, node) in retried.iter_mut().flatten().zip(new) {
        child.0.error = node.error;
    }
    let worst = |children: &[NewChild]| children.iter().map(|c| c.0.error).fold(0.0, f64::max);
    // The level as built, taken out to be put back parent by parent.
    let mut built = level
        .nodes
        .split_off(start)
        .into_iter()
        .zip(level.regions.split_off(start))
        .zip(level.depths.split_off(start))
        .zip(level.surface_centred.split_off(start))
        .map(|(((node, region), depth), centred)| (node, region, depth, centred));
    let mut retried = failed.iter().zip(retried).peekable();
    for &parent in parents {
        let count = level.nodes[parent].children.len();
        let solid_children: Vec<NewChild> = built.by_ref().take(count).collect();
        let children = match retried.next_if(|(p, _)| **p == parent) {
            Some((_, on_shell)) if worst(&on_shell) < worst(&solid_children) => on_shell,
            _ => solid_children,
        };
        level.push(parent, children)?;
    }
    Ok(())
}

/// In a tree built to a depth on an open mesh taken as a solid: a child of the level
/// starting at `start` that reaches farther than its parent, by their certified errors,
/// after both divisions were tried ([`redivide_on_the_shell`]), takes its parent's sphere
/// (which covers the child's region, being a part of the parent's), so no level is
/// looser than the one above it. It happens where the surface's pieces are still too
/// large for spheres around them to beat the medial balls pinned by a hole's dent.
fn keep_the_parent_where_looser(
    nodes: &mut [TreeNode],
    depths: &mut [f64],
    surface_centred: &mut [bool],
    start: usize,
) {
    for child in start..nodes.len() {
        let Some(parent) = nodes[child].parent.map(|p| p as usize) else {
            continue;
        };
        if nodes[child].error > nodes[parent].error {
            nodes[child].sphere = nodes[parent].sphere;
            nodes[child].error = nodes[parent].error;
            depths[child] = depths[parent];
            surface_centred[child] = surface_centred[parent];
        }
    }
}

/// The error of a tolerance that cannot be met, from the tree as it stands.
fn unreachable(
    tolerance: Option<f64>,
    nodes: &[TreeNode],
    levels: usize,
    limit: usize,
) -> SphereTreeError {
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
        limit,
        depth: MAX_MEDIAL_DEPTH,
    }
}

/// Whether eq. 2 (the radius less the centre's depth) bounds a sphere's error: on a
/// shell, and on a solid whose inside is bounded by the mesh alone, a closed mesh (a ball
/// of the depth's radius about an inside centre is then inside). An open mesh taken as a
/// solid (a scan with holes) has an inside that reaches out through its holes: its
/// nodes' errors are certified by evaluation instead.
fn eq2_bounds(surface: &Surface) -> bool {
    !surface.has_inside() || surface.is_embedded_solid() || closed_chain(surface.mesh())
}

/// Whether the triangles' oriented edges cancel (every edge, by its corners' positions,
/// used as often in one direction as in the other): the generalized winding number is
/// then an integer off the mesh and changes only across it, so the inside it defines is
/// bounded by the mesh.
fn closed_chain(mesh: &sphaera_mesh::TriMesh) -> bool {
    let positions = mesh.positions();
    let key = |v: u32| positions[v as usize].to_array().map(f64::to_bits);
    // Every vertex named by its position's rank among the distinct positions: the same
    // name for the same position, names ordered as the positions' bits.
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    // Vertices at one position tie, and get one name whatever their order: the sorts are
    // free to differ (on every core with `parallel`).
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        order.par_sort_unstable_by_key(|&v| key(v));
    }
    #[cfg(not(feature = "parallel"))]
    order.sort_unstable_by_key(|&v| key(v));
    let mut name = vec![0_u32; positions.len()];
    let mut rank = 0_u32;
    for (i, &v) in order.iter().enumerate() {
        if i > 0 && key(v) != key(order[i - 1]) {
            rank += 1;
        }
        name[v as usize] = rank;
    }
    // Every oriented edge as its two names, the smaller first, and whether it runs from
    // the larger; a degenerate edge counts as backward alone.
    let mut edges: Vec<(u64, bool)> = Vec::with_capacity(3 * mesh.triangle_count());
    for t in mesh.triangles() {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let (a, b) = (u64::from(name[a as usize]), u64::from(name[b as usize]));
            edges.push(if a < b {
                ((a << 32) | b, false)
            } else {
                ((b << 32) | a, true)
            });
        }
    }
    // Equal entries are the same entry: any sort gives the same sequence.
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        edges.par_sort_unstable();
    }
    #[cfg(not(feature = "parallel"))]
    edges.sort_unstable();
    // Per edge, as many forward as backward.
    edges
        .chunk_by(|x, y| x.0 == y.0)
        .all(|run| 2 * run.iter().filter(|e| !e.1).count() == run.len())
}

/// A node of an open mesh taken as a solid whose certified error exceeds its eq. 2 error
/// this many times reaches out through a hole: its region is divided around the surface
/// itself ([`on_the_surface`]).
const THROUGH_A_HOLE: f64 = 1.5;

/// Whether a node of a tolerance tree on an open mesh taken as a solid (eq. 2 bounds
/// nothing there) is divided around the surface itself, on the shell, rather than around
/// the solid's medial candidates: when its certified error exceeds its eq. 2 error
/// [`THROUGH_A_HOLE`] times. The medial balls of a region beside a hole reach into it
/// (no triangle stops them there), so its children would be centred in the hole again,
/// deep by eq. 2 and poking out through it, level after level, and the tolerance never
/// met. On the shell a centre's depth is minus its distance to the surface, so a child's
/// eq. 2 error is its radius plus that distance, which bounds how far it reaches from the
/// surface (the distance is 1-Lipschitz), hence beyond the solid: its children shrink
/// with their pieces until they meet any tolerance. A node no tighter than its parent
/// (whose division gave back the parent's sphere: its children would have reached
/// farther by eq. 2, which under-estimates here) is divided on the shell as well.
fn on_the_surface(node: &TreeNode, depth: f64, parent: Option<&TreeNode>) -> bool {
    node.error > THROUGH_A_HOLE * super::eq2(node.sphere.radius, depth).max(0.0)
        || parent.is_some_and(|parent| node.error >= parent.error)
}

/// The surface, and the same surface taken as a shell (when some node needs it).
struct Surfaces<'a> {
    solid: &'a Surface,
    shell: Option<&'a Surface>,
}

/// A parent's region as divided (its pieces) and its children.
type Division = (Vec<Piece>, Vec<Child>);

/// Divides every parent's region (in batches, each on every core with the `parallel`
/// feature; each division is independent, so the result is the same): per parent, its
/// pieces as divided and the children. `done(n)` is called from the calling thread after
/// each batch.
#[allow(clippy::too_many_arguments)]
fn divide_all(
    surfaces: &Surfaces<'_>,
    nodes: &[TreeNode],
    depths: &[f64],
    regions: &[Vec<Piece>],
    parents: &[usize],
    on_surface: &[bool],
    goal: Goal,
    effort: Plan,
    done: &dyn Fn(usize),
) -> Result<Vec<Division>, SphereTreeError> {
    let most = match goal {
        Goal::Count(k) => k,
        Goal::Within { most, .. } => most,
    };
    let one = |(&parent, &centred): (&usize, &bool)| -> Result<Division, SphereTreeError> {
        let region = &regions[parent];
        let pieces = refine(region, piece_size(region, most, &effort))?;
        let node = &nodes[parent];
        if centred && let Some(shell) = surfaces.shell {
            // The parent stands with its certified error (its depth made to give it):
            // no child reaches farther.
            let depth = node.sphere.radius - node.error;
            let children = divide(shell, &pieces, goal, (node.sphere, depth), effort)?;
            return Ok((pieces, children));
        }
        let surface = surfaces.solid;
        // Where eq. 2 under-estimates (an open mesh taken as a solid: the node's certified
        // error is above its eq. 2), the children must meet eq. 2 by as much more, or a
        // region would be divided into the same sphere again and again.
        let goal = match goal {
            Goal::Within { tolerance, most } => {
                let eq2 = super::eq2(node.sphere.radius, depths[parent]);
                let under = if node.error > eq2 {
                    (eq2 / node.error).clamp(0.0, 1.0)
                } else {
                    1.0
                };
                Goal::Within {
                    tolerance: tolerance * under,
                    most,
                }
            }
            count => count,
        };
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
    for (batch, (chunk, centred)) in parents
        .chunks(PROGRESS_BATCH)
        .zip(on_surface.chunks(PROGRESS_BATCH))
        .enumerate()
    {
        done(batch * PROGRESS_BATCH);
        #[cfg(feature = "parallel")]
        let divided: Result<Vec<_>, SphereTreeError> = {
            use rayon::prelude::*;
            chunk.par_iter().zip(centred).map(one).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let divided: Result<Vec<_>, SphereTreeError> = chunk.iter().zip(centred).map(one).collect();
        out.extend(divided?);
    }
    Ok(out)
}

/// The longest edge a region's pieces are split to before it is divided into `most`
/// children: about the plan's pieces per node (or per child) over the region's area, and
/// never so fine that the region exceeds the pieces cap (checked by `refine`). Slivers
/// (a thin rod's long side triangles) split along their length into far more pieces than
/// their area suggests: the edge is then lengthened until the region makes at most twice
/// the pieces wanted.
fn piece_size(region: &[Piece], most: usize, plan: &Plan) -> f64 {
    let total: f64 = region.iter().map(area).sum();
    let wanted = plan.pieces.max(plan.pieces_per_child.saturating_mul(most));
    // A piece split to longest edge h has area about h²/4.
    let h = (4.0 * total / wanted as f64).sqrt();
    if !(h > 0.0 && h.is_finite()) {
        return f64::INFINITY;
    }
    // Unsplit, the region has its own count of pieces: never asked below that.
    let limit = wanted.saturating_mul(2).max(region.len());
    let fits = |h: f64| refined_count(region, h, limit) <= limit;
    if fits(h) {
        return h;
    }
    // Doubling h ends: past the longest edge nothing is split.
    let (mut short, mut long) = (h, 2.0 * h);
    while !fits(long) {
        (short, long) = (long, 2.0 * long);
    }
    // Halving the ratio in log scale; powers of two scale every step exactly.
    for _ in 0..6 {
        let middle = (short * long).sqrt();
        if fits(middle) {
            long = middle;
        } else {
            short = middle;
        }
    }
    long
}

/// The certified error of every node of a new level whose eq. 2 error exceeds the
/// tolerance (`None` in a tree built to a depth: none does), or of every node when eq. 2
/// bounds nothing (`eq2_bounds` false, see [`eq2_bounds`]); a node of a tolerance tree whose certified error meets
/// the tolerance is then a leaf.
fn certify_level(
    surface: &Surface,
    level: &mut [TreeNode],
    surface_centred: &[bool],
    tolerance: Option<f64>,
    eq2_bounds: bool,
) -> Result<(), SphereTreeError> {
    let one = |(node, &centred): (&TreeNode, &bool)| -> Result<f64, SphereTreeError> {
        // A child of a division on the shell: its eq. 2 error bounds its protrusion.
        let eq2_bounds = eq2_bounds || centred;
        let within = tolerance.is_none_or(|t| node.error <= t);
        if eq2_bounds && within {
            return Ok(node.error);
        }
        let goal = tolerance.unwrap_or(node.error);
        let options = EvaluationOptions::default().with_tolerance(sphaera_mesh::Length::Absolute(
            (CERTIFY_FRACTION * goal).max(f64::MIN_POSITIVE),
        ));
        let fit = sphere_error(surface, &node.sphere, &options)?;
        Ok(if eq2_bounds {
            node.error.min(fit.upper)
        } else {
            fit.upper
        })
    };
    #[cfg(feature = "parallel")]
    let errors: Result<Vec<f64>, SphereTreeError> = {
        use rayon::prelude::*;
        level.par_iter().zip(surface_centred).map(one).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let errors: Result<Vec<f64>, SphereTreeError> =
        level.iter().zip(surface_centred).map(one).collect();
    for (node, error) in level.iter_mut().zip(errors?) {
        node.error = error;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use sphaera_mesh::{TriMesh, shapes};

    use super::closed_chain;

    #[test]
    fn a_closed_chain_is_told_by_positions() {
        let cube = shapes::cube(2.0, 2).expect("cube");
        assert!(closed_chain(&cube));
        // Every triangle with its own corners: still closed by positions.
        let positions: Vec<_> = cube
            .triangles()
            .iter()
            .flat_map(|t| t.map(|v| cube.positions()[v as usize]))
            .collect();
        let triangles: Vec<[u32; 3]> = (0..cube.triangle_count() as u32)
            .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        let soup = TriMesh::new(positions, triangles).expect("soup");
        assert!(closed_chain(&soup));
        // A triangle missing, or one turned over: open.
        let mut open = cube.triangles().to_vec();
        let last = open.pop().expect("a triangle");
        let holed = TriMesh::new(cube.positions().to_vec(), open.clone()).expect("holed");
        assert!(!closed_chain(&holed));
        open.push([last[0], last[2], last[1]]);
        let flipped = TriMesh::new(cube.positions().to_vec(), open).expect("flipped");
        assert!(!closed_chain(&flipped));
    }
}
