//! Tests of [`super::edge_collapse_radius`]: brute-force checks of both invariants on
//! applied collapses, and comparisons with the simple map and the half-edge collapse.

use super::*;
use crate::quadric::{optimal_position, vertex_quadrics};
use crate::spheres::{BoundaryPolicy, collapse_radius};
use proptest::prelude::*;
use sphaera_mesh::TriMesh;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
use sphaera_mesh::shapes;
use sphaera_tests::pattern_search::{Boundary, PatternSearch, SearchBudget, TWELVE_DIRECTIONS};
use sphaera_tests::random::SplitMix64;

/// Slack of the brute-force checks (the meshes are of unit size).
const SLACK: f64 = 1e-9;

/// A unit sphere with every vertex moved by up to `noise` in each coordinate.
fn noisy_sphere(resolution: usize, noise: f64, rng: &mut SplitMix64) -> HalfEdgeMesh {
    let mesh = shapes::sphere(1.0, resolution).unwrap();
    let p = mesh
        .positions()
        .iter()
        .map(|&x| x + noise * rng.vector_by_max())
        .collect();
    HalfEdgeMesh::from_trimesh(&TriMesh::new(p, mesh.triangles().to_vec()).unwrap())
}

/// An `n × n` grid of the unit square, jittered in the plane by `jitter` (in cells) and
/// in height by `bump`.
fn noisy_grid(n: u32, jitter: f64, bump: f64, rng: &mut SplitMix64) -> HalfEdgeMesh {
    let cell = 1.0 / f64::from(n);
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let d = rng.vector_by_max();
            let x = f64::from(i) * cell + jitter * cell * d.x;
            let y = f64::from(j) * cell + jitter * cell * d.y;
            p.push(DVec3::new(x, y, bump * d.z));
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
    HalfEdgeMesh::from_trimesh(&TriMesh::new(p, t).unwrap())
}

/// `min over λ of |x − λ·P| + sign · λ·R` over the triangle (convex in `λ`): a grid of
/// the simplex refined around its best point ([`sphaera_tests::pattern_search`]: 16 grid
/// steps, twelve directions, negative coordinates clamped, steps down to 1e-13). Any
/// sampled value bounds the minimum from above, so a small value proves the inclusion
/// being checked. The pattern search is capped at 3,000 rounds: a (nearly) flat valley
/// would otherwise be crawled at tiny steps; stopping early only makes the check stricter.
fn min_over_triangle(x: DVec3, p: [DVec3; 3], r: [f64; 3], sign: f64) -> f64 {
    let f = move |a: f64, b: f64| {
        let c = 1.0 - a - b;
        (x - (a * p[0] + b * p[1] + c * p[2])).length() + sign * (a * r[0] + b * r[1] + c * r[2])
    };
    PatternSearch {
        grid: 16,
        directions: &TWELVE_DIRECTIONS,
        min_step: 1e-13,
        budget: SearchBudget::Rounds(3000),
        boundary: Boundary::ClampNegative,
    }
    .minimise(f)
    .value
}

/// Triangles with per-corner radii.
type Patch = Vec<([DVec3; 3], [f64; 3])>;

/// The live faces around `x`, with radii.
fn star(mesh: &HalfEdgeMesh, radii: &[f64], xs: &[VertexId]) -> Patch {
    let mut faces: Vec<u32> = xs
        .iter()
        .flat_map(|&x| mesh.vertex_faces(x).map(|f| f.0))
        .collect();
    faces.sort_unstable();
    faces.dedup();
    faces
        .into_iter()
        .map(|f| {
            let c = mesh.face_vertices(sphaera_mesh::topology::FaceId(f));
            (c.map(|x| mesh.position(x)), c.map(|x| radii[x.0 as usize]))
        })
        .collect()
}

/// Grid samples of a patch, with their interpolated radii.
fn samples(patch: &Patch, n: u32) -> Vec<(DVec3, f64)> {
    let mut out = Vec::new();
    for (p, r) in patch {
        for i in 0..=n {
            for j in 0..=(n - i) {
                let a = f64::from(i) / f64::from(n);
                let b = f64::from(j) / f64::from(n);
                let c = 1.0 - a - b;
                out.push((
                    a * p[0] + b * p[1] + c * p[2],
                    a * r[0] + b * r[1] + c * r[2],
                ));
            }
        }
    }
    out
}

