//! Labels: silhouette vertices get 0 and labels grow away from the contour; a precomputed
//! view's labels come back exactly; the mapping is conservative; scaling by a power of
//! two changes nothing; and the awkward inputs the issue lists.
// Labels of 0 and exact distances are compared exactly on purpose.
#![allow(clippy::float_cmp)]

use proptest::prelude::*;
use sphaera_mesh::glam::DVec2;
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_silhouette::{
    Contours, DistanceTransform, FaceGrid, Interpolation, LabelOptions, Labels, Projection,
    SilhouetteError, ViewSet, label_view,
};

fn directions() -> Vec<DVec3> {
    vec![
        DVec3::Z,
        DVec3::X,
        DVec3::new(0.3, -0.5, 0.8),
        DVec3::new(-0.61, 0.2, -0.35),
    ]
}

#[test]
fn silhouette_vertices_have_label_zero_and_labels_grow_inward() {
    let meshes = [
        shapes::sphere(1.0, 24).unwrap(),
        shapes::torus(1.0, 0.35, 24).unwrap(),
        shapes::cube(1.0, 4).unwrap(),
    ];
    for (m, mesh) in meshes.iter().enumerate() {
        for projection in [
            Projection::Orthographic,
            Projection::Perspective { distance: 3.0 },
        ] {
            for transform in [DistanceTransform::Euclidean, DistanceTransform::Chamfer] {
                for d in directions() {
                    let labels =
                        label_view(mesh, d, projection, 96, transform, Contours::All).unwrap();
                    for (v, &on) in labels.silhouette.iter().enumerate() {
                        if on {
                            assert_eq!(labels.vertices[v], 0.0, "mesh {m}, vertex {v}, {d}");
                        }
                    }
                    assert!(labels.faces.iter().all(|f| f.is_finite() && *f >= 0.0));
                    assert!(
                        labels
                            .edge_labels
                            .iter()
                            .all(|e| e.is_finite() && *e >= 0.0)
                    );
                    // A face's label is at most that of any of its vertices' cells.
                    for (f, t) in mesh.triangles().iter().enumerate() {
                        for &v in t {
                            assert!(labels.faces[f] <= labels.vertices[v as usize] + 1e-6);
                        }
                    }
                }
            }
        }
    }
    // A sphere seen from above: the label falls as the vertex's projection nears the rim.
    let mesh = shapes::sphere(1.0, 48).unwrap();
    let labels = label_view(
        &mesh,
        DVec3::Z,
        Projection::Orthographic,
        128,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .unwrap();
    let mut upper: Vec<(f64, f32)> = mesh
        .positions()
        .iter()
        .zip(&labels.vertices)
        .filter(|(p, _)| p.z > 0.0)
        .map(|(p, &l)| (p.truncate().length(), l))
        .collect();
    upper.sort_by(|a, b| a.0.total_cmp(&b.0));
    for pair in upper.windows(2) {
        assert!(pair[1].1 <= pair[0].1 + 1.5, "{pair:?}");
    }
    let center = upper[0].1;
    assert!(
        center > 55.0 && center < 65.0,
        "the pole is about 64 cells in: {center}"
    );
}

#[test]
fn precomputed_views_come_back_exactly_and_new_views_interpolate() {
    let mesh = shapes::torus(1.0, 0.35, 20).unwrap();
    let views = ViewSet::regular(30.0).unwrap();
    let labels = Labels::compute(
        &mesh,
        &views,
        &LabelOptions::default()
            .with_resolution(64)
            .with_contours(Contours::All),
    )
    .unwrap();
    assert_eq!(
        labels.storage_bytes(),
        2 * mesh.positions().len() * views.len()
    );
    for k in [0, 5, 17, views.len() - 1] {
        let own = labels.view(k);
        for interpolation in [Interpolation::Nearest, Interpolation::Average(4)] {
            assert_eq!(
                labels
                    .for_view(views.direction(k) * 3.0, interpolation)
                    .unwrap(),
                own
            );
        }
        // The stored labels are the view's own, quantized to a sixteenth of a cell.
        let direct = label_view(
            &mesh,
            views.direction(k),
            Projection::Orthographic,
            64,
            DistanceTransform::Euclidean,
            Contours::All,
        )
        .unwrap();
        for (a, b) in own.iter().zip(&direct.vertices) {
            assert!((a - b).abs() <= 1.0 / 32.0 + 1e-6);
        }
    }
    let between = DVec3::new(0.31, 0.44, 0.52);
    let nearest = views.nearest(between).unwrap();
    assert_eq!(
        labels.for_view(between, Interpolation::Nearest).unwrap(),
        labels.view(nearest)
    );
    let four = views.nearest_n(between, 4).unwrap();
    let averaged = labels.for_view(between, Interpolation::Average(4)).unwrap();
    for (v, &a) in averaged.iter().enumerate() {
        let mean = four.iter().map(|&k| labels.view(k)[v]).sum::<f32>() / 4.0;
        assert!((a - mean).abs() < 1e-4);
    }
    assert!(matches!(
        labels.for_view(between, Interpolation::Average(0)),
        Err(SilhouetteError::InvalidNearest { .. })
    ));
}

#[test]
fn scaling_by_a_power_of_two_changes_no_label() {
    let mesh = shapes::torus(1.0, 0.3, 16).unwrap();
    let moved = |s: f64| {
        TriMesh::new(
            mesh.positions()
                .iter()
                .map(|&p| p * s + DVec3::splat(3.0 * s))
                .collect(),
            mesh.triangles().to_vec(),
        )
        .unwrap()
    };
    let views = ViewSet::regular(45.0).unwrap();
    let reference = Labels::compute(
        &moved(1.0),
        &views,
        &LabelOptions::default().with_resolution(48),
    )
    .unwrap();
    for s in [0.25, 1024.0, 2f64.powi(-30)] {
        let labels = Labels::compute(
            &moved(s),
            &views,
            &LabelOptions::default().with_resolution(48),
        )
        .unwrap();
        for k in 0..views.len() {
            assert_eq!(labels.stored(k), reference.stored(k), "scale {s}, view {k}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(200)))]

    /// Every cell holding a point of a triangle lists the triangle.
    #[test]
    fn the_mapping_is_conservative(
        corners in proptest::collection::vec((-1.2_f64..1.2, -1.2_f64..1.2), 3),
        resolution in 1_usize..40,
        samples in proptest::collection::vec((0.0_f64..1.0, 0.0_f64..1.0), 50),
    ) {
        let t = [0, 1, 2].map(|i| DVec2::new(corners[i].0, corners[i].1));
        let grid = FaceGrid::new(&[t], resolution).expect("a resolution within the cap");
        for (a, b) in samples {
            let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
            let p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
            if p.abs().max_element() >= 1.0 {
                continue;
            }
            prop_assert_eq!(grid.faces(grid.cell_of(p)), &[0][..], "{}", p);
        }
        // The corners and edge midpoints too (thin triangles).
        for k in 0..3 {
            for p in [t[k], (t[k] + t[(k + 1) % 3]) / 2.0] {
                if p.abs().max_element() < 1.0 {
                    prop_assert_eq!(grid.faces(grid.cell_of(p)), &[0][..], "{}", p);
                }
            }
        }
    }
}

#[test]
fn awkward_inputs() {
    // A flat square seen exactly along its plane (edge-on faces), and face-on.
    let square = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    for d in [DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(1.0, 1.0, 0.0)] {
        let labels = label_view(
            &square,
            d,
            Projection::Orthographic,
            32,
            DistanceTransform::Euclidean,
            Contours::All,
        )
        .unwrap();
        assert!(labels.vertices.iter().all(|l| l.is_finite()), "{d}");
    }
    // Resolution 1: one cell, under the mesh, background beyond.
    let sphere = shapes::sphere(1.0, 12).unwrap();
    let one = label_view(
        &sphere,
        DVec3::Z,
        Projection::Orthographic,
        1,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .unwrap();
    assert_eq!(one.cells.len(), 1);
    // Open (a cube without its top: back faces seen through the hole) and non-manifold
    // (a fin on an edge) meshes.
    let cube = shapes::cube(1.0, 2).unwrap();
    let open = TriMesh::new(
        cube.positions().to_vec(),
        cube.triangles()
            .iter()
            .copied()
            .filter(|t| t.iter().any(|&v| cube.positions()[v as usize].z < 0.49))
            .collect(),
    )
    .unwrap();
    let mut fin = cube.triangles().to_vec();
    let [a, b, _] = fin[0];
    let mut positions = cube.positions().to_vec();
    positions.push(DVec3::new(3.0, 3.0, 3.0));
    fin.push([a, b, (positions.len() - 1) as u32]);
    let finned = TriMesh::new(positions, fin).unwrap();
    for mesh in [&open, &finned] {
        let views = ViewSet::regular(45.0).unwrap();
        let labels = Labels::compute(
            mesh,
            &views,
            &LabelOptions::default()
                .with_resolution(32)
                .with_transform(DistanceTransform::Chamfer),
        )
        .unwrap();
        assert_eq!(labels.views().len(), 26);
    }
    // Errors, named.
    assert!(matches!(
        label_view(
            &sphere,
            DVec3::Z,
            Projection::Perspective { distance: 0.5 },
            8,
            DistanceTransform::Euclidean,
            Contours::All
        ),
        Err(SilhouetteError::CameraInside { .. })
    ));
    assert!(matches!(
        label_view(
            &sphere,
            DVec3::Z,
            Projection::Orthographic,
            0,
            DistanceTransform::Euclidean,
            Contours::All
        ),
        Err(SilhouetteError::InvalidResolution { resolution: 0 })
    ));
    assert!(matches!(
        label_view(
            &sphere,
            DVec3::NAN,
            Projection::Orthographic,
            8,
            DistanceTransform::Euclidean,
            Contours::All
        ),
        Err(SilhouetteError::InvalidDirection { .. })
    ));
    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    assert!(matches!(
        label_view(
            &empty,
            DVec3::Z,
            Projection::Orthographic,
            8,
            DistanceTransform::Euclidean,
            Contours::All
        ),
        Err(SilhouetteError::EmptyMesh)
    ));
}

#[test]
fn real_meshes_label_their_silhouettes_zero() {
    let Some(data) = sphaera_tests::data_dir("real_meshes_label_their_silhouettes_zero") else {
        return;
    };
    for file in ["bunny_lowres.obj", "spot.obj", "fandisk.obj"] {
        let mesh = sphaera_io::load(data.join(file)).unwrap();
        for d in directions() {
            let labels = label_view(
                &mesh,
                d,
                Projection::Orthographic,
                128,
                DistanceTransform::Euclidean,
                Contours::All,
            )
            .unwrap();
            let zero = labels
                .silhouette
                .iter()
                .zip(&labels.vertices)
                .all(|(&on, &l)| !on || l == 0.0);
            assert!(zero, "{file} from {d}");
            assert!(
                labels.vertices.iter().any(|&l| l > 2.0),
                "{file}: some vertex inside"
            );
        }
    }
}

#[test]
fn coverage_of_a_sphere_is_its_disc_and_a_simplification_differs_at_its_outline() {
    use sphaera_silhouette::{bounding_sphere, coverage, silhouette_difference};
    let mesh = shapes::sphere(1.0, 64).unwrap();
    let frame = bounding_sphere(&mesh).unwrap();
    for d in directions() {
        let image = coverage(&mesh, frame, d, Projection::Orthographic, 128).unwrap();
        let covered = image.iter().filter(|&&c| c).count() as f64;
        let disc = std::f64::consts::PI * 64.0 * 64.0;
        assert!(
            (covered - disc).abs() < 0.03 * disc,
            "{d}: {covered} against {disc}"
        );
        assert_eq!(silhouette_difference(&image, &image), 0);
    }
    let coarse = shapes::sphere(1.0, 8).unwrap();
    let a = coverage(&mesh, frame, DVec3::Z, Projection::Orthographic, 128).unwrap();
    let b = coverage(&coarse, frame, DVec3::Z, Projection::Orthographic, 128).unwrap();
    let wrong = silhouette_difference(&a, &b);
    assert!(wrong > 0 && wrong < 2000, "{wrong}");
    assert!(matches!(
        coverage(&mesh, frame, DVec3::ZERO, Projection::Orthographic, 8),
        Err(SilhouetteError::InvalidDirection { .. })
    ));
}

/// `mesh` moved by `offset`.
fn shifted(mesh: &TriMesh, offset: DVec3) -> TriMesh {
    TriMesh::new(
        mesh.positions().iter().map(|&p| p + offset).collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap()
}

/// Two meshes as one.
fn both(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let n = a.positions().len() as u32;
    TriMesh::new(
        [a.positions(), b.positions()].concat(),
        a.triangles()
            .iter()
            .copied()
            .chain(b.triangles().iter().map(|t| t.map(|v| v + n)))
            .collect(),
    )
    .unwrap()
}

#[test]
fn a_contour_hidden_behind_another_part_cuts_no_hole() {
    // A small ball right behind a big one, seen from +z: its outline is hidden.
    let big = shapes::sphere(1.0, 48).unwrap();
    let small = shifted(
        &shapes::sphere(0.3, 24).unwrap(),
        DVec3::new(0.2, 0.1, -2.0),
    );
    let scene = both(&big, &small);
    let label = |contours| {
        label_view(
            &scene,
            DVec3::Z,
            Projection::Orthographic,
            128,
            DistanceTransform::Euclidean,
            contours,
        )
        .unwrap()
    };
    // Front vertices of the big ball well inside its outline (more than 6 cells of the
    // 128² image, framed on a ball of radius about 1.65).
    let inside: Vec<usize> = (0..big.positions().len())
        .filter(|&v| {
            let p = big.positions()[v];
            p.z > 0.0 && p.x * p.x + p.y * p.y < 0.8 * 0.8
        })
        .collect();
    assert!(inside.len() > 100);
    let all = label(Contours::All);
    // The small ball's silhouette is hidden: none of its vertices counts, and the big
    // ball's labels keep their distance to its own outline.
    let n = big.positions().len();
    assert!(all.silhouette[n..].iter().all(|&s| !s));
    let nearest = inside
        .iter()
        .map(|&v| all.vertices[v])
        .fold(f32::INFINITY, f32::min);
    assert!(nearest > 3.0, "{nearest}");
    // Seen from −z the small ball is in front: its outline is an internal silhouette of
    // the image and cuts the big ball's labels near it.
    let from_below = label_view(
        &scene,
        DVec3::NEG_Z,
        Projection::Orthographic,
        128,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .unwrap();
    assert!(from_below.silhouette[n..].iter().any(|&s| s));
    let behind: Vec<usize> = (0..n)
        .filter(|&v| {
            let p = big.positions()[v];
            p.z < 0.0 && p.x * p.x + p.y * p.y < 0.8 * 0.8
        })
        .collect();
    let cut = behind
        .iter()
        .filter(|&&v| from_below.vertices[v] <= 1.0)
        .count();
    assert!(cut > 5, "{cut}");
}

#[test]
fn a_zero_area_face_makes_no_silhouette_vertex() {
    // A flat square seen face on, with a zero-area sliver along its diagonal: no vertex
    // is shared by faces toward and away from the camera.
    let mesh = TriMesh::new(
        vec![
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
        ],
        vec![[0, 1, 2], [0, 2, 3], [0, 4, 2]],
    )
    .unwrap();
    let labels = label_view(
        &mesh,
        DVec3::Z,
        Projection::Orthographic,
        32,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .unwrap();
    assert!(
        labels.silhouette.iter().all(|&s| !s),
        "{:?}",
        labels.silhouette
    );
}
