//! Sphere-trees of `sphaera-spheretree` checked with `sphaera-sweep`'s exact closest
//! points (Meshsweeper sessions: a different algorithm from the triangle tree that the
//! sphere-tree crate itself queries through `sphaera_query::Surface`) and
//! `sphaera-mesh`'s independent random surface samples, on a capsule, a torus, the
//! embedded low-resolution bunny and a Franka Panda link.
//!
//! # What must hold
//!
//! The error of a sphere `S` is `E(S) = max f(x)` over the points `x` of its surface,
//! `f(x)` the distance from `x` to the mesh when `x` is outside the object, 0 inside
//! (`sphaera_spheretree::evaluate`). Three numbers bracket it:
//!
//! - `evaluate_set` certifies `fit.lower ≤ E(S) ≤ fit.upper` for each sphere;
//! - the construction error `TreeNode::error` is the paper's eq. 2: for a centre inside
//!   the object at distance `d` from the surface, `r − d`, which bounds `f` from above
//!   because the ball of radius `d` about the centre lies inside the object; for a centre
//!   outside, `r + d`, because every point of the sphere is within `r + d` of the surface
//!   point closest to the centre (`sphaera_medial::MedialSphere::error`, "an upper bound
//!   of the largest distance from a point of the sphere outside the object to the
//!   surface"). So `E(S) ≤ error`, but `error` may be far above `E(S)` (eq. 2 is exact
//!   only for convex parts): nothing orders `error` and `fit.upper`.
//! - a point `x` of the sphere's surface that is outside the object (by
//!   `Surface::is_inside_certified`) gives `f(x)`, measured here with sweep's exact
//!   distance: each is at most `E(S)`, and so is their maximum.
//!
//! Checked, for every node of every level, up to rounding (`1e-12` of the diagonal):
//!
//! 1. `f(x) ≤ fit.upper` and `f(x) ≤ error` at 300 points of the sphere's surface (a
//!    Fibonacci lattice, [`fibonacci_sphere`]), so the largest `f` found is a lower bound
//!    of `E(S)` below both;
//! 2. `fit.lower ≤ error`; and `fit.lower` is sweep's exact distance at its witness
//!    point, which lies on the sphere and outside the object;
//! 3. coverage, for the medial-axis methods: 20,000 area-weighted random surface samples
//!    (a seed the construction does not use) each lie inside some sphere of every level
//!    (the construction certifies coverage of the whole surface), and `evaluate_set` finds
//!    no uncovered sample. The baselines (octree, grid, Hubbard) cover their own samples
//!    only, so for them 1 and 2 are checked and coverage is not.
//!
//! Every method of [`Method::ALL`] is checked on every mesh.
//!
//! # Time
//!
//! 8.5 s wall in the test profile on the shared 2-core machine, the four meshes side by
//! side with seven methods each (the default method alone took 1.7–3.1 s).

use sphaera_io as io;
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_query::sampling;
use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set};
use sphaera_spheretree::{Method, SphereTree, SphereTreeOptions, TreeNode, build};
use sphaera_sweep::{Session, Sweeper, build_hierarchy};
use sphaera_tests::point_sets::fibonacci_sphere;

/// Points per sphere surface where the error is measured.
const POINTS_PER_SPHERE: usize = 300;

/// Independent surface samples of the coverage check.
const COVERAGE_SAMPLES: usize = 20_000;

/// Their seed (the construction samples with `SphereTreeOptions::seed`, 1 by default).
const COVERAGE_SEED: u64 = 0x5EED_C0DE;

/// Small construction options, as in `sphaera-spheretree`'s own tests.
fn options() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_depth(2)
        .with_branch(4)
        .with_samples(1_500)
        .with_initial_spheres(100)
        .with_min_spheres_per_node(30)
}

/// Builds the tree of `mesh` with every method and checks each (see the module
/// documentation).
fn check(name: &str, mesh: &TriMesh) {
    let surface = Surface::new(mesh).unwrap_or_else(|e| panic!("{name}: surface: {e}"));
    let hierarchy = build_hierarchy(mesh).unwrap_or_else(|e| panic!("{name}: hierarchy: {e}"));
    let sweeper = Sweeper::new(&hierarchy).unwrap_or_else(|e| panic!("{name}: sweeper: {e}"));
    let mut session = sweeper.session();
    for method in Method::ALL {
        let name = format!("{name} ({})", method.name());
        check_method(&name, mesh, &surface, &mut session, method);
    }
}

