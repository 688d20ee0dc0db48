//! `silhouette_temporal`: the paper's argument for the mean of the 4 nearest views,
//! measured. A camera orbits the mesh 1° per frame for [`FRAMES`] frames (crossing the
//! 15° cameras' boundaries several times); each frame extracts a level of detail with
//! the defaults (`e` = [`ERROR`] of the diagonal) from the nearest camera's labels or
//! from the mean of the 4 nearest. Popping is what changes on screen because the mesh
//! changed rather than the camera: the pixels where this frame's mesh and the previous
//! frame's, both drawn from this frame's camera, differ (`sphaera_tests::silhouette_image`
//! at [`RESOLUTION`]²). The CSV has, per mesh and interpolation, the mean and largest
//! popping, the mean wrong pixels against the original and the mean triangle count; the
//! chart plots the popping frame by frame (log axes).

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::mesh::{DVec3, TriMesh};
use sphaera::silhouette::{
    ContourTolerance, Interpolation, LabelOptions, Labels, ViewDependent, ViewSet,
};
use sphaera::simplify::{Hierarchy, SimplifyOptions};
use sphaera_tests::silhouette_image::{Frame, render, wrong_pixels};

use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name (`--only silhouette_temporal`).
pub const NAME: &str = "silhouette_temporal";

/// Frames of the orbit, 1° apart.
pub const FRAMES: usize = 360;

/// The allowed error `e`, relative to the diagonal.
pub const ERROR: f64 = 0.01;

/// Pixels a side of the judging images (and cells of the labels).
pub const RESOLUTION: usize = 512;

/// The shared meshes measured.
pub const SHARED: &[&str] = &["bunny_lowres.obj", "spot.obj"];

/// Runs the experiment.
pub fn run(data: &Path, out: &Path) -> Result<()> {
    let views = ViewSet::regular(15.0)?;
    let mut meshes = crate::experiments::load_all_or_skip(data, SHARED)?;
    meshes.push((
        "quadruped (procedural)".to_owned(),
        sphaera_tests::animal::quadruped(),
    ));
    let mut rows = Vec::new();
    let mut panels_data = Vec::new();
    for (name, mesh) in &meshes {
        let labels = Labels::compute(
            mesh,
            &views,
            &LabelOptions::default().with_resolution(RESOLUTION),
        )
        .with_context(|| format!("the labels of {name}"))?;
        let hierarchy = Hierarchy::build(mesh, &SimplifyOptions::default())?;
        let tolerance = ContourTolerance::new(ERROR * mesh.bounding_box_diagonal());
        let mut series = Vec::new();
        for (label, interpolation) in [
            ("nearest camera", Interpolation::Nearest),
            ("mean of 4 nearest", Interpolation::Average(4)),
        ] {
            let mut lod = ViewDependent::new(&hierarchy, &labels)?;
            let mut previous: Option<TriMesh> = None;
            let mut popping = Vec::with_capacity(FRAMES);
            let (mut wrong, mut triangles) = (0, 0);
            for f in 0..FRAMES {
                let direction = orbit(f);
                let extraction = lod.extract(direction, interpolation, tolerance)?;
                let now = extraction.simplified.mesh;
                let frame = Frame::orthographic(mesh, direction);
                let image = render(&now, &frame, RESOLUTION);
                wrong += wrong_pixels(&render(mesh, &frame, RESOLUTION), &image);
                triangles += now.triangle_count();
                if let Some(before) = &previous {
                    popping.push(wrong_pixels(&render(before, &frame, RESOLUTION), &image));
                }
                previous = Some(now);
            }
            let mean = |x: usize, n: usize| x as f64 / n as f64;
            let total: usize = popping.iter().sum();
            let largest = popping.iter().copied().max().unwrap_or(0);
            eprintln!(
                "{name}, {label}: popping {:.1} px a frame (largest {largest}), {:.1} wrong px, {:.0} triangles",
                mean(total, popping.len()),
                mean(wrong, FRAMES),
                mean(triangles, FRAMES)
            );
            rows.push(vec![
                name.clone(),
                label.to_owned(),
                format!("{:.2}", mean(total, popping.len())),
                largest.to_string(),
                format!("{:.2}", mean(wrong, FRAMES)),
                format!("{:.1}", mean(triangles, FRAMES)),
            ]);
            series.push(Series {
                name: label.to_owned(),
                points: popping
                    .iter()
                    .enumerate()
                    .map(|(k, &p)| ((k + 1) as f64, (p as f64).max(0.5)))
                    .collect(),
            });
        }
        panels_data.push((name.clone(), series));
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "interpolation",
            "mean_popping_pixels",
            "largest_popping_pixels",
            "mean_wrong_pixels",
            "mean_triangles",
        ],
        &rows,
    )?;
    let panels: Vec<Panel<'_>> = panels_data
        .iter()
        .map(|(title, series)| Panel {
            spec: ChartSpec {
                title,
                x_label: "frame (1° apart)",
                y_label: "pixels changed by the mesh alone (0 drawn at 0.5)",
            },
            series,
            diagonal: false,
            legend: SeriesLabelPosition::UpperRight,
        })
        .collect();
    log_log_panels(&out.join(format!("{NAME}.svg")), &panels)
}

/// The camera of frame `f`: 1° per frame around a tilted axis, so that it crosses rings
/// and azimuths of the 15° cameras.
fn orbit(f: usize) -> DVec3 {
    let a = (f as f64).to_radians();
    let tilt = 25f64.to_radians();
    DVec3::new(a.cos(), a.sin() * tilt.cos(), a.sin() * tilt.sin() + 0.3).normalize()
}