/// `min over triangles T of patch, y ∈ T, of |x − y| + sign · r(y)`, pruned by the
/// distance lower bound.
fn min_over_patch(x: DVec3, patch: &Patch, sign: f64, good_enough: f64) -> f64 {
    let mut order: Vec<(f64, usize)> = patch
        .iter()
        .enumerate()
        .map(|(i, (p, r))| {
            let d = point_triangle_distance_squared(x, &Triangle::new(p[0], p[1], p[2])).sqrt();
            let extreme = if sign < 0.0 {
                r[0].max(r[1]).max(r[2])
            } else {
                -(r[0].min(r[1]).min(r[2]))
            };
            (d - extreme, i)
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = f64::INFINITY;
    for (lower, i) in order {
        if lower > best || best <= good_enough {
            break;
        }
        let mut value = min_over_triangle(x, patch[i].0, patch[i].1, sign);
        if value > good_enough + 0.5 * SLACK {
            // The pattern search can stall short of the minimum; settle it exactly.
            value = value.min(nested_min_over_triangle(x, patch[i].0, patch[i].1, sign));
        }
        best = best.min(value);
    }
    best
}

/// The minimum of a convex function on `[lo, hi]` by golden-section search (the bracket
/// shrinks to ~1e-13 of the interval), evaluated at the final point.
fn golden_min(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (lo, hi);
    let mut m1 = hi - ratio * (hi - lo);
    let mut m2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (f(m1), f(m2));
    for _ in 0..64 {
        if f1 < f2 {
            hi = m2;
            (m2, f2) = (m1, f1);
            m1 = hi - ratio * (hi - lo);
            f1 = f(m1);
        } else {
            lo = m1;
            (m1, f1) = (m2, f2);
            m2 = lo + ratio * (hi - lo);
            f2 = f(m2);
        }
    }
    f(0.5 * (lo + hi)).min(f1).min(f2)
}

/// The same minimum as [`min_over_triangle`], by nested golden-section searches: the function is
/// jointly convex in `λ`, so its minimum over `a` for fixed `b` is convex in `b`. Slower
/// (~4,400 evaluations) but never stalls; used only where the fast search fails a check.
fn nested_min_over_triangle(x: DVec3, p: [DVec3; 3], r: [f64; 3], sign: f64) -> f64 {
    let f = |a: f64, b: f64| {
        let c = 1.0 - a - b;
        (x - (a * p[0] + b * p[1] + c * p[2])).length() + sign * (a * r[0] + b * r[1] + c * r[2])
    };
    golden_min(0.0, 1.0, |b| golden_min(0.0, 1.0 - b, |a| f(a, b)))
}

/// Applies the collapse with radius `r` and returns the worst slacks of (A) — every old
/// point's ball `B(p, r_old(p))` inside the new tolerance volume — and (B) — every new
/// point `y` within `r(y)` of the old region swept by its old radii.
fn check(mesh: &HalfEdgeMesh, radii: &[f64], h: HalfEdgeId, target: DVec3, r: f64) -> (f64, f64) {
    let (u, v) = (mesh.origin(h), mesh.target(h));
    let old = star(mesh, radii, &[u, v]);
    let mut after = mesh.clone();
    after.collapse_edge(h, target).unwrap();
    let mut new_radii = radii.to_vec();
    new_radii[v.0 as usize] = r;
    let new = star(&after, &new_radii, &[v]);
    let worst_a = samples(&old, 6)
        .into_iter()
        .map(|(p, rp)| min_over_patch(p, &new, -1.0, -rp) + rp)
        .fold(f64::NEG_INFINITY, f64::max);
    let worst_b = samples(&new, 6)
        .into_iter()
        .map(|(y, ry)| min_over_patch(y, &old, 1.0, ry) - ry)
        .fold(f64::NEG_INFINITY, f64::max);
    (worst_a, worst_b)
}

/// The targets tried for an edge: `v`, the midpoint, the quadric optimum and a random
/// point near the edge.
fn targets(mesh: &HalfEdgeMesh, h: HalfEdgeId, rng: &mut SplitMix64) -> [DVec3; 4] {
    let (u, v) = (mesh.origin(h), mesh.target(h));
    let (pu, pv) = (mesh.position(u), mesh.position(v));
    let q = vertex_quadrics(mesh, 0.0);
    let optimum = optimal_position(&(q[u.0 as usize] + q[v.0 as usize]), pu, pv);
    let near = 0.5 * (pu + pv) + 0.3 * (pu - pv).length() * rng.vector_by_max();
    [pv, 0.5 * (pu + pv), optimum, near]
}

/// Checks both invariants for every collapsible interior edge of `mesh` (every
/// `stride`-th one) and every target; returns how many collapses were checked.
fn check_mesh(
    mesh: &HalfEdgeMesh,
    stride: usize,
    radius_scale: f64,
    rng: &mut SplitMix64,
) -> usize {
    let radii: Vec<f64> = (0..mesh.vertex_count())
        .map(|_| radius_scale * rng.unit_by_max())
        .collect();
    let mut checked = 0;
    for h in (0..mesh.halfedge_count()).step_by(stride) {
        let h = HalfEdgeId(h as u32);
        if mesh.check_collapse(h).is_err() {
            continue;
        }
        for target in targets(mesh, h, rng) {
            let Some(r) = edge_collapse_radius(mesh, &radii, h, target) else {
                continue;
            };
            let (a, b) = check(mesh, &radii, h, target, r);
            assert!(
                a <= SLACK,
                "(A) fails by {a} on {h:?} to {target} (r = {r})"
            );
            assert!(
                b <= SLACK,
                "(B) fails by {b} on {h:?} to {target} (r = {r})"
            );
            checked += 1;
        }
    }
    checked
}

#[test]
fn invariants_hold_on_a_noisy_sphere() {
    let mut rng = SplitMix64::new(1);
    let mesh = noisy_sphere(10, 0.02, &mut rng);
    assert!(check_mesh(&mesh, 5, 0.0, &mut rng) > 30);
}

#[test]
fn invariants_hold_on_a_noisy_grid_with_old_radii() {
    let mut rng = SplitMix64::new(2);
    let mesh = noisy_grid(6, 0.25, 0.05, &mut rng);
    assert!(check_mesh(&mesh, 3, 0.03, &mut rng) > 30);
}

#[test]
fn flat_region_with_target_in_the_plane_costs_nothing() {
    let mut rng = SplitMix64::new(3);
    let mesh = noisy_grid(6, 0.2, 0.0, &mut rng);
    let radii = vec![0.0; mesh.vertex_count()];
    let mut tried = 0;
    for h in 0..mesh.halfedge_count() {
        let h = HalfEdgeId(h as u32);
        if mesh.check_collapse(h).is_err() {
            continue;
        }
        let (pu, pv) = (mesh.position(mesh.origin(h)), mesh.position(mesh.target(h)));
        let Some(r) = edge_collapse_radius(&mesh, &radii, h, 0.5 * (pu + pv)) else {
            continue;
        };
        assert!(r < 1e-9, "flat collapse costs {r}");
        tried += 1;
    }
    assert!(tried > 10);
}

#[test]
fn tight_map_beats_the_simple_one_on_smooth_fans() {
    let mut rng = SplitMix64::new(4);
    // On a coarse sphere the tight map is better; on a fine one (a smoother region) by
    // far more, since its cost shrinks like the square of the edge length (least near the
    // poles of the UV sphere, where the regions are wide fans of slivers).
    for (resolution, worst_ratio) in [(16, 0.7), (64, 0.15)] {
        let mesh = noisy_sphere(resolution, 0.0, &mut rng);
        let radii = vec![0.0; mesh.vertex_count()];
        let mut compared = 0;
        for h in (0..mesh.halfedge_count()).step_by(17) {
            let h = HalfEdgeId(h as u32);
            if mesh.check_collapse(h).is_err() {
                continue;
            }
            let (pu, pv) = (mesh.position(mesh.origin(h)), mesh.position(mesh.target(h)));
            let region = Region::gather(&mesh, &radii, h, 0.5 * (pu + pv)).unwrap();
            let tight = region.tight_radius(region.candidate_normals()[0]).unwrap();
            let simple = region.simple_radius();
            assert!(
                tight < worst_ratio * simple,
                "tight {tight} vs simple {simple} at resolution {resolution}"
            );
            compared += 1;
        }
        assert!(compared > 20);
    }
}

#[test]
fn target_at_v_is_no_worse_than_the_half_edge_collapse() {
    let mut rng = SplitMix64::new(5);
    for mesh in [
        noisy_sphere(12, 0.01, &mut rng),
        noisy_grid(7, 0.2, 0.03, &mut rng),
    ] {
        let radii: Vec<f64> = (0..mesh.vertex_count())
            .map(|_| 0.02 * rng.unit_by_max())
            .collect();
        let mut compared = 0;
        for h in 0..mesh.halfedge_count() {
            let h = HalfEdgeId(h as u32);
            if mesh.check_collapse(h).is_err() || mesh.is_boundary_vertex(mesh.target(h)) {
                continue;
            }
            let Some(half) = collapse_radius(&mesh, &radii, h, BoundaryPolicy::Lock) else {
                continue;
            };
            let pv = mesh.position(mesh.target(h));
            let full = edge_collapse_radius(&mesh, &radii, h, pv).unwrap();
            assert!(full <= half + 1e-9, "full {full} vs half-edge {half}");
            compared += 1;
        }
        assert!(compared > 30);
    }
}

#[test]
fn boundary_edges_and_bad_targets_are_refused() {
    let mut rng = SplitMix64::new(6);
    let mesh = noisy_grid(4, 0.1, 0.0, &mut rng);
    let radii = vec![0.0; mesh.vertex_count()];
    for h in 0..mesh.halfedge_count() {
        let h = HalfEdgeId(h as u32);
        let (u, v) = (mesh.origin(h), mesh.target(h));
        let pv = mesh.position(v);
        let r = edge_collapse_radius(&mesh, &radii, h, pv);
        if mesh.is_boundary_vertex(u) || mesh.is_boundary_vertex(v) {
            assert!(r.is_none());
        }
        assert!(edge_collapse_radius(&mesh, &radii, h, DVec3::NAN).is_none());
        // Far outside the link polygon, in the plane: triangles flip.
        let far = pv + DVec3::new(10.0, 0.0, 0.0);
        assert!(edge_collapse_radius(&mesh, &radii, h, far).is_none());
    }
}

#[test]
fn raised_target_needs_at_least_its_height() {
    let mut rng = SplitMix64::new(8);
    let mesh = noisy_grid(6, 0.0, 0.0, &mut rng);
    let radii = vec![0.0; mesh.vertex_count()];
    // Interior vertex (3, 3) and its right neighbour (4, 3).
    let (u, v) = (VertexId(7 * 3 + 3), VertexId(7 * 3 + 4));
    let h = mesh.outgoing(u).find(|&g| mesh.target(g) == v).unwrap();
    let mid = 0.5 * (mesh.position(u) + mesh.position(v));
    let r = edge_collapse_radius(&mesh, &radii, h, mid + DVec3::Z * 0.05).unwrap();
    assert!(r >= 0.05, "{r}");
    // The projected map moves points straight up: the height itself, plus rounding.
    assert!(r <= 0.05 * (1.0 + 1e-9), "{r}");
    assert!(check(&mesh, &radii, h, mid + DVec3::Z * 0.05, r).0 <= SLACK);
}

#[test]
fn a_spike_overlapping_the_other_star_is_not_taken_for_injective() {
    // Projections where each star turns once around its centre but the stars overlap:
    // the new fan is not star-shaped, so the tight map must give up.
    let center = DVec2::ZERO;
    let fan = [
        (DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)),
        (DVec2::new(0.0, 1.0), DVec2::new(-1.0, 0.0)),
        (DVec2::new(-1.0, 0.0), DVec2::new(0.0, -1.0)),
        (DVec2::new(0.0, -1.0), DVec2::new(1.0, 0.0)),
    ];
    assert!(is_one_turn(center, fan.into_iter()));
    assert!(!is_one_turn(DVec2::new(2.0, 0.0), fan.into_iter()));
    assert!(!is_one_turn(center, fan.into_iter().take(3)));
}

#[test]
fn helpers_locate_and_cross() {
    let tri = [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(0.0, 2.0)];
    let (l, tag) = locate(DVec2::new(0.5, 0.5), [(tri, 7)].into_iter()).unwrap();
    assert_eq!(tag, 7);
    assert!((l[1] - 0.25).abs() < 1e-15 && (l[2] - 0.25).abs() < 1e-15);
    assert!(locate(DVec2::new(3.0, 3.0), [(tri, 7)].into_iter()).is_none());
    let (s, t) = crossing(
        DVec2::new(-1.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, -1.0),
        DVec2::new(0.0, 3.0),
    )
    .unwrap();
    assert!((s - 0.5).abs() < 1e-15 && (t - 0.25).abs() < 1e-15);
    assert!(crossing(DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::new(1.0, 1.0)).is_none());
    assert_eq!(required(1.0, 0.5), Some(2.0));
    assert_eq!(required(-1.0, 0.5), Some(0.0));
    assert_eq!(required(1.0, 0.0), None);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(64), ..ProptestConfig::default() })]

    #[test]
    fn invariants_hold_for_random_collapses(
        sphere: bool,
        noise in 0.0f64..0.3,
        old_radii in 0.0f64..0.05,
        edge in 0usize..10_000,
        which in 0usize..4,
        seed in 0u64..u64::MAX,
    ) {
        let mut rng = SplitMix64::new(seed);
        let mesh = if sphere {
            noisy_sphere(8, 0.1 * noise, &mut rng)
        } else {
            noisy_grid(5, noise, 0.2 * noise, &mut rng)
        };
        let radii: Vec<f64> = (0..mesh.vertex_count()).map(|_| old_radii * rng.unit_by_max()).collect();
        let h = HalfEdgeId((edge % mesh.halfedge_count()) as u32);
        prop_assume!(mesh.check_collapse(h).is_ok());
        let target = targets(&mesh, h, &mut rng)[which];
        if let Some(r) = edge_collapse_radius(&mesh, &radii, h, target) {
            prop_assert!(r >= 0.0);
            let (a, b) = check(&mesh, &radii, h, target, r);
            prop_assert!(a <= SLACK, "(A) fails by {}", a);
            prop_assert!(b <= SLACK, "(B) fails by {}", b);
        }
    }
}
