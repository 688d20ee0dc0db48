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
//! outline-only, nearest-camera, 2-cell variant. The CSV also has the largest contour
//! displacement ([`contour_displacement`], in cells, the mean over the views of each
//! view's largest) for both.
//!
//! Object space (`silhouette_object_error.csv`): for the outline-only, nearest-camera,
//! 2-cell variant and [`OBJECT_VIEWS`] views between the cameras, the certified one-sided
//! Hausdorff distance (`sphaera-sweep`, gap at most 10⁻⁵ of the diagonal) from the
//! extraction's contour region, and from the rest, to the original, against the bounds
//! the extraction certifies for each region.
//!
//! The bunny also gets the paper's Fig. 3 made by code (`picture.rs`,
//! [`picture::FILE`]). Timing like the paper's Tables 1–2 is its own experiment
//! (`timing.rs`, [`timing::NAME`]).

pub mod picture;
pub mod plain;
pub mod temporal;
pub mod timing;

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::mesh::{DVec3, Length, TriMesh};
use sphaera::query::Surface;
use sphaera::silhouette::{
    ContourRegion, ContourTolerance, Contours, Extraction, Interpolation, LabelOptions, Labels,
    Projection, ViewDependent, ViewSet, bounding_sphere, contour_displacement, coverage,
    silhouette_difference,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions};
use sphaera::sweep::{HausdorffOptions, hausdorff};
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

/// Views between the cameras whose object-space errors are measured.
pub const OBJECT_VIEWS: usize = 4;

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
    let between = between_cameras(&views, VIEWS, 29);
    let kinds: [(&str, Vec<DVec3>); 2] = [
        ("at cameras", cameras.directions().to_vec()),
        ("between cameras", between.clone()),
    ];
    let mut rows = Vec::new();
    let mut object_rows = Vec::new();
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
                    &LabelOptions::default()
                        .with_resolution(RESOLUTION)
                        .with_contours(contours),
                )
                .with_context(|| format!("labels of {file}"))?,
            );
        }
        if *file == MESHES[0] {
            picture::write(out, &mesh, &hierarchy, [&labels[1], &labels[0]], RESOLUTION)?;
        }
        // The paper's method: its region rule, `e · f` alone.
        let mut lods = [
            ViewDependent::new(&hierarchy, &labels[0])?.with_region(ContourRegion::Corners),
            ViewDependent::new(&hierarchy, &labels[1])?.with_region(ContourRegion::Corners),
        ];
        let diagonal = mesh.bounding_box_diagonal();
        object_rows.extend(object_errors(
            file,
            &mesh,
            &labels[1],
            &mut lods[1],
            &between[..OBJECT_VIEWS],
        )?);
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
                    let mut sums = Sums::default();
                    for (d, original) in directions.iter().zip(&originals) {
                        let lod = &mut lods[usize::from(variant.contours == Contours::External)];
                        let extraction = lod.extract(
                            *d,
                            variant.interpolation,
                            ContourTolerance {
                                error: e * diagonal,
                                factor: FACTOR,
                                threshold: variant.threshold,
                                cells: f64::INFINITY,
                            },
                        )?;
                        let n = extraction.simplified.mesh.triangle_count();
                        let uniform = hierarchy.level_by_triangles(n);
                        let picture =
                            |m| coverage(m, frame, *d, Projection::Orthographic, RESOLUTION);
                        let (ours, theirs) = (
                            picture(&extraction.simplified.mesh)?,
                            picture(&uniform.mesh)?,
                        );
                        sums.add(n, original, &ours, &theirs);
                    }
                    let count = directions.len() as f64;
                    let mean = |x: f64| x / count;
                    let (t, w, u) = (
                        mean(sums.triangles as f64),
                        mean(sums.weighted_pixels as f64),
                        mean(sums.uniform_pixels as f64),
                    );
                    let (wd, ud) = (mean(sums.weighted_moved), mean(sums.uniform_moved));
                    series[s].points.push((t, w.max(0.1)));
                    if s == 1 {
                        unweighted.points.push((t, u.max(0.1)));
                    }
                    eprintln!(
                        "{file}, {kind}, e = {e}: {} — {t:.0} triangles, {w:.1} pixels against {u:.1} unweighted ({:.2}×), contour moved {wd:.2} against {ud:.2} cells",
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
                        format!("{wd:.2}"),
                        format!("{ud:.2}"),
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
            "mean_displacement_cells_labels",
            "mean_displacement_cells_unweighted",
        ],
        &rows,
    )?;
    write_csv(
        &out.join("silhouette_object_error.csv"),
        &[
            "mesh",
            "error_rel_diagonal",
            "views",
            "contour_bound_rel",
            "contour_measured_lower_rel",
            "contour_measured_upper_rel",
            "other_bound_rel",
            "other_measured_lower_rel",
            "other_measured_upper_rel",
            "contour_from_original_rel",
            "other_from_original_rel",
        ],
        &object_rows,
    )?;
    chart(out, &panels_data)
}

