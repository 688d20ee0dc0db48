//! Tree-against-tree traversal: exact against brute force with an unlimited budget, a
//! prefix level with a budget, deterministic order.

// Costs are sums of small integers and placed spheres the same arithmetic: exact.
#![allow(clippy::float_cmp)]

mod common;

use common::small_tree;
use std::sync::OnceLock;
use std::time::Duration;

use glam::{DAffine3, DQuat};
use proptest::prelude::*;
use sphaera_mesh::{DVec3, Sphere, shapes};
use sphaera_spheretree::collide::{
    Budget, Collision, CostModel, Similarity, TraversalStats, collide, overlaps,
};
use sphaera_spheretree::{SphereTree, SphereTreeError, TreeNode};
use sphaera_tests::SplitMix64;

/// Two small built trees: a capsule and a cube, depth 2, branch 4.
fn built() -> &'static (SphereTree, SphereTree) {
    static TREES: OnceLock<(SphereTree, SphereTree)> = OnceLock::new();
    TREES.get_or_init(|| {
        (
            small_tree(&shapes::capsule(0.5, 2.0, 10).unwrap()),
            small_tree(&shapes::cube(1.5, 2).unwrap()),
        )
    })
}

/// A random tree of up to `depth` levels below the root, with 0–3 children per node (so
/// leaves at every level), children near their parent.
fn synthetic(seed: u64, depth: usize, branch: usize) -> SphereTree {
    let mut rng = SplitMix64::new(seed);
    let root = TreeNode {
        sphere: Sphere::new(DVec3::ZERO, 1.0),
        error: 0.5,
        level: 0,
        parent: None,
        children: 0..0,
        region_samples: 0,
    };
    let mut levels = vec![vec![root]];
    // The index of the first node of the level being expanded.
    let mut first = 0;
    for level in 0..depth {
        let next_first = first + levels[level].len();
        let mut next = Vec::new();
        for (k, parent) in levels[level].iter_mut().enumerate() {
            let kids = rng.below(branch as u64 + 1) as usize;
            let start = (next_first + next.len()) as u32;
            let (pc, pr) = (parent.sphere.center, parent.sphere.radius);
            for _ in 0..kids {
                let r = pr * (0.3 + 0.4 * rng.unit());
                let offset = [0, 1, 2].map(|_| (rng.unit() - 0.5) * pr);
                let error = 0.5 * r * rng.unit();
                next.push(TreeNode {
                    sphere: Sphere::new(
                        DVec3::new(pc.x + offset[0], pc.y + offset[1], pc.z + offset[2]),
                        r,
                    ),
                    error,
                    level: level as u32 + 1,
                    parent: Some((first + k) as u32),
                    children: 0..0,
                    region_samples: 0,
                });
            }
            if kids > 0 {
                parent.children = start..start + kids as u32;
            }
        }
        if next.is_empty() {
            break;
        }
        first = next_first;
        levels.push(next);
    }
    SphereTree::from_levels(branch, levels).unwrap()
}

fn is_leaf(tree: &SphereTree, i: usize) -> bool {
    tree.nodes()[i].children.is_empty()
}

/// The ancestor of node `i` at `level`, or `i` itself when it is at or above `level`.
fn ancestor(tree: &SphereTree, mut i: usize, level: usize) -> usize {
    while tree.nodes()[i].level as usize > level {
        i = tree.nodes()[i].parent.unwrap() as usize;
    }
    i
}

/// The stand-ins of level `level`: its nodes, and the leaves above it.
fn stand_ins(tree: &SphereTree, level: usize) -> Vec<usize> {
    (0..tree.nodes().len())
        .filter(|&i| {
            let l = tree.nodes()[i].level as usize;
            l == level || (l < level && is_leaf(tree, i))
        })
        .collect()
}

