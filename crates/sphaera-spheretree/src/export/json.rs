//! The JSON form of a sphere-tree, written and read back with validation.

use std::io::Write;

use glam::DVec3;
use serde::{Deserialize, Serialize};
use sphaera_mesh::Sphere;

use crate::{SphereTree, SphereTreeError, TreeDefect, TreeNode};

/// The value of [`TreeJson::format`].
pub const JSON_FORMAT: &str = "sphaera-spheretree";

/// The value of [`TreeJson::version`] this crate writes and reads.
pub const JSON_VERSION: u32 = 1;

/// A sphere-tree as JSON. The field names are stable within a [`JSON_VERSION`]:
///
/// ```json
/// {
///   "format": "sphaera-spheretree",
///   "version": 1,
///   "branch": 8,
///   "levels": [ { "first": 0, "count": 1, "worst_error": 0.41 }, … ],
///   "nodes": [
///     { "center": [x, y, z], "radius": r, "error": e, "level": 0,
///       "parent": null, "children": [1, 2, 3], "region_samples": 10000 },
///     …
///   ]
/// }
/// ```
///
/// - `nodes` are stored level by level, root first; a node's index is its position, and
///   parents and children refer to nodes by index.
/// - `levels[k]` gives the index of the first node of level `k`, its node count and its
///   worst (largest) node error.
/// - `error` is the node's construction error ([`TreeNode::error`]), in the mesh's units.
/// - `children` are consecutive indices in the next level (possibly none).
/// - `region_samples` is optional on reading (0 when absent); unknown fields are ignored.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::TreeJson;
/// use sphaera_spheretree::{SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let json = TreeJson::from_tree(&tree);
/// assert_eq!(json.levels.len(), 2);
/// assert_eq!(json.nodes[0].parent, None);
/// assert_eq!(json.to_tree()?, tree);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TreeJson {
    /// Always [`JSON_FORMAT`].
    pub format: String,
    /// Always [`JSON_VERSION`].
    pub version: u32,
    /// The branching factor the tree was built with (a node has at most this many
    /// children).
    pub branch: usize,
    /// One entry per level, root first.
    pub levels: Vec<LevelJson>,
    /// Every node, level by level.
    pub nodes: Vec<NodeJson>,
}

/// One level of a [`TreeJson`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LevelJson {
    /// The index of the level's first node.
    pub first: usize,
    /// The number of nodes of the level.
    pub count: usize,
    /// The largest error of the level's nodes.
    pub worst_error: f64,
    /// How the level's coverage of the whole surface was certified (`null` when it was
    /// not; see [`crate::cover`]).
    #[serde(default)]
    pub coverage: Option<crate::CoverageCertificate>,
}

/// One node of a [`TreeJson`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodeJson {
    /// The sphere's centre.
    pub center: [f64; 3],
    /// The sphere's radius.
    pub radius: f64,
    /// The construction error ([`TreeNode::error`]).
    pub error: f64,
    /// The depth (0 for the root).
    pub level: u32,
    /// The parent's index (`null` for the root).
    pub parent: Option<u32>,
    /// The children's indices, consecutive, in the next level.
    pub children: Vec<u32>,
    /// The number of surface samples of the node's region (0 when unknown).
    #[serde(default)]
    pub region_samples: u32,
}

impl TreeJson {
    /// The JSON form of `tree`.
    ///
    /// # Examples
    ///
    /// See [`TreeJson`].
    ///
    /// # Panics
    ///
    /// Never.
    #[must_use]
    pub fn from_tree(tree: &SphereTree) -> Self {
        let levels = (0..tree.level_count())
            .map(|k| {
                let nodes = tree.level(k);
                LevelJson {
                    first: tree.level_starts.get(k).copied().unwrap_or_default(),
                    count: nodes.len(),
                    worst_error: worst_error(nodes),
                    coverage: tree.coverage().get(k).copied(),
                }
            })
            .collect();
        let nodes = tree
            .nodes()
            .iter()
            .map(|n| NodeJson {
                center: n.sphere.center.to_array(),
                radius: n.sphere.radius,
                error: n.error,
                level: n.level,
                parent: n.parent,
                children: n.children.clone().collect(),
                region_samples: n.region_samples,
            })
            .collect();
        Self {
            format: JSON_FORMAT.to_owned(),
            version: JSON_VERSION,
            branch: tree.branch(),
            levels,
            nodes,
        }
    }

