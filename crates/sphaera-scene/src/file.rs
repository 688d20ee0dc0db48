//! Scene files: JSON naming meshes, the instances with their poses, and a camera. The
//! format is documented in the crate docs, section "Scene files".

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DQuat, DVec3, EulerRot};
use serde::Deserialize;
use sphaera_io::FilePolicy;
use sphaera_mesh::geometry::Similarity;

use crate::{Camera, ModelOptions, ObjectModel, Scene, SceneError};

/// A scene file as written, before any mesh is read.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Mesh names and their files (a name given twice is an error).
    #[serde(deserialize_with = "unique_names")]
    pub meshes: BTreeMap<String, PathBuf>,
    /// The instances.
    pub instances: Vec<InstanceEntry>,
    /// The camera, if any.
    #[serde(default)]
    pub camera: Option<CameraEntry>,
    /// Silhouette label files by mesh name (feature `silhouette`; read by no build
    /// without it): each mesh's model reads its labels from the file instead of computing
    /// them, and the file must hold labels of that mesh computed with the model's
    /// silhouette options. A name given twice, or one not in [`SceneFile::meshes`], is an
    /// error.
    #[serde(default, deserialize_with = "unique_names")]
    pub labels: BTreeMap<String, PathBuf>,
}

/// One instance of a scene file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InstanceEntry {
    /// Its name (default `MESH-INDEX`).
    #[serde(default)]
    pub name: Option<String>,
    /// The name of its mesh in [`SceneFile::meshes`].
    pub mesh: String,
    /// Where its mesh's origin goes.
    #[serde(default)]
    pub position: [f64; 3],
    /// Rotations about x, then y, then z, in degrees.
    #[serde(default)]
    pub rotation_degrees: Option<[f64; 3]>,
    /// A unit quaternion `[x, y, z, w]` (normalised if it is not quite unit).
    #[serde(default)]
    pub quaternion: Option<[f64; 4]>,
    /// A uniform scale (default 1).
    #[serde(default = "one")]
    pub scale: f64,
}

fn one() -> f64 {
    1.0
}

/// The camera of a scene file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraEntry {
    /// The eye.
    pub eye: [f64; 3],
    /// The point looked at.
    pub target: [f64; 3],
    /// The vertical field of view, in degrees.
    pub fov_y_degrees: f64,
    /// The image width in pixels.
    pub width: u32,
    /// The image height in pixels.
    pub height: u32,
    /// The near-plane distance (default 1/1000 of the eye–target distance).
    #[serde(default)]
    pub near: Option<f64>,
}

/// A scene read from a file, its models built.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The instances with their poses.
    pub scene: Scene,
    /// The file's camera.
    pub camera: Option<Camera>,
    /// The models built, in the order of their names.
    pub models: Vec<Arc<ObjectModel>>,
}

/// A checked scene file: poses and camera valid, every instance's mesh defined.
#[derive(Clone, Debug)]
pub struct SceneDescription {
    path: PathBuf,
    policy: FilePolicy,
    file: SceneFile,
    poses: Vec<Similarity>,
    camera: Option<Camera>,
}

