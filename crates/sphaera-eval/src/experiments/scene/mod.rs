//! `scene_time_vs_error`: the paper's falling-objects simulation made real in rapier.
//!
//! 200 bodies (the low-resolution bunny, the dragon at its lowest resolution, pybullet's
//! duck and the Panda's second link, 50 of each, every object scaled to a bounding-box
//! diagonal of 1) fall into a box and settle for four simulated seconds (240 steps at
//! 60 Hz, one thread). The same bodies, masses and start poses are simulated with three
//! kinds of colliders:
//!
//! - **Sphaera**: a compound of balls, the sphere-tree level `Scene::detail` chooses for a
//!   tolerance of 10 %, 5 %, 2 %, 1 % and 0.5 % of each object's size, and once for a
//!   tolerance of 2 pixels on a camera looking at the box (each body gets the level its
//!   distance needs: "no more than the scene needs"); and the smallest cut through each
//!   tree meeting 10 %, 5 % and 2 % (`spheretree::cut_for_tolerance`: coarse nodes where
//!   they are tight enough, fine ones only where needed). The default trees (depth 3)
//!   end at about 2 %, so 1 % and 0.5 % take their finest level; depth-4 trees that
//!   reach them have about 3,000 balls per body, which rapier could not step through in
//!   reasonable time or memory (see `docs/benchmarks.md`);
//! - rapier's **trimesh** colliders (the true meshes);
//! - rapier's **convex decomposition** (V-HACD with parry's default parameters).
//!
//! Measured: the mean wall time of a step, and the error where the simulation ends with
//! bodies in contact, on the true meshes (`sphaera::mesh::Surface`: inside test and exact
//! closest points): the deepest penetration of a true mesh into another or below the
//! floor, and the mean gap between true meshes over contacts where they do not touch (the
//! over-approximation the colliders showed). Runs whose colliders equal an earlier run's
//! are not simulated again; they take its figures. Writes `scene_time_vs_error.svg` and
//! `.csv`.

mod physics;

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Result;
use rapier3d_f64::prelude::{Pose, SharedShape};
use sphaera::mesh::DVec3;
use sphaera::mesh::geometry::Similarity;
use sphaera::scene::{Camera, ModelOptions, ObjectModel, Scene, Tolerance};

use self::physics::{BODIES, Errors, Object, STEPS};
use super::load_or_skip;
use crate::chart::{
    ChartSpec, LegendEntry, Marker, Series, Style, StyledPanel, StyledSeries, XAxis, palette,
    titled_panels, write_csv,
};

/// The experiment's name, and its chart's.
pub(super) const NAME: &str = "scene_time_vs_error";

/// The objects, from `shared/data`.
const OBJECTS: [&str; 4] = [
    "bunny_lowres.obj",
    "dragon_vrip_res4.ply",
    "robots/objects/duck.obj",
    "robots/franka_panda/visual/link2.obj",
];

/// Tolerances, as fractions of each object's size.
const TOLERANCES: [f64; 5] = [0.10, 0.05, 0.02, 0.01, 0.005];

/// The camera's tolerance, in pixels.
const CAMERA_PIXELS: f64 = 2.0;

/// One simulation's figures.
#[derive(Clone)]
struct Row {
    method: String,
    /// Colliders per body: spheres, triangles or convex parts (mean).
    parts: f64,
    /// The chosen levels' certified error, mean over bodies, in object sizes (Sphaera).
    certified: Option<f64>,
    build_seconds: f64,
    step_ms: f64,
    errors: Errors,
}

