//! Deformation support: replayed radii and inflated radii keep both error-sphere
//! invariants for the deformed input, in refined states too.

mod common;

use common::{SLACK, original_samples, shape, worst_containment, worst_coverage};
use proptest::prelude::*;
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_simplify::{Hierarchy, Simplified, SimplifyError, SimplifyOptions};

/// A smooth deformation of amplitude `amplitude`, different per `seed`.
fn deform(p: DVec3, amplitude: f64, seed: u64) -> DVec3 {
    let k = 1.0 + (seed % 5) as f64;
    p + amplitude
        * DVec3::new(
            (k * p.y).sin(),
            (k * p.z + 1.0).cos(),
            (k * p.x).sin() * (p.y).cos(),
        )
}

/// Checks both invariants between `input` and `out` (whose positions are replaced by
/// `positions` through the original vertex map).
fn check(input: &TriMesh, mut out: Simplified, positions: &[DVec3], seed: u64) {
    let moved: Vec<DVec3> = out
        .original_vertex
        .iter()
        .map(|&i| positions[i as usize])
        .collect();
    out.mesh = TriMesh::new(moved, out.mesh.triangles().to_vec()).unwrap();
    let xs = original_samples(input, 300, seed);
    let cover = worst_coverage(&out, &xs);
    assert!(cover <= SLACK, "invariant (A) fails by {cover}");
    let contain = worst_containment(&out, input, 4);
    assert!(contain <= SLACK, "invariant (B) fails by {contain}");
}

/// Random splits of a refinement, returning the refined mesh.
fn refined(h: &Hierarchy, picks: &[u32]) -> Simplified {
    let mut r = h.refinement();
    for pick in picks {
        let splittable: Vec<u32> = (0..h.vertex_count() as u32)
            .filter(|&v| r.can_split(v))
            .collect();
        if splittable.is_empty() {
            break;
        }
        r.split_vertex(splittable[*pick as usize % splittable.len()])
            .unwrap();
    }
    r.to_simplified()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(24), ..ProptestConfig::default() })]

    #[test]
    fn replayed_radii_hold_for_the_deformed_mesh(
        kind in 0u8..3,
        resolution in 4usize..9,
        amplitude in 0.0f64..0.4,
        picks in prop::collection::vec(any::<u32>(), 0..10),
        seed in 0u64..1000,
    ) {
        let mesh = shape(kind, resolution);
        let h = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
        let moved: Vec<DVec3> = mesh.positions().iter().map(|&p| deform(p, amplitude, seed)).collect();
        let frame = h.replay(&moved).unwrap();
        let deformed = TriMesh::new(moved.clone(), mesh.triangles().to_vec()).unwrap();
        check(&deformed, frame.base(), &moved, seed);
        check(&deformed, refined(&frame, &picks), &moved, seed);
    }

    #[test]
    fn inflated_radii_hold_for_any_motion_within_the_bound(
        kind in 0u8..3,
        resolution in 4usize..9,
        amplitude in 0.0f64..0.2,
        picks in prop::collection::vec(any::<u32>(), 0..10),
        seed in 0u64..1000,
    ) {
        let mesh = shape(kind, resolution);
        let h = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
        let moved: Vec<DVec3> = mesh.positions().iter().map(|&p| deform(p, amplitude, seed)).collect();
        let displacement: Vec<f64> = mesh.positions().iter().zip(&moved).map(|(a, b)| (*a - *b).length()).collect();
        let inflated = h.inflate(&displacement).unwrap();
        let deformed = TriMesh::new(moved.clone(), mesh.triangles().to_vec()).unwrap();
        check(&deformed, inflated.base(), &moved, seed);
        check(&deformed, refined(&inflated, &picks), &moved, seed);
    }
}

#[test]
fn replay_with_the_same_positions_is_valid_and_close_to_the_build() {
    // Not identical: the replay may take the simple map where it is cheaper, which
    // changes later radii either way.
    let mesh = shapes::torus(1.0, 0.3, 14).unwrap();
    let h = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let same = h.replay(mesh.positions()).unwrap();
    check(&mesh, same.base(), mesh.positions(), 7);
    let (a, b) = (h.base().error_bound, same.base().error_bound);
    assert!(b <= 1.5 * a && a <= 1.5 * b, "build {a}, replay {b}");
}

#[test]
fn zero_displacement_changes_nothing() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let h = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let same = h.inflate(&vec![0.0; mesh.vertex_count()]).unwrap();
    assert_eq!(same.base(), h.base());
}

#[test]
fn bad_deformation_input_is_an_error() {
    let mesh = shapes::sphere(1.0, 6).unwrap();
    let h = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let n = mesh.vertex_count();
    assert!(matches!(
        h.replay(&mesh.positions()[1..]),
        Err(SimplifyError::LengthMismatch {
            name: "positions",
            ..
        })
    ));
    let mut nan = mesh.positions().to_vec();
    nan[3].y = f64::NAN;
    assert!(matches!(h.replay(&nan), Err(SimplifyError::Mesh(_))));
    assert!(matches!(
        h.inflate(&vec![0.1; n + 1]),
        Err(SimplifyError::LengthMismatch {
            name: "displacement",
            ..
        })
    ));
    let mut bad = vec![0.1; n];
    bad[2] = -1.0;
    assert!(matches!(
        h.inflate(&bad),
        Err(SimplifyError::InvalidVertexValue { index: 2, .. })
    ));
    bad[2] = f64::NAN;
    assert!(matches!(
        h.inflate(&bad),
        Err(SimplifyError::InvalidVertexValue { index: 2, .. })
    ));
}

#[test]
fn deformation_of_an_optimal_placement_hierarchy_is_a_clear_error() {
    let mesh = shapes::sphere(1.0, 6).unwrap();
    let h = Hierarchy::build(
        &mesh,
        &SimplifyOptions::default().with_placement(sphaera_simplify::Placement::Optimal),
    )
    .unwrap();
    let err = h.replay(mesh.positions()).unwrap_err();
    assert!(matches!(
        err,
        SimplifyError::NeedsSubsetPlacement {
            operation: "replay"
        }
    ));
    assert!(err.to_string().contains("subset placement"));
    let err = h.inflate(&vec![0.0; mesh.vertex_count()]).unwrap_err();
    assert!(matches!(
        err,
        SimplifyError::NeedsSubsetPlacement {
            operation: "inflate"
        }
    ));
}
