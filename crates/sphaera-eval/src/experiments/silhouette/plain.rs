//! `silhouette_vs_simplify`: the comparison a user makes — `sphaera silhouette MESH --view V
//! --error e` against `sphaera simplify MESH --triangles N` at the triangle count the
//! first gave — on meshes nobody tuned the method for.
//!
//! For each closed mesh of the shared data ([`SHARED`]) and each procedural shape
//! ([`procedural`]): labels as the CLI computes them (every 15°, 266 views, [`RESOLUTION`]²),
//! the hierarchy, and [`GIVEN`] seeded view directions between the cameras. For each
//! allowed error `e` of [`ERRORS`] (relative to the diagonal), each variant of
//! [`variants`] and each given view, the guided extraction for that view, and the plain
//! simplifier (`sphaera_simplify::simplify`, the CLI's defaults) at its triangle count.
//! Both are rendered with `sphaera_tests::silhouette_image` — an image of its own, not
//! `sphaera-silhouette`'s — at [`RESOLUTION`]², at the given view and at [`AROUND`] views
//! [`AROUND_DEGREES`]° around it (a camera moving on), and the pixels differing from the
//! original's are counted. The CSV has, per mesh, variant and `e`, the mean triangle
//! counts and wrong pixels of both, their ratio (0 when neither has a wrong pixel) and a
//! verdict: `gains` (at most half, at the view and around it), `gains less than 2x`,
//! `worse`, or `no outline detail to keep` (the plain simplifier is within a pixel a
//! view). The chart plots, per variant, the largest ratio over the meshes with detail to
//! keep against `e`, one panel per view kind.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::mesh::{DVec3, TriMesh, shapes};
use sphaera::silhouette::{
    ContourRegion, ContourTolerance, Contours, Interpolation, LabelOptions, Labels, ViewDependent,
    ViewSet,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions, simplify};
use sphaera_tests::silhouette_image::{Frame, directions_around, render, wrong_pixels};

use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name (`--only silhouette_vs_simplify`).
pub const NAME: &str = "silhouette_vs_simplify";

/// The closed meshes of the shared data.
pub const SHARED: &[&str] = &[
    "bunny_lowres.obj",
    "spot.obj",
    "fandisk.obj",
    "rocker-arm.obj",
    "eight.off",
];

/// Cells a side of the labels, and pixels a side of the judging images.
pub const RESOLUTION: usize = 512;

/// The allowed errors `e`, relative to the diagonal.
pub const ERRORS: &[f64] = &[0.0025, 0.005, 0.01, 0.02];

/// Given views per mesh.
pub const GIVEN: usize = 4;

/// Views around each given view, and their angle to it.
pub const AROUND: usize = 8;
/// See [`AROUND`].
pub const AROUND_DEGREES: f64 = 7.5;

/// The procedural shapes: a horned quadruped, a ball of spikes, a torus, a bumpy ball.
///
/// # Errors
///
/// Never in practice (the shapes' parameters are valid).
pub fn procedural() -> Result<Vec<(String, TriMesh)>> {
    let bumpy = shapes::sphere(1.0, 96)?;
    let bumpy = TriMesh::new(
        bumpy
            .positions()
            .iter()
            .map(|&p| {
                let n = p.normalize();
                n * (1.0 + 0.06 * (7.0 * n.x).sin() * (5.0 * n.y).cos() * (6.0 * n.z).sin())
            })
            .collect(),
        bumpy.triangles().to_vec(),
    )?;
    Ok(vec![
        (
            "quadruped (procedural)".to_owned(),
            sphaera_tests::animal::quadruped(),
        ),
        (
            "star of 12 spikes (procedural)".to_owned(),
            sphaera_tests::awkward::star_of_spikes(12),
        ),
        (
            "torus (procedural)".to_owned(),
            shapes::torus(1.0, 0.35, 48)?,
        ),
        ("bumpy ball (procedural)".to_owned(), bumpy),
    ])
}

/// One way of guiding the extraction.
pub struct Variant {
    /// Its name in the CSV and the chart.
    pub name: &'static str,
    /// Which silhouettes the labels measure.
    pub contours: Contours,
    /// The labels for a view between cameras.
    pub interpolation: Interpolation,
    /// The contour region, in cells.
    pub threshold: f32,
    /// The factor `f` on `e` in the contour region.
    pub factor: f64,
    /// When set, the contour region's allowance is at most this many cells of the labels'
    /// images ([`ContourTolerance::cells`]).
    pub cells: Option<f64>,
    /// Which triangles are in the contour region.
    pub region: ContourRegion,
    /// The labels' cameras (degrees apart) and cells a side.
    pub labels: (f64, usize),
}

/// The defaults of the library and the CLI: the widened region, at most ¼ e and ¼ cell.
pub const DEFAULT: &str = "default: widened, f = 0.25, 1/4 cell";
/// The paper's rule: corners, `e · f` alone.
pub const PAPER: &str = "paper: corners, f = 0.25";

