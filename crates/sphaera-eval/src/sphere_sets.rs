//! Flat sets of exactly `N` spheres around a mesh, and growing another library's set until
//! it covers the surface: the measured calls of the `spheres_vs_count` experiment and the
//! `spheres_vs_morphit` bench, so that both time exactly the same thing.
//!
//! - [`one_level_minimax`]: Sphaera's answer to "N spheres around this mesh", a one-level
//!   minimax sphere-tree of branching factor `N` on `Surface::solid_or_shell`, from the
//!   loaded mesh to the spheres (the surface's preparation included);
//! - [`grow_to_cover`]: the collision buffer a planner adds to a set that does not cover
//!   the surface (morphit-rs's, which packs the volume): every radius grown by the same
//!   amount, the largest gap measured on dense samples, then the coverage of every point
//!   of every triangle certified by `sphaera::spheretree::cover::certify_coverage`, which
//!   grows single spheres further where the samples missed a gap.

use anyhow::{Context, Result, bail};
use sphaera::mesh::{Sphere, Surface, TriMesh};
use sphaera::spheretree::{
    CoverageCertificate, EvaluationOptions, SphereTreeOptions, build, cover::certify_coverage,
    evaluate::coverage,
};

/// Sphaera's one-level tree of exactly `N` spheres.
pub struct OneLevel {
    /// The surface it was built on (a solid when the mesh has an inside, else a shell).
    pub surface: Surface,
    /// The spheres of level 1.
    pub spheres: Vec<Sphere>,
    /// Each sphere's own certified error bound (`TreeNode::error`), in the same order.
    pub node_errors: Vec<f64>,
}

/// Sphaera's `n` spheres around `mesh`: `sphaera::spheretree::build(&Surface::solid_or_shell(mesh),
/// &SphereTreeOptions::default().with_depth(1).with_branch(n))`, its level 1.
///
/// # Errors
///
/// When the surface cannot be prepared or the tree cannot be built (`n` of 0 or above
/// the library's `MAX_BRANCH`).
pub fn one_level_minimax(mesh: &TriMesh, n: usize) -> Result<OneLevel> {
    let surface = Surface::solid_or_shell(mesh).context("preparing the surface")?;
    let options = SphereTreeOptions::default().with_depth(1).with_branch(n);
    let tree = build(&surface, &options).with_context(|| format!("a one-level tree of {n}"))?;
    let level = tree.level(1);
    Ok(OneLevel {
        spheres: level.iter().map(|node| node.sphere).collect(),
        node_errors: level.iter().map(|node| node.error).collect(),
        surface,
    })
}

/// Surface samples of [`grow_to_cover`]'s uniform growth: ten times the evaluator's
/// coverage samples, with another seed, so that the evaluator's coverage figure is
/// measured on samples the growth never saw.
pub const GROWTH_SAMPLES: usize = 1_000_000;

/// Their seed (the evaluator's default is `0x5EA1`).
pub const GROWTH_SEED: u64 = 36;

/// A set grown until it covers the surface.
pub struct Grown {
    /// The grown spheres (same centres, larger radii).
    pub spheres: Vec<Sphere>,
    /// The growth of every radius: the largest distance from a sample (of
    /// [`GROWTH_SAMPLES`] random surface points and every vertex) outside every sphere to
    /// the nearest sphere's surface.
    pub uniform: f64,
    /// What `certify_coverage` then did: spheres grown further, and the largest further
    /// growth.
    pub certificate: CoverageCertificate,
}

/// `spheres` grown to cover every point of `mesh`'s triangles: every radius by the same
/// amount (the largest gap on dense samples and the vertices), then certified at
/// `resolution` by `certify_coverage`, which grows a sphere further wherever a piece of a
/// triangle is still outside every sphere.
///
/// # Errors
///
/// When `spheres` is empty or invalid, or the mesh cannot be sampled.
pub fn grow_to_cover(mesh: &TriMesh, spheres: &[Sphere], resolution: f64) -> Result<Grown> {
    if spheres.is_empty() {
        bail!("no spheres to grow");
    }
    let options = EvaluationOptions::default()
        .with_coverage_samples(GROWTH_SAMPLES)
        .with_seed(GROWTH_SEED);
    let sampled = coverage(mesh, spheres, &options).context("measuring the gaps")?;
    let at_vertices = mesh
        .positions()
        .iter()
        .map(|&p| {
            spheres
                .iter()
                .map(|s| p.distance(s.center) - s.radius)
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let uniform = sampled.largest_gap.max(at_vertices);
    let mut grown: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(s.center, s.radius + uniform))
        .collect();
    let (certificate, _) = certify_coverage(mesh, &mut grown, resolution);
    Ok(Grown {
        spheres: grown,
        uniform,
        certificate,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera::mesh::{DVec3, shapes};
    use sphaera::spheretree::evaluate_set;

    #[test]
    fn exactly_n_spheres_that_cover() -> Result<()> {
        let mesh = shapes::capsule(0.5, 2.0, 12)?;
        let set = one_level_minimax(&mesh, 5)?;
        assert_eq!(set.spheres.len(), 5);
        assert_eq!(set.node_errors.len(), 5);
        let fit = evaluate_set(&set.surface, &set.spheres, &EvaluationOptions::default())?;
        assert_eq!(fit.coverage.uncovered, 0);
        Ok(())
    }

    #[test]
    fn a_set_inside_grows_to_cover_the_surface() -> Result<()> {
        let mesh = shapes::cube(2.0, 2)?;
        // Two balls inside the cube [-1, 1]³: most of its surface is outside them.
        let inside = [
            Sphere::new(DVec3::new(-0.5, 0.0, 0.0), 0.5),
            Sphere::new(DVec3::new(0.5, 0.0, 0.0), 0.5),
        ];
        let grown = grow_to_cover(&mesh, &inside, 1e-3)?;
        // The corners are √(0.25 + 2) − 0.5 from the balls' surfaces: a vertex sets it.
        let corner = (0.25_f64 + 2.0).sqrt() - 0.5;
        assert!((grown.uniform - corner).abs() < 1e-12, "{}", grown.uniform);
        let options = EvaluationOptions::default().with_coverage_samples(20_000);
        let fit = evaluate_set(&Surface::new(&mesh)?, &grown.spheres, &options)?;
        assert_eq!(fit.coverage.uncovered, 0);
        Ok(())
    }
}
