//! Silhouette-aware detail (feature `silhouette`): for every instance, a mesh whose
//! outline, as the camera sees it, meets the tolerance while its interior may be coarser
//! (Mata, Pastor and Rodríguez, section 3.3, on the certified hierarchy).

use serde::Serialize;
use sphaera_silhouette::{ContourTolerance, Interpolation, ViewDependent};

use crate::detail::{allowed_error, choose_level, measure};
use crate::{Camera, Instance, Scene, SceneError, Tolerance};

/// What [`Scene::silhouette_detail`] asks for beyond the tolerance.
///
/// # Examples
///
/// ```
/// use sphaera_scene::SilhouetteDetailOptions;
///
/// let options = SilhouetteDetailOptions::default();
/// assert_eq!((options.interior, options.threshold_cells, options.check_outline), (4.0, 2.0, true));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SilhouetteDetailOptions {
    /// How many times the tolerance the interior may be off (at least 1; default 4). An
    /// error inside the outline moves shading, not the outline, and shows far less.
    pub interior: f64,
    /// The contour region: triangles with a corner at most this many label cells from
    /// the silhouette (default 2; the cells are those of
    /// [`SilhouetteOptions::resolution`](crate::SilhouetteOptions::resolution)).
    pub threshold_cells: f32,
    /// With a tolerance in pixels, draw each instance and its chosen mesh at the camera's
    /// pixels and measure how far the outline moved ([`SilhouetteChoice::outline_pixels`];
    /// default `true`). It costs two rasterizations and a distance transform over the
    /// instance's image per instance.
    pub check_outline: bool,
}

impl Default for SilhouetteDetailOptions {
    fn default() -> Self {
        Self {
            interior: 4.0,
            threshold_cells: 2.0,
            check_outline: true,
        }
    }
}

impl SilhouetteDetailOptions {
    /// With the interior allowed `interior` times the tolerance.
    #[must_use]
    pub fn with_interior(mut self, interior: f64) -> Self {
        self.interior = interior;
        self
    }

    /// With the contour region `cells` label cells wide.
    #[must_use]
    pub fn with_threshold_cells(mut self, cells: f32) -> Self {
        self.threshold_cells = cells;
        self
    }

    /// With the outline drawn and measured, or not ([`SilhouetteDetailOptions::check_outline`]).
    #[must_use]
    pub fn with_check_outline(mut self, check: bool) -> Self {
        self.check_outline = check;
        self
    }
}

/// The silhouette-aware mesh chosen for one instance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SilhouetteChoice {
    /// Its index in the scene.
    pub instance: usize,
    /// Its name.
    pub name: String,
    /// Its model's name.
    pub model: String,
    /// Whether the camera sees its mesh's bounding sphere.
    pub visible: bool,
    /// The mesh's triangles.
    pub triangles: usize,
    /// Of which in the contour region.
    pub contour_triangles: usize,
    /// The certified error of the contour region, in the scene's units.
    pub contour_error: f64,
    /// The same in the tolerance's unit (0 when the camera cannot see it).
    pub contour_measured: f64,
    /// The certified error of the rest, in the scene's units.
    pub interior_error: f64,
    /// The same in the tolerance's unit.
    pub interior_measured: f64,
    /// With a tolerance in pixels (and [`SilhouetteDetailOptions::check_outline`]): the
    /// most pixels the chosen mesh's outline lies from the instance's own, both drawn at
    /// the camera's pixels (so in whole pixels, within one of the true distance), over the
    /// pixels within the frame's half-diagonal cone (what is drawn beyond the frame does
    /// not count: 0 for an instance beside it); `None` otherwise, or when part of the
    /// instance is at or behind the camera. This checks the
    /// claim of the contour region's certified error, which bounds only the triangles the
    /// labels put in the region.
    pub outline_pixels: Option<f64>,
    /// Whether the contour region meets the tolerance and the rest its multiple.
    pub meets: bool,
    /// The triangles of the coarsest mesh level meeting the tolerance everywhere (what
    /// [`Scene::detail`] chooses), for comparison.
    pub uniform_triangles: usize,
}

