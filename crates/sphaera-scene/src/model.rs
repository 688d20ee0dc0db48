//! An object built once per mesh: its sphere-tree and its simplification hierarchy, with
//! the certified error of every level.

use sphaera_mesh::geometry::{minimum_enclosing_ball, minimum_enclosing_ball_of_balls};
use sphaera_mesh::{Sphere, Surface, TriMesh};
use sphaera_simplify::{Hierarchy, Simplified, SimplifyOptions};
use sphaera_spheretree::select::level_worst_errors;
use sphaera_spheretree::{SphereTree, SphereTreeOptions};

use crate::SceneError;

/// How [`ObjectModel::build`] builds a model.
///
/// # Examples
///
/// ```
/// use sphaera_scene::ModelOptions;
///
/// let options = ModelOptions::default();
/// assert_eq!(options.tree.depth, 3);
/// assert_eq!(options.mesh_ladder_step, 2f64.sqrt());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ModelOptions {
    /// The sphere-tree's options (default: [`SphereTreeOptions::default`], depth 3 and
    /// branch 8).
    pub tree: SphereTreeOptions,
    /// The simplification hierarchy's options (default: simplify as far as it goes).
    pub simplify: SimplifyOptions,
    /// The ratio between the error bounds of successive mesh levels (default `√2`: each
    /// level's bound is at most `1/√2` of the coarser one's). Must be above 1.
    pub mesh_ladder_step: f64,
    /// The most mesh levels between the base mesh and the input (default 40; the input
    /// itself is always the finest level).
    pub mesh_ladder_levels: usize,
    /// How the silhouette labels are computed (used with the `silhouette` feature,
    /// ignored without it).
    pub silhouette: SilhouetteOptions,
}

/// How an object model's silhouette labels are computed (feature `silhouette`; see
/// `ObjectModel::silhouette_labels`): the views, the image resolution, and which
/// silhouettes count.
///
/// The defaults (62 views every 30°, 128² cells, outlines only) take a fraction of the
/// sphere-tree's time: the labels are for choosing where a view's outline runs, which a
/// coarse grid does well.
///
/// # Examples
///
/// ```
/// use sphaera_scene::SilhouetteOptions;
///
/// let options = SilhouetteOptions::default();
/// assert_eq!((options.step_degrees, options.resolution, options.outline_only), (30.0, 128, true));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SilhouetteOptions {
    /// The views: a latitude–longitude grid every this many degrees (must divide 180
    /// and lie in `(0, 90]`; default 30, 62 views).
    pub step_degrees: f64,
    /// The cells across each view's image (default 128).
    pub resolution: usize,
    /// Label the distance to the outline alone (default `true`), not to the internal
    /// silhouettes too: the contour region stays narrow, where it matters most.
    pub outline_only: bool,
}

impl Default for SilhouetteOptions {
    fn default() -> Self {
        Self {
            step_degrees: 30.0,
            resolution: 128,
            outline_only: true,
        }
    }
}

impl Default for ModelOptions {
    fn default() -> Self {
        Self {
            tree: SphereTreeOptions::default(),
            simplify: SimplifyOptions::default(),
            mesh_ladder_step: std::f64::consts::SQRT_2,
            mesh_ladder_levels: 40,
            silhouette: SilhouetteOptions::default(),
        }
    }
}

impl ModelOptions {
    /// With the given sphere-tree options.
    #[must_use]
    pub fn with_tree(mut self, tree: SphereTreeOptions) -> Self {
        self.tree = tree;
        self
    }

    /// With the given simplification options.
    #[must_use]
    pub fn with_simplify(mut self, simplify: SimplifyOptions) -> Self {
        self.simplify = simplify;
        self
    }
}

/// One level of an object's mesh ladder: a selectively refined mesh of its
/// simplification hierarchy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshLevel {
    /// The bound the level was refined to: every vertex whose error radius exceeded it
    /// was split.
    pub requested: f64,
    /// The certified error of the level (its largest vertex radius, at most `requested`):
    /// a bound on the Hausdorff distance between this level and the input, both ways, in
    /// the model's units.
    pub error_bound: f64,
    /// Its triangles.
    pub triangles: usize,
}

