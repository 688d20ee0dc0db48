//! Level and cut choice by tolerance: against their definitions and against an
//! exhaustive search for the smallest cut.

mod common;

use common::small_tree;
use proptest::prelude::*;
use sphaera_mesh::{DVec3, Sphere, shapes};
use sphaera_spheretree::select::{
    cut_for_tolerance, level_for_tolerance, level_worst_errors, spheres_for_tolerance,
};
use sphaera_spheretree::{SphereTree, TreeNode};

/// A tree from child counts listed breadth-first (the root first) and one error per node.
fn tree_from_shape(child_counts: &[usize], errors: &[f64], branch: usize) -> SphereTree {
    let node = |level: u32, parent: Option<u32>, error: f64| TreeNode {
        sphere: Sphere::new(DVec3::ZERO, 1.0 / f64::from(level + 1)),
        error,
        level,
        parent,
        children: 0..0,
        region_samples: 0,
    };
    let mut levels = vec![vec![node(0, None, errors[0])]];
    let mut counts = child_counts.iter().copied();
    // Nodes before the level being expanded.
    let mut first = 0;
    loop {
        let level = levels.len() - 1;
        let next_first = first + levels[level].len();
        let mut next = Vec::new();
        for (k, parent) in levels[level].iter_mut().enumerate() {
            let kids = counts.next().unwrap_or(0).min(branch);
            let start = (next_first + next.len()) as u32;
            for _ in 0..kids {
                let e = errors[(next_first + next.len()) % errors.len()];
                next.push(node(level as u32 + 1, Some((first + k) as u32), e));
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

fn children(tree: &SphereTree, i: usize) -> Vec<usize> {
    let r = &tree.nodes()[i].children;
    (r.start as usize..r.end as usize).collect()
}

/// Every cut of the subtree of `i` whose nodes all meet `tolerance` (leaves that do not
/// meet it are allowed, as `cut_for_tolerance` keeps them): the sizes of all of them.
fn all_cut_sizes(tree: &SphereTree, i: usize, tolerance: f64) -> Vec<usize> {
    let kids = children(tree, i);
    let mut sizes = Vec::new();
    if tree.nodes()[i].error <= tolerance || kids.is_empty() {
        sizes.push(1);
    }
    if !kids.is_empty() {
        let mut combos = vec![0_usize];
        for k in kids {
            let sub = all_cut_sizes(tree, k, tolerance);
            combos = combos
                .iter()
                .flat_map(|&c| sub.iter().map(move |&s| c + s))
                .collect();
            combos.sort_unstable();
            combos.dedup();
        }
        sizes.extend(combos);
    }
    sizes
}

fn shape() -> impl Strategy<Value = (Vec<usize>, Vec<f64>)> {
    (
        prop::collection::vec(0..4_usize, 1..10),
        prop::collection::vec(0.0..1.0_f64, 1..12),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(128)))]

    #[test]
    fn the_level_is_the_shallowest_meeting_the_tolerance(
        (counts, errors) in shape(), tolerance in -0.1..1.1_f64,
    ) {
        let tree = tree_from_shape(&counts, &errors, 3);
        let worst = level_worst_errors(&tree);
        let expected = (0..tree.level_count())
            .find(|&k| tree.level(k).iter().all(|n| n.error <= tolerance));
        prop_assert_eq!(level_for_tolerance(&tree, tolerance), expected);
        if let Some(k) = expected {
            prop_assert!(worst[k] <= tolerance);
            prop_assert_eq!(spheres_for_tolerance(&tree, tolerance), Some(tree.level_spheres(k)));
        } else {
            prop_assert_eq!(spheres_for_tolerance(&tree, tolerance), None);
        }
    }

    #[test]
    fn the_cut_is_a_cut_meets_the_tolerance_and_is_smallest(
        (counts, errors) in shape(), tolerance in 0.0..1.0_f64,
    ) {
        let tree = tree_from_shape(&counts, &errors, 3);
        let cut = cut_for_tolerance(&tree, tolerance);
        prop_assert!(cut.nodes.windows(2).all(|w| w[0] < w[1]));
        // Every leaf has exactly one cut node on its path to the root.
        for leaf in (0..tree.nodes().len()).filter(|&i| tree.nodes()[i].children.is_empty()) {
            let mut on_path = 0;
            let mut i = Some(leaf);
            while let Some(k) = i {
                on_path += usize::from(cut.nodes.contains(&k));
                i = tree.nodes()[k].parent.map(|p| p as usize);
            }
            prop_assert_eq!(on_path, 1);
        }
        // Kept nodes meet the tolerance or are leaves; their ancestors do not meet it.
        for &k in &cut.nodes {
            let node = &tree.nodes()[k];
            prop_assert!(node.error <= tolerance || node.children.is_empty());
            let mut up = node.parent;
            while let Some(p) = up {
                prop_assert!(tree.nodes()[p as usize].error > tolerance);
                up = tree.nodes()[p as usize].parent;
            }
        }
        let meets = cut.nodes.iter().all(|&k| tree.nodes()[k].error <= tolerance);
        prop_assert_eq!(cut.meets_tolerance, meets);
        let worst = cut.nodes.iter().map(|&k| tree.nodes()[k].error).fold(f64::NEG_INFINITY, f64::max);
        prop_assert_eq!(cut.worst_error.to_bits(), worst.to_bits());
        // The smallest among all cuts (exhaustive).
        let smallest = all_cut_sizes(&tree, 0, tolerance).into_iter().min();
        prop_assert_eq!(Some(cut.nodes.len()), smallest);
        prop_assert_eq!(cut.spheres(&tree).len(), cut.nodes.len());
    }
}

#[test]
fn on_a_built_tree_the_cut_never_has_more_spheres_than_the_level() {
    let tree = small_tree(&shapes::capsule(0.4, 2.5, 10).unwrap());
    let worst = level_worst_errors(&tree);
    assert_eq!(worst.len(), 3);
    for (k, &w) in worst.iter().enumerate() {
        assert_eq!(level_for_tolerance(&tree, w).map(|l| l <= k), Some(true));
        let level = level_for_tolerance(&tree, w).unwrap();
        let cut = cut_for_tolerance(&tree, w);
        assert!(cut.meets_tolerance);
        assert!(cut.worst_error <= w);
        assert!(cut.nodes.len() <= tree.level(level).len());
    }
    // Tighter than the deepest level: no level, and the cut keeps failing leaves.
    let tight = worst[2] * 0.5;
    assert_eq!(level_for_tolerance(&tree, tight), None);
    let cut = cut_for_tolerance(&tree, tight);
    assert!(!cut.meets_tolerance);
    assert_eq!(level_for_tolerance(&tree, f64::NAN), None);
    assert_eq!(level_for_tolerance(&tree, f64::INFINITY), Some(0));
}
