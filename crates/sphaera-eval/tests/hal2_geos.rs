//! 2D point inclusion of the HAL tree against GEOS prepared geometry on every shared
//! outline (`shared/data/polygons/*.txt`): random points in the bounding box and within
//! an edge's length of the outline, every vertex, every edge midpoint, and points an ulp
//! and a little more beside the outline. HAL's answer (through its cell grid) is also its
//! hierarchy's walk alone at every point.
//! HAL's `Inside` must be GEOS's `contains`, `Inside | Boundary` its `intersects`
//! (`sphaera_eval::geos_peer`). Needs the `geos` feature (`required-features`); skipped
//! with a message when the data is absent, failing under `SPHAERA_REQUIRE_DATA=1`.

use geos::{Geom, Geometry, PreparedGeometry};
use sphaera::hal::{Containment, HalTree2, Polyline2, contains_brute, ray_crossing};
use sphaera::mesh::glam::DVec2;
use sphaera_eval::geos_peer::{QUERY_SEED, geos_containment, geos_points, geos_polygon, outlines};
use sphaera_eval::query_sets::{box_points, near_outline_points};

/// Random points per outline.
const RANDOM_POINTS: usize = 2_000;

/// Edge midpoints per outline decided by the brute-force reference as well (an O(N)
/// scan each; every midpoint on outlines of at most this many edges).
const BRUTE_MIDPOINTS: usize = 1_000;

/// One outline, its tree and its prepared GEOS polygon.
struct Case<'a> {
    name: &'a str,
    outline: &'a Polyline2,
    tree: HalTree2,
    prepared: PreparedGeometry<'a>,
}

impl Case<'_> {
    /// HAL's answer at `x`, checked against the hierarchy's walk alone.
    fn hal(&self, x: DVec2) -> Containment {
        let answer = self.tree.contains(x).expect("a closed outline");
        let walk = self
            .tree
            .contains_by_hierarchy(x)
            .expect("a closed outline");
        assert_eq!(
            answer, walk,
            "{}: the grid and the walk differ at {x:?}",
            self.name
        );
        answer
    }

    /// GEOS's answer at each of `points`, in HAL's terms.
    fn geos(&self, points: &[DVec2]) -> Vec<Containment> {
        let geometries: Vec<Geometry> = geos_points(points).expect("GEOS points");
        geometries
            .iter()
            .map(|g| geos_containment(&self.prepared, g).expect("GEOS answers"))
            .collect()
    }

    /// Asserts that HAL and GEOS agree at every point of `points` (`what` names them).
    fn assert_agree(&self, what: &str, points: &[DVec2]) {
        let geos = self.geos(points);
        let differ: Vec<(DVec2, Containment, Containment)> = points
            .iter()
            .zip(geos)
            .map(|(&x, g)| (x, self.hal(x), g))
            .filter(|(_, hal, geos)| hal != geos)
            .collect();
        assert!(
            differ.is_empty(),
            "{}: HAL and GEOS differ at {} of {} {what} (point, HAL, GEOS), first: {:?}",
            self.name,
            differ.len(),
            points.len(),
            &differ[..differ.len().min(5)]
        );
    }
}

#[test]
fn hal_contains_equals_geos_on_every_outline() {
    let Some(data) = sphaera_tests::data_dir("hal2_geos") else {
        return;
    };
    let outlines = outlines(&data).expect("the shared outlines");
    for (name, outline) in &outlines {
        let polygon = geos_polygon(outline).expect("a GEOS polygon");
        let case = Case {
            name,
            outline,
            tree: HalTree2::build(outline).expect("builds"),
            prepared: polygon.to_prepared_geom().expect("GEOS prepares it"),
        };
        check_outline(&case);
    }
}

fn check_outline(case: &Case<'_>) {
    let outline = case.outline;
    let n = outline.edge_count();

    // Random points in the bounding box (the bench's points, and more).
    let random = box_points(outline, RANDOM_POINTS, QUERY_SEED);
    case.assert_agree("random points", &random);
    let near = near_outline_points(outline, RANDOM_POINTS, QUERY_SEED);
    case.assert_agree("random points near the outline", &near);
    assert!(
        random.iter().any(|&x| case.hal(x) == Containment::Inside)
            && random.iter().any(|&x| case.hal(x) == Containment::Outside),
        "{}: the random points should fall both inside and outside",
        case.name
    );

    // Every vertex is on the boundary: GEOS intersects, does not contain.
    let vertices = outline.points();
    assert!(
        vertices
            .iter()
            .all(|&v| case.hal(v) == Containment::Boundary),
        "{}: a vertex is not on HAL's boundary",
        case.name
    );
    case.assert_agree("vertices", vertices);

    // Every edge midpoint. The rounded midpoint of a–b lies on the edge only when the
    // rounding happens to keep it on the line; otherwise it is a point within an ulp
    // beside the edge, strictly inside or outside. Which one is decided exactly: the
    // edge's own exact test (`ray_crossing` is `None` exactly on the segment) says
    // whether it is on the boundary (on a simple outline no other edge passes through
    // it), and `contains_brute`, exact, decides the side on up to `BRUTE_MIDPOINTS` of
    // them. HAL must give these exact answers; GEOS is compared with HAL everywhere: on
    // the edge it must answer boundary (intersects, not contains), and beside it the
    // exact side, since its orientation test (double-double behind a filter) decides
    // points an ulp from a segment of these coordinates correctly.
    let midpoints: Vec<DVec2> = (0..n)
        .map(|i| {
            let (a, b) = outline.edge(i);
            0.5 * (a + b)
        })
        .collect();
    let mut on_edge = 0;
    for (i, &m) in midpoints.iter().enumerate() {
        let (a, b) = outline.edge(i);
        if ray_crossing(a, b, m).is_none() {
            on_edge += 1;
            assert_eq!(
                case.hal(m),
                Containment::Boundary,
                "{}: midpoint {i} is on its edge",
                case.name
            );
        }
    }
    let stride = n.div_ceil(BRUTE_MIDPOINTS).max(1);
    for (i, &m) in midpoints.iter().enumerate().step_by(stride) {
        assert_eq!(
            case.hal(m),
            contains_brute(outline, m).expect("closed"),
            "{}: midpoint {i}",
            case.name
        );
    }
    case.assert_agree("edge midpoints", &midpoints);
    // On these outlines about a third of the midpoints round onto their edge and the
    // others fall inside or outside about evenly (counted when this test was written):
    // both kinds are exercised.
    assert!(on_edge > 0, "{}: no midpoint is on its edge", case.name);

    // Near the boundary: each vertex moved by one ulp in x and in y (some of these land
    // on an adjacent edge, e.g. along a horizontal one: boundary points again), and each
    // midpoint moved across its edge by about 10⁻⁹ of the coordinates' size, both ways.
    let mut near = Vec::with_capacity(8 * n);
    for &v in vertices {
        near.extend([
            DVec2::new(v.x.next_up(), v.y),
            DVec2::new(v.x.next_down(), v.y),
            DVec2::new(v.x, v.y.next_up()),
            DVec2::new(v.x, v.y.next_down()),
        ]);
    }
    for (i, &m) in midpoints.iter().enumerate() {
        let (a, b) = outline.edge(i);
        let normal = (b - a).perp().normalize_or_zero();
        let step = 1e-9 * m.abs().max_element().max(1.0);
        near.extend([m + step * normal, m - step * normal]);
    }
    case.assert_agree("points near the boundary", &near);
}