/// An object built once per mesh and shared by every instance of it (wrap it in an
/// [`Arc`](std::sync::Arc)): its mesh, its sphere-tree with the worst certified error
/// of each level, and its simplification hierarchy with a ladder of mesh levels from the
/// base mesh to the input, each with its certified error.
///
/// Levels are numbered coarsest first, for the sphere-tree (level 0: the roots) and the
/// mesh ladder (level 0: the base mesh; the last: the input, error 0) alike. With the
/// `hal` feature a model also carries its HAL tree (`ObjectModel::hal_tree`), and with
/// `silhouette` its silhouette labels (`ObjectModel::silhouette_labels`).
///
/// # Examples
///
/// ```
/// use sphaera_scene::{ModelOptions, ObjectModel};
/// use sphaera_spheretree::SphereTreeOptions;
///
/// let mesh = sphaera_mesh::shapes::torus(1.0, 0.3, 24)?;
/// let options = ModelOptions::default().with_tree(
///     SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(800)
///         .with_initial_spheres(80).with_min_spheres_per_node(20),
/// );
/// let model = ObjectModel::build("torus", mesh, &options)?;
/// assert_eq!(model.tree().level_count(), 3);
/// let ladder = model.mesh_levels();
/// // Coarsest first; the finest level is the input, exactly.
/// assert!(ladder[0].triangles < ladder[ladder.len() - 1].triangles);
/// assert_eq!(ladder[ladder.len() - 1].error_bound, 0.0);
/// assert_eq!(ladder.last().unwrap().triangles, model.mesh().triangle_count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ObjectModel {
    name: String,
    mesh: TriMesh,
    diagonal: f64,
    bounding_sphere: Sphere,
    root_bound: Sphere,
    tree: SphereTree,
    tree_errors: Vec<f64>,
    hierarchy: Hierarchy,
    mesh_levels: Vec<MeshLevel>,
    mesh_errors: Vec<f64>,
    #[cfg(feature = "hal")]
    hal: Result<sphaera_hal::HalTree3, sphaera_hal::HalError>,
    #[cfg(feature = "silhouette")]
    silhouette: Result<sphaera_silhouette::Labels, sphaera_silhouette::SilhouetteError>,
}

impl ObjectModel {
    /// Builds the sphere-tree and the simplification hierarchy of `mesh` (a closed mesh
    /// for the sphere-tree: it needs an inside), then the mesh ladder.
    ///
    /// # Errors
    ///
    /// [`SceneError::Mesh`] for an empty or invalid mesh, [`SceneError::SphereTree`] when
    /// the sphere-tree cannot be built (an open mesh, too few distinct samples, bad
    /// options), [`SceneError::Simplify`] for bad simplification options. A ladder step
    /// at or below 1 (or NaN) is taken as `√2`.
    ///
    /// # Performance
    ///
    /// Dominated by the sphere-tree, whose cost follows its samples more than the
    /// triangles: 2.8–3.2 s at the default options (10,000 samples, depth 3, branch 8) for
    /// the shared meshes of 3,674 to 12,716 triangles, all told (`scene_time_vs_error` in
    /// `docs/benchmarks.md`); the hierarchy and the ladder take a fraction of that.
    pub fn build(
        name: impl Into<String>,
        mesh: TriMesh,
        options: &ModelOptions,
    ) -> Result<Self, SceneError> {
        let surface = Surface::new(&mesh)?;
        let tree = sphaera_spheretree::build(&surface, &options.tree)?;
        let hierarchy = Hierarchy::build(&mesh, &options.simplify)?;
        Self::from_parts(name, mesh, tree, hierarchy, options)
    }

