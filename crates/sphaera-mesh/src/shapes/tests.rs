//! Brute-force checks of every shape: closed, oriented, manifold, genus, volume.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use proptest::prelude::*;

use super::*;
use crate::TriMesh;

fn signed_volume(mesh: &TriMesh) -> f64 {
    mesh.triangle_iter()
        .map(|t| t.a.dot(t.b.cross(t.c)) / 6.0)
        .sum()
}

/// Panics with a message unless the mesh is a closed, consistently oriented 2-manifold
/// without degenerate or duplicate triangles or unreferenced vertices, of the given genus.
fn assert_closed_manifold(mesh: &TriMesh, genus: i64, what: &str) {
    let tris = mesh.triangles();
    assert!(!tris.is_empty(), "{what}: no triangles");

    // Every directed edge once, and its reverse once: closed, 2 faces per edge, oriented.
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, &[a, b, c]) in tris.iter().enumerate() {
        assert!(
            a != b && b != c && c != a,
            "{what}: triangle {t} repeats a vertex"
        );
        for e in [(a, b), (b, c), (c, a)] {
            assert!(
                directed.insert(e, t).is_none(),
                "{what}: directed edge {e:?} used twice (non-manifold or flipped)"
            );
        }
    }
    for &(a, b) in directed.keys() {
        assert!(
            directed.contains_key(&(b, a)),
            "{what}: edge {a}-{b} is a boundary"
        );
    }

    // No duplicate triangles (same vertex set).
    let mut seen = HashSet::new();
    for (t, tri) in tris.iter().enumerate() {
        let mut key = *tri;
        key.sort_unstable();
        assert!(seen.insert(key), "{what}: triangle {t} duplicates another");
    }

    // Every vertex referenced, and its umbrella is a single fan (vertex-manifold).
    let mut next: HashMap<u32, HashMap<u32, u32>> = HashMap::new();
    for &[a, b, c] in tris {
        for (v, p, q) in [(a, b, c), (b, c, a), (c, a, b)] {
            next.entry(v).or_default().insert(p, q);
        }
    }
    assert_eq!(
        next.len(),
        mesh.vertex_count(),
        "{what}: unreferenced vertices"
    );
    for (&v, link) in &next {
        let (&start, _) = link.iter().next().unwrap();
        let (mut current, mut steps) = (start, 0);
        loop {
            current = link[&current];
            steps += 1;
            if current == start {
                break;
            }
            assert!(
                steps <= link.len(),
                "{what}: vertex {v} link is not a cycle"
            );
        }
        assert_eq!(
            steps,
            link.len(),
            "{what}: vertex {v} is non-manifold (two fans)"
        );
    }

    // No degenerate triangles, relative to the mesh's scale and the triangle's own edges.
    for (t, tri) in mesh.triangle_iter().enumerate() {
        assert!(
            !tri.is_degenerate(1e-3),
            "{what}: triangle {t} is degenerate: {tri:?}"
        );
    }

    // Euler characteristic; closed ⇒ E = 3F/2.
    let (v, f) = (mesh.vertex_count() as i64, tris.len() as i64);
    let e = directed.len() as i64 / 2;
    assert_eq!(v - e + f, 2 - 2 * genus, "{what}: Euler characteristic");

    assert!(signed_volume(mesh) > 0.0, "{what}: inward oriented");
}

#[test]
fn every_default_shape_is_a_closed_oriented_manifold_of_its_genus() {
    for shape in &DEFAULT_SHAPES {
        for resolution in [3, 4, 5, 8, 13, 32] {
            let mesh = shape.build(resolution).unwrap();
            let what = format!("{} at resolution {resolution}", shape.name());
            assert_closed_manifold(&mesh, i64::from(shape.genus()), &what);
        }
    }
}

#[test]
fn cube_and_l_block_work_at_resolution_one() {
    for shape in [DEFAULT_SHAPES[0], DEFAULT_SHAPES[9]] {
        let mesh = shape.build(1).unwrap();
        assert_closed_manifold(&mesh, 0, shape.name());
    }
}