/// What [`Scene::silhouette_detail`] chose, with the totals against uniform and full
/// detail.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SilhouetteReport {
    /// The tolerance, as text.
    pub tolerance: String,
    /// The unit of the measured errors: `world`, `relative` or `px`.
    pub unit: &'static str,
    /// The interior's multiple of the tolerance.
    pub interior: f64,
    /// The interior's tolerance, as text.
    pub interior_tolerance: String,
    /// One entry per instance, in scene order.
    pub instances: Vec<SilhouetteChoice>,
    /// Triangles of the silhouette-aware meshes.
    pub triangles: usize,
    /// Triangles of the uniform levels meeting the tolerance everywhere.
    pub uniform_triangles: usize,
    /// Triangles of every instance's input mesh.
    pub full_triangles: usize,
    /// Whether every choice meets its tolerances.
    pub all_meet: bool,
}

impl Scene {
    /// For each instance, the coarsest mesh whose **outline** as `camera` sees it meets
    /// `tolerance`, while the rest may be off by `options.interior` times as much: the
    /// view-dependent extraction of Mata, Pastor and Rodríguez from the instance's
    /// silhouette labels ([`ObjectModel::silhouette_labels`](crate::ObjectModel::silhouette_labels)),
    /// refined from the certified hierarchy, so both regions' errors are certified.
    ///
    /// The contour region is the labels' estimate of where the outline runs: labels are
    /// computed for orthographic views and interpolated for the direction from the
    /// instance to the camera, so for a camera close to an object (strong perspective)
    /// the outline may run a little outside it. The region's error bound holds for the
    /// triangles in it whatever the labels.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_scene::{Camera, DVec3, ModelOptions, ObjectModel, Scene, SilhouetteDetailOptions, Tolerance};
    /// use sphaera_spheretree::SphereTreeOptions;
    ///
    /// let tree = SphereTreeOptions::default().with_depth(1).with_branch(4).with_samples(400)
    ///     .with_initial_spheres(40).with_min_spheres_per_node(20);
    /// let mesh = sphaera_mesh::shapes::torus(1.0, 0.3, 48)?;
    /// let model = Arc::new(ObjectModel::build("torus", mesh, &ModelOptions::default().with_tree(tree))?);
    /// let mut scene = Scene::new();
    /// scene.add("torus", model, Similarity::IDENTITY);
    /// let camera = Camera::perspective(DVec3::new(0.0, -4.0, 3.0), DVec3::ZERO, 50.0, 1280, 720)?;
    /// let report = scene.silhouette_detail(&camera, Tolerance::Pixels(1.0), &SilhouetteDetailOptions::default())?;
    /// let torus = &report.instances[0];
    /// // The outline within a pixel, the interior within four, both certified; drawn at
    /// // the camera's pixels, the outline moved at most a pixel (and one of sampling).
    /// assert!(torus.meets && torus.contour_measured <= 1.0 && torus.interior_measured <= 4.0);
    /// assert!(torus.outline_pixels.is_some_and(|moved| moved <= 2.0));
    /// assert!(report.triangles < report.uniform_triangles);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidTolerance`] for a bad tolerance or an interior multiple below
    /// 1 (or not finite), a NaN threshold; [`SceneError::NoSilhouetteLabels`] for a model
    /// whose labels could not be computed.
    ///
    /// # Performance
    ///
    /// One extraction per instance (a scan of its hierarchy, then the contour region), in
    /// parallel with the `parallel` feature. The time for 200 instances is in the section
    /// *Collision over a whole scene, and the level choice (criterion, same run)* of
    /// `docs/benchmarks.md` in the repository (`cargo bench -p sphaera-eval --bench
    /// scene_vs_rapier -- scene_detail_200`).
    pub fn silhouette_detail(
        &self,
        camera: &Camera,
        tolerance: Tolerance,
        options: &SilhouetteDetailOptions,
    ) -> Result<SilhouetteReport, SceneError> {
        let tolerance = tolerance.validated()?;
        if !(options.interior.is_finite() && options.interior >= 1.0) {
            return Err(SceneError::InvalidOption {
                name: "interior",
                value: options.interior,
                requirement: "a finite multiple of the tolerance of at least 1",
            });
        }
        if options.threshold_cells.is_nan() {
            return Err(SceneError::InvalidOption {
                name: "threshold_cells",
                value: f64::from(options.threshold_cells),
                requirement: "a number of label cells",
            });
        }
        for instance in self.instances() {
            if let Err(e) = instance.model.silhouette_labels() {
                return Err(SceneError::NoSilhouetteLabels {
                    model: instance.model.name().to_owned(),
                    reason: e.to_string(),
                });
            }
        }
        let choose = |(index, instance): (usize, &Instance)| {
            choose_silhouette(index, instance, camera, tolerance, options)
        };
        #[cfg(feature = "parallel")]
        let instances: Result<Vec<SilhouetteChoice>, SceneError> = {
            use rayon::prelude::*;
            self.instances()
                .par_iter()
                .enumerate()
                .map(choose)
                .collect()
        };
        #[cfg(not(feature = "parallel"))]
        let instances: Result<Vec<SilhouetteChoice>, SceneError> =
            self.instances().iter().enumerate().map(choose).collect();
        let instances = instances?;
        Ok(SilhouetteReport {
            tolerance: tolerance.to_string(),
            unit: tolerance.unit(),
            interior: options.interior,
            interior_tolerance: tolerance.scaled(options.interior).to_string(),
            triangles: instances.iter().map(|c| c.triangles).sum(),
            uniform_triangles: instances.iter().map(|c| c.uniform_triangles).sum(),
            full_triangles: self
                .instances()
                .iter()
                .map(|i| i.model.mesh().triangle_count())
                .sum(),
            all_meet: instances.iter().all(|c| c.meets),
            instances,
        })
    }
}

