//! The two error-sphere invariants, checked by brute force on procedural meshes.

// Exact values are expected here (a copied maximum, an untouched zero).
#![allow(clippy::float_cmp)]

mod common;

use common::{SLACK, grid, original_samples, shape, worst_containment, worst_coverage};
use proptest::prelude::*;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_simplify::{Order, Placement, Simplified, SimplifyOptions, simplify};

fn check_both(original: &TriMesh, out: &Simplified, samples: usize, seed: u64) {
    let xs = original_samples(original, samples, seed);
    let cover = worst_coverage(out, &xs);
    assert!(
        cover <= SLACK,
        "invariant (A) fails: an original point is {cover} outside"
    );
    let contain = worst_containment(out, original, 4);
    assert!(
        contain <= SLACK,
        "invariant (B) fails: a simplified point is {contain} beyond its radius"
    );
    let max = out.vertex_radii.iter().fold(0.0_f64, |m, &r| m.max(r));
    assert_eq!(out.error_bound, max);
    let measured = sphaera_tests::reference_hausdorff(original, &out.mesh, 2000, seed).symmetric();
    assert!(
        measured <= out.error_bound + SLACK,
        "bound {} below measured {measured}",
        out.error_bound
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(96), ..ProptestConfig::default() })]

    #[test]
    fn both_invariants_hold_on_small_shapes(
        kind in 0u8..4,
        resolution in 4usize..12,
        ratio in 0.05f64..0.9,
        lock_boundary: bool,
        optimal: bool,
        batched: bool,
        seed in 0u64..1000,
    ) {
        let mesh = shape(kind, resolution);
        let placement = if optimal { Placement::Optimal } else { Placement::Subset };
        let order = if batched { Order::Batched } else { Order::Strict };
        let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(ratio).with_lock_boundary(lock_boundary).with_placement(placement).with_order(order))
            .unwrap();
        check_both(&mesh, &out, 300, seed);
    }
}

#[test]
fn sphere_to_ten_percent_keeps_both_invariants() {
    let mesh = shapes::sphere(1.0, 16).unwrap();
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.1)).unwrap();
    assert!(out.mesh.triangle_count() <= mesh.triangle_count() / 10 + 1);
    assert!(out.error_bound > 0.0);
    check_both(&mesh, &out, 2000, 7);
}

#[test]
fn torus_keeps_both_invariants() {
    let mesh = shapes::torus(1.0, 0.3, 16).unwrap();
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.2)).unwrap();
    check_both(&mesh, &out, 1000, 3);
}

#[test]
fn bumpy_open_grid_keeps_both_invariants_and_its_boundary() {
    let mesh = grid(10, |x, y| 0.1 * (5.0 * x).sin() * (4.0 * y).sin());
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.1)).unwrap();
    assert_eq!(out.locked.boundary, 40);
    check_both(&mesh, &out, 1000, 11);
}

#[test]
fn open_grid_with_free_boundary_keeps_both_invariants() {
    let mesh = grid(10, |x, y| 0.1 * (5.0 * x).sin() * (4.0 * y).sin());
    let out = simplify(
        &mesh,
        &SimplifyOptions::default()
            .with_target_ratio(0.05)
            .with_lock_boundary(false),
    )
    .unwrap();
    assert_eq!(out.locked.boundary, 0);
    assert!(out.mesh.triangle_count() <= 11);
    check_both(&mesh, &out, 1000, 12);
}
