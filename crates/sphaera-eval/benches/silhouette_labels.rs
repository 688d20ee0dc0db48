//! Silhouette labels: the distance transforms against `imageproc`'s in the same run (on
//! the binary image of the Stanford bunny seen from the side at 512², background on the
//! silhouettes), the labels of the 69k bunny for every 15° view (266) at 512², and the
//! view-dependent extraction from its full hierarchy (error 1 % of the diagonal, factor ¼
//! within 2 cells of the contour) for a view between the cameras from scratch and for a
//! camera orbiting 1° per frame from the previous frame's mesh, against the label lookup
//! alone.
//!
//! `imageproc` measures distances to its *foreground* (non-zero) pixels, so it gets the
//! complement of our object image; it treats nothing beyond the image as background, which
//! changes nothing here (the mesh's image lies inside the grid). Its exact transform is
//! `euclidean_squared_distance_transform` (squared `f64` distances, square roots not
//! taken); `distance_transform` with `Norm::L1` is its two-pass chamfer, saturating at 255.
//! Run with `cargo bench -p sphaera-eval --bench silhouette_labels`.

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use imageproc::distance_transform::{
    Norm, distance_transform, euclidean_squared_distance_transform,
};
use imageproc::image::{GrayImage, Luma};
use sphaera::mesh::DVec3;
use sphaera::silhouette::{
    ContourTolerance, Contours, DistanceTransform, Interpolation, LabelOptions, Labels, Projection,
    ViewDependent, ViewSet, label_view,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions};

/// Cells a side.
const RESOLUTION: usize = 512;

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("silhouette_labels") else {
        return;
    };
    let bunny = sphaera::mesh::io::load(data.join("stanford-bunny.obj")).expect("the bunny");
    let side = label_view(
        &bunny,
        DVec3::new(0.0, 0.0, 1.0),
        Projection::Orthographic,
        RESOLUTION,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .expect("labels");
    let object: Vec<bool> = side.cells.iter().map(|&d| d > 0.0).collect();
    let complement = GrayImage::from_fn(RESOLUTION as u32, RESOLUTION as u32, |x, y| {
        Luma([if object[y as usize * RESOLUTION + x as usize] {
            0
        } else {
            255
        }])
    });

    let mut group = c.benchmark_group("distance_transform_512");
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("sphaera_euclidean", |b| {
        b.iter(|| black_box(DistanceTransform::Euclidean.apply(&object, RESOLUTION, RESOLUTION)));
    });
    group.bench_function("sphaera_chamfer", |b| {
        b.iter(|| black_box(DistanceTransform::Chamfer.apply(&object, RESOLUTION, RESOLUTION)));
    });
    group.bench_function("imageproc_euclidean_squared", |b| {
        b.iter(|| black_box(euclidean_squared_distance_transform(&complement)));
    });
    group.bench_function("imageproc_chamfer_l1", |b| {
        b.iter(|| black_box(distance_transform(&complement, Norm::L1)));
    });
    group.finish();

    let views = ViewSet::regular(15.0).expect("266 views");
    // Extraction for a new view (from the base mesh each time), labels by the nearest view
    // and by the 4 nearest, and the lookup alone.
    let labels = Labels::compute(
        &bunny,
        &views,
        &LabelOptions::default().with_resolution(RESOLUTION),
    )
    .expect("labels");
    let hierarchy = Hierarchy::build(&bunny, &SimplifyOptions::default()).expect("a hierarchy");
    let mut extractor = ViewDependent::new(&hierarchy, &labels).expect("the same mesh");
    let tolerance = ContourTolerance {
        error: 0.01 * bunny.bounding_box_diagonal(),
        factor: 0.25,
        threshold: 2.0,
        cells: f64::INFINITY,
    };
    let between = DVec3::new(0.31, 0.44, 0.52);
    let mut group = c.benchmark_group("extraction_bunny_69k");
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(5));
    // From scratch: a new extractor for the view (the first phase, refining the whole
    // mesh to the error, included).
    group.bench_function("extract_scratch_nearest", |b| {
        b.iter(|| {
            let mut fresh = ViewDependent::new(&hierarchy, &labels).expect("the same mesh");
            black_box(
                fresh
                    .extract(between, Interpolation::Nearest, tolerance)
                    .expect("extracts"),
            )
        });
    });
    // From the previous view's mesh: a camera orbiting 1° per frame.
    for (name, interpolation) in [
        ("nearest", Interpolation::Nearest),
        ("average_4", Interpolation::Average(4)),
    ] {
        let mut frame = 0_u32;
        group.bench_function(format!("extract_next_{name}"), |b| {
            b.iter(|| {
                frame = (frame + 1) % 360;
                let a = f64::from(frame).to_radians();
                let direction = DVec3::new(a.cos(), 0.35, a.sin());
                black_box(
                    extractor
                        .extract(direction, interpolation, tolerance)
                        .expect("extracts"),
                )
            });
        });
        group.bench_function(format!("labels_{name}"), |b| {
            b.iter(|| black_box(labels.for_view(between, interpolation).expect("labels")));
        });
    }
    group.finish();

    let mut group = c.benchmark_group("labels_bunny_69k");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    // The outline (the default) and every silhouette the camera sees (a depth buffer per
    // view on top).
    for (name, contours) in [
        ("266_views_512_outline", Contours::External),
        ("266_views_512_all_visible", Contours::All),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                black_box(
                    Labels::compute(
                        &bunny,
                        &views,
                        &LabelOptions::default()
                            .with_resolution(RESOLUTION)
                            .with_contours(contours),
                    )
                    .expect("labels"),
                )
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