fn choose_silhouette(
    index: usize,
    instance: &Instance,
    camera: &Camera,
    tolerance: Tolerance,
    options: &SilhouetteDetailOptions,
) -> Result<SilhouetteChoice, SceneError> {
    let model = &instance.model;
    let labels = model
        .silhouette_labels()
        .map_err(|e| SceneError::NoSilhouetteLabels {
            model: model.name().to_owned(),
            reason: e.to_string(),
        })?;
    let scale = instance.pose.scale();
    let largest = model.mesh_errors().first().copied().unwrap_or(0.0);
    // The contour's allowance and the interior's (the projected error grows faster than
    // the error, so the interior's is found as its own tolerance); `error · factor` must
    // not round above the contour's.
    let contour = allowed_error(instance, Some(camera), tolerance, largest);
    let error = allowed_error(
        instance,
        Some(camera),
        tolerance.scaled(options.interior),
        largest,
    )
    .max(contour);
    let mut factor = if error > 0.0 { contour / error } else { 1.0 };
    while error * factor > contour {
        factor = factor.next_down();
    }
    let direction = view_direction(instance, camera);
    // The widened region (the default): the paper's corner rule lets coarse triangles
    // that stand for outline points keep the interior's error, and the outline drifts
    // to the edge of the tolerance and past it.
    let mut lod = ViewDependent::new(model.hierarchy(), labels)?;
    // The nearest camera's labels: the mean of the 4 nearest pops more along an orbit and
    // keeps the outline worse (`silhouette_temporal` in `docs/benchmarks.md`).
    let extraction = lod.extract(
        direction,
        Interpolation::Nearest,
        // The allowance comes from the scene's camera, not the labels' cells.
        ContourTolerance {
            error,
            factor,
            threshold: options.threshold_cells,
            cells: f64::INFINITY,
        },
    )?;
    let measured = |e: f64| measure(instance, Some(camera), tolerance, e * scale).unwrap_or(0.0);
    let contour_measured = measured(extraction.contour_error);
    let interior_measured = measured(extraction.other_error);
    let uniform = choose_level(
        instance,
        Some(camera),
        tolerance,
        model.mesh_errors(),
        &|l| model.mesh_levels().get(l).map_or(0, |m| m.triangles),
    );
    Ok(SilhouetteChoice {
        instance: index,
        name: instance.name.clone(),
        model: model.name().to_owned(),
        visible: camera
            .pixels_per_unit(&instance.bounding_sphere())
            .is_some(),
        triangles: extraction.simplified.mesh.triangle_count(),
        contour_triangles: extraction.contour_triangles,
        contour_error: extraction.contour_error * scale,
        contour_measured,
        interior_error: extraction.other_error * scale,
        interior_measured,
        outline_pixels: match tolerance {
            Tolerance::Pixels(_) if options.check_outline => {
                outline_moved(instance, camera, &extraction.simplified.mesh)?
            }
            _ => None,
        },
        meets: contour_measured <= tolerance.value()
            && interior_measured <= tolerance.value() * options.interior,
        uniform_triangles: uniform.count,
    })
}

