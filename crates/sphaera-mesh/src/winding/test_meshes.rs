//! Small closed and open meshes built inline for the winding-number tests (the crate's
//! `shapes` module is written separately; these tests must not depend on it).

use std::f64::consts::PI;

use glam::DVec3;

use crate::TriMesh;

/// Orients every triangle of a convex shape so that its normal points away from `centre`.
fn convex(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>, centre: DVec3) -> TriMesh {
    let triangles = triangles
        .into_iter()
        .map(|[a, b, c]| {
            let (pa, pb, pc) = (
                positions[a as usize],
                positions[b as usize],
                positions[c as usize],
            );
            let n = (pb - pa).cross(pc - pa);
            if n.dot(pa - centre) >= 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            }
        })
        .collect();
    TriMesh::new(positions, triangles).expect("test mesh is valid")
}

/// The tetrahedron with corners 0, X, Y, Z.
pub(crate) fn tetrahedron() -> TriMesh {
    convex(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]],
        DVec3::splat(0.25),
    )
}

/// The unit cube `[0, 1]³`.
pub(crate) fn cube() -> TriMesh {
    let positions = (0..8)
        .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
        .collect();
    // Faces as quads of corner indices (bit 0 = x, bit 1 = y, bit 2 = z).
    let quads = [
        [0, 2, 6, 4],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 5, 7, 6],
    ];
    let triangles = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    convex(positions, triangles, DVec3::splat(0.5))
}

/// The regular octahedron with corners at ±X, ±Y, ±Z.
pub(crate) fn octahedron() -> TriMesh {
    let positions = vec![
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ];
    let mut triangles = Vec::new();
    for x in [0, 1] {
        for y in [2, 3] {
            for z in [4, 5] {
                triangles.push([x, y, z]);
            }
        }
    }
    convex(positions, triangles, DVec3::ZERO)
}

/// A latitude-longitude sphere of radius `radius` centred at the origin, outward oriented,
/// with single pole vertices (so it is closed and manifold). `skip_top_rows` removes that
/// many rows of triangles around the north pole, leaving a hole.
pub(crate) fn uv_sphere_with_hole(
    latitudes: u32,
    longitudes: u32,
    radius: f64,
    skip_top_rows: u32,
) -> TriMesh {
    let mut positions = vec![DVec3::Z * radius];
    for i in 1..latitudes {
        let theta = PI * f64::from(i) / f64::from(latitudes);
        for j in 0..longitudes {
            let phi = 2.0 * PI * f64::from(j) / f64::from(longitudes);
            positions.push(
                radius
                    * DVec3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    ),
            );
        }
    }
    let south = u32::try_from(positions.len()).expect("small test mesh");
    positions.push(-DVec3::Z * radius);
    let ring = |i: u32, j: u32| 1 + (i - 1) * longitudes + j % longitudes;
    let mut triangles = Vec::new();
    for j in 0..longitudes {
        if skip_top_rows == 0 {
            triangles.push([0, ring(1, j), ring(1, j + 1)]);
        }
        for i in 1..latitudes - 1 {
            if i < skip_top_rows {
                continue;
            }
            let (a, b, c, d) = (
                ring(i, j),
                ring(i + 1, j),
                ring(i + 1, j + 1),
                ring(i, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
        triangles.push([south, ring(latitudes - 1, j + 1), ring(latitudes - 1, j)]);
    }
    TriMesh::new(positions, triangles).expect("test mesh is valid")
}

/// A closed latitude-longitude sphere of radius 1.
pub(crate) fn uv_sphere(latitudes: u32, longitudes: u32) -> TriMesh {
    uv_sphere_with_hole(latitudes, longitudes, 1.0, 0)
}

/// A closed torus around the z axis with major radius 1 and minor radius 0.35.
pub(crate) fn torus(major_steps: u32, minor_steps: u32) -> TriMesh {
    let (major, minor) = (1.0, 0.35);
    let mut positions = Vec::new();
    for i in 0..major_steps {
        let u = 2.0 * PI * f64::from(i) / f64::from(major_steps);
        for j in 0..minor_steps {
            let v = 2.0 * PI * f64::from(j) / f64::from(minor_steps);
            let r = major + minor * v.cos();
            positions.push(DVec3::new(r * u.cos(), r * u.sin(), minor * v.sin()));
        }
    }
    let index = |i: u32, j: u32| (i % major_steps) * minor_steps + j % minor_steps;
    let mut triangles = Vec::new();
    for i in 0..major_steps {
        for j in 0..minor_steps {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles).expect("test mesh is valid")
}

/// A flat square sheet `[0, 1]² × {0}` split into `2 n²` triangles (an open patch).
pub(crate) fn flat_sheet(n: u32) -> TriMesh {
    let step = 1.0 / f64::from(n);
    let mut positions = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            positions.push(DVec3::new(f64::from(i) * step, f64::from(j) * step, 0.0));
        }
    }
    let index = |i: u32, j: u32| i * (n + 1) + j;
    let mut triangles = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles).expect("test mesh is valid")
}

/// The closed test shapes with a point well inside each.
pub(crate) fn closed_shapes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("tetrahedron", tetrahedron()),
        ("cube", cube()),
        ("octahedron", octahedron()),
        ("sphere", uv_sphere(24, 48)),
        ("torus", torus(48, 24)),
    ]
}

/// A point well inside the named closed shape.
pub(crate) fn interior_point(name: &str) -> DVec3 {
    match name {
        "tetrahedron" => DVec3::splat(0.2),
        "cube" => DVec3::splat(0.5),
        "torus" => DVec3::new(0.0, 1.0, 0.05),
        _ => DVec3::new(0.05, -0.03, 0.02),
    }
}
