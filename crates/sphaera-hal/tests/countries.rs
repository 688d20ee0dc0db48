//! Real multipolygons (`tests/data/countries`: Natural Earth countries with their islands
//! and holes, kept in the repository): inclusion, localisation and intersection against
//! brute force, and what a GIS user expects of them (San Marino is not in Italy, though
//! Italy surrounds it; Lesotho borders South Africa).

use std::path::PathBuf;

use glam::DVec2;
use sphaera_hal::{Containment, HalMultiPolygon2, MultiPolygon2, RingId, intersecting_edges_brute};
use sphaera_io::{FilePolicy, read_shapes};
use sphaera_tests::random::SplitMix64;

fn country(name: &str) -> MultiPolygon2 {
    country_and_dropped(name).0
}

/// The country, and the rings dropped as bounding no area.
fn country_and_dropped(name: &str) -> (MultiPolygon2, Vec<RingId>) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/countries")
        .join(format!("{name}.geojson"));
    let shapes = read_shapes(&path, &FilePolicy::default()).expect("the country file");
    MultiPolygon2::from_rings_dropping_degenerate(shapes.polygons).expect("a multipolygon")
}

/// The mean of a multipolygon's first exterior's vertices (inside for these small,
/// round countries).
fn middle(shape: &MultiPolygon2) -> DVec2 {
    let points = shape.polygons()[0].exterior().points();
    points.iter().sum::<DVec2>() / points.len() as f64
}

#[test]
fn inclusion_on_countries_equals_brute_force() {
    // Italy's Vatican hole is two points at 1:10m: dropped, and said so.
    let vatican = vec![RingId {
        polygon: 0,
        ring: 2,
    }];
    for (name, polygons, rings, dropped) in [
        ("italy", 29, 30, vatican),
        ("south-africa", 3, 4, vec![]),
        ("indonesia", 264, 264, vec![]),
        ("san-marino", 1, 1, vec![]),
    ] {
        let (shape, found) = country_and_dropped(name);
        assert_eq!(found, dropped, "{name}");
        assert_eq!(
            (shape.polygons().len(), shape.ring_count()),
            (polygons, rings),
            "{name}"
        );
        let tree = HalMultiPolygon2::build(&shape).unwrap();
        let (lo, hi) = shape.bounds();
        let mut rng = SplitMix64::new(41);
        let mut points: Vec<DVec2> = (0..3_000)
            .map(|_| DVec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y)))
            .collect();
        // Every tenth vertex of every ring: on the boundary.
        for polygon in shape.polygons() {
            for ring in polygon.rings() {
                points.extend(ring.points().iter().step_by(10));
            }
        }
        let mut counts = [0_usize; 3];
        for x in points {
            let expected = shape.contains_brute(x);
            assert_eq!(tree.contains(x), expected, "{name} at {x}");
            counts[expected as usize] += 1;
        }
        assert!(counts.iter().all(|&c| c > 0), "{name}: {counts:?}");
    }
}

#[test]
fn enclaves_are_holes_and_their_borders_are_shared() {
    for (outer, enclave) in [("italy", "san-marino"), ("south-africa", "lesotho")] {
        let (big, small) = (country(outer), country(enclave));
        let (tb, ts) = (
            HalMultiPolygon2::build(&big).unwrap(),
            HalMultiPolygon2::build(&small).unwrap(),
        );
        let inside_enclave = middle(&small);
        assert_eq!(
            ts.contains(inside_enclave),
            Containment::Inside,
            "{enclave}"
        );
        let location = tb.locate(inside_enclave);
        assert_eq!(
            location.containment,
            Containment::Outside,
            "{enclave} is not in {outer}"
        );
        let hole = location.ring.expect("in a hole");
        assert!(hole.is_hole(), "{outer}: {hole:?}");
        // The border is shared: edges meet, the regions intersect, and every pair found is
        // one brute force finds.
        assert!(tb.intersects(&ts) && ts.intersects(&tb));
        let pairs = tb.intersecting_edges(&ts);
        assert!(!pairs.is_empty());
        let brute = intersecting_edges_brute(
            tb.ring(hole).polyline(),
            ts.ring(RingId {
                polygon: 0,
                ring: 0,
            })
            .polyline(),
        );
        let found: Vec<(usize, usize)> = pairs
            .iter()
            .filter(|(a, _)| a.ring == hole)
            .map(|(a, b)| (a.edge, b.edge))
            .collect();
        assert_eq!(found, brute, "{outer} and {enclave}");
        // The nearest edge to the enclave's middle is on the hole or the enclave's ring:
        // the same border.
        let nearest = tb.nearest_edge(inside_enclave);
        assert_eq!(nearest.at.ring, hole, "{outer}");
    }
}
