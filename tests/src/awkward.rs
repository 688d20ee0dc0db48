//! Meshes of the kind users bring and nobody here has: a pinched (non-manifold) vertex,
//! slivers, a tiny detached component, components far apart, long thin parts, spikes.
//! Each is generated, so a test can run every method and every output format on all of
//! them.
//!
//! Parts are joined without welding (except where a pinch is the point): overlapping
//! closed parts are fine for the winding-number inside test every method uses.

use sphaera_mesh::glam::{DQuat, DVec3};

use crate::random::SplitMix64;
use sphaera_mesh::{TriMesh, shapes};

/// One awkward mesh with a name for assertion messages.
#[derive(Debug, Clone)]
pub struct Awkward {
    /// What it is, e.g. `"tori touching at a vertex"`.
    pub name: &'static str,
    /// The mesh.
    pub mesh: TriMesh,
}

/// Every awkward mesh of this module, at a resolution that keeps a sphere-tree build on
/// each under a second.
///
/// # Panics
///
/// Never: the shapes' parameters are valid.
#[must_use]
pub fn all() -> Vec<Awkward> {
    let named = |name, mesh| Awkward { name, mesh };
    vec![
        named("tori touching at a vertex", tori_touching_at_a_vertex(24)),
        named("cube with a tiny detached cube", cube_with_a_tiny_cube()),
        named("box of slivers", box_of_slivers(1e-7)),
        named("two far-apart spheres", far_apart_spheres(1e4)),
        named("long thin rod", long_thin_rod()),
        named("capsule with horns", capsule_with_horns()),
        named("star of spikes", star_of_spikes(12)),
    ]
}

/// The parts as one mesh (vertices and triangles concatenated, nothing welded).
///
/// # Panics
///
/// Never for valid parts.
#[must_use]
pub fn join(parts: &[TriMesh]) -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for part in parts {
        let offset = positions.len() as u32;
        positions.extend_from_slice(part.positions());
        triangles.extend(part.triangles().iter().map(|t| t.map(|i| i + offset)));
    }
    TriMesh::new(positions, triangles).expect("parts are valid meshes")
}

/// `mesh` with every position mapped by `f` (reversing the triangles when `flip`, for a
/// reflection).
///
/// # Panics
///
/// Never for a finite map.
#[must_use]
pub fn mapped(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec3, flip: bool) -> TriMesh {
    let positions = mesh.positions().iter().map(|&p| f(p)).collect();
    let triangles = mesh
        .triangles()
        .iter()
        .map(|&[a, b, c]| if flip { [a, c, b] } else { [a, b, c] })
        .collect();
    TriMesh::new(positions, triangles).expect("a finite map keeps the mesh valid")
}

/// Two tori (major radius 1, minor 0.3, `resolution` segments around) side by side along
/// x, the second the mirror image of the first, sharing exactly one vertex: the surface is
/// closed but pinched there (the shared vertex is non-manifold).
///
/// # Panics
///
/// If `resolution < 3`.
#[must_use]
pub fn tori_touching_at_a_vertex(resolution: usize) -> TriMesh {
    let torus = shapes::torus(1.0, 0.3, resolution).expect("valid torus");
    let positions = torus.positions();
    let (pinch, &tip) = positions
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.x.total_cmp(&b.1.x).then(b.0.cmp(&a.0)))
        .expect("a torus has vertices");
    // Mirror about the plane x = tip.x: the tip maps onto itself exactly.
    let mirror = mapped(&torus, |p| DVec3::new(2.0 * tip.x - p.x, p.y, p.z), true);
    let n = positions.len() as u32;
    let mut all = positions.to_vec();
    all.extend_from_slice(mirror.positions());
    let weld = |i: u32| {
        if i == pinch as u32 {
            pinch as u32
        } else {
            i + n
        }
    };
    let mut triangles = torus.triangles().to_vec();
    triangles.extend(mirror.triangles().iter().map(|t| t.map(weld)));
    // Drop the mirror's copy of the shared vertex (now unreferenced) by compacting.
    let (all, triangles) = compact(all, triangles);
    TriMesh::new(all, triangles).expect("welded tori are a valid mesh")
}

/// Removes unreferenced vertices, keeping the order of the rest.
fn compact(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut used = vec![false; positions.len()];
    for t in &triangles {
        for &i in t {
            used[i as usize] = true;
        }
    }
    let mut index = vec![0_u32; positions.len()];
    let mut kept = Vec::with_capacity(positions.len());
    for (i, p) in positions.into_iter().enumerate() {
        if used[i] {
            index[i] = kept.len() as u32;
            kept.push(p);
        }
    }
    let triangles = triangles
        .into_iter()
        .map(|t| t.map(|i| index[i as usize]))
        .collect();
    (kept, triangles)
}

/// A unit cube and, two units away, a detached cube a thousandth its size.
///
/// # Panics
///
/// Never.
#[must_use]
pub fn cube_with_a_tiny_cube() -> TriMesh {
    let big = shapes::cube(1.0, 4).expect("valid cube");
    let tiny = shapes::cube(1e-3, 1).expect("valid cube");
    join(&[big, mapped(&tiny, |p| p + DVec3::new(2.0, 0.0, 0.0), false)])
}

