//! Sphere-tree construction: structure, coverage of the samples at every level, the
//! trivial cases and clear errors.

use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_query::{QueryError, sampling};
use sphaera_spheretree::{Method, SphereTree, SphereTreeError, SphereTreeOptions, Surface, build};

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
fn light() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_initial_spheres(100)
        .with_min_spheres_per_node(30)
}

fn small(method: Method) -> SphereTreeOptions {
    light()
        .with_samples(1_500)
        .with_depth(2)
        .with_branch(4)
        .with_method(method)
}

#[test]
fn every_reducer_builds_a_consistent_tree_on_a_capsule() {
    let mesh = shapes::capsule(0.5, 2.0, 12).unwrap();
    for method in [Method::Merge, Method::Expand, Method::Combined] {
        let tree = build(&Surface::new(&mesh).unwrap(), &small(method)).unwrap();
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
            assert!(!tree.level(level).is_empty(), "{method:?} level {level}");
            // Regions partition the samples.
            let total: u32 = tree.level(level).iter().map(|n| n.region_samples).sum();
            assert_eq!(total, 1_500, "{method:?} level {level}");
        }
        // Every surface sample (the same ones: same count and seed) lies in a sphere of
        // every level.
        let samples = sampling::poisson_disk(&mesh, 1_500, 1).unwrap().samples;
        for level in 0..tree.level_count() {
            let spheres = tree.level_spheres(level);
            for s in &samples {
                assert!(
                    spheres.iter().any(|b| b.contains_point(s.position, 1e-9)),
                    "{method:?}: a sample is outside every sphere of level {level}"
                );
            }
        }
        // Errors shrink level by level.
        let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
        assert!(worst(2) < worst(1) && worst(1) < worst(0), "{method:?}");
    }
}

#[test]
fn combined_is_never_worse_than_merge_or_expand_on_a_node() {
    let mesh = shapes::torus(1.0, 0.35, 16).unwrap();
    let params = |r| light().with_samples(1_500).with_depth(1).with_method(r);
    let worst = |t: &SphereTree| t.level(1).iter().map(|n| n.error).fold(0.0, f64::max);
    let merge = build(&Surface::new(&mesh).unwrap(), &params(Method::Merge)).unwrap();
    let expand = build(&Surface::new(&mesh).unwrap(), &params(Method::Expand)).unwrap();
    let combined = build(&Surface::new(&mesh).unwrap(), &params(Method::Combined)).unwrap();
    assert!(worst(&combined) <= worst(&merge).min(worst(&expand)) + 1e-12);
}

#[test]
fn depth_zero_and_branch_one_are_valid() {
    let mesh = shapes::sphere(1.0, 12).unwrap();
    let root_only = build(
        &Surface::new(&mesh).unwrap(),
        &light().with_samples(500).with_depth(0),
    )
    .unwrap();
    assert_eq!(root_only.level_count(), 1);
    let chain = build(
        &Surface::new(&mesh).unwrap(),
        &light()
            .with_samples(400)
            .with_depth(2)
            .with_branch(1)
            .with_min_spheres_per_node(10),
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
        Surface::new(&triangle),
        Err(QueryError::NoInside { .. })
    ));
    let mesh = shapes::sphere(1.0, 8).unwrap();
    assert!(matches!(
        build(
            &Surface::new(&mesh).unwrap(),
            &SphereTreeOptions::default().with_branch(0)
        ),
        Err(SphereTreeError::InvalidParameter { .. })
    ));
    assert!(matches!(
        build(
            &Surface::new(&mesh).unwrap(),
            &SphereTreeOptions::default()
                .with_method(Method::Merge)
                .with_samples(2)
        ),
        Err(SphereTreeError::InvalidParameter { .. })
    ));
    // The paper's medial methods need a solid; minimax (the default) covers a sheet.
    let sheet = Surface::shell(&triangle).unwrap();
    assert!(matches!(
        build(
            &sheet,
            &SphereTreeOptions::default().with_method(Method::Expand)
        ),
        Err(SphereTreeError::NeedsInside { method: "expand" })
    ));
    assert!(build(&sheet, &SphereTreeOptions::default().with_depth(1)).is_ok());
}

/// A digest of a tree's nodes (the bits of every sphere and error, and the structure), to
/// compare runs across feature sets.
fn digest(tree: &SphereTree) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    let mut mix = |bits: u64| hash = (hash ^ bits).wrapping_mul(0x0100_0000_01b3);
    for node in tree.nodes() {
        let s = node.sphere;
        for value in [s.center.x, s.center.y, s.center.z, s.radius, node.error] {
            mix(value.to_bits());
        }
        mix(u64::from(node.parent.unwrap_or(u32::MAX)));
        mix(u64::from(node.region_samples));
    }
    hash
}

/// The same tree with and without the `parallel` feature, for every method:
/// `cargo xtask test` runs this test both ways against the same recorded digests. (A
/// change to the algorithm changes them: record the new values printed on failure,
/// after checking that both builds agree.)
#[test]
fn the_parallel_feature_does_not_change_the_tree() {
    // An L-shaped block: no sine or cosine, whose last bit could differ between system
    // libraries.
    let mesh = shapes::l_block(2.0, 1.0, 0.5, 4).unwrap();
    let digests: Vec<u64> = [
        Method::Merge,
        Method::Burst,
        Method::Expand,
        Method::Combined,
        Method::Minimax,
    ]
    .into_iter()
    .map(|method| digest(&build(&Surface::new(&mesh).unwrap(), &small(method)).unwrap()))
    .collect();
    assert_eq!(digests, EXPECTED_DIGESTS, "digests {digests:#x?}");
}

const EXPECTED_DIGESTS: [u64; 5] = [
    0x73cf_af10_dbce_928a,
    0x7987_93ff_f3ed_ca70,
    0x602f_cd73_261e_9218,
    0xdc4e_6798_0767_10a2,
    0x8946_8461_d862_569b,
];

/// A thorough tree is never looser than the default's: built to a depth, the product of
/// its levels' worst errors is no larger; with a tolerance, it has no more leaves (the
/// default's tree is built as well and kept when tighter).
#[test]
fn thorough_trees_are_never_looser_than_the_defaults() {
    use sphaera_mesh::Length;
    use sphaera_spheretree::Effort;
    let meshes = [
        ("capsule", shapes::capsule(0.5, 2.0, 8).expect("valid")),
        ("torus", shapes::torus(1.0, 0.3, 16).expect("valid")),
    ];
    let score = |tree: &SphereTree| -> f64 {
        (1..tree.level_count())
            .map(|level| {
                tree.level(level)
                    .iter()
                    .map(|n| n.error)
                    .fold(0.0, f64::max)
                    .ln()
            })
            .sum()
    };
    for (name, mesh) in meshes {
        let surface = Surface::new(&mesh).expect("closed");
        let at = |effort, tolerance: Option<f64>| {
            let mut options = SphereTreeOptions::default()
                .with_effort(effort)
                .with_depth(2)
                .with_branch(4);
            if let Some(t) = tolerance {
                options = options.with_tolerance(Length::RelativeToDiagonal(t));
            }
            build(&surface, &options).expect("builds")
        };
        let (default, thorough) = (at(Effort::Default, None), at(Effort::Thorough, None));
        assert!(score(&thorough) <= score(&default), "{name} to a depth");
        let (default, thorough) = (
            at(Effort::Default, Some(0.03)),
            at(Effort::Thorough, Some(0.03)),
        );
        assert!(
            thorough.leaves().len() <= default.leaves().len(),
            "{name} at 3 %"
        );
    }
}