pub(super) fn run(data: &Path, out: &Path) -> Result<()> {
    let mut objects = Vec::new();
    let mut models = Vec::new();
    for file in OBJECTS {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        let object = Object::new(file, &mesh)?;
        let started = Instant::now();
        let model = ObjectModel::build(file, object.mesh.clone(), &ModelOptions::default())?;
        eprintln!(
            "{file}: {} triangles, model built in {:.1} s, tree errors {:?}",
            mesh.triangle_count(),
            started.elapsed().as_secs_f64(),
            model.tree_errors()
        );
        objects.push(object);
        models.push(Arc::new(model));
    }
    if objects.is_empty() {
        eprintln!("{NAME}: no object found, nothing written");
        return Ok(());
    }
    let starts = physics::start_poses(objects.len());
    let mut scene = Scene::new();
    for (i, &(object, pose)) in starts.iter().enumerate() {
        let similarity = Similarity::from_rotation_translation(pose.rotation, pose.translation)?;
        scene.add(format!("body-{i}"), Arc::clone(&models[object]), similarity);
    }

    let mut rows = Vec::new();
    // Runs already simulated, by their colliders, so that a run choosing the same
    // colliders as an earlier one takes its figures.
    let mut simulated: Vec<(String, usize)> = Vec::new();
    let mut runs: Vec<(String, Tolerance, Option<Camera>)> = TOLERANCES
        .iter()
        .map(|&t| {
            (
                format!("sphaera {}%", t * 100.0),
                Tolerance::RelativeToDiagonal(t),
                None,
            )
        })
        .collect();
    let camera = Camera::perspective(
        DVec3::new(0.0, 6.0, 14.0),
        DVec3::new(0.0, 1.0, 0.0),
        50.0,
        1280,
        720,
    )?;
    runs.push((
        format!("sphaera {CAMERA_PIXELS}px"),
        Tolerance::Pixels(CAMERA_PIXELS),
        Some(camera),
    ));
    for (method, tolerance, camera) in runs {
        let started = Instant::now();
        let report = scene.detail(camera.as_ref(), tolerance)?;
        let shapes: Vec<SharedShape> = report
            .instances
            .iter()
            .map(|d| ball_compound(&models[starts[d.instance].0], d))
            .collect();
        let build_seconds = started.elapsed().as_secs_f64();
        let certified = report
            .instances
            .iter()
            .map(|d| d.spheres.error)
            .sum::<f64>()
            / BODIES as f64;
        let levels: Vec<usize> = report.instances.iter().map(|d| d.spheres.level).collect();
        let key = format!("levels {levels:?}");
        let row = Run {
            method: &method,
            parts: report.spheres as f64 / BODIES as f64,
            certified: Some(certified),
            build_seconds,
        };
        rows.push(simulate_once(
            &mut simulated,
            &rows,
            key,
            row,
            &objects,
            &starts,
            shapes,
        )?);
    }
    // The smallest cut through each tree meeting the tolerance: coarser nodes where they
    // are already tight enough, finer ones only where needed.
    for &t in &TOLERANCES[..3] {
        let started = Instant::now();
        let cuts: Vec<_> = models
            .iter()
            .map(|m| sphaera::spheretree::cut_for_tolerance(m.tree(), t * m.diagonal()))
            .collect();
        let per_object: Vec<SharedShape> = models
            .iter()
            .zip(&cuts)
            .map(|(m, cut)| crate::rapier_shapes::ball_compound(&cut.spheres(m.tree())))
            .collect();
        let shapes = starts.iter().map(|&(o, _)| per_object[o].clone()).collect();
        let build_seconds = started.elapsed().as_secs_f64();
        let mean = |f: &dyn Fn(usize) -> f64| {
            starts.iter().map(|&(o, _)| f(o)).sum::<f64>() / BODIES as f64
        };
        let nodes: Vec<&[usize]> = cuts.iter().map(|c| c.nodes.as_slice()).collect();
        let key = format!("cut {nodes:?}");
        let row = Run {
            method: &format!("sphaera cut {}%", t * 100.0),
            parts: mean(&|o| cuts[o].nodes.len() as f64),
            certified: Some(mean(&|o| cuts[o].worst_error / models[o].diagonal())),
            build_seconds,
        };
        rows.push(simulate_once(
            &mut simulated,
            &rows,
            key,
            row,
            &objects,
            &starts,
            shapes,
        )?);
    }
    // rapier's own colliders: the true meshes, and their convex decomposition.
    let started = Instant::now();
    let trimeshes = objects
        .iter()
        .map(|o| SharedShape::trimesh(o.mesh.positions().to_vec(), o.mesh.triangles().to_vec()))
        .collect::<Result<Vec<_>, _>>()?;
    let build = started.elapsed().as_secs_f64();
    let triangles = |o: usize| objects[o].mesh.triangle_count();
    rows.push(per_object_run(
        "rapier trimesh",
        &objects,
        &starts,
        &trimeshes,
        &triangles,
        build,
    )?);
    let started = Instant::now();
    let hulls: Vec<SharedShape> = objects
        .iter()
        .map(|o| SharedShape::convex_decomposition(o.mesh.positions(), o.mesh.triangles()))
        .collect();
    let build = started.elapsed().as_secs_f64();
    let convex_parts = |o: usize| hulls[o].as_compound().map_or(1, |c| c.shapes().len());
    rows.push(per_object_run(
        "rapier convex decomposition",
        &objects,
        &starts,
        &hulls,
        &convex_parts,
        build,
    )?);
    write_outputs(out, &rows)
}

