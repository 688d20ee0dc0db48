//! The adaptive medial approximation on shapes, degenerate and failure cases, and the real
//! meshes: coverage of every sample, errors against brute-force distances, targets,
//! regions and determinism.

#![allow(clippy::print_stderr)]

use sphaera_io as io;
use sphaera_medial::{
    CoverCriterion, MedialApproximation, MedialError, MedialOptions, RegionOptions, SphereKind,
    Surface,
};
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_query::{QueryError, sampling};
use sphaera_tests::hausdorff::DistanceToMesh;

fn samples(mesh: &TriMesh, n: usize) -> Vec<DVec3> {
    sampling::poisson_disk(mesh, n, 3)
        .unwrap()
        .samples
        .iter()
        .map(|s| s.position)
        .collect()
}

/// Coverage of every sample by brute force, and every error against a brute-force
/// distance to the mesh.
fn check(mesh: &TriMesh, medial: &MedialApproximation<'_>, name: &str) {
    let spheres = medial.spheres();
    assert!(!spheres.is_empty(), "{name}: no spheres");
    let tolerance = 1e-9 * mesh.bounding_box_diagonal();
    for (i, &p) in medial.samples().iter().enumerate() {
        assert!(
            spheres
                .iter()
                .any(|s| (p - s.center).length() <= s.radius + tolerance),
            "{name}: sample {i} is not covered"
        );
    }
    assert!(medial.uncovered_samples().is_empty(), "{name}");
    let brute = DistanceToMesh::new(mesh);
    for s in &spheres {
        let d = brute.distance(s.center);
        let expected = match s.kind {
            SphereKind::Internal => s.radius - d,
            SphereKind::Cover | SphereKind::External => s.radius + d,
        };
        assert!(
            (s.error - expected.max(0.0)).abs() <= 1e-9 * mesh.bounding_box_diagonal(),
            "{name}: error {} != {expected}",
            s.error
        );
        for &c in &s.covers {
            let q = medial.samples()[c as usize];
            assert!((q - s.center).length() <= s.radius + tolerance);
        }
    }
}

fn build<'s>(
    surface: &'s Surface,
    points: &[DVec3],
    params: &MedialOptions,
) -> MedialApproximation<'s> {
    MedialApproximation::build(surface, points, params).unwrap()
}

#[test]
fn shapes_with_cospherical_and_coplanar_samples_are_covered() {
    for (name, mesh) in [
        ("cube", shapes::cube(2.0, 6).unwrap()),
        ("sphere", shapes::sphere(1.0, 16).unwrap()),
        ("cylinder", shapes::cylinder(0.5, 2.0, 16).unwrap()),
        ("torus", shapes::torus(1.0, 0.3, 16).unwrap()),
    ] {
        let surface = Surface::new(&mesh).unwrap();
        let points = samples(&mesh, 1_500);
        let medial = build(
            &surface,
            &points,
            &MedialOptions::default().with_target_spheres(150),
        );
        assert!(medial.sphere_count() >= 150, "{name}");
        check(&mesh, &medial, name);
        // The vertices of the cube (exactly on a grid) as samples: all cospherical.
        if name == "cube" {
            let corners: Vec<DVec3> = mesh.positions().to_vec();
            let medial = build(
                &surface,
                &corners,
                &MedialOptions::default().with_target_spheres(30),
            );
            check(&mesh, &medial, "cube vertices");
        }
    }
}

#[test]
fn the_error_target_is_reached_and_errors_shrink() {
    let mesh = shapes::capsule(0.5, 2.0, 16).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points = samples(&mesh, 3_000);
    let coarse = build(&surface, &points, &MedialOptions::default());
    let fine = build(
        &surface,
        &points,
        &MedialOptions::default().with_max_error(0.02),
    );
    assert!(fine.worst_error() <= 0.02);
    assert!(fine.worst_error() < coarse.worst_error());
    check(&mesh, &fine, "capsule");
    for criterion in [
        CoverCriterion::SmallestError,
        CoverCriterion::LargestCoverage,
    ] {
        let medial = build(
            &surface,
            &points,
            &MedialOptions::default()
                .with_target_spheres(100)
                .with_cover(criterion),
        );
        check(&mesh, &medial, "capsule, criterion");
    }
}

