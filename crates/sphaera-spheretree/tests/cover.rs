//! Certified coverage: every level of a built tree covers the whole surface (checked on
//! dense independent samples), and `certify_coverage` against brute force on random
//! triangles and spheres.

use proptest::prelude::*;
use sphaera_io as io;
use sphaera_mesh::{DVec3, Sphere, TriMesh, shapes};
use sphaera_spheretree::cover::certify_coverage;
use sphaera_spheretree::evaluate::coverage;
use sphaera_spheretree::{EvaluationOptions, Method, SphereTreeOptions, Surface, build};

fn light() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_initial_spheres(120)
        .with_min_spheres_per_node(30)
        .with_samples(2_000)
        .with_depth(2)
}

/// Every level of `mesh`'s tree leaves no sample of 50,000 random ones uncovered.
fn check_every_level_covers(name: &str, mesh: &TriMesh, params: &SphereTreeOptions) {
    let tree = build(&Surface::new(mesh).unwrap(), params).unwrap();
    assert_eq!(tree.coverage().len(), tree.level_count(), "{name}");
    let options = EvaluationOptions::default()
        .with_coverage_samples(50_000)
        .with_seed(7);
    for level in 0..tree.level_count() {
        let c = coverage(mesh, &tree.level_spheres(level), &options).unwrap();
        assert_eq!(
            c.uncovered, 0,
            "{name} level {level}: {} samples uncovered, largest gap {}",
            c.uncovered, c.largest_gap
        );
    }
}

#[test]
fn every_level_covers_the_surface_of_simple_shapes() {
    let shapes = [
        ("capsule", shapes::capsule(0.5, 2.0, 12).unwrap()),
        ("cube", shapes::cube(1.0, 2).unwrap()),
        ("torus", shapes::torus(1.0, 0.3, 16).unwrap()),
    ];
    for (name, mesh) in &shapes {
        for method in [Method::Merge, Method::Expand] {
            check_every_level_covers(name, mesh, &light().with_method(method));
        }
    }
}

#[test]
fn every_level_covers_the_low_res_bunny() {
    let Some(dir) = sphaera_tests::data_dir("every_level_covers_the_low_res_bunny") else {
        return;
    };
    let mesh = io::load(dir.join("bunny_lowres.obj")).unwrap();
    check_every_level_covers("bunny_lowres", &mesh, &light().with_method(Method::Expand));
}

#[test]
fn without_certification_there_is_no_certificate() {
    let mesh = shapes::capsule(0.5, 2.0, 8).unwrap();
    let tree = build(
        &Surface::new(&mesh).unwrap(),
        &light().with_depth(1).with_certify_coverage(false),
    )
    .unwrap();
    assert!(tree.coverage().is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(64), ..ProptestConfig::default() })]

    /// After certification, every point of the triangle (on a dense barycentric grid)
    /// is inside a sphere, no sphere shrank or moved, growth is reported exactly, and nothing
    /// grows when one sphere already contains the triangle.
    #[test]
    fn certified_triangles_are_covered(
        corners in prop::array::uniform3(prop::array::uniform3(-1.0..1.0_f64)),
        spheres in prop::collection::vec((prop::array::uniform3(-1.0..1.0_f64), 0.05..0.8_f64), 1..8),
    ) {
        let corners = corners.map(DVec3::from_array);
        let mesh = TriMesh::new(corners.to_vec(), vec![[0, 1, 2]]);
        prop_assume!(mesh.is_ok());
        let Ok(mesh) = mesh else { return Ok(()) };
        let original: Vec<Sphere> = spheres
            .iter()
            .map(|&(c, r)| Sphere::new(DVec3::from_array(c), r))
            .collect();
        let mut grown = original.clone();
        let (certificate, growth) = certify_coverage(&mesh, &mut grown, 0.05);
        for ((before, after), g) in original.iter().zip(&grown).zip(&growth) {
            prop_assert!(after.radius >= before.radius);
            prop_assert_eq!(after.center, before.center);
            prop_assert!((after.radius - before.radius - g).abs() <= 1e-12);
        }
        let n = 40;
        for i in 0..=n {
            for j in 0..=n - i {
                let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
                let p = corners[0] + u * (corners[1] - corners[0]) + v * (corners[2] - corners[0]);
                prop_assert!(
                    grown.iter().any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-12) + 1e-15),
                    "{p} uncovered"
                );
            }
        }
        // Spheres that already contain the triangle are never grown.
        if original.iter().any(|s| corners.iter().all(|c| c.distance(s.center) <= s.radius)) {
            prop_assert_eq!(certificate.grown_spheres, 0);
        }
    }
}
