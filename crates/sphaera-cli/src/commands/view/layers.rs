//! What a page can show beside the mesh and its sphere-tree: other surfaces (the rungs of
//! a simplification, HAL approximations) and fields on the mesh's vertices (the distance
//! to another mesh, silhouette labels).

use std::path::Path;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::hal::HalTree3;
use sphaera::mesh::io::colormap;
use sphaera::mesh::{Length, TriMesh};
use sphaera::silhouette::{Contours, LabelOptions, Labels, ViewSet};
use sphaera::sweep::{Direction, HausdorffDistance, HausdorffOptions, hausdorff_with_progress};

use crate::input::read_mesh;
use crate::progress;

/// Which kind of surface a [`Layer`] is, and so what its bound means.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LayerKind {
    /// A rung of the simplification hierarchy: `bound` is its certified error bound
    /// (every point of either surface lies within it of the other).
    Simplified,
    /// A level of the HAL tree: `bound` is the widest lens its triangles keep.
    HalLevel,
    /// The HAL tree's adaptive approximation for `--hal T`: `bound` as for a level.
    HalTolerance,
}

/// A surface the page can show instead of the input mesh.
#[derive(Debug)]
pub struct Layer {
    pub kind: LayerKind,
    /// What the page's surface menu calls it.
    pub label: String,
    pub mesh: TriMesh,
    pub bound: f64,
}

/// The rungs of the simplification hierarchy from half the input's triangles down to
/// `ratio`, halving each time (`ratio` itself last), each with its certified bound.
pub fn simplification_ladder(mesh: &TriMesh, ratio: f64, quiet: bool) -> Result<Vec<Layer>> {
    let hierarchy = progress::hierarchy(quiet, mesh);
    let hierarchy = hierarchy.context("cannot simplify the mesh")?;
    let mut fractions = Vec::new();
    let mut fraction = 0.5;
    while fraction > ratio {
        fractions.push(fraction);
        fraction /= 2.0;
    }
    fractions.push(ratio);
    let total = mesh.triangle_count() as f64;
    let mut layers: Vec<Layer> = Vec::new();
    for fraction in fractions {
        let target = ((total * fraction).round() as usize).max(1);
        let level = hierarchy.level_by_triangles(target);
        if layers
            .last()
            .is_some_and(|l| l.mesh.triangle_count() == level.mesh.triangle_count())
        {
            continue;
        }
        layers.push(Layer {
            kind: LayerKind::Simplified,
            label: format!("simplified to {}", percent_of(fraction)),
            mesh: level.mesh,
            bound: level.error_bound,
        });
    }
    Ok(layers)
}

/// `0.125` as `12.5 %`, `0.5` as `50 %`.
fn percent_of(fraction: f64) -> String {
    let text = format!("{:.3}", 100.0 * fraction);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    format!("{text} %")
}

/// The HAL tree's levels from the root down to the first with at least half the input's
/// triangles (the finer ones differ little from the input), then the adaptive
/// approximation within `tolerance`.
pub fn hal_layers(mesh: &TriMesh, tolerance: Length, source: &str) -> Result<Vec<Layer>> {
    let tree = HalTree3::build(mesh).with_context(|| format!("no HAL tree for {source}"))?;
    let mut layers: Vec<Layer> = Vec::new();
    let half = mesh.triangle_count().div_ceil(2);
    for level in 0..=tree.depth() {
        let approximation = tree.level(level)?;
        let triangles = approximation.triangle_count();
        if layers
            .last()
            .is_some_and(|l| l.mesh.triangle_count() == triangles)
        {
            continue;
        }
        layers.push(Layer {
            kind: LayerKind::HalLevel,
            label: format!("HAL level {level}"),
            mesh: approximation,
            bound: tree.kept_width(|n| n.level < level),
        });
        if triangles >= half {
            break;
        }
    }
    let width = tolerance.resolve(mesh.bounding_box_diagonal());
    layers.push(Layer {
        kind: LayerKind::HalTolerance,
        label: format!("HAL within {width:.4}"),
        mesh: tree.approximate(width)?,
        bound: tree.kept_width(|n| n.width > width),
    });
    Ok(layers)
}

/// The distance from the mesh to another, certified, for vertex colours.
#[derive(Debug)]
pub struct DistanceField {
    /// The other mesh's file.
    pub other_name: String,
    pub other: TriMesh,
    pub distance: HausdorffDistance,
    /// The tolerance the bounds were refined to.
    pub tolerance: f64,
}

