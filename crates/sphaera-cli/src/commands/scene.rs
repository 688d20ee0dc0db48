//! `sphaera scene`: per-instance level of detail and budgeted collision for a scene.

use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use serde::Serialize;
use sphaera::mesh::geometry::Similarity;
use sphaera::mesh::{DVec3, TriMesh};
use sphaera::scene::{
    Budget, Camera, CollisionSummary, DetailReport, LoadedScene, ModelOptions, ObjectModel, Scene,
    SceneDescription, SilhouetteDetailOptions, SilhouetteReport, Tolerance,
};
use sphaera::spheretree::SphereTreeOptions;

use crate::{
    cli::SceneArgs,
    input::{EMBEDDED_NAME, read_mesh},
    output::{print_report, thousands, yes_no},
    progress,
};

/// Instances of the demo scene.
const DEMO_INSTANCES: usize = 8;

/// Everything `sphaera scene` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    /// The scene file, or `demo: 8 embedded bunnies`.
    scene: String,
    /// Each model built (one per mesh).
    models: Vec<ModelReport>,
    /// The camera used (`null` without one).
    camera: Option<CameraReport>,
    /// The levels chosen per instance, with their certified errors and the totals.
    detail: DetailReport,
    /// With a camera: meshes whose outlines meet the tolerance and whose interiors meet
    /// `--silhouette` times it, with their certified errors per region.
    silhouette: Option<SilhouetteReport>,
    /// The collision budget: `unlimited`, `cost N` or `time N ms`.
    budget: String,
    /// What the collision query found.
    collision: CollisionSummary,
    /// The pairs of instances in contact.
    contacts: Vec<PairReport>,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct ModelReport {
    name: String,
    triangles: usize,
    /// The bounding-box diagonal (model units).
    diagonal: f64,
    /// The worst certified error of each cut of the base sphere-tree, root first (model
    /// units).
    tree_errors: Vec<f64>,
    /// Spheres per cut of the base sphere-tree.
    tree_spheres: Vec<usize>,
    /// Every sphere-tree the model has, in build order: the base tree, then the trees
    /// built to a tolerance.
    trees: Vec<TreeReport>,
    /// The mesh ladder, coarsest first: triangles and certified error (model units).
    mesh_levels: Vec<(usize, f64)>,
}

#[derive(Debug, Serialize)]
struct TreeReport {
    /// The tolerance it was built to (model units); `null` for the base tree.
    tolerance: Option<f64>,
    /// Its levels, the root's included.
    levels: usize,
    /// Its leaves.
    leaves: usize,
    /// The worst certified error of its leaves (model units).
    worst_error: f64,
    /// The seconds its construction took.
    build_seconds: f64,
}

#[derive(Debug, Serialize)]
struct CameraReport {
    eye: [f64; 3],
    forward: [f64; 3],
    fov_y_degrees: f64,
    width: u32,
    height: u32,
}

#[derive(Debug, Serialize)]
struct PairReport {
    a: String,
    b: String,
    level: usize,
    completed: bool,
    contacts: usize,
    /// The instances are at most this far apart (as solids).
    separation_bound: Option<f64>,
    /// Every contact is within this of the true contact region.
    max_error_bound: Option<f64>,
}

#[derive(Debug, Serialize)]
struct Seconds {
    /// Reading the meshes and building their models (base trees and hierarchies).
    build: f64,
    /// Choosing detail, building the sphere-trees the tolerance needs included
    /// (`detail.tree_seconds`).
    detail: f64,
    silhouette: f64,
    collide: f64,
}