#[test]
fn the_same_input_gives_the_same_spheres() {
    let mesh = shapes::torus(1.0, 0.4, 16).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points = samples(&mesh, 2_000);
    let params = MedialOptions::default().with_target_spheres(200);
    let a = build(&surface, &points, &params).spheres();
    let b = build(&surface, &points, &params).spheres();
    assert_eq!(a, b);
}

/// A digest of the spheres (their bits), to compare runs across feature sets.
fn digest(spheres: &[sphaera_medial::MedialSphere]) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    for s in spheres {
        for bits in [s.center.x, s.center.y, s.center.z, s.radius, s.error].map(f64::to_bits) {
            hash = (hash ^ bits).wrapping_mul(0x0100_0000_01b3);
        }
    }
    hash
}

/// The same spheres with and without the `parallel` feature: `cargo xtask test` runs this
/// test both ways against the same recorded digest. (A change to the algorithm changes
/// the digest: record the new value printed on failure, after checking that both builds
/// agree.)
#[test]
fn the_parallel_feature_does_not_change_the_spheres() {
    // An L-shaped block: no sine or cosine, whose last bit could differ between system
    // libraries.
    let mesh = shapes::l_block(2.0, 1.0, 0.5, 4).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points = samples(&mesh, 2_000);
    let medial = build(
        &surface,
        &points,
        &MedialOptions::default().with_target_spheres(300),
    );
    let spheres = medial.spheres();
    assert_eq!(
        digest(&spheres),
        EXPECTED_DIGEST,
        "digest {:#x} of {} spheres",
        digest(&spheres),
        spheres.len()
    );
}

const EXPECTED_DIGEST: u64 = 0x5c31_a9a8_1e24_8005;

#[test]
fn a_region_is_refined_to_its_goal_and_coverage_is_kept() {
    let mesh = shapes::capsule(0.5, 2.0, 16).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points = samples(&mesh, 2_000);
    let mut medial = build(
        &surface,
        &points,
        &MedialOptions::default().with_target_spheres(40),
    );
    // The samples of the top half.
    let region: Vec<u32> = (0..points.len() as u32)
        .filter(|&i| points[i as usize].z > 0.5)
        .collect();
    let before = medial.worst_error();
    let outcome = medial
        .refine_region(
            &region,
            &RegionOptions::default()
                .with_min_spheres(50)
                .with_max_error(before / 4.0),
        )
        .unwrap();
    assert!(outcome.reached, "{outcome:?}");
    assert!(outcome.spheres.len() >= 50);
    assert!(outcome.worst_error <= before / 4.0);
    // Exactly the set's spheres covering a region sample, by brute force.
    let expected: Vec<_> = medial
        .spheres()
        .into_iter()
        .filter(|s| s.covers.iter().any(|c| region.contains(c)))
        .collect();
    assert_eq!(outcome.spheres, expected);
    // A second call with a goal already met changes nothing.
    let again = medial
        .refine_region(
            &region,
            &RegionOptions::default()
                .with_min_spheres(10)
                .with_max_error(before),
        )
        .unwrap();
    assert_eq!(again.improvements, 0);
    assert_eq!(again.spheres, expected);
    check(&mesh, &medial, "capsule after region refinement");
    assert!(matches!(
        medial.refine_region(
            &[u32::MAX],
            &RegionOptions::default()
                .with_min_spheres(1)
                .with_max_error(1.0)
        ),
        Err(MedialError::RegionOutOfRange { .. })
    ));
    assert!(matches!(
        medial.refine_region(
            &region,
            &RegionOptions::default()
                .with_min_spheres(1)
                .with_max_error(f64::NAN)
        ),
        Err(MedialError::InvalidParameter { .. })
    ));
}

#[test]
fn thin_parts_touching_components_and_duplicate_samples() {
    // A thin plate (1 % as thick as wide).
    let cube = shapes::cube(1.0, 4).unwrap();
    let plate = TriMesh::new(
        cube.positions()
            .iter()
            .map(|p| DVec3::new(p.x * 2.0, p.y, p.z * 0.02))
            .collect(),
        cube.triangles().to_vec(),
    )
    .unwrap();
    // Two cubes touching along a face.
    let mut positions = cube.positions().to_vec();
    positions.extend(cube.positions().iter().map(|p| *p + DVec3::X));
    let offset = cube.vertex_count() as u32;
    let mut triangles = cube.triangles().to_vec();
    triangles.extend(cube.triangles().iter().map(|t| t.map(|v| v + offset)));
    let twins = TriMesh::new(positions, triangles).unwrap();
    for (name, mesh) in [("thin plate", plate), ("touching cubes", twins)] {
        let surface = Surface::new(&mesh).unwrap();
        let mut points = samples(&mesh, 1_500);
        // Every sample twice.
        points.extend(points.clone());
        let medial = build(
            &surface,
            &points,
            &MedialOptions::default().with_target_spheres(120),
        );
        check(&mesh, &medial, name);
    }
}

