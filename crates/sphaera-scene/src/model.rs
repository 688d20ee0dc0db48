//! An object built once per mesh: its sphere-tree and its simplification hierarchy, with
//! the certified error of every level.

use std::sync::Arc;
#[cfg(any(feature = "hal", feature = "silhouette"))]
use std::sync::OnceLock;
use std::time::Instant;

use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_mesh::{Length, Sphere, TriMesh};
use sphaera_query::Surface;
use sphaera_simplify::{Hierarchy, Simplified, SimplifyOptions};
use sphaera_spheretree::{Effort, SphereTree, SphereTreeOptions};

use crate::trees::{ModelTree, Selection, TreePolicy, Trees};
use crate::{InstanceDetail, SceneError};

/// How [`ObjectModel::build`] builds a model.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::Length;
/// use sphaera_scene::ModelOptions;
///
/// let options = ModelOptions::default();
/// assert_eq!((options.tree.depth, options.tree.branch), (2, 8));
/// assert_eq!(options.tolerance_tree.branch, 16);
/// assert_eq!(options.tolerance_tree.effort, sphaera_spheretree::Effort::Quick);
/// assert_eq!(options.finest_tolerance, Length::RelativeToDiagonal(1e-3));
/// assert_eq!(options.mesh_ladder_step, 2f64.sqrt());
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ModelOptions {
    /// The base sphere-tree's options: the tree built with the model (default:
    /// [`SphereTreeOptions::default`] to depth 2, 64 spheres at branch 8; any method).
    /// Finer tolerances get trees of their own ([`ModelOptions::tolerance_tree`]), so a
    /// deep base tree only pays where collisions need it before any detail request does.
    pub tree: SphereTreeOptions,
    /// The options of the trees built to a tolerance when a detail request needs a finer
    /// one than every tree the model has ([`ObjectModel::tree_for`]; default
    /// [`SphereTreeOptions::default`] with branch 16 and [`Effort::Quick`]: they are
    /// built while a request waits: on the four shared meshes at 2 % of their size,
    /// measured by hand, quick trees took a fraction of the default effort's time for a
    /// few more leaves, and branch 16 less time than branch 8). They are built with
    /// [`SphereTreeOptions::with_tolerance`] and coverage certification on, so the
    /// method must be the minimax (`auto`, the default); `depth` is not used.
    pub tolerance_tree: SphereTreeOptions,
    /// The finest tolerance a tree is built to (default 10⁻³ of the mesh's bounding-box
    /// diagonal): below it, a detail request says so
    /// ([`SceneError::ToleranceBelowFinest`]) rather than building for minutes and
    /// thousands of spheres. Lower it when that is what a scene needs.
    pub finest_tolerance: Length,
    /// The simplification hierarchy's options (default: simplify as far as it goes).
    pub simplify: SimplifyOptions,
    /// The ratio between the error bounds of successive mesh levels (default `√2`: each
    /// level's bound is at most `1/√2` of the coarser one's). Must be above 1.
    pub mesh_ladder_step: f64,
    /// The most mesh levels between the base mesh and the input (default 40, at most
    /// [`MAX_MESH_LADDER_LEVELS`]; the input itself is always the finest level).
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
#[non_exhaustive]
pub struct SilhouetteOptions {
    /// The views: a latitude–longitude grid every this many degrees (must divide 180
    /// and lie in `(0, 90]`, and be at least 1.40625° so that there are at most
    /// `sphaera_silhouette::MAX_VIEWS` views; default 30, 62 views).
    pub step_degrees: f64,
    /// The cells across each view's image (default 128; at most
    /// `sphaera_silhouette::MAX_RESOLUTION`, 4,096). The labels take 2 bytes per vertex per
    /// view, at most `sphaera_silhouette::MAX_LABELS`. Values beyond a cap leave the model
    /// without labels, and `ObjectModel::silhouette_labels` says which cap.
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
            tree: SphereTreeOptions::default().with_depth(2),
            tolerance_tree: SphereTreeOptions::default()
                .with_branch(16)
                .with_effort(Effort::Quick),
            finest_tolerance: Length::RelativeToDiagonal(1e-3),
            simplify: SimplifyOptions::default(),
            mesh_ladder_step: std::f64::consts::SQRT_2,
            mesh_ladder_levels: 40,
            silhouette: SilhouetteOptions::default(),
        }
    }
}

