//! The 2D HAL tree against brute force: point inclusion on random and degenerate polygons
//! (collinear runs, repeated vertices, points on edges, self-touching outlines), the
//! tree's structure and bounding areas, adaptive approximation, and the real outlines of
//! `shared/data/polygons`.

use glam::DVec2;
use proptest::prelude::*;
use sphaera_hal::{Containment, HalError, HalTree2, LensKind, Node2, Polyline2, contains_brute};
use sphaera_tests::random::SplitMix64;
use sphaera_tests::regions::{self, Side};

/// Where `x` lies, by the reference outside this crate (a winding number with exact
/// orientation tests, `sphaera_tests::regions`), in HAL's terms. The crate's own
/// [`contains_brute`], a documented reference users call, is checked against it too.
fn reference(outline: &Polyline2, x: DVec2) -> Containment {
    let expected = match regions::locate_in_outline(outline.points(), x) {
        Side::Inside => Containment::Inside,
        Side::Boundary => Containment::Boundary,
        Side::Outside => Containment::Outside,
    };
    assert_eq!(
        contains_brute(outline, x).unwrap(),
        expected,
        "contains_brute at {x}"
    );
    expected
}

fn polygon(points: &[(f64, f64)]) -> Polyline2 {
    Polyline2::polygon(points.iter().map(|&(x, y)| DVec2::new(x, y)).collect()).expect("valid")
}

/// The polyline positions `first..=last` of `node`, as points.
fn part(tree: &HalTree2, node: &Node2) -> Vec<DVec2> {
    (node.first..=node.last)
        .map(|p| tree.polyline().points()[tree.vertex_at(p)])
        .collect()
}

/// Every structural promise: in-order traversal gives the outline, one node per vertex
/// off the level-0 chord, each node's bounding area holds its part (vertices and points
/// along its edges), and the split vertex lies strictly inside the part.
fn check_structure(tree: &HalTree2) {
    let n = tree.polyline().points().len();
    let full = tree.level(tree.depth());
    let expected: Vec<usize> = (0..n).map(|p| tree.vertex_at(p as u32)).collect();
    assert_eq!(full, expected, "in-order traversal is the outline");
    // The level-0 chord's two ends have no node.
    assert_eq!(tree.nodes().len(), n - 2, "one node per vertex (Theorem 3)");
    for node in tree.nodes() {
        assert!(node.first < node.split && node.split < node.last);
        let points = part(tree, node);
        let (a, b) = (points[0], points[points.len() - 1]);
        for pair in points.windows(2) {
            for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
                let x = pair[0].lerp(pair[1], t);
                assert!(
                    node.lens.may_contain(a, b, x),
                    "node {node:?}: {x} of its part outside its bounding area"
                );
            }
        }
    }
}

#[test]
fn awkward_polygons_keep_their_structure_and_answer_as_brute_force() {
    let regular: Vec<(f64, f64)> = (0..24)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 24.0;
            (a.cos(), a.sin())
        })
        .collect();
    let cases: Vec<(&str, Polyline2)> = vec![
        ("triangle", polygon(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])),
        (
            "regular 24-gon (every vertex on the smallest disc)",
            polygon(&regular),
        ),
        (
            "square with collinear runs",
            polygon(&[
                (0.0, 0.0),
                (1.0, 0.0),
                (2.0, 0.0),
                (3.0, 0.0),
                (3.0, 1.0),
                (3.0, 2.0),
                (3.0, 3.0),
                (2.0, 3.0),
                (1.0, 3.0),
                (0.0, 3.0),
                (0.0, 2.0),
                (0.0, 1.0),
            ]),
        ),
        (
            "repeated vertices",
            polygon(&[
                (0.0, 0.0),
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 0.0),
                (2.0, 2.0),
                (0.0, 2.0),
            ]),
        ),
        (
            "self-touching bow tie",
            polygon(&[
                (0.0, 0.0),
                (1.0, 1.0),
                (2.0, 0.0),
                (2.0, 2.0),
                (1.0, 1.0),
                (0.0, 2.0),
            ]),
        ),
        (
            "collinear back-track (a spike along an edge's line)",
            polygon(&[(0.0, 0.0), (4.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]),
        ),
        (
            "flat polygon",
            polygon(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)]),
        ),
    ];
    let mut rng = SplitMix64::new(17);
    for (name, outline) in &cases {
        let tree = HalTree2::build(outline).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_structure(&tree);
        // Vertices, edge midpoints, points near them, and random points.
        let mut queries: Vec<DVec2> = Vec::new();
        for i in 0..outline.edge_count() {
            let (a, b) = outline.edge(i);
            queries.extend([a, b, a.midpoint(b), a.midpoint(b) + DVec2::new(1e-9, -1e-9)]);
        }
        for _ in 0..400 {
            queries.push(DVec2::new(rng.range(-1.0, 4.5), rng.range(-1.0, 3.5)));
        }
        for x in queries {
            assert_eq!(
                tree.contains(x).unwrap(),
                reference(outline, x),
                "{name}: point {x}"
            );
        }
    }
}