/// A unit cube whose every face is cut into a fan of four triangles around a point
/// `height` inside one of its edges: one of the four is a sliver of that height.
///
/// # Panics
///
/// Never for `0 < height < 0.5`.
#[must_use]
pub fn box_of_slivers(height: f64) -> TriMesh {
    let corner = |i: u32| {
        DVec3::new(
            f64::from(i & 1),
            f64::from((i >> 1) & 1),
            f64::from((i >> 2) & 1),
        ) - DVec3::splat(0.5)
    };
    let mut positions: Vec<DVec3> = (0..8).map(corner).collect();
    // The six faces, counter-clockwise seen from outside.
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut triangles = Vec::new();
    for quad in quads {
        let [p, q] = [quad[0], quad[1]].map(|i| positions[i as usize]);
        let center = quad.iter().map(|&i| positions[i as usize]).sum::<DVec3>() * 0.25;
        let middle = (p + q) * 0.5;
        let m = middle + (center - middle).normalize() * height;
        let mi = positions.len() as u32;
        positions.push(m);
        for k in 0..4 {
            triangles.push([quad[k], quad[(k + 1) % 4], mi]);
        }
    }
    TriMesh::new(positions, triangles).expect("a fanned cube is a valid mesh")
}

/// Two unit spheres whose centres are `distance` apart along x.
///
/// # Panics
///
/// Never for a finite distance.
#[must_use]
pub fn far_apart_spheres(distance: f64) -> TriMesh {
    let sphere = shapes::sphere(1.0, 16).expect("valid sphere");
    let far = mapped(&sphere, |p| p + DVec3::new(distance, 0.0, 0.0), false);
    join(&[sphere, far])
}

/// A rod of radius 0.01 and length 10 with flat ends, its sides long thin triangles:
/// the thin tube on which expand-select fails (the paper's own failure case).
///
/// # Panics
///
/// Never.
#[must_use]
pub fn long_thin_rod() -> TriMesh {
    let stub = shapes::cylinder(0.5, 1.0, 12).expect("valid cylinder");
    mapped(
        &stub,
        |p| DVec3::new(0.02 * p.x, 0.02 * p.y, 10.0 * p.z),
        false,
    )
}

/// A capsule body (radius 0.5, length 2, along z) with two long thin horns (cones of
/// base radius 0.05 and height 2) rising from its top, splayed apart.
///
/// # Panics
///
/// Never.
#[must_use]
pub fn capsule_with_horns() -> TriMesh {
    let body = shapes::capsule(0.5, 2.0, 16).expect("valid capsule");
    let horn = shapes::cone(0.05, 2.0, 24).expect("valid cone");
    let horns = [-1.0, 1.0].map(|side: f64| {
        let tilt = DQuat::from_rotation_y(side * 0.5);
        // Base at z = 0, then tilted and set into the capsule's top.
        mapped(
            &horn,
            |p| tilt * (p + DVec3::Z) + DVec3::new(side * 0.25, 0.0, 1.2),
            false,
        )
    });
    let [left, right] = horns;
    join(&[body, left, right])
}

/// A sphere of radius 0.3 with `spikes` thin cones (base radius 0.03, height 1.5)
/// pointing out along a Fibonacci lattice of directions.
///
/// # Panics
///
/// Never for `spikes ≥ 1`.
#[must_use]
pub fn star_of_spikes(spikes: usize) -> TriMesh {
    let core = shapes::sphere(0.3, 16).expect("valid sphere");
    let cone = shapes::cone(0.03, 1.5, 24).expect("valid cone");
    let mut parts = vec![core];
    for direction in crate::point_sets::fibonacci_sphere(spikes) {
        let turn = DQuat::from_rotation_arc(DVec3::Z, direction.normalize());
        // Base at z = 0, turned to the direction, set into the core.
        parts.push(mapped(
            &cone,
            |p| turn * (p + 0.75 * DVec3::Z) + direction * 0.2,
            false,
        ));
    }
    join(&parts)
}

/// A ball of `resolution` with its radius bumped by up to `bump` (a fraction) by three
/// random waves, then scaled by `scale` and moved by `offset`: genus 0, closed, star
/// shaped (so never self-intersecting for `bump < 1`).
pub fn bumpy_ball(resolution: usize, bump: f64, seed: u64, scale: f64, offset: DVec3) -> TriMesh {
    let ball = shapes::sphere(1.0, resolution).expect("a valid sphere");
    let mut rng = SplitMix64::new(seed);
    let waves: Vec<(DVec3, f64)> = (0..3)
        .map(|_| {
            (
                DVec3::new(
                    rng.range(-5.0, 5.0),
                    rng.range(-5.0, 5.0),
                    rng.range(-5.0, 5.0),
                ),
                rng.range(0.0, 6.3),
            )
        })
        .collect();
    TriMesh::new(
        ball.positions()
            .iter()
            .map(|&p| {
                let n = p.normalize();
                let wave: f64 = waves
                    .iter()
                    .map(|&(k, phase)| (k.dot(n) + phase).sin())
                    .sum();
                n * (1.0 + bump * wave / 3.0) * scale + offset
            })
            .collect(),
        ball.triangles().to_vec(),
    )
    .expect("a mesh")
}