impl ModelOptions {
    /// With the given base sphere-tree options.
    #[must_use]
    pub fn with_tree(mut self, tree: SphereTreeOptions) -> Self {
        self.tree = tree;
        self
    }

    /// With the given options for the trees built to a tolerance.
    #[must_use]
    pub fn with_tolerance_tree(mut self, tree: SphereTreeOptions) -> Self {
        self.tolerance_tree = tree;
        self
    }

    /// With the given finest tolerance.
    #[must_use]
    pub fn with_finest_tolerance(mut self, finest: Length) -> Self {
        self.finest_tolerance = finest;
        self
    }

    /// With the given simplification options.
    #[must_use]
    pub fn with_simplify(mut self, simplify: SimplifyOptions) -> Self {
        self.simplify = simplify;
        self
    }

    /// With the given ratio between the error bounds of successive mesh levels.
    #[must_use]
    pub fn with_mesh_ladder_step(mut self, step: f64) -> Self {
        self.mesh_ladder_step = step;
        self
    }

    /// With at most this many mesh levels between the base mesh and the input (at most
    /// [`MAX_MESH_LADDER_LEVELS`], checked when a model is built).
    #[must_use]
    pub fn with_mesh_ladder_levels(mut self, levels: usize) -> Self {
        self.mesh_ladder_levels = levels;
        self
    }

    /// With the given silhouette-label options.
    #[must_use]
    pub fn with_silhouette(mut self, silhouette: SilhouetteOptions) -> Self {
        self.silhouette = silhouette;
        self
    }
}

impl SilhouetteOptions {
    /// With views every `degrees` degrees of latitude and longitude.
    #[must_use]
    pub fn with_step_degrees(mut self, degrees: f64) -> Self {
        self.step_degrees = degrees;
        self
    }

