//! The query sets shared by experiments and benches, so both measure the same points.
//!
//! In 2D (point inclusion: the `hal` experiment, the `hal2_vs_geos` bench and test), two
//! sets of seeded points ([`SplitMix64`]): [`box_points`], uniform in the outline's
//! bounding box, and [`near_outline_points`], within an edge's length of the outline.
//!
//! In 3D, the closest-point sets of the `sweep_throughput` experiment and the
//! `sweep_vs_parry` bench:
//! Three sets, each of `n` points and seeded (the same mesh and `n` give the same points):
//! - `uniform`: points uniform in the bounding box scaled 1.5× about its centre;
//! - `near`: points within 1 % of the diagonal of the surface (a uniform surface sample
//!   moved along a random direction by a random fraction of that distance);
//! - `path`: a smooth closed curve around the centre (a tilted, wavy ellipse at 0.9× the
//!   half-extents) walked in steps of `1 / PATH_STEPS_PER_LOOP` of a turn, i.e. about
//!   0.15 % of the diagonal per step: coherent queries. The step does not depend on `n`
//!   (fewer points walk part of the loop).

use anyhow::{Context, Result};
use sphaera::hal::Polyline2;
use sphaera::mesh::glam::DVec2;
use sphaera::mesh::{DVec3, TriMesh, sampling};
use sphaera_tests::random::{Lcg64, SplitMix64};

/// Steps of the `path` set per full turn of its curve.
pub const PATH_STEPS_PER_LOOP: usize = 2_000;

/// The names of the query sets, in the order [`query_sets`] returns them.
pub const SET_NAMES: [&str; 3] = ["uniform", "near", "path"];

/// The three query sets of the module docs, `n` points each, named as in [`SET_NAMES`].
///
/// # Errors
///
/// If the mesh has no area (no surface to sample the `near` set from).
pub fn query_sets(mesh: &TriMesh, n: usize) -> Result<Vec<(&'static str, Vec<DVec3>)>> {
    let bounds = mesh.bounding_box();
    let center = 0.5 * (bounds.min + bounds.max);
    let half = 0.5 * (bounds.max - bounds.min);
    let diagonal = mesh.bounding_box_diagonal();
    let mut rng = Lcg64::new(7);
    let uniform = (0..n)
        .map(|_| {
            let u = rng.unit_cube();
            center + 1.5 * half * (2.0 * u - DVec3::ONE)
        })
        .collect();
    let samples = sampling::random(mesh, n, 11).context("the mesh has no area to sample")?;
    let near = samples
        .iter()
        .map(|s| {
            let d = rng.unit_cube() * 2.0 - DVec3::ONE;
            s.position + d.normalize_or_zero() * (0.01 * diagonal * rng.unit())
        })
        .collect();
    let path = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / PATH_STEPS_PER_LOOP as f64;
            center + 0.9 * half * DVec3::new(a.cos(), a.sin(), 0.5 * (3.0 * a).sin())
        })
        .collect();
    Ok(vec![
        (SET_NAMES[0], uniform),
        (SET_NAMES[1], near),
        (SET_NAMES[2], path),
    ])
}

/// `n` points uniform in the outline's bounding box, from [`SplitMix64`] seeded with
/// `seed`: the same outline, `n` and seed give the same points.
#[must_use]
pub fn box_points(outline: &Polyline2, n: usize, seed: u64) -> Vec<DVec2> {
    let (lo, hi) = outline.bounds();
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| DVec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y)))
        .collect()
}

/// `n` points near the outline, where point inclusion is hardest: each on a random edge
/// (uniform over the edges, so dense where the vertices are), moved across it by up to
/// the edge's length either way; seeded as [`box_points`]. Empty for an outline without
/// edges.
#[must_use]
pub fn near_outline_points(outline: &Polyline2, n: usize, seed: u64) -> Vec<DVec2> {
    let edges = outline.edge_count();
    if edges == 0 {
        return Vec::new();
    }
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            let k = ((rng.range(0.0, 1.0) * edges as f64) as usize).min(edges - 1);
            let (a, b) = outline.edge(k);
            let along = a + (b - a) * rng.range(0.0, 1.0);
            along + (b - a).perp() * rng.range(-1.0, 1.0)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::shapes;

    use super::*;

    #[test]
    fn query_sets_are_where_they_say() {
        let sphere = shapes::sphere(1.0, 16).unwrap();
        let diagonal = sphere.bounding_box_diagonal();
        let sets = query_sets(&sphere, 100).unwrap();
        let names: Vec<&str> = sets.iter().map(|(name, _)| *name).collect();
        assert_eq!(names, SET_NAMES);
        for (name, points) in &sets {
            assert_eq!(points.len(), 100, "{name}");
        }
        // Uniform: inside the 1.5× box. Near: within 1 % of the diagonal of the sphere
        // (whose tessellation is within a few % of the unit sphere).
        assert!(sets[0].1.iter().all(|p| p.abs().max_element() <= 1.5));
        assert!(
            sets[1]
                .1
                .iter()
                .all(|p| (p.length() - 1.0).abs() <= 0.01 * diagonal + 0.05)
        );
        // Path: small steps, independent of `n`.
        let step = sets[2].1.windows(2).map(|w| w[0].distance(w[1]));
        assert!(step.fold(0.0, f64::max) < 0.01 * diagonal);
        let fewer = query_sets(&sphere, 10).unwrap();
        assert_eq!(fewer[2].1[..], sets[2].1[..10]);
        // Deterministic.
        assert_eq!(query_sets(&sphere, 100).unwrap(), sets);
    }

    #[test]
    fn outline_points_are_where_they_say() {
        let square = Polyline2::polygon(vec![
            DVec2::ZERO,
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 4.0),
            DVec2::new(0.0, 4.0),
        ])
        .unwrap();
        let spread = box_points(&square, 200, 3);
        assert!(
            spread
                .iter()
                .all(|p| p.cmpge(DVec2::ZERO).all() && p.cmple(DVec2::splat(4.0)).all())
        );
        assert_eq!(spread, box_points(&square, 200, 3));
        let near = near_outline_points(&square, 200, 3);
        // Within an edge's length (4) of the outline: of its nearest side's line.
        assert!(near.iter().all(|p| {
            let to_side =
                p.x.abs()
                    .min((p.x - 4.0).abs())
                    .min(p.y.abs())
                    .min((p.y - 4.0).abs());
            to_side <= 4.0
        }));
        assert_ne!(near, spread);
    }
}
