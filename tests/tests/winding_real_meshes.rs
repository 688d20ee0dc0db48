//! Inside/outside on the real meshes: the generalized winding number against ray parity
//! (exact agreement on closed meshes), against parry3d's pseudo-normal containment, and
//! sensible answers on the open and non-manifold scans.

use glam::DVec3;
use parry3d_f64::{
    query::PointQuery,
    shape::{TriMesh as ParryTriMesh, TriMeshFlags},
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sphaera_io as io;
use sphaera_mesh::TriMesh;
use sphaera_query::winding::{WindingNumber, inside_by_ray_parity};
use sphaera_tests::data_dir;

/// Closed, consistently oriented meshes of the test data.
const CLOSED: &[&str] = &[
    "bunny_lowres.obj",
    "spot.obj",
    "fandisk.obj",
    "eight.off",
    "robots/objects/duck.obj",
    "robots/franka_panda/collision/link3.obj",
];

fn random_points_in_box(mesh: &TriMesh, n: usize, seed: u64) -> Vec<DVec3> {
    let bbox = mesh
        .bounding_box()
        .expanded(0.05 * mesh.bounding_box_diagonal());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let t = DVec3::new(rng.random(), rng.random(), rng.random());
            bbox.min + t * (bbox.max - bbox.min)
        })
        .collect()
}

fn parry_mesh(mesh: &TriMesh) -> ParryTriMesh {
    ParryTriMesh::with_flags(
        mesh.positions().to_vec(),
        mesh.triangles().to_vec(),
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES,
    )
    .expect("parry accepts the closed mesh")
}

#[test]
fn winding_classification_agrees_exactly_with_ray_parity_on_closed_meshes() {
    let Some(data) = data_dir("winding_classification_agrees_exactly_with_ray_parity") else {
        return;
    };
    for file in CLOSED {
        let mesh = io::load(data.join(file)).expect("the mesh loads");
        let winding = WindingNumber::new(&mesh).expect("a non-empty mesh");
        let points = random_points_in_box(&mesh, 400, 11);
        let certified = winding.classify_certified(&points);
        let fast = winding.classify(&points);
        let parry = parry_mesh(&mesh);
        let diagonal = mesh.bounding_box_diagonal();
        let mut compared = 0;
        for (i, &p) in points.iter().enumerate() {
            let Some(parity) = inside_by_ray_parity(&mesh, p) else {
                continue; // on the surface
            };
            compared += 1;
            assert_eq!(
                certified[i], parity,
                "{file}: point {p} certified winding {} vs ray parity {parity}",
                certified[i]
            );
            // The accelerated answer is exact away from the surface.
            let distance = parry.distance_to_local_point(p, false);
            if distance > 1e-3 * diagonal {
                assert_eq!(fast[i], parity, "{file}: point {p} at distance {distance}");
                assert_eq!(
                    parry.contains_local_point(p),
                    parity,
                    "{file}: parry disagrees at {p}"
                );
            }
        }
        assert!(compared > 350, "{file}: only {compared} points compared");
    }
}

#[test]
fn open_and_non_manifold_scans_get_sensible_answers() {
    let Some(data) = data_dir("open_and_non_manifold_scans_get_sensible_answers") else {
        return;
    };
    // The Stanford bunny has five holes in its base; the dragon is non-manifold; the
    // Panda hand is several open shells.
    for file in [
        "stanford-bunny.obj",
        "dragon_vrip_res3.ply",
        "robots/franka_panda/visual/hand.obj",
    ] {
        let mesh = io::load(data.join(file)).expect("the mesh loads");
        let winding = WindingNumber::new(&mesh).expect("a non-empty mesh");
        winding
            .check_solid()
            .unwrap_or_else(|e| panic!("{file} encloses a volume: {e}"));
        let far = mesh.bounding_box().center() + DVec3::splat(10.0 * mesh.bounding_box_diagonal());
        assert!(
            winding.winding_number(far).abs() < 1e-3,
            "{file}: far point"
        );
        // Away from the holes the answer is clear-cut: w is near 0 or near 1, and some
        // of the box is inside.
        let points = random_points_in_box(&mesh, 2_000, 5);
        let w = winding.winding_numbers(&points);
        let clear = w
            .iter()
            .filter(|w| w.abs() < 0.1 || (*w - 1.0).abs() < 0.1)
            .count();
        let inside = w.iter().filter(|&&w| w > 0.5).count();
        assert!(
            clear >= 1_900,
            "{file}: only {clear} of 2,000 values near 0 or 1"
        );
        assert!(inside >= 50, "{file}: only {inside} of 2,000 points inside");
    }
    // The bunny's bounding-box centre is inside its body despite the holes.
    let bunny = io::load(data.join("stanford-bunny.obj")).expect("the bunny loads");
    let winding = WindingNumber::new(&bunny).expect("a non-empty mesh");
    let w = winding.winding_number(bunny.bounding_box().center());
    assert!(w > 0.95, "w = {w} at the bunny's center");
}

#[test]
fn a_lone_open_sheet_is_reported_as_not_solid() {
    let sheet = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .expect("a valid mesh");
    let winding = WindingNumber::new(&sheet).expect("a non-empty mesh");
    assert!(winding.check_solid().is_err());
}