pub fn run(args: &SceneArgs, quiet: bool) -> Result<()> {
    let options = ModelOptions::default()
        .with_tree(
            SphereTreeOptions::default()
                .with_depth(args.depth)
                .with_branch(args.branch)
                .with_samples(args.samples),
        )
        .with_finest_tolerance(args.finest);
    let started = Instant::now();
    let (source, loaded) = match &args.scene {
        Some(path) => (
            path.display().to_string(),
            load_file(path, &options, quiet)?,
        ),
        None => (
            format!("demo: {DEMO_INSTANCES} instances of {EMBEDDED_NAME}"),
            demo(&options, quiet)?,
        ),
    };
    let build_seconds = started.elapsed().as_secs_f64();
    let LoadedScene {
        scene,
        camera,
        models,
    } = loaded;
    let camera = match args.camera {
        Some(c) => Some(
            Camera::perspective(
                DVec3::new(c[0], c[1], c[2]),
                DVec3::new(c[3], c[4], c[5]),
                args.fov,
                args.image.0,
                args.image.1,
            )
            .context("--camera")?,
        ),
        None => camera,
    };
    let tolerance = args.tolerance.unwrap_or(if camera.is_some() {
        Tolerance::Pixels(2.0)
    } else {
        Tolerance::Relative(0.01)
    });

    let started = Instant::now();
    let spinner = progress::spinner(
        quiet,
        "choosing detail (building the sphere-trees the tolerance needs)",
    );
    let detail = scene.detail(camera.as_ref(), tolerance);
    spinner.finish_and_clear();
    let detail = detail?;
    let detail_seconds = started.elapsed().as_secs_f64();

    let started = Instant::now();
    let silhouette = camera
        .as_ref()
        .map(|camera| {
            let options = SilhouetteDetailOptions {
                interior: args.silhouette,
                ..SilhouetteDetailOptions::default()
            };
            scene
                .silhouette_detail(camera, tolerance, &options)
                .context("--silhouette")
        })
        .transpose()?;
    let silhouette_seconds = started.elapsed().as_secs_f64();

    let (budget, budget_text) = match (args.budget, args.time_budget_ms) {
        (Some(cost), _) => (Budget::cost(cost), format!("cost {cost}")),
        (None, Some(ms)) if ms.is_nan() || ms < 0.0 => {
            anyhow::bail!("--time-budget-ms {ms}: must be a non-negative number of milliseconds")
        }
        (None, Some(ms)) => match Duration::try_from_secs_f64(ms / 1e3) {
            Ok(time) => (Budget::Time(time), format!("time {ms} ms")),
            // Longer than any run could take (infinity included): no limit.
            Err(_) => (Budget::Unlimited, format!("time {ms} ms (no limit)")),
        },
        (None, None) => (Budget::Unlimited, "unlimited".to_owned()),
    };
    let started = Instant::now();
    let collision = scene.collide(&budget)?;
    let collide_seconds = started.elapsed().as_secs_f64();

    let name = |i: usize| {
        scene
            .instances()
            .get(i)
            .map_or_else(String::new, |inst| inst.name.clone())
    };
    let report = Report {
        scene: source,
        models: models.iter().map(|m| model_report(m)).collect(),
        camera: camera.map(|c| CameraReport {
            eye: c.eye().to_array(),
            forward: c.forward().to_array(),
            fov_y_degrees: c.fov_y().to_degrees(),
            width: c.image_size().0,
            height: c.image_size().1,
        }),
        detail,
        silhouette,
        budget: budget_text,
        collision: collision.summary(),
        contacts: collision
            .pairs
            .iter()
            .map(|p| PairReport {
                a: name(p.a),
                b: name(p.b),
                level: p.level,
                completed: p.completed,
                contacts: p.contacts.len(),
                separation_bound: p.separation_bound(),
                max_error_bound: p.max_error_bound(),
            })
            .collect(),
        seconds: Seconds {
            build: build_seconds,
            detail: detail_seconds,
            silhouette: silhouette_seconds,
            collide: collide_seconds,
        },
    };
    print_report(&report, args.print.json)
}

fn model_report(model: &ObjectModel) -> ModelReport {
    let tree = model.tree();
    ModelReport {
        name: model.name().to_owned(),
        triangles: model.mesh().triangle_count(),
        diagonal: model.diagonal(),
        tree_errors: model.tree_errors().to_vec(),
        tree_spheres: (0..tree.level_count())
            .map(|l| tree.cut_at(l).len())
            .collect(),
        trees: model
            .trees()
            .iter()
            .map(|t| TreeReport {
                tolerance: t.tolerance(),
                levels: t.tree().level_count(),
                leaves: t.leaf_count(),
                worst_error: t.worst_error(),
                build_seconds: t.build_seconds(),
            })
            .collect(),
        mesh_levels: model
            .mesh_levels()
            .iter()
            .map(|l| (l.triangles, l.error_bound))
            .collect(),
    }
}

