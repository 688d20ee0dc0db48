//! The burst reducer: every point stays covered, at most the target count, deterministic;
//! on random clouds (proptest) and on real medial candidates.

use proptest::prelude::*;
use sphaera_medial::{MedialApproximation, MedialOptions, Surface};
use sphaera_mesh::{DVec3, Sphere, TriMesh, shapes};
use sphaera_query::sampling;
use sphaera_spheretree::reduce::{Candidate, FittedSphere, ReductionInput, burst, merge, worst};

/// Every point lies in a sphere that lists it, and every listed point is inside.
fn assert_covers(points: &[DVec3], spheres: &[FittedSphere]) {
    for i in 0..points.len() {
        assert!(
            spheres.iter().any(|s| s.covers.contains(&(i as u32))),
            "point {i} is listed by no sphere"
        );
    }
    for s in spheres {
        assert!(
            s.covers.windows(2).all(|w| w[0] < w[1]),
            "covers not ascending"
        );
        for &c in &s.covers {
            let p = points[c as usize];
            assert!(
                s.sphere.contains_point(p, 1e-9 * s.sphere.radius.max(1.0)),
                "listed point {c} is outside its sphere"
            );
        }
    }
}

/// Candidates around random points: each covers the points within its radius.
fn cover_candidates(points: &[DVec3], centers: &[(DVec3, f64)]) -> Vec<Candidate> {
    let mut candidates: Vec<Candidate> = centers
        .iter()
        .map(|&(c, r)| {
            let covers: Vec<u32> = (0..points.len() as u32)
                .filter(|&i| points[i as usize].distance(c) <= r)
                .collect();
            Candidate {
                sphere: Sphere::new(c, r),
                covers,
            }
        })
        .filter(|c| !c.covers.is_empty())
        .collect();
    // Points no candidate covers get a small sphere of their own.
    for (i, &p) in points.iter().enumerate() {
        if !candidates.iter().any(|c| c.covers.contains(&(i as u32))) {
            candidates.push(Candidate {
                sphere: Sphere::new(p, 0.05),
                covers: vec![i as u32],
            });
        }
    }
    candidates
}

fn unit_sphere() -> (TriMesh, Surface) {
    let mesh = shapes::sphere(1.0, 10).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    (mesh, surface)
}

fn point() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    #[test]
    fn burst_keeps_every_point_covered(
        points in prop::collection::vec(point(), 1..60),
        centers in prop::collection::vec((point(), 0.05..0.8f64), 1..40),
        target in 1usize..10,
    ) {
        let (_, surface) = unit_sphere();
        let candidates = cover_candidates(&points, &centers);
        let input = ReductionInput { surface: &surface, points: &points, candidates: &candidates };
        let reduced = burst(&input, target).unwrap();
        prop_assert!(!reduced.is_empty());
        prop_assert!(reduced.len() <= target.max(1));
        prop_assert!(reduced.len() <= candidates.len());
        assert_covers(&points, &reduced);
        // Deterministic.
        prop_assert_eq!(burst(&input, target).unwrap(), reduced);
    }
}

#[test]
fn target_zero_and_uncovered_points_are_errors() {
    let (_, surface) = unit_sphere();
    let points = [DVec3::ZERO, DVec3::X];
    let candidates = [Candidate {
        sphere: Sphere::new(DVec3::ZERO, 0.1),
        covers: vec![0],
    }];
    let input = ReductionInput {
        surface: &surface,
        points: &points,
        candidates: &candidates,
    };
    assert!(burst(&input, 0).is_err());
    assert!(burst(&input, 3).is_err());
}

/// Real medial candidates of a region: the surface samples of a capsule (a robot link).
#[test]
fn burst_reduces_a_capsule_medial_set() {
    let mesh = shapes::capsule(0.3, 1.5, 16).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let points: Vec<DVec3> = sampling::poisson_disk(&mesh, 1_000, 3)
        .unwrap()
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    let medial = MedialApproximation::build(
        &surface,
        &points,
        &MedialOptions::default().with_target_spheres(150),
    )
    .unwrap();
    let candidates: Vec<Candidate> = medial
        .spheres()
        .iter()
        .map(|m| Candidate {
            sphere: Sphere::new(m.center, m.radius),
            covers: m.covers.clone(),
        })
        .filter(|c| !c.covers.is_empty())
        .collect();
    assert!(candidates.len() > 100);
    let input = ReductionInput {
        surface: &surface,
        points: &points,
        candidates: &candidates,
    };
    for target in [1, 3, 8] {
        let reduced = burst(&input, target).unwrap();
        assert!(!reduced.is_empty() && reduced.len() <= target);
        assert_covers(&points, &reduced);
        assert_eq!(burst(&input, target).unwrap(), reduced);
        // A capsule is a tube: a few spheres along the axis fit it well; the burst's
        // eq. 2 error stays within a small multiple of merge's.
        let merged = merge(&input, target).unwrap();
        assert!(
            worst(&reduced) <= 2.0 * worst(&merged) + 1e-9,
            "target {target}: burst {} vs merge {}",
            worst(&reduced),
            worst(&merged)
        );
    }
}
