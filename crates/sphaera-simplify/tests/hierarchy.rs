//! The progressive hierarchy: its base and levels agree with the simplifier, selective
//! refinement keeps the reported triangle changes in sync with the real state, reset
//! restores the base, and both error-sphere invariants hold in refined states.

// Exact values are expected here (copied radii).
#![allow(clippy::float_cmp)]

mod common;

use std::collections::BTreeSet;

use common::{SLACK, original_samples, shape, worst_containment, worst_coverage};
use proptest::prelude::*;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_simplify::{
    Hierarchy, Order, Placement, Refinement, Simplified, SimplifyError, SimplifyOptions, simplify,
};

fn check_invariants(original: &TriMesh, out: &Simplified, seed: u64) {
    let xs = original_samples(original, 300, seed);
    let cover = worst_coverage(out, &xs);
    assert!(cover <= SLACK, "invariant (A) fails by {cover}");
    let contain = worst_containment(out, original, 4);
    assert!(contain <= SLACK, "invariant (B) fails by {contain}");
}

/// Checks the reported changes of the undone collapses against the live sets before and
/// after, and the radius changes against the affected lists.
fn check_split_report(
    hierarchy: &Hierarchy,
    before: &Refinement<'_>,
    after: &Refinement<'_>,
    undone: &[u32],
    live: &mut BTreeSet<u32>,
) {
    for &c in undone {
        for &t in hierarchy.triangles_removed_by_split(c) {
            assert!(
                live.remove(&t),
                "collapse {c}: removed triangle {t} was not live"
            );
        }
        for &t in hierarchy.triangles_revived_by_split(c) {
            assert!(
                !live.contains(&t),
                "collapse {c}: revived triangle {t} was live"
            );
        }
        live.extend(hierarchy.triangles_added_by_split(c));
    }
    let actual: BTreeSet<u32> = after.live_triangles().collect();
    assert_eq!(*live, actual, "reported changes out of sync with the state");
    // Every live triangle whose corners or radii changed is reported.
    let reported: BTreeSet<u32> = undone
        .iter()
        .flat_map(|&c| {
            hierarchy
                .triangles_added_by_split(c)
                .iter()
                .chain(hierarchy.triangles_affected_by_split(c))
                .copied()
        })
        .collect();
    for t in actual {
        let corners = after.corners(t).unwrap();
        let changed = before.corners(t) != Some(corners)
            || corners
                .iter()
                .any(|&x| before.radius(x) != after.radius(x) || !before.is_present(x));
        if changed {
            assert!(
                reported.contains(&t),
                "triangle {t} changed but was not reported"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(48), ..ProptestConfig::default() })]

    #[test]
    fn base_and_levels_match_the_simplifier(
        kind in 0u8..4,
        resolution in 4usize..10,
        ratio in 0.05f64..0.9,
        lock_boundary: bool,
        batched: bool,
    ) {
        let mesh = shape(kind, resolution);
        let order = if batched { Order::Batched } else { Order::Strict };
        let options = SimplifyOptions::default().with_lock_boundary(lock_boundary).with_order(order);
        let hierarchy = Hierarchy::build(&mesh, &options).unwrap();
        prop_assert_eq!(hierarchy.base(), simplify(&mesh, &options).unwrap());
        let n = (ratio * mesh.triangle_count() as f64) as usize;
        let level = hierarchy.level_by_triangles(n);
        let direct = simplify(&mesh, &options.with_target_triangles(n)).unwrap();
        prop_assert_eq!(&level.mesh, &direct.mesh);
        prop_assert_eq!(&level.vertex_radii, &direct.vertex_radii);
        prop_assert_eq!(level.error_bound, direct.error_bound);
    }

    #[test]
    fn selective_refinement_stays_in_sync_and_valid(
        kind in 0u8..4,
        resolution in 4usize..10,
        picks in prop::collection::vec(any::<u32>(), 1..24),
        optimal: bool,
        seed in 0u64..1000,
    ) {
        let mesh = shape(kind, resolution);
        let placement = if optimal { Placement::Optimal } else { Placement::Subset };
        let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default().with_placement(placement)).unwrap();
        let mut refinement = hierarchy.refinement();
        let base_count = refinement.live_triangle_count();
        let mut live: BTreeSet<u32> = refinement.live_triangles().collect();
        prop_assert_eq!(live.len(), base_count);
        for (i, pick) in picks.iter().enumerate() {
            let splittable: Vec<u32> = (0..hierarchy.vertex_count() as u32)
                .filter(|&v| refinement.can_split(v))
                .collect();
            if splittable.is_empty() {
                break;
            }
            let v = splittable[*pick as usize % splittable.len()];
            let before = refinement.clone();
            let undone = refinement.split_vertex(v).unwrap();
            prop_assert!(!undone.is_empty());
            // Topological order: decreasing build index.
            prop_assert!(undone.windows(2).all(|w| w[0] > w[1]));
            prop_assert!(refinement.radius(v) <= before.radius(v));
            check_split_report(&hierarchy, &before, &refinement, &undone, &mut live);
            prop_assert_eq!(refinement.live_triangle_count(), live.len());
            if i % 8 == 7 {
                check_invariants(&mesh, &refinement.to_simplified(), seed + i as u64);
            }
        }
        check_invariants(&mesh, &refinement.to_simplified(), seed);
        refinement.reset();
        prop_assert_eq!(refinement.undone_count(), 0);
        prop_assert_eq!(refinement.to_simplified(), hierarchy.base());
    }

    #[test]
    fn level_by_error_meets_the_bound(
        kind in 0u8..4,
        resolution in 4usize..10,
        fraction in 0.0f64..1.0,
        seed in 0u64..1000,
    ) {
        let mesh = shape(kind, resolution);
        let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
        let base = hierarchy.base();
        let bound = fraction * base.error_bound;
        let level = hierarchy.level_by_error(bound);
        prop_assert!(level.error_bound <= bound);
        prop_assert!(level.mesh.triangle_count() >= base.mesh.triangle_count());
        check_invariants(&mesh, &level, seed);
    }
}

