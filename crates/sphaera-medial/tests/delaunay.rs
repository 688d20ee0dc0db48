//! The tetrahedralization against brute force: empty circumspheres, positive volumes,
//! the Euler characteristic, hull volume, order independence and determinism, on random
//! and on degenerate (cospherical, coplanar, grid) input.

// Exact comparisons are the point: the inputs are exact grid and lattice points.
#![allow(clippy::float_cmp)]

use std::collections::BTreeSet;

use proptest::prelude::*;
use sphaera_medial::{DVec3, Delaunay, DelaunayError, INFINITE};
use sphaera_tests::point_sets::{integer_sphere, random_in_cube};

fn signed_volume(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    (a - d).dot((b - d).cross(c - d)) / 6.0
}

/// Everything the tests check on one tetrahedralization.
fn check(points: &[DVec3]) -> Delaunay {
    let delaunay = Delaunay::new(points).expect("tetrahedralization");
    delaunay.validate().expect("valid");
    check_built(&delaunay);
    delaunay
}

fn check_built(delaunay: &Delaunay) {
    let points = delaunay.points();
    // Positive volumes, and the sum equals the hull's volume (no overlap, no gap).
    let mut volume = 0.0;
    let mut scale: f64 = 0.0;
    for (_, t) in delaunay.tetrahedra() {
        let [a, b, c, d] = t.map(|v| delaunay.point(v));
        let v = signed_volume(a, b, c, d);
        assert!(v > 0.0, "flat or negative tetrahedron {t:?}");
        volume += v;
        scale = scale.max((b - a).length()).max((c - a).length());
    }
    let mut hull = 0.0;
    let mut hull_faces = 0;
    let mut live_ghosts = 0;
    for t in 0..u32::try_from(delaunay.vertex_count() * 8).unwrap() {
        if !delaunay.is_live(t) || delaunay.is_finite(t) {
            continue;
        }
        live_ghosts += 1;
        let vertices = delaunay.vertices(t);
        let slot = vertices.iter().position(|&v| v == INFINITE).unwrap();
        // The apex stands beyond the facet, so the facet with the origin as the apex's
        // stand-in gives the volume of the cone from the origin, negated.
        let mut q = vertices.map(|v| {
            if v == INFINITE {
                DVec3::ZERO
            } else {
                delaunay.point(v)
            }
        });
        q[slot] = DVec3::ZERO;
        hull -= signed_volume(q[0], q[1], q[2], q[3]);
        hull_faces += 1;
    }
    assert_eq!(live_ghosts, hull_faces);
    let tolerance = 1e-9 * scale.powi(3).max(1e-300) * points.len() as f64;
    assert!(
        (volume - hull).abs() <= tolerance,
        "volume {volume} != hull {hull}"
    );
    // Euler characteristic of a triangulated ball: V − E + F − T = 1.
    let mut edges = BTreeSet::new();
    let mut faces = BTreeSet::new();
    let mut vertices = BTreeSet::new();
    let mut tets = 0_i64;
    for (_, t) in delaunay.tetrahedra() {
        tets += 1;
        let mut s = t;
        s.sort_unstable();
        for i in 0..4 {
            vertices.insert(s[i]);
            for j in i + 1..4 {
                edges.insert((s[i], s[j]));
            }
            let f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| s[k]).collect();
            faces.insert(f);
        }
    }
    let euler = vertices.len() as i64 - edges.len() as i64 + faces.len() as i64 - tets;
    assert_eq!(euler, 1, "Euler characteristic");
    // Every non-duplicate point is a vertex.
    let used = (0..delaunay.vertex_count() as u32)
        .filter(|&v| delaunay.duplicate_of(v).is_none())
        .count();
    assert_eq!(used, vertices.len());
}

/// Brute-force emptiness: no point strictly inside any circumsphere (exact predicate).
fn check_empty_spheres(delaunay: &Delaunay) {
    let coord = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    for (_, t) in delaunay.tetrahedra() {
        let [a, b, c, d] = t.map(|v| coord(delaunay.point(v)));
        for (v, &p) in delaunay.points().iter().enumerate() {
            if t.contains(&(v as u32)) {
                continue;
            }
            let inside = robust::insphere(a, b, c, d, coord(p));
            assert!(inside <= 0.0, "point {v} inside the circumsphere of {t:?}");
        }
    }
}

/// The tetrahedra as sets of positions, independent of vertex ids.
fn canonical(delaunay: &Delaunay) -> BTreeSet<[[u64; 3]; 4]> {
    delaunay
        .tetrahedra()
        .map(|(_, t)| {
            let mut corners = t.map(|v| delaunay.point(v).to_array().map(f64::to_bits));
            corners.sort_unstable();
            corners
        })
        .collect()
}

