//! Polygons with holes, multipolygons and the queries that say where, against brute force:
//! random multipolygons of star-shaped islands with star-shaped lakes (snapped to a grid,
//! so that query points fall exactly on vertices and edges; touching and overlapping
//! islands included), scaled by powers of two and moved far from the origin; the nearest
//! edge and every intersecting pair of edges of single outlines too.

// The tree's nearest edge is computed by the same segment arithmetic as brute force's.
#![allow(clippy::float_cmp)]

use glam::DVec2;
use proptest::prelude::*;
use sphaera_hal::{
    Containment, HalError, HalMultiPolygon2, HalTree2, MultiPolygon2, Polyline2, RingId,
    intersecting_edges_brute, intersects_brute, nearest_edge_brute,
};
use sphaera_tests::random::SplitMix64;
use sphaera_tests::regions::{self, Side};

/// A star around `center`: `k` vertices at radii between `low` and `high`, snapped to a
/// grid of 1/4.
fn star(rng: &mut SplitMix64, center: DVec2, k: usize, low: f64, high: f64) -> Vec<DVec2> {
    (0..k)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / k as f64;
            let p = center + DVec2::from_angle(angle) * rng.range(low, high);
            (p * 4.0).round() / 4.0
        })
        .collect()
}

/// Islands on a 3 × 3 grid of spacing `spacing` (close enough to touch or overlap when
/// small), each with up to two lakes.
fn islands(seed: u64, spacing: f64) -> Vec<Vec<Vec<DVec2>>> {
    let mut rng = SplitMix64::new(seed);
    let count = 1 + rng.below(6) as usize;
    (0..count)
        .map(|i| {
            let center = DVec2::new((i % 3) as f64, (i / 3) as f64) * spacing;
            let k = 3 + rng.below(12) as usize;
            let mut rings = vec![star(&mut rng, center, k, 6.0, 10.0)];
            for lake in 0..rng.below(3) {
                let offset = DVec2::new(if lake == 0 { -2.5 } else { 2.5 }, 0.0);
                let k = 3 + rng.below(6) as usize;
                rings.push(star(&mut rng, center + offset, k, 0.5, 2.0));
            }
            rings
        })
        .collect()
}

/// The reference outside this crate: per polygon, the winding-number side of each ring
/// (`sphaera_tests::regions`), combined as GEOS does (inside the exterior, in no hole's
/// closure; on any ring, boundary, unless inside another polygon).
fn reference(shape: &[Vec<Vec<DVec2>>], x: DVec2) -> Containment {
    let mut boundary = false;
    for rings in shape {
        let sides: Vec<Side> = rings
            .iter()
            .map(|r| regions::locate_in_outline(r, x))
            .collect();
        if sides.contains(&Side::Boundary) && sides[0] != Side::Outside {
            boundary = true;
        }
        if sides[0] == Side::Inside && sides[1..].iter().all(|&s| s == Side::Outside) {
            return Containment::Inside;
        }
    }
    if boundary {
        Containment::Boundary
    } else {
        Containment::Outside
    }
}

/// Query points: a grid over the box (on vertices and edges of the 1/4 grid), every
/// vertex, every edge's midpoint.
fn queries(shape: &[Vec<Vec<DVec2>>], rng: &mut SplitMix64) -> Vec<DVec2> {
    let points: Vec<DVec2> = shape.iter().flatten().flatten().copied().collect();
    let (lo, hi) = points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(l, h), &p| (l.min(p), h.max(p)),
    );
    let mut out = points.clone();
    for ring in shape.iter().flatten() {
        for (i, &a) in ring.iter().enumerate() {
            out.push(a.midpoint(ring[(i + 1) % ring.len()]));
        }
    }
    for _ in 0..300 {
        let p = DVec2::new(
            rng.range(lo.x - 1.0, hi.x + 1.0),
            rng.range(lo.y - 1.0, hi.y + 1.0),
        );
        out.push((p * 8.0).round() / 8.0);
    }
    out
}

