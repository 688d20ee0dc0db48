//! Fit evaluation: certified intervals against brute force, closed forms, coverage against
//! brute force, errors, and the real low-res bunny.

#![allow(clippy::print_stderr)] // the measurements are printed

use std::sync::OnceLock;
use std::time::Instant;

use proptest::prelude::*;
use sphaera_mesh::{Length, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_query::sampling;
use sphaera_spheretree::evaluate::{
    EvaluationOptions, coverage, evaluate_set, sphere_error, sphere_errors,
};
use sphaera_spheretree::{DVec3, Sphere, SphereTreeError};

/// `n` nearly uniform unit directions (Fibonacci sphere).
fn fibonacci(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let a = golden * i as f64;
            DVec3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect()
}

/// `max f` over the given directions of the sphere: a lower estimate of its error.
fn sampled_error(surface: &Surface, sphere: &Sphere, directions: &[DVec3]) -> f64 {
    directions
        .iter()
        .map(|u| {
            let x = sphere.center + sphere.radius * *u;
            if surface.is_inside(x) {
                0.0
            } else {
                surface.closest(x).unwrap().distance
            }
        })
        .fold(0.0, f64::max)
}

struct Shape {
    mesh: TriMesh,
    surface: Surface,
}

fn shape(i: usize) -> &'static Shape {
    static SHAPES: OnceLock<Vec<Shape>> = OnceLock::new();
    let all = SHAPES.get_or_init(|| {
        [
            shapes::sphere(1.0, 16).unwrap(),
            shapes::cube(2.0, 2).unwrap(),
            shapes::capsule(0.5, 1.5, 16).unwrap(),
        ]
        .into_iter()
        .map(|mesh| {
            let surface = Surface::new(&mesh).unwrap();
            Shape { mesh, surface }
        })
        .collect()
    });
    &all[i % all.len()]
}

fn directions() -> &'static [DVec3] {
    static DIRECTIONS: OnceLock<Vec<DVec3>> = OnceLock::new();
    DIRECTIONS.get_or_init(|| fibonacci(20_000))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(24)))]

    /// `lower` is a true value of `f`, the dense estimate is `≤` the true maximum, and
    /// the true maximum is `≤ upper`; so `estimate ≤ upper` and, the estimate being within
    /// the sampling's Lipschitz gap of the maximum, `lower ≤ estimate + gap`.
    #[test]
    fn interval_contains_the_dense_estimate(
        which in 0_usize..3,
        cx in -1.5..1.5_f64, cy in -1.5..1.5_f64, cz in -1.5..1.5_f64,
        radius in 0.05..1.2_f64,
    ) {
        let s = shape(which);
        let sphere = Sphere::new(DVec3::new(cx, cy, cz), radius);
        let options = EvaluationOptions::default();
        let tolerance = options.tolerance_for(s.surface.diagonal());
        let fit = sphere_error(&s.surface, &sphere, &options).unwrap();
        let estimate = sampled_error(&s.surface, &sphere, directions());
        // Largest angular gap of 20,000 Fibonacci directions: below 0.03 rad.
        let gap = 0.03 * radius;
        prop_assert!(fit.lower <= fit.upper);
        prop_assert!(estimate <= fit.upper + 1e-9, "estimate {} > upper {}", estimate, fit.upper);
        prop_assert!(fit.lower <= estimate + gap, "lower {} > estimate {} + {}", fit.lower, estimate, gap);
        if fit.converged {
            prop_assert!(fit.upper - fit.lower <= tolerance * (1.0 + 1e-9));
        }
        if let Some(w) = fit.witness {
            prop_assert!((w.distance(sphere.center) - radius).abs() <= 1e-9);
            prop_assert!(!s.surface.is_inside(w));
            prop_assert!((s.surface.closest(w).unwrap().distance - fit.lower).abs() <= 1e-12);
        }
    }
}

