//! A scene: instances of shared object models, each with a pose.

use std::sync::Arc;

use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::Similarity;

use crate::{ObjectModel, SceneError};

/// One object placed in a scene.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Its name in reports.
    pub name: String,
    /// The model it is an instance of (shared with the other instances of it).
    pub model: Arc<ObjectModel>,
    /// Where it is: the model's frame mapped to the scene's (a rotation or mirror, a
    /// uniform scale and a translation).
    pub pose: Similarity,
}

impl Instance {
    /// The bounding sphere of its mesh, in the scene.
    #[must_use]
    pub fn bounding_sphere(&self) -> Sphere {
        self.pose.sphere(&self.model.bounding_sphere())
    }

    /// The broad-phase sphere (around its mesh and the roots of its model's collision
    /// tree), in the scene.
    #[must_use]
    pub fn root_bound(&self) -> Sphere {
        self.pose.sphere(&self.model.root_bound())
    }

    /// Its size in the scene: the model's bounding-box diagonal times the pose's scale.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.model.diagonal() * self.pose.scale()
    }
}

/// Instances of object models with their poses: what [`Scene::detail`] chooses levels
/// for and [`Scene::collide`] finds contacts in.
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
/// use sphaera_mesh::geometry::Similarity;
/// use sphaera_scene::{DVec3, ModelOptions, ObjectModel, Scene, Tolerance};
/// use sphaera_spheretree::SphereTreeOptions;
///
/// let tree = SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(600)
///     .with_initial_spheres(60).with_min_spheres_per_node(20);
/// let capsule = sphaera_mesh::shapes::capsule(0.5, 2.0, 12)?;
/// let model = Arc::new(ObjectModel::build("capsule", capsule, &ModelOptions::default().with_tree(tree))?);
///
/// let mut scene = Scene::new();
/// scene.add("near", Arc::clone(&model), Similarity::IDENTITY);
/// scene.add("far", model, Similarity::from_translation(DVec3::new(100.0, 0.0, 0.0))?);
///
/// // Half a percent of each object's size: both take the same levels.
/// let report = scene.detail(None, Tolerance::RelativeToDiagonal(0.005))?;
/// assert_eq!(report.instances[0].spheres.level, report.instances[1].spheres.level);
/// assert!(report.triangles <= report.full_triangles);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Scene {
    instances: Vec<Instance>,
}

impl Scene {
    /// An empty scene.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds an instance of `model` at `pose`; returns its index.
    pub fn add(
        &mut self,
        name: impl Into<String>,
        model: Arc<ObjectModel>,
        pose: Similarity,
    ) -> usize {
        self.instances.push(Instance {
            name: name.into(),
            model,
            pose,
        });
        self.instances.len() - 1
    }

    /// The instances, in the order they were added.
    #[must_use]
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// The number of instances.
    #[must_use]
    pub fn len(&self) -> usize {
        self.instances.len()
    }

    /// Whether the scene has no instance.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    /// Moves instance `index` to `pose`.
    ///
    /// # Errors
    ///
    /// [`SceneError::NoSuchInstance`] when `index` is out of range.
    pub fn set_pose(&mut self, index: usize, pose: Similarity) -> Result<(), SceneError> {
        let count = self.instances.len();
        let instance = self
            .instances
            .get_mut(index)
            .ok_or(SceneError::NoSuchInstance { index, count })?;
        instance.pose = pose;
        Ok(())
    }
}