    /// The sphere-tree, after checking that the structure is consistent.
    ///
    /// # Examples
    ///
    /// See [`TreeJson`].
    ///
    /// # Errors
    ///
    /// - [`SphereTreeError::InvalidTree`] naming what is wrong: a `format` or `version`
    ///   other than this crate's, a first level that is not a single root, levels that do
    ///   not tile the nodes in order, children that are not consecutive indices, a
    ///   `worst_error` that is not its level's largest error, or anything
    ///   [`SphereTree::from_levels`] refuses (a branching factor of 0, no nodes, a
    ///   `level`, `parent` or `children` field that disagrees with the levels: children
    ///   not in the next level, more than `branch`, or not naming their parent back; a
    ///   non-finite error).
    /// - [`SphereTreeError::InvalidSphere`] for a NaN or infinite centre or radius, or a
    ///   negative radius, with the node's index.
    ///
    /// # Panics
    ///
    /// Never.
    pub fn to_tree(&self) -> Result<SphereTree, SphereTreeError> {
        let bad = |defect: TreeDefect| Err(SphereTreeError::InvalidTree(defect));
        if self.format != JSON_FORMAT {
            return bad(TreeDefect::WrongFormat {
                found: self.format.clone(),
            });
        }
        if self.version != JSON_VERSION {
            return bad(TreeDefect::UnsupportedVersion {
                version: self.version,
            });
        }
        if self.branch == 0 || self.nodes.is_empty() {
            // `SphereTree::from_levels` names both.
            return SphereTree::from_levels(self.branch, Vec::new());
        }
        if self.levels.first().map(|l| (l.first, l.count)) != Some((0, 1)) {
            return bad(TreeDefect::NotSingleRoot);
        }
        let mut next = 0_usize;
        for (k, level) in self.levels.iter().enumerate() {
            if level.first != next || level.count == 0 {
                return bad(TreeDefect::LevelTiling {
                    level: k,
                    first: level.first,
                    count: level.count,
                    expected: next,
                });
            }
            next = next.saturating_add(level.count);
        }
        if next != self.nodes.len() {
            return bad(TreeDefect::NodeCountMismatch {
                levels: next,
                nodes: self.nodes.len(),
            });
        }
        // The levels tile the nodes in order: split them, and let `from_levels` check the
        // structure (levels, parents, children, spheres, errors).
        let mut levels = Vec::with_capacity(self.levels.len());
        for level in &self.levels {
            let mut nodes = Vec::with_capacity(level.count);
            for index in level.first..level.first + level.count {
                nodes.push(self.node(index)?);
            }
            levels.push(nodes);
        }
        let mut tree = SphereTree::from_levels(self.branch, levels)?;
        for (k, level) in self.levels.iter().enumerate() {
            let actual = worst_error(tree.level(k));
            if level.worst_error.to_bits() != actual.to_bits() {
                return bad(TreeDefect::WorstErrorMismatch {
                    level: k,
                    stored: level.worst_error,
                    actual,
                });
            }
        }
        // Certificates are kept only when every level has one.
        tree.coverage = self
            .levels
            .iter()
            .map(|l| l.coverage)
            .collect::<Option<Vec<_>>>()
            .unwrap_or_default();
        Ok(tree)
    }

