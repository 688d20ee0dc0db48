//! Independent checks of a built tree, by brute force on the surface: coverage of dense
//! random surface samples, and the protrusion of points sampled on the spheres measured
//! with exact closest points.

use sphaera_mesh::{DVec3, Sphere};
use sphaera_query::{Surface, sampling};
use sphaera_spheretree::SphereTree;

/// Points spread over a sphere's surface (a Fibonacci lattice of `n` points).
pub fn sphere_points(sphere: &Sphere, n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).max(0.0).sqrt();
            let t = golden * i as f64;
            sphere.center + sphere.radius * DVec3::new(r * t.cos(), y, r * t.sin())
        })
        .collect()
}

/// The largest distance to the surface of a point of `points` lying outside the object
/// (every point, for a shell), by exact closest points and the certified side.
pub fn protrusion(surface: &Surface, points: &[DVec3]) -> f64 {
    points
        .iter()
        .map(|&p| {
            let signed = surface.signed_closest(p).expect("finite point");
            if signed.inside {
                0.0
            } else {
                signed.closest.distance
            }
        })
        .fold(0.0, f64::max)
}

/// Asserts that the spheres of every cut of `tree` cover `samples` random surface
/// samples (with a relative slack of 1e-9 of the diagonal for rounding), and that no
/// sampled point of a node's sphere lies farther outside the object than the node's
/// error (`per_sphere` points on each sphere; errors are certified upper bounds). `what`
/// names the case in failure messages.
pub fn check_tree(
    surface: &Surface,
    tree: &SphereTree,
    samples: usize,
    per_sphere: usize,
    what: &str,
) {
    let diagonal = surface.diagonal();
    let slack = 1e-9 * diagonal;
    let points: Vec<DVec3> = sampling::random(surface.mesh(), samples, 0xC0DE)
        .expect("the mesh has area")
        .iter()
        .map(|s| s.position)
        .collect();
    for level in 0..tree.level_count() {
        let spheres = tree.cut_spheres(level);
        for p in &points {
            assert!(
                spheres
                    .iter()
                    .any(|s| s.center.distance(*p) <= s.radius + slack),
                "{what}: level {level}: surface point {p} outside every sphere of the cut"
            );
        }
    }
    for (i, node) in tree.nodes().iter().enumerate() {
        let worst = protrusion(surface, &sphere_points(&node.sphere, per_sphere));
        assert!(
            worst <= node.error + slack,
            "{what}: node {i} reaches {worst} beyond the surface, its error is {}",
            node.error
        );
    }
}