#[test]
fn the_boundary_is_reported_exactly() {
    let square = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]);
    let tree = HalTree2::build(&square).unwrap();
    for (x, expected) in [
        ((1.0, 0.0), Containment::Boundary),
        ((2.0, 2.0), Containment::Boundary),
        ((0.0, 1.5), Containment::Boundary),
        ((1.0, 1.0), Containment::Inside),
        ((1.0, 1e-300), Containment::Inside),
        ((1.0, -1e-300), Containment::Outside),
        ((3.0, 1.0), Containment::Outside),
    ] {
        assert_eq!(
            tree.contains(DVec2::new(x.0, x.1)).unwrap(),
            expected,
            "{x:?}"
        );
    }
}

#[test]
fn a_collinear_back_track_makes_a_union_that_is_never_used_to_prune() {
    // The chord's line holds a vertex outside the chord: no disc through the chord's ends
    // holds it, Theorem 1's premise fails, and the area is a half-plane ∪ a disc.
    let spike = Polyline2::open(vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(3.0, 0.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(1.0, -1.0),
        DVec2::new(2.0, 0.0),
    ])
    .unwrap();
    let tree = HalTree2::build(&spike).unwrap();
    let root = tree.nodes()[0];
    assert_eq!(root.lens.kind(), LensKind::Union);
    assert!(root.width.is_infinite());
    let (a, b) = (DVec2::ZERO, DVec2::new(2.0, 0.0));
    assert!(root.lens.may_contain(a, b, DVec2::new(-5.0, -5.0)));
}

#[test]
fn open_polylines_have_a_chord_root_and_no_inside() {
    let line = Polyline2::open(vec![DVec2::ZERO, DVec2::X]).unwrap();
    let tree = HalTree2::build(&line).unwrap();
    assert!(tree.nodes().is_empty());
    assert_eq!(tree.level(0), vec![0, 1]);
    assert!(matches!(
        tree.contains(DVec2::ZERO),
        Err(HalError::OpenPolyline)
    ));
    assert!(matches!(
        tree.contains_by_hierarchy(DVec2::ZERO),
        Err(HalError::OpenPolyline)
    ));
    let zigzag: Vec<DVec2> = (0..9)
        .map(|i| DVec2::new(f64::from(i), f64::from(i % 2)))
        .collect();
    let tree = HalTree2::build(&Polyline2::open(zigzag).unwrap()).unwrap();
    check_structure(&tree);
    assert_eq!(tree.level(0), vec![0, 8]);
}

#[test]
fn bad_input_is_refused_with_its_reason() {
    assert!(matches!(
        Polyline2::polygon(vec![DVec2::ZERO, DVec2::X]),
        Err(HalError::TooFewVertices {
            needed: 3,
            count: 2,
            ..
        })
    ));
    assert!(matches!(
        Polyline2::open(vec![DVec2::ZERO]),
        Err(HalError::TooFewVertices { needed: 2, .. })
    ));
    assert!(matches!(
        Polyline2::polygon(vec![DVec2::ZERO, DVec2::X, DVec2::new(f64::NAN, 0.0)]),
        Err(HalError::NonFinite { vertex: 2, .. })
    ));
    let error = Polyline2::parse("# a comment\n0 0\n1 0\n1 x\n", true).unwrap_err();
    assert!(matches!(error, HalError::Parse { line: 4, .. }), "{error}");
    assert!(matches!(
        Polyline2::read_polygon("/nonexistent/outline.txt"),
        Err(HalError::Io { .. })
    ));
}