/// The spheres `detail` chose in `model`'s trees (the cut of the tree built for its
/// tolerance) as one compound of balls.
fn ball_compound(model: &ObjectModel, detail: &sphaera::scene::InstanceDetail) -> SharedShape {
    let spheres = model
        .detail_spheres(detail)
        .unwrap_or_else(|| model.tree().level_spheres(model.tree().level_count() - 1));
    crate::rapier_shapes::ball_compound(&spheres)
}

/// A run where every body of an object shares that object's collider; `parts` counts an
/// object's triangles or convex parts.
fn per_object_run(
    method: &str,
    objects: &[Object],
    starts: &[(usize, Pose)],
    per_object: &[SharedShape],
    parts: &dyn Fn(usize) -> usize,
    build_seconds: f64,
) -> Result<Row> {
    let mean_parts = starts.iter().map(|&(o, _)| parts(o) as f64).sum::<f64>() / BODIES as f64;
    let shapes = starts.iter().map(|&(o, _)| per_object[o].clone()).collect();
    let run = Run {
        method,
        parts: mean_parts,
        certified: None,
        build_seconds,
    };
    simulate(run, objects, starts, shapes)
}

/// What a run is, before its simulation.
#[derive(Clone, Copy)]
struct Run<'a> {
    method: &'a str,
    parts: f64,
    certified: Option<f64>,
    build_seconds: f64,
}

/// Simulates `run`, unless a run with the same colliders (`key`) was simulated before, in
/// which case that run's figures are taken under this run's name.
fn simulate_once(
    simulated: &mut Vec<(String, usize)>,
    rows: &[Row],
    key: String,
    run: Run<'_>,
    objects: &[Object],
    starts: &[(usize, Pose)],
    shapes: Vec<SharedShape>,
) -> Result<Row> {
    if let Some(&(_, earlier)) = simulated.iter().find(|(k, _)| *k == key) {
        let mut row = rows[earlier].clone();
        eprintln!(
            "{}: the same colliders as {}, not simulated again",
            run.method, row.method
        );
        run.method.clone_into(&mut row.method);
        row.build_seconds = run.build_seconds;
        return Ok(row);
    }
    simulated.push((key, rows.len()));
    simulate(run, objects, starts, shapes)
}

fn simulate(
    run: Run<'_>,
    objects: &[Object],
    starts: &[(usize, Pose)],
    shapes: Vec<SharedShape>,
) -> Result<Row> {
    let Run {
        method,
        parts,
        certified,
        build_seconds,
    } = run;
    let run = physics::simulate(objects, starts, shapes)?;
    let errors = physics::measure(objects, starts, &run)?;
    eprintln!(
        "{method}: {parts:.0} parts per body, {:.2} ms per step ({:.0} steps per second), \
         {} contacts, penetration at most {:.2} %, mean gap {:.2} % (largest {:.2} %)",
        run.step_ms,
        1e3 / run.step_ms,
        errors.contacts,
        100.0 * errors.max_penetration,
        100.0 * errors.mean_gap,
        100.0 * errors.max_gap
    );
    Ok(Row {
        method: method.to_owned(),
        parts,
        certified,
        build_seconds,
        step_ms: run.step_ms,
        errors,
    })
}

/// One series of the chart: its legend, which rows it holds, its marker.
type Kind<'a> = (&'a str, &'a dyn Fn(&Row) -> bool, Marker);

