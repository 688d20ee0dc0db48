//! Trees built to a tolerance: every leaf meets it, certified, and the leaves cover the
//! surface, checked independently (sampled sphere surfaces against exact distances, dense
//! random surface samples), on random shapes, tolerances and similarity transforms, on
//! the awkward meshes users bring, and scaled by powers of two.

mod checks;

use proptest::prelude::*;
use sphaera_mesh::{DVec3, Length, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::{Effort, SphereTree, SphereTreeError, SphereTreeOptions, build};
use sphaera_tests::awkward;

fn tolerance_tree(surface: &Surface, tolerance: f64, effort: Effort) -> SphereTree {
    let options = SphereTreeOptions::default()
        .with_tolerance(Length::Absolute(tolerance))
        .with_effort(effort);
    build(surface, &options).expect("a tolerance of a few percent is reachable")
}

fn assert_meets(surface: &Surface, tree: &SphereTree, tolerance: f64, what: &str) {
    let leaves = tree.leaves();
    assert!(!leaves.is_empty(), "{what}");
    for &leaf in &leaves {
        let error = tree.nodes()[leaf].error;
        assert!(
            error <= tolerance,
            "{what}: leaf {leaf} error {error} > {tolerance}"
        );
    }
    checks::check_tree(surface, tree, 3_000, 96, what);
}

/// A shape by number, placed by a similarity: turned about a random axis, scaled and
/// moved.
fn placed(shape: usize, axis: DVec3, angle: f64, scale: f64, offset: DVec3) -> TriMesh {
    let mesh = match shape % 4 {
        0 => shapes::capsule(0.4, 1.5, 10),
        1 => shapes::torus(1.0, 0.3, 12),
        2 => shapes::l_block(2.0, 0.8, 0.6, 2),
        _ => shapes::cube(1.0, 2),
    }
    .expect("valid shape");
    let turn = glam::DQuat::from_axis_angle(axis.normalize_or(DVec3::Z), angle);
    awkward::mapped(&mesh, |p| turn * p * scale + offset, false)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(6), ..ProptestConfig::default() })]

    /// Random shapes, placements and tolerances: every leaf within the tolerance, by the
    /// tree's certificate and by the independent check.
    #[test]
    fn every_leaf_meets_a_random_tolerance(
        shape in 0_usize..4,
        axis in (-1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64),
        angle in 0.0..std::f64::consts::TAU,
        scale_exponent in -8_i32..8,
        offset in (-100.0..100.0_f64, -100.0..100.0_f64, -100.0..100.0_f64),
        fraction in 0.03..0.12_f64,
    ) {
        let scale = f64::from(scale_exponent).exp2();
        let offset = DVec3::new(offset.0, offset.1, offset.2) * scale;
        let mesh = placed(shape, DVec3::new(axis.0, axis.1, axis.2), angle, scale, offset);
        let surface = Surface::new(&mesh).expect("closed shape");
        let tolerance = fraction * surface.diagonal();
        let tree = tolerance_tree(&surface, tolerance, Effort::Quick);
        assert_meets(&surface, &tree, tolerance, &format!("shape {shape}"));
    }
}

/// The awkward meshes (a pinched vertex, slivers, far-apart parts, a thin rod, horns,
/// spikes, a tiny detached cube) at two tolerances.
#[test]
fn awkward_meshes_meet_their_tolerances() {
    for case in awkward::all() {
        let Ok(surface) = Surface::solid_or_shell(&case.mesh) else {
            continue;
        };
        for fraction in [0.1, 0.04] {
            let tolerance = fraction * surface.diagonal();
            let tree = tolerance_tree(&surface, tolerance, Effort::Quick);
            assert_meets(
                &surface,
                &tree,
                tolerance,
                &format!("{} at {fraction}", case.name),
            );
        }
    }
}

