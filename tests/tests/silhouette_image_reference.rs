//! `sphaera_tests::silhouette_image` against pixel counts known in closed form.

use sphaera_mesh::glam::DVec3;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_tests::silhouette_image::{Frame, directions_around, render, wrong_pixels};

/// Pixel centres of a `resolution`-wide image in `[−s, s]` along one axis.
fn centres_within(s: f64, resolution: usize) -> usize {
    let size = 2.0 / resolution as f64;
    (0..resolution)
        .filter(|&i| (-1.0 + (i as f64 + 0.5) * size).abs() <= s)
        .count()
}

#[test]
fn a_unit_cube_seen_face_on_covers_the_square_of_its_face() {
    let cube = shapes::cube(1.0, 3).expect("a cube");
    let frame = Frame::orthographic(&cube, DVec3::Z);
    // Framed on the ball of radius √3/2 around its centre: the face spans ±(½)/(√3/2).
    let s = 0.5 / (3f64.sqrt() / 2.0);
    for resolution in [7, 64, 255] {
        let image = render(&cube, &frame, resolution);
        let side = centres_within(s, resolution);
        assert_eq!(
            image.iter().filter(|&&c| c).count(),
            side * side,
            "{resolution}"
        );
    }
}

#[test]
fn a_sphere_covers_a_disc_and_flipped_faces_count_the_same() {
    let sphere = shapes::sphere(2.0, 64).expect("a sphere");
    let frame = Frame::orthographic(&sphere, DVec3::new(0.3, -0.2, 0.9));
    let image = render(&sphere, &frame, 512);
    let covered = image.iter().filter(|&&c| c).count() as f64;
    // The inscribed polygon's disc: a little under π (256)² pixels.
    let disc = std::f64::consts::PI * 256.0 * 256.0;
    assert!(
        covered < disc && covered > 0.99 * disc,
        "{covered} against {disc}"
    );
    let flipped = TriMesh::new(
        sphere.positions().to_vec(),
        sphere
            .triangles()
            .iter()
            .map(|&[a, b, c]| [a, c, b])
            .collect(),
    )
    .expect("a mesh");
    assert_eq!(wrong_pixels(&image, &render(&flipped, &frame, 512)), 0);
}

#[test]
fn a_perspective_camera_sees_the_near_face_larger_than_the_far_one() {
    // Two squares of side 1 at z = ±1, seen from +z by a camera 3 radii away.
    let square = |z: f64| {
        TriMesh::new(
            vec![
                DVec3::new(-0.5, -0.5, z),
                DVec3::new(0.5, -0.5, z),
                DVec3::new(0.5, 0.5, z),
                DVec3::new(-0.5, 0.5, z),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .expect("a square")
    };
    let both = TriMesh::new(
        [square(1.0).positions(), square(-1.0).positions()].concat(),
        vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    )
    .expect("two squares");
    let frame = Frame::orthographic(&both, DVec3::Z).perspective(3.0);
    let count = |m: &TriMesh| render(m, &frame, 256).iter().filter(|&&c| c).count();
    let (near, far) = (count(&square(1.0)), count(&square(-1.0)));
    // Radius √1.5, eye at z = 3√1.5: a half side ½ at depth d spans ½·√8/d.
    let radius = 1.5_f64.sqrt();
    let expected = |depth: f64| centres_within(0.5 * 8f64.sqrt() / depth, 256).pow(2);
    assert_eq!(near, expected(3.0 * radius - 1.0));
    assert_eq!(far, expected(3.0 * radius + 1.0));
    assert!(near > far);
}

#[test]
fn directions_around_a_view_are_at_the_angle_asked() {
    let view = DVec3::new(1.0, 2.0, -0.5);
    let around = directions_around(view, 7.5, 8);
    assert_eq!(around.len(), 8);
    for d in &around {
        let angle = d.dot(view.normalize()).clamp(-1.0, 1.0).acos().to_degrees();
        assert!((angle - 7.5).abs() < 1e-9, "{angle}");
    }
}