#[test]
fn volume_converges_to_the_analytic_volume() {
    for shape in &DEFAULT_SHAPES {
        let exact = shape.volume();
        let mut previous = f64::INFINITY;
        for resolution in [8, 16, 32, 64, 128] {
            let mesh = shape.build(resolution).unwrap();
            let error = (signed_volume(&mesh) - exact).abs() / exact;
            // The coarsest circle: the torus's minor circle has resolution·r/R segments.
            let segments = match *shape {
                Shape::Torus {
                    major_radius,
                    minor_radius,
                } => resolution as f64 * minor_radius / major_radius,
                _ => resolution as f64,
            };
            let bound = 20.0 / (segments * segments);
            assert!(
                error <= bound,
                "{} at {resolution}: relative volume error {error:e} > {bound:e}",
                shape.name()
            );
            // Polygonal shapes get better; exact ones stay exact (up to rounding).
            assert!(
                error <= previous || error < 1e-10,
                "{}: not converging ({error:e} after {previous:e})",
                shape.name()
            );
            previous = error;
        }
    }
}

#[test]
fn exact_shapes_have_exact_volume() {
    for shape in [DEFAULT_SHAPES[0], DEFAULT_SHAPES[9]] {
        for resolution in [1, 2, 7] {
            let mesh = shape.build(resolution).unwrap();
            let error = (signed_volume(&mesh) - shape.volume()).abs();
            assert!(error < 1e-12, "{}: {error:e}", shape.name());
        }
    }
}

#[test]
fn cone_apex_is_a_single_vertex() {
    let mesh = cone(1.0, 2.0, 17).unwrap();
    let apex = DVec3::new(0.0, 0.0, 1.0);
    let apex_vertices: Vec<usize> = (0..mesh.vertex_count())
        .filter(|&v| mesh.positions()[v].distance(apex) < 1e-9)
        .collect();
    assert_eq!(apex_vertices.len(), 1);
    let fan = mesh
        .triangles()
        .iter()
        .filter(|t| t.contains(&(apex_vertices[0] as u32)))
        .count();
    assert_eq!(fan, 17);
}

#[test]
fn shapes_are_deterministic() {
    for shape in &DEFAULT_SHAPES {
        assert_eq!(shape.build(11).unwrap(), shape.build(11).unwrap());
    }
}

#[test]
fn bad_parameters_are_errors() {
    use crate::MeshError::{InvalidParameter, ShapeTooLarge};
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            sphere(bad, 8),
            Err(InvalidParameter { name: "radius", .. })
        ));
        assert!(matches!(
            cube(bad, 8),
            Err(InvalidParameter { name: "size", .. })
        ));
        assert!(matches!(
            cylinder(1.0, bad, 8),
            Err(InvalidParameter { name: "height", .. })
        ));
        assert!(cone(bad, 1.0, 8).is_err());
        assert!(torus(1.0, bad, 8).is_err());
        assert!(thick_tube(0.5, 1.0, bad, 8).is_err());
        assert!(s_tube(bad, 1.0, 8).is_err());
        assert!(l_block(2.0, 1.0, bad, 8).is_err());
        assert!(ellipsoid(DVec3::new(1.0, bad, 1.0), 8).is_err());
    }
    assert!(matches!(
        capsule(1.0, -1.0, 8),
        Err(InvalidParameter { name: "length", .. })
    ));
    assert!(capsule(1.0, 0.0, 8).is_ok());
    for resolution in [0, 1, 2] {
        assert!(matches!(
            sphere(1.0, resolution),
            Err(InvalidParameter {
                name: "resolution",
                ..
            })
        ));
    }
    assert!(matches!(
        cube(1.0, 0),
        Err(InvalidParameter {
            name: "resolution",
            ..
        })
    ));
    assert!(matches!(
        torus(1.0, 1.0, 8),
        Err(InvalidParameter {
            name: "minor_radius",
            ..
        })
    ));
    assert!(matches!(
        thick_tube(1.0, 1.0, 1.0, 8),
        Err(InvalidParameter {
            name: "inner_radius",
            ..
        })
    ));
    assert!(matches!(
        s_tube(2.0, 1.0, 8),
        Err(InvalidParameter {
            name: "tube_radius",
            ..
        })
    ));
    assert!(matches!(
        l_block(1.0, 1.0, 1.0, 8),
        Err(InvalidParameter {
            name: "arm_width",
            ..
        })
    ));
    // Huge requests are refused before allocating.
    assert!(matches!(sphere(1.0, usize::MAX), Err(ShapeTooLarge { .. })));
    assert!(matches!(cube(1.0, usize::MAX), Err(ShapeTooLarge { .. })));
    assert!(matches!(
        torus(1.0, 0.999, 1 << 20),
        Err(ShapeTooLarge { .. })
    ));
    assert!(matches!(s_tube(1e-300, 1.0, 8), Err(ShapeTooLarge { .. })));
    assert!(matches!(
        l_block(1e300, 1e-300, 1.0, 1),
        Err(ShapeTooLarge { .. })
    ));
    assert!(matches!(
        cylinder(1e-300, 1.0, 8),
        Err(ShapeTooLarge { .. })
    ));
    let message = sphere(-1.0, 8).unwrap_err().to_string();
    assert_eq!(
        message,
        "parameter `radius` is -1, but it must be finite and positive"
    );
}