/// Running sums over the views of one setting.
#[derive(Default)]
struct Sums {
    triangles: usize,
    weighted_pixels: usize,
    uniform_pixels: usize,
    /// Sums of each view's largest contour displacement (a view where a level shows
    /// nothing counts the grid's side).
    weighted_moved: f64,
    uniform_moved: f64,
}

impl Sums {
    fn add(&mut self, triangles: usize, original: &[bool], ours: &[bool], theirs: &[bool]) {
        let moved =
            |x: &[bool]| contour_displacement(original, x, RESOLUTION).unwrap_or(RESOLUTION as f64);
        self.triangles += triangles;
        self.weighted_pixels += silhouette_difference(original, ours);
        self.uniform_pixels += silhouette_difference(original, theirs);
        self.weighted_moved += moved(ours);
        self.uniform_moved += moved(theirs);
    }
}

/// For each allowed error, the largest certified bound and measured distance (certified
/// lower and upper bounds of the one-sided Hausdorff distance to the original, at most
/// 10⁻⁵ of the diagonal apart) of the contour region and of the rest, over `directions`,
/// relative to the diagonal; and the paper's measure, the other way (after Aspert et al.:
/// from every vertex of the original's surface to the extraction), split by the vertex's
/// label (contour: at most 2 cells).
fn object_errors(
    file: &str,
    mesh: &TriMesh,
    labels: &Labels,
    lod: &mut ViewDependent<'_>,
    directions: &[DVec3],
) -> Result<Vec<Vec<String>>> {
    let diagonal = mesh.bounding_box_diagonal();
    let options = HausdorffOptions::default()
        .with_symmetric(false)
        .with_tolerance(Length::RelativeToDiagonal(1e-5));
    let mut used = vec![false; mesh.positions().len()];
    for &v in mesh.triangles().iter().flatten() {
        used[v as usize] = true;
    }
    let mut rows = Vec::new();
    for &e in ERRORS {
        // Per region: the largest bound, and the largest lower and upper measured bounds;
        // then the paper's measure per region.
        let mut worst = [0.0_f64; 8];
        for &d in directions {
            let extraction = lod.extract(
                d,
                Interpolation::Nearest,
                ContourTolerance {
                    error: e * diagonal,
                    factor: FACTOR,
                    threshold: 2.0,
                    cells: f64::INFINITY,
                },
            )?;
            for (k, contour) in [true, false].into_iter().enumerate() {
                let part = region(&extraction, contour)?;
                let (lower, upper) = match part {
                    Some(part) => {
                        let h = hausdorff(&part, mesh, &options)?;
                        (h.lower, h.upper)
                    }
                    None => (0.0, 0.0),
                };
                let bound = if contour {
                    extraction.contour_error
                } else {
                    extraction.other_error
                };
                for (w, x) in worst[3 * k..3 * k + 3]
                    .iter_mut()
                    .zip([bound, lower, upper])
                {
                    *w = w.max(x / diagonal);
                }
            }
            let surface = Surface::new(&extraction.simplified.mesh)?;
            let view = labels.for_view(d, Interpolation::Nearest)?;
            for ((p, &label), &on) in mesh.positions().iter().zip(&view).zip(&used) {
                // A vertex no triangle uses is no point of the surface (the scans have
                // some).
                if !on {
                    continue;
                }
                let distance = surface.closest(*p)?.distance / diagonal;
                let slot = if label <= 2.0 { 6 } else { 7 };
                worst[slot] = worst[slot].max(distance);
            }
        }
        eprintln!(
            "{file}, e = {e}: contour region bound {:.3e}, measured {:.3e}–{:.3e}; elsewhere bound {:.3e}, measured {:.3e}–{:.3e}; from the original's vertices {:.3e} and {:.3e} (of the diagonal)",
            worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst[6], worst[7]
        );
        let mut row = vec![file.to_owned(), e.to_string(), directions.len().to_string()];
        row.extend(worst.iter().map(|w| format!("{w:.4e}")));
        rows.push(row);
    }
    Ok(rows)
}

/// The extraction's triangles in (or out of) the contour region, as a mesh; `None` when
/// there are none.
fn region(extraction: &Extraction, contour: bool) -> Result<Option<TriMesh>> {
    let mesh = &extraction.simplified.mesh;
    let triangles: Vec<[u32; 3]> = mesh
        .triangles()
        .iter()
        .zip(&extraction.in_contour)
        .filter(|&(_, &c)| c == contour)
        .map(|(&t, _)| t)
        .collect();
    if triangles.is_empty() {
        return Ok(None);
    }
    Ok(Some(TriMesh::new(mesh.positions().to_vec(), triangles)?))
}

/// `count` random directions from `seed`, none within 2° of a camera of `views`.
fn between_cameras(views: &ViewSet, count: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
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
                    // Not a camera: at least 2° from every one. Invariant: `d` is a unit
                    // vector, a valid direction.
                    let nearest = views.nearest(d).expect("a unit direction");
                    if views.direction(nearest).dot(d) < 2f64.to_radians().cos() {
                        break d;
                    }
                }
            }
        })
        .collect()
}

/// The pixel-error chart: one panel per mesh and view kind.
fn chart(out: &Path, panels_data: &[(String, Vec<Series>)]) -> Result<()> {
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
