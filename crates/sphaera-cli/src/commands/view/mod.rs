//! `sphaera view`: one self-contained HTML page showing a mesh, its sphere-tree and
//! whatever else was asked for: the rungs of a simplification, HAL approximations, the
//! distance to another mesh as vertex colours, silhouette labels in grey levels.
//!
//! The page inlines three.js (npm `three` 0.160.1, MIT, vendored in `assets/three/` with
//! its licence; its single-file ES module, given to the page's script through an import
//! map of a `data:` URL, so nothing is fetched at view time) and the page's own script
//! (`assets/view/view.js`, kept readable in its own file). Meshes and spheres go in as
//! base64 little-endian typed arrays.

mod layers;
mod page;
mod robot;
mod tree;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::mesh::Surface;

use crate::{
    cli::ViewArgs,
    input::read_mesh,
    output::{check_target, print_report, thousands},
};
use layers::{DistanceField, LabelField, Layer, LayerKind};

/// Everything `sphaera view` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// The mesh's bounding-box diagonal (the page gives errors as a percentage of it).
    diagonal: f64,
    /// `built` (depth and branch) or the tree file read.
    tree: String,
    /// Per level, its cut (the level's nodes and the leaves above it): spheres and the
    /// certified worst error (`null` when the mesh has no surface to measure against).
    levels: Vec<LevelReport>,
    /// The other surfaces the page can show, in its menu's order: the rungs of
    /// `--simplify` (bound: certified error), then the HAL levels and the approximation of
    /// `--hal` (bound: the widest lens kept).
    surfaces: Vec<SurfaceReport>,
    /// With `--hausdorff`: the certified distance to the other mesh.
    hausdorff: Option<HausdorffReport>,
    /// With `--silhouette`: the label views.
    silhouette: Option<SilhouetteReport>,
    output: String,
    /// The page's size in bytes.
    bytes: usize,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct LevelReport {
    level: usize,
    spheres: usize,
    error_lower: Option<f64>,
    error_upper: Option<f64>,
}

#[derive(Debug, Serialize)]
struct SurfaceReport {
    /// `simplified`, `hal_level` or `hal_tolerance`.
    kind: LayerKind,
    label: String,
    triangles: usize,
    /// `null` for a HAL level with an unbounded lens (the root level of a ball is two
    /// triangles, each lens a half-space).
    bound: Option<f64>,
}

#[derive(Debug, Serialize)]
struct HausdorffReport {
    other: String,
    other_triangles: usize,
    /// Certified: the symmetric Hausdorff distance lies in `[lower, upper]`.
    lower: f64,
    upper: f64,
    tolerance: f64,
    /// `mesh_to_other` or `other_to_mesh`.
    dominating: &'static str,
    /// Where the maximum is reached (marked on the page) and its closest point.
    farthest: [f64; 3],
    closest: [f64; 3],
    /// The largest certified vertex distance from the mesh to the other (the reddest
    /// vertex colour is the upper bound of `h(mesh → other)`).
    largest_vertex_distance: f64,
}

#[derive(Debug, Serialize)]
struct SilhouetteReport {
    views: usize,
    step_degrees: f64,
    resolution: usize,
    /// The label, in cells, drawn white.
    white_at_cells: f32,
}

