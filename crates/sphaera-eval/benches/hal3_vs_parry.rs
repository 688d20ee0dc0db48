//! Point inclusion in a closed genus-0 mesh: the 3D HAL tree against brute-force ray
//! parity, `sphaera-mesh`'s certified winding number, parry3d-f64's `contains_point`
//! (its BVH with angle-weighted pseudo-normals) and libigl's fast winding number (Python,
//! one thread, `peers/igl_winding.py`; skipped with a message when Python or the package
//! is absent), in the same run; and the HAL tree's build.
//!
//! Meshes: `spot.obj` (5,856 triangles), `fandisk.obj` (12,946; coplanar-rich) and the
//! Stanford bunny (`stanford-bunny.obj`, 69,451 triangles with five holes in its base,
//! closed here by a fan from each hole's centroid: 69,674 triangles, genus 0) from
//! `shared/data` (skipped with a message when absent), and a procedural sphere of about
//! 50,000 triangles (`shapes::sphere(1.0, 224)`). Queries: `QUERIES` points uniform in the
//! mesh's bounding box grown by 20 % (seeded `SplitMix64`), the same for every method;
//! criterion reports the time per block. libigl is timed by its script on the block
//! repeated as many times as criterion asks (at least `IGL_MIN_BLOCKS`, scaled back), less
//! a call on a single point (libigl builds its hierarchy in every call). Brute force only on the two smaller real meshes (it
//! is linear in the triangles); the bunny's build (seconds) is said once instead of
//! benched. Run with `cargo bench -p sphaera-eval --bench hal3_vs_parry` (libigl:
//! `SPHAERA_IGL_PYTHON=env/bin/python`, see `sphaera_eval::peers`).

// The hole filling, the bunny's build and the inside counts are said on the terminal.
#![allow(clippy::print_stderr)]

use std::{
    hint::black_box,
    path::{Path, PathBuf},
    time::{Duration, Instant},
};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh as ParryTriMesh, TriMeshFlags};
use sphaera::hal::{Containment, HalTree3, contains3_brute};
use sphaera::mesh::topology::{HalfEdgeMesh, analyze};
use sphaera::mesh::{DVec3, Surface, TriMesh, shapes};
use sphaera_eval::peers::{igl_python, run_igl_winding, write_points};
use sphaera_tests::random::SplitMix64;

/// Queries per measured block.
const QUERIES: usize = 200;

fn queries(mesh: &TriMesh, seed: u64) -> Vec<DVec3> {
    let bounds = mesh.bounding_box();
    let (lo, hi) = (bounds.min, bounds.max);
    let grow = (hi - lo) * 0.1;
    let mut rng = SplitMix64::new(seed);
    (0..QUERIES)
        .map(|_| {
            let t = DVec3::new(rng.unit(), rng.unit(), rng.unit());
            lo - grow + (hi - lo + 2.0 * grow) * t
        })
        .collect()
}

/// `mesh` with each hole closed by a fan of triangles from a new vertex at the centroid of
/// the hole's boundary loop, oriented as the faces around it. `sphaera-mesh` finds the
/// loops (`HalfEdgeMesh::boundary_loops`) but has no hole filling: this is the simplest
/// that closes a manifold mesh whose holes are nearly flat and convex (the bunny's base).
fn fill_holes(mesh: &TriMesh) -> TriMesh {
    let halfedges = HalfEdgeMesh::from_trimesh(mesh);
    let mut positions = mesh.positions().to_vec();
    let mut triangles = mesh.triangles().to_vec();
    for cycle in halfedges.boundary_loops() {
        let ring: Vec<u32> = cycle
            .iter()
            .map(|&h| halfedges.original_vertex(halfedges.origin(h)))
            .collect();
        let center = ring.iter().map(|&v| positions[v as usize]).sum::<DVec3>() / ring.len() as f64;
        let c = positions.len() as u32;
        positions.push(center);
        // The loop runs with the faces (the hole on its right): the cap runs against it.
        for (i, &u) in ring.iter().enumerate() {
            triangles.push([ring[(i + 1) % ring.len()], u, c]);
        }
    }
    TriMesh::new(positions, triangles).expect("the caps use the mesh's vertices and new ones")
}

/// A bench mesh: its name, the mesh, and whether brute force and the build are benched.
struct Case {
    name: String,
    mesh: TriMesh,
    brute: bool,
    build: bool,
}