fn mapped(shape: &[Vec<Vec<DVec2>>], map: impl Fn(DVec2) -> DVec2) -> Vec<Vec<Vec<DVec2>>> {
    shape
        .iter()
        .map(|rings| {
            rings
                .iter()
                .map(|r| r.iter().map(|&p| map(p)).collect())
                .collect()
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Inclusion and localisation equal the references on every query point, at any
    /// power-of-two scale and far from the origin (answers identical, as the maps are
    /// exact on the snapped coordinates).
    #[test]
    fn inclusion_equals_the_references(
        seed in any::<u64>(),
        spacing in prop::sample::select(vec![12.0, 18.0, 25.0]),
        exponent in -20_i32..20,
        offset in prop::sample::select(vec![0.0, 1.0e6, -3.0e9]),
    ) {
        let scale = 2.0_f64.powi(exponent);
        let shape = mapped(&islands(seed, spacing), |p| p * scale + DVec2::splat(offset));
        let multi = MultiPolygon2::from_rings(shape.clone()).unwrap();
        let tree = HalMultiPolygon2::build(&multi).unwrap();
        let mut rng = SplitMix64::new(seed ^ 0x5eed);
        for x in queries(&shape, &mut rng) {
            let expected = reference(&shape, x);
            prop_assert_eq!(multi.contains_brute(x), expected, "contains_brute at {}", x);
            let location = tree.locate(x);
            prop_assert_eq!(location.containment, expected, "locate at {}", x);
            match (location.containment, location.ring) {
                (Containment::Inside, Some(ring)) => {
                    prop_assert!(!ring.is_hole());
                    let rings = &shape[ring.polygon];
                    prop_assert_eq!(regions::locate_in_outline(&rings[0], x), Side::Inside);
                }
                (Containment::Boundary, Some(ring)) => {
                    let outline = &shape[ring.polygon][ring.ring];
                    prop_assert_eq!(regions::locate_in_outline(outline, x), Side::Boundary);
                }
                (Containment::Outside, Some(ring)) => {
                    prop_assert!(ring.is_hole());
                    let outline = &shape[ring.polygon][ring.ring];
                    prop_assert_eq!(regions::locate_in_outline(outline, x), Side::Inside);
                }
                (Containment::Outside, None) => {}
                other => prop_assert!(false, "{:?} at {}", other, x),
            }
        }
    }

    /// The nearest edge's distance equals brute force's over every ring, and the edge
    /// named is that near.
    #[test]
    fn nearest_edge_equals_brute_force(seed in any::<u64>(), spacing in 12.0_f64..30.0) {
        let shape = islands(seed, spacing);
        let multi = MultiPolygon2::from_rings(shape.clone()).unwrap();
        let tree = HalMultiPolygon2::build(&multi).unwrap();
        let mut rng = SplitMix64::new(seed ^ 0xface);
        for x in queries(&shape, &mut rng) {
            let brute = multi
                .polygons()
                .iter()
                .flat_map(sphaera_hal::Polygon2::rings)
                .map(|r| nearest_edge_brute(r, x).distance)
                .fold(f64::INFINITY, f64::min);
            let nearest = tree.nearest_edge(x);
            prop_assert_eq!(nearest.distance, brute, "at {}", x);
            let ring = tree.ring(nearest.at.ring).polyline();
            let (a, b) = ring.edge(nearest.at.edge);
            let point = sphaera_hal::closest_on_segment(a, b, x);
            prop_assert_eq!(point.distance(x), brute);
            prop_assert_eq!(nearest.point, point);
        }
    }

    /// Every pair of intersecting ring edges, and whether the regions meet, equal brute
    /// force over every pair of rings (islands touching, overlapping, nested in lakes).
    #[test]
    fn intersection_equals_brute_force(
        first in any::<u64>(),
        second in any::<u64>(),
        shift in (-30_i32..30, -30_i32..30),
    ) {
        let a = islands(first, 20.0);
        let b = mapped(&islands(second, 20.0), |p| {
            p * 0.5 + DVec2::new(f64::from(shift.0), f64::from(shift.1)) * 0.5
        });
        let (ma, mb) = (
            MultiPolygon2::from_rings(a.clone()).unwrap(),
            MultiPolygon2::from_rings(b.clone()).unwrap(),
        );
        let (ta, tb) = (HalMultiPolygon2::build(&ma).unwrap(), HalMultiPolygon2::build(&mb).unwrap());
        let mut expected = Vec::new();
        for (ra, ring_a) in ta.rings() {
            for (rb, ring_b) in tb.rings() {
                for (i, j) in intersecting_edges_brute(ring_a.polyline(), ring_b.polyline()) {
                    expected.push((
                        sphaera_hal::RingEdge { ring: ra, edge: i },
                        sphaera_hal::RingEdge { ring: rb, edge: j },
                    ));
                }
            }
        }
        expected.sort_unstable();
        prop_assert_eq!(&ta.intersecting_edges(&tb), &expected);
        // The regions meet when boundaries do, or a polygon holds another's vertex.
        let holds = |m: &MultiPolygon2, other: &[Vec<Vec<DVec2>>]| {
            other.iter().any(|rings| m.contains_brute(rings[0][0]) != Containment::Outside)
        };
        let meet = !expected.is_empty() || holds(&ma, &b) || holds(&mb, &a);
        prop_assert_eq!(ta.intersects(&tb), meet);
        prop_assert_eq!(tb.intersects(&ta), meet);
    }

    /// Single outlines: the nearest edge and the intersecting pairs equal brute force,
    /// polygons against open polylines included (GEOS's region semantics).
    #[test]
    fn single_outline_queries_equal_brute_force(
        seed in any::<u64>(),
        closed in any::<bool>(),
        shift in (-12_i32..12, -12_i32..12),
    ) {
        let mut rng = SplitMix64::new(seed);
        let k = 3 + rng.below(30) as usize;
        let a = Polyline2::polygon(star(&mut rng, DVec2::ZERO, k, 3.0, 10.0)).unwrap();
        let center = DVec2::new(f64::from(shift.0), f64::from(shift.1));
        let k = 3 + rng.below(20) as usize;
        let points = star(&mut rng, center, k, 1.0, 6.0);
        let b = if closed { Polyline2::polygon(points) } else { Polyline2::open(points) }.unwrap();
        let (ta, tb) = (HalTree2::build(&a).unwrap(), HalTree2::build(&b).unwrap());
        prop_assert_eq!(ta.intersecting_edges(&tb), intersecting_edges_brute(&a, &b));
        let flipped: Vec<(usize, usize)> = intersecting_edges_brute(&b, &a);
        prop_assert_eq!(tb.intersecting_edges(&ta), flipped);
        let expected = regions::outlines_meet(a.points(), true, b.points(), closed);
        prop_assert_eq!(intersects_brute(&a, &b), expected);
        prop_assert_eq!(ta.intersects(&tb), expected);
        prop_assert_eq!(tb.intersects(&ta), expected);
        let multi = HalMultiPolygon2::build(&MultiPolygon2::from_rings(vec![vec![a.points().to_vec()]]).unwrap()).unwrap();
        prop_assert_eq!(multi.intersects_outline(&tb), expected);
        for x in queries(&[vec![a.points().to_vec(), b.points().to_vec()]], &mut rng) {
            for (tree, outline) in [(&ta, &a), (&tb, &b)] {
                let brute = nearest_edge_brute(outline, x);
                let nearest = tree.nearest_edge(x);
                prop_assert_eq!(nearest.distance, brute.distance, "at {}", x);
            }
        }
    }
}

#[test]
fn bad_rings_are_named() {
    let square = vec![
        DVec2::ZERO,
        DVec2::new(1.0, 0.0),
        DVec2::ONE,
        DVec2::new(0.0, 1.0),
    ];
    let error = MultiPolygon2::from_rings(vec![
        vec![square.clone()],
        vec![square.clone(), vec![DVec2::ZERO, DVec2::ONE]],
    ])
    .unwrap_err();
    assert!(
        matches!(
            error,
            HalError::Ring {
                polygon: 1,
                ring: 1,
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(
        error.to_string(),
        "polygon 1, hole 0: a polygon needs at least 3 vertices, got 2"
    );
    let nan = MultiPolygon2::from_rings(vec![vec![vec![
        DVec2::ZERO,
        DVec2::new(f64::NAN, 0.0),
        DVec2::ONE,
    ]]])
    .unwrap_err();
    assert!(
        nan.to_string()
            .starts_with("polygon 0, the exterior: vertex 1"),
        "{nan}"
    );
    assert!(matches!(
        MultiPolygon2::from_rings(vec![]),
        Err(HalError::EmptyMultiPolygon)
    ));
    assert!(matches!(
        MultiPolygon2::from_rings(vec![vec![]]),
        Err(HalError::Ring {
            polygon: 0,
            ring: 0,
            ..
        })
    ));
    let open = Polyline2::open(square.clone()).unwrap();
    let closed = Polyline2::polygon(square.clone()).unwrap();
    assert!(matches!(
        sphaera_hal::Polygon2::new(closed, vec![open]),
        Err(HalError::OpenRing { ring: 1 })
    ));
    // GeoJSON's repeated closing point is dropped, not taken as a zero-length edge.
    let mut repeated = square.clone();
    repeated.push(square[0]);
    let multi = MultiPolygon2::from_rings(vec![vec![repeated]]).unwrap();
    assert_eq!(multi.polygons()[0].exterior().points().len(), 4);
}

/// A lake with an island in it (the island a polygon of its own, as GeoJSON writes it):
/// the island's land is inside, the water between outside in the lake's ring.
#[test]
fn an_island_in_a_lake() {
    let square = |lo: f64, hi: f64| {
        vec![
            DVec2::new(lo, lo),
            DVec2::new(hi, lo),
            DVec2::new(hi, hi),
            DVec2::new(lo, hi),
        ]
    };
    let multi = MultiPolygon2::from_rings(vec![
        vec![square(0.0, 10.0), square(2.0, 8.0)],
        vec![square(4.0, 6.0)],
    ])
    .unwrap();
    let tree = HalMultiPolygon2::build(&multi).unwrap();
    let water = tree.locate(DVec2::new(3.0, 5.0));
    assert_eq!(water.containment, Containment::Outside);
    assert_eq!(
        water.ring,
        Some(RingId {
            polygon: 0,
            ring: 1
        })
    );
    let island = tree.locate(DVec2::new(5.0, 5.0));
    assert_eq!(island.containment, Containment::Inside);
    assert_eq!(
        island.ring,
        Some(RingId {
            polygon: 1,
            ring: 0
        })
    );
    assert_eq!(tree.contains(DVec2::new(1.0, 1.0)), Containment::Inside);
    assert_eq!(tree.contains(DVec2::new(11.0, 1.0)), Containment::Outside);
    assert_eq!(tree.locate(DVec2::new(11.0, 1.0)).ring, None);
}
