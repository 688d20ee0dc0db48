//! Motion of the mesh (issue 4, "Coherence and motion"; paper sections 5.2–5.3): rigid
//! poses and deformations, every answer checked against brute force on the moved mesh.

#![allow(clippy::print_stderr)] // the policy comparison reports its counts

use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::glam::{DAffine3, DQuat};
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_simplify::Hierarchy;
use sphaera_sweep::{DeformedShape, Session, SweepError, Sweeper, Tolerance, build_hierarchy};
use sphaera_tests::random::Lcg64;

/// A point of the cube `[−scale, scale]³` (x, y, z drawn in that order).
fn random_vector(rng: &mut Lcg64, scale: f64) -> DVec3 {
    DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * (2.0 * scale)
}

/// A rotation about a random axis by a random angle.
fn random_rotation(rng: &mut Lcg64) -> DQuat {
    let axis = random_vector(rng, 1.0).try_normalize().unwrap_or(DVec3::Z);
    DQuat::from_axis_angle(axis, std::f64::consts::TAU * rng.unit())
}

/// A sphere with noise (so the hierarchy is not trivially symmetric).
fn noisy_sphere() -> TriMesh {
    let sphere = shapes::sphere(1.0, 10).expect("a valid sphere");
    let mut rng = Lcg64::new(5);
    let positions: Vec<DVec3> = sphere
        .positions()
        .iter()
        .map(|p| *p * (1.0 + 0.05 * rng.unit()))
        .collect();
    TriMesh::new(positions, sphere.triangles().to_vec()).expect("same triangles")
}

