//! Brute-force checkers of the two error-sphere invariants.

#![allow(dead_code, clippy::print_stderr)]

use glam::DVec3;
use sphaera_mesh::TriMesh;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
use sphaera_simplify::Simplified;
use sphaera_tests::pattern_search::{Boundary, PatternSearch, SearchBudget, TWELVE_DIRECTIONS};

/// Slack allowed in the checks (absolute, the shapes are of unit size).
pub const SLACK: f64 = 1e-9;

/// `min over λ of |x − λ·P| − λ·R` on a grid of the simplex, refined around the best
/// point by the shared pattern search (24 grid steps, twelve directions, negative
/// coordinates clamped, steps down to 1e-14). The function is convex, so this converges;
/// any sampled value is an upper bound of the true minimum, so a value ≤ slack proves
/// membership.
pub fn tolerance_slack(x: DVec3, p: [DVec3; 3], r: [f64; 3]) -> f64 {
    let f = |a: f64, b: f64| {
        let c = 1.0 - a - b;
        (x - (a * p[0] + b * p[1] + c * p[2])).length() - (a * r[0] + b * r[1] + c * r[2])
    };
    PatternSearch {
        grid: 24,
        directions: &TWELVE_DIRECTIONS,
        min_step: 1e-14,
        budget: SearchBudget::Rounds(usize::MAX),
        boundary: Boundary::ClampNegative,
    }
    .minimise(f)
    .value
}

/// Checks invariant (A) for the points `xs` of the original surface; returns the worst
/// slack (the smallest over triangles, the largest over points).
pub fn worst_coverage(out: &Simplified, xs: &[DVec3]) -> f64 {
    let tris: Vec<([DVec3; 3], [f64; 3])> = out
        .mesh
        .triangles()
        .iter()
        .map(|t| {
            let p = t.map(|i| out.mesh.positions()[i as usize]);
            let r = t.map(|i| out.vertex_radii[i as usize]);
            (p, r)
        })
        .collect();
    let mut worst = f64::NEG_INFINITY;
    for &x in xs {
        // Cheap lower bound first: the slack is at least dist(x, T) − max r.
        let mut order: Vec<(f64, usize)> = tris
            .iter()
            .enumerate()
            .map(|(i, (p, r))| {
                let d = point_triangle_distance_squared(x, &Triangle::new(p[0], p[1], p[2])).sqrt();
                (d - r[0].max(r[1]).max(r[2]), i)
            })
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::INFINITY;
        for &(lower, i) in &order {
            if lower > best.min(SLACK) {
                break;
            }
            best = best.min(tolerance_slack(x, tris[i].0, tris[i].1));
            if best <= SLACK {
                break;
            }
        }
        worst = worst.max(best);
    }
    worst
}

/// Distance from `x` to `mesh`, brute force over its triangles.
pub fn distance_to(mesh: &TriMesh, x: DVec3) -> f64 {
    mesh.triangle_iter()
        .map(|t| point_triangle_distance_squared(x, &t))
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// Checks invariant (B): points of every simplified triangle on a barycentric grid of
/// `n` steps; returns the worst `dist(y, original) − r(y)`.
pub fn worst_containment(out: &Simplified, original: &TriMesh, n: u32) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for t in out.mesh.triangles() {
        let p = t.map(|i| out.mesh.positions()[i as usize]);
        let r = t.map(|i| out.vertex_radii[i as usize]);
        for i in 0..=n {
            for j in 0..=(n - i) {
                let a = f64::from(i) / f64::from(n);
                let b = f64::from(j) / f64::from(n);
                let c = 1.0 - a - b;
                let y = a * p[0] + b * p[1] + c * p[2];
                let ry = a * r[0] + b * r[1] + c * r[2];
                worst = worst.max(distance_to(original, y) - ry);
            }
        }
    }
    worst
}

/// Original surface samples: all vertices plus `n` random points.
pub fn original_samples(mesh: &TriMesh, n: usize, seed: u64) -> Vec<DVec3> {
    let mut xs = mesh.positions().to_vec();
    if let Ok(samples) = sphaera_query::sampling::random(mesh, n, seed) {
        xs.extend(samples.iter().map(|s| s.position));
    }
    xs
}

/// An open `n × n` grid patch of the unit square, lifted by `height(x, y)`.
pub fn grid(n: u32, height: impl Fn(f64, f64) -> f64) -> TriMesh {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            p.push(DVec3::new(x, y, height(x, y)));
        }
    }
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = (n + 1) * j + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    TriMesh::new(p, t).expect("a valid grid")
}

/// The procedural test shapes: 0 sphere, 1 torus, 2 cube, otherwise a wavy open grid.
pub fn shape(kind: u8, resolution: usize) -> TriMesh {
    use sphaera_mesh::shapes;
    match kind {
        0 => shapes::sphere(1.0, resolution.max(4)).unwrap(),
        1 => shapes::torus(1.0, 0.35, resolution.max(6)).unwrap(),
        2 => shapes::cube(1.0, resolution.clamp(1, 6)).unwrap(),
        _ => grid(resolution.clamp(2, 10) as u32, |x, y| {
            0.2 * (3.0 * x).sin() * (2.0 * y).cos()
        }),
    }
}
