//! The body of the `delaunay` fuzz target (`fuzz/fuzz_targets/delaunay.rs`, which depends
//! on this crate by path), shared with the proptest replay in
//! `tests/tests/delaunay_fuzz_replay.rs` so that every CI run exercises it.
//!
//! [`check`] decodes arbitrary bytes into points (grids of small integers, so that ties,
//! cospherical and coplanar subsets and duplicates are the rule), tetrahedralizes all but
//! the last few, inserts those one at a time, and panics on anything wrong: an error other
//! than the documented input errors (and then only when brute force agrees the input
//! deserves it), a failed [`Delaunay::validate`], a wrong duplicate report, a vertex
//! missing from every tetrahedron, or two builds of the same input that differ.
//!
//! Byte layout: byte 0 selects the mode (bits 0–1) and the grid side `2..=8`
//! (`2 + (byte0 >> 2) % 7`); byte 1 the number of points inserted one at a time after
//! the build (`byte1 % 17`); the rest are points:
//!
//! | mode | bytes per point | coordinate |
//! |---|---|---|
//! | 0 | 3 | `b % side`: an integer grid, exact ties everywhere |
//! | 1 | 3 | `0.3 + 0.1 · (b % side)`: a grid that is not exactly one in binary |
//! | 2 | 4 | the integer grid, each coordinate moved by 0 or ±2⁻⁴⁰ (bits of the 4th byte): nearly degenerate |
//! | 3 | 12 | little-endian `i32` / 2¹⁶: general position, and whatever the fuzzer repeats |

use sphaera_medial::{DVec3, Delaunay, DelaunayError};

/// At most this many points are decoded, so that one input stays fast.
const MAX_POINTS: usize = 300;

/// The points to build from and the points to insert afterwards, one at a time.
#[derive(Clone, Debug, PartialEq)]
pub struct Decoded {
    /// Given to `Delaunay::new`.
    pub initial: Vec<DVec3>,
    /// Given to `Delaunay::insert`, in order.
    pub inserted: Vec<DVec3>,
}

/// Decodes `bytes` as described in the module documentation.
///
/// # Examples
///
/// ```
/// use sphaera_medial::DVec3;
/// use sphaera_tests::delaunay_fuzz::decode;
///
/// // Mode 0 on a grid of side 2 + (8 >> 2) % 7 = 4; one point inserted late.
/// let decoded = decode(&[8, 1, 1, 2, 3, 5, 6, 7]);
/// assert_eq!(decoded.initial, [DVec3::new(1.0, 2.0, 3.0)]);
/// assert_eq!(decoded.inserted, [DVec3::new(1.0, 2.0, 3.0)]);
/// ```
pub fn decode(bytes: &[u8]) -> Decoded {
    let (&header, rest) = bytes.split_first().unwrap_or((&0, &[]));
    let (&insert_byte, body) = rest.split_first().unwrap_or((&0, &[]));
    let mode = header & 3;
    let side = 2 + (header >> 2) % 7;
    let grid = |b: u8| f64::from(b % side);
    let points: Vec<DVec3> = match mode {
        0 => body
            .chunks_exact(3)
            .map(|c| DVec3::new(grid(c[0]), grid(c[1]), grid(c[2])))
            .collect(),
        1 => body
            .chunks_exact(3)
            .map(|c| DVec3::new(grid(c[0]), grid(c[1]), grid(c[2])) * 0.1 + 0.3)
            .collect(),
        2 => body
            .chunks_exact(4)
            .map(|c| {
                let nudge = |k: u32| match (c[3] >> (2 * k)) & 3 {
                    1 => 2f64.powi(-40),
                    2 => -(2f64.powi(-40)),
                    _ => 0.0,
                };
                DVec3::new(
                    grid(c[0]) + nudge(0),
                    grid(c[1]) + nudge(1),
                    grid(c[2]) + nudge(2),
                )
            })
            .collect(),
        _ => body
            .chunks_exact(12)
            .map(|c| {
                let coordinate = |k: usize| {
                    let word = [c[4 * k], c[4 * k + 1], c[4 * k + 2], c[4 * k + 3]];
                    f64::from(i32::from_le_bytes(word)) / 65_536.0
                };
                DVec3::new(coordinate(0), coordinate(1), coordinate(2))
            })
            .collect(),
    };
    let mut points = points;
    points.truncate(MAX_POINTS);
    let split = points.len().saturating_sub(usize::from(insert_byte % 17));
    let inserted = points.split_off(split);
    Decoded {
        initial: points,
        inserted,
    }
}

