//! The 3D HAL tree on random genus-0 meshes nobody chose: star-shaped balls with random
//! bumps, resolutions, rotations, scales and offsets (tiny to huge coordinates). Point
//! inclusion and placed intersection are checked against `sphaera_tests::regions` (exact
//! winding numbers and parry3d's intersection test, outside this crate).

use proptest::prelude::*;
use sphaera_hal::{Containment, HalTree3};
use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::glam::{DAffine3, DQuat, EulerRot};
use sphaera_mesh::{DVec3, TriMesh};
use sphaera_tests::random::SplitMix64;
use sphaera_tests::regions::{self, Side};

/// A bumpy genus-0 ball ([`sphaera_tests::awkward::bumpy_ball`]).
fn bumpy(resolution: usize, bump: f64, seed: u64, scale: f64, offset: DVec3) -> TriMesh {
    sphaera_tests::awkward::bumpy_ball(resolution, bump, seed, scale, offset)
}

fn side(c: Containment) -> Side {
    match c {
        Containment::Inside => Side::Inside,
        Containment::Boundary => Side::Boundary,
        Containment::Outside => Side::Outside,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    #[test]
    fn inclusion_equals_the_winding_number(
        resolution in 4usize..14,
        bump in 0.0..0.6f64,
        seed in any::<u64>(),
        exponent in -6i32..7,
        far in 0i32..7,
        offset in prop::array::uniform3(-1.0..1.0f64),
    ) {
        // Up to a million times its size from the origin.
        let scale = 10f64.powi(exponent);
        let offset = DVec3::from_array(offset) * scale * 10f64.powi(far);
        let mesh = bumpy(resolution, bump, seed, scale, offset);
        let tree = HalTree3::build(&mesh).expect("genus 0");
        let mut rng = SplitMix64::new(seed ^ 0x9e37);
        let mut queries: Vec<DVec3> = (0..60)
            .map(|_| offset + DVec3::new(rng.range(-1.8, 1.8), rng.range(-1.8, 1.8), rng.range(-1.8, 1.8)) * scale)
            .collect();
        // On the surface: vertices and face centroids (Boundary or a rounding off it).
        queries.extend(mesh.positions().iter().step_by(7).copied());
        for t in mesh.triangles().iter().step_by(11) {
            let [a, b, c] = t.map(|v| mesh.positions()[v as usize]);
            queries.push((a + b + c) / 3.0);
        }
        for x in queries {
            prop_assert_eq!(side(tree.contains(x)), regions::locate_in_solid(&mesh, x), "{}", x);
        }
    }

    #[test]
    fn placed_intersection_equals_the_reference(
        seeds in (any::<u64>(), any::<u64>()),
        bumps in (0.0..0.5f64, 0.0..0.5f64),
        angles in prop::array::uniform3(0.0..6.3f64),
        shift in prop::array::uniform3(-3.0..3.0f64),
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
        let mapped = TriMesh::new(
            b.positions().iter().map(|&p| placement.point(p)).collect(),
            b.triangles().to_vec(),
        )
        .expect("a mesh");
        prop_assert_eq!(ta.intersects(&tb, &placement), regions::solids_meet(&a, &mapped));
    }
}