impl SceneDescription {
    /// Reads and checks a scene file; reads no mesh. The scene file and, later, its
    /// meshes are read by the default [`FilePolicy`] (regular files only, each at most
    /// [`DEFAULT_MAX_FILE_BYTES`](sphaera_io::DEFAULT_MAX_FILE_BYTES), anywhere): a
    /// service reading scenes it did not write uses [`SceneDescription::read_with`] with a
    /// root.
    ///
    /// # Errors
    ///
    /// [`SceneError::ReadFile`] when the file cannot be read or the policy refuses it,
    /// [`SceneError::ParseFile`] for malformed JSON, an unknown key or a wrong type (with
    /// the line and column), [`SceneError::InvalidEntry`] for an instance naming an
    /// undefined mesh, a non-finite or zero pose, both rotation forms, or an invalid
    /// camera.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, SceneError> {
        Self::read_with(path, &FilePolicy::default())
    }

    /// [`SceneDescription::read`] by `policy`: the scene file and every mesh it names are
    /// read only if the policy admits them (with a root, a mesh path may still be absolute
    /// or climb with `..`, but must end inside the root once links are resolved).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_io::FilePolicy;
    /// use sphaera_scene::{ModelOptions, SceneDescription};
    ///
    /// let folder = std::env::temp_dir().join(format!("sphaera-scene-policy-{}", std::process::id()));
    /// std::fs::create_dir_all(&folder)?;
    /// let scene = folder.join("scene.json");
    /// std::fs::write(&scene, r#"{"meshes": {"zero": "/dev/zero"}, "instances": [{"mesh": "zero"}]}"#)?;
    /// let policy = FilePolicy::default().with_root(&folder);
    /// let description = SceneDescription::read_with(&scene, &policy)?;
    /// let error = description.build(&ModelOptions::default()).unwrap_err();
    /// assert!(error.to_string().contains("outside the allowed folder"), "{error}");
    /// std::fs::remove_dir_all(&folder)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`SceneDescription::read`].
    pub fn read_with(path: impl AsRef<Path>, policy: &FilePolicy) -> Result<Self, SceneError> {
        let path = path.as_ref();
        let text = policy
            .read_to_string(path)
            .map_err(|error| SceneError::ReadFile {
                path: path.to_owned(),
                source: Box::new(error),
            })?;
        Ok(Self::parse(path, &text)?.with_file_policy(policy.clone()))
    }

    /// The same description, its meshes read by `policy`.
    #[must_use]
    pub fn with_file_policy(mut self, policy: FilePolicy) -> Self {
        self.policy = policy;
        self
    }

    /// The policy the meshes are read by.
    #[must_use]
    pub fn file_policy(&self) -> &FilePolicy {
        &self.policy
    }

    /// Checks the text of a scene file; `path` names it in errors and mesh paths are
    /// relative to its folder.
    ///
    /// # Errors
    ///
    /// As [`SceneDescription::read`], without the reading.
    pub fn parse(path: impl AsRef<Path>, text: &str) -> Result<Self, SceneError> {
        let path = path.as_ref().to_owned();
        let file: SceneFile = serde_json::from_str(text).map_err(|e| SceneError::ParseFile {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let invalid = |place: String, message: String| SceneError::InvalidEntry {
            path: path.clone(),
            place,
            message,
        };
        let mut poses = Vec::with_capacity(file.instances.len());
        for (index, entry) in file.instances.iter().enumerate() {
            let place = format!("instances[{index}] ({:?})", instance_name(entry, index));
            if !file.meshes.contains_key(&entry.mesh) {
                let known: Vec<&str> = file.meshes.keys().map(String::as_str).collect();
                return Err(invalid(
                    place,
                    format!(
                        "mesh `{}` is not defined in `meshes` (defined: {})",
                        entry.mesh,
                        if known.is_empty() {
                            "none".to_owned()
                        } else {
                            known.join(", ")
                        }
                    ),
                ));
            }
            poses.push(pose(entry).map_err(|message| invalid(place, message))?);
        }
        if let Some(name) = file.labels.keys().find(|n| !file.meshes.contains_key(*n)) {
            return Err(invalid(
                format!("labels.{name}"),
                format!("mesh `{name}` is not defined in `meshes`"),
            ));
        }
        let camera = file
            .camera
            .as_ref()
            .map(|c| {
                let camera = Camera::perspective(
                    DVec3::from_array(c.eye),
                    DVec3::from_array(c.target),
                    c.fov_y_degrees,
                    c.width,
                    c.height,
                )?;
                match c.near {
                    Some(near) => camera.with_near(near),
                    None => Ok(camera),
                }
            })
            .transpose()
            .map_err(|e| invalid("camera".to_owned(), e.to_string()))?;
        Ok(Self {
            path,
            policy: FilePolicy::default(),
            file,
            poses,
            camera,
        })
    }

    /// The file as written.
    #[must_use]
    pub fn file(&self) -> &SceneFile {
        &self.file
    }

    /// The camera, if the file has one.
    #[must_use]
    pub fn camera(&self) -> Option<&Camera> {
        self.camera.as_ref()
    }

    /// The file of mesh `name`, resolved against the scene file's folder.
    #[must_use]
    pub fn mesh_path(&self, name: &str) -> Option<PathBuf> {
        let relative = self.file.meshes.get(name)?;
        Some(self.folder().join(relative))
    }

    /// The silhouette label file of mesh `name`, if the scene names one, resolved against
    /// the scene file's folder.
    #[must_use]
    pub fn labels_path(&self, name: &str) -> Option<PathBuf> {
        let relative = self.file.labels.get(name)?;
        Some(self.folder().join(relative))
    }

    /// The folder relative paths start from.
    fn folder(&self) -> &Path {
        self.path.parent().unwrap_or_else(|| Path::new(""))
    }

    /// The names of the meshes some instance uses, sorted.
    #[must_use]
    pub fn used_meshes(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .file
            .instances
            .iter()
            .map(|i| i.mesh.as_str())
            .collect();
        names.sort_unstable();
        names.dedup();
        names
    }

    /// Reads every used mesh (by [`SceneDescription::file_policy`]), builds its model (on
    /// every core with `parallel`), gives it the labels of its label file if the scene
    /// names one (feature `silhouette`), and places the instances.
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidEntry`] naming the mesh (`meshes.NAME`) and its file when it
    /// cannot be read, the policy refuses it, or its model cannot be built; naming the
    /// label file (`labels.NAME`) when it cannot be read, the policy refuses it, or its
    /// labels do not fit the model (another mesh, other settings:
    /// `SceneError::SilhouetteLabels` in the message).
    pub fn build(&self, options: &ModelOptions) -> Result<LoadedScene, SceneError> {
        self.build_with(|name, path| {
            let mesh = sphaera_io::read_with(path, &self.policy)?.mesh;
            ObjectModel::build(name, mesh, options)
        })
    }

    /// As [`SceneDescription::build`], with the caller building each model from its name
    /// and file (to cache models, report progress, or read them from elsewhere). Only
    /// files [`SceneDescription::file_policy`] admits reach `make`, which should read them
    /// by that policy too (`sphaera_io::read_with`). Label files are read here, after
    /// `make`, as [`SceneDescription::build`] reads them.
    ///
    /// # Errors
    ///
    /// As [`SceneDescription::build`].
    pub fn build_with<F>(&self, make: F) -> Result<LoadedScene, SceneError>
    where
        F: Fn(&str, &Path) -> Result<ObjectModel, SceneError> + Sync,
    {
        let names = self.used_meshes();
        let make_one = |name: &&str| -> Result<Arc<ObjectModel>, SceneError> {
            let path = self.mesh_path(name).unwrap_or_default();
            self.policy
                .check_file(&path)
                .map_err(SceneError::from)
                .and_then(|_| make(name, &path))
                .map_err(|e| SceneError::InvalidEntry {
                    path: self.path.clone(),
                    place: format!("meshes.{name} ({})", path.display()),
                    message: e.to_string(),
                })
                .and_then(|model| self.with_labels(name, model))
                .map(Arc::new)
        };
        #[cfg(feature = "parallel")]
        let models: Vec<Arc<ObjectModel>> = {
            use rayon::prelude::*;
            names.par_iter().map(make_one).collect::<Result<_, _>>()?
        };
        #[cfg(not(feature = "parallel"))]
        let models: Vec<Arc<ObjectModel>> = names.iter().map(make_one).collect::<Result<_, _>>()?;
        let mut scene = Scene::new();
        for (index, (entry, pose)) in self.file.instances.iter().zip(&self.poses).enumerate() {
            let Some(k) = names.iter().position(|n| *n == entry.mesh) else {
                continue;
            };
            let Some(model) = models.get(k) else {
                continue;
            };
            scene.add(instance_name(entry, index), Arc::clone(model), *pose);
        }
        Ok(LoadedScene {
            scene,
            camera: self.camera,
            models,
        })
    }
}

impl SceneDescription {
    /// `model` with the labels of mesh `name`'s label file, if the scene names one
    /// (feature `silhouette`; without it the model is returned as it is).
    #[cfg_attr(not(feature = "silhouette"), allow(clippy::unnecessary_wraps))]
    fn with_labels(&self, name: &str, model: ObjectModel) -> Result<ObjectModel, SceneError> {
        #[cfg(feature = "silhouette")]
        if let Some(path) = self.labels_path(name) {
            let with = |model: ObjectModel| -> Result<ObjectModel, String> {
                let labels =
                    sphaera_silhouette::Labels::load_with(&path, model.mesh(), &self.policy)
                        .map_err(|e| format!("model `{name}`: {e}"))?;
                model
                    .with_silhouette_labels(labels)
                    .map_err(|e| e.to_string())
            };
            return with(model).map_err(|message| SceneError::InvalidEntry {
                path: self.path.clone(),
                place: format!("labels.{name} ({})", path.display()),
                message,
            });
        }
        #[cfg(not(feature = "silhouette"))]
        let _ = name;
        Ok(model)
    }
}

fn instance_name(entry: &InstanceEntry, index: usize) -> String {
    entry
        .name
        .clone()
        .unwrap_or_else(|| format!("{}-{index}", entry.mesh))
}

/// The pose of an instance entry, or what is wrong with it.
fn pose(entry: &InstanceEntry) -> Result<Similarity, String> {
    let finite = |name: &str, values: &[f64]| {
        if values.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(format!(
                "`{name}` has a NaN or infinite number ({values:?})"
            ))
        }
    };
    finite("position", &entry.position)?;
    finite("scale", &[entry.scale])?;
    if entry.scale <= 0.0 {
        return Err(format!(
            "`scale` must be positive (got {}); a mirror is not a scale",
            entry.scale
        ));
    }
    let rotation = match (entry.rotation_degrees, entry.quaternion) {
        (Some(_), Some(_)) => {
            return Err("give `rotation_degrees` or `quaternion`, not both".to_owned());
        }
        (Some(r), None) => {
            finite("rotation_degrees", &r)?;
            DQuat::from_euler(
                EulerRot::ZYX,
                r[2].to_radians(),
                r[1].to_radians(),
                r[0].to_radians(),
            )
        }
        (None, Some(q)) => {
            finite("quaternion", &q)?;
            let q = DQuat::from_array(q);
            let norm = q.length();
            if !(norm > 0.5 && norm < 2.0) {
                return Err(format!(
                    "`quaternion` must be a unit quaternion [x, y, z, w] (its norm is {norm})"
                ));
            }
            q / norm
        }
        (None, None) => DQuat::IDENTITY,
    };
    let affine = glam::DAffine3::from_scale_rotation_translation(
        DVec3::splat(entry.scale),
        rotation,
        DVec3::from_array(entry.position),
    );
    Similarity::new(affine).map_err(|e| e.to_string())
}

/// A JSON object of mesh names and files, refusing a name given twice: JSON allows it,
/// but the later file would silently replace the earlier.
fn unique_names<'de, D>(deserializer: D) -> Result<BTreeMap<String, PathBuf>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    struct Names;
    impl<'de> serde::de::Visitor<'de> for Names {
        type Value = BTreeMap<String, PathBuf>;
        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("an object of mesh names and their files")
        }
        fn visit_map<A>(self, mut map: A) -> Result<Self::Value, A::Error>
        where
            A: serde::de::MapAccess<'de>,
        {
            let mut names = BTreeMap::new();
            while let Some((name, file)) = map.next_entry::<String, PathBuf>()? {
                if names.contains_key(&name) {
                    return Err(serde::de::Error::custom(format_args!(
                        "mesh name `{name}` is given twice"
                    )));
                }
                names.insert(name, file);
            }
            Ok(names)
        }
    }
    deserializer.deserialize_map(Names)
}
