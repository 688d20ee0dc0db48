//! Where, in 3D: the nearest face of a HAL tree and the pairs of faces where two placed
//! trees meet, against brute force over every face and every pair of faces (and, for
//! whether any pair meets, parry3d's intersection test through `sphaera_tests::regions`),
//! on random genus-0 meshes (star-shaped balls with random bumps, scales and offsets)
//! and a few exact cases.

use proptest::prelude::*;
use sphaera_hal::{HalTree3, triangles_meet};
use sphaera_mesh::geometry::{Similarity, Triangle, closest_point_on_triangle};
use sphaera_mesh::glam::{DAffine3, DQuat, EulerRot};
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_tests::random::SplitMix64;
use sphaera_tests::regions;

/// A bumpy genus-0 ball ([`sphaera_tests::awkward::bumpy_ball`]).
fn bumpy(resolution: usize, bump: f64, seed: u64, scale: f64, offset: DVec3) -> TriMesh {
    sphaera_tests::awkward::bumpy_ball(resolution, bump, seed, scale, offset)
}

/// The nearest face by brute force: the least (squared distance, face index), with the
/// distance's square root and the nearest point.
fn nearest_brute(mesh: &TriMesh, x: DVec3) -> (usize, f64, DVec3) {
    let mut best: Option<(f64, usize, DVec3)> = None;
    for (i, t) in mesh.triangles().iter().enumerate() {
        let [a, b, c] = t.map(|v| mesh.positions()[v as usize]);
        let hit = closest_point_on_triangle(x, &Triangle::new(a, b, c));
        if best.is_none_or(|(d2, _, _)| hit.distance_squared.total_cmp(&d2).is_lt()) {
            best = Some((hit.distance_squared, i, hit.point));
        }
    }
    let (d2, face, point) = best.expect("a mesh with faces");
    (face, d2.sqrt(), point)
}

