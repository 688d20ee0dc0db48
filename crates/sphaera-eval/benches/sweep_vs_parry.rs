//! Closest-point queries: Sphaera's sessions (exact answers from the tree by default, and
//! the paper's way) and its static `TriangleTree`
//! (one query at a time, through a coherent `TreeCursor`, and `closest_many` on both
//! cores) against parry3d-f64's `TriMesh` point projection (its BVH), in the same run.
//!
//! Query sets (seeded; `sphaera_eval::query_sets`, shared with the `sweep_throughput`
//! experiment), on the 69k-triangle bunny and the 871k-triangle dragon:
//! - `uniform`: points uniform in the bounding box scaled 1.5×;
//! - `near`: points within 1 % of the diagonal of the surface (a surface sample moved
//!   along a random direction);
//! - `path`: a smooth closed path of small steps (coherent queries).
//!
//! Each measurement answers a block of `QUERIES` queries with one session (Sphaera) or
//! one BVH (parry); criterion reports the time per block. On the path, parry also runs
//! with the previous answer as a distance bound (`project_local_point_with_max_dist` with
//! the previous distance plus the step, which the answer cannot exceed). The paper's
//! linear worst case is timed too: queries at the centre of a sphere mesh (within 1e-9
//! of it), each from a fresh session. Hierarchy and BVH builds are
//! benched beside, and a deforming mesh frame by frame (`sweep_deforming`: Sphaera
//! refits its tree, parry rebuilds). Run with `cargo bench -p sphaera-eval --bench sweep_vs_parry` (append
//! `-- bunny` for the bunny only). Needs `../shared/data`; without it the bench says so.

#![allow(clippy::print_stderr)]

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh as ParryTriMesh, TriMeshFlags};
use sphaera::{
    mesh::{DVec3, TriMesh, closest::TriangleTree, io, shapes},
    sweep::{SessionOptions, Sweeper, Tolerance, build_hierarchy},
};
use sphaera_eval::query_sets::query_sets;
use sphaera_tests::hausdorff::DistanceToMesh;

/// Queries per measured block.
const QUERIES: usize = 2_000;

/// The meshes: bench name, file in `shared/data`.
const MESHES: &[(&str, &str)] = &[
    ("bunny_69k", "stanford-bunny.obj"),
    ("dragon_871k", "dragon_vrip.ply"),
];

fn sweep_vs_parry(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("sweep_vs_parry bench") else {
        return;
    };
    for &(name, file) in MESHES {
        let path = data.join(file);
        if !path.is_file() {
            eprintln!("sweep_vs_parry: skipped {name}, no {}", path.display());
            continue;
        }
        let mesh = io::load(&path).expect("the mesh loads");
        let mut group = c.benchmark_group(format!("sweep_build/{name}"));
        group.sample_size(10);
        group.measurement_time(Duration::from_secs(1));
        group.bench_function("sphaera_hierarchy", |b| {
            b.iter(|| build_hierarchy(black_box(&mesh)).expect("builds"));
        });
        group.bench_function("sphaera_triangle_tree", |b| {
            b.iter(|| TriangleTree::new(black_box(&mesh)).expect("builds"));
        });
        group.bench_function("parry_bvh", |b| {
            b.iter(|| DistanceToMesh::new(black_box(&mesh)));
        });
        group.finish();
        deforming(c, name, &mesh);
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        let hierarchy = build_hierarchy(&mesh).expect("builds");
        let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
        let parry = DistanceToMesh::new(&mesh);
        for (set, points) in query_sets(&mesh, QUERIES).expect("the mesh has area") {
            let mut group = c.benchmark_group(format!("sweep/{name}/{set}_{QUERIES}"));
            group.sample_size(10);
            group.warm_up_time(Duration::from_millis(300));
            group.measurement_time(Duration::from_secs(2));
            for (name, options) in [
                ("sphaera_session", SessionOptions::default()),
                (
                    "sphaera_session_paper",
                    SessionOptions::default().with_exact_by_tree(false),
                ),
            ] {
                group.bench_function(name, |b| {
                    b.iter(|| {
                        let mut session = sweeper.session_with(&options);
                        points
                            .iter()
                            .map(|&p| session.closest(p).expect("finite").distance)
                            .sum::<f64>()
                    });
                });
            }
            let one_percent = Tolerance::Absolute(0.01 * mesh.bounding_box_diagonal());
            group.bench_function("sphaera_session_anytime_1%", |b| {
                b.iter(|| {
                    let mut session = sweeper.session();
                    points
                        .iter()
                        .map(|&p| {
                            session
                                .closest_within(p, one_percent)
                                .expect("finite")
                                .upper
                        })
                        .sum::<f64>()
                });
            });
            group.bench_function("sphaera_triangle_tree", |b| {
                b.iter(|| {
                    points
                        .iter()
                        .map(|&p| tree.closest(p).expect("finite").distance)
                        .sum::<f64>()
                });
            });
            group.bench_function("sphaera_tree_cursor", |b| {
                b.iter(|| {
                    let mut cursor = tree.cursor();
                    points
                        .iter()
                        .map(|&p| cursor.closest(p).expect("finite").distance)
                        .sum::<f64>()
                });
            });
            group.bench_function("sphaera_closest_many_2_threads", |b| {
                b.iter(|| {
                    tree.closest_many(&points)
                        .expect("finite")
                        .iter()
                        .map(|c| c.distance)
                        .sum::<f64>()
                });
            });
            group.bench_function("parry", |b| {
                b.iter(|| points.iter().map(|&p| parry.distance(p)).sum::<f64>());
            });
            if set == "path" {
                let bounded = parry_mesh(&mesh);
                group.bench_function("parry_previous_bound", |b| {
                    b.iter(|| path_with_previous_bound(&bounded, &points));
                });
            }
            group.finish();
        }
    }
    worst_case(c);
}