#[test]
fn bad_input_gets_clear_errors() {
    // A flat open sheet: inside is meaningless.
    let sheet = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let err = Surface::new(&sheet).unwrap_err();
    assert!(matches!(err, QueryError::NoInside { .. }), "{err}");
    eprintln!("flat sheet: {err}");

    let cube = shapes::cube(1.0, 2).unwrap();
    let surface = Surface::new(&cube).unwrap();
    let params = MedialOptions::default();
    // Fewer than 4 samples, and flat samples.
    let three = [DVec3::ZERO, DVec3::X, DVec3::Y];
    assert!(matches!(
        MedialApproximation::build(&surface, &three, &params),
        Err(MedialError::TooFewSamples(_))
    ));
    let flat: Vec<DVec3> = (0..20)
        .map(|i| DVec3::new(f64::from(i % 5), f64::from(i / 5), 0.5))
        .collect();
    assert!(matches!(
        MedialApproximation::build(&surface, &flat, &params),
        Err(MedialError::TooFewSamples(_))
    ));
    // NaN.
    let mut points = samples(&cube, 200);
    points[17].y = f64::NAN;
    assert!(matches!(
        MedialApproximation::build(&surface, &points, &params),
        Err(MedialError::NonFiniteSample { index: 17 })
    ));
    // Bad parameters.
    let points = samples(&cube, 200);
    assert!(matches!(
        MedialApproximation::build(
            &surface,
            &points,
            &MedialOptions::default().with_max_error(-1.0)
        ),
        Err(MedialError::InvalidParameter { .. })
    ));
    assert!(matches!(
        MedialApproximation::build(
            &surface,
            &points,
            &MedialOptions::default().with_initial_points(2)
        ),
        Err(MedialError::InvalidParameter { .. })
    ));
}

#[test]
fn static_sampling_leaves_gaps_that_coverage_closes() {
    let mesh = shapes::torus(1.0, 0.3, 16).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points = samples(&mesh, 2_000);
    let hubbard = MedialApproximation::build_static(&surface, &points, 60, None).unwrap();
    let covered = MedialApproximation::build_static(
        &surface,
        &points,
        60,
        Some(CoverCriterion::SmallestError),
    )
    .unwrap();
    eprintln!(
        "static, 60 forming points: {} uncovered of {}",
        hubbard.uncovered_samples().len(),
        points.len()
    );
    assert!(covered.uncovered_samples().is_empty());
    check(&mesh, &covered, "static with coverage");
    assert!(
        hubbard
            .spheres()
            .iter()
            .all(|s| s.kind == SphereKind::Internal)
    );
}

#[test]
fn real_meshes_open_and_non_manifold_are_covered() {
    let Some(dir) = sphaera_tests::data_dir("real_meshes_open_and_non_manifold_are_covered") else {
        return;
    };
    for name in [
        "bunny_lowres.obj",
        "stanford-bunny.obj",
        "dragon_vrip_res4.ply",
        "robots/franka_panda/visual/finger.obj",
        "robots/kuka_iiwa/link_7.obj",
        "teapot.obj",
    ] {
        let mesh = io::load(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let surface = match Surface::new(&mesh) {
            Ok(surface) => surface,
            Err(e) => panic!("{name}: {e}"),
        };
        let points = samples(&mesh, 3_000);
        let medial = build(
            &surface,
            &points,
            &MedialOptions::default().with_target_spheres(300),
        );
        eprintln!(
            "{name}: {} spheres, worst error {:.3} % of the diagonal, {:?}",
            medial.sphere_count(),
            100.0 * medial.worst_error() / surface.diagonal(),
            medial.stats()
        );
        check(&mesh, &medial, name);
    }
}
