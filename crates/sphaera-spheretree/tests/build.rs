//! Sphere-tree construction: structure, coverage of the samples at every level, the
//! trivial cases and clear errors.

use sphaera_mesh::{DVec3, TriMesh, sampling, shapes};
use sphaera_spheretree::{Params, Reducer, SphereTree, SphereTreeError, build};

/// Every node's children are in the next level and point back to it; no node has more
/// than `branch` children; every level's spheres are valid.
fn check_structure(tree: &SphereTree) {
    for (i, node) in tree.nodes().iter().enumerate() {
        assert!(node.sphere.is_valid());
        assert!(node.children.len() <= tree.branch());
        for child in tree.children(i) {
            assert_eq!(child.parent, Some(i as u32));
            assert_eq!(child.level, node.level + 1);
        }
    }
}

/// Small settings, so that the tests stay fast.
fn light() -> Params {
    Params::default()
        .initial_spheres(100)
        .min_spheres_per_node(30)
}

fn small(reducer: Reducer) -> Params {
    light().samples(1_500).depth(2).branch(4).reducer(reducer)
}

#[test]
fn every_reducer_builds_a_consistent_tree_on_a_capsule() {
    let mesh = shapes::capsule(0.5, 2.0, 12).unwrap();
    for reducer in [Reducer::Merge, Reducer::Expand, Reducer::Combined] {
        let tree = build(&mesh, &small(reducer)).unwrap();
        check_structure(&tree);
        assert_eq!(tree.level_count(), 3);
        assert_eq!(tree.level(0).len(), 1);
        // The root contains every vertex.
        let root = tree.level(0)[0].sphere;
        assert!(
            mesh.positions()
                .iter()
                .all(|&p| root.contains_point(p, 1e-9))
        );
        for level in 1..3 {
            assert!(!tree.level(level).is_empty(), "{reducer:?} level {level}");
            // Regions partition the samples.
            let total: u32 = tree.level(level).iter().map(|n| n.region_samples).sum();
            assert_eq!(total, 1_500, "{reducer:?} level {level}");
        }
        // Every surface sample (the same ones: same count and seed) lies in a sphere of
        // every level.
        let samples = sampling::poisson_disk(&mesh, 1_500, 1).unwrap().samples;
        for level in 0..tree.level_count() {
            let spheres = tree.level_spheres(level);
            for s in &samples {
                assert!(
                    spheres.iter().any(|b| b.contains_point(s.position, 1e-9)),
                    "{reducer:?}: a sample is outside every sphere of level {level}"
                );
            }
        }
        // Errors shrink level by level.
        let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
        assert!(worst(2) < worst(1) && worst(1) < worst(0), "{reducer:?}");
    }
}

#[test]
fn combined_is_never_worse_than_merge_or_expand_on_a_node() {
    let mesh = shapes::torus(1.0, 0.35, 16).unwrap();
    let params = |r| light().samples(1_500).depth(1).reducer(r);
    let worst = |t: &SphereTree| t.level(1).iter().map(|n| n.error).fold(0.0, f64::max);
    let merge = build(&mesh, &params(Reducer::Merge)).unwrap();
    let expand = build(&mesh, &params(Reducer::Expand)).unwrap();
    let combined = build(&mesh, &params(Reducer::Combined)).unwrap();
    assert!(worst(&combined) <= worst(&merge).min(worst(&expand)) + 1e-12);
}

#[test]
fn depth_zero_and_branch_one_are_valid() {
    let mesh = shapes::sphere(1.0, 12).unwrap();
    let root_only = build(&mesh, &light().samples(500).depth(0)).unwrap();
    assert_eq!(root_only.level_count(), 1);
    let chain = build(
        &mesh,
        &light()
            .samples(400)
            .depth(2)
            .branch(1)
            .min_spheres_per_node(10),
    )
    .unwrap();
    check_structure(&chain);
    for level in 1..chain.level_count() {
        assert_eq!(chain.level(level).len(), 1);
    }
}

#[test]
fn bad_input_gets_clear_errors() {
    let triangle = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    assert!(matches!(
        build(&triangle, &Params::default().samples(200)),
        Err(SphereTreeError::Medial(_))
    ));
    let mesh = shapes::sphere(1.0, 8).unwrap();
    assert!(matches!(
        build(&mesh, &Params::default().branch(0)),
        Err(SphereTreeError::InvalidParameter(_))
    ));
    assert!(matches!(
        build(&mesh, &Params::default().samples(2)),
        Err(SphereTreeError::InvalidParameter(_))
    ));
}
