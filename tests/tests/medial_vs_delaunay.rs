//! `sphaera-medial`'s adaptive medial approximation checked by its own Delaunay
//! tetrahedralization's `validate` after every step that changes it, and by other crates:
//!
//! - after the static build (Hubbard's baseline), the adaptive build (coverage and
//!   improvement) and two region refinements (the sphere-tree step), on a capsule, a cube
//!   (coplanar and cospherical samples on its faces), a torus and the embedded
//!   low-resolution Stanford bunny (a real scan):
//!   - `approximation.delaunay().validate()` (every invariant, local Delaunayhood of every
//!     face with exact predicates);
//!   - the Delaunay property once more, globally and by brute force in floating point: the
//!     sphere of every finite Voronoi vertex passes through at least four forming points
//!     and has none inside;
//!   - every sphere of the set: its error is the paper's eq. 2 from `sphaera-sweep`'s
//!     exact distance (a Meshsweeper session, not the triangle tree the approximation
//!     queried), `r − d` for an internal sphere and `r + d` for a cover sphere, and the
//!     samples it lists are inside it;
//!   - once coverage is complete, every surface sample is inside some sphere of the set;
//! - a region refinement returns spheres that each cover a sample of the region, and
//!   reports their worst error.
//!
//! # Time
//!
//! 0.4 s wall in the test profile on the shared 2-core machine (the four shapes side by
//! side; up to 280 forming points and 1,430 Voronoi vertices per shape after the last
//! step, with cover spheres on all but the capsule's adaptive build).

use sphaera_io as io;
use sphaera_medial::{
    MedialApproximation, MedialOptions, MedialSphere, RegionOptions, SphereKind, Surface,
};
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_query::sampling;
use sphaera_sweep::{Session, Sweeper, build_hierarchy};

/// Surface samples per shape.
const SAMPLES: usize = 2_000;

/// Forming points of the static (Hubbard) diagram.
const STATIC_FORMING: usize = 64;

/// Spheres the adaptive build improves to.
const SPHERES: usize = 150;

/// Runs every step on `mesh` and checks after each.
fn check(name: &str, mesh: &TriMesh) {
    let surface = Surface::new(mesh).unwrap_or_else(|e| panic!("{name}: surface: {e}"));
    let samples: Vec<DVec3> = sampling::poisson_disk(mesh, SAMPLES, 1)
        .unwrap_or_else(|e| panic!("{name}: sampling: {e}"))
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    let hierarchy = build_hierarchy(mesh).unwrap_or_else(|e| panic!("{name}: hierarchy: {e}"));
    let sweeper = Sweeper::new(&hierarchy).unwrap_or_else(|e| panic!("{name}: sweeper: {e}"));
    let mut session = sweeper.session();
    let diagonal = mesh.bounding_box_diagonal();
    let mut checker = Checker {
        name,
        session: &mut session,
        diagonal,
    };

    let hubbard = MedialApproximation::build_static(&surface, &samples, STATIC_FORMING, None)
        .unwrap_or_else(|e| panic!("{name}: static build: {e}"));
    checker.step("static build", &hubbard, false);

    let params = MedialOptions::default().with_target_spheres(SPHERES);
    let mut medial = MedialApproximation::build(&surface, &samples, &params)
        .unwrap_or_else(|e| panic!("{name}: build: {e}"));
    assert!(medial.sphere_count() >= SPHERES, "{name}: not improved");
    checker.step("adaptive build", &medial, true);

    // Two halves of the samples, refined one after the other (as sphere-tree siblings).
    let center = samples.iter().copied().sum::<DVec3>() / samples.len() as f64;
    let (low, high): (Vec<u32>, Vec<u32>) =
        (0..samples.len() as u32).partition(|&s| samples[s as usize].x < center.x);
    for (half, region) in [("low", &low), ("high", &high)] {
        let mut goal = RegionOptions::default()
            .with_min_spheres(80)
            .with_max_error(0.0);
        goal.max_iterations = 60;
        let outcome = medial
            .refine_region(region, &goal)
            .unwrap_or_else(|e| panic!("{name}: refine {half}: {e}"));
        assert!(outcome.improvements > 0, "{name}: {half} half not refined");
        let worst = outcome.spheres.iter().map(|s| s.error).fold(0.0, f64::max);
        assert!(
            worst.to_bits() == outcome.worst_error.to_bits(),
            "{name}: {half} half: worst error {} reported as {}",
            worst,
            outcome.worst_error
        );
        for sphere in &outcome.spheres {
            assert!(
                sphere
                    .covers
                    .iter()
                    .any(|s| region.binary_search(s).is_ok()),
                "{name}: {half} half: a returned sphere covers no sample of the region"
            );
        }
        checker.step(&format!("refine the {half} half"), &medial, true);
    }
}

