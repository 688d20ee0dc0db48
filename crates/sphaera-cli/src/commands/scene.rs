//! `sphaera scene`: per-instance level of detail and budgeted collision for a scene.

use std::path::{Path, PathBuf};
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
    let defaults = ModelOptions::default();
    let tolerance_tree = defaults.tolerance_tree.clone().with_effort(args.effort);
    let options = defaults
        .with_tree(
            SphereTreeOptions::default()
                .with_depth(args.depth)
                .with_branch(args.branch)
                .with_samples(args.samples),
        )
        .with_tolerance_tree(tolerance_tree)
        .with_finest_tolerance(args.finest);
    let started = Instant::now();
    let is_scene_file = |p: &Path| {
        p.extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
    };
    let (source, loaded) = match args.inputs.as_slice() {
        [] => (
            format!("demo: {DEMO_INSTANCES} instances of {EMBEDDED_NAME}"),
            demo(&options, quiet)?,
        ),
        [path] if is_scene_file(path) => (
            path.display().to_string(),
            load_file(path, &options, quiet)?,
        ),
        paths => {
            if let Some(json) = paths.iter().find(|p| is_scene_file(p)) {
                anyhow::bail!(
                    "{}: a scene file is given alone, not with other files (give a scene file, or mesh files)",
                    json.display()
                );
            }
            (
                format!(
                    "{} mesh file{} side by side",
                    paths.len(),
                    if paths.len() == 1 { "" } else { "s" }
                ),
                load_meshes(paths, &options, quiet)?,
            )
        }
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
        Tolerance::RelativeToDiagonal(0.01)
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
            let options = SilhouetteDetailOptions::default().with_interior(args.silhouette);
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
    let description = SceneDescription::read_with(path, &crate::input::file_policy())?;
    let used = description.used_meshes().len();
    let bar = progress::bar(
        quiet,
        &format!("building {used} object models (base sphere-tree and hierarchy)"),
        used as u64,
    );
    let policy = description.file_policy();
    let loaded = description.build_with(|name, mesh_path| {
        let mesh = sphaera::io::read_with(mesh_path, policy)?.mesh;
        let model = ObjectModel::build(name, mesh, options);
        bar.inc(1);
        model
    });
    bar.finish_and_clear();
    Ok(loaded?)
}

/// Reads mesh files and builds their models (in parallel), one instance each, side by
/// side along x with a quarter of the largest diagonal between their bounding boxes.
fn load_meshes(paths: &[PathBuf], options: &ModelOptions, quiet: bool) -> Result<LoadedScene> {
    let mut names: Vec<String> = Vec::with_capacity(paths.len());
    for path in paths {
        let stem = path
            .file_stem()
            .map_or_else(|| "mesh".to_owned(), |s| s.to_string_lossy().into_owned());
        let mut name = stem.clone();
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{stem}-{k}");
            k += 1;
        }
        names.push(name);
    }
    let bar = progress::bar(
        quiet,
        &format!(
            "building {} object models (base sphere-tree and hierarchy)",
            paths.len()
        ),
        paths.len() as u64,
    );
    let built: Vec<Result<ObjectModel>> = std::thread::scope(|scope| {
        let handles: Vec<_> = paths
            .iter()
            .zip(&names)
            .map(|(path, name)| {
                let bar = &bar;
                scope.spawn(move || {
                    let mesh = sphaera::mesh::io::load(path)
                        .with_context(|| format!("reading {}", path.display()))?;
                    let model = ObjectModel::build(name.as_str(), mesh, options)
                        .with_context(|| format!("building the model of {}", path.display()));
                    bar.inc(1);
                    model
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(anyhow::anyhow!("a model's construction panicked")))
            })
            .collect()
    });
    bar.finish_and_clear();
    let models: Vec<Arc<ObjectModel>> = built
        .into_iter()
        .map(|m| m.map(Arc::new))
        .collect::<Result<_>>()?;
    let gap = 0.25 * models.iter().map(|m| m.diagonal()).fold(0.0_f64, f64::max);
    let mut scene = Scene::new();
    let mut x = 0.0;
    for model in &models {
        let bounds = model.mesh().bounding_box();
        let half = 0.5 * (bounds.max.x - bounds.min.x);
        let center = bounds.center();
        let pose = Similarity::from_translation(DVec3::new(x + half, 0.0, 0.0) - center)?;
        scene.add(model.name(), Arc::clone(model), pose);
        x += 2.0 * half + gap;
    }
    Ok(LoadedScene {
        scene,
        camera: None,
        models,
    })
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
            "instance          seen  spheres (level, tree)  {:>9}  smallest cut  mesh triangles (level)  {:>9}",
            format!("error {}", d.unit),
            format!("error {}", d.unit)
        ));
        for i in &d.instances {
            lines.push(format!(
                "  {:<16} {:>4}  {:>7} ({:>2}/{}, {}{})  {:>9.4}  {:>12}  {:>9} ({:>2}/{})  {:>9.4}",
                i.name,
                yes_no(i.visible),
                thousands(i.spheres.count),
                i.spheres.level,
                i.spheres.levels.saturating_sub(1),
                i.tree.index,
                if i.tree.built { ", built" } else { "" },
                i.spheres.measured,
                thousands(i.cut.count),
                thousands(i.mesh.count),
                i.mesh.level,
                i.mesh.levels.saturating_sub(1),
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
            "spheres         {} of {} at full detail (the models' finest trees' leaves; {:.1} % saved); {} in the smallest cuts of mixed levels",
            thousands(d.spheres),
            thousands(d.full_spheres),
            d.spheres_saved_percent,
            thousands(d.cut_spheres),
        ));
        lines.push(format!(
            "triangles       {} of {} at full detail ({:.1} % saved)",
            thousands(d.triangles),
            thousands(d.full_triangles),
            d.triangles_saved_percent
        ));
        lines.push(format!(
            "trees built     {} for this tolerance, in {:.3} s",
            d.trees_built, d.tree_seconds
        ));
        lines.push(format!(
            "                every instance meets {} (certified)",
            d.tolerance
        ));
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
            // The outline drawn at the camera's pixels, the claim checked.
            let moved = s
                .instances
                .iter()
                .filter_map(|c| c.outline_pixels)
                .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
            if let Some(moved) = moved {
                let drawn = s
                    .instances
                    .iter()
                    .filter(|c| c.outline_pixels.is_some())
                    .count();
                lines.push(format!(
                    "                drawn at the camera's pixels, the outlines of {drawn} instances moved at most {moved:.1} px (whole pixels)"
                ));
            }
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