#[test]
fn resolutions_whose_vertex_count_overflows_are_refused() {
    use crate::MeshError::ShapeTooLarge;
    // `(n + 1)²` is 2⁶⁴ here, which wraps to 0 in `usize` arithmetic: the estimate is in
    // `f64`, so the request is refused before anything is allocated.
    let wraps = u32::MAX as usize;
    for resolution in [wraps, usize::MAX] {
        let error = square_sheet(1.0, resolution).expect_err("too large");
        assert!(
            matches!(
                error,
                ShapeTooLarge {
                    limit: MAX_VERTICES,
                    ..
                }
            ),
            "{error}"
        );
        assert!(matches!(
            ring_sheet(1.0, 0.5, resolution),
            Err(ShapeTooLarge { .. })
        ));
        assert!(matches!(
            ring_sheet(1.0, 0.0, resolution),
            Err(ShapeTooLarge { .. })
        ));
    }
    let message = square_sheet(1.0, wraps).unwrap_err().to_string();
    assert!(message.contains(&MAX_VERTICES.to_string()), "{message}");
    // The cap itself passes the check; one vertex more does not.
    assert!(check_vertex_budget("test", MAX_VERTICES as f64).is_ok());
    assert!(check_vertex_budget("test", MAX_VERTICES as f64 + 1.0).is_err());
    assert!(check_vertex_budget("test", f64::INFINITY).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    /// Random proportions and resolutions: still closed, oriented, manifold, right genus.
    #[test]
    fn random_proportions_give_valid_meshes(
        index in 0usize..10,
        a in 0.05f64..3.0,
        b in 0.05f64..0.95,
        c in 0.05f64..3.0,
        resolution in 3usize..24,
    ) {
        let shape = match DEFAULT_SHAPES[index] {
            Shape::Cube { .. } => Shape::Cube { size: a },
            Shape::Sphere { .. } => Shape::Sphere { radius: a },
            Shape::Ellipsoid { .. } => Shape::Ellipsoid { semi_axes: DVec3::new(a, b, c) },
            Shape::Capsule { .. } => Shape::Capsule { radius: a, length: c },
            Shape::Cylinder { .. } => Shape::Cylinder { radius: a, height: c },
            Shape::Cone { .. } => Shape::Cone { radius: a, height: c },
            Shape::Torus { .. } => Shape::Torus { major_radius: a, minor_radius: a * b },
            Shape::ThickTube { .. } => {
                Shape::ThickTube { inner_radius: a * b, outer_radius: a, height: c }
            }
            Shape::STube { .. } => Shape::STube { tube_radius: a * b, bend_radius: a },
            Shape::LBlock { .. } => {
                Shape::LBlock { leg_length: a, arm_width: a * b.max(0.2), depth: c }
            }
        };
        let mesh = shape.build(resolution).unwrap();
        assert_closed_manifold(&mesh, i64::from(shape.genus()), &format!("{shape:?}"));
        let error = (signed_volume(&mesh) - shape.volume()).abs() / shape.volume();
        prop_assert!(error < 0.9, "{shape:?}: volume error {error}");
    }
}
