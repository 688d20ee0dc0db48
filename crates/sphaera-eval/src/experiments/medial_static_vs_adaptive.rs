//! Medial-axis approximation: static (Hubbard) against adaptive sampling, the paper's
//! figures 10 to 13 (Bradshaw and O'Sullivan 2004, section 6.1).
//!
//! For each mesh of [`MESHES`], [`SAMPLES`] Poisson-disk surface samples (seed
//! [`SAMPLE_SEED`]) are the candidate forming points, shared by every method:
//!
//! - **adaptive**: `MedialApproximation::build` with `MedialOptions::default().with_target_spheres(n)`
//!   for each `n` of [`ADAPTIVE_TARGETS`] (coverage of the samples completed, then the
//!   worst sphere replaced until `n` spheres);
//! - **static** (Hubbard): `MedialApproximation::build_static` with `f` forming points for
//!   each `f` of [`STATIC_FORMING`], spread by farthest-point selection, internal spheres
//!   only, coverage **not** completed;
//! - **static + cover**: the same with coverage of the samples completed
//!   (`CoverCriterion::SmallestError`), to show what forcing coverage costs the static
//!   set.
//!
//! Measured per build: the sphere count, the worst (and mean) sphere error of the paper's
//! eq. 2 as the method reports it, the time of the build alone (best of [`RUNS`]; the surface
//! preparation and the sampling are shared and reported once per mesh as
//! `prep_seconds`), the fraction of the forming samples left uncovered, and — the point
//! of the chart — the **uncovered surface**: the fraction of [`CHECK_SAMPLES`]
//! independent, area-weighted random surface points (seed [`CHECK_SEED`], not the
//! forming samples) outside every sphere, with the largest gap (distance from an
//! uncovered point to the nearest sphere; the CSV gives the samples' ideal spacing beside
//! it, the scale of the holes between them). The adaptive method guarantees coverage of
//! its samples only, not of the surface between them, so its uncovered fraction is
//! measured, not assumed. Distances are relative to the mesh's bounding-box diagonal.
//!
//! By design this chart covers only [`MESHES`]; `cargo xtask charts --check` checks them.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::{
    medial::{CoverCriterion, MedialApproximation, MedialOptions, MedialSphere, Surface},
    mesh::{DVec3, TriMesh, sampling},
};

use sphaera::query::grid::UniformGrid;

use super::{load_or_skip, min_time};
use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name: its files are `medial_static_vs_adaptive.{svg,csv}`.
pub const NAME: &str = "medial_static_vs_adaptive";

/// The meshes: file in `shared/data` and label. The full 871k-triangle dragon keeps the
/// whole experiment at about a minute on 2 cores (its surface preparation and sampling
/// take a few seconds; the builds depend on the sample count, not the triangle count).
pub const MESHES: &[(&str, &str)] = &[
    ("stanford-bunny.obj", "bunny 69k"),
    ("dragon_vrip.ply", "dragon 871k"),
];

/// Poisson-disk surface samples per mesh: the forming-point candidates of every method.
pub const SAMPLES: usize = 10_000;

/// Seed of the forming samples.
pub const SAMPLE_SEED: u64 = 1;

/// Independent random surface points per mesh for the uncovered fraction.
pub const CHECK_SAMPLES: usize = 100_000;

/// Seed of the independent points (not [`SAMPLE_SEED`]: another stream, another sampler).
pub const CHECK_SEED: u64 = 0x00C0_FFEE;

/// Timing runs per build (the minimum is kept).
pub const RUNS: usize = 3;

/// Sphere-count targets of the adaptive method.
pub const ADAPTIVE_TARGETS: &[usize] = &[100, 200, 400, 800, 1600, 3200];

/// Forming-point counts of the static method: it makes about 2 to 3 internal spheres per
/// forming point, so its sphere counts span about the adaptive targets' range.
pub const STATIC_FORMING: &[usize] = &[40, 80, 160, 320, 640, 1280];

/// A point is covered by a sphere within this distance of it, relative to the diagonal
/// (forming points lie on their spheres up to rounding; the medial crate uses the same).
const COVER_TOLERANCE: f64 = 1e-9;

/// The methods, in the order of the chart's series.
const METHODS: &[Method] = &[Method::Adaptive, Method::Static, Method::StaticCovered];

/// How a set of spheres is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Method {
    Adaptive,
    Static,
    StaticCovered,
}

