//! The spheres of a link's meshes: one-level and tolerance minimax trees on their
//! surface, with certified bounds on how far each sphere reaches beyond it.

use glam::DVec3;
use sphaera_mesh::{Length, Sphere};
use sphaera_query::Surface;
use sphaera_spheretree::{EvaluationOptions, SphereTree, evaluate_set_bounded};

use super::{PartFit, SpherizeOptions};
/// The surface of a link's meshes: its vertices at identical positions welded first
/// (meshes exported per triangle, as OBJ and STL files often are, become the closed
/// manifolds they are, certified embedded solids), then a solid when it has an inside,
/// else a shell. The geometry is unchanged.
pub(super) fn prepare_surface(
    mesh: &sphaera_mesh::TriMesh,
) -> Result<Surface, sphaera_query::QueryError> {
    let (welded, _) = sphaera_mesh::topology::weld_vertices(mesh, 0.0)?;
    Surface::solid_or_shell(&welded)
}

/// Whether the sphere-tree's node errors (the paper's eq. 2 on the certified side of
/// the centre) bound the spheres' protrusion: on a certified embedded solid (a closed
/// manifold) and on a shell. On a mesh that encloses a solid only loosely (holes,
/// non-manifold edges: the winding number does not jump from 0 to 1 across every
/// triangle) a point can leave the inside without crossing the surface, so the spheres
/// are evaluated in full instead.
fn bounds_hold(surface: &Surface) -> bool {
    surface.is_embedded_solid() || !surface.has_inside()
}

/// How far `ball` reaches beyond the solid (or shell) of `surface`, at most: eq. 2 where
/// it holds, else the branch and bound's certified upper end.
pub(super) fn ball_bound(surface: &Surface, ball: Sphere) -> Result<f64, String> {
    if bounds_hold(surface) {
        let side = surface
            .signed_closest(ball.center)
            .map_err(|e| e.to_string())?;
        return Ok((ball.radius + side.signed_distance()).max(0.0));
    }
    let options = EvaluationOptions::default().with_coverage_samples(1);
    sphaera_spheretree::evaluate_set(surface, &[ball], &options)
        .map(|fit| fit.worst_upper)
        .map_err(|e| e.to_string())
}

/// Exactly `count` spheres of a one-level minimax tree on `surface`.
pub(super) fn mesh_count(
    surface: &Surface,
    count: usize,
    options: &SpherizeOptions,
) -> Result<PartFit, String> {
    let mut tree_options = options.tree.clone().with_depth(1).with_branch(count);
    tree_options.tolerance = None;
    let tree = sphaera_spheretree::build(surface, &tree_options).map_err(|e| e.to_string())?;
    let (spheres, bounds) = cut(&tree, 1);
    let upper = certified_uppers(surface, &spheres, &bounds, None)?;
    finish(surface, spheres, &upper, tree.coverage().get(1).is_some())
}

/// The spheres within `tolerance` of `surface`: the leaves of a minimax tolerance tree,
/// each within it by construction where the node errors hold ([`bounds_hold`]).
/// Elsewhere every leaf is evaluated in full, and a leaf that reaches farther (near a
/// hole, a point can be outside without crossing the surface) is replaced by a tolerance
/// tree of the surface that meets it, taken as a shell: those spheres reach no farther
/// from that part of the surface, hence from the object, than the tolerance, and they
/// cover every point of the surface the leaf covered.
pub(super) fn mesh_tolerance(
    surface: &Surface,
    tolerance: f64,
    options: &SpherizeOptions,
) -> Result<PartFit, String> {
    let tree_options = options
        .tree
        .clone()
        .with_tolerance(Length::Absolute(tolerance));
    let tree = sphaera_spheretree::build(surface, &tree_options).map_err(|e| e.to_string())?;
    let deepest = tree.level_count().saturating_sub(1);
    let (leaves, bounds) = cut(&tree, deepest);
    let leaf_upper = certified_uppers(surface, &leaves, &bounds, Some(tolerance))?;
    let mut certified = tree.coverage().get(deepest).is_some();
    let mut spheres = Vec::with_capacity(leaves.len());
    let mut upper = Vec::with_capacity(leaves.len());
    for (leaf, u) in leaves.into_iter().zip(leaf_upper) {
        if u <= tolerance {
            spheres.push(leaf);
            upper.push(u);
            continue;
        }
        let Some(patch) = clip_to_sphere(surface.mesh(), leaf) else {
            // No surface meets the leaf: it covers nothing.
            continue;
        };
        let shell = Surface::shell(&patch).map_err(|e| e.to_string())?;
        let patch_tree =
            sphaera_spheretree::build(&shell, &tree_options).map_err(|e| e.to_string())?;
        let (patch_spheres, patch_bounds) = cut(&patch_tree, patch_tree.level_count() - 1);
        certified &= !patch_tree.coverage().is_empty();
        spheres.extend(patch_spheres);
        upper.extend(patch_bounds);
    }
    finish(surface, spheres, &upper, certified)
}