#[test]
fn concentric_sphere_error_is_between_the_circumradius_and_inradius_gaps() {
    // The unit-sphere mesh is inscribed: every vertex at 1, the faces no closer than the
    // inradius. A ray from the centre leaves the polyhedron between the two, so the error
    // of a concentric sphere of radius R lies in [R − 1, R − inradius].
    let s = shape(0);
    let inradius = s.surface.closest(DVec3::ZERO).unwrap().distance;
    let options = EvaluationOptions::default();
    let tolerance = options.tolerance_for(s.surface.diagonal());
    for big in [1.2, 2.0] {
        let fit = sphere_error(&s.surface, &Sphere::new(DVec3::ZERO, big), &options).unwrap();
        eprintln!(
            "concentric R = {big}: [{:.6}, {:.6}], {} patches, converged {}",
            fit.lower, fit.upper, fit.patches, fit.converged
        );
        assert!(fit.lower >= big - 1.0 - tolerance, "{fit:?}");
        // `upper` may exceed the true error by the tolerance.
        assert!(fit.upper <= big - inradius + tolerance, "{fit:?}");
        assert!(fit.converged);
    }
}

#[test]
fn sphere_inside_has_no_error() {
    for (which, sphere) in [
        (0, Sphere::new(DVec3::new(0.1, 0.0, 0.0), 0.8)),
        (1, Sphere::new(DVec3::ZERO, 0.99)),
        (2, Sphere::new(DVec3::new(0.0, 0.0, 0.7), 0.45)),
        (1, Sphere::new(DVec3::new(0.5, 0.5, 0.5), 0.0)),
    ] {
        let surface = &shape(which).surface;
        let options = EvaluationOptions::default();
        let fit = sphere_error(surface, &sphere, &options).unwrap();
        assert!(fit.converged);
        // The search stops as soon as the interval is within the tolerance.
        assert!(fit.lower <= 0.0, "{sphere:?}: {fit:?}");
        assert!(
            fit.upper <= options.tolerance_for(surface.diagonal()),
            "{sphere:?}: {fit:?}"
        );
        assert_eq!(fit.witness, None);
    }
}

#[test]
fn sphere_outside_error_is_its_farthest_point() {
    let options = EvaluationOptions::default();
    // The cube [-1, 1]³ and a sphere beside the face x = 1: f(x) = x − 1 on it.
    let cube = &shape(1).surface;
    let tolerance = options.tolerance_for(cube.diagonal());
    let fit = sphere_error(cube, &Sphere::new(DVec3::new(3.0, 0.0, 0.0), 0.5), &options).unwrap();
    assert!(fit.converged);
    assert!(
        fit.lower <= 2.5 + 1e-12 && 2.5 <= fit.upper + 1e-12,
        "{fit:?}"
    );
    assert!(fit.upper - fit.lower <= tolerance);
    // D = 1.5 from the object, radius 0.5: D + 2r = 2.5.
    // The unit-sphere mesh: f(x) ∈ [|x| − 1, |x| − inradius], largest at |x| = |c| + r.
    let ball = &shape(0).surface;
    let inradius = ball.closest(DVec3::ZERO).unwrap().distance;
    let center = DVec3::new(1.0, 2.0, -1.5);
    let radius = 0.4;
    let far = center.length() + radius;
    let fit = sphere_error(ball, &Sphere::new(center, radius), &options).unwrap();
    assert!(fit.converged);
    assert!(fit.lower >= far - 1.0 - tolerance, "{fit:?}");
    assert!(fit.upper <= far - inradius + tolerance, "{fit:?}");
}

#[test]
fn poking_spheres_of_the_cube_have_exact_errors() {
    let cube = &shape(1).surface;
    let options = EvaluationOptions::default();
    let tolerance = options.tolerance_for(cube.diagonal());
    for (sphere, exact) in [
        // Through the top face by 0.5.
        (Sphere::new(DVec3::new(0.0, 0.0, 0.5), 1.0), 0.5),
        // Centred on a corner: the outside points are within 0.3 of the corner, and the
        // point along the diagonal is exactly 0.3 away.
        (Sphere::new(DVec3::ONE, 0.3), 0.3),
        // Centred on an edge.
        (Sphere::new(DVec3::new(1.0, 1.0, 0.0), 0.2), 0.2),
    ] {
        let fit = sphere_error(cube, &sphere, &options).unwrap();
        assert!(fit.converged, "{sphere:?}: {fit:?}");
        assert!(
            fit.lower <= exact + 1e-12 && exact <= fit.upper + 1e-12,
            "{sphere:?}: {fit:?}"
        );
        assert!(fit.upper - fit.lower <= tolerance);
    }
}

