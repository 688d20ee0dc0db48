//! The sphere-tree file formats by name or extension, and one writer for all of them.

use std::fmt;
use std::io::Write;
use std::path::Path;
use std::str::FromStr;

use glam::DVec3;

use super::{CollisionLink, SphFile, collision_spheres_yaml, tree_to_json, write_sph};
use crate::{SphereTree, SphereTreeError};

/// A file format for a whole sphere-tree.
///
/// # Examples
///
/// ```
/// use std::path::Path;
/// use sphaera_spheretree::export::TreeFormat;
///
/// assert_eq!(TreeFormat::from_path(Path::new("bunny.SPH")), Some(TreeFormat::Sph));
/// assert_eq!(TreeFormat::from_path(Path::new("bunny.yml")), Some(TreeFormat::Yaml));
/// assert_eq!(TreeFormat::from_path(Path::new("bunny.obj")), None);
/// assert_eq!("json".parse::<TreeFormat>(), Ok(TreeFormat::Json));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TreeFormat {
    /// The library's JSON ([`tree_to_json`]): every node, read back with validation.
    Json,
    /// The original toolkit's `.sph` text ([`SphFile`]): a complete tree of fixed branch.
    Sph,
    /// The YAML collision-spheres list of motion planners ([`collision_spheres_yaml`]):
    /// the tree's leaves, named after the mesh.
    Yaml,
}

impl TreeFormat {
    /// The format for a file extension (`json`, `sph`, `yaml` or `yml`, in any case).
    pub fn from_extension(extension: &str) -> Option<Self> {
        match extension.to_ascii_lowercase().as_str() {
            "json" => Some(Self::Json),
            "sph" => Some(Self::Sph),
            "yaml" | "yml" => Some(Self::Yaml),
            _ => None,
        }
    }

    /// The format for a path's extension.
    pub fn from_path(path: &Path) -> Option<Self> {
        path.extension()
            .and_then(|e| e.to_str())
            .and_then(Self::from_extension)
    }

    /// The format's usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Json => "json",
            Self::Sph => "sph",
            Self::Yaml => "yaml",
        }
    }
}

impl fmt::Display for TreeFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.extension())
    }
}

/// A name that is not a [`TreeFormat`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown sphere-tree format `{0}` (use json, sph or yaml)")]
pub struct ParseTreeFormatError(pub String);

impl FromStr for TreeFormat {
    type Err = ParseTreeFormatError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_extension(s).ok_or_else(|| ParseTreeFormatError(s.to_owned()))
    }
}

/// The text of `tree` in `format`; `name` names the collision link of the YAML list (the
/// mesh's name, say).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{TreeFormat, tree_to_text};
/// use sphaera_spheretree::{SphereTreeOptions, Surface, build};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default().with_depth(1).with_branch(4).with_samples(400);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let yaml = tree_to_text(&tree, TreeFormat::Yaml, "capsule")?;
/// assert!(yaml.starts_with("collision_spheres:"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::SphLayout`] when `.sph`'s complete tree would need too many slots
/// (a deep tree: write JSON or YAML, which store only the nodes the tree has); the YAML
/// writer's errors.
pub fn tree_to_text(
    tree: &SphereTree,
    format: TreeFormat,
    name: &str,
) -> Result<String, SphereTreeError> {
    match format {
        TreeFormat::Json => Ok(tree_to_json(tree)),
        TreeFormat::Sph => write_sph(&SphFile::from_tree(tree)?, DVec3::ZERO),
        TreeFormat::Yaml => {
            let leaves = tree
                .leaves()
                .into_iter()
                .map(|i| tree.nodes()[i].sphere)
                .collect();
            collision_spheres_yaml(&[CollisionLink::new(name, leaves)])
        }
    }
}

/// Writes [`tree_to_text`] to any writer (a file: write it atomically with
/// `sphaera_io::write_atomic`).
///
/// # Errors
///
/// As [`tree_to_text`]; [`SphereTreeError::Write`] when the writer fails.
pub fn write_tree(
    mut out: impl Write,
    tree: &SphereTree,
    format: TreeFormat,
    name: &str,
) -> Result<(), SphereTreeError> {
    let text = tree_to_text(tree, format, name)?;
    out.write_all(text.as_bytes())
        .map_err(SphereTreeError::Write)
}