/// Decodes `bytes` and checks everything; panics on any failure.
///
/// # Examples
///
/// ```
/// // Three points: too few for a tetrahedralization, and `check` agrees with the error.
/// sphaera_tests::delaunay_fuzz::check(&[0, 0, 1, 2, 3]);
/// // A 2×2×2 grid (header 0: side 2) is cospherical everywhere and still valid.
/// let mut bytes = vec![0, 0];
/// for i in 0..8_u8 {
///     bytes.extend([i & 1, (i >> 1) & 1, (i >> 2) & 1]);
/// }
/// sphaera_tests::delaunay_fuzz::check(&bytes);
/// ```
///
/// # Panics
///
/// On any failed check, with the input points.
pub fn check(bytes: &[u8]) {
    let Decoded { initial, inserted } = decode(bytes);
    let expected = expected_error(&initial);
    let mut delaunay = match Delaunay::new(&initial) {
        Ok(delaunay) => {
            assert_eq!(expected, None, "built a tetrahedralization of {initial:?}");
            delaunay
        }
        Err(error) => {
            assert_eq!(Some(error), expected, "wrong error for {initial:?}");
            return;
        }
    };
    check_built(&delaunay);
    let again = Delaunay::new(&initial).expect("the same input builds again");
    assert!(
        delaunay.tetrahedra().eq(again.tetrahedra()),
        "two builds of {initial:?} differ"
    );
    for &p in &inserted {
        let before = delaunay.vertex_count();
        let report = delaunay.insert(p).expect("a finite point inserts");
        assert_eq!(delaunay.point(report.vertex), p, "inserting {p}");
        if report.duplicate {
            assert_eq!(delaunay.vertex_count(), before, "duplicate {p} took an id");
            assert!(report.removed.is_empty() && report.created.is_empty());
        } else {
            assert_eq!(report.vertex as usize, before, "inserting {p}");
            assert!(!report.created.is_empty(), "inserting {p} created nothing");
        }
    }
    check_built(&delaunay);
}

/// The error `Delaunay::new` must return, by brute force with exact predicates.
fn expected_error(points: &[DVec3]) -> Option<DelaunayError> {
    let mut distinct: Vec<DVec3> = Vec::new();
    for &p in points {
        if !distinct.contains(&p) {
            distinct.push(p);
        }
    }
    if distinct.len() < 4 {
        return Some(DelaunayError::TooFewPoints {
            distinct: distinct.len(),
        });
    }
    let a = distinct[0];
    let b = distinct[1];
    let coord = |p: DVec3, x: usize, y: usize| robust::Coord { x: p[x], y: p[y] };
    let collinear = |c: DVec3| {
        [(0, 1), (1, 2), (2, 0)]
            .iter()
            .all(|&(x, y)| robust::orient2d(coord(a, x, y), coord(b, x, y), coord(c, x, y)) == 0.0)
    };
    let Some(&c) = distinct.iter().find(|&&c| !collinear(c)) else {
        return Some(DelaunayError::Flat { dimension: 1 });
    };
    let coord3 = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    let solid = distinct
        .iter()
        .any(|&d| robust::orient3d(coord3(a), coord3(b), coord3(c), coord3(d)) != 0.0);
    if solid {
        None
    } else {
        Some(DelaunayError::Flat { dimension: 2 })
    }
}

/// Validity, duplicates, and every distinct point in some finite tetrahedron.
fn check_built(delaunay: &Delaunay) {
    if let Err(error) = delaunay.validate() {
        panic!("{error} for {:?}", delaunay.points());
    }
    let points = delaunay.points();
    let mut used = vec![false; points.len()];
    for (_, t) in delaunay.tetrahedra() {
        for v in t {
            used[v as usize] = true;
        }
    }
    for (v, &p) in points.iter().enumerate() {
        let id = u32::try_from(v).expect("few points");
        let earlier = points[..v].iter().position(|&q| q == p);
        match delaunay.duplicate_of(id) {
            Some(original) => {
                assert_eq!(points[original as usize], p, "vertex {v}: wrong original");
                assert!(
                    used[original as usize] && !used[v],
                    "vertex {v}: duplicate in use"
                );
                assert!(delaunay.duplicate_of(original).is_none());
            }
            None => {
                assert!(used[v], "vertex {v} ({p}) is in no tetrahedron");
                if let Some(e) = earlier {
                    // The earlier copy must then be the duplicate.
                    assert_eq!(delaunay.duplicate_of(e as u32), Some(id), "vertex {v}");
                }
            }
        }
    }
}