#[test]
fn adaptive_approximation_stays_within_its_width() {
    let mut rng = SplitMix64::new(5);
    // A wobbly circle of 400 vertices.
    let points: Vec<DVec2> = (0..400)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 400.0;
            DVec2::from_angle(a) * (1.0 + 0.2 * (7.0 * a).sin() + 0.01 * rng.range(-1.0, 1.0))
        })
        .collect();
    let outline = Polyline2::polygon(points.clone()).unwrap();
    let tree = HalTree2::build(&outline).unwrap();
    let mut previous = 0;
    for tolerance in [0.5, 0.1, 0.02, 0.005] {
        let approximation = tree.approximate(tolerance);
        assert!(approximation.width <= tolerance);
        assert!(approximation.vertices.len() >= 3 || tolerance >= 0.5);
        // Every vertex lies within the width of the line of the edge standing for it.
        let kept = &approximation.vertices;
        let position = |v: usize| (v + points.len() - tree.vertex_at(0)) % points.len();
        for (k, &v) in kept.iter().enumerate() {
            let w = kept[(k + 1) % kept.len()];
            let (a, b) = (points[v], points[w]);
            let end = if position(w) == 0 {
                points.len()
            } else {
                position(w)
            };
            for p in position(v)..=end {
                let x = points[tree.vertex_at(p as u32)];
                let distance = (b - a).perp_dot(x - a).abs() / a.distance(b);
                assert!(distance <= approximation.width * (1.0 + 1e-9) + 1e-12);
            }
        }
        // A smaller tolerance refines a superset of the nodes.
        assert!(kept.len() >= previous);
        previous = kept.len();
    }
    assert_eq!(tree.approximate(0.0).vertices.len(), 400);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// Random polygons on a coarse integer grid (so collinear runs, repeated vertices and
    /// queries exactly on edges and vertices are common): the tree answers as brute force.
    #[test]
    fn point_inclusion_equals_brute_force(
        raw in prop::collection::vec((0i32..12, 0i32..12), 3..40),
        queries in prop::collection::vec((-1i32..26, -1i32..26), 1..60),
    ) {
        let outline = Polyline2::polygon(
            raw.iter().map(|&(x, y)| DVec2::new(f64::from(x), f64::from(y))).collect(),
        ).unwrap();
        let tree = HalTree2::build(&outline).unwrap();
        check_structure(&tree);
        for (qx, qy) in queries {
            // Half-grid queries: on vertices, on edge midpoints, between.
            let x = DVec2::new(f64::from(qx) * 0.5, f64::from(qy) * 0.5);
            prop_assert_eq!(tree.contains(x).unwrap(), reference(&outline, x));
            prop_assert_eq!(tree.contains_by_hierarchy(x).unwrap(), reference(&outline, x));
        }
    }

    /// Random star-shaped polygons in general position: the same.
    #[test]
    fn point_inclusion_equals_brute_force_on_stars(
        radii in prop::collection::vec(0.2f64..1.0, 3..80),
        queries in prop::collection::vec((-1.2f64..1.2, -1.2f64..1.2), 1..40),
    ) {
        let n = radii.len() as f64;
        let points: Vec<DVec2> = radii.iter().enumerate()
            .map(|(i, &r)| DVec2::from_angle(std::f64::consts::TAU * i as f64 / n) * r)
            .collect();
        let outline = Polyline2::polygon(points).unwrap();
        let tree = HalTree2::build(&outline).unwrap();
        check_structure(&tree);
        for (x, y) in queries {
            let x = DVec2::new(x, y);
            prop_assert_eq!(tree.contains(x).unwrap(), reference(&outline, x));
            prop_assert_eq!(tree.contains_by_hierarchy(x).unwrap(), reference(&outline, x));
        }
    }
}

#[test]
fn real_outlines_answer_as_brute_force() {
    let Some(data) = sphaera_tests::data_dir("real_outlines_answer_as_brute_force") else {
        return;
    };
    let dir = data.join("polygons");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "txt"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    let mut rng = SplitMix64::new(3);
    for file in files {
        let outline = Polyline2::read_polygon(&file).unwrap();
        let tree = HalTree2::build(&outline).unwrap();
        let n = outline.points().len();
        assert_eq!(tree.level(tree.depth()).len(), n);
        assert_eq!(tree.nodes().len(), n - 2);
        let (lo, hi) = outline.bounds();
        let queries = if n > 20_000 { 200 } else { 1_000 };
        for k in 0..queries {
            let x = if k % 10 == 0 {
                outline.points()[rng.below(n as u64) as usize]
            } else {
                DVec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y))
            };
            assert_eq!(
                tree.contains(x).unwrap(),
                reference(&outline, x),
                "{}: {x}",
                file.display()
            );
            assert_eq!(
                tree.contains_by_hierarchy(x).unwrap(),
                reference(&outline, x),
                "{}: {x}",
                file.display()
            );
        }
    }
}

