//! 3D point inclusion where rays run into edges and vertices: points on the axes of a cube
//! and an octahedron (every axis-aligned and diagonal ray from the centre passes through an
//! edge or a vertex), and random lattice-aligned meshes queried at lattice points, where
//! most rays graze something. Checked against `sphaera_tests::regions` (exact on-face tests
//! and the winding number, outside this crate) and the crate's `contains3_brute`.

use proptest::prelude::*;
use sphaera_hal::{Containment, HalTree3, contains3_brute};
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_tests::random::SplitMix64;
use sphaera_tests::regions::{self, Side};

fn side(c: Containment) -> Side {
    match c {
        Containment::Inside => Side::Inside,
        Containment::Boundary => Side::Boundary,
        Containment::Outside => Side::Outside,
    }
}

/// `mesh` scaled by `scale` and moved by `offset` (powers of two keep lattices exact).
fn moved(mesh: &TriMesh, scale: f64, offset: DVec3) -> TriMesh {
    TriMesh::new(
        mesh.positions()
            .iter()
            .map(|&p| p * scale + offset)
            .collect(),
        mesh.triangles().to_vec(),
    )
    .expect("a mesh")
}

/// Checks the tree and the brute force against the reference at every point.
fn check(name: &str, mesh: &TriMesh, points: &[DVec3]) -> [usize; 3] {
    let tree = HalTree3::build(mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut counts = [0; 3];
    for &x in points {
        let expected = regions::locate_in_solid(mesh, x);
        assert_eq!(side(tree.contains(x)), expected, "{name}: {x}");
        assert_eq!(
            side(contains3_brute(mesh, x)),
            expected,
            "{name}: brute force at {x}"
        );
        counts[expected as usize] += 1;
    }
    counts
}

/// Points on the three axes (and the diagonals) of the cube and the octahedron, on a
/// lattice that hits the faces' diagonals, the edges and the corners, near and far from
/// the origin: the regression for `Boundary` answered off the surface when every ray ran
/// into an edge.
#[test]
fn axis_points_of_a_cube_and_an_octahedron_are_exact() {
    let shapes_ = [
        ("cube, 12 triangles", shapes::cube(2.0, 1).expect("a cube")),
        ("cube, 4 per side", shapes::cube(2.0, 2).expect("a cube")),
        ("octahedron", shapes::fixtures::octahedron()),
    ];
    for (name, mesh) in &shapes_ {
        for (scale, offset) in [
            (1.0, DVec3::ZERO),
            (1.0 / 1024.0, DVec3::splat(4096.0)),
            (65536.0, DVec3::new(-2f64.powi(40), 2f64.powi(30), 0.0)),
        ] {
            let mesh = moved(mesh, scale, offset);
            let mut points = Vec::new();
            for i in -12..=12 {
                let t = f64::from(i) / 8.0;
                for axis in [
                    DVec3::X,
                    DVec3::Y,
                    DVec3::Z,
                    DVec3::ONE,
                    DVec3::new(1.0, -1.0, 1.0),
                ] {
                    points.push(axis * t * scale + offset);
                }
            }
            let counts = check(name, &mesh, &points);
            assert!(
                counts.iter().all(|&c| c > 0),
                "{name}: inside, boundary and outside all met ({counts:?})"
            );
            // The centre: every axis-aligned ray meets an edge or a vertex.
            let tree = HalTree3::build(&mesh).expect("genus 0");
            assert_eq!(tree.contains(offset), Containment::Inside, "{name}");
        }
    }
}

/// A star-shaped ball with its vertices rounded to the integer lattice (so edges and
/// faces lie along lattice directions and many rays from lattice points graze them).
fn lattice_ball(resolution: usize, size: f64, bump: f64, seed: u64) -> TriMesh {
    let ball = shapes::sphere(1.0, resolution).expect("a sphere");
    let mut rng = SplitMix64::new(seed);
    let wave = DVec3::new(
        rng.range(-3.0, 3.0),
        rng.range(-3.0, 3.0),
        rng.range(-3.0, 3.0),
    );
    TriMesh::new(
        ball.positions()
            .iter()
            .map(|&p| {
                let n = p.normalize();
                (n * size * (1.0 + bump * wave.dot(n).sin())).round()
            })
            .collect(),
        ball.triangles().to_vec(),
    )
    .expect("a mesh")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    /// Random lattice-aligned meshes (moved by powers of two, so still on a lattice) at
    /// every point of a lattice of half-units around them: vertices, edge midpoints, points
    /// on faces and points whose axis rays pass through vertices and edges.
    #[test]
    fn lattice_points_in_lattice_meshes_are_exact(
        resolution in 5usize..14,
        size in 4.0..12.0f64,
        bump in 0.0..0.4f64,
        seed in any::<u64>(),
        exponent in -20i32..20,
        far in 0i32..30,
        signs in prop::array::uniform3(any::<bool>()),
    ) {
        let mesh = lattice_ball(resolution, size.round(), bump, seed);
        let scale = 2f64.powi(exponent);
        let offset = DVec3::from_array(signs.map(|s| if s { 1.0 } else { -1.0 })) * 2f64.powi(far) * scale;
        let mesh = moved(&mesh, scale, offset);
        let Ok(tree) = HalTree3::build(&mesh) else {
            // Rounding may pinch the ball into a non-manifold or degenerate mesh: not a
            // genus-0 surface, nothing to test.
            return Ok(());
        };
        let reach = (size * 1.5).ceil() as i32;
        let mut rng = SplitMix64::new(seed ^ 0x5eed);
        let mut points: Vec<DVec3> = (0..150)
            .map(|_| {
                let mut lattice = || f64::from(rng.below((4 * reach + 1) as u64) as i32 - 2 * reach) / 2.0;
                DVec3::new(lattice(), lattice(), lattice())
            })
            .collect();
        // Points on the axes through the centre, where rays meet the most vertices.
        for i in -2 * reach..=2 * reach {
            let t = f64::from(i) / 2.0;
            points.extend([DVec3::X * t, DVec3::Y * t, DVec3::Z * t]);
        }
        for x in points {
            let x = x * scale + offset;
            let expected = regions::locate_in_solid(&mesh, x);
            prop_assert_eq!(side(tree.contains(x)), expected, "{}", x);
            prop_assert_eq!(side(contains3_brute(&mesh, x)), expected, "brute force at {}", x);
        }
    }
}

/// The shared genus-0 meshes (fandisk is a CAD part: large flat faces, many on
/// coordinate planes) at points built from their vertices' coordinates, so that axis
/// rays run through vertices and along edges: vertices, and points taking each
/// coordinate from a different vertex, against the reference; the rounded midpoints of
/// edges (on the surface or within a rounding of it, where the winding number cannot
/// judge) against the brute force.
#[test]
fn real_meshes_at_points_aligned_with_their_vertices_are_exact() {
    let Some(data) =
        sphaera_tests::data_dir("real_meshes_at_points_aligned_with_their_vertices_are_exact")
    else {
        return;
    };
    for file in ["fandisk.obj", "spot.obj", "bunny_lowres.obj"] {
        let mesh = sphaera_io::load(data.join(file)).expect("a shared mesh");
        let p = mesh.positions();
        let mut rng = SplitMix64::new(77);
        let mut points = Vec::new();
        for _ in 0..80 {
            let [a, b, c] = [0; 3].map(|_| p[rng.index(p.len())]);
            points.push(DVec3::new(a.x, b.y, c.z));
            points.push(a);
        }
        let counts = check(file, &mesh, &points);
        assert!(
            counts[0] > 0 && counts[1] > 0 && counts[2] > 0,
            "{file}: {counts:?}"
        );
        let tree = HalTree3::build(&mesh).expect("genus 0");
        for t in mesh.triangles().iter().step_by(37) {
            let [a, b, _] = t.map(|v| p[v as usize]);
            let x = (a + b) / 2.0;
            assert_eq!(tree.contains(x), contains3_brute(&mesh, x), "{file}: {x}");
        }
    }
}
