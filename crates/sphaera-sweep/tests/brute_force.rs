//! Every query against brute force (every input triangle), on procedural shapes and
//! random points.

// The coherence test prints its counters.
#![allow(clippy::print_stderr)]

use proptest::prelude::*;
use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_simplify::Hierarchy;
use sphaera_sweep::{Session, SessionOptions, Sweeper, Tolerance, build_hierarchy};
use sphaera_tests::brute;

/// A few shapes with their hierarchies (built once).
fn fixtures() -> &'static [(TriMesh, Hierarchy)] {
    use std::sync::OnceLock;
    static FIXTURES: OnceLock<Vec<(TriMesh, Hierarchy)>> = OnceLock::new();
    FIXTURES.get_or_init(|| {
        let meshes = vec![
            shapes::sphere(1.0, 12).expect("sphere"),
            shapes::torus(1.0, 0.3, 16).expect("torus"),
            shapes::cube(1.0, 5).expect("cube"),
            shapes::s_tube(0.2, 1.0, 12).expect("tube"),
        ];
        meshes
            .into_iter()
            .map(|m| {
                let h = build_hierarchy(&m).expect("hierarchy");
                (m, h)
            })
            .collect()
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    (-3.0..3.0_f64, -3.0..3.0_f64, -3.0..3.0_f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// Checks one exact answer of `session` against brute force.
fn check_closest(mesh: &TriMesh, session: &mut Session<'_>, p: DVec3) {
    let expected = brute::sorted_distances(mesh, p)[0];
    let answer = session.closest(p).expect("finite query");
    assert!(
        brute::close(answer.distance, expected),
        "closest({p}) = {} but brute force says {expected}",
        answer.distance
    );
    assert!(brute::close((answer.point - p).length(), answer.distance));
    let triangle = mesh.triangle(answer.triangle as usize).expect("in range");
    let on = point_triangle_distance_squared(answer.point, &triangle).sqrt();
    assert!(on <= 1e-9, "the point is {on} off its triangle");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    #[test]
    fn closest_matches_brute_force_fresh_and_in_sessions(
        shape in 0..4_usize,
        points in prop::collection::vec(point(), 1..12),
        step in 0.0..0.2_f64,
    ) {
        let (mesh, hierarchy) = &fixtures()[shape];
        let sweeper = Sweeper::new(hierarchy).expect("non-empty");
        // Both exact engines: the tree of input triangles and the paper's refinement.
        for by_tree in [true, false] {
            let options = SessionOptions::default().with_exact_by_tree(by_tree);
            // Independent queries, one coherent session, and a session that never resets.
            let mut session = sweeper.session_with(&options);
            let mut sticky = sweeper.session_with(&options.with_max_triangles(usize::MAX).with_jump_factor(f64::INFINITY));
            for &p in &points {
                check_closest(mesh, &mut sweeper.session_with(&options), p);
                check_closest(mesh, &mut session, p);
                check_closest(mesh, &mut sticky, p);
                // A small step from there (the constant-time case or a little refinement).
                let q = p + DVec3::new(step, -0.5 * step, 0.25 * step);
                check_closest(mesh, &mut session, q);
                check_closest(mesh, &mut sticky, q);
            }
            prop_assert_eq!(session.stats().tree_queries > 0, by_tree);
        }
    }

    #[test]
    fn bounds_are_certified(
        shape in 0..4_usize,
        p in point(),
        tolerance in 0.0..0.5_f64,
        budget in 0..40_usize,
    ) {
        let (mesh, hierarchy) = &fixtures()[shape];
        let sweeper = Sweeper::new(hierarchy).expect("non-empty");
        let truth = brute::sorted_distances(mesh, p)[0];
        // Both engines: the tree of input triangles and the paper's refinement.
        for by_tree in [true, false] {
            let mut session =
                sweeper.session_with(&SessionOptions::default().with_exact_by_tree(by_tree));
            let bounds = session.closest_within(p, Tolerance::Absolute(tolerance)).expect("ok");
            prop_assert!(bounds.lower <= truth + 1e-12 && truth <= bounds.upper + 1e-12,
                "{bounds:?} misses {truth}");
            prop_assert!(bounds.gap() <= tolerance + 1e-12 || bounds.closest.is_some());
            if let Some(c) = bounds.closest {
                prop_assert!((c.distance - truth).abs() <= 1e-12 * (1.0 + truth));
            }
            let bounds = session.closest_with_budget(p, budget).expect("ok");
            prop_assert!(bounds.lower <= truth + 1e-12 && truth <= bounds.upper + 1e-12,
                "{bounds:?} misses {truth}");
            prop_assert!(bounds.splits <= budget);
            let relative = session.closest_within(p, Tolerance::RelativeToUpper(0.1)).expect("ok");
            prop_assert!(relative.lower <= truth + 1e-12 && truth <= relative.upper + 1e-12);
            prop_assert!(relative.gap() <= 0.1 * relative.upper + 1e-12 || relative.closest.is_some());
        }
    }

    #[test]
    fn k_closest_and_within_match_brute_force(
        shape in 0..4_usize,
        p in point(),
        k in 1..30_usize,
        radius in 0.0..1.0_f64,
    ) {
        let (mesh, hierarchy) = &fixtures()[shape];
        let sweeper = Sweeper::new(hierarchy).expect("non-empty");
        let mut session = sweeper.session();
        let truth = brute::sorted_distances(mesh, p);
        let near = session.k_closest(p, k).expect("ok");
        prop_assert_eq!(near.len(), k.min(truth.len()));
        for (answer, expected) in near.iter().zip(&truth) {
            prop_assert!(brute::close(answer.distance, *expected), "{} vs {}", answer.distance, expected);
        }
        let mut triangles: Vec<u32> = near.iter().map(|a| a.triangle).collect();
        triangles.sort_unstable();
        triangles.dedup();
        prop_assert_eq!(triangles.len(), near.len());
        // The session still answers single queries correctly afterwards.
        check_closest(mesh, &mut session, p);
        let limit = truth[0] + radius;
        let inside = session.within(p, limit).expect("ok");
        let expected = truth.iter().filter(|&&d| d <= limit).count();
        // Ties at the limit may round either way.
        let borderline = truth.iter().filter(|&&d| (d - limit).abs() <= 1e-9).count();
        prop_assert!(inside.len() + borderline >= expected && inside.len() <= expected + borderline,
            "{} within {limit}, brute force {expected}", inside.len());
        prop_assert!(inside.iter().all(|a| a.distance <= limit));
    }
}

/// The paper's exact path (section 5.1): coherence saves refinement.
#[test]
fn a_coherent_path_refines_far_less_than_fresh_queries() {
    let sphere = shapes::sphere(1.0, 24).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let paper = SessionOptions::default().with_exact_by_tree(false);
    let mut session = sweeper.session_with(&paper);
    for i in 0..100 {
        let angle = f64::from(i) * 0.01;
        let p = 2.0 * DVec3::new(angle.cos(), angle.sin(), 0.1);
        check_closest(&sphere, &mut session, p);
    }
    let coherent = session.stats();
    let mut fresh_splits = 0;
    for i in 0..100 {
        let angle = f64::from(i) * 0.01;
        let p = 2.0 * DVec3::new(angle.cos(), angle.sin(), 0.1);
        let mut session = sweeper.session_with(&paper);
        check_closest(&sphere, &mut session, p);
        fresh_splits += session.stats().splits;
    }
    eprintln!("coherent {coherent:?}, fresh splits {fresh_splits}");
    assert!(
        coherent.splits * 4 < fresh_splits,
        "coherence saves little: {coherent:?} vs {fresh_splits}"
    );
}