    /// With `resolution` cells across each view's image.
    #[must_use]
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// Labelling the distance to the outline alone (`true`) or to the internal
    /// silhouettes too.
    #[must_use]
    pub fn with_outline_only(mut self, outline_only: bool) -> Self {
        self.outline_only = outline_only;
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
/// [`Arc`]): its mesh, its sphere-trees with the certified error of every cut, and its
/// simplification hierarchy with a ladder of mesh levels from the base mesh to the
/// input, each with its certified error.
///
/// A model starts with one sphere-tree, its **base tree** ([`ModelOptions::tree`]).
/// When a request needs a finer tolerance than every tree it has
/// ([`ObjectModel::tree_for`], which [`Scene::detail`](crate::Scene::detail) calls), it
/// builds a **tolerance tree** for it (the minimax method: every leaf's certified error
/// within the tolerance, refined only where needed) and keeps it, so each tolerance is
/// built once per model whatever the number of instances or requests. Building is
/// thread-safe (one build at a time per model; a request waiting for a build uses it
/// when it meets its tolerance) and deterministic: the same requests in the same order
/// give the same trees.
///
/// Levels are numbered coarsest first, for the sphere-trees (level 0: the roots) and the
/// mesh ladder (level 0: the base mesh; the last: the input, error 0) alike. With the
/// `hal` feature a model also carries its HAL tree (`ObjectModel::hal_tree`), and with
/// `silhouette` its silhouette labels (`ObjectModel::silhouette_labels`), each computed
/// on first use.
///
/// # Examples
///
/// ```
/// use sphaera_scene::{ModelOptions, ObjectModel};
/// use sphaera_spheretree::SphereTreeOptions;
///
/// let mesh = sphaera_mesh::shapes::torus(1.0, 0.3, 24)?;
/// let options = ModelOptions::default().with_tree(SphereTreeOptions::default().with_depth(2).with_branch(4));
/// let model = ObjectModel::build("torus", mesh, &options)?;
/// assert_eq!(model.tree().level_count(), 3);
/// let ladder = model.mesh_levels();
/// // Coarsest first; the finest level is the input, exactly.
/// assert!(ladder[0].triangles < ladder[ladder.len() - 1].triangles);
/// assert_eq!(ladder[ladder.len() - 1].error_bound, 0.0);
/// assert_eq!(ladder.last().unwrap().triangles, model.mesh().triangle_count());
///
/// // 2 % of its diagonal, finer than the base tree reaches: a tree is built for it.
/// let tolerance = 0.02 * model.diagonal();
/// assert!(model.base_tree().worst_error() > tolerance);
/// let (tree, built) = model.tree_for(tolerance)?;
/// assert!(built && tree.worst_error() <= tolerance);
/// assert_eq!(model.trees().len(), 2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ObjectModel {
    name: String,
    surface: Surface,
    diagonal: f64,
    bounding_sphere: Sphere,
    trees: Trees,
    policy: TreePolicy,
    hierarchy: Hierarchy,
    mesh_levels: Vec<MeshLevel>,
    mesh_errors: Vec<f64>,
    #[cfg(feature = "hal")]
    hal: OnceLock<Result<sphaera_hal::HalTree3, sphaera_hal::HalError>>,
    #[cfg(feature = "silhouette")]
    silhouette: OnceLock<Result<sphaera_silhouette::Labels, sphaera_silhouette::SilhouetteError>>,
    #[cfg(feature = "silhouette")]
    silhouette_options: SilhouetteOptions,
}

impl ObjectModel {
    /// Builds the base sphere-tree and the simplification hierarchy of `mesh`, then the
    /// mesh ladder. The mesh may be a closed solid or a sheet (the minimax trees cover
    /// shells; the paper's medial methods need an inside).
    ///
    /// # Errors
    ///
    /// [`SceneError::Mesh`] for an empty or invalid mesh, [`SceneError::SphereTree`] when
    /// the base tree cannot be built (bad options, a medial method on a sheet),
    /// [`SceneError::Simplify`] for bad simplification options;
    /// [`SceneError::InvalidOption`] for more ladder levels than
    /// [`MAX_MESH_LADDER_LEVELS`]. A ladder step at or below 1 (or NaN) is taken as `√2`.
    ///
    /// # Performance
    ///
    /// The base tree and the hierarchy, one after the other (every core works inside
    /// each with the `parallel` feature); at the defaults (a minimax tree to depth 2) the
    /// tree costs more than the hierarchy and the ladder. Tolerance trees are built later,
    /// when a request needs one (see the crate's Performance section).
    pub fn build(
        name: impl Into<String>,
        mesh: TriMesh,
        options: &ModelOptions,
    ) -> Result<Self, SceneError> {
        check_options(options)?;
        let surface = Surface::solid_or_shell(&mesh)?;
        drop(mesh);
        let started = Instant::now();
        let tree = sphaera_spheretree::build(&surface, &options.tree)?;
        let seconds = started.elapsed().as_secs_f64();
        let hierarchy = Hierarchy::build(surface.mesh(), &options.simplify)?;
        Self::assemble(name.into(), surface, tree, seconds, hierarchy, options)
    }

    /// A model from a base sphere-tree and a hierarchy built elsewhere (for example read
    /// from files), both of `mesh`. Finer tolerances get trees built from
    /// [`ModelOptions::tolerance_tree`].
    ///
    /// # Errors
    ///
    /// [`SceneError::Mesh`] for an empty mesh or a tree without spheres;
    /// [`SceneError::InvalidOption`] for more ladder levels than
    /// [`MAX_MESH_LADDER_LEVELS`].
    pub fn from_parts(
        name: impl Into<String>,
        mesh: TriMesh,
        tree: SphereTree,
        hierarchy: Hierarchy,
        options: &ModelOptions,
    ) -> Result<Self, SceneError> {
        check_options(options)?;
        let surface = Surface::solid_or_shell(&mesh)?;
        drop(mesh);
        Self::assemble(name.into(), surface, tree, 0.0, hierarchy, options)
    }