/// The spheres of the cut of `tree` at `level` (the level itself for a one-level tree,
/// the leaves at the deepest level of a tolerance tree) and their node errors.
fn cut(tree: &SphereTree, level: usize) -> (Vec<Sphere>, Vec<f64>) {
    tree.cut_at(level)
        .into_iter()
        .map(|i| (tree.nodes()[i].sphere, tree.nodes()[i].error))
        .unzip()
}

/// A certified upper bound on each sphere's protrusion: its node error where those
/// hold ([`bounds_hold`]), else the upper end of a full branch and bound (to a finer
/// interval for the spheres whose interval holds `tolerance`, so that a sphere within it
/// is found to be).
fn certified_uppers(
    surface: &Surface,
    spheres: &[Sphere],
    bounds: &[f64],
    tolerance: Option<f64>,
) -> Result<Vec<f64>, String> {
    if bounds_hold(surface) {
        return Ok(bounds.to_vec());
    }
    let options = EvaluationOptions::default().with_coverage_samples(1);
    let fit =
        sphaera_spheretree::evaluate_set(surface, spheres, &options).map_err(|e| e.to_string())?;
    let mut upper: Vec<f64> = fit.fits.iter().map(|f| f.upper).collect();
    if let Some(t) = tolerance {
        let open: Vec<usize> = (0..spheres.len())
            .filter(|&i| fit.fits[i].lower <= t && upper[i] > t)
            .collect();
        if !open.is_empty() {
            let again: Vec<Sphere> = open.iter().map(|&i| spheres[i]).collect();
            let fine = options.with_tolerance(Length::Absolute(1e-3 * t));
            let refit = sphaera_spheretree::evaluate_set(surface, &again, &fine)
                .map_err(|e| e.to_string())?;
            for (&i, f) in open.iter().zip(&refit.fits) {
                upper[i] = upper[i].min(f.upper);
            }
        }
    }
    Ok(upper)
}

/// The fit of `spheres` given certified per-sphere upper bounds: the worst protrusion
/// tightened by branch and bound, and the coverage of independent surface samples.
fn finish(
    surface: &Surface,
    spheres: Vec<Sphere>,
    upper: &[f64],
    certified: bool,
) -> Result<PartFit, String> {
    let fit = evaluate_set_bounded(surface, &spheres, upper, &EvaluationOptions::default())
        .map_err(|e| e.to_string())?;
    Ok(PartFit {
        spheres,
        protrusion: fit.worst_upper,
        covered: fit.coverage.samples - fit.coverage.uncovered,
        samples: fit.coverage.samples,
        certified,
    })
}

/// The part of `mesh` that meets `sphere` (grown by a relative 10⁻⁹ so that rounding
/// loses nothing inside it), in pieces: every triangle that meets it split at its
/// longest edge until its pieces are under a quarter of the radius long, the pieces
/// that meet the sphere kept. They hold every point of the surface inside the sphere.
/// `None` when nothing meets it.
fn clip_to_sphere(mesh: &sphaera_mesh::TriMesh, sphere: Sphere) -> Option<sphaera_mesh::TriMesh> {
    use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
    let reach = sphere.radius * (1.0 + 1e-9);
    let small = 0.25 * sphere.radius;
    let meets = |t: &Triangle| point_triangle_distance_squared(sphere.center, t) <= reach * reach;
    let mut positions: Vec<DVec3> = Vec::new();
    let mut stack: Vec<Triangle> = mesh.triangle_iter().filter(|t| meets(t)).collect();
    while let Some(t) = stack.pop() {
        let [a, b, c] = [t.a, t.b, t.c];
        let edges = [(a, b, c), (b, c, a), (c, a, b)];
        let (p, q, r) = edges.into_iter().max_by(|x, y| {
            x.0.distance_squared(x.1)
                .total_cmp(&y.0.distance_squared(y.1))
        })?;
        if p.distance(q) <= small {
            positions.extend([a, b, c]);
            continue;
        }
        let m = 0.5 * (p + q);
        for half in [Triangle::new(p, m, r), Triangle::new(m, q, r)] {
            if meets(&half) {
                stack.push(half);
            }
        }
    }
    let triangles: Vec<[u32; 3]> = (0..u32::try_from(positions.len() / 3).ok()?)
        .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    if triangles.is_empty() {
        return None;
    }
    sphaera_mesh::TriMesh::new(positions, triangles).ok()
}
