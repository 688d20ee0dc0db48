//! `sphaera-eval`: Sphaera's speed-versus-accuracy experiments and its same-run
//! comparisons with other libraries. Unpublished (`publish = false`), so that the peers it
//! measures against (parry3d-f64, meshopt, `delaunay`) never enter a published crate's
//! dependency graph.
//!
//! It has three parts that share this library:
//!
//! - the **experiments** ([`experiments`]), run by the `sphaera-eval` binary: each measures
//!   one capability over the real meshes in `../shared/data` and writes a chart
//!   (`docs/charts/NAME.svg`) with the data behind it (`NAME.csv`). `cargo xtask charts`
//!   runs all of them into `docs/charts`; directly:
//!
//!   ```text
//!   cargo run --release -p sphaera-eval -- --out docs/charts [--only NAME]
//!   ```
//!
//! - the **criterion benches** (`benches/*.rs`): Sphaera against a peer library in the same
//!   run (`cargo bench -p sphaera-eval --bench NAME`), with the figures in
//!   `docs/benchmarks.md`;
//! - the **measured code** both of them call ([`brute`], [`methods`], [`query_sets`]), so
//!   that a bench and the experiment charting the same comparison time exactly the same
//!   calls on exactly the same inputs.
//!
//! Timings are the minimum of several runs, on whatever machine runs them; the figures in
//! `docs/benchmarks.md` say which machine that was.
//!
//! # Modules
//!
//! - [`brute`]: brute-force point–mesh distance and the paper's naive Hausdorff estimate
//!   (the `sweep_throughput` and `hausdorff_gap_vs_time` experiments, the `hausdorff`
//!   bench);
//! - [`methods`]: the simplification calls compared, Sphaera's placements and meshopt (the
//!   `simplify_error_vs_time` experiment, the `simplify_vs_meshopt` bench);
//! - [`query_sets`]: the seeded closest-point query sets and their generator (the
//!   `sweep_throughput` experiment, the `sweep_vs_parry` and `polyline_vs_parry` benches);
//! - [`rapier_shapes`]: meshes scaled to a size of 1 and sphere sets as rapier colliders
//!   (the `scene_time_vs_error` experiment, the `scene_vs_rapier` bench);
//! - [`peers`]: peers run as child processes: cascading-upper-bounds in Python (the
//!   `hausdorff_gap_vs_time` experiment, the `hausdorff` bench), morphit-rs (the
//!   `spheres_vs_count` experiment, the `spheres_vs_morphit` bench) and libigl's fast
//!   winding number (the `hal3_vs_parry` bench);
//! - [`sphere_sets`]: exactly N spheres from Sphaera's one-level tree, and another set
//!   grown until it covers the surface (the `spheres_vs_count` experiment, the
//!   `spheres_vs_morphit` bench);
//! - `geos_peer` (with the `geos` feature, which needs the system's libgeos): GEOS
//!   prepared geometry as the same-run peer of 2D HAL point inclusion, its answers in
//!   HAL's terms (the `hal2_vs_geos` bench and test);
//! - [`chart`]: SVG charts (plotters) and the CSV written beside each (every experiment);
//! - [`experiments`]: one private module per experiment, with [`experiments::NAMES`] and
//!   [`experiments::run`] (the binary), and the voxel k-means sphere baseline
//!   [`experiments::voxel`] (the `robot_protrusion_vs_spheres` experiment, the
//!   `robot_spheres` bench).
//!
//! # Example
//!
//! The shared pieces work on any mesh, e.g. a procedural cube:
//!
//! ```
//! use sphaera::mesh::{DVec3, shapes};
//! use sphaera_eval::{brute::BruteForce, query_sets::query_sets};
//!
//! let cube = shapes::cube(2.0, 2)?;
//! let brute = BruteForce::new(&cube);
//! assert!((brute.distance(DVec3::new(3.0, 0.0, 0.0)) - 2.0).abs() < 1e-12);
//!
//! // The same seeded points every time.
//! let sets = query_sets(&cube, 10)?;
//! assert_eq!(sets, query_sets(&cube, 10)?);
//! # Ok::<(), anyhow::Error>(())
//! ```
//!
//! # Errors
//!
//! Everything here reports failures as [`anyhow::Error`] with context: the callers are a
//! binary and benches, which only print them.

pub mod brute;
pub mod chart;
pub mod experiments;
#[cfg(feature = "geos")]
pub mod geos_peer;
pub mod methods;
pub mod peers;
pub mod query_sets;
pub mod rapier_shapes;
pub mod sphere_sets;
