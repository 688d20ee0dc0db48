//! Closest-point queries on a 3D polyline: Sphaera's polyline sessions (exact answers
//! from the segment tree, the default, and the paper's capsule hierarchy,
//! `with_exact_by_tree(false)`) against parry3d-f64's `Polyline` point projection (its
//! BVH), in the same run; and anytime queries at 1 % of the helix's diagonal.
//!
//! The polyline (seeded): a noisy helix of 100 000 points, 20 turns of radius 1 and pitch
//! 0.25, each point moved by up to 1 % of the radius. Query sets (seeded; the generator
//! of both is `sphaera_tests::random::Lcg64`):
//! - `uniform`: points uniform in the bounding box scaled 1.5× about its centre;
//! - `path`: a smooth path of small steps (about 2 · 10⁻³ each) winding around the helix
//!   at radius 1.3, the coherent case.
//!
//! Each measurement answers a block of `QUERIES` queries with one session (Sphaera) or one
//! BVH (parry); criterion reports the time per block (queries/s = `QUERIES` / time). The
//! builds are benched beside. Run with
//! `cargo bench -p sphaera-eval --bench polyline_vs_parry`.

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use parry3d_f64::{query::PointQuery, shape::Polyline as ParryPolyline};
use sphaera::{
    mesh::DVec3,
    sweep::{Polyline, Tolerance, polyline::PolylineSessionOptions},
};
use sphaera_tests::random::Lcg64;

/// Points of the polyline.
const POINTS: usize = 100_000;

/// Queries per measured block.
const QUERIES: usize = 2_000;

/// The noisy helix of the module docs.
fn helix() -> Vec<DVec3> {
    let mut rng = Lcg64::new(3);
    let turns = 20.0;
    (0..POINTS)
        .map(|i| {
            let a = std::f64::consts::TAU * turns * i as f64 / POINTS as f64;
            let noise = 0.01 * (2.0 * rng.unit_cube() - DVec3::ONE);
            DVec3::new(a.cos(), a.sin(), 0.25 * a / std::f64::consts::TAU) + noise
        })
        .collect()
}

/// The two query sets of the module docs.
fn query_sets(points: &[DVec3]) -> Vec<(&'static str, Vec<DVec3>)> {
    let (min, max) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let center = 0.5 * (min + max);
    let half = 0.5 * (max - min);
    let mut rng = Lcg64::new(7);
    let uniform = (0..QUERIES)
        .map(|_| center + 1.5 * half * (2.0 * rng.unit_cube() - DVec3::ONE))
        .collect();
    let path = (0..QUERIES)
        .map(|i| {
            let a = 1.5e-3 * i as f64;
            DVec3::new(1.3 * a.cos(), 1.3 * a.sin(), 2.0 + 0.1 * a)
        })
        .collect();
    vec![("uniform", uniform), ("path", path)]
}

fn polyline_vs_parry(c: &mut Criterion) {
    let points = helix();
    let mut group = c.benchmark_group(format!("polyline_build/helix_{POINTS}"));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(2));
    group.bench_function("sphaera", |b| {
        b.iter(|| Polyline::open(black_box(points.clone())).expect("valid"));
    });
    group.bench_function("parry_bvh", |b| {
        b.iter(|| ParryPolyline::new(black_box(points.clone()), None));
    });
    group.finish();
    let polyline = Polyline::open(points.clone()).expect("valid");
    let parry = ParryPolyline::new(points.clone(), None);
    for (set, queries) in query_sets(&points) {
        let mut group = c.benchmark_group(format!("polyline/helix_{POINTS}/{set}_{QUERIES}"));
        group.throughput(Throughput::Elements(QUERIES as u64));
        group.sample_size(10);
        group.warm_up_time(Duration::from_millis(300));
        group.measurement_time(Duration::from_secs(2));
        group.bench_function("sphaera_session", |b| {
            b.iter(|| {
                let mut session = polyline.session();
                queries
                    .iter()
                    .map(|&p| session.closest(p).expect("finite").distance)
                    .sum::<f64>()
            });
        });
        let paper = PolylineSessionOptions::default().with_exact_by_tree(false);
        group.bench_function("sphaera_session_paper", |b| {
            b.iter(|| {
                let mut session = polyline.session_with(&paper);
                queries
                    .iter()
                    .map(|&p| session.closest(p).expect("finite").distance)
                    .sum::<f64>()
            });
        });
        let one_percent = Tolerance::Absolute(0.01 * polyline.diagonal());
        group.bench_function("sphaera_anytime_1%", |b| {
            b.iter(|| {
                let mut session = polyline.session();
                queries
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
        group.bench_function("parry", |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|&p| parry.distance_to_local_point(p, true))
                    .sum::<f64>()
            });
        });
        group.finish();
    }
}

criterion_group!(benches, polyline_vs_parry);
criterion_main!(benches);