/// The variants measured: the defaults, the paper's rule (the defaults before issue 40),
/// each of the defaults' two changes alone, the certified region, the internal
/// silhouettes, the scene's coarser labels (30°, 128²: a quarter of their cell is a
/// pixel of the 512² judge), and the paper's factor swept (its Fig. 7) with the widened
/// region.
#[must_use]
pub fn variants() -> Vec<Variant> {
    let variant = |name, region, factor, cells| Variant {
        name,
        contours: Contours::External,
        interpolation: Interpolation::Nearest,
        threshold: 2.0,
        factor,
        cells,
        region,
        labels: (15.0, RESOLUTION),
    };
    vec![
        variant(DEFAULT, ContourRegion::Widened, 0.25, Some(0.25)),
        variant(PAPER, ContourRegion::Corners, 0.25, None),
        variant(
            "corners, 1/4 cell",
            ContourRegion::Corners,
            0.25,
            Some(0.25),
        ),
        variant(
            "certified, 1/4 cell",
            ContourRegion::Certified,
            0.25,
            Some(0.25),
        ),
        Variant {
            contours: Contours::All,
            ..variant(
                "internal silhouettes too, widened, 1/4 cell",
                ContourRegion::Widened,
                0.25,
                Some(0.25),
            )
        },
        Variant {
            labels: (30.0, 128),
            ..variant(
                "the scene's labels (30°, 128²), widened, 1/4 cell",
                ContourRegion::Widened,
                0.25,
                Some(0.25),
            )
        },
        variant("widened, f = 0.1", ContourRegion::Widened, 0.1, None),
        variant("widened, f = 0.5", ContourRegion::Widened, 0.5, None),
    ]
}