pub fn run(args: &ViewArgs, quiet: bool) -> Result<()> {
    if let Some(path) = args.mesh.as_deref()
        && path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
    {
        return robot::run(args, path, quiet);
    }
    if !args.joints.is_empty() {
        bail!("--joint applies to a robot's URDF, not to a mesh");
    }
    let started = Instant::now();
    let output: PathBuf = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from("view.html"));
    check_target(&output)?;
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = input.loaded.mesh;
    if mesh.triangle_count() == 0 {
        bail!(
            "{}: the mesh has no triangles: nothing to view",
            input.source
        );
    }
    // A mesh without inside (a sheet, an open patch) is a shell: its tree covers it and
    // its errors are measured from its surface.
    let surface = Surface::solid_or_shell(&mesh).ok();
    let (levels, tree_source) =
        tree::levels(args.tree.as_deref(), surface.as_ref(), &input.source, quiet)?;
    tree::check_tree_fits(&mesh, &levels.spheres, &tree_source)?;
    let evaluations = tree::evaluate(surface.as_ref(), &levels, quiet)?;
    let mut surfaces: Vec<Layer> = Vec::new();
    if let Some(ratio) = args.simplify {
        surfaces.extend(
            layers::simplification_ladder(&mesh, ratio, quiet)
                .with_context(|| format!("cannot simplify {}", input.source))?,
        );
    }
    if let Some(tolerance) = args.hal {
        surfaces.extend(layers::hal_layers(&mesh, tolerance, &input.source)?);
    }
    let distance = match &args.hausdorff {
        Some(path) => Some(layers::distance_field(&mesh, path, quiet)?),
        None => None,
    };
    let labels = if args.silhouette {
        Some(layers::label_field(&mesh, quiet)?)
    } else {
        None
    };
    let page = page::page(&page::Contents {
        name: &input.source,
        mesh: &mesh,
        levels: &levels.spheres,
        evaluations: &evaluations,
        layers: &surfaces,
        distance: distance.as_ref(),
        labels: labels.as_ref(),
    });
    sphaera::mesh::io::write_atomic(&output, |w| std::io::Write::write_all(w, page.as_bytes()))
        .with_context(|| format!("cannot write {}", output.display()))?;
    let report = Report {
        mesh: input.source,
        triangles: mesh.triangle_count(),
        diagonal: mesh.bounding_box_diagonal(),
        tree: tree_source,
        levels: levels
            .spheres
            .iter()
            .zip(&evaluations)
            .enumerate()
            .map(|(level, (spheres, e))| LevelReport {
                level,
                spheres: spheres.len(),
                error_lower: e.map(|e| e.lower),
                error_upper: e.map(|e| e.upper),
            })
            .collect(),
        surfaces: surfaces
            .iter()
            .map(|s| SurfaceReport {
                kind: s.kind,
                label: s.label.clone(),
                triangles: s.mesh.triangle_count(),
                bound: s.bound.is_finite().then_some(s.bound),
            })
            .collect(),
        hausdorff: distance.as_ref().map(hausdorff_report),
        silhouette: labels.as_ref().map(silhouette_report),
        output: output.display().to_string(),
        bytes: page.len(),
        seconds: started.elapsed().as_secs_f64(),
    };
    print_report(&report, args.print.json)
}

fn hausdorff_report(field: &DistanceField) -> HausdorffReport {
    let (farthest, closest) = field.farthest();
    HausdorffReport {
        other: field.other_name.clone(),
        other_triangles: field.other.triangle_count(),
        lower: field.distance.lower,
        upper: field.distance.upper,
        tolerance: field.tolerance,
        dominating: field.dominating(),
        farthest,
        closest,
        largest_vertex_distance: field
            .distance
            .a_to_b
            .vertex_distances
            .iter()
            .copied()
            .fold(0.0, f64::max),
    }
}

fn silhouette_report(field: &LabelField) -> SilhouetteReport {
    SilhouetteReport {
        views: field.directions.len(),
        step_degrees: field.step_degrees,
        resolution: field.resolution,
        white_at_cells: field.scale,
    }
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!(
                "mesh            {} ({} triangles)",
                self.mesh,
                thousands(self.triangles)
            ),
            format!("tree            {}", self.tree),
        ];
        for l in &self.levels {
            lines.push(format!(
                "  level {}       {:>6} spheres, certified worst error {}",
                l.level,
                thousands(l.spheres),
                match (l.error_lower, l.error_upper) {
                    (Some(a), Some(b)) => format!("[{a:.6}, {b:.6}]"),
                    _ => "not measured (no surface)".to_owned(),
                }
            ));
        }
        for s in &self.surfaces {
            lines.push(format!(
                "surface         {}: {} triangles, {} {}",
                s.label,
                thousands(s.triangles),
                match s.kind {
                    LayerKind::Simplified => "certified error bound",
                    LayerKind::HalLevel | LayerKind::HalTolerance => "widest lens",
                },
                s.bound
                    .map_or_else(|| "unbounded".to_owned(), |b| format!("{b:.6}"))
            ));
        }
        if let Some(h) = &self.hausdorff {
            lines.push(format!(
                "hausdorff       H(mesh, {}) in [{:.6}, {:.6}] (certified), largest at ({:.4}, {:.4}, {:.4}) ({})",
                h.other, h.lower, h.upper, h.farthest[0], h.farthest[1], h.farthest[2], h.dominating
            ));
        }
        if let Some(s) = &self.silhouette {
            lines.push(format!(
                "silhouette      labels of {} views every {}°, {}² cells; white at {:.1} cells from the outline",
                s.views, s.step_degrees, s.resolution, s.white_at_cells
            ));
        }
        lines.push(format!(
            "wrote           {} ({} KB, opens offline in any browser)",
            self.output,
            self.bytes / 1024
        ));
        lines.push(format!("time            {:.3} s", self.seconds));
        lines.join("\n") + "\n"
    }
}