fn write_outputs(out: &Path, rows: &[Row]) -> Result<()> {
    let header = [
        "method",
        "parts_per_body",
        "certified_error_pct",
        "collider_build_s",
        "ms_per_step",
        "steps_per_second",
        "contacts",
        "max_penetration_pct",
        "mean_gap_pct",
        "max_gap_pct",
    ];
    let lines: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.method.clone(),
                format!("{:.1}", r.parts),
                r.certified
                    .map_or_else(String::new, |c| format!("{:.3}", 100.0 * c)),
                format!("{:.3}", r.build_seconds),
                format!("{:.3}", r.step_ms),
                format!("{:.1}", 1e3 / r.step_ms),
                r.errors.contacts.to_string(),
                format!("{:.3}", 100.0 * r.errors.max_penetration),
                format!("{:.3}", 100.0 * r.errors.mean_gap),
                format!("{:.3}", 100.0 * r.errors.max_gap),
            ]
        })
        .collect();
    write_csv(&out.join(format!("{NAME}.csv")), &header, &lines)?;

    // One series per kind of collider; the Sphaera points labelled by their tolerance.
    let kinds: [Kind<'_>; 4] = [
        (
            "Sphaera tree level",
            &|r: &Row| r.method.starts_with("sphaera") && !r.method.starts_with("sphaera cut"),
            Marker::Circle,
        ),
        (
            "Sphaera tree cut",
            &|r: &Row| r.method.starts_with("sphaera cut"),
            Marker::Square,
        ),
        (
            "rapier trimesh",
            &|r: &Row| r.method == "rapier trimesh",
            Marker::Triangle,
        ),
        (
            "rapier convex parts",
            &|r: &Row| r.method == "rapier convex decomposition",
            Marker::Circle,
        ),
    ];
    let panel_series = |x: &dyn Fn(&Row) -> f64| -> Vec<StyledSeries> {
        kinds
            .iter()
            .enumerate()
            .map(|(k, (name, keep, marker))| {
                // One point per distinct figure: runs that took an earlier run's figures
                // share its point, labelled with every run's name.
                let mut points: Vec<((f64, f64), String)> = Vec::new();
                for r in rows.iter().filter(|r| keep(r)) {
                    // A zero error is drawn at 10⁻³ % so it shows on the log axis.
                    let point = ((100.0 * x(r)).max(1e-3), r.step_ms);
                    let label = if r.method.starts_with("rapier") {
                        String::new()
                    } else {
                        r.method
                            .trim_start_matches("sphaera ")
                            .trim_start_matches("cut ")
                            .to_owned()
                    };
                    match points.iter_mut().find(|(p, _)| *p == point) {
                        Some((_, shared)) => {
                            shared.push_str(", ");
                            shared.push_str(&label);
                        }
                        None => points.push((point, label)),
                    }
                }
                let mut series = Series::new(name);
                series.points = points.iter().map(|&(p, _)| p).collect();
                StyledSeries::new(
                    series,
                    Style {
                        color: palette(k),
                        marker: *marker,
                        filled: true,
                        line: false,
                    },
                )
                .with_labels(points.into_iter().map(|(_, l)| l).collect())
            })
            .collect()
    };
    let gap = panel_series(&|r: &Row| r.errors.mean_gap);
    let penetration = panel_series(&|r: &Row| r.errors.max_penetration);
    let panels = [
        StyledPanel {
            spec: ChartSpec {
                title: "Over-approximation: mean gap between true meshes in contact",
                x_label: "mean gap (% of the object's size)",
                y_label: "ms per step (200 bodies, one thread)",
            },
            x_axis: XAxis::Log,
            series: &gap,
            notes: &[],
        },
        StyledPanel {
            spec: ChartSpec {
                title: "Penetration of true meshes",
                x_label: "deepest penetration (% of the object's size; 0 drawn at 0.001)",
                y_label: "ms per step (200 bodies, one thread)",
            },
            x_axis: XAxis::Log,
            series: &penetration,
            notes: &[],
        },
    ];
    let legend: Vec<LegendEntry> = kinds
        .iter()
        .enumerate()
        .map(|(k, (name, _, marker))| LegendEntry {
            label: (*name).to_owned(),
            style: Style {
                color: palette(k),
                marker: *marker,
                filled: true,
                line: false,
            },
        })
        .collect();
    titled_panels(
        &out.join(format!("{NAME}.svg")),
        &format!(
            "{BODIES} bodies falling into a box, {STEPS} steps in rapier: time against error on the true meshes"
        ),
        &panels,
        &legend,
    )
}