/// Runs the experiment.
pub fn run(data: &Path, out: &Path) -> Result<()> {
    let views = ViewSet::regular(15.0)?;
    let mut meshes = crate::experiments::load_all_or_skip(data, SHARED)?;
    meshes.extend(procedural()?);
    let variants = variants();
    let mut rows = Vec::new();
    // Per variant and error, the largest ratio over the meshes with detail to keep.
    let mut worst = vec![vec![[0.0_f64; 2]; ERRORS.len()]; variants.len()];
    for (name, mesh) in &meshes {
        let hierarchy = Hierarchy::build(mesh, &SimplifyOptions::default())
            .with_context(|| format!("the hierarchy of {name}"))?;
        let given = given_views(&views, GIVEN, name);
        // The original's images, at each given view and around it.
        let frames: Vec<Vec<Frame>> = given
            .iter()
            .map(|&d| {
                std::iter::once(d)
                    .chain(directions_around(d, AROUND_DEGREES, AROUND))
                    .map(|d| Frame::orthographic(mesh, d))
                    .collect()
            })
            .collect();
        let originals: Vec<Vec<Vec<bool>>> = frames
            .iter()
            .map(|fs| fs.iter().map(|f| render(mesh, f, RESOLUTION)).collect())
            .collect();
        let diagonal = mesh.bounding_box_diagonal();
        // Labels by their settings, computed once.
        let mut computed: Vec<((Contours, u64, usize), Labels)> = Vec::new();
        for (slot_v, variant) in variants.iter().enumerate() {
            let (step, resolution) = variant.labels;
            let key = (variant.contours, step.to_bits(), resolution);
            let labels = match computed.iter().position(|(k, _)| *k == key) {
                Some(k) => &computed[k].1,
                None => {
                    computed.push((
                        key,
                        Labels::compute(
                            mesh,
                            &ViewSet::regular(step)?,
                            &LabelOptions::default()
                                .with_resolution(resolution)
                                .with_contours(variant.contours),
                        )
                        .with_context(|| format!("the labels of {name}"))?,
                    ));
                    &computed[computed.len() - 1].1
                }
            };
            let mut lod = ViewDependent::new(&hierarchy, labels)?.with_region(variant.region);
            for (slot_e, &e) in ERRORS.iter().enumerate() {
                let mut sums = Sums::default();
                for ((&d, frames), originals) in given.iter().zip(&frames).zip(&originals) {
                    let extraction = lod.extract(
                        d,
                        variant.interpolation,
                        ContourTolerance {
                            error: e * diagonal,
                            factor: variant.factor,
                            threshold: variant.threshold,
                            cells: variant.cells.unwrap_or(f64::INFINITY),
                        },
                    )?;
                    let guided = &extraction.simplified.mesh;
                    let n = guided.triangle_count();
                    let plain =
                        simplify(mesh, &SimplifyOptions::default().with_target_triangles(n))
                            .with_context(|| format!("{name} simplified to {n} triangles"))?
                            .mesh;
                    sums.guided_triangles += n;
                    sums.plain_triangles += plain.triangle_count();
                    for (k, (frame, original)) in frames.iter().zip(originals).enumerate() {
                        let ours = wrong_pixels(original, &render(guided, frame, RESOLUTION));
                        let theirs = wrong_pixels(original, &render(&plain, frame, RESOLUTION));
                        let slot = usize::from(k > 0);
                        sums.guided[slot] += ours;
                        sums.plain[slot] += theirs;
                    }
                }
                let mean = |x: usize, n: usize| x as f64 / n as f64;
                let (g, a) = (GIVEN, GIVEN * AROUND);
                // Both without a wrong pixel: nothing to gain, nothing lost.
                let ratio = |ours: usize, theirs: usize| {
                    if theirs == 0 {
                        if ours == 0 { 0.0 } else { f64::INFINITY }
                    } else {
                        ours as f64 / theirs as f64
                    }
                };
                let (given_r, around_r) = (
                    ratio(sums.guided[0], sums.plain[0]),
                    ratio(sums.guided[1], sums.plain[1]),
                );
                eprintln!(
                    "{name}, {}, e = {e}: {:.0} / {:.0} triangles; given view {:.1} / {:.1} px ({given_r:.2}), around {:.1} / {:.1} px ({around_r:.2})",
                    variant.name,
                    mean(sums.guided_triangles, g),
                    mean(sums.plain_triangles, g),
                    mean(sums.guided[0], g),
                    mean(sums.plain[0], g),
                    mean(sums.guided[1], a),
                    mean(sums.plain[1], a),
                );
                // Nothing to keep: the plain simplifier is within a pixel a view.
                let no_detail = sums.plain[0] <= g && sums.plain[1] <= a;
                let verdict = if no_detail {
                    "no outline detail to keep"
                } else if given_r <= 0.5 && around_r <= 0.5 {
                    "gains"
                } else if given_r <= 1.0 && around_r <= 1.0 {
                    "gains less than 2x"
                } else {
                    "worse"
                };
                if !no_detail {
                    let w = &mut worst[slot_v][slot_e];
                    w[0] = w[0].max(given_r);
                    w[1] = w[1].max(around_r);
                }
                rows.push(vec![
                    name.clone(),
                    variant.name.to_owned(),
                    e.to_string(),
                    format!("{:.1}", mean(sums.guided_triangles, g)),
                    format!("{:.1}", mean(sums.plain_triangles, g)),
                    format!("{:.2}", mean(sums.guided[0], g)),
                    format!("{:.2}", mean(sums.plain[0], g)),
                    format!("{given_r:.3}"),
                    format!("{:.2}", mean(sums.guided[1], a)),
                    format!("{:.2}", mean(sums.plain[1], a)),
                    format!("{around_r:.3}"),
                    verdict.to_owned(),
                ]);
            }
        }
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "method",
            "error_rel_diagonal",
            "mean_triangles_guided",
            "mean_triangles_plain",
            "given_view_pixels_guided",
            "given_view_pixels_plain",
            "given_view_ratio",
            "around_pixels_guided",
            "around_pixels_plain",
            "around_ratio",
            "verdict",
        ],
        &rows,
    )?;
    let series = |k: usize| -> Vec<Series> {
        variants
            .iter()
            .zip(&worst)
            .map(|(v, w)| Series {
                name: v.name.to_owned(),
                points: ERRORS
                    .iter()
                    .zip(w)
                    .map(|(&e, r)| (100.0 * e, r[k].max(0.005)))
                    .collect(),
            })
            .collect()
    };
    let (given_series, around_series) = (series(0), series(1));
    let panels = [
        ("worst mesh, at the given view", &given_series),
        ("worst mesh, 7.5° around it", &around_series),
    ];
    let panels: Vec<Panel<'_>> = panels
        .iter()
        .map(|(title, series)| Panel {
            spec: ChartSpec {
                title,
                x_label: "allowed error e (% of the diagonal)",
                y_label: "wrong silhouette pixels, guided / plain (largest over the meshes)",
            },
            series,
            diagonal: false,
            legend: SeriesLabelPosition::UpperLeft,
        })
        .collect();
    log_log_panels(&out.join(format!("{NAME}.svg")), &panels)
}

/// Wrong pixels summed over the views of one setting: `[given, around]`.
#[derive(Default)]
struct Sums {
    guided_triangles: usize,
    plain_triangles: usize,
    guided: [usize; 2],
    plain: [usize; 2],
}

/// `count` random directions seeded by the mesh's name, none within 2° of a camera of
/// `views`.
fn given_views(views: &ViewSet, count: usize, name: &str) -> Vec<DVec3> {
    let seed = name.bytes().fold(0x5eed_u64, |h, b| {
        h.wrapping_mul(31).wrapping_add(u64::from(b))
    });
    super::between_cameras(views, count, seed)
}