#[test]
fn vertex_errors_are_the_papers_two_values() {
    let mesh = shapes::sphere(1.0, 10).unwrap();
    let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let mut seen = 0;
    for v in 0..hierarchy.vertex_count() as u32 {
        let Some(c) = hierarchy.collapse_of(v) else {
            assert!(hierarchy.vertex_errors(v).is_none());
            continue;
        };
        seen += 1;
        let parent = hierarchy.parent(v).unwrap();
        assert_eq!(hierarchy.removed_vertex(c), Some(v));
        assert_eq!(hierarchy.kept_vertex(c), Some(parent));
        assert!(hierarchy.splits_with(parent).contains(&c));
        let (own, parent_before) = hierarchy.vertex_errors(v).unwrap();
        // Radii only grow along the sequence.
        assert!(parent_before <= hierarchy.radius_after(c).unwrap());
        assert!(own >= 0.0);
        for &d in hierarchy.split_before(c) {
            assert!(d > c, "split-before must point to later collapses");
        }
    }
    assert_eq!(seen, hierarchy.collapse_count());
}

#[test]
fn splitting_a_removed_or_unknown_vertex_is_an_error() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let mut refinement = hierarchy.refinement();
    let removed = (0..hierarchy.vertex_count() as u32)
        .find(|&v| !refinement.is_present(v))
        .unwrap();
    assert!(matches!(
        refinement.split_vertex(removed),
        Err(SimplifyError::VertexNotPresent { vertex }) if vertex == removed
    ));
    assert!(matches!(
        refinement.split_vertex(u32::MAX),
        Err(SimplifyError::VertexNotPresent { .. })
    ));
    // A present vertex with nothing to split returns no steps.
    let leaf = (0..hierarchy.vertex_count() as u32)
        .find(|&v| refinement.is_present(v) && !refinement.can_split(v));
    if let Some(leaf) = leaf {
        assert!(refinement.split_vertex(leaf).unwrap().is_empty());
    }
}

#[test]
fn refining_everything_gives_back_the_input() {
    let mesh = shapes::torus(1.0, 0.4, 12).unwrap();
    let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
    let finest = hierarchy.level_by_error(0.0);
    assert_eq!(finest.mesh.triangle_count(), mesh.triangle_count());
    assert_eq!(finest.error_bound, 0.0);
    let memory = hierarchy.memory();
    assert!(memory.bytes_per_triangle(memory.fixed_tables) > 0.0);
}

/// A case proptest found on a fresh CI run (2026-11-21): on the open height-field grid
/// with optimal placement, three splits left a refined state where invariant (A) failed by
/// 8.8e-4. The cause: a full-edge collapse moves the kept vertex, so its radius reads the
/// kept vertex's one-ring too, and the recorder did not make it depend on the collapses
/// into those neighbours; undoing one of them left the moved vertex's radius stale.
#[test]
fn refined_open_grid_with_optimal_placement_keeps_invariant_a() {
    let mesh = shape(3, 6);
    let hierarchy = Hierarchy::build(
        &mesh,
        &SimplifyOptions::default().with_placement(Placement::Optimal),
    )
    .unwrap();
    let mut refinement = hierarchy.refinement();
    for pick in [386_499_168_u32, 1_059_914_931, 147_362_565] {
        let splittable: Vec<u32> = (0..hierarchy.vertex_count() as u32)
            .filter(|&v| refinement.can_split(v))
            .collect();
        let v = splittable[pick as usize % splittable.len()];
        refinement.split_vertex(v).unwrap();
    }
    check_invariants(&mesh, &refinement.to_simplified(), 0);
}
