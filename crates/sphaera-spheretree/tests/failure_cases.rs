//! The "where it must not fail" list: thin tubes, a cube, the open bunny, the
//! non-manifold dragon, robot collision meshes, more spheres than samples. Each builds
//! a valid tree whose every level covers the surface (the certificate) and every sample.

use sphaera_io as io;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_query::sampling;
use sphaera_spheretree::{Method, SphereTree, SphereTreeOptions, Surface, build};

fn light() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_initial_spheres(100)
        .with_min_spheres_per_node(30)
        .with_samples(1_500)
        .with_depth(2)
}

/// Structure, certificates and sample coverage of every level.
fn check(name: &str, mesh: &TriMesh, params: &SphereTreeOptions, tree: &SphereTree) {
    assert_eq!(tree.level_count(), params.depth + 1, "{name}");
    assert_eq!(tree.coverage().len(), tree.level_count(), "{name}");
    let samples = sampling::poisson_disk(mesh, params.samples, params.seed)
        .unwrap()
        .samples;
    for level in 0..tree.level_count() {
        let spheres = tree.level_spheres(level);
        assert!(!spheres.is_empty(), "{name} level {level}");
        assert!(spheres.len() <= params.branch.pow(level as u32), "{name}");
        for s in &samples {
            assert!(
                spheres.iter().any(|b| b.contains_point(s.position, 1e-9)),
                "{name}: a sample is outside level {level}"
            );
        }
    }
}

#[test]
fn thin_tubes_build_with_every_reducer() {
    // A long thin capsule and a thin torus: the expand-select failure shapes.
    let tubes = [
        ("thin capsule", shapes::capsule(0.05, 3.0, 16).unwrap()),
        ("thin torus", shapes::torus(1.0, 0.04, 32).unwrap()),
    ];
    for (name, mesh) in &tubes {
        for method in [Method::Merge, Method::Expand, Method::Combined] {
            let params = light().with_method(method);
            let tree = build(&Surface::new(mesh).unwrap(), &params).unwrap();
            check(name, mesh, &params, &tree);
        }
    }
}

#[test]
fn a_cube_gets_a_tight_first_level() {
    let mesh = shapes::cube(2.0, 4).unwrap();
    let params = light().with_depth(1).with_method(Method::Combined);
    let tree = build(&Surface::new(&mesh).unwrap(), &params).unwrap();
    check("cube", &mesh, &params, &tree);
    // Eight children of a cube of side 2 reach out less than the root does.
    let root = tree.level(0)[0].error;
    let worst = tree.level(1).iter().map(|n| n.error).fold(0.0, f64::max);
    assert!(worst < root, "{worst} vs {root}");
}

#[test]
fn more_spheres_than_samples_is_valid() {
    // Branch 8, depth 3 from 40 samples: nodes run out of samples, and regions with
    // fewer samples than children keep only the children they need.
    let mesh = shapes::sphere(1.0, 12).unwrap();
    let params = SphereTreeOptions::default()
        .with_samples(40)
        .with_initial_spheres(30)
        .with_min_spheres_per_node(200)
        .with_depth(3);
    let tree = build(&Surface::new(&mesh).unwrap(), &params).unwrap();
    check("sphere, 40 samples", &mesh, &params, &tree);
}

#[test]
fn real_meshes_build() {
    let Some(dir) = sphaera_tests::data_dir("real_meshes_build") else {
        return;
    };
    let files = [
        "robots/franka_panda/collision/link0.obj",
        "robots/franka_panda/collision/link3.obj",
        "robots/franka_panda/collision/hand.obj",
        "robots/franka_panda/collision/finger.obj",
        // Non-manifold, with holes.
        "dragon_vrip_res4.ply",
    ];
    for file in files {
        let mesh = io::load(dir.join(file)).unwrap();
        let params = light();
        let surface = Surface::new(&mesh).unwrap_or_else(|e| panic!("{file}: {e}"));
        let tree = build(&surface, &params).unwrap_or_else(|e| panic!("{file}: {e}"));
        check(file, &mesh, &params, &tree);
    }
}

#[test]
fn the_open_stanford_bunny_builds() {
    let Some(dir) = sphaera_tests::data_dir("the_open_stanford_bunny_builds") else {
        return;
    };
    let mesh = io::load(dir.join("stanford-bunny.obj")).unwrap();
    let params = light().with_depth(1).with_method(Method::Expand);
    let tree = build(&Surface::new(&mesh).unwrap(), &params).unwrap();
    check("stanford-bunny", &mesh, &params, &tree);
}