#[test]
fn budget_exhaustion_keeps_a_valid_interval() {
    let s = shape(0);
    let sphere = Sphere::new(DVec3::ZERO, 1.3);
    let options = EvaluationOptions::default()
        .with_tolerance(Length::Absolute(1e-9))
        .with_max_patches(200);
    let fit = sphere_error(&s.surface, &sphere, &options).unwrap();
    assert!(!fit.converged);
    assert!(fit.patches <= 200);
    let estimate = sampled_error(&s.surface, &sphere, directions());
    assert!(
        fit.lower <= estimate + 0.03 * 1.3 && estimate <= fit.upper,
        "{fit:?} vs {estimate}"
    );
}

#[test]
fn results_are_deterministic() {
    let s = shape(2);
    let spheres: Vec<Sphere> = (0..16)
        .map(|i| {
            let t = f64::from(i);
            Sphere::new(
                DVec3::new(0.3 * t.sin(), 0.3 * t.cos(), 0.1 * t - 0.8),
                0.3 + 0.02 * t,
            )
        })
        .collect();
    let options = EvaluationOptions::default().with_coverage_samples(3_000);
    let a = evaluate_set(&s.surface, &spheres, &options).unwrap();
    let b = evaluate_set(&s.surface, &spheres, &options).unwrap();
    assert_eq!(a.fits, b.fits);
    assert_eq!(a.coverage, b.coverage);
    let one_by_one: Vec<_> = spheres
        .iter()
        .map(|sp| sphere_error(&s.surface, sp, &options).unwrap())
        .collect();
    assert_eq!(a.fits, one_by_one);
}

/// Screening keeps the worst error's interval as tight as the full evaluation (the same
/// worst sphere, an interval within the tolerance and overlapping the full one), and
/// every sphere's interval stays valid (it contains the full evaluation's).
#[test]
fn screening_keeps_the_worst_interval() {
    let s = shape(2);
    let spheres: Vec<Sphere> = (0..24)
        .map(|i| {
            let t = f64::from(i);
            Sphere::new(
                DVec3::new(0.3 * t.sin(), 0.3 * t.cos(), 0.07 * t - 0.8),
                0.25 + 0.015 * t,
            )
        })
        .collect();
    let options = EvaluationOptions::default().with_coverage_samples(2_000);
    let full = evaluate_set(&s.surface, &spheres, &options).unwrap();
    let screened = evaluate_set(&s.surface, &spheres, &options.with_screening(true)).unwrap();
    assert!(screened.worst_upper - screened.worst_lower <= screened.tolerance);
    assert!(screened.worst_lower <= full.worst_upper && full.worst_lower <= screened.worst_upper);
    for (a, b) in full.fits.iter().zip(&screened.fits) {
        assert!(b.lower <= a.upper && a.lower <= b.upper, "{a:?} {b:?}");
    }
    assert!(screened.mean_error >= full.mean_error - full.tolerance);
    let patches =
        |e: &sphaera_spheretree::SetEvaluation| e.fits.iter().map(|f| f.patches).sum::<usize>();
    assert!(patches(&screened) <= patches(&full), "screening costs more");
}

#[test]
fn set_statistics_follow_the_fits() {
    let s = shape(0);
    let spheres = [
        Sphere::new(DVec3::ZERO, 0.5),
        Sphere::new(DVec3::new(0.0, 0.0, 1.0), 0.3),
        Sphere::new(DVec3::new(1.0, 0.0, 0.0), 0.2),
    ];
    let options = EvaluationOptions::default().with_coverage_samples(2_000);
    let set = evaluate_set(&s.surface, &spheres, &options).unwrap();
    assert_eq!(set.sphere_count, 3);
    assert_eq!(set.worst_index, 1);
    let uppers: Vec<f64> = set.fits.iter().map(|f| f.upper).collect();
    let mean = uppers.iter().sum::<f64>() / 3.0;
    let variance = uppers.iter().map(|u| (u - mean).powi(2)).sum::<f64>() / 3.0;
    assert!((set.mean_error - mean).abs() <= 1e-15);
    assert!((set.error_variance - variance).abs() <= 1e-15);
    assert!((set.worst_upper - uppers[1]).abs() <= 0.0);
    assert!(set.worst_lower <= set.worst_upper);
    assert!(set.converged);
}