impl Method {
    /// Name in the CSV and the legend.
    fn name(self) -> &'static str {
        match self {
            Self::Adaptive => "adaptive",
            Self::Static => "static",
            Self::StaticCovered => "static+cover",
        }
    }

    /// The parameter values: sphere targets or forming-point counts.
    fn parameters(self) -> &'static [usize] {
        match self {
            Self::Adaptive => ADAPTIVE_TARGETS,
            Self::Static | Self::StaticCovered => STATIC_FORMING,
        }
    }

    fn build<'s>(
        self,
        surface: &'s Surface,
        samples: &[DVec3],
        parameter: usize,
    ) -> Result<MedialApproximation<'s>> {
        let built = match self {
            Self::Adaptive => MedialApproximation::build(
                surface,
                samples,
                &MedialOptions::default().with_target_spheres(parameter),
            ),
            Self::Static => MedialApproximation::build_static(surface, samples, parameter, None),
            Self::StaticCovered => MedialApproximation::build_static(
                surface,
                samples,
                parameter,
                Some(CoverCriterion::SmallestError),
            ),
        };
        built.with_context(|| format!("{} medial build ({parameter}) failed", self.name()))
    }
}

/// One measured build.
struct Row {
    file: &'static str,
    method: Method,
    parameter: usize,
    prep_seconds: f64,
    /// The Poisson-disk samples' ideal spacing, relative to the diagonal.
    spacing: f64,
    seconds: f64,
    spheres: usize,
    forming_points: usize,
    worst_error: f64,
    mean_error: f64,
    uncovered_samples: f64,
    uncovered_surface: f64,
    largest_gap: f64,
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    for &(file, label) in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        measure_mesh(file, label, &mesh, &mut rows)?;
    }
    write_table(out, &rows)?;
    draw(out, &rows)
}

/// Every method at every parameter on one mesh.
fn measure_mesh(
    file: &'static str,
    label: &str,
    mesh: &TriMesh,
    rows: &mut Vec<Row>,
) -> Result<()> {
    let diagonal = mesh.bounding_box_diagonal();
    let (prep_seconds, (surface, poisson)) = min_time(1, || {
        let surface = Surface::new(mesh).context("cannot prepare the surface")?;
        Ok((surface, sampling::poisson_disk(mesh, SAMPLES, SAMPLE_SEED)?))
    })?;
    let samples: Vec<DVec3> = poisson.samples.iter().map(|s| s.position).collect();
    let spacing = poisson.ideal_spacing / diagonal;
    let check: Vec<DVec3> = sampling::random(mesh, CHECK_SAMPLES, CHECK_SEED)?
        .iter()
        .map(|s| s.position)
        .collect();
    eprintln!(
        "{label}: {} triangles, {} samples (spacing {:.3} % diag), surface and samples in \
         {prep_seconds:.2} s",
        mesh.triangle_count(),
        samples.len(),
        100.0 * spacing,
    );
    for &method in METHODS {
        for &parameter in method.parameters() {
            let (seconds, medial) = min_time(RUNS, || method.build(&surface, &samples, parameter))?;
            let spheres = medial.spheres();
            let coverage = Coverage::measure(&spheres, &check, COVER_TOLERANCE * diagonal);
            let errors = spheres.iter().map(|s| s.error);
            let mean_error = errors.clone().sum::<f64>() / spheres.len().max(1) as f64;
            rows.push(Row {
                file,
                method,
                parameter,
                prep_seconds,
                spacing,
                seconds,
                spheres: medial.sphere_count(),
                forming_points: medial.delaunay().vertex_count(),
                worst_error: medial.worst_error() / diagonal,
                mean_error: mean_error / diagonal,
                uncovered_samples: medial.uncovered_samples().len() as f64
                    / samples.len().max(1) as f64,
                uncovered_surface: coverage.uncovered as f64 / check.len().max(1) as f64,
                largest_gap: coverage.largest_gap / diagonal,
            });
            report(label, rows.last());
        }
    }
    Ok(())
}

/// How well a set of spheres covers a set of points.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Coverage {
    /// Points outside every sphere (beyond the tolerance).
    uncovered: usize,
    /// The largest distance from an uncovered point to the nearest sphere (0 if none).
    largest_gap: f64,
}

impl Coverage {
    /// Counts the `points` outside every sphere (further than `tolerance` from all of
    /// them), with a uniform grid over the points' bounding box: each sphere is listed in
    /// the cells its bounding box overlaps, each point tests the spheres of its cell. The
    /// gap of an uncovered point is measured against every sphere (uncovered points are
    /// few, and a far sphere can be the nearest).
    fn measure(spheres: &[MedialSphere], points: &[DVec3], tolerance: f64) -> Self {
        let grid = SphereGrid::new(spheres, points);
        let mut uncovered = 0;
        let mut largest_gap = 0.0_f64;
        for &p in points {
            let covered = grid.candidates(p).iter().any(|&i| {
                let s = &spheres[i as usize];
                (p - s.center).length() <= s.radius + tolerance
            });
            if !covered {
                uncovered += 1;
                let gap = spheres
                    .iter()
                    .map(|s| (p - s.center).length() - s.radius)
                    .fold(f64::INFINITY, f64::min);
                if gap.is_finite() {
                    largest_gap = largest_gap.max(gap);
                }
            }
        }
        Self {
            uncovered,
            largest_gap,
        }
    }
}