/// The brute-force distance from `p` to the triangles of `mesh`'s topology at `positions`.
fn brute(mesh: &TriMesh, positions: &[DVec3], p: DVec3) -> f64 {
    mesh.triangles()
        .iter()
        .map(|t| {
            let triangle = sphaera_mesh::geometry::Triangle::new(
                positions[t[0] as usize],
                positions[t[1] as usize],
                positions[t[2] as usize],
            );
            point_triangle_distance_squared(p, &triangle)
        })
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// Checks `closest` and `closest_within` at `p` against brute force at `positions`
/// (world coordinates).
fn check(session: &mut Session<'_>, mesh: &TriMesh, positions: &[DVec3], p: DVec3) {
    let truth = brute(mesh, positions, p);
    let answer = session.closest(p).expect("a finite query");
    assert!(
        (answer.distance - truth).abs() <= 1e-9 * truth.max(1e-3),
        "closest({p}) = {} but brute force says {truth}",
        answer.distance
    );
    assert!(((answer.point - p).length() - truth).abs() <= 1e-9 * truth.max(1e-3));
    let q = p + DVec3::new(0.013, -0.007, 0.011);
    let truth = brute(mesh, positions, q);
    let bounds = session
        .closest_within(q, Tolerance::RelativeToUpper(0.05))
        .expect("a finite query");
    let slack = 1e-12 * truth.max(1.0);
    assert!(
        bounds.lower <= truth + slack && truth <= bounds.upper + slack,
        "[{}, {}] misses {truth} at {q}",
        bounds.lower,
        bounds.upper
    );
}

#[test]
fn rigid_poses_coherent_and_jumping() {
    let mesh = noisy_sphere();
    let hierarchy = build_hierarchy(&mesh).expect("a valid mesh");
    let sweeper = Sweeper::new(&hierarchy).expect("triangles");
    let mut session = sweeper.session();
    let mut rng = Lcg64::new(17);
    let queries: Vec<DVec3> = (0..6).map(|_| random_vector(&mut rng, 1.6)).collect();
    let mut rotation = DQuat::IDENTITY;
    let mut translation = DVec3::ZERO;
    for step in 0..60 {
        if step % 15 == 14 {
            // A jump.
            rotation = random_rotation(&mut rng);
            translation = random_vector(&mut rng, 3.0);
        } else {
            // A small coherent step.
            rotation = (DQuat::from_axis_angle(DVec3::new(0.3, 1.0, 0.2).normalize(), 0.02)
                * rotation)
                .normalize();
            translation += DVec3::new(0.01, 0.005, -0.004);
        }
        let pose = DAffine3::from_rotation_translation(rotation, translation);
        session.move_mesh(pose).expect("rigid");
        let positions: Vec<DVec3> = mesh
            .positions()
            .iter()
            .map(|&x| pose.transform_point3(x))
            .collect();
        for &q in &queries {
            check(&mut session, &mesh, &positions, translation + q);
        }
        // Far queries: here the mesh's own motion bounds the widening.
        check(
            &mut session,
            &mesh,
            &positions,
            translation + DVec3::new(9.0, 1.0, 0.0),
        );
    }
}

/// A smooth deformation field at phase `s`.
fn deformed(mesh: &TriMesh, s: f64) -> Vec<DVec3> {
    mesh.positions()
        .iter()
        .map(|p| {
            *p + DVec3::new(
                0.2 * (2.0 * p.y + s).sin(),
                0.15 * (3.0 * p.z - s).cos() - 0.15,
                0.3 * s * p.x * p.y,
            )
        })
        .collect()
}

/// Positions at time `t` between two lists, as [`DeformedShape::between`] computes them.
fn lerp(a: &[DVec3], b: &[DVec3], t: f64) -> Vec<DVec3> {
    a.iter().zip(b).map(|(&p, &q)| p + (q - p) * t).collect()
}

#[test]
fn keyframes_interpolated_are_exact() {
    let mesh = noisy_sphere();
    let hierarchy = build_hierarchy(&mesh).expect("a valid mesh");
    let sweeper = Sweeper::new(&hierarchy).expect("triangles");
    let keys: Vec<Vec<DVec3>> = (0..3)
        .map(|k| deformed(&mesh, 0.5 * f64::from(k)))
        .collect();
    let frames: Vec<Hierarchy> = keys
        .iter()
        .map(|p| hierarchy.replay(p).expect("same topology"))
        .collect();
    let mut session = sweeper.session();
    let mut rng = Lcg64::new(23);
    let queries: Vec<DVec3> = (0..5).map(|_| random_vector(&mut rng, 1.5)).collect();
    for k in 0..2 {
        for step in 0..=8 {
            let t = f64::from(step) / 8.0;
            let shape = DeformedShape::between(&frames[k], &frames[k + 1], t).expect("same tables");
            session.deform(shape).expect("same tables");
            let positions = lerp(&keys[k], &keys[k + 1], t);
            for &q in &queries {
                check(&mut session, &mesh, &positions, q);
            }
        }
    }
    // With a pose on top.
    let pose =
        DAffine3::from_rotation_translation(random_rotation(&mut rng), DVec3::new(1.0, 2.0, 3.0));
    session.move_mesh(pose).expect("rigid");
    let world: Vec<DVec3> = keys[2].iter().map(|&x| pose.transform_point3(x)).collect();
    for &q in &queries {
        check(&mut session, &mesh, &world, pose.transform_point3(q));
    }
}

#[test]
fn inflated_radii_cover_moves_within_the_bounds() {
    let mesh = noisy_sphere();
    let hierarchy = build_hierarchy(&mesh).expect("a valid mesh");
    let sweeper = Sweeper::new(&hierarchy).expect("triangles");
    let end = deformed(&mesh, 0.4);
    let bound: Vec<f64> = mesh
        .positions()
        .iter()
        .zip(&end)
        .map(|(p, q)| (*q - *p).length() * 1.5)
        .collect();
    let mut session = sweeper.session();
    session
        .deform(DeformedShape::inflated(&hierarchy, &bound).expect("valid bounds"))
        .expect("same tables");
    let mut rng = Lcg64::new(29);
    let queries: Vec<DVec3> = (0..5).map(|_| random_vector(&mut rng, 1.5)).collect();
    for step in 0..=10 {
        let positions = lerp(mesh.positions(), &end, f64::from(step) / 10.0);
        session
            .move_vertices(&positions)
            .expect("within the bounds");
        for &q in &queries {
            check(&mut session, &mesh, &positions, q);
        }
    }
}

#[test]
fn stale_widening_against_reset_on_an_animation() {
    // Not a timing test: counts of distance evaluations and splits, deterministic.
    let mesh = noisy_sphere();
    let hierarchy = build_hierarchy(&mesh).expect("a valid mesh");
    let sweeper = Sweeper::new(&hierarchy).expect("triangles");
    let keys: Vec<Vec<DVec3>> = (0..2)
        .map(|k| deformed(&mesh, 0.3 * f64::from(k)))
        .collect();
    let frames: Vec<Hierarchy> = keys
        .iter()
        .map(|p| hierarchy.replay(p).expect("same topology"))
        .collect();
    let mut counts = Vec::new();
    for reset in [false, true] {
        let mut session = sweeper.session();
        for step in 0..=40 {
            let t = f64::from(step) / 40.0;
            session
                .deform(DeformedShape::between(&frames[0], &frames[1], t).expect("same tables"))
                .expect("same tables");
            if reset {
                session.reset();
            }
            let positions = lerp(&keys[0], &keys[1], t);
            let p = DVec3::new(1.4 * t.cos(), 1.4 * t.sin(), 0.2);
            let truth = brute(&mesh, &positions, p);
            let answer = session.closest(p).expect("finite");
            assert!((answer.distance - truth).abs() <= 1e-9 * truth.max(1e-3));
        }
        let stats = session.stats();
        counts.push((stats.distance_evaluations, stats.splits));
    }
    eprintln!(
        "41 frames: widen (evaluations, splits) = {:?}, reset = {:?}",
        counts[0], counts[1]
    );
}

#[test]
fn failure_cases() {
    let mesh = noisy_sphere();
    let hierarchy = build_hierarchy(&mesh).expect("a valid mesh");
    let sweeper = Sweeper::new(&hierarchy).expect("triangles");
    let mut session = sweeper.session();
    let p = DVec3::new(0.0, 0.0, 3.0);
    let before = session.closest(p).expect("finite");

    // Non-rigid poses and NaN.
    for bad in [
        DAffine3::from_scale(DVec3::new(1.0, 1.0, 1.01)),
        DAffine3::from_cols(DVec3::X, DVec3::new(0.1, 1.0, 0.0), DVec3::Z, DVec3::ZERO),
        DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)),
    ] {
        assert!(matches!(
            session.move_mesh(bad),
            Err(SweepError::NotRigid { .. })
        ));
    }
    let mut nan = DAffine3::IDENTITY;
    nan.matrix3.x_axis.x = f64::NAN;
    assert!(matches!(
        session.move_mesh(nan),
        Err(SweepError::NonFinitePose)
    ));
    assert_eq!(session.pose(), DAffine3::IDENTITY);

    // A hierarchy with other tables (built again from the same mesh).
    let other = build_hierarchy(&mesh).expect("a valid mesh");
    assert!(matches!(
        session.deform(DeformedShape::keyframe(&other)),
        Err(SweepError::ForeignHierarchy)
    ));
    assert!(matches!(
        DeformedShape::between(&hierarchy, &other, 0.5),
        Err(SweepError::ForeignHierarchy)
    ));
    for t in [f64::NAN, -0.1, 1.1] {
        assert!(matches!(
            DeformedShape::between(&hierarchy, &hierarchy, t),
            Err(SweepError::InvalidParameter { name: "t", .. })
        ));
    }

    // Wrong lengths and bad values.
    let n = mesh.vertex_count();
    assert!(matches!(
        DeformedShape::inflated(&hierarchy, &vec![0.1; n - 1]),
        Err(SweepError::LengthMismatch { expected, .. }) if expected == n
    ));
    let mut nan_bound = vec![0.1; n];
    nan_bound[3] = f64::NAN;
    assert!(matches!(
        DeformedShape::inflated(&hierarchy, &nan_bound),
        Err(SweepError::InvalidVertexValue { index: 3, .. })
    ));
    assert!(matches!(
        session.move_vertices(&mesh.positions()[1..]),
        Err(SweepError::LengthMismatch { .. })
    ));
    let mut moved = mesh.positions().to_vec();
    moved[2].x += 0.1; // the rest shape allows no motion
    assert!(matches!(
        session.move_vertices(&moved),
        Err(SweepError::InvalidVertexValue { index: 2, .. })
    ));
    moved[2].x = f64::NAN;
    assert!(matches!(
        session.move_vertices(&moved),
        Err(SweepError::InvalidVertexValue { index: 2, .. })
    ));
    assert!(hierarchy.replay(&moved).is_err());

    // The session is unchanged by all of this.
    assert!(session.deformed_shape().is_none());
    assert_eq!(session.closest(p).expect("finite"), before);
}