    /// A model from a sphere-tree and a hierarchy built elsewhere (for example read from
    /// files), both of `mesh`.
    ///
    /// # Errors
    ///
    /// [`SceneError::Mesh`] for an empty mesh or a tree without spheres.
    pub fn from_parts(
        name: impl Into<String>,
        mesh: TriMesh,
        tree: SphereTree,
        hierarchy: Hierarchy,
        options: &ModelOptions,
    ) -> Result<Self, SceneError> {
        let bounding_sphere = minimum_enclosing_ball(mesh.positions())?;
        let roots = tree.level_spheres(0);
        // The roots cover the surface (certified), so the ball around them holds it too;
        // the mesh's own ball is added for trees built elsewhere.
        let mut balls = roots;
        balls.push(bounding_sphere);
        let root_bound = minimum_enclosing_ball_of_balls(&balls)?;
        let tree_errors = level_worst_errors(&tree);
        let mesh_levels = mesh_ladder(&hierarchy, options);
        let mesh_errors = mesh_levels.iter().map(|l| l.error_bound).collect();
        #[cfg(feature = "hal")]
        let hal = sphaera_hal::HalTree3::build(&mesh);
        #[cfg(feature = "silhouette")]
        let silhouette = silhouette_labels(&mesh, &options.silhouette);
        Ok(Self {
            name: name.into(),
            diagonal: mesh.bounding_box_diagonal(),
            mesh,
            bounding_sphere,
            root_bound,
            tree,
            tree_errors,
            hierarchy,
            mesh_levels,
            mesh_errors,
            #[cfg(feature = "hal")]
            hal,
            #[cfg(feature = "silhouette")]
            silhouette,
        })
    }

    /// The model's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The mesh, in the model's own frame.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// The diagonal of the mesh's bounding box.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The smallest sphere holding the mesh.
    #[must_use]
    pub fn bounding_sphere(&self) -> Sphere {
        self.bounding_sphere
    }

    /// A sphere holding the mesh and every root sphere of the tree: the broad phase of
    /// [`Scene::collide`](crate::Scene::collide) tests these.
    #[must_use]
    pub fn root_bound(&self) -> Sphere {
        self.root_bound
    }

    /// The sphere-tree.
    #[must_use]
    pub fn tree(&self) -> &SphereTree {
        &self.tree
    }

    /// The worst node error of each sphere-tree level, root first (how far a level's
    /// spheres reach beyond the surface, at most).
    #[must_use]
    pub fn tree_errors(&self) -> &[f64] {
        &self.tree_errors
    }

    /// The simplification hierarchy.
    #[must_use]
    pub fn hierarchy(&self) -> &Hierarchy {
        &self.hierarchy
    }

    /// The mesh ladder, coarsest first; the last level is the input (error 0).
    #[must_use]
    pub fn mesh_levels(&self) -> &[MeshLevel] {
        &self.mesh_levels
    }

    /// The HAL tree of the mesh (feature `hal`): its hierarchy of approximating triangles
    /// with bounding balls, for point inclusion and intersection tests; the reason when
    /// the mesh has none (it must be closed and of genus 0).
    ///
    /// # Errors
    ///
    /// The [`sphaera_hal::HalError`] the tree's construction gave.
    #[cfg(feature = "hal")]
    pub fn hal_tree(&self) -> Result<&sphaera_hal::HalTree3, &sphaera_hal::HalError> {
        self.hal.as_ref()
    }

    /// The silhouette labels of the mesh (feature `silhouette`): for each of
    /// [`ModelOptions::silhouette`]'s views, how many image cells each vertex lies from the
    /// silhouette (Mata, Pastor and Rodríguez). [`Scene::silhouette_detail`](crate::Scene::silhouette_detail)
    /// uses them to keep outlines finer than interiors; the reason when the mesh has none
    /// (bad options).
    ///
    /// # Errors
    ///
    /// The [`sphaera_silhouette::SilhouetteError`] the labelling gave.
    #[cfg(feature = "silhouette")]
    pub fn silhouette_labels(
        &self,
    ) -> Result<&sphaera_silhouette::Labels, &sphaera_silhouette::SilhouetteError> {
        self.silhouette.as_ref()
    }

    /// The certified error of each mesh ladder level, coarsest first (model units).
    #[must_use]
    pub fn mesh_errors(&self) -> &[f64] {
        &self.mesh_errors
    }