/// The most pixels the outline of `chosen` (the instance's mesh simplified, in the
/// model's frame) lies from the instance's own outline on `camera`'s image, both drawn
/// at the camera's pixels (whole pixels: a pixel either side of a true sub-pixel move),
/// over the pixels within the frame's half-diagonal cone (`Some(0.0)` for an instance
/// beside the frame), or `None` when some vertex is at or behind the eye plane.
fn outline_moved(
    instance: &Instance,
    camera: &Camera,
    chosen: &sphaera_mesh::TriMesh,
) -> Result<Option<f64>, SceneError> {
    let pose = instance.pose.affine();
    let original = instance.model.mesh();
    let project = |mesh: &sphaera_mesh::TriMesh| -> Option<Vec<glam::DVec2>> {
        mesh.positions()
            .iter()
            .map(|&p| camera.project(pose.transform_point3(p)).map(|(x, _)| x))
            .collect()
    };
    let (Some(ours), Some(theirs)) = (project(original), project(chosen)) else {
        return Ok(None);
    };
    // A square window of whole pixels around the original's image, a margin of 2.
    let (lo, hi) = ours.iter().fold(
        (
            glam::DVec2::splat(f64::INFINITY),
            glam::DVec2::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let lo = (lo - 2.0).floor();
    let side = ((hi - lo).max_element() + 2.0).ceil();
    // Larger than the cap, cells of several pixels each.
    let cells = side.min(sphaera_silhouette::MAX_RESOLUTION as f64);
    let pixels_per_cell = side / cells;
    let to_window = |points: Vec<glam::DVec2>| -> Vec<glam::DVec2> {
        points
            .into_iter()
            .map(|p| (p - lo) / side * 2.0 - glam::DVec2::ONE)
            .collect()
    };
    let resolution = cells as usize;
    let draw = |points: Vec<glam::DVec2>, mesh: &sphaera_mesh::TriMesh| {
        sphaera_silhouette::coverage_of_projection(&to_window(points), mesh.triangles(), resolution)
    };
    let (a, b) = (draw(ours, original)?, draw(theirs, chosen)?);
    // Only what the camera shows counts: cells whose centre lies within the frame's
    // half-diagonal angle of the axis (the cone the measures bound; an instance beside
    // the frame shows no outline to move).
    let frame = camera.focal_pixels() * camera.half_diagonal_angle().tan();
    let seen: Vec<bool> = (0..resolution * resolution)
        .map(|cell| {
            let at = glam::DVec2::new((cell % resolution) as f64, (cell / resolution) as f64);
            (lo + (at + 0.5) * pixels_per_cell).length() <= frame
        })
        .collect();
    Ok(
        sphaera_silhouette::contour_displacement_seen(&a, &b, resolution, &seen)
            .map(|d| d * pixels_per_cell),
    )
}

/// The direction from the instance towards the camera, in the model's frame (a mirror
/// pose mirrors it too); the camera's backward axis when the eye is at the centre.
fn view_direction(instance: &Instance, camera: &Camera) -> glam::DVec3 {
    let to_model = instance.pose.affine().inverse();
    let towards = camera.eye() - instance.bounding_sphere().center;
    let towards = if towards.length_squared() > 0.0 {
        towards
    } else {
        -camera.forward()
    };
    let direction = to_model.transform_vector3(towards);
    if direction.length_squared() > 0.0 && direction.is_finite() {
        direction.normalize()
    } else {
        glam::DVec3::Z
    }
}