/// A tolerance and a node budget together: the tolerance met within the budget, or
/// refused; never more nodes, never a looser leaf.
#[test]
fn a_tolerance_within_a_node_budget_is_met_or_refused() {
    let surface = Surface::new(&shapes::torus(1.0, 0.3, 12).expect("torus")).expect("closed");
    let tolerance = 0.03 * surface.diagonal();
    let free = tolerance_tree(&surface, tolerance, Effort::Quick);
    let needed = free.nodes().len();
    let options = SphereTreeOptions::default()
        .with_tolerance(Length::Absolute(tolerance))
        .with_effort(Effort::Quick);
    let roomy = build(&surface, &options.clone().with_max_nodes(needed)).expect("fits");
    assert_eq!(roomy.nodes(), free.nodes());
    for max_nodes in [1, needed / 2] {
        assert!(matches!(
            build(&surface, &options.clone().with_max_nodes(max_nodes)),
            Err(SphereTreeError::ToleranceUnreachable { limit, spheres, .. })
                if limit == max_nodes && spheres <= max_nodes
        ));
    }
    for bad in [0, sphaera_spheretree::MAX_TREE_NODES + 1] {
        assert!(matches!(
            build(&surface, &options.clone().with_max_nodes(bad)),
            Err(SphereTreeError::InvalidParameter {
                name: "max_nodes",
                ..
            })
        ));
    }
}

/// Scaling the mesh by a power of two scales the tree: the same structure, every centre,
/// radius and error scaled, bit for bit.
#[test]
fn a_power_of_two_scales_the_tree_exactly() {
    let mesh = shapes::capsule(0.5, 2.0, 10).expect("capsule");
    let base = Surface::new(&mesh).expect("closed");
    let tolerance = 0.05 * base.diagonal();
    let tree = tolerance_tree(&base, tolerance, Effort::Quick);
    for exponent in [-40, -3, 5, 40] {
        let factor = f64::from(exponent).exp2();
        let scaled = Surface::new(&awkward::mapped(&mesh, |p| p * factor, false)).expect("closed");
        let other = tolerance_tree(&scaled, tolerance * factor, Effort::Quick);
        assert_eq!(other.nodes().len(), tree.nodes().len(), "2^{exponent}");
        for (a, b) in tree.nodes().iter().zip(other.nodes()) {
            let bits = |v: DVec3| v.to_array().map(f64::to_bits);
            assert_eq!(bits(a.sphere.center * factor), bits(b.sphere.center));
            assert_eq!(
                (a.sphere.radius * factor).to_bits(),
                b.sphere.radius.to_bits()
            );
            assert_eq!((a.error * factor).to_bits(), b.error.to_bits());
            assert_eq!(a.parent, b.parent);
        }
    }
}

/// A tolerance no tree can reach within the limits is refused with the reason, not met
/// silently looser; a tolerance of zero or NaN is refused before any work.
#[test]
fn unreachable_and_invalid_tolerances_say_why() {
    let surface = Surface::shell(&shapes::square_sheet(1.0, 1).expect("square")).expect("shell");
    // Within a node budget (the default limit, 2^21 nodes, is reached the same way, only
    // later).
    let options = SphereTreeOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(1e-6))
        .with_effort(Effort::Quick)
        .with_max_nodes(5_000);
    match build(&surface, &options) {
        Err(SphereTreeError::ToleranceUnreachable {
            tolerance,
            worst,
            spheres,
            limit,
            ..
        }) => {
            assert!(worst > tolerance);
            assert!(spheres <= limit && limit == 5_000, "{spheres} of {limit}");
        }
        other => panic!("{other:?}"),
    }
    // Deeper than the depth limit: one child per node never gets below the root's error.
    let options = SphereTreeOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(0.01))
        .with_effort(Effort::Quick)
        .with_branch(1);
    match build(&surface, &options) {
        Err(SphereTreeError::ToleranceUnreachable {
            tolerance,
            worst,
            levels,
            depth,
            ..
        }) => {
            assert!(worst > tolerance);
            assert!(levels <= depth, "{levels} levels of {depth}");
        }
        other => panic!("{other:?}"),
    }
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let options = SphereTreeOptions::default().with_tolerance(Length::Absolute(bad));
        assert!(matches!(
            build(&surface, &options),
            Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                ..
            })
        ));
    }
}
