//! `silhouette_error_vs_triangles`: does a level of detail guided by silhouette labels
//! keep the outline better than an unweighted one with as many triangles?
//!
//! For each mesh of [`MESHES`]: labels for every 15° view (266) at [`RESOLUTION`]², and
//! the full simplification hierarchy. For each allowed error `e` of [`ERRORS`] (relative
//! to the diagonal) and each evaluation view, the view-dependent extraction (contour
//! factor [`FACTOR`]) is compared with the hierarchy's uniform level of the same triangle
//! count (`Hierarchy::level_by_triangles`): the image-space silhouette error is the number
//! of pixels where the coverage image (cell centres covered, [`RESOLUTION`]², framed on
//! the original's bounding sphere) differs from the original's. Evaluation views:
//! [`VIEWS`] of the precomputed cameras (every 45°), and as many between the cameras
//! (seeded random directions, none within 2° of a camera). Variants (`VARIANTS`):
//! labels of the outline and the internal silhouettes or of the outline alone; the
//! nearest camera's labels or the mean of the 4 nearest; a contour region of 2 or 4
//! cells. The chart plots the mean pixel error against the mean triangle count, one panel
//! per mesh and view kind; the unweighted series is at the triangle counts of the
//! outline-only, nearest-camera, 2-cell variant.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::mesh::DVec3;
use sphaera::silhouette::{
    ContourTolerance, Contours, DistanceTransform, Interpolation, Labels, Projection,
    ViewDependent, ViewSet, bounding_sphere, coverage, silhouette_difference,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions};
use sphaera_tests::random::SplitMix64;

use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name (`--only silhouette_error_vs_triangles`).
pub const NAME: &str = "silhouette_error_vs_triangles";

/// The meshes.
pub const MESHES: &[&str] = &["stanford-bunny.obj", "dragon_vrip_res2.ply"];

/// Cells a side, for the labels and for the coverage images.
pub const RESOLUTION: usize = 512;

/// The allowed errors `e`, relative to the diagonal.
pub const ERRORS: &[f64] = &[0.005, 0.01, 0.02, 0.04];

/// The factor `f` on `e` in the contour region.
pub const FACTOR: f64 = 0.1;

/// Evaluation views of each kind.
pub const VIEWS: usize = 26;

/// One way of choosing the contour region.
struct Variant {
    name: &'static str,
    contours: Contours,
    interpolation: Interpolation,
    threshold: f32,
}

const VARIANTS: [Variant; 4] = [
    Variant {
        name: "outline and internal, nearest camera, 2 cells",
        contours: Contours::All,
        interpolation: Interpolation::Nearest,
        threshold: 2.0,
    },
    Variant {
        name: "outline, nearest camera, 2 cells",
        contours: Contours::External,
        interpolation: Interpolation::Nearest,
        threshold: 2.0,
    },
    Variant {
        name: "outline, nearest camera, 4 cells",
        contours: Contours::External,
        interpolation: Interpolation::Nearest,
        threshold: 4.0,
    },
    Variant {
        name: "outline, mean of 4 nearest, 2 cells",
        contours: Contours::External,
        interpolation: Interpolation::Average(4),
        threshold: 2.0,
    },
];

