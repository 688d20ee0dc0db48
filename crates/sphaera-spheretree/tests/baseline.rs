//! The baseline sphere-trees (octree, grid, Hubbard): structure, coverage of the samples
//! at every level, clear errors, and the octree's loose fit against the medial build.

use sphaera_mesh::{DVec3, Length, TriMesh, shapes};
use sphaera_query::{Surface, sampling};
use sphaera_spheretree::{
    EvaluationOptions, MAX_BASELINE_DEPTH, MAX_BASELINE_SAMPLES, Method, SphereTree,
    SphereTreeError, SphereTreeOptions, build, evaluate_set,
};

const METHODS: [Method; 3] = [Method::Octree, Method::Grid, Method::Hubbard];

/// The tree of `mesh` by `method`.
fn run(
    method: Method,
    mesh: &TriMesh,
    options: &SphereTreeOptions,
) -> Result<SphereTree, SphereTreeError> {
    build(&Surface::new(mesh)?, &options.clone().with_method(method))
}

/// Levels, parent and children links, consecutive children in the next level, regions
/// partitioned between children, and every sample inside a sphere of every level.
fn check(name: &str, mesh: &TriMesh, tree: &SphereTree, params: &SphereTreeOptions) {
    assert_eq!(tree.level_count(), params.depth + 1, "{name}");
    assert_eq!(tree.level(0).len(), 1, "{name}");
    assert_eq!(
        tree.level(0)[0].region_samples as usize,
        params.samples,
        "{name}"
    );
    let mut seen = 0;
    for level in 0..tree.level_count() {
        for node in tree.level(level) {
            assert_eq!(node.level as usize, level, "{name}");
            assert!(node.sphere.is_valid() && node.error.is_finite(), "{name}");
        }
        seen += tree.level(level).len();
    }
    assert_eq!(seen, tree.nodes().len(), "{name}");
    for (i, node) in tree.nodes().iter().enumerate() {
        assert!(node.children.len() <= tree.branch(), "{name}");
        let children = tree.children(i);
        for child in children {
            assert_eq!(child.parent, Some(i as u32), "{name}");
            assert_eq!(child.level, node.level + 1, "{name}");
            assert!(child.region_samples > 0, "{name}");
        }
        if (node.level as usize) < params.depth {
            let split: u32 = children.iter().map(|c| c.region_samples).sum();
            assert_eq!(split, node.region_samples, "{name}: node {i}'s region");
        }
    }
    let samples = sampling::poisson_disk(mesh, params.samples, params.seed)
        .unwrap()
        .samples;
    for level in 0..tree.level_count() {
        let spheres = tree.level_spheres(level);
        for s in &samples {
            assert!(
                spheres.iter().any(|b| b.contains_point(s.position, 1e-9)),
                "{name}: a sample is outside every sphere of level {level}"
            );
        }
    }
}

fn small() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_depth(3)
        .with_branch(4)
        .with_samples(1_500)
        .with_forming_points(120)
}

#[test]
fn every_baseline_builds_a_consistent_tree_on_a_capsule_and_a_cube() {
    let meshes = [
        ("capsule", shapes::capsule(0.5, 2.0, 12).unwrap()),
        ("cube", shapes::cube(1.0, 4).unwrap()),
    ];
    for (mesh_name, mesh) in &meshes {
        for method in METHODS {
            let name = format!("{} on the {mesh_name}", method.name());
            let params = small();
            let tree = run(method, mesh, &params).unwrap();
            check(&name, mesh, &tree, &params);
            if method == Method::Octree {
                assert_eq!(tree.branch(), 8, "{name}");
            }
            if method == Method::Hubbard {
                assert_eq!(tree.branch(), 4, "{name}");
            }
            // Deterministic.
            assert_eq!(run(method, mesh, &params).unwrap(), tree, "{name}");
        }
    }
}