fn grid(n: i32) -> Vec<DVec3> {
    let mut points = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                points.push(DVec3::new(f64::from(x), f64::from(y), f64::from(z)));
            }
        }
    }
    points
}

/// Samples of a cube's surface on a grid: many coplanar and cocircular points.
fn cube_surface(n: i32) -> Vec<DVec3> {
    grid(n + 1)
        .into_iter()
        .filter(|p| p.min_element() == 0.0 || p.max_element() == f64::from(n))
        .collect()
}

/// Integer points on the circle x² + y² = 25 at several heights: an exactly cocircular
/// cylinder.
fn integer_cylinder() -> Vec<DVec3> {
    let circle = [
        (5, 0),
        (4, 3),
        (3, 4),
        (0, 5),
        (-3, 4),
        (-4, 3),
        (-5, 0),
        (-4, -3),
        (-3, -4),
        (0, -5),
        (3, -4),
        (4, -3),
    ];
    (0..6)
        .flat_map(|z| {
            circle
                .iter()
                .map(move |&(x, y)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
        })
        .collect()
}

#[test]
fn degenerate_inputs_give_valid_tetrahedralizations() {
    for (name, points) in [
        ("grid 6", grid(6)),
        ("cube surface 8", cube_surface(8)),
        ("sphere r=5", integer_sphere(5)),
        ("sphere r=9", integer_sphere(9)),
        ("cylinder", integer_cylinder()),
    ] {
        let delaunay = check(&points);
        check_empty_spheres(&delaunay);
        assert_eq!(delaunay.fallback_scans(), 0, "{name}");
    }
}

#[test]
fn the_result_does_not_depend_on_the_input_order() {
    for points in [
        cube_surface(6),
        integer_sphere(5),
        integer_cylinder(),
        grid(5),
    ] {
        let reference = canonical(&check(&points));
        let mut reversed = points.clone();
        reversed.reverse();
        assert_eq!(canonical(&check(&reversed)), reference);
        // One at a time through `insert`, in a third order.
        let mut rotated = points.clone();
        rotated.rotate_left(points.len() / 3);
        let start = rotated.len().min(40);
        if let Ok(mut incremental) = Delaunay::new(&rotated[..start]) {
            for &p in &rotated[start..] {
                incremental.insert(p).unwrap();
            }
            incremental.validate().unwrap();
            assert_eq!(canonical(&incremental), reference);
        }
    }
}

#[test]
fn the_same_input_gives_the_same_output() {
    let points = random_in_cube(3_000, 11);
    let a = Delaunay::new(&points).unwrap();
    let b = Delaunay::new(&points).unwrap();
    let ids = |d: &Delaunay| d.tetrahedra().collect::<Vec<_>>();
    assert_eq!(ids(&a), ids(&b));
}

#[test]
fn twenty_thousand_random_in_cube() {
    let points = random_in_cube(20_000, 3);
    let delaunay = check(&points);
    assert_eq!(delaunay.fallback_scans(), 0);
    // About 6.5 tetrahedra per point for uniform random points.
    let per_point = delaunay.tetrahedron_count() as f64 / 20_000.0;
    assert!((6.0..7.0).contains(&per_point), "{per_point}");
}

#[test]
fn insert_reports_what_changed() {
    let mut delaunay = Delaunay::new(&integer_sphere(3)).unwrap();
    let before: BTreeSet<u32> = delaunay.tetrahedra().map(|(t, _)| t).collect();
    let report = delaunay.insert(DVec3::new(0.1, 0.2, 0.3)).unwrap();
    assert!(!report.duplicate);
    delaunay.validate().unwrap();
    let after: BTreeSet<u32> = delaunay.tetrahedra().map(|(t, _)| t).collect();
    // Every created tetrahedron contains the new vertex; every finite tetrahedron that
    // disappeared was reported removed.
    for &t in &report.created {
        assert!(delaunay.vertices(t).contains(&report.vertex));
    }
    for t in before.difference(&after) {
        assert!(report.removed.contains(t));
    }
    for t in after.difference(&before) {
        assert!(report.created.contains(t));
    }
    // A duplicate changes nothing.
    let again = delaunay.insert(DVec3::new(0.1, 0.2, 0.3)).unwrap();
    assert!(again.duplicate);
    assert_eq!(again.vertex, report.vertex);
    assert!(again.removed.is_empty() && again.created.is_empty());
    // A point far outside the hull.
    delaunay.insert(DVec3::new(40.0, -3.0, 7.0)).unwrap();
    delaunay.validate().unwrap();
    check_built(&delaunay);
}

#[test]
fn voronoi_cells_surround_their_points() {
    let points = random_in_cube(500, 5);
    let delaunay = check(&points);
    let mut total = 0;
    for v in 0..500 {
        let cell = delaunay.voronoi_cell(v).unwrap();
        total += cell.tetrahedra.len();
        for &t in &cell.tetrahedra {
            let (center, radius) = delaunay.circumsphere(t).unwrap();
            // The Voronoi vertex is equidistant from the cell's point and its other
            // forming points, and no point is closer.
            let to_v = (delaunay.point(v) - center).length();
            assert!((to_v - radius).abs() <= 1e-9 * radius.max(1.0));
            let nearest = points
                .iter()
                .map(|p| (*p - center).length())
                .fold(f64::INFINITY, f64::min);
            assert!(nearest >= radius * (1.0 - 1e-9) - 1e-12);
        }
    }
    assert_eq!(total, 4 * delaunay.tetrahedron_count());
}

#[test]
fn bad_inputs_get_clear_errors() {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    assert_eq!(
        Delaunay::new(&[p(0.0, 0.0, 0.0), p(1.0, f64::NAN, 0.0)]).unwrap_err(),
        DelaunayError::NonFinite { index: 1 }
    );
    assert_eq!(
        Delaunay::new(&[p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)]).unwrap_err(),
        DelaunayError::TooFewPoints { distinct: 3 }
    );
    assert_eq!(
        Delaunay::new(&[]).unwrap_err(),
        DelaunayError::TooFewPoints { distinct: 0 }
    );
    let duplicates = vec![p(1.0, 2.0, 3.0); 10];
    assert_eq!(
        Delaunay::new(&duplicates).unwrap_err(),
        DelaunayError::TooFewPoints { distinct: 1 }
    );
    let line: Vec<DVec3> = (0..10)
        .map(|i| p(f64::from(i), 2.0 * f64::from(i), 0.5))
        .collect();
    assert_eq!(
        Delaunay::new(&line).unwrap_err(),
        DelaunayError::Flat { dimension: 1 }
    );
    let plane: Vec<DVec3> = grid(4).into_iter().filter(|q| q.z == 1.0).collect();
    assert_eq!(
        Delaunay::new(&plane).unwrap_err(),
        DelaunayError::Flat { dimension: 2 }
    );
    let mut d = Delaunay::new(&grid(2)).unwrap();
    assert!(matches!(
        d.insert(p(f64::INFINITY, 0.0, 0.0)),
        Err(DelaunayError::NonFinite { .. })
    ));
    d.validate().unwrap();
}

