//! Silhouette labels: the distance transforms against `imageproc`'s in the same run (on
//! the binary image of the Stanford bunny seen from the side at 512², background on the
//! silhouettes), and the labels of the 69k bunny for every 15° view (266) at 512².
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
use sphaera::silhouette::{DistanceTransform, Labels, Projection, ViewSet, label_view};

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
    let mut group = c.benchmark_group("labels_bunny_69k");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.bench_function("266_views_512", |b| {
        b.iter(|| {
            black_box(
                Labels::compute(&bunny, &views, RESOLUTION, DistanceTransform::Euclidean)
                    .expect("labels"),
            )
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