/// Runs the experiment.
pub fn run(data: &Path, out: &Path) -> Result<()> {
    let views = ViewSet::regular(15.0)?;
    let cameras = ViewSet::regular(45.0)?;
    let mut rng = SplitMix64::new(29);
    let between: Vec<DVec3> = (0..VIEWS)
        .map(|_| {
            loop {
                let d = DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                );
                let length = d.length();
                if length > 0.2 && length <= 1.0 {
                    let d = d / length;
                    // Not a camera: at least 2° from every one.
                    let nearest = views.nearest(d).expect("a direction");
                    if views.direction(nearest).dot(d) < 2f64.to_radians().cos() {
                        break d;
                    }
                }
            }
        })
        .collect();
    let kinds: [(&str, Vec<DVec3>); 2] = [
        ("at cameras", cameras.directions().to_vec()),
        ("between cameras", between),
    ];
    let mut rows = Vec::new();
    let mut panels_data: Vec<(String, Vec<Series>)> = Vec::new();
    for file in MESHES {
        let Some(mesh) = crate::experiments::load_or_skip(data, file)? else {
            continue;
        };
        let frame = bounding_sphere(&mesh)?;
        let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default())?;
        let mut labels = Vec::new();
        for contours in [Contours::All, Contours::External] {
            labels.push(
                Labels::compute(
                    &mesh,
                    &views,
                    RESOLUTION,
                    DistanceTransform::Euclidean,
                    contours,
                )
                .with_context(|| format!("labels of {file}"))?,
            );
        }
        let mut lods = [
            ViewDependent::new(&hierarchy, &labels[0])?,
            ViewDependent::new(&hierarchy, &labels[1])?,
        ];
        let diagonal = mesh.bounding_box_diagonal();
        for (kind, directions) in &kinds {
            let originals: Vec<Vec<bool>> = directions
                .iter()
                .map(|&d| coverage(&mesh, frame, d, Projection::Orthographic, RESOLUTION))
                .collect::<Result<_, _>>()?;
            let mut series: Vec<Series> = VARIANTS.iter().map(|v| Series::new(v.name)).collect();
            let mut unweighted =
                Series::new("unweighted, as many triangles as the outline, nearest, 2 cells");
            for &e in ERRORS {
                for (s, variant) in VARIANTS.iter().enumerate() {
                    let (mut triangles, mut weighted_pixels, mut uniform_pixels) = (0, 0, 0);
                    for (d, original) in directions.iter().zip(&originals) {
                        let lod = &mut lods[usize::from(variant.contours == Contours::External)];
                        let extraction = lod.extract(
                            *d,
                            variant.interpolation,
                            ContourTolerance {
                                error: e * diagonal,
                                factor: FACTOR,
                                threshold: variant.threshold,
                            },
                        )?;
                        let n = extraction.simplified.mesh.triangle_count();
                        let uniform = hierarchy.level_by_triangles(n);
                        let picture =
                            |m| coverage(m, frame, *d, Projection::Orthographic, RESOLUTION);
                        weighted_pixels +=
                            silhouette_difference(original, &picture(&extraction.simplified.mesh)?);
                        uniform_pixels += silhouette_difference(original, &picture(&uniform.mesh)?);
                        triangles += n;
                    }
                    let count = directions.len() as f64;
                    let (t, w, u) = (
                        triangles as f64 / count,
                        weighted_pixels as f64 / count,
                        uniform_pixels as f64 / count,
                    );
                    series[s].points.push((t, w.max(0.1)));
                    if s == 1 {
                        unweighted.points.push((t, u.max(0.1)));
                    }
                    eprintln!(
                        "{file}, {kind}, e = {e}: {} — {t:.0} triangles, {w:.1} pixels against {u:.1} unweighted ({:.2}×)",
                        variant.name,
                        if w > 0.0 { u / w } else { f64::INFINITY }
                    );
                    rows.push(vec![
                        (*file).to_owned(),
                        (*kind).to_owned(),
                        variant.name.to_owned(),
                        e.to_string(),
                        format!("{t:.1}"),
                        format!("{w:.2}"),
                        format!("{u:.2}"),
                    ]);
                }
            }
            series.push(unweighted);
            panels_data.push((format!("{file}, {kind}"), series));
        }
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "views",
            "method",
            "error_rel_diagonal",
            "mean_triangles",
            "mean_pixels_labels",
            "mean_pixels_unweighted",
        ],
        &rows,
    )?;
    let panels: Vec<Panel<'_>> = panels_data
        .iter()
        .map(|(title, series)| Panel {
            spec: ChartSpec {
                title,
                x_label: "triangles (mean over the views)",
                y_label: "silhouette pixels wrong at 512² (mean)",
            },
            series,
            diagonal: false,
            legend: SeriesLabelPosition::UpperRight,
        })
        .collect();
    log_log_panels(&out.join(format!("{NAME}.svg")), &panels)
}