#[test]
fn duplicate_points_are_recorded_not_inserted() {
    let mut points = grid(3);
    points.extend(grid(3));
    let delaunay = check(&points);
    for v in 27..54 {
        assert_eq!(
            delaunay.duplicate_of(v).map(|u| delaunay.point(u)),
            Some(points[v as usize])
        );
    }
    assert!(delaunay.voronoi_cell(30).is_none());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    #[test]
    fn random_points_give_a_delaunay_tetrahedralization(
        raw in prop::collection::vec((-1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64), 5..80)
    ) {
        let points: Vec<DVec3> = raw.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
        let delaunay = check(&points);
        check_empty_spheres(&delaunay);
    }

    #[test]
    fn points_on_a_small_grid_give_a_delaunay_tetrahedralization(
        raw in prop::collection::vec((0..4_i32, 0..4_i32, 0..3_i32), 8..70)
    ) {
        // Heavy duplication, coplanarity and cosphericity.
        let points: Vec<DVec3> = raw
            .iter()
            .map(|&(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
            .collect();
        match Delaunay::new(&points) {
            Ok(delaunay) => {
                delaunay.validate().unwrap();
                check_built(&delaunay);
                check_empty_spheres(&delaunay);
                let mut shuffled = points.clone();
                shuffled.reverse();
                let other = Delaunay::new(&shuffled).unwrap();
                prop_assert_eq!(canonical(&other), canonical(&delaunay));
            }
            Err(DelaunayError::Flat { .. } | DelaunayError::TooFewPoints { .. }) => {}
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn points_on_a_sphere_in_floating_point(
        raw in prop::collection::vec((0.0..std::f64::consts::TAU, -1.0..1.0_f64), 5..80)
    ) {
        let points: Vec<DVec3> = raw
            .iter()
            .map(|&(phi, z)| {
                let r = (1.0 - z * z).sqrt();
                DVec3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        if let Ok(delaunay) = Delaunay::new(&points) {
            delaunay.validate().unwrap();
            check_built(&delaunay);
            check_empty_spheres(&delaunay);
        }
    }
}
