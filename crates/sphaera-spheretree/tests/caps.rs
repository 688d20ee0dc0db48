//! The caps on parameters that size memory (issue 38): each is refused just above its cap,
//! quickly and before anything is sampled or allocated, with an error naming the
//! parameter and the cap.

use sphaera_mesh::shapes;
use sphaera_query::sampling::{MAX_SAMPLES, PoissonDiskOptions};
use sphaera_spheretree::evaluate::coverage;
use sphaera_spheretree::{
    EvaluationOptions, MAX_BASELINE_DEPTH, MAX_BASELINE_SAMPLES, MAX_BRANCH, MAX_COVERAGE_SAMPLES,
    MAX_MEDIAL_DEPTH, MAX_PATCHES, MAX_SURFACE_SAMPLES, MAX_TREE_NODES, Method, Sphere,
    SphereTreeError, SphereTreeOptions, Surface, build, evaluate_set,
};

/// Asserts `error` is an `InvalidParameter` named `name` whose message names `cap`.
fn assert_capped(error: &SphereTreeError, name: &str, cap: &str) {
    assert!(
        matches!(error, SphereTreeError::InvalidParameter { name: n, .. } if *n == name),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(message.contains(name) && message.contains(cap), "{message}");
}

fn surface() -> Surface {
    Surface::new(&shapes::sphere(1.0, 8).expect("sphere")).expect("surface")
}

#[test]
fn tree_options_above_their_caps_are_refused_before_building() {
    let surface = surface();
    let cases = [
        (
            SphereTreeOptions::default().with_depth(MAX_MEDIAL_DEPTH + 1),
            "depth",
            "MAX_MEDIAL_DEPTH",
        ),
        (
            SphereTreeOptions::default().with_branch(MAX_BRANCH + 1),
            "branch",
            "MAX_BRANCH",
        ),
        (
            SphereTreeOptions::default().with_branch(usize::MAX),
            "branch",
            "MAX_BRANCH",
        ),
        (
            SphereTreeOptions::default().with_max_nodes(MAX_TREE_NODES + 1),
            "max_nodes",
            "MAX_TREE_NODES",
        ),
        (
            SphereTreeOptions::default()
                .with_method(Method::Expand)
                .with_depth(MAX_MEDIAL_DEPTH + 1),
            "depth",
            "MAX_MEDIAL_DEPTH",
        ),
        (
            SphereTreeOptions::default()
                .with_method(Method::Expand)
                .with_samples(MAX_SURFACE_SAMPLES + 1),
            "samples",
            "MAX_SURFACE_SAMPLES",
        ),
        (
            SphereTreeOptions::default()
                .with_method(Method::Merge)
                .with_samples(usize::MAX),
            "samples",
            "MAX_SURFACE_SAMPLES",
        ),
        (
            SphereTreeOptions::default()
                .with_method(Method::Octree)
                .with_depth(MAX_BASELINE_DEPTH + 1),
            "depth",
            "MAX_BASELINE_DEPTH",
        ),
        (
            SphereTreeOptions::default()
                .with_method(Method::Hubbard)
                .with_samples(MAX_BASELINE_SAMPLES + 1),
            "samples",
            "MAX_BASELINE_SAMPLES",
        ),
    ];
    for (options, name, cap) in cases {
        let error = build(&surface, &options).expect_err("above the cap");
        assert_capped(&error, name, cap);
    }
}

#[test]
fn the_sample_cap_is_what_the_sampler_draws() {
    // Five candidates per sample: the cap is the most the sampler accepts, and one more
    // sample would pass the sampler's own cap.
    let oversampling = PoissonDiskOptions::default().oversampling;
    assert!((oversampling * MAX_SURFACE_SAMPLES as f64).ceil() <= MAX_SAMPLES as f64);
    assert!((oversampling * (MAX_SURFACE_SAMPLES + 1) as f64).ceil() > MAX_SAMPLES as f64);
    assert_eq!(MAX_BASELINE_SAMPLES, MAX_SURFACE_SAMPLES);
}

#[test]
fn evaluation_budgets_above_their_caps_are_refused() {
    let surface = surface();
    let spheres = [Sphere {
        center: sphaera_spheretree::DVec3::ZERO,
        radius: 1.1,
    }];
    for (options, name, cap) in [
        (
            EvaluationOptions::default().with_max_patches(MAX_PATCHES + 1),
            "max_patches",
            "MAX_PATCHES",
        ),
        (
            EvaluationOptions::default().with_max_patches(usize::MAX),
            "max_patches",
            "MAX_PATCHES",
        ),
        (
            EvaluationOptions::default().with_coverage_samples(MAX_COVERAGE_SAMPLES + 1),
            "coverage_samples",
            "MAX_COVERAGE_SAMPLES",
        ),
    ] {
        let error = options.validate().expect_err("above the cap");
        assert_capped(&error, name, cap);
        let error = evaluate_set(&surface, &spheres, &options).expect_err("above the cap");
        assert_capped(&error, name, cap);
        let error = coverage(surface.mesh(), &spheres, &options).expect_err("above the cap");
        assert_capped(&error, name, cap);
    }
    // The caps themselves pass the check.
    let at_caps = EvaluationOptions::default()
        .with_max_patches(MAX_PATCHES)
        .with_coverage_samples(MAX_COVERAGE_SAMPLES);
    assert!(at_caps.validate().is_ok());
}