#[test]
fn coverage_matches_brute_force() {
    let s = shape(2);
    let samples = 4_000;
    for (seed, spheres) in [
        (1, vec![Sphere::new(DVec3::new(0.0, 0.0, 0.5), 0.8)]),
        (
            2,
            (0..40)
                .map(|i| {
                    let t = f64::from(i);
                    Sphere::new(
                        DVec3::new(0.5 * (1.7 * t).sin(), 0.5 * (1.3 * t).cos(), 0.06 * t - 1.2),
                        0.1 + 0.2 * (0.7 * t).sin().abs(),
                    )
                })
                .collect(),
        ),
    ] {
        let options = EvaluationOptions::default()
            .with_coverage_samples(samples)
            .with_seed(seed);
        let cover = coverage(&s.mesh, &spheres, &options).unwrap();
        let points = sampling::random(&s.mesh, samples, seed).unwrap();
        let gaps: Vec<f64> = points
            .iter()
            .map(|p| {
                spheres
                    .iter()
                    .map(|sp| p.position.distance(sp.center) - sp.radius)
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let uncovered = gaps.iter().filter(|g| **g > 0.0).count();
        let largest = gaps.iter().copied().fold(0.0, f64::max);
        assert_eq!(cover.samples, samples);
        assert_eq!(cover.uncovered, uncovered);
        assert!((cover.uncovered_fraction - uncovered as f64 / samples as f64).abs() <= 0.0);
        assert!((cover.largest_gap - largest).abs() <= 0.0);
        assert!(uncovered > 0 && uncovered < samples, "{uncovered}");
    }
}

#[test]
fn invalid_input_is_reported() {
    let s = shape(0);
    let options = EvaluationOptions::default();
    let good = Sphere::new(DVec3::ZERO, 1.0);
    for bad in [
        Sphere::new(DVec3::ZERO, f64::NAN),
        Sphere::new(DVec3::ZERO, -0.1),
        Sphere::new(DVec3::new(f64::INFINITY, 0.0, 0.0), 1.0),
    ] {
        assert!(matches!(
            sphere_errors(&s.surface, &[good, good, bad], &options),
            Err(SphereTreeError::InvalidSphere { index: 2 })
        ));
        assert!(matches!(
            evaluate_set(&s.surface, &[bad, good], &options),
            Err(SphereTreeError::InvalidSphere { index: 0 })
        ));
        assert!(matches!(
            sphere_error(&s.surface, &bad, &options),
            Err(SphereTreeError::InvalidSphere { index: 0 })
        ));
    }
    assert!(matches!(
        evaluate_set(&s.surface, &[], &options),
        Err(SphereTreeError::EmptySphereSet)
    ));
    assert!(matches!(
        coverage(&s.mesh, &[], &options),
        Err(SphereTreeError::EmptySphereSet)
    ));
    for bad in [
        options.with_tolerance(Length::Absolute(0.0)),
        options.with_tolerance(Length::Absolute(f64::NAN)),
        options.with_tolerance(Length::RelativeToDiagonal(-1.0)),
        options.with_max_patches(3),
        options.with_coverage_samples(0),
    ] {
        assert!(matches!(
            evaluate_set(&s.surface, &[good], &bad),
            Err(SphereTreeError::InvalidParameter { .. })
        ));
    }
    // Refused by the evaluation's own cap (`MAX_COVERAGE_SAMPLES`, the sampler's) before
    // the sampler is asked, naming the option.
    assert!(matches!(
        coverage(&s.mesh, &[good], &options.with_coverage_samples(usize::MAX)),
        Err(SphereTreeError::InvalidParameter {
            name: "coverage_samples",
            ..
        })
    ));
}

/// Spheres like a sphere-tree's deeper levels: centred `depth` below random surface
/// points, each poking out by `poke` (both ranges in fractions of the diagonal).
fn poking_spheres(
    mesh: &TriMesh,
    count: usize,
    seed: u64,
    depth: (f64, f64),
    poke: (f64, f64),
) -> Vec<Sphere> {
    let diagonal = mesh.bounding_box_diagonal();
    sampling::random(mesh, count, seed)
        .unwrap()
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let t = i as f64;
            let d = diagonal * (depth.0 + (depth.1 - depth.0) * (0.5 + 0.5 * (1.7 * t).sin()));
            let p = diagonal * (poke.0 + (poke.1 - poke.0) * (0.5 + 0.5 * (2.3 * t).cos()));
            Sphere::new(s.position - d * s.normal, d + p)
        })
        .collect()
}

