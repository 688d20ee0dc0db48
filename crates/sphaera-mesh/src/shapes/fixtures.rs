//! Small fixed meshes for tests, here and in the crates above: hand-built solids whose
//! vertex and triangle order tests may rely on (half-edge 0 of the octahedron runs from
//! vertex 0 to vertex 2, the grid numbers its vertices row by row), open meshes, and thin
//! wrappers around [`crate::shapes`] for the procedural closed ones.
//!
//! Behind the `fixtures` feature (off by default), for the test code of crates that build
//! on this one.
//!
//! # Panics
//!
//! These are test fixtures: parameters that give no valid mesh (a zero resolution, a
//! transform that makes a coordinate NaN, more than `u32::MAX` vertices in a union) panic
//! instead of returning an error.
//!
//! ```
//! use sphaera_mesh::{shapes::fixtures, topology};
//!
//! let report = topology::analyze(&fixtures::octahedron());
//! assert!(report.is_closed && report.is_manifold);
//! assert!(!topology::analyze(&fixtures::grid(3, 2)).is_closed);
//! ```

use glam::DVec3;

use crate::{TriMesh, shapes};

/// The tetrahedron with corners 0, X, Y, Z, outward oriented.
pub fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap()
}

/// The regular octahedron with corners ±X, ±Y, ±Z (in that order), outward oriented;
/// triangle 0 is `[0, 2, 4]`.
pub fn octahedron() -> TriMesh {
    TriMesh::new(
        vec![
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ],
        vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
    .unwrap()
}

/// The unit cube `[0, 1]³` (corner `i` has bit 0 = x, bit 1 = y, bit 2 = z), two
/// triangles per side, outward oriented. Unlike [`shapes::cube`] it is not centred: tests
/// name its corners, edges and faces by coordinates.
pub fn unit_cube() -> TriMesh {
    let p = (0..8)
        .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let t = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    TriMesh::new(p, t).unwrap()
}

/// An open `n × m` grid of unit squares in the plane `z = 0` (a disc), normals along +z.
/// Vertex `(i, j)` is `j (n + 1) + i`; square `(i, j)` gives the triangles
/// `[a, a + 1, a + n + 2]` and `[a, a + n + 2, a + n + 1]` with `a = j (n + 1) + i`.
pub fn grid(n: u32, m: u32) -> TriMesh {
    let mut p = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            p.push(DVec3::new(f64::from(i), f64::from(j), 0.0));
        }
    }
    let mut t = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let a = j * (n + 1) + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    TriMesh::new(p, t).unwrap()
}

/// The square `[0, 1]² × {0}` as an open [`grid`] of `n × n` squares.
pub fn unit_sheet(n: u32) -> TriMesh {
    transformed(&grid(n, n), |p| p / f64::from(n))
}

/// [`shapes::torus`] around the z axis with major radius 1, `major` segments around the
/// axis and `minor` around the tube (`3 ≤ minor ≤ 10`, `minor ≤ major`).
pub fn torus(major: u32, minor: u32) -> TriMesh {
    // `shapes::torus` puts round(major · r) segments around the tube.
    let minor_radius = 0.95 * f64::from(minor) / f64::from(major);
    let mesh = shapes::torus(1.0, minor_radius, major as usize).unwrap();
    assert_eq!(mesh.vertex_count(), (major * minor) as usize, "torus grid");
    mesh
}

/// [`shapes::sphere`] of radius 1 with `resolution` segments around the equator, without
/// the triangles whose centroid is less than `hole_degrees` from the north pole (their
/// vertices are kept, unreferenced). The rings are `360° / resolution` apart, so a multiple
/// of that angle removes whole rows.
pub fn sphere_with_hole(resolution: usize, hole_degrees: f64) -> TriMesh {
    let (positions, triangles) = shapes::sphere(1.0, resolution).unwrap().into_parts();
    let cos_hole = hole_degrees.to_radians().cos();
    let kept = triangles
        .into_iter()
        .filter(|t| {
            let c = t.iter().map(|&v| positions[v as usize]).sum::<DVec3>();
            c.z <= cos_hole * c.length()
        })
        .collect();
    TriMesh::new(positions, kept).unwrap()
}

/// `mesh` with every position mapped by `f`.
pub fn transformed(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec3) -> TriMesh {
    let (p, t) = mesh.clone().into_parts();
    TriMesh::new(p.into_iter().map(f).collect(), t).unwrap()
}

/// `mesh` moved by `shift` along x.
pub fn shifted(mesh: &TriMesh, shift: f64) -> TriMesh {
    transformed(mesh, |p| p + DVec3::X * shift)
}

/// Two meshes side by side, as one.
pub fn union(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let offset = u32::try_from(a.vertex_count()).unwrap();
    let mut p = a.positions().to_vec();
    p.extend_from_slice(b.positions());
    let mut t = a.triangles().to_vec();
    t.extend(b.triangles().iter().map(|tri| tri.map(|v| v + offset)));
    TriMesh::new(p, t).unwrap()
}

/// The closed test shapes, by name: hand-built tetrahedron, cube and octahedron, and a
/// sphere (radius 1) and torus (radii 1 and 0.35) from [`crate::shapes`].
pub fn closed_shapes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("tetrahedron", tetrahedron()),
        ("cube", unit_cube()),
        ("octahedron", octahedron()),
        ("sphere", shapes::sphere(1.0, 48).unwrap()),
        ("torus", shapes::torus(1.0, 0.35, 48).unwrap()),
    ]
}

/// A point well inside the named closed shape of [`closed_shapes`].
pub fn interior_point(name: &str) -> DVec3 {
    match name {
        "tetrahedron" => DVec3::splat(0.2),
        "cube" => DVec3::splat(0.5),
        "torus" => DVec3::new(0.0, 1.0, 0.05),
        _ => DVec3::new(0.05, -0.03, 0.02),
    }
}