/// Brute force: every pair of level-`level` stand-ins whose spheres overlap and whose
/// ancestors at every level above overlap too.
fn brute_force(
    a: &SphereTree,
    pa: &Similarity,
    b: &SphereTree,
    pb: &Similarity,
    level: usize,
) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for &x in &stand_ins(a, level) {
        for &y in &stand_ins(b, level) {
            let chain = (0..=level).all(|k| {
                let sa = pa.sphere(&a.nodes()[ancestor(a, x, k)].sphere);
                let sb = pb.sphere(&b.nodes()[ancestor(b, y, k)].sphere);
                sa.intersects(&sb)
            });
            if chain {
                pairs.push((x, y));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

fn pairs(c: &Collision) -> Vec<(usize, usize)> {
    c.contacts.iter().map(|c| (c.a, c.b)).collect()
}

fn deepest(tree: &SphereTree) -> usize {
    tree.level_count() - 1
}

/// Every contact is consistent: its spheres are the placed nodes, it overlaps, its
/// bound is the sum of the placed errors.
fn check_contacts(c: &Collision, a: &SphereTree, pa: &Similarity, b: &SphereTree, pb: &Similarity) {
    for contact in &c.contacts {
        assert_eq!(contact.sphere_a, pa.sphere(&a.nodes()[contact.a].sphere));
        assert_eq!(contact.sphere_b, pb.sphere(&b.nodes()[contact.b].sphere));
        assert!(contact.depth >= -1e-12);
        let bound =
            a.nodes()[contact.a].error * pa.scale() + b.nodes()[contact.b].error * pb.scale();
        assert!((contact.error_bound - bound).abs() <= 1e-12 * bound.abs().max(1.0));
    }
}

fn placement(axis: [f64; 3], angle: f64, t: [f64; 3], scale: f64) -> Similarity {
    let axis = DVec3::from_array(axis);
    let rotation = if axis.length() > 1e-3 {
        DQuat::from_axis_angle(axis.normalize(), angle)
    } else {
        DQuat::IDENTITY
    };
    Similarity::new(DAffine3::from_scale_rotation_translation(
        DVec3::splat(scale),
        rotation,
        DVec3::from_array(t),
    ))
    .unwrap()
}

fn coord() -> impl Strategy<Value = [f64; 3]> {
    [-1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    #[test]
    fn unlimited_equals_brute_force_on_built_trees(
        axis in coord(), angle in -3.2..3.2_f64, t in coord(), swap in any::<bool>(),
    ) {
        let (capsule, cube) = built();
        let (a, b) = if swap { (cube, capsule) } else { (capsule, cube) };
        let pa = Similarity::IDENTITY;
        let pb = placement(axis, angle, [t[0] * 2.0, t[1] * 2.0, t[2] * 2.0], 1.0);
        let c = collide(a, &pa, b, &pb, &Budget::Unlimited).unwrap();
        prop_assert!(c.completed);
        let expected = brute_force(a, &pa, b, &pb, deepest(a).max(deepest(b)));
        prop_assert_eq!(pairs(&c), expected.clone());
        prop_assert_eq!(overlaps(a, &pa, b, &pb), !expected.is_empty());
        check_contacts(&c, a, &pa, b, &pb);
    }

    #[test]
    fn unlimited_equals_brute_force_on_uneven_trees(
        seed_a in any::<u64>(), seed_b in any::<u64>(),
        axis in coord(), angle in -3.2..3.2_f64, t in coord(),
        scale_a in 0.5..2.0_f64, scale_b in 0.5..2.0_f64,
    ) {
        let a = synthetic(seed_a, 3, 3);
        let b = synthetic(seed_b, 2, 4);
        let pa = placement([0.0, 0.0, 1.0], 0.3, [0.0; 3], scale_a);
        let pb = placement(axis, angle, t, scale_b);
        let c = collide(&a, &pa, &b, &pb, &Budget::Unlimited).unwrap();
        prop_assert!(c.completed);
        let expected = brute_force(&a, &pa, &b, &pb, deepest(&a).max(deepest(&b)));
        prop_assert_eq!(pairs(&c), expected.clone());
        prop_assert_eq!(overlaps(&a, &pa, &b, &pb), !expected.is_empty());
        check_contacts(&c, &a, &pa, &b, &pb);
    }

    #[test]
    fn a_cost_budget_gives_a_prefix_level_within_the_budget(
        seed_a in any::<u64>(), seed_b in any::<u64>(), t in coord(), fraction in 0.0..1.2_f64,
    ) {
        let a = synthetic(seed_a, 3, 3);
        let b = synthetic(seed_b, 3, 3);
        let pa = Similarity::IDENTITY;
        let pb = placement([1.0, 0.0, 0.0], 0.7, [t[0] * 0.5, t[1] * 0.5, t[2] * 0.5], 1.0);
        let full = collide(&a, &pa, &b, &pb, &Budget::Unlimited).unwrap();
        let full_cost = full.stats.cost(&CostModel::default());
        let limit = (fraction * full_cost).max(5.0);
        let c = collide(&a, &pa, &b, &pb, &Budget::cost(limit)).unwrap();
        prop_assert!(c.stats.cost(&CostModel::default()) <= limit);
        prop_assert!(c.level <= full.level);
        prop_assert_eq!(pairs(&c), brute_force(&a, &pa, &b, &pb, c.level));
        if limit >= full_cost {
            prop_assert_eq!(&c, &full);
        } else {
            prop_assert!(!c.completed);
        }
        // The stats of a cut-short traversal are a prefix of the full one's work.
        prop_assert!(c.stats.tests <= full.stats.tests && c.stats.updates <= full.stats.updates);
    }
}

#[test]
fn every_level_of_a_budgeted_traversal_is_the_truncated_answer() {
    let (capsule, _) = built();
    let pa = Similarity::IDENTITY;
    let pb = Similarity::from_translation(DVec3::new(0.8, 0.1, 0.0)).unwrap();
    let full = collide(capsule, &pa, capsule, &pb, &Budget::Unlimited).unwrap();
    assert!(full.completed);
    assert_eq!(full.level, 2);
    let mut levels = Vec::new();
    // Sweep the budget over the whole range: the level never decreases, each result is
    // the brute-force answer truncated at its level.
    let full_cost = full.stats.cost(&CostModel::default());
    for step in 0..=40 {
        let limit = full_cost * f64::from(step) / 40.0;
        let c = collide(capsule, &pa, capsule, &pb, &Budget::cost(limit)).unwrap();
        assert_eq!(pairs(&c), brute_force(capsule, &pa, capsule, &pb, c.level));
        levels.push(c.level);
        // Coarser levels bound the error more loosely.
        if let (Some(coarse), Some(fine)) = (c.max_error_bound(), full.max_error_bound()) {
            assert!(coarse >= fine - 1e-12);
        }
    }
    assert!(levels.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(levels.first(), Some(&0));
    assert_eq!(levels.last(), Some(&2));
}

#[test]
fn zero_time_stops_at_the_roots_and_ample_time_completes() {
    let (capsule, cube) = built();
    let pa = Similarity::IDENTITY;
    let pb = Similarity::from_translation(DVec3::new(0.5, 0.0, 0.0)).unwrap();
    let none = collide(capsule, &pa, cube, &pb, &Budget::Time(Duration::ZERO)).unwrap();
    assert_eq!(
        (none.level, none.completed, none.contacts.len()),
        (0, false, 1)
    );
    let ample = collide(
        capsule,
        &pa,
        cube,
        &pb,
        &Budget::Time(Duration::from_secs(600)),
    )
    .unwrap();
    let exact = collide(capsule, &pa, cube, &pb, &Budget::Unlimited).unwrap();
    assert_eq!(ample, exact);
}

#[test]
fn separated_trees_have_no_contact_and_complete_at_the_roots() {
    let (capsule, cube) = built();
    let far = Similarity::from_translation(DVec3::new(10.0, 0.0, 0.0)).unwrap();
    let c = collide(
        capsule,
        &Similarity::IDENTITY,
        cube,
        &far,
        &Budget::Unlimited,
    )
    .unwrap();
    assert!(c.contacts.is_empty() && c.completed);
    assert_eq!(c.level, 0);
    assert_eq!(
        c.stats,
        TraversalStats {
            updates: 2,
            tests: 1
        }
    );
    assert_eq!(c.max_error_bound(), None);
    assert!(!overlaps(capsule, &Similarity::IDENTITY, cube, &far));
}

#[test]
fn the_result_is_deterministic_and_sorted() {
    let (capsule, cube) = built();
    let pa = Similarity::IDENTITY;
    let pb = placement([0.2, 1.0, 0.0], 0.9, [0.3, 0.2, 0.1], 1.0);
    let first = collide(capsule, &pa, cube, &pb, &Budget::Unlimited).unwrap();
    let second = collide(capsule, &pa, cube, &pb, &Budget::Unlimited).unwrap();
    assert_eq!(first, second);
    let p = pairs(&first);
    assert!(!p.is_empty());
    assert!(p.windows(2).all(|w| w[0] < w[1]));
}

#[test]
fn the_root_pair_is_always_tested() {
    let (capsule, _) = built();
    let c = collide(
        capsule,
        &Similarity::IDENTITY,
        capsule,
        &Similarity::IDENTITY,
        &Budget::cost(0.0),
    )
    .unwrap();
    assert_eq!((c.level, c.contacts.len(), c.completed), (0, 1, false));
    assert_eq!(c.stats.cost(&CostModel::default()), 5.0);
    let root = capsule.nodes()[0].sphere;
    assert_eq!(c.contacts[0].depth, 2.0 * root.radius);
}

#[test]
fn invalid_budgets_and_placements_are_errors() {
    let (capsule, _) = built();
    let p = Similarity::IDENTITY;
    for budget in [
        Budget::cost(f64::NAN),
        Budget::cost(-1.0),
        Budget::Cost {
            limit: 10.0,
            model: CostModel {
                update_cost: -1.0,
                test_cost: 1.0,
            },
        },
    ] {
        assert!(matches!(
            collide(capsule, &p, capsule, &p, &budget),
            Err(SphereTreeError::InvalidParameter { .. })
        ));
    }
    let shear =
        DAffine3::from_cols_array(&[1.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert!(Similarity::new(shear).is_err());
    assert!(Similarity::from_translation(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
    assert!(
        Similarity::from_rotation_translation(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0), DVec3::ZERO)
            .is_err()
    );
    // A mirror maps spheres to spheres.
    let mirror = Similarity::new(DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0))).unwrap();
    assert_eq!(
        mirror.sphere(&Sphere::new(DVec3::X, 1.0)),
        Sphere::new(-DVec3::X, 1.0)
    );
}