/// Reads a scene file and builds its models, one progress step per model.
fn load_file(path: &Path, options: &ModelOptions, quiet: bool) -> Result<LoadedScene> {
    let description = SceneDescription::read(path)?;
    let used = description.used_meshes().len();
    let bar = progress::bar(
        quiet,
        &format!("building {used} object models (base sphere-tree and hierarchy)"),
        used as u64,
    );
    let loaded = description.build_with(|name, mesh_path| {
        let mesh = sphaera::mesh::io::load(mesh_path)?;
        let model = ObjectModel::build(name, mesh, options);
        bar.inc(1);
        model
    });
    bar.finish_and_clear();
    Ok(loaded?)
}

/// Eight embedded bunnies going away from the camera; the first two touch.
fn demo(options: &ModelOptions, quiet: bool) -> Result<LoadedScene> {
    let input = read_mesh(None, quiet)?;
    let mesh: TriMesh = input.loaded.mesh;
    let size = mesh.bounding_box_diagonal();
    let center = mesh.bounding_box().center();
    let spinner = progress::spinner(quiet, "building the bunny's sphere-tree and hierarchy");
    let model = ObjectModel::build("bunny", mesh, options);
    spinner.finish_and_clear();
    let model = Arc::new(model?);
    let mut scene = Scene::new();
    for i in 0..DEMO_INSTANCES {
        // The second bunny leans into the first; the others recede, each twice as far
        // as the one before (1.5 to 48 sizes away).
        let offset = match i {
            0 => DVec3::ZERO,
            1 => DVec3::new(0.45 * size, 0.0, 0.0),
            _ => DVec3::new(
                0.4 * size * (i % 2) as f64,
                0.0,
                -1.5 * size * 2f64.powi(i as i32 - 2),
            ),
        };
        let pose = Similarity::from_translation(offset - center)?;
        scene.add(format!("bunny-{i}"), Arc::clone(&model), pose);
    }
    // Five sizes back, on a 1280×720 image: two pixels are about 1 % of the nearest
    // bunny's size, a tree the bunny builds in a second or two.
    let camera = Camera::perspective(
        DVec3::new(0.2 * size, 0.3 * size, 5.0 * size),
        DVec3::new(0.2 * size, 0.0, -6.0 * size),
        60.0,
        1280,
        720,
    )?;
    Ok(LoadedScene {
        scene,
        camera: Some(camera),
        models: vec![model],
    })
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![format!("scene           {}", self.scene)];
        let percent = |e: f64, diagonal: f64| {
            if diagonal > 0.0 {
                format!("{:.2} %", 100.0 * e / diagonal)
            } else {
                "-".to_owned()
            }
        };
        for m in &self.models {
            lines.push(format!(
                "model           {}: {} triangles, {} mesh levels, {} sphere-tree{}",
                m.name,
                thousands(m.triangles),
                m.mesh_levels.len(),
                m.trees.len(),
                if m.trees.len() == 1 { "" } else { "s" }
            ));
            for (k, t) in m.trees.iter().enumerate() {
                let what = match t.tolerance {
                    None => "base".to_owned(),
                    Some(tolerance) => format!("to {}", percent(tolerance, m.diagonal)),
                };
                lines.push(format!(
                    "  tree {k}          {what}: {} {} in {} level{}, worst {} of the diagonal, {:.3} s",
                    thousands(t.leaves),
                    if t.leaves == 1 { "leaf" } else { "leaves" },
                    t.levels,
                    if t.levels == 1 { "" } else { "s" },
                    percent(t.worst_error, m.diagonal),
                    t.build_seconds
                ));
            }
        }
        if let Some(c) = &self.camera {
            lines.push(format!(
                "camera          eye ({:.4}, {:.4}, {:.4}), {:.0}° vertical, {}x{} px",
                c.eye[0], c.eye[1], c.eye[2], c.fov_y_degrees, c.width, c.height
            ));
        }
        let d = &self.detail;
        lines.push(format!("tolerance       {}", d.tolerance));
        lines.push(format!(
            "instance          seen  spheres (tree)  {:>9}  mesh triangles (level)  {:>9}",
            format!("error {}", d.unit),
            format!("error {}", d.unit)
        ));
        for i in &d.instances {
            lines.push(format!(
                "  {:<16} {:>4}  {:>7} ({}{}){}  {:>9.3}  {:>9} ({:>2}/{})  {:>9.3}",
                i.name,
                yes_no(i.visible),
                thousands(i.cut.count),
                i.tree.index,
                if i.tree.built { ", built" } else { "" },
                if i.cut.meets { " " } else { "!" },
                i.cut.measured,
                thousands(i.mesh.count),
                i.mesh.level,
                i.mesh.levels - 1,
                i.mesh.measured,
            ));
        }
        let saved = |part: usize, whole: usize| {
            if whole == 0 {
                0.0
            } else {
                100.0 * (1.0 - part as f64 / whole as f64)
            }
        };
        lines.push(format!(
            "spheres         {} in the smallest cuts meeting the tolerance ({} at whole levels; the trees used have {} leaves)",
            thousands(d.cut_spheres),
            thousands(d.spheres),
            thousands(d.full_spheres),
        ));
        lines.push(format!(
            "triangles       {} of {} at full detail ({:.1} % saved)",
            thousands(d.triangles),
            thousands(d.full_triangles),
            saved(d.triangles, d.full_triangles)
        ));
        lines.push(format!(
            "trees built     {} for this tolerance, in {:.3} s",
            d.trees_built, d.tree_seconds
        ));
        let unmet: Vec<_> = d.instances.iter().filter(|i| !i.cut.meets).collect();
        if unmet.is_empty() {
            lines.push(format!(
                "                every instance meets {} (certified)",
                d.tolerance
            ));
        }
        for i in unmet {
            lines.push(format!(
                "                ! {} does not meet the tolerance: {}",
                i.name,
                i.unmet.as_deref().unwrap_or("no reason given")
            ));
        }
        if let Some(s) = &self.silhouette {
            lines.push(format!(
                "silhouettes     outlines within {}, interiors within {}: {} triangles, {} at uniform levels ({:.1} % fewer){}",
                s.tolerance,
                s.interior_tolerance,
                thousands(s.triangles),
                thousands(s.uniform_triangles),
                saved(s.triangles, s.uniform_triangles),
                if s.all_meet { "" } else { " ! not all met" }
            ));
        }
        let c = &self.collision;
        lines.push(format!(
            "collision       budget {}: {} pairs in contact of {} close, {} sphere contacts, level {}{}, {} spheres placed, {} pairs tested",
            self.budget,
            c.pairs_in_contact,
            c.broad_phase_pairs,
            thousands(c.contacts),
            c.level,
            if c.completed { " (leaves)" } else { "" },
            thousands(c.updates as usize),
            thousands(c.tests as usize),
        ));
        for p in &self.contacts {
            lines.push(format!(
                "  {} - {}: {} contacts at level {}, at most {:.3e} apart, contacts within {:.3e}",
                p.a,
                p.b,
                thousands(p.contacts),
                p.level,
                p.separation_bound.unwrap_or(0.0),
                p.max_error_bound.unwrap_or(0.0)
            ));
        }
        lines.push(format!(
            "time            {:.3} s to build the models, {:.3} s to choose detail ({:.3} s of it building trees), {:.6} s for silhouettes, {:.6} s to collide",
            self.seconds.build,
            self.seconds.detail,
            self.detail.tree_seconds,
            self.seconds.silhouette,
            self.seconds.collide
        ));
        lines.join("\n") + "\n"
    }
}
