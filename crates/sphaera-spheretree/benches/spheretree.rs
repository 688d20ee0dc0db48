//! Sphere-tree construction on the low-res bunny (the reference case: depth 3,
//! branch 8, 10,000 samples), every medial reducer beside the classic baselines (octree,
//! grid, Hubbard) in the same run, and a Franka Panda collision link. The certified
//! worst error of each level is printed once (stderr), as a percentage of the diagonal,
//! since criterion reports only times.
//!
//! Run with `cargo bench -p sphaera-spheretree --bench spheretree` (about four minutes on
//! the 2-core reference machine; the surface is prepared inside the timed build, as a user
//! does); needs `../shared/data` (skipped with a message without
//! it).

#![allow(clippy::print_stderr)]

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera_io as io;
use sphaera_mesh::{Length, TriMesh};
use sphaera_query::Surface;
use sphaera_spheretree::{
    EvaluationOptions, Method, SphereTree, SphereTreeError, SphereTreeOptions, build, evaluate_set,
};

/// Prints each level's certified worst error (upper bound) and uncovered surface.
fn report(name: &str, mesh: &TriMesh, tree: &SphereTree) {
    let surface = Surface::new(mesh).expect("the mesh has an inside");
    let options = EvaluationOptions::default().with_tolerance(Length::RelativeToDiagonal(1e-3));
    let diagonal = mesh.bounding_box_diagonal();
    let levels: Vec<String> = (1..tree.level_count())
        .map(|level| {
            let e =
                evaluate_set(&surface, &tree.level_spheres(level), &options).expect("evaluates");
            format!(
                "L{level} {} spheres {:.2} % ({:.3} % bare)",
                e.sphere_count,
                100.0 * e.worst_upper / diagonal,
                100.0 * e.coverage.uncovered_fraction
            )
        })
        .collect();
    eprintln!("{name}: {}", levels.join(", "));
}

/// What a user runs for `method`: prepare the surface, then build (the surface's
/// preparation is timed with the build, as before the single entry point).
fn build_tree(mesh: &TriMesh, method: Method) -> Result<SphereTree, SphereTreeError> {
    let surface = Surface::new(mesh)?;
    build(&surface, &SphereTreeOptions::default().with_method(method))
}

fn bench_mesh(c: &mut Criterion, group_name: &str, file: &str) {
    let Some(data) = sphaera_tests::data_dir(group_name) else {
        return;
    };
    let path = data.join(file);
    if !path.is_file() {
        eprintln!("{file}: absent, skipped");
        return;
    }
    let mesh = io::load(&path).expect("the shared mesh loads");
    let mut group = c.benchmark_group(group_name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(8));
    for method in Method::ALL {
        let name = method.name();
        let tree = build_tree(&mesh, method).expect("builds");
        report(&format!("{group_name}/{name}"), &mesh, &tree);
        group.bench_function(name, |b| {
            b.iter(|| build_tree(black_box(&mesh), method).expect("builds"));
        });
    }
    group.finish();
}

fn bunny(c: &mut Criterion) {
    bench_mesh(c, "spheretree/bunny_lowres", "bunny_lowres.obj");
}

fn franka(c: &mut Criterion) {
    bench_mesh(
        c,
        "spheretree/franka_link3",
        "robots/franka_panda/collision/link3.obj",
    );
}

criterion_group!(benches, bunny, franka);
criterion_main!(benches);