/// Builds the tree of `mesh` with `method` and checks it.
fn check_method(
    name: &str,
    mesh: &TriMesh,
    surface: &Surface,
    session: &mut Session<'_>,
    method: Method,
) {
    let tree = build(surface, &options().with_method(method))
        .unwrap_or_else(|e| panic!("{name}: build: {e}"));
    let diagonal = mesh.bounding_box_diagonal();
    let slack = 1e-12 * diagonal;
    if method.is_medial() {
        check_coverage(name, mesh, &tree, 1e-9 * diagonal);
    }
    let options = EvaluationOptions::default().with_coverage_samples(10_000);
    let directions = fibonacci_sphere(POINTS_PER_SPHERE);
    let mut measured = 0;
    for level in 0..tree.level_count() {
        let nodes = tree.level(level);
        let spheres = tree.level_spheres(level);
        let set = evaluate_set(surface, &spheres, &options)
            .unwrap_or_else(|e| panic!("{name}: evaluate level {level}: {e}"));
        if method.is_medial() {
            assert_eq!(
                set.coverage.uncovered, 0,
                "{name}: level {level} leaves samples uncovered"
            );
        }
        for (k, (node, fit)) in nodes.iter().zip(&set.fits).enumerate() {
            let at = format!("{name}: level {level}, sphere {k}");
            let found = largest_outside_distance(surface, session, node, &directions);
            measured += usize::from(found > 0.0);
            assert!(
                found <= fit.upper + slack,
                "{at}: a point of the sphere is {found} from the mesh, above the certified \
                 error {}",
                fit.upper
            );
            assert!(
                found <= node.error + slack,
                "{at}: a point of the sphere is {found} from the mesh, above the construction \
                 error {}",
                node.error
            );
            assert!(
                fit.lower <= node.error + slack,
                "{at}: certified lower bound {} above the construction error {}",
                fit.lower,
                node.error
            );
            check_witness(&at, surface, session, node, fit.lower, fit.witness);
        }
    }
    assert!(measured > 0, "{name}: no sphere pokes out of the mesh");
}

/// The largest exact distance to the mesh (sweep) of the points of `node`'s sphere, along
/// `directions`, that are outside the object; 0 when none is.
fn largest_outside_distance(
    surface: &Surface,
    session: &mut Session<'_>,
    node: &TreeNode,
    directions: &[DVec3],
) -> f64 {
    let mut largest: f64 = 0.0;
    for &d in directions {
        let x = node.sphere.center + node.sphere.radius * d;
        if surface.is_inside_certified(x) {
            continue;
        }
        let exact = session
            .closest(x)
            .unwrap_or_else(|e| panic!("closest point of {x}: {e}"));
        largest = largest.max(exact.distance);
    }
    largest
}

/// The certified lower bound is sweep's exact distance at its witness, a point of the
/// sphere outside the object.
fn check_witness(
    at: &str,
    surface: &Surface,
    session: &mut Session<'_>,
    node: &TreeNode,
    lower: f64,
    witness: Option<DVec3>,
) {
    let Some(w) = witness else {
        assert!(lower == 0.0, "{at}: lower bound {lower} without a witness");
        return;
    };
    let scale = node
        .sphere
        .radius
        .max(node.sphere.center.abs().max_element());
    assert!(
        (w.distance(node.sphere.center) - node.sphere.radius).abs() <= 1e-9 * scale,
        "{at}: the witness {w} is not on the sphere"
    );
    assert!(
        !surface.is_inside_certified(w),
        "{at}: the witness {w} is inside"
    );
    let exact = session
        .closest(w)
        .unwrap_or_else(|e| panic!("{at}: closest point of {w}: {e}"))
        .distance;
    assert!(
        (exact - lower).abs() <= 1e-9 * scale,
        "{at}: the certified lower bound {lower} is not the distance {exact} at its witness"
    );
}

/// Every independent surface sample is inside some sphere of every level.
fn check_coverage(name: &str, mesh: &TriMesh, tree: &SphereTree, tolerance: f64) {
    let samples = sampling::random(mesh, COVERAGE_SAMPLES, COVERAGE_SEED)
        .unwrap_or_else(|e| panic!("{name}: sampling: {e}"));
    for level in 0..tree.level_count() {
        let spheres = tree.level_spheres(level);
        for s in &samples {
            assert!(
                spheres
                    .iter()
                    .any(|b| b.contains_point(s.position, tolerance)),
                "{name}: the surface point {} (triangle {}) is outside every sphere of level \
                 {level}",
                s.position,
                s.triangle
            );
        }
    }
}

#[test]
fn capsule_tree_covers_and_its_errors_bound_exact_distances() {
    check("capsule", &shapes::capsule(0.5, 2.0, 12).unwrap());
}

#[test]
fn torus_tree_covers_and_its_errors_bound_exact_distances() {
    check("torus", &shapes::torus(1.0, 0.35, 16).unwrap());
}

#[test]
fn embedded_bunny_tree_covers_and_its_errors_bound_exact_distances() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../crates/sphaera-cli/assets/bunny_lowres.obj");
    let bunny = io::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    check("bunny_lowres", &bunny);
}

#[test]
fn franka_link_tree_covers_and_its_errors_bound_exact_distances() {
    let Some(dir) =
        sphaera_tests::data_dir("franka_link_tree_covers_and_its_errors_bound_exact_distances")
    else {
        return;
    };
    let name = "robots/franka_panda/collision/link1.obj";
    let link = io::load(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    check(name, &link);
}