    fn assemble(
        name: String,
        surface: Surface,
        tree: SphereTree,
        seconds: f64,
        hierarchy: Hierarchy,
        options: &ModelOptions,
    ) -> Result<Self, SceneError> {
        let mesh = surface.mesh();
        let bounding_sphere = minimum_enclosing_ball(mesh.positions())?;
        let diagonal = mesh.bounding_box_diagonal();
        let base = ModelTree::new(tree, 0, None, seconds, bounding_sphere)?;
        let mesh_levels = mesh_ladder(&hierarchy, options);
        let mesh_errors = mesh_levels.iter().map(|l| l.error_bound).collect();
        Ok(Self {
            name,
            diagonal,
            bounding_sphere,
            trees: Trees::new(base),
            policy: TreePolicy {
                options: options.tolerance_tree.clone(),
                finest: options.finest_tolerance.resolve(diagonal),
            },
            hierarchy,
            mesh_levels,
            mesh_errors,
            surface,
            #[cfg(feature = "hal")]
            hal: OnceLock::new(),
            #[cfg(feature = "silhouette")]
            silhouette: OnceLock::new(),
            #[cfg(feature = "silhouette")]
            silhouette_options: options.silhouette,
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
        self.surface.mesh()
    }

    /// The mesh prepared for exact closest points and inside tests (a solid, or a shell
    /// for a mesh without an inside): what the sphere-trees are built and checked on.
    #[must_use]
    pub fn surface(&self) -> &Surface {
        &self.surface
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

    /// A sphere holding the mesh and the roots of the tree collisions use
    /// ([`ObjectModel::collision_tree`]): the broad phase of
    /// [`Scene::collide`](crate::Scene::collide) tests these.
    #[must_use]
    pub fn root_bound(&self) -> Sphere {
        self.collision_tree().bound()
    }

    /// The base sphere-tree (built with the model from [`ModelOptions::tree`]).
    #[must_use]
    pub fn tree(&self) -> &SphereTree {
        self.trees.base().tree()
    }

    /// The base sphere-tree with its cut errors.
    #[must_use]
    pub fn base_tree(&self) -> &ModelTree {
        self.trees.base()
    }

    /// The worst node error of each cut of the base tree, root first (how far its spheres
    /// reach beyond the surface at that detail, at most).
    #[must_use]
    pub fn tree_errors(&self) -> &[f64] {
        self.trees.base().level_errors()
    }

    /// Every sphere-tree the model has, in the order they were built: the base tree,
    /// then the tolerance trees.
    #[must_use]
    pub fn trees(&self) -> Vec<Arc<ModelTree>> {
        self.trees.all()
    }

    /// The tree collisions descend: the one with the smallest worst leaf error (the
    /// earliest on a tie). It is the base tree until a tolerance tree finer than it has
    /// been built.
    #[must_use]
    pub fn collision_tree(&self) -> Arc<ModelTree> {
        self.trees.finest()
    }

    /// A sphere-tree with a cut meeting `tolerance` (in the model's units, certified),
    /// and whether it was built for this call.
    ///
    /// A tree meets a tolerance when one of its cuts [`SphereTree::cut_at`]`(level)` has
    /// a certified error within it: each node's error
    /// ([`TreeNode::error`](sphaera_spheretree::TreeNode::error)), or, for a node over
    /// the tolerance, the smaller of it and the upper bound of the node's sphere
    /// evaluated on the exact surface ([`sphaera_spheretree::evaluate::sphere_error`],
    /// computed once per node and kept). When some tree meets it, the one whose coarsest
    /// such cut has the fewest spheres is returned (the earliest on a tie). Otherwise a
    /// tolerance tree is built from [`ModelOptions::tolerance_tree`], to `tolerance`, or
    /// to half the finest tolerance built before when that is smaller: a run of
    /// tightening requests (a camera coming closer) builds once per halving, not once
    /// per request. The tree is kept. Only trees whose coverage is certified at every
    /// level ([`ModelTree::coverage_certified`]) are used.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_scene::{ModelOptions, ObjectModel, SceneError};
    ///
    /// let model = ObjectModel::build("ball", sphaera_mesh::shapes::sphere(1.0, 12)?, &ModelOptions::default())?;
    /// let (tree, built) = model.tree_for(0.05)?;
    /// assert!(tree.worst_error() <= 0.05);
    /// // Below the finest tolerance (10⁻³ of the diagonal by default): refused, and said so.
    /// let refused = model.tree_for(1e-4).unwrap_err();
    /// assert!(matches!(refused, SceneError::ToleranceBelowFinest { .. }));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::ToleranceBelowFinest`] for a tolerance below
    /// [`ModelOptions::finest_tolerance`] that no tree meets (or NaN),
    /// [`SceneError::ToleranceTree`] when the tree cannot be built: the tolerance is out of
    /// reach ([`SphereTreeError::ToleranceUnreachable`](sphaera_spheretree::SphereTreeError::ToleranceUnreachable),
    /// remembered so that a finer request fails at once) or the options are invalid.
    ///
    /// # Performance
    ///
    /// Choosing among the trees walks their cuts, probing a node's sphere the first time a
    /// tolerance below its node error is asked (32 closest-point queries) and evaluating it
    /// when the probes do not rule it out. A build costs about what the tree's spheres cost
    /// (with [`Effort::Quick`](sphaera_spheretree::Effort::Quick), the default; see the
    /// crate's Performance section).
    pub fn tree_for(&self, tolerance: f64) -> Result<(Arc<ModelTree>, bool), SceneError> {
        self.ensure_tree(tolerance)
            .map(|(selection, built)| (selection.tree, built))
    }

    /// [`ObjectModel::tree_for`] with what the tree offers `tolerance`.
    pub(crate) fn ensure_tree(&self, tolerance: f64) -> Result<(Selection, bool), SceneError> {
        self.trees.ensure(
            &self.name,
            tolerance,
            &self.surface,
            &self.policy,
            self.bounding_sphere,
        )
    }

    /// The spheres an instance's detail chose ([`InstanceDetail::spheres`]: the cut
    /// [`SphereTree::cut_at`]`(level)` of tree [`InstanceDetail::tree`]), in the model's
    /// frame (place them with the instance's pose); `None` when `detail` names a tree
    /// this model does not have (a detail of another model).
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_scene::{ModelOptions, ObjectModel, Scene, Tolerance};
    ///
    /// let model = Arc::new(ObjectModel::build("ball", sphaera_mesh::shapes::sphere(1.0, 12)?, &ModelOptions::default())?);
    /// let mut scene = Scene::new();
    /// scene.add("ball", Arc::clone(&model), Similarity::IDENTITY);
    /// let report = scene.detail(None, Tolerance::RelativeToDiagonal(0.05))?;
    /// let spheres = model.detail_spheres(&report.instances[0]).expect("its model");
    /// assert_eq!(spheres.len(), report.instances[0].spheres.count);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn detail_spheres(&self, detail: &InstanceDetail) -> Option<Vec<Sphere>> {
        let trees = self.trees.all();
        let tree = trees.get(detail.tree.index)?;
        (detail.spheres.level < tree.tree().level_count())
            .then(|| tree.tree().cut_spheres(detail.spheres.level))
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

    /// The HAL tree of the mesh (feature `hal`), built on the first call: its hierarchy
    /// of approximating triangles with bounding balls, for point inclusion and
    /// intersection tests; the reason when the mesh has none (it must be closed and of
    /// genus 0).
    ///
    /// # Errors
    ///
    /// The [`sphaera_hal::HalError`] the tree's construction gave.
    #[cfg(feature = "hal")]
    pub fn hal_tree(&self) -> Result<&sphaera_hal::HalTree3, &sphaera_hal::HalError> {
        self.hal
            .get_or_init(|| sphaera_hal::HalTree3::build(self.mesh()))
            .as_ref()
    }

    /// The silhouette labels of the mesh (feature `silhouette`), computed on the first
    /// call (or given: [`ObjectModel::with_silhouette_labels`]): for each of
    /// [`ModelOptions::silhouette`]'s views, how many image cells each
    /// vertex lies from the silhouette (Mata, Pastor and Rodríguez).
    /// [`Scene::silhouette_detail`](crate::Scene::silhouette_detail) uses them to keep
    /// outlines finer than interiors; the reason when the mesh has none (bad options).
    ///
    /// # Errors
    ///
    /// The [`sphaera_silhouette::SilhouetteError`] the labelling gave.
    #[cfg(feature = "silhouette")]
    pub fn silhouette_labels(
        &self,
    ) -> Result<&sphaera_silhouette::Labels, &sphaera_silhouette::SilhouetteError> {
        self.silhouette
            .get_or_init(|| silhouette_labels(self.mesh(), &self.silhouette_options))
            .as_ref()
    }

    /// The same model with `labels` as its silhouette labels (feature `silhouette`), in
    /// place of computing them on first use: labels computed earlier, kept in a label
    /// file (`sphaera_silhouette::Labels::load`, or a scene file's `labels`). They must
    /// belong to the model's mesh and have been computed with
    /// [`ModelOptions::silhouette`]'s settings (its step, resolution and contours,
    /// orthographic views and the exact Euclidean transform), so that the model answers
    /// the same as if it had computed them.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_scene::{ModelOptions, ObjectModel};
    /// use sphaera_silhouette::Labels;
    ///
    /// let options = ModelOptions::default();
    /// let mesh = sphaera_mesh::shapes::sphere(1.0, 10)?;
    /// let model = ObjectModel::build("ball", mesh.clone(), &options)?;
    /// // Label once and keep the labels in a file...
    /// let dir = tempfile::tempdir()?;
    /// let path = dir.path().join("ball.labels");
    /// let labels = model.silhouette_labels().expect("the default options give labels");
    /// labels.save(model.mesh(), &path)?;
    /// // ... which a later model of the same mesh reads instead of labelling.
    /// let again = ObjectModel::build("ball", mesh, &options)?;
    /// let labels = Labels::load(&path, again.mesh())?;
    /// let again = again.with_silhouette_labels(labels)?;
    /// assert_eq!(again.silhouette_labels().ok(), model.silhouette_labels().ok());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::SilhouetteLabels`] naming the model when the labels belong to
    /// another mesh or were computed with other settings (the message names the
    /// setting), or when the model's options cannot give labels at all.
    #[cfg(feature = "silhouette")]
    pub fn with_silhouette_labels(
        mut self,
        labels: sphaera_silhouette::Labels,
    ) -> Result<Self, SceneError> {
        let fits = silhouette_settings(&self.silhouette_options).and_then(|(views, options)| {
            labels.check_mesh(self.mesh())?;
            labels.check_settings(&views, &options)
        });
        if let Err(error) = fits {
            return Err(SceneError::SilhouetteLabels {
                model: self.name.clone(),
                source: Box::new(error),
            });
        }
        self.silhouette = OnceLock::from(Ok(labels));
        Ok(self)
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

    /// The coarsest cut of the base tree whose worst error is at most `tolerance` (in the
    /// model's units), or the finest and `false` when none is ([`ObjectModel::tree_for`]
    /// builds a tree that meets it).
    #[must_use]
    pub fn tree_level_for(&self, tolerance: f64) -> (usize, bool) {
        coarsest_meeting(self.tree_errors(), |e| e <= tolerance)
    }

    /// The coarsest mesh level whose certified error is at most `tolerance` (in the
    /// model's units); the input (error 0) meets every tolerance.
    #[must_use]
    pub fn mesh_level_for(&self, tolerance: f64) -> (usize, bool) {
        coarsest_meeting(&self.mesh_errors, |e| e <= tolerance)
    }
}

/// The views and label options of `options`: orthographic views, exact Euclidean
/// distances.
#[cfg(feature = "silhouette")]
fn silhouette_settings(
    options: &SilhouetteOptions,
) -> Result<
    (
        sphaera_silhouette::ViewSet,
        sphaera_silhouette::LabelOptions,
    ),
    sphaera_silhouette::SilhouetteError,
> {
    use sphaera_silhouette::{Contours, LabelOptions, ViewSet};
    let views = ViewSet::regular(options.step_degrees)?;
    let contours = if options.outline_only {
        Contours::External
    } else {
        Contours::All
    };
    let label_options = LabelOptions::default()
        .with_resolution(options.resolution)
        .with_contours(contours);
    Ok((views, label_options))
}

/// The labels of `mesh` for `options`' views.
#[cfg(feature = "silhouette")]
fn silhouette_labels(
    mesh: &TriMesh,
    options: &SilhouetteOptions,
) -> Result<sphaera_silhouette::Labels, sphaera_silhouette::SilhouetteError> {
    let (views, label_options) = silhouette_settings(options)?;
    sphaera_silhouette::Labels::compute(mesh, &views, &label_options)
}

/// The most mesh levels a model's ladder may have ([`ModelOptions::mesh_ladder_levels`]):
/// 1,000. Each level costs a refinement of the hierarchy and a scan of its vertices, so
/// a larger count only spends time; it is refused ([`SceneError::InvalidOption`] named
/// `"mesh_ladder_levels"`) before the model is built.
pub const MAX_MESH_LADDER_LEVELS: usize = 1_000;

/// Checks the options that size a model's work before it is built.
fn check_options(options: &ModelOptions) -> Result<(), SceneError> {
    if options.mesh_ladder_levels > MAX_MESH_LADDER_LEVELS {
        return Err(SceneError::InvalidOption {
            name: "mesh_ladder_levels",
            value: options.mesh_ladder_levels as f64,
            requirement: "at most 1,000 (`MAX_MESH_LADDER_LEVELS`)",
        });
    }
    Ok(())
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