/// Most cells along an axis of [`SphereGrid`].
const GRID_MAX_CELLS: usize = 96;

/// Sphere indices bucketed by the uniform cells of the points' bounding box that the
/// spheres' bounding boxes overlap (`sphaera-query`'s grid, its cell chosen here).
struct SphereGrid(UniformGrid);

impl SphereGrid {
    fn new(spheres: &[MedialSphere], points: &[DVec3]) -> Self {
        let lo = points.iter().copied().fold(DVec3::INFINITY, DVec3::min);
        let hi = points.iter().copied().fold(DVec3::NEG_INFINITY, DVec3::max);
        let extent = if lo.is_finite() && hi.is_finite() {
            (hi - lo).max_element()
        } else {
            0.0
        };
        // Cells about the median radius, at most GRID_MAX_CELLS along the longest axis.
        let mut radii: Vec<f64> = spheres
            .iter()
            .map(|s| s.radius)
            .filter(|r| r.is_finite())
            .collect();
        radii.sort_unstable_by(f64::total_cmp);
        let median = radii.get(radii.len() / 2).copied().unwrap_or(0.0);
        let cell = median.max(extent / GRID_MAX_CELLS as f64);
        let boxes = || {
            spheres.iter().map(|s| {
                let reach = DVec3::splat(s.radius);
                (s.center.is_finite() && s.radius.is_finite())
                    .then(|| (s.center - reach, s.center + reach))
            })
        };
        let dims = ((hi - lo) / cell)
            .to_array()
            .map(|d| (d.floor() as usize + 1).min(GRID_MAX_CELLS + 1));
        // No extent (or a refused grid): one cell holding every sphere. Invariant: one
        // cell of edge 1 lists each of fewer than 2³² spheres once.
        let grid = UniformGrid::new(lo, cell, dims, boxes())
            .or_else(|_| UniformGrid::new(DVec3::ZERO, 1.0, [1, 1, 1], boxes()))
            .expect("a one-cell grid of fewer than 2³² spheres");
        Self(grid)
    }

    /// The spheres listed in the cell of `p` (clamped into the grid).
    fn candidates(&self, p: DVec3) -> &[u32] {
        self.0.items_at(p)
    }
}

fn report(label: &str, row: Option<&Row>) {
    if let Some(r) = row {
        eprintln!(
            "{label:<12} {:<13} {:>5}  {:>5} spheres  {:>5} forming  worst {:6.3} %  \
             uncovered samples {:6.3} %  surface {:6.3} %  gap {:6.3} %  {:7.3} s",
            r.method.name(),
            r.parameter,
            r.spheres,
            r.forming_points,
            100.0 * r.worst_error,
            100.0 * r.uncovered_samples,
            100.0 * r.uncovered_surface,
            100.0 * r.largest_gap,
            r.seconds,
        );
    }
}

fn write_table(out: &Path, rows: &[Row]) -> Result<()> {
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.file.to_owned(),
                r.method.name().to_owned(),
                r.parameter.to_string(),
                r.spheres.to_string(),
                r.forming_points.to_string(),
                format!("{:.4}", 100.0 * r.worst_error),
                format!("{:.4}", 100.0 * r.mean_error),
                format!("{:.4}", 100.0 * r.uncovered_samples),
                format!("{:.4}", 100.0 * r.uncovered_surface),
                format!("{:.4}", 100.0 * r.largest_gap),
                format!("{:.4}", 100.0 * r.spacing),
                format!("{:.4}", r.seconds),
                format!("{:.4}", r.prep_seconds),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "file",
            "method",
            "parameter",
            "spheres",
            "forming_points",
            "worst_error_pct_diag",
            "mean_error_pct_diag",
            "uncovered_samples_pct",
            "uncovered_surface_pct",
            "largest_gap_pct_diag",
            "sample_spacing_pct_diag",
            "build_seconds",
            "prep_seconds",
        ],
        &table,
    )
}