/// A deforming mesh, frame by frame: every vertex moved by a smooth displacement field
/// (amplitude 1 % of the diagonal, wavelength half the diagonal, its phase advancing each
/// frame), then [`FRAME_QUERIES`] exact queries near the surface. Sphaera refits its
/// tree to the new positions (`TriangleTree::refit`, on both cores), then answers one
/// query at a time (`sphaera_tree_refit`), all on one thread (`_1_thread`), or in a batch
/// on both cores (`_closest_many`); parry refits its BVH
/// (`TriMesh::set_vertices` on a `DEFORMABLE` mesh), and also builds it anew. All pay for
/// computing the positions.
fn deforming(c: &mut Criterion, name: &str, mesh: &TriMesh) {
    let diagonal = mesh.bounding_box_diagonal();
    let (amplitude, wave) = (0.01 * diagonal, std::f64::consts::TAU / (0.5 * diagonal));
    let at_frame = |frame: u32| -> Vec<DVec3> {
        let phase = 0.1 * f64::from(frame);
        mesh.positions()
            .iter()
            .map(|&p| {
                p + amplitude
                    * DVec3::new(
                        (wave * p.y + phase).sin(),
                        (wave * p.z + phase).sin(),
                        (wave * p.x + phase).sin(),
                    )
            })
            .collect()
    };
    let Some((_, points)) = query_sets(mesh, FRAME_QUERIES)
        .expect("the mesh has area")
        .into_iter()
        .find(|(set, _)| *set == "near")
    else {
        return;
    };
    let mut tree = TriangleTree::new(mesh).expect("non-empty");
    let mut group = c.benchmark_group(format!("sweep_deforming/{name}_frame_{FRAME_QUERIES}"));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    let mut frame = 0_u32;
    group.bench_function("sphaera_tree_refit", |b| {
        b.iter(|| {
            frame += 1;
            tree.refit(&at_frame(frame))
                .expect("one position per vertex");
            points
                .iter()
                .map(|&p| tree.closest(p).expect("finite").distance)
                .sum::<f64>()
        });
    });
    let mut frame = 0_u32;
    group.bench_function("sphaera_tree_refit_closest_many", |b| {
        b.iter(|| {
            frame += 1;
            tree.refit(&at_frame(frame))
                .expect("one position per vertex");
            tree.closest_many(&points)
                .expect("finite")
                .iter()
                .map(|c| c.distance)
                .sum::<f64>()
        });
    });
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a pool");
    let mut frame = 0_u32;
    group.bench_function("sphaera_tree_refit_1_thread", |b| {
        b.iter(|| {
            frame += 1;
            one_thread.install(|| {
                tree.refit(&at_frame(frame))
                    .expect("one position per vertex");
                points
                    .iter()
                    .map(|&p| tree.closest(p).expect("finite").distance)
                    .sum::<f64>()
            })
        });
    });
    let mut frame = 0_u32;
    let mut deformable = ParryTriMesh::with_flags(
        mesh.positions().to_vec(),
        mesh.triangles().to_vec(),
        TriMeshFlags::DEFORMABLE,
    )
    .expect("a non-empty mesh");
    group.bench_function("parry_refit", |b| {
        b.iter(|| {
            frame += 1;
            deformable.set_vertices(&at_frame(frame));
            points
                .iter()
                .map(|&p| deformable.distance_to_local_point(p, false))
                .sum::<f64>()
        });
    });
    let mut frame = 0_u32;
    group.bench_function("parry_rebuild", |b| {
        b.iter(|| {
            frame += 1;
            let moved = ParryTriMesh::with_flags(
                at_frame(frame),
                mesh.triangles().to_vec(),
                TriMeshFlags::empty(),
            )
            .expect("a non-empty mesh");
            points
                .iter()
                .map(|&p| moved.distance_to_local_point(p, false))
                .sum::<f64>()
        });
    });
    group.finish();
}