/// Norway's fjords: at the same covering error, the adaptive approximation needs far
/// fewer vertices than a uniform level (the paper's Fig. 6 point).
#[test]
fn adaptivity_pays_on_the_fjords() {
    let Some(data) = sphaera_tests::data_dir("adaptivity_pays_on_the_fjords") else {
        return;
    };
    let outline = Polyline2::read_polygon(data.join("polygons/norway.txt")).unwrap();
    let tree = HalTree2::build(&outline).unwrap();
    for level in [6, 9, 12] {
        let uniform = tree.level(level);
        let width = tree.level_width(level);
        let adaptive = tree.approximate(width);
        assert!(adaptive.width <= width);
        assert!(
            adaptive.vertices.len() <= uniform.len(),
            "level {level}: adaptive {} against uniform {}",
            adaptive.vertices.len(),
            uniform.len()
        );
    }
}

#[test]
fn lens_areas_are_the_caps_of_their_discs() {
    use sphaera_hal::Lens;
    let (a, b) = (DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0));
    // Bulge 0 on both sides: the diametral disc, area π.
    let disc = Lens {
        left: 0.0,
        right: 0.0,
    };
    assert!((disc.area(a, b).unwrap() - std::f64::consts::PI).abs() < 1e-12);
    // One side only: a half disc.
    let half = Lens {
        left: 0.0,
        right: f64::INFINITY,
    };
    assert!((half.area(a, b).unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert_eq!(Lens::EMPTY.area(a, b), Some(0.0));
    assert_eq!(
        Lens {
            left: f64::INFINITY,
            right: 0.0
        }
        .area(a, b),
        None
    );
    // A shallow lens against a Monte-Carlo count of its points.
    let lens = Lens {
        left: -1.5,
        right: 0.7,
    };
    let mut rng = SplitMix64::new(9);
    let inside = (0..200_000)
        .filter(|_| lens.may_contain(a, b, DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0))))
        .count();
    let estimate = 4.0 * inside as f64 / 200_000.0;
    assert!(
        (lens.area(a, b).unwrap() - estimate).abs() < 0.02,
        "{estimate}"
    );
}

/// Scaling by a power of two gives the same tree, every width scaled exactly; a turn by a
/// quarter and a translation by a power of two (both exact in floating point) give the
/// same tree too.
#[test]
// Exact equality is the point: these transforms are exact in floating point.
#[allow(clippy::float_cmp)]
fn exact_similarities_give_the_same_tree() {
    let mut rng = SplitMix64::new(23);
    let points: Vec<DVec2> = (0..300)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 300.0;
            DVec2::from_angle(a) * (1.0 + 0.3 * rng.range(-1.0, 1.0))
        })
        .collect();
    let base = HalTree2::build(&Polyline2::polygon(points.clone()).unwrap()).unwrap();
    type Map = Box<dyn Fn(DVec2) -> DVec2>;
    let transforms: [(&str, Map, f64); 4] = [
        ("×8", Box::new(|p| p * 8.0), 8.0),
        ("×2⁻³⁰", Box::new(|p| p * 2f64.powi(-30)), 2f64.powi(-30)),
        ("quarter turn", Box::new(|p: DVec2| p.perp()), 1.0),
        (
            "moved by 1024",
            Box::new(|p| p + DVec2::new(1024.0, -512.0)),
            1.0,
        ),
    ];
    for (name, map, scale) in transforms {
        let moved = Polyline2::polygon(points.iter().map(|&p| map(p)).collect()).unwrap();
        let tree = HalTree2::build(&moved).unwrap();
        assert_eq!(
            tree.vertex_at(0),
            base.vertex_at(0),
            "{name}: level-0 chord"
        );
        assert_eq!(tree.nodes().len(), base.nodes().len());
        for (a, b) in base.nodes().iter().zip(tree.nodes()) {
            assert_eq!(
                (a.first, a.last, a.split, a.level),
                (b.first, b.last, b.split, b.level),
                "{name}"
            );
            if scale != 1.0 {
                // Bulges are scale free; widths scale exactly.
                assert_eq!(a.lens, b.lens, "{name}");
                assert_eq!(a.width * scale, b.width, "{name}");
            } else {
                // The move costs the coordinates 10 bits; widths move by that rounding.
                assert!(
                    (a.width - b.width).abs() <= 1e-9 * (1.0 + a.width),
                    "{name}: {} against {}",
                    a.width,
                    b.width
                );
            }
        }
    }
}

