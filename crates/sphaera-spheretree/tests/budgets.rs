//! Budgets: a one-level tree of `N` spheres has exactly `N`, covers the surface, and
//! reaches no farther beyond it than each node's error says; more spheres never reach
//! farther.
//!
//! Every `N` from 1 to 600 on three meshes is the `#[ignore]`d
//! `every_budget_from_1_to_600` (about ten minutes in release: `cargo test --release -p
//! sphaera-spheretree --test budgets -- --ignored`); the suite runs every `N` up to 40 and
//! a spread of larger ones.

mod checks;

use sphaera_mesh::{TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::{Effort, SphereTree, SphereTreeOptions, build};
use sphaera_tests::awkward;

/// Three small meshes: a capsule, a torus and the L block.
fn meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("capsule", shapes::capsule(0.5, 2.0, 10).expect("capsule")),
        ("torus", shapes::torus(1.0, 0.3, 12).expect("torus")),
        (
            "l block",
            shapes::l_block(2.0, 0.8, 0.6, 2).expect("l block"),
        ),
    ]
}

fn one_level(surface: &Surface, n: usize, effort: Effort) -> SphereTree {
    let options = SphereTreeOptions::default()
        .with_depth(1)
        .with_branch(n)
        .with_effort(effort);
    build(surface, &options).expect("a budget builds")
}

fn check_budget(surface: &Surface, n: usize, effort: Effort, what: &str) -> f64 {
    let tree = one_level(surface, n, effort);
    assert_eq!(tree.level(1).len(), n, "{what}: {n} asked");
    assert_eq!(tree.leaves().len(), n, "{what}: {n} asked");
    tree.level(1)
        .iter()
        .map(|node| node.error)
        .fold(0.0, f64::max)
}

#[test]
fn small_budgets_are_exact() {
    for (name, mesh) in meshes() {
        let surface = Surface::new(&mesh).expect("closed");
        for n in (1..=40).chain([53, 64, 97, 128]) {
            check_budget(&surface, n, Effort::Quick, name);
        }
    }
}

#[test]
fn large_budgets_are_exact_and_cover() {
    let (name, mesh) = ("capsule", shapes::capsule(0.5, 2.0, 10).expect("capsule"));
    let surface = Surface::new(&mesh).expect("closed");
    for n in [255, 600] {
        let tree = one_level(&surface, n, Effort::Quick);
        assert_eq!(tree.level(1).len(), n, "{name}: {n}");
        checks::check_tree(&surface, &tree, 4_000, 24, name);
    }
}

/// A budget beyond a thousand goes in two steps (groups, then their shares): still exact.
#[test]
fn a_budget_in_two_steps_is_exact() {
    let mesh = shapes::sphere(1.0, 12).expect("sphere");
    let surface = Surface::new(&mesh).expect("closed");
    check_budget(&surface, 1_100, Effort::Quick, "sphere");
}

/// On the awkward meshes (a pinched vertex, slivers, far-apart parts, a thin rod, horns,
/// spikes, a tiny cube), budgets are exact and cover.
#[test]
fn awkward_budgets_are_exact_and_cover() {
    for case in awkward::all() {
        let Ok(surface) = Surface::solid_or_shell(&case.mesh) else {
            continue;
        };
        for n in [1, 7, 24] {
            let tree = one_level(&surface, n, Effort::Quick);
            assert_eq!(tree.level(1).len(), n, "{}: {n}", case.name);
            checks::check_tree(&surface, &tree, 2_000, 48, case.name);
        }
    }
}

/// More spheres never reach farther beyond the surface (at the default effort, on the
/// same mesh, for a few doublings).
#[test]
fn more_spheres_are_never_looser() {
    let mesh = shapes::capsule(0.5, 2.0, 10).expect("capsule");
    let surface = Surface::new(&mesh).expect("closed");
    let mut previous = f64::INFINITY;
    for n in [1, 2, 4, 8, 16, 32] {
        let worst = check_budget(&surface, n, Effort::Default, "capsule");
        assert!(
            worst <= previous * (1.0 + 1e-9),
            "{n} spheres: {worst} > {previous}"
        );
        previous = worst;
    }
}

#[test]
#[ignore = "every budget from 1 to 600 on three meshes: about ten minutes in release"]
fn every_budget_from_1_to_600() {
    for (name, mesh) in meshes() {
        let surface = Surface::new(&mesh).expect("closed");
        for n in 1..=600 {
            check_budget(&surface, n, Effort::Quick, name);
        }
    }
}