#[test]
fn grid_levels_have_about_branch_to_the_level_cells() {
    let mesh = shapes::sphere(1.0, 12).unwrap();
    let params = SphereTreeOptions::default()
        .with_depth(2)
        .with_branch(8)
        .with_samples(2_000);
    let tree = run(Method::Grid, &mesh, &params).unwrap();
    // At most 8 occupied cells at level 1, 64 at level 2; a cell straddling parents
    // counts once per parent.
    assert!(
        (2..=8).contains(&tree.level(1).len()),
        "{}",
        tree.level(1).len()
    );
    let spheres = tree.level_spheres(2);
    let mut distinct: Vec<[u64; 4]> = spheres
        .iter()
        .map(|s| {
            [
                s.center.x.to_bits(),
                s.center.y.to_bits(),
                s.center.z.to_bits(),
                s.radius.to_bits(),
            ]
        })
        .collect();
    distinct.sort_unstable();
    distinct.dedup();
    assert!((16..=64).contains(&distinct.len()), "{}", distinct.len());
}

#[test]
fn depth_zero_and_bad_input() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    for method in METHODS {
        let name = method.name();
        let root = run(method, &mesh, &small().with_depth(0)).unwrap();
        assert_eq!(root.level_count(), 1, "{name}");
        for bad in [
            small().with_depth(MAX_BASELINE_DEPTH + 1),
            small().with_branch(0),
            small().with_samples(2),
            small().with_forming_points(3),
        ] {
            assert!(
                matches!(
                    run(method, &mesh, &bad),
                    Err(SphereTreeError::InvalidParameter { .. })
                ),
                "{name}: {bad:?}"
            );
        }
        let empty = TriMesh::new(Vec::new(), Vec::new()).unwrap();
        assert!(run(method, &empty, &small()).is_err(), "{name}: empty mesh");
    }
    // A NaN vertex never makes a mesh.
    assert!(TriMesh::new(vec![DVec3::NAN, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).is_err());
}

/// The limits' messages name the values of the public constants.
#[test]
fn limit_messages_name_the_constants() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let thousands = |n: usize| {
        let digits = n.to_string();
        let mut out = String::new();
        for (i, c) in digits.chars().enumerate() {
            if i > 0 && (digits.len() - i).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    for (options, limit) in [
        (
            small().with_depth(MAX_BASELINE_DEPTH + 1),
            MAX_BASELINE_DEPTH,
        ),
        (
            small().with_samples(MAX_BASELINE_SAMPLES + 1),
            MAX_BASELINE_SAMPLES,
        ),
    ] {
        let Err(SphereTreeError::InvalidParameter { requirement, .. }) =
            run(Method::Octree, &mesh, &options)
        else {
            panic!("{options:?} accepted");
        };
        assert!(
            requirement.contains(&thousands(limit)),
            "{requirement:?} does not name {limit}"
        );
    }
}

#[test]
fn bunny_baselines_are_consistent_and_the_octree_is_looser_than_the_medial_build() {
    let Some(dir) = sphaera_tests::data_dir("bunny_baselines") else {
        return;
    };
    let mesh = sphaera_io::load(dir.join("bunny_lowres.obj")).unwrap();
    let params = SphereTreeOptions::default()
        .with_samples(3_000)
        .with_forming_points(300);
    let trees: Vec<SphereTree> = METHODS
        .iter()
        .map(|&method| {
            let tree = run(method, &mesh, &params).unwrap();
            check(method.name(), &mesh, &tree, &params);
            tree
        })
        .collect();
    let surface = Surface::new(&mesh).unwrap();
    let medial = build(
        &surface,
        &SphereTreeOptions::default()
            .with_samples(3_000)
            .with_initial_spheres(200)
            .with_min_spheres_per_node(40)
            .with_method(Method::Merge),
    )
    .unwrap();
    let options = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(1e-2))
        .with_coverage_samples(2_000);
    for level in 2..=3 {
        let evaluate =
            |t: &SphereTree| evaluate_set(&surface, &t.level_spheres(level), &options).unwrap();
        let octree_fit = evaluate(&trees[0]);
        let medial_fit = evaluate(&medial);
        assert!(
            octree_fit.worst_lower > medial_fit.worst_upper,
            "level {level}: octree {} vs medial {}",
            octree_fit.worst_lower,
            medial_fit.worst_upper
        );
    }
}
