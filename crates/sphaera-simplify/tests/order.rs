//! The two collapse orders: the batched one gives the same answer on any thread count,
//! `Order::Auto` picks by size, and both stay tight on a large mesh.

use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_simplify::{Hierarchy, Order, SimplifyOptions, simplify};

/// A bumpy sphere of about 20k triangles: enough for batches of many stale vertices.
fn bumpy_sphere() -> TriMesh {
    let sphere = shapes::sphere(1.0, 100).unwrap();
    let positions: Vec<DVec3> = sphere
        .positions()
        .iter()
        .map(|&p| {
            p * (1.0 + 0.05 * (7.0 * p.x).sin() * (5.0 * p.y).cos() + 0.02 * (13.0 * p.z).sin())
        })
        .collect();
    TriMesh::new(positions, sphere.triangles().to_vec()).unwrap()
}

#[test]
fn batched_order_does_not_depend_on_the_thread_count() {
    let mesh = bumpy_sphere();
    let options = SimplifyOptions::default()
        .with_target_ratio(0.1)
        .with_order(Order::Batched);
    let here = simplify(&mesh, &options).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| simplify(&mesh, &options).unwrap());
    let three = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap()
        .install(|| simplify(&mesh, &options).unwrap());
    assert_eq!(here, one);
    assert_eq!(here, three);
    // And the hierarchy records the same run.
    let hierarchy = Hierarchy::build(&mesh, &options).unwrap();
    assert_eq!(hierarchy.base(), here);
}

#[test]
fn auto_is_strict_below_the_threshold_and_batched_above() {
    let small = shapes::torus(1.0, 0.3, 24).unwrap();
    assert!(small.vertex_count() < Order::STRICT_BELOW);
    let options = SimplifyOptions::default().with_target_ratio(0.2);
    assert_eq!(
        simplify(&small, &options).unwrap(),
        simplify(&small, &options.clone().with_order(Order::Strict)).unwrap()
    );
    let large = shapes::sphere(1.0, 260).unwrap();
    assert!(large.vertex_count() >= Order::STRICT_BELOW);
    assert_eq!(
        simplify(&large, &options).unwrap(),
        simplify(&large, &options.with_order(Order::Batched)).unwrap()
    );
}

#[test]
fn both_orders_reach_the_target_with_a_comparable_bound() {
    let mesh = bumpy_sphere();
    let options = SimplifyOptions::default().with_target_ratio(0.05);
    let strict = simplify(&mesh, &options.clone().with_order(Order::Strict)).unwrap();
    let batched = simplify(&mesh, &options.with_order(Order::Batched)).unwrap();
    assert_eq!(strict.mesh.triangle_count(), batched.mesh.triangle_count());
    // The batched order drifts from the greedy one, not far.
    assert!(
        batched.error_bound <= 1.5 * strict.error_bound,
        "batched {} against strict {}",
        batched.error_bound,
        strict.error_bound
    );
    let measured = sphaera_tests::reference_hausdorff(&mesh, &batched.mesh, 5000, 3).symmetric();
    assert!(measured <= batched.error_bound);
    assert!(
        batched.error_bound <= 2.0 * measured,
        "{} {measured}",
        batched.error_bound
    );
}

/// FNV-1a over the output's positions, triangles and radii (bit patterns).
fn digest(out: &sphaera_simplify::Simplified) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for byte in x.to_le_bytes() {
            h = (h ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in out.mesh.positions() {
        for c in p.to_array() {
            eat(c.to_bits());
        }
    }
    for t in out.mesh.triangles() {
        for &i in t {
            eat(u64::from(i));
        }
    }
    for r in &out.vertex_radii {
        eat(r.to_bits());
    }
    h
}

#[test]
fn batched_result_is_the_same_with_and_without_the_parallel_feature() {
    // `cargo xtask test` runs this crate's tests with and without `parallel`; both must
    // give the recorded digest.
    let out = simplify(
        &bumpy_sphere(),
        &SimplifyOptions::default()
            .with_target_ratio(0.1)
            .with_order(Order::Batched),
    )
    .unwrap();
    assert_eq!(
        digest(&out),
        0x0e04_e11f_500b_e291,
        "digest {:#x}",
        digest(&out)
    );
}

#[test]
fn batched_order_stops_at_the_error_bound_and_respects_it() {
    let mesh = bumpy_sphere();
    let bound = 0.002 * mesh.bounding_box_diagonal();
    let options = SimplifyOptions::default().with_max_error(sphaera_mesh::Length::Absolute(bound));
    let batched = simplify(&mesh, &options.clone().with_order(Order::Batched)).unwrap();
    let strict = simplify(&mesh, &options.with_order(Order::Strict)).unwrap();
    assert!(batched.error_bound <= bound);
    // It goes about as far as the greedy order (no candidate is left out by a stale key).
    let (b, s) = (batched.mesh.triangle_count(), strict.mesh.triangle_count());
    assert!(b * 10 <= s * 11, "batched kept {b} triangles, strict {s}");
}
