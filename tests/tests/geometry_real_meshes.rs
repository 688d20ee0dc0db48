//! Geometry and sampling on the real meshes, checked against brute force and parry3d.

use glam::DVec3;
use parry3d_f64::{
    query::PointQuery,
    shape::{TriMesh as ParryTriMesh, TriMeshFlags},
};
use sphaera_io as io;
use sphaera_mesh::geometry;
use sphaera_query::sampling;
use sphaera_tests::data_dir;

#[test]
fn closest_point_by_brute_force_matches_parry_projection() {
    let Some(data) = data_dir("closest_point_by_brute_force_matches_parry_projection") else {
        return;
    };
    for file in [
        "bunny_lowres.obj",
        "robots/kuka_iiwa/link_3.obj",
        "teapot.obj",
    ] {
        let mesh = io::load(data.join(file)).expect("the mesh loads");
        let parry = ParryTriMesh::with_flags(
            mesh.positions().to_vec(),
            mesh.triangles().to_vec(),
            TriMeshFlags::empty(),
        )
        .expect("parry accepts the mesh");
        let bbox = mesh
            .bounding_box()
            .expanded(0.2 * mesh.bounding_box_diagonal());
        for i in 0..60 {
            // A deterministic spread of query points (a 3D Halton-like lattice).
            let t = DVec3::new(
                (f64::from(i) * 0.618_034).fract(),
                (f64::from(i) * 0.414_214).fract(),
                (f64::from(i) * 0.732_051).fract(),
            );
            let p = bbox.min + t * (bbox.max - bbox.min);
            let ours = mesh
                .triangle_iter()
                .map(|tri| geometry::closest_point_on_triangle(p, &tri).distance_squared)
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            let theirs = parry.distance_to_local_point(p, false);
            assert!(
                (ours - theirs).abs() <= 1e-9 * theirs.max(1e-12),
                "{file}: distance from {p}: ours {ours}, parry {theirs}"
            );
        }
    }
}

#[test]
fn surface_samples_lie_on_the_bunny_and_are_reproducible() {
    let Some(data) = data_dir("surface_samples_lie_on_the_bunny_and_are_reproducible") else {
        return;
    };
    let mesh = io::load(data.join("stanford-bunny.obj")).expect("the bunny loads");
    let diagonal = mesh.bounding_box_diagonal();
    let random = sampling::random(&mesh, 20_000, 3).expect("the bunny has area");
    let even = sampling::poisson_disk(&mesh, 5_000, 3).expect("the bunny has area");
    assert_eq!(random.len(), 20_000);
    assert_eq!(even.samples.len(), 5_000);
    for sample in random.iter().chain(&even.samples) {
        let triangle = mesh
            .triangle(sample.triangle)
            .expect("a triangle of the mesh");
        let on = geometry::closest_point_on_triangle(sample.position, &triangle);
        assert!(on.distance_squared.sqrt() <= 1e-12 * diagonal);
    }
    // Poisson-disk samples are spread out: no two closer than half the ideal spacing.
    assert!(
        even.relative_min_distance() > 0.5,
        "relative minimum distance {}",
        even.relative_min_distance()
    );
    // Same seed, same samples.
    let again = sampling::poisson_disk(&mesh, 5_000, 3).expect("the bunny has area");
    assert!(
        even.samples
            .iter()
            .zip(&again.samples)
            .all(|(a, b)| a.position == b.position && a.triangle == b.triangle)
    );
}