fn cases() -> Vec<Case> {
    let mut cases = Vec::new();
    if let Some(data) = sphaera_tests::data_dir("hal3_vs_parry") {
        for name in ["spot.obj", "fandisk.obj"] {
            let mesh = sphaera::mesh::io::load(data.join(name)).expect("a shared mesh");
            cases.push(Case {
                name: name.trim_end_matches(".obj").to_owned(),
                mesh,
                brute: true,
                build: true,
            });
        }
        let bunny = sphaera::mesh::io::load(data.join("stanford-bunny.obj")).expect("the bunny");
        let closed = fill_holes(&bunny);
        let report = analyze(&closed);
        assert!(
            report.is_closed
                && report.is_manifold
                && report.is_oriented
                && report.component_count == 1
                && report.genus == Some(0),
            "the bunny's holes filled: {report:?}"
        );
        eprintln!(
            "hal3_vs_parry: the bunny's {} holes filled: {} triangles, closed, genus 0",
            analyze(&bunny).boundary_loop_count,
            closed.triangle_count()
        );
        cases.push(Case {
            name: format!("bunny_{}k", closed.triangle_count() / 1000),
            mesh: closed,
            brute: false,
            build: false,
        });
    }
    let sphere = shapes::sphere(1.0, 224).expect("a sphere");
    cases.push(Case {
        name: format!("sphere_{}k", sphere.triangle_count() / 1000),
        mesh: sphere,
        brute: false,
        build: true,
    });
    cases
}

/// At least this many blocks in each call of the Python peer: libigl builds its hierarchy
/// in every call, and the build (timed apart and subtracted) varies by milliseconds, so
/// the queries must take far longer.
const IGL_MIN_BLOCKS: u64 = 1000;

/// The Python peer's seconds for `blocks` blocks (its query time, measured on at least
/// [`IGL_MIN_BLOCKS`] blocks and scaled), and the number of the block's points it finds
/// inside.
fn igl_seconds(python: &Path, mesh: &Path, points: &Path, blocks: u64) -> (Duration, u64) {
    let repeats = blocks.max(IGL_MIN_BLOCKS);
    let runs = run_igl_winding(python, mesh, points, repeats, 1).expect("igl_winding.py runs");
    let run = runs[0];
    let seconds = run.seconds * blocks as f64 / repeats as f64;
    (Duration::from_secs_f64(seconds), run.inside)
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    let python = igl_python("hal3_vs_parry bench");
    let folder: PathBuf = std::env::temp_dir().join(format!("sphaera-hal3-{}", std::process::id()));
    if python.is_some() {
        std::fs::create_dir_all(&folder).expect("a temporary folder");
    }

    let mut group = c.benchmark_group("point_in_mesh");
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    for case in &cases {
        let (name, mesh) = (&case.name, &case.mesh);
        let points = queries(mesh, 23);
        let start = Instant::now();
        let tree = HalTree3::build(mesh).expect("genus 0");
        if !case.build {
            eprintln!(
                "hal3_vs_parry: {name}: HAL tree built in {:.2} s ({} nodes)",
                start.elapsed().as_secs_f64(),
                tree.nodes().len()
            );
        }
        let surface = Surface::new(mesh).expect("closed");
        let parry = ParryTriMesh::with_flags(
            mesh.positions().to_vec(),
            mesh.triangles().to_vec(),
            TriMeshFlags::ORIENTED,
        )
        .expect("an oriented mesh");
        let inside_hal = points
            .iter()
            .filter(|&&p| tree.contains(p) == Containment::Inside)
            .count();
        let inside_parry = points
            .iter()
            .filter(|&&p| parry.contains_local_point(p))
            .count();
        group.bench_with_input(BenchmarkId::new("hal", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| tree.contains(p) == Containment::Inside)
                    .count()
            });
        });
        group.bench_with_input(BenchmarkId::new("winding", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| surface.is_inside_certified(p))
                    .count()
            });
        });
        group.bench_with_input(BenchmarkId::new("parry", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| parry.contains_local_point(p))
                    .count()
            });
        });
        let mut inside_igl = None;
        if let Some(python) = &python {
            let (mesh_file, points_file) = (
                folder.join(format!("{name}.obj")),
                folder.join(format!("{name}.txt")),
            );
            sphaera::mesh::io::write_obj(&mesh_file, mesh).expect("a temporary mesh file");
            write_points(&points_file, &points).expect("a temporary points file");
            group.bench_function(BenchmarkId::new("libigl", name), |b| {
                b.iter_custom(|iters| {
                    let (seconds, inside) = igl_seconds(python, &mesh_file, &points_file, iters);
                    inside_igl = Some(inside);
                    seconds
                });
            });
        }
        eprintln!(
            "hal3_vs_parry: {name}: inside of {QUERIES}: HAL {inside_hal}, parry {inside_parry}{}",
            inside_igl.map_or_else(String::new, |k| format!(", libigl {k}"))
        );
        if case.brute {
            group.bench_with_input(
                BenchmarkId::new("brute_force", name),
                &points,
                |b, points| {
                    b.iter(|| {
                        points
                            .iter()
                            .filter(|&&p| contains3_brute(mesh, p) == Containment::Inside)
                            .count()
                    });
                },
            );
        }
    }
    group.finish();
    if python.is_some() {
        let _ = std::fs::remove_dir_all(&folder);
    }

    let mut group = c.benchmark_group("hal3_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    for case in cases.iter().filter(|case| case.build) {
        group.bench_with_input(
            BenchmarkId::from_parameter(&case.name),
            &case.mesh,
            |b, mesh| {
                b.iter(|| black_box(HalTree3::build(mesh).expect("genus 0")));
            },
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