    /// Node `index` as a [`TreeNode`]; its children must be consecutive indices (the rest
    /// is checked by [`SphereTree::from_levels`]).
    fn node(&self, index: usize) -> Result<TreeNode, SphereTreeError> {
        let bad = |defect: TreeDefect| Err(SphereTreeError::InvalidTree(defect));
        let Some(node) = self.nodes.get(index) else {
            return bad(TreeDefect::MissingNode { node: index });
        };
        let start = node.children.first().copied().unwrap_or(0);
        let consecutive = node
            .children
            .iter()
            .enumerate()
            .all(|(k, &c)| u32::try_from(k).ok().and_then(|k| start.checked_add(k)) == Some(c));
        if !consecutive {
            return bad(TreeDefect::NonConsecutiveChildren { node: index });
        }
        let end = start.saturating_add(u32::try_from(node.children.len()).unwrap_or(u32::MAX));
        Ok(TreeNode {
            sphere: Sphere::new(DVec3::from_array(node.center), node.radius),
            error: node.error,
            level: node.level,
            parent: node.parent,
            children: if node.children.is_empty() {
                0..0
            } else {
                start..end
            },
            region_samples: node.region_samples,
        })
    }
}

fn worst_error(nodes: &[TreeNode]) -> f64 {
    nodes
        .iter()
        .map(|n| n.error)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// `tree` as pretty-printed JSON ([`TreeJson`]).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{tree_from_json, tree_to_json};
/// use sphaera_spheretree::{SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let text = tree_to_json(&tree);
/// assert!(text.contains("\"format\": \"sphaera-spheretree\""));
/// assert_eq!(tree_from_json(&text)?, tree);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
#[must_use]
pub fn tree_to_json(tree: &SphereTree) -> String {
    // Serialising plain structs of numbers, strings and vectors to a string cannot fail
    // (no maps with non-string keys, no I/O); NaN would become `null`, which the
    // reader then refuses.
    serde_json::to_string_pretty(&TreeJson::from_tree(tree)).unwrap_or_default()
}

/// Reads a sphere-tree written by [`tree_to_json`], checking its structure.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::tree_from_json;
/// use sphaera_spheretree::SphereTreeError;
///
/// let text = r#"{ "format": "sphaera-spheretree", "version": 1, "branch": 2,
///   "levels": [ { "first": 0, "count": 1, "worst_error": 0.5 } ],
///   "nodes": [ { "center": [0, 0, 0], "radius": 1, "error": 0.5, "level": 0,
///                "parent": null, "children": [] } ] }"#;
/// let tree = tree_from_json(text)?;
/// assert_eq!(tree.level_count(), 1);
///
/// let broken = text.replace("\"children\": []", "\"children\": [1]");
/// assert!(matches!(tree_from_json(&broken), Err(SphereTreeError::InvalidTree(_))));
/// assert!(matches!(tree_from_json("{"), Err(SphereTreeError::Json { line: 1, .. })));
/// # Ok::<(), SphereTreeError>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::Json`] (with the line) when the text is not JSON of the
/// [`TreeJson`] shape; otherwise as [`TreeJson::to_tree`].
///
/// # Panics
///
/// Never.
pub fn tree_from_json(text: &str) -> Result<SphereTree, SphereTreeError> {
    let json: TreeJson = serde_json::from_str(text).map_err(|source| SphereTreeError::Json {
        line: source.line(),
        source,
    })?;
    json.to_tree()
}

/// Writes `tree` as JSON ([`tree_to_json`]) to any writer: a file (write it atomically
/// with `sphaera_io::write_atomic`), a socket, a buffer.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{tree_from_json, write_tree_json};
/// use sphaera_spheretree::{SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let mut text = Vec::new();
/// write_tree_json(&mut text, &tree)?;
/// assert_eq!(tree_from_json(std::str::from_utf8(&text)?)?, tree);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// The writer's error.
///
/// # Panics
///
/// Never.
pub fn write_tree_json(mut out: impl Write, tree: &SphereTree) -> std::io::Result<()> {
    out.write_all(tree_to_json(tree).as_bytes())
}