/// Queries per frame of the deforming bench.
const FRAME_QUERIES: usize = 1_000;

/// parry's mesh of `mesh` (no topology needed for projection).
fn parry_mesh(mesh: &TriMesh) -> ParryTriMesh {
    ParryTriMesh::with_flags(
        mesh.positions().to_vec(),
        mesh.triangles().to_vec(),
        TriMeshFlags::empty(),
    )
    .expect("a non-empty mesh")
}

/// The sum of distances along a path, each projection bounded by the previous distance
/// plus the step (1-Lipschitz), falling back to an unbounded one if that ever failed.
fn path_with_previous_bound(mesh: &ParryTriMesh, points: &[DVec3]) -> f64 {
    let mut previous: Option<(DVec3, f64)> = None;
    let mut sum = 0.0;
    for &p in points {
        let d = match previous {
            Some((q, d)) => mesh
                .project_local_point_with_max_dist(p, false, d + (p - q).length() + 1e-12)
                .map_or_else(
                    || mesh.distance_to_local_point(p, false),
                    |projection| (projection.point - p).length(),
                ),
            None => mesh.distance_to_local_point(p, false),
        };
        previous = Some((p, d));
        sum += d;
    }
    sum
}

/// The linear worst case: the centre of a sphere mesh (every triangle at about the same
/// distance), 100 queries within 1e-9 of it, a fresh session each.
fn worst_case(c: &mut Criterion) {
    let sphere = shapes::sphere(1.0, 48).expect("a sphere");
    let hierarchy = build_hierarchy(&sphere).expect("builds");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let parry = parry_mesh(&sphere);
    let points: Vec<DVec3> = (0..100)
        .map(|i| {
            let t = f64::from(i);
            1e-9 * DVec3::new(t.sin(), (2.0 * t).cos(), (3.0 * t).sin())
        })
        .collect();
    let mut group = c.benchmark_group(format!(
        "sweep_worst_case/sphere_{}_centre_100",
        sphere.triangle_count()
    ));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(2));
    for (name, options) in [
        ("sphaera_fresh_sessions", SessionOptions::default()),
        (
            "sphaera_fresh_sessions_paper",
            SessionOptions::default().with_exact_by_tree(false),
        ),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                points
                    .iter()
                    .map(|&p| {
                        sweeper
                            .session_with(&options)
                            .closest(p)
                            .expect("finite")
                            .distance
                    })
                    .sum::<f64>()
            });
        });
    }
    group.bench_function("parry", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|&p| parry.distance_to_local_point(p, false))
                .sum::<f64>()
        });
    });
    group.finish();
}

criterion_group!(benches, sweep_vs_parry);
criterion_main!(benches);
