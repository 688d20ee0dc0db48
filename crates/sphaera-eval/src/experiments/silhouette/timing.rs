//! `silhouette_time_vs_faces`: the paper's Tables 1–2 on meshes of 11k to 871k faces.
//! For each mesh of [`MESHES`]: the labels of every 15° view (266) at 512² (outline
//! labels, exact transform), the full hierarchy, then for a camera orbiting 1° per frame
//! ([`FRAMES`] frames between the cameras, error 1 % of the diagonal, factor ¼, 2 cells)
//! the label lookup alone (nearest camera, mean of the 4 nearest) and the extraction, from
//! scratch (a new extractor, the refinement to the error included) and from the previous
//! frame. The share of a frame spent on labels is lookup ÷ (lookup + extraction from the
//! previous frame), the paper's measure. Means over the frames, one thread for the
//! per-frame work, both cores for the labels and the hierarchy.

use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use sphaera::mesh::DVec3;
use sphaera::silhouette::{
    ContourTolerance, Contours, Interpolation, LabelOptions, Labels, ViewDependent, ViewSet,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions};

use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name (`--only silhouette_time_vs_faces`).
pub const NAME: &str = "silhouette_time_vs_faces";

/// The meshes, smallest first.
pub const MESHES: &[&str] = &[
    "dragon_vrip_res4.ply",
    "dragon_vrip_res3.ply",
    "stanford-bunny.obj",
    "dragon_vrip_res2.ply",
    "dragon_vrip.ply",
];

/// Frames of the orbit.
pub const FRAMES: u32 = 60;

/// Frames extracted from scratch (each with a new extractor).
const SCRATCH_FRAMES: u32 = 5;

/// Runs the experiment.
pub fn run(data: &Path, out: &Path) -> Result<()> {
    let views = ViewSet::regular(15.0)?;
    let mut rows = Vec::new();
    let names = [
        "labels (266 views at 512²)",
        "hierarchy",
        "extraction from scratch",
        "extraction from the previous frame",
        "lookup, nearest camera",
        "lookup, mean of 4 nearest",
    ];
    let mut series: Vec<Series> = names.iter().map(|n| Series::new(n)).collect();
    for file in MESHES {
        let Some(mesh) = crate::experiments::load_or_skip(data, file)? else {
            continue;
        };
        let faces = mesh.triangle_count();
        let started = Instant::now();
        let labels = Labels::compute(
            &mesh,
            &views,
            &LabelOptions::default()
                .with_resolution(512)
                .with_contours(Contours::External),
        )?;
        let labels_seconds = started.elapsed().as_secs_f64();
        let started = Instant::now();
        let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default())?;
        let hierarchy_seconds = started.elapsed().as_secs_f64();
        let tolerance = ContourTolerance {
            error: 0.01 * mesh.bounding_box_diagonal(),
            factor: 0.25,
            threshold: 2.0,
            cells: f64::INFINITY,
        };
        let direction = |frame: u32| {
            let a = f64::from(frame).to_radians() + 0.1;
            DVec3::new(a.cos(), 0.35, a.sin())
        };
        let mut scratch = 0.0;
        for frame in 0..SCRATCH_FRAMES {
            let started = Instant::now();
            ViewDependent::new(&hierarchy, &labels)?.extract(
                direction(frame * 7),
                Interpolation::Nearest,
                tolerance,
            )?;
            scratch += started.elapsed().as_secs_f64();
        }
        let scratch = scratch / f64::from(SCRATCH_FRAMES);
        let mut extractor = ViewDependent::new(&hierarchy, &labels)?;
        extractor.extract(direction(0), Interpolation::Nearest, tolerance)?;
        let (mut next, mut nearest, mut four, mut triangles) = (0.0, 0.0, 0.0, 0);
        for frame in 1..=FRAMES {
            let d = direction(frame);
            let started = Instant::now();
            std::hint::black_box(labels.for_view(d, Interpolation::Nearest)?);
            nearest += started.elapsed().as_secs_f64();
            let started = Instant::now();
            std::hint::black_box(labels.for_view(d, Interpolation::Average(4))?);
            four += started.elapsed().as_secs_f64();
            let started = Instant::now();
            let extraction = extractor.extract(d, Interpolation::Nearest, tolerance)?;
            next += started.elapsed().as_secs_f64();
            triangles += extraction.simplified.mesh.triangle_count();
        }
        let per_frame = |x: f64| x / f64::from(FRAMES);
        let (next, nearest, four) = (per_frame(next), per_frame(nearest), per_frame(four));
        let triangles = triangles / FRAMES as usize;
        let share = |lookup: f64| 100.0 * lookup / (lookup + next);
        eprintln!(
            "{file}: {faces} faces; labels {labels_seconds:.2} s, hierarchy {hierarchy_seconds:.2} s; \
             extraction {:.2} ms from scratch, {:.2} ms from the previous frame ({triangles} triangles); \
             lookup {:.3} ms nearest ({:.2} %), {:.3} ms 4 nearest ({:.2} %)",
            1e3 * scratch,
            1e3 * next,
            1e3 * nearest,
            share(nearest),
            1e3 * four,
            share(four)
        );
        let times = [
            labels_seconds,
            hierarchy_seconds,
            scratch,
            next,
            nearest,
            four,
        ];
        for (s, &t) in series.iter_mut().zip(&times) {
            s.points.push((faces as f64, t));
        }
        rows.push(vec![
            (*file).to_owned(),
            faces.to_string(),
            format!("{labels_seconds:.3}"),
            format!("{hierarchy_seconds:.3}"),
            format!("{:.3}", 1e3 * scratch),
            format!("{:.3}", 1e3 * next),
            triangles.to_string(),
            format!("{:.4}", 1e3 * nearest),
            format!("{:.4}", 1e3 * four),
            format!("{:.3}", share(nearest)),
            format!("{:.3}", share(four)),
        ]);
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "faces",
            "labels_s",
            "hierarchy_s",
            "extract_scratch_ms",
            "extract_next_ms",
            "triangles_out",
            "lookup_nearest_ms",
            "lookup_4_nearest_ms",
            "share_nearest_percent",
            "share_4_nearest_percent",
        ],
        &rows,
    )?;
    let (once, per_frame) = series.split_at(2);
    log_log_panels(
        &out.join(format!("{NAME}.svg")),
        &[
            Panel {
                spec: ChartSpec {
                    title: "once per mesh (2 cores)",
                    x_label: "faces of the input mesh",
                    y_label: "seconds",
                },
                series: once,
                diagonal: false,
                legend: SeriesLabelPosition::LowerRight,
            },
            Panel {
                spec: ChartSpec {
                    title: "per frame, camera orbiting 1° a frame (1 thread)",
                    x_label: "faces of the input mesh",
                    y_label: "seconds",
                },
                series: per_frame,
                diagonal: false,
                legend: SeriesLabelPosition::UpperLeft,
            },
        ],
    )
}