/// The checks made after each step.
struct Checker<'c, 's> {
    name: &'c str,
    session: &'c mut Session<'s>,
    diagonal: f64,
}

impl Checker<'_, '_> {
    fn step(&mut self, step: &str, medial: &MedialApproximation<'_>, covered: bool) {
        let at = format!("{}: after the {step}", self.name);
        if let Err(e) = medial.delaunay().validate() {
            panic!("{at}: {e}");
        }
        self.empty_spheres(&at, medial);
        let spheres = medial.spheres();
        assert!(!spheres.is_empty(), "{at}: no sphere");
        for sphere in &spheres {
            self.error_is_eq2(&at, sphere);
            for &s in &sphere.covers {
                let p = medial.samples()[s as usize];
                assert!(
                    p.distance(sphere.center) <= sphere.radius + 1e-9 * self.diagonal,
                    "{at}: sample {s} listed but outside its sphere"
                );
            }
        }
        if covered {
            assert!(
                medial.uncovered_samples().is_empty(),
                "{at}: uncovered samples"
            );
            for (s, &p) in medial.samples().iter().enumerate() {
                assert!(
                    spheres
                        .iter()
                        .any(|b| p.distance(b.center) <= b.radius + 1e-9 * self.diagonal),
                    "{at}: sample {s} ({p}) is in no sphere"
                );
            }
        }
    }

    /// The sphere of every finite Voronoi vertex passes through at least four forming
    /// points and has none strictly inside (brute force, in floating point).
    fn empty_spheres(&self, at: &str, medial: &MedialApproximation<'_>) {
        let delaunay = medial.delaunay();
        let forming: Vec<DVec3> = (0..delaunay.vertex_count() as u32)
            .filter(|&v| delaunay.duplicate_of(v).is_none())
            .map(|v| delaunay.point(v))
            .collect();
        for sphere in medial.voronoi_spheres() {
            // Circumcentres of flat tetrahedra are ill-conditioned: allow for their
            // rounding relative to the radius as well as to the object.
            let tolerance = 1e-9 * (self.diagonal + sphere.radius);
            let mut on = 0;
            for &p in &forming {
                let d = p.distance(sphere.center);
                assert!(
                    d >= sphere.radius - tolerance,
                    "{at}: forming point {p} is inside the Voronoi sphere at {} (r = {}) by {}",
                    sphere.center,
                    sphere.radius,
                    sphere.radius - d
                );
                on += usize::from(d <= sphere.radius + tolerance);
            }
            assert!(
                on >= 4,
                "{at}: the Voronoi sphere at {} passes through {on} forming points",
                sphere.center
            );
        }
    }

    /// A sphere's error is eq. 2 from sweep's exact distance of its centre.
    fn error_is_eq2(&mut self, at: &str, sphere: &MedialSphere) {
        let exact = self
            .session
            .closest(sphere.center)
            .unwrap_or_else(|e| panic!("{at}: closest point of {}: {e}", sphere.center));
        let tolerance = 1e-9 * (self.diagonal + sphere.radius);
        assert!(
            (exact.distance - sphere.closest.distance(sphere.center)).abs() <= tolerance,
            "{at}: the sphere at {} has its closest surface point {} away; sweep says {}",
            sphere.center,
            sphere.closest.distance(sphere.center),
            exact.distance
        );
        let expected = match sphere.kind {
            SphereKind::Internal => (sphere.radius - exact.distance).max(0.0),
            SphereKind::Cover | SphereKind::External => sphere.radius + exact.distance,
        };
        assert!(
            (sphere.error - expected).abs() <= tolerance,
            "{at}: {:?} sphere at {} (r = {}): error {} but eq. 2 with sweep's distance {} \
             gives {expected}",
            sphere.kind,
            sphere.center,
            sphere.radius,
            sphere.error,
            exact.distance
        );
    }
}

#[test]
fn capsule_medial_steps_keep_a_valid_delaunay() {
    check("capsule", &shapes::capsule(0.5, 2.0, 12).unwrap());
}

#[test]
fn cube_medial_steps_keep_a_valid_delaunay() {
    check("cube", &shapes::cube(2.0, 4).unwrap());
}

#[test]
fn torus_medial_steps_keep_a_valid_delaunay() {
    check("torus", &shapes::torus(1.0, 0.35, 16).unwrap());
}

#[test]
fn embedded_bunny_medial_steps_keep_a_valid_delaunay() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../crates/sphaera-cli/assets/bunny_lowres.obj");
    let bunny = io::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    check("bunny_lowres", &bunny);
}