    /// The mesh of ladder level `level` (its vertices, triangles and radii), `None` out
    /// of range. Rebuilt from the hierarchy on each call.
    #[must_use]
    pub fn mesh_level(&self, level: usize) -> Option<Simplified> {
        let requested = self.mesh_levels.get(level)?.requested;
        Some(self.hierarchy.level_by_error(requested))
    }

    /// The coarsest sphere-tree level whose worst error is at most `tolerance` (in the
    /// model's units), or the finest level and `false` when none is.
    #[must_use]
    pub fn tree_level_for(&self, tolerance: f64) -> (usize, bool) {
        coarsest_meeting(&self.tree_errors, |e| e <= tolerance)
    }

    /// The coarsest mesh level whose certified error is at most `tolerance` (in the
    /// model's units); the input (error 0) meets every tolerance.
    #[must_use]
    pub fn mesh_level_for(&self, tolerance: f64) -> (usize, bool) {
        coarsest_meeting(&self.mesh_errors, |e| e <= tolerance)
    }
}

/// The labels of `mesh` for `options`' orthographic views, exact Euclidean distances.
#[cfg(feature = "silhouette")]
fn silhouette_labels(
    mesh: &TriMesh,
    options: &SilhouetteOptions,
) -> Result<sphaera_silhouette::Labels, sphaera_silhouette::SilhouetteError> {
    use sphaera_silhouette::{Contours, DistanceTransform, Labels, ViewSet};
    let views = ViewSet::regular(options.step_degrees)?;
    let contours = if options.outline_only {
        Contours::External
    } else {
        Contours::All
    };
    Labels::compute(
        mesh,
        &views,
        options.resolution,
        DistanceTransform::Euclidean,
        contours,
    )
}

/// The first index whose error meets `ok`, or the last and `false`.
fn coarsest_meeting(errors: &[f64], ok: impl Fn(f64) -> bool) -> (usize, bool) {
    match errors.iter().position(|&e| ok(e)) {
        Some(i) => (i, true),
        None => (errors.len().saturating_sub(1), false),
    }
}

/// The ladder: the base mesh, then refinements to bounds shrinking by the step, then the
/// input. A refinement only ever splits further, so one refinement walks the ladder.
fn mesh_ladder(hierarchy: &Hierarchy, options: &ModelOptions) -> Vec<MeshLevel> {
    let step = if options.mesh_ladder_step > 1.0 && options.mesh_ladder_step.is_finite() {
        options.mesh_ladder_step
    } else {
        std::f64::consts::SQRT_2
    };
    let mut refinement = hierarchy.refinement();
    let max_radius = |r: &sphaera_simplify::Refinement<'_>| {
        (0..hierarchy.vertex_count() as u32)
            .filter(|&v| r.is_present(v))
            .map(|v| r.radius(v))
            .fold(0.0_f64, f64::max)
    };
    let mut levels: Vec<MeshLevel> = Vec::new();
    let push = |levels: &mut Vec<MeshLevel>, level: MeshLevel| {
        match levels.last_mut() {
            // The refinement only splits further: the same triangle count is the same mesh.
            // Keep the smaller request, which names it as well.
            Some(last) if last.triangles == level.triangles => {
                last.requested = level.requested;
            }
            _ => levels.push(level),
        }
    };
    let base_error = max_radius(&refinement);
    push(
        &mut levels,
        MeshLevel {
            requested: base_error,
            error_bound: base_error,
            triangles: refinement.live_triangle_count(),
        },
    );
    let mut bound = base_error;
    for _ in 0..options.mesh_ladder_levels {
        bound /= step;
        if bound <= 0.0 {
            break;
        }
        refinement.refine_to_error(bound);
        push(
            &mut levels,
            MeshLevel {
                requested: bound,
                error_bound: max_radius(&refinement),
                triangles: refinement.live_triangle_count(),
            },
        );
    }
    refinement.refine_to_error(0.0);
    push(
        &mut levels,
        MeshLevel {
            requested: 0.0,
            error_bound: max_radius(&refinement),
            triangles: refinement.live_triangle_count(),
        },
    );
    levels
}