/// Every pair of faces (first mesh's, second's mapped by `placement`) that meet.
fn pairs_brute(first: &TriMesh, second: &TriMesh, placement: &Similarity) -> Vec<(usize, usize)> {
    let corners = |m: &TriMesh, t: [u32; 3], map: &Similarity| {
        t.map(|v| map.point(m.positions()[v as usize]))
    };
    let mut pairs = Vec::new();
    for (i, &t) in first.triangles().iter().enumerate() {
        let t = corners(first, t, &Similarity::IDENTITY);
        for (j, &u) in second.triangles().iter().enumerate() {
            if triangles_meet(t, corners(second, u, placement)) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

fn check_nearest(name: &str, mesh: &TriMesh, tree: &HalTree3, x: DVec3) {
    let found = tree.nearest_face(x).expect("a finite point");
    let (face, distance, point) = nearest_brute(mesh, x);
    assert_eq!(
        (found.face, found.distance, found.point),
        (face, distance, point),
        "{name}: nearest face to {x}"
    );
}

/// Exact cases: the cube's sides and corners from outside and inside, points on faces,
/// edges and vertices (distance 0), and a point equally near several faces (the lowest
/// index wins, as the brute force's first minimum).
#[test]
fn nearest_faces_of_a_cube_are_the_brute_forces() {
    let cube = shapes::cube(2.0, 2).expect("a cube");
    let tree = HalTree3::build(&cube).expect("genus 0");
    let points = [
        DVec3::new(3.0, 0.25, 0.5),
        DVec3::new(-0.25, 7.0, -0.5),
        DVec3::splat(2.0),
        DVec3::ZERO,
        DVec3::new(0.9, 0.1, 0.2),
        DVec3::new(1.0, 0.25, 0.5),
        DVec3::new(1.0, 1.0, 0.3),
        DVec3::ONE,
        DVec3::new(0.0, 0.0, -1.0),
    ];
    for x in points {
        check_nearest("cube", &cube, &tree, x);
    }
    let outside = tree
        .nearest_face(DVec3::new(3.0, 0.25, 0.5))
        .expect("finite");
    assert_eq!(
        (outside.distance, outside.point),
        (2.0, DVec3::new(1.0, 0.25, 0.5))
    );
    let corner = tree.nearest_face(DVec3::ONE).expect("finite");
    assert_eq!((corner.distance, corner.point), (0.0, DVec3::ONE));
    assert!(
        tree.nearest_face(DVec3::new(f64::INFINITY, 0.0, 0.0))
            .is_none()
    );
}

/// Exact cases of meeting faces: a cube against itself moved by its size (a shared
/// side: every face on the side, and those around it, touch), moved apart (none), nested
/// inside it at half size (none: only the surfaces count) and turned in place.
#[test]
fn intersecting_faces_of_cubes_are_the_brute_forces() {
    let cube = shapes::cube(2.0, 2).expect("a cube");
    let tree = HalTree3::build(&cube).expect("genus 0");
    let placements = [
        Similarity::from_translation(DVec3::new(2.0, 0.0, 0.0)).expect("a translation"),
        Similarity::from_translation(DVec3::new(2.5, 0.0, 0.0)).expect("a translation"),
        Similarity::new(DAffine3::from_scale(DVec3::splat(0.5))).expect("a scaling"),
        Similarity::new(DAffine3::from_quat(DQuat::from_rotation_z(0.4))).expect("a rotation"),
    ];
    let counts: Vec<usize> = placements
        .iter()
        .map(|placement| {
            let pairs = tree.intersecting_faces(&tree, placement);
            assert_eq!(pairs, pairs_brute(&cube, &cube, placement), "{placement:?}");
            pairs.len()
        })
        .collect();
    assert!(counts[0] > 0 && counts[3] > 0, "{counts:?}");
    assert_eq!((counts[1], counts[2]), (0, 0));
    // Nested: no face meets, yet the solids intersect.
    assert!(tree.intersects(&tree, &placements[2]));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    #[test]
    fn nearest_face_equals_brute_force(
        resolution in 4usize..14,
        bump in 0.0..0.6f64,
        seed in any::<u64>(),
        exponent in -6i32..7,
        far in 0i32..7,
        offset in prop::array::uniform3(-1.0..1.0f64),
    ) {
        let scale = 10f64.powi(exponent);
        let offset = DVec3::from_array(offset) * scale * 10f64.powi(far);
        let mesh = bumpy(resolution, bump, seed, scale, offset);
        let tree = HalTree3::build(&mesh).expect("genus 0");
        let mut rng = SplitMix64::new(seed ^ 0x4ea7);
        let mut queries: Vec<DVec3> = (0..40)
            .map(|_| offset + DVec3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)) * scale)
            .collect();
        queries.extend(mesh.positions().iter().step_by(9).copied());
        for t in mesh.triangles().iter().step_by(13) {
            let [a, b, c] = t.map(|v| mesh.positions()[v as usize]);
            queries.push((a + b + c) / 3.0);
        }
        for x in queries {
            let found = tree.nearest_face(x).expect("a finite point");
            let (face, distance, point) = nearest_brute(&mesh, x);
            prop_assert_eq!((found.face, found.distance, found.point), (face, distance, point), "{}", x);
        }
    }

    #[test]
    fn intersecting_faces_equal_brute_force(
        seeds in (any::<u64>(), any::<u64>()),
        bumps in (0.0..0.5f64, 0.0..0.5f64),
        angles in prop::array::uniform3(0.0..6.3f64),
        shift in prop::array::uniform3(-2.5..2.5f64),
        scale in 0.1..2.0f64,
    ) {
        let a = bumpy(8, bumps.0, seeds.0, 1.0, DVec3::ZERO);
        let b = bumpy(6, bumps.1, seeds.1, 1.0, DVec3::ZERO);
        let (ta, tb) = (HalTree3::build(&a).expect("genus 0"), HalTree3::build(&b).expect("genus 0"));
        let placement = Similarity::new(DAffine3::from_scale_rotation_translation(
            DVec3::splat(scale),
            DQuat::from_euler(EulerRot::XYZ, angles[0], angles[1], angles[2]),
            DVec3::from_array(shift),
        ))
        .expect("a similarity");
        let pairs = ta.intersecting_faces(&tb, &placement);
        prop_assert_eq!(&pairs, &pairs_brute(&a, &b, &placement));
        // Some pair exactly when the surfaces meet, by parry's test outside this crate.
        let mapped = TriMesh::new(
            b.positions().iter().map(|&p| placement.point(p)).collect(),
            b.triangles().to_vec(),
        )
        .expect("a mesh");
        prop_assert_eq!(!pairs.is_empty(), regions::surfaces_meet(&a, &mapped));
        // Faces meet only where the solids do.
        if !pairs.is_empty() {
            prop_assert!(ta.intersects(&tb, &placement));
        }
    }
}