impl DistanceField {
    /// Each input vertex's colour: its certified distance to the other mesh, from blue (0)
    /// to red (the certified upper bound of `h(mesh → other)`).
    pub fn colors(&self) -> Vec<[u8; 3]> {
        let top = self.distance.a_to_b.upper.max(f64::MIN_POSITIVE);
        colormap::scalars_to_colors(&self.distance.a_to_b.vertex_distances, Some((0.0, top)))
    }

    /// Where the distance is largest (on the mesh when `h(mesh → other)` dominates, on the
    /// other mesh else) and its closest point on the other surface.
    pub fn farthest(&self) -> ([f64; 3], [f64; 3]) {
        let side = self.distance.dominating_side();
        (side.farthest.to_array(), side.closest.to_array())
    }

    /// `mesh → other` or `other → mesh`: the direction where the maximum is reached.
    pub fn dominating(&self) -> &'static str {
        match self.distance.dominating {
            Direction::AToB => "mesh_to_other",
            Direction::BToA => "other_to_mesh",
        }
    }
}

/// The symmetric Hausdorff distance between `mesh` and the mesh in `path`, refined until
/// its bounds are 0.01 % of both meshes' diagonal apart, with every vertex's distance
/// certified (they colour the vertices).
pub fn distance_field(mesh: &TriMesh, path: &Path, quiet: bool) -> Result<DistanceField> {
    let input = read_mesh(Some(path), quiet)?;
    let other = input.loaded.mesh;
    if other.triangle_count() == 0 {
        bail!(
            "{}: the mesh has no triangles: no distance to show",
            input.source
        );
    }
    let (a, b) = (mesh.bounding_box(), other.bounding_box());
    let tolerance = 1e-4 * (a.max.max(b.max) - a.min.min(b.min)).length();
    let options = HausdorffOptions::default()
        .with_tolerance(Length::Absolute(tolerance))
        .with_exact_vertex_distances(true)
        .with_symmetric(true);
    let spinner = progress::spinner(
        quiet,
        &format!("measuring the distance to {}", input.source),
    );
    let distance = hausdorff_with_progress(mesh, &other, &options, &|_| {});
    spinner.finish_and_clear();
    let distance = distance.with_context(|| {
        format!(
            "cannot measure the distance between the mesh and {}",
            input.source
        )
    })?;
    Ok(DistanceField {
        other_name: input.source,
        other,
        distance,
        tolerance,
    })
}

/// Silhouette labels of every view, as grey levels for the page.
#[derive(Debug)]
pub struct LabelField {
    /// The views' unit directions from the mesh toward the camera.
    pub directions: Vec<[f64; 3]>,
    /// View-major: view `k`'s grey levels are `grey[k · vertices..][..vertices]`, 0 on the
    /// outline (black) to 255 at `scale` cells or more (white).
    pub grey: Vec<u8>,
    /// The label (in cells of the grid) that is white.
    pub scale: f32,
    pub step_degrees: f64,
    pub resolution: usize,
}

/// The views every 30° (62 cameras), 128² cells, the outline only: the defaults of a
/// scene's object models.
pub const LABEL_STEP_DEGREES: f64 = 30.0;
/// Cells a side of each view's label grid.
pub const LABEL_RESOLUTION: usize = 128;

/// The silhouette labels of `mesh` (its distance, in cells of each view's grid, from the
/// outline that view sees), for every view of the regular set.
pub fn label_field(mesh: &TriMesh, quiet: bool) -> Result<LabelField> {
    let views = ViewSet::regular(LABEL_STEP_DEGREES)?;
    let bar = progress::bar(
        quiet,
        &format!("labelling {} views at {LABEL_RESOLUTION}²", views.len()),
        views.len() as u64,
    );
    let labels = Labels::compute_with_progress(
        mesh,
        &views,
        &LabelOptions::default()
            .with_resolution(LABEL_RESOLUTION)
            .with_contours(Contours::External),
        &|done| bar.set_position(done as u64),
    );
    bar.finish_and_clear();
    let labels = labels.context("cannot compute the silhouette labels")?;
    let mut scale = 1.0_f32;
    for k in 0..views.len() {
        scale = labels.view(k).into_iter().fold(scale, f32::max);
    }
    let mut grey = Vec::with_capacity(views.len() * labels.vertex_count());
    for k in 0..views.len() {
        grey.extend(
            labels
                .view(k)
                .into_iter()
                .map(|v| (255.0 * (v / scale).clamp(0.0, 1.0)).round() as u8),
        );
    }
    Ok(LabelField {
        directions: (0..views.len())
            .map(|k| views.direction(k).normalize().to_array())
            .collect(),
        grey,
        scale,
        step_degrees: LABEL_STEP_DEGREES,
        resolution: LABEL_RESOLUTION,
    })
}