#[test]
fn bunny_fixed_sampling_under_estimates_the_certified_error() {
    let Some(dir) = sphaera_tests::data_dir("bunny_fixed_sampling_under_estimates") else {
        return;
    };
    let mesh = sphaera_io::load(dir.join("bunny_lowres.obj")).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let diagonal = surface.diagonal();
    // Shallow caps (the sphere pokes out by a third of its radius) and narrow caps (by a
    // tenth or less, as the tight spheres of a good tree do).
    for (name, depth, poke) in [
        ("wide caps", (0.01, 0.05), (0.005, 0.025)),
        ("narrow caps", (0.03, 0.08), (0.001, 0.008)),
    ] {
        let spheres = poking_spheres(&mesh, 24, 11, depth, poke);
        let options = EvaluationOptions::default().with_coverage_samples(20_000);
        let start = Instant::now();
        let set = evaluate_set(&surface, &spheres, &options).unwrap();
        let elapsed = start.elapsed();
        assert!(set.converged);
        let fixed = fibonacci(48);
        let mut ratios = Vec::new();
        for (sphere, fit) in spheres.iter().zip(&set.fits) {
            let sampled = sampled_error(&surface, sphere, &fixed);
            assert!(sampled <= fit.upper + 1e-12);
            assert!(fit.upper - fit.lower <= set.tolerance * (1.0 + 1e-9));
            if fit.lower > 0.0 {
                ratios.push(1.0 - sampled / fit.lower);
            }
        }
        ratios.sort_by(f64::total_cmp);
        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
        let patches: usize = set.fits.iter().map(|f| f.patches).sum();
        eprintln!(
            "bunny_lowres, {} spheres ({name}): 48 fixed directions under-estimate the \
             certified error by {:.1} % on average (median {:.1} %, max {:.1} %); worst error \
             {:.3} % of the diagonal [{:.5}, {:.5}]; {:.1} patches per sphere; {:.2?}",
            spheres.len(),
            100.0 * mean,
            100.0 * ratios[ratios.len() / 2],
            100.0 * ratios[ratios.len() - 1],
            100.0 * set.worst_upper / diagonal,
            set.worst_lower,
            set.worst_upper,
            patches as f64 / spheres.len() as f64,
            elapsed,
        );
        assert!(mean > 0.0);
    }
}

/// Run with `cargo test --release -p sphaera-spheretree --test evaluate -- --ignored
/// --nocapture` to time the evaluation of 512 spheres on the low-res bunny.
#[test]
#[ignore = "timing measurement, run by hand in release"]
fn bunny_512_spheres_timing() {
    let Some(dir) = sphaera_tests::data_dir("bunny_512_spheres_timing") else {
        return;
    };
    let mesh = sphaera_io::load(dir.join("bunny_lowres.obj")).unwrap();
    let surface = Surface::new(&mesh).unwrap();
    let spheres = poking_spheres(&mesh, 512, 5, (0.03, 0.08), (0.001, 0.008));
    for relative in [1e-3, 1e-4] {
        let options =
            EvaluationOptions::default().with_tolerance(Length::RelativeToDiagonal(relative));
        let start = Instant::now();
        let fits = sphere_errors(&surface, &spheres, &options).unwrap();
        let errors = start.elapsed();
        let start = Instant::now();
        let cover = coverage(&mesh, &spheres, &options).unwrap();
        let cover_time = start.elapsed();
        let patches: usize = fits.iter().map(|f| f.patches).sum();
        let most = fits.iter().map(|f| f.patches).max().unwrap_or(0);
        eprintln!(
            "512 spheres, tolerance {relative:e} of the diagonal: errors {errors:.2?} \
             ({:.0} patches per sphere, at most {most}, {} not converged), coverage of \
             {} samples {cover_time:.2?}",
            patches as f64 / 512.0,
            fits.iter().filter(|f| !f.converged).count(),
            cover.samples,
        );
    }
}