/// Left: worst error against sphere count. Right: uncovered surface against sphere
/// count (zero fractions cannot be drawn on the log axis; the CSV has them). One series
/// per mesh and method, the same colour in both panels.
fn draw(out: &Path, rows: &[Row]) -> Result<()> {
    let mut errors = Vec::new();
    let mut uncovered = Vec::new();
    for &(file, label) in MESHES {
        for &method in METHODS {
            let of = || rows.iter().filter(|r| r.file == file && r.method == method);
            let name = format!("{}, {label}", method.name());
            let mut error = Series::new(&name);
            error.points = of()
                .map(|r| (r.spheres as f64, 100.0 * r.worst_error))
                .collect();
            let mut surface = Series::new(&name);
            surface.points = of()
                .map(|r| (r.spheres as f64, 100.0 * r.uncovered_surface))
                .collect();
            errors.push(error);
            uncovered.push(surface);
        }
    }
    let uncovered_label = format!(
        "uncovered surface, % of {}k random points",
        CHECK_SAMPLES / 1000
    );
    log_log_panels(
        &out.join(format!("{NAME}.svg")),
        &[
            Panel {
                spec: ChartSpec {
                    title: "Medial spheres: worst error (eq. 2) against count",
                    x_label: "spheres",
                    y_label: "worst sphere error, % of diagonal",
                },
                series: &errors,
                diagonal: false,
                legend: SeriesLabelPosition::LowerLeft,
            },
            Panel {
                spec: ChartSpec {
                    title: "Medial spheres: uncovered surface against count",
                    x_label: "spheres",
                    y_label: &uncovered_label,
                },
                series: &uncovered,
                diagonal: false,
                // Static sets sit near 10 %, covered ones below 1 %: the middle is free.
                legend: SeriesLabelPosition::MiddleLeft,
            },
        ],
    )
}

#[cfg(test)]
mod tests {
    use sphaera::medial::SphereKind;

    use super::*;
    use sphaera_tests::random::Lcg64;

    fn sphere(center: DVec3, radius: f64) -> MedialSphere {
        MedialSphere {
            center,
            radius,
            error: 0.0,
            closest: center,
            kind: SphereKind::Internal,
            covers: Vec::new(),
        }
    }

    /// Deterministic pseudo-random values in `[0, 1)`.
    fn values(seed: u64, n: usize) -> Vec<f64> {
        let mut rng = Lcg64::new(seed);
        (0..n).map(|_| rng.unit()).collect()
    }

    fn brute(spheres: &[MedialSphere], points: &[DVec3]) -> Coverage {
        let mut uncovered = 0;
        let mut largest_gap = 0.0_f64;
        for &p in points {
            let gap = spheres
                .iter()
                .map(|s| (p - s.center).length() - s.radius)
                .fold(f64::INFINITY, f64::min);
            if gap > 0.0 {
                uncovered += 1;
                largest_gap = largest_gap.max(gap);
            }
        }
        Coverage {
            uncovered,
            largest_gap,
        }
    }

    #[test]
    fn grid_coverage_matches_brute_force() {
        for seed in 0..8 {
            let v = values(seed, 4 * 60 + 3 * 2_000);
            let spheres: Vec<MedialSphere> = v[..240]
                .chunks_exact(4)
                .map(|c| {
                    // Radii from tiny to half the box, so cells hold spheres of all sizes.
                    sphere(
                        DVec3::new(c[0], c[1], c[2]) * 1.2 - 0.1,
                        0.5 * c[3] * c[3] * c[3],
                    )
                })
                .collect();
            let points: Vec<DVec3> = v[240..]
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2]))
                .collect();
            let grid = Coverage::measure(&spheres, &points, 0.0);
            let expected = brute(&spheres, &points);
            assert_eq!(grid.uncovered, expected.uncovered, "seed {seed}");
            assert!((grid.largest_gap - expected.largest_gap).abs() < 1e-12);
        }
    }

    #[test]
    fn coverage_of_no_spheres_and_no_points() {
        let points = [DVec3::ZERO, DVec3::X];
        let none = Coverage::measure(&[], &points, 0.0);
        assert_eq!(none.uncovered, 2);
        assert!(none.largest_gap.abs() < 1e-300);
        let all = Coverage::measure(&[sphere(DVec3::ZERO, 2.0)], &points, 0.0);
        assert_eq!(all.uncovered, 0);
        assert_eq!(
            Coverage::measure(&[sphere(DVec3::ZERO, 1.0)], &[], 0.0).uncovered,
            0
        );
        // A single point: the grid has no extent.
        let one = Coverage::measure(&[sphere(DVec3::X, 0.5)], &[DVec3::ZERO], 0.0);
        assert_eq!(one.uncovered, 1);
        assert!((one.largest_gap - 0.5).abs() < 1e-12);
    }
}