/// Theorem 2's worst case: a half-circle arc whose radius shrinks slightly toward its end,
/// so that every split peels one vertex; the tree is as deep as the arc is long, and still
/// answers as brute force (the work stack, not recursion, carries the depth).
#[test]
fn the_worst_case_makes_a_tree_as_deep_as_the_outline() {
    let n: u32 = 2_000;
    let last = f64::from(n - 1);
    let points: Vec<DVec2> = (0..n)
        .map(|i| {
            let t = f64::from(i) / last;
            DVec2::from_angle(std::f64::consts::PI * t) * (1.0 + 1e-3 * (1.0 - t))
        })
        .collect();
    let tree = HalTree2::build(&Polyline2::open(points.clone()).unwrap()).unwrap();
    assert_eq!(tree.depth(), n as usize - 2);
    check_structure(&tree);
    // Closed, the same arc still builds and locates.
    let closed = Polyline2::polygon(points).unwrap();
    let tree = HalTree2::build(&closed).unwrap();
    for x in [
        DVec2::new(0.0, 0.5),
        DVec2::new(0.0, 1.0005),
        DVec2::new(0.3, -0.1),
    ] {
        assert_eq!(tree.contains(x).unwrap(), reference(&closed, x));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// Nearly collinear runs (vertices a few ulps off a line, which give near-straight
    /// chords huge bulges) far from the origin: inclusion and intersection answer as the
    /// reference outside this crate.
    #[test]
    fn near_collinear_outlines_far_away_answer_as_the_reference(
        wiggles in prop::collection::vec(-4i32..5, 3..30),
        offset_exponent in 0i32..13,
        offset in (-1.0..1.0f64, -1.0..1.0f64),
        queries in prop::collection::vec((-0.2f64..1.2, -3i32..4), 1..40),
        shift in (-0.5..0.5f64, -3i32..4),
    ) {
        let origin = DVec2::new(offset.0, offset.1) * 10f64.powi(offset_exponent);
        let n = wiggles.len();
        let ulp = |x: f64| f64::EPSILON * x.abs().max(1.0);
        // A run along y = 0 from x = 0 to 1, each vertex a few ulps off the line, closed
        // by a vertex below.
        let outline = |shift: DVec2| -> Vec<DVec2> {
            let mut points: Vec<DVec2> = wiggles.iter().enumerate().map(|(i, &w)| {
                let p = origin + shift + DVec2::new(i as f64 / (n - 1) as f64, 0.0);
                DVec2::new(p.x, p.y + f64::from(w) * ulp(p.y))
            }).collect();
            points.push(origin + shift + DVec2::new(0.5, -1.0));
            points
        };
        let first = outline(DVec2::ZERO);
        let Ok(polygon) = Polyline2::polygon(first.clone()) else {
            // Repeated points after rounding: refused by name, nothing to check.
            return Ok(());
        };
        let tree = HalTree2::build(&polygon).unwrap();
        for (x, k) in queries {
            let p = origin + DVec2::new(x, 0.0);
            let x = DVec2::new(p.x, p.y + f64::from(k) * ulp(p.y));
            prop_assert_eq!(tree.contains(x).unwrap(), reference(&polygon, x), "{}", x);
            prop_assert_eq!(tree.contains_by_hierarchy(x).unwrap(), reference(&polygon, x), "{}", x);
        }
        // A copy moved by a fraction along the run and a few ulps across it.
        let moved = DVec2::new(shift.0, f64::from(shift.1) * ulp(origin.y));
        let second = outline(moved);
        if let Ok(other) = Polyline2::polygon(second.clone()) {
            let other_tree = HalTree2::build(&other).unwrap();
            prop_assert_eq!(
                tree.intersects(&other_tree),
                regions::outlines_meet(&first, true, &second, true),
                "moved by {}", moved
            );
        }
    }
}
