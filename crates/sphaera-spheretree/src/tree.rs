//! The sphere-tree: nodes stored level by level, each with its sphere, its construction
//! error, its parent and its children.

use sphaera_mesh::Sphere;

use crate::SphereTreeError;
use crate::cover::CoverageCertificate;

/// One node of a [`SphereTree`].
#[derive(Debug, Clone, PartialEq)]
pub struct TreeNode {
    /// The sphere.
    pub sphere: Sphere,
    /// Its construction error: the paper's eq. 2 (for a centre inside the object, radius
    /// minus the centre's distance to the surface; for one outside, radius plus it), an
    /// upper bound on the sphere's certified error. The medial methods compute it in the
    /// mesh's canonical pose and add what can separate it from the value on the mesh
    /// itself: the pose's snapping displacement and any growth of the coverage certificate.
    pub error: f64,
    /// The depth of the node (0 for the root).
    pub level: u32,
    /// The parent node's index (`None` for the root).
    pub parent: Option<u32>,
    /// The children's indices (consecutive, in the next level).
    pub children: std::ops::Range<u32>,
    /// The number of surface samples in the node's region.
    pub region_samples: u32,
}

/// A sphere-tree: the root is the minimum enclosing ball of the mesh; each node's
/// children cover the part of the surface assigned to it.
#[derive(Debug, Clone, PartialEq)]
pub struct SphereTree {
    pub(crate) branch: usize,
    pub(crate) nodes: Vec<TreeNode>,
    /// Index of the first node of each level, plus the node count at the end.
    pub(crate) level_starts: Vec<usize>,
    /// Per level, the surface-coverage certificate (empty when not certified).
    pub(crate) coverage: Vec<CoverageCertificate>,
}

impl SphereTree {
    /// A sphere-tree from its nodes, level by level (`levels[0]` holds the root), after
    /// checking that they form one: the validated way to make a tree that was not built
    /// by [`crate::build`] (a tree from another tool, a synthetic tree in a test). The
    /// JSON reader ([`crate::export::TreeJson::to_tree`]) goes through it.
    ///
    /// A node's index is its position in the concatenated levels; `parent` and `children`
    /// refer to nodes by index. The tree carries no coverage certificate
    /// ([`SphereTree::coverage`] is empty).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::{DVec3, Sphere, SphereTree, SphereTreeError, TreeDefect, TreeNode};
    ///
    /// let node = |x: f64, radius: f64, level: u32, parent: Option<u32>| TreeNode {
    ///     sphere: Sphere::new(DVec3::new(x, 0.0, 0.0), radius),
    ///     error: 0.1 * radius,
    ///     level,
    ///     parent,
    ///     children: 0..0,
    ///     region_samples: 0,
    /// };
    /// let root = TreeNode { children: 1..3, ..node(0.0, 2.0, 0, None) };
    /// let leaves = vec![node(-1.0, 1.0, 1, Some(0)), node(1.0, 1.0, 1, Some(0))];
    /// let tree = SphereTree::from_levels(2, vec![vec![root.clone()], leaves.clone()])?;
    /// assert_eq!(tree.level_count(), 2);
    /// assert_eq!(tree.children(0), &leaves[..]);
    ///
    /// // A child that does not name its parent back is refused, and says where.
    /// let orphan = TreeNode { parent: None, ..leaves[1].clone() };
    /// let broken = SphereTree::from_levels(2, vec![vec![root], vec![leaves[0].clone(), orphan]]);
    /// assert!(matches!(
    ///     broken,
    ///     Err(SphereTreeError::InvalidTree(TreeDefect::ChildDisowns { node: 0, child: 2 }))
    /// ));
    /// # Ok::<(), SphereTreeError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// - [`SphereTreeError::InvalidTree`] naming what is wrong (and the node, by index): a
    ///   branching factor of 0, no nodes, a first level that is not a single root, an
    ///   empty level, a sphere of radius 0, a non-finite error, a `level` field other than the level the node is
    ///   stored in, a parent outside the level above or that does not list the node among
    ///   its children, a root with a parent or another node without one, more children
    ///   than `branch`, a decreasing `children` range, children outside the next level or
    ///   that do not name the node as their parent.
    /// - [`SphereTreeError::InvalidSphere`] for a NaN or infinite centre or radius, or a
    ///   negative radius, with the node's index.
    ///
    /// # Panics
    ///
    /// Never.
    pub fn from_levels(branch: usize, levels: Vec<Vec<TreeNode>>) -> Result<Self, SphereTreeError> {
        let bad = |defect: TreeDefect| Err(SphereTreeError::InvalidTree(defect));
        if branch == 0 {
            return bad(TreeDefect::NoBranch);
        }
        if levels.iter().all(Vec::is_empty) {
            return bad(TreeDefect::NoNodes);
        }
        if levels.first().map(Vec::len) != Some(1) {
            return bad(TreeDefect::NotSingleRoot);
        }
        if let Some(level) = levels.iter().position(Vec::is_empty) {
            return bad(TreeDefect::EmptyLevel { level });
        }
        let mut level_starts = Vec::with_capacity(levels.len() + 1);
        let mut next = 0_usize;
        for level in &levels {
            level_starts.push(next);
            next += level.len();
        }
        level_starts.push(next);
        if u32::try_from(next).is_err() {
            return bad(TreeDefect::TooManyNodes { count: next });
        }
        let nodes: Vec<TreeNode> = levels.into_iter().flatten().collect();
        let tree = Self {
            branch,
            nodes,
            level_starts,
            coverage: Vec::new(),
        };
        for level in 0..tree.level_count() {
            for index in tree.level_starts[level]..tree.level_starts[level + 1] {
                tree.check_node(index, level)?;
            }
        }
        Ok(tree)
    }

    /// Node `index`, stored in level `level`, checked against its parent and children.
    fn check_node(&self, index: usize, level: usize) -> Result<(), SphereTreeError> {
        let bad = |defect: TreeDefect| Err(SphereTreeError::InvalidTree(defect));
        let Some(node) = self.nodes.get(index) else {
            return bad(TreeDefect::MissingNode { node: index });
        };
        if !node.sphere.is_valid() {
            return Err(SphereTreeError::InvalidSphere { index });
        }
        if node.sphere.radius == 0.0 {
            return bad(TreeDefect::ZeroRadius { node: index });
        }
        if !node.error.is_finite() {
            return bad(TreeDefect::NonFiniteError {
                node: index,
                error: node.error,
            });
        }
        if node.level as usize != level {
            return bad(TreeDefect::WrongLevel {
                node: index,
                field: node.level,
                stored: level,
            });
        }
        let range_of = |k: usize| match (self.level_starts.get(k), self.level_starts.get(k + 1)) {
            (Some(&a), Some(&b)) => a..b,
            _ => 0..0,
        };
        match (node.parent, level.checked_sub(1)) {
            (None, None) => {}
            (Some(parent), Some(above)) => {
                let parent = parent as usize;
                if !range_of(above).contains(&parent) {
                    return bad(TreeDefect::ParentNotAbove {
                        node: index,
                        parent,
                        level: above,
                    });
                }
                let listed = self.nodes.get(parent).is_some_and(|p| {
                    p.children.start as usize <= index && index < p.children.end as usize
                });
                if !listed {
                    return bad(TreeDefect::NotListedByParent {
                        node: index,
                        parent,
                    });
                }
            }
            (None, Some(_)) => return bad(TreeDefect::NoParent { node: index }),
            (Some(_), None) => return bad(TreeDefect::RootWithParent { node: index }),
        }
        let children = node.children.clone();
        if children.start > children.end {
            return bad(TreeDefect::ChildrenNotARange {
                node: index,
                start: children.start,
                end: children.end,
            });
        }
        if children.len() > self.branch {
            return bad(TreeDefect::TooManyChildren {
                node: index,
                children: children.len(),
                branch: self.branch,
            });
        }
        let below = range_of(level + 1);
        for child in children {
            let child = child as usize;
            if !below.contains(&child) {
                return bad(TreeDefect::ChildNotBelow {
                    node: index,
                    child,
                    level: level + 1,
                });
            }
            if self.nodes.get(child).and_then(|c| c.parent) != u32::try_from(index).ok() {
                return bad(TreeDefect::ChildDisowns { node: index, child });
            }
        }
        Ok(())
    }

    /// The branching factor it was built with (a node has at most this many children).
    #[must_use]
    pub fn branch(&self) -> usize {
        self.branch
    }

    /// Every node, level by level (the root first).
    #[must_use]
    pub fn nodes(&self) -> &[TreeNode] {
        &self.nodes
    }

    /// The number of levels, the root's included.
    #[must_use]
    pub fn level_count(&self) -> usize {
        self.level_starts.len().saturating_sub(1)
    }

    /// The nodes of level `level` (empty beyond the deepest).
    #[must_use]
    pub fn level(&self, level: usize) -> &[TreeNode] {
        match (
            self.level_starts.get(level),
            self.level_starts.get(level + 1),
        ) {
            (Some(&a), Some(&b)) => &self.nodes[a..b],
            _ => &[],
        }
    }

    /// The spheres of level `level`.
    #[must_use]
    pub fn level_spheres(&self, level: usize) -> Vec<Sphere> {
        self.level(level).iter().map(|n| n.sphere).collect()
    }

    /// Per level, how its coverage of the whole surface was certified
    /// ([`crate::cover::certify_coverage`]): empty when the tree was built without
    /// certification ([`crate::SphereTreeOptions::certify_coverage`] off).
    #[must_use]
    pub fn coverage(&self) -> &[CoverageCertificate] {
        &self.coverage
    }

    /// The leaves (nodes without children), by index, ascending: the finest spheres of
    /// every part of the surface. For a tree built to a tolerance they are the spheres
    /// that meet it.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_query::Surface;
    /// use sphaera_mesh::shapes;
    /// use sphaera_spheretree::{SphereTreeOptions, build};
    ///
    /// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
    /// let tree = build(&surface, &SphereTreeOptions::default().with_depth(2).with_branch(4))?;
    /// assert_eq!(tree.leaves().len(), tree.level(2).len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn leaves(&self) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| self.nodes[i].children.is_empty())
            .collect()
    }

    /// The cut at depth `level`: the nodes of that level and the leaves above it, by
    /// index, ascending. It covers what the whole tree covers, at the detail of `level`
    /// where the tree reaches that deep: what a traversal that stops at `level` tests.
    /// In a tree whose every node above the deepest level has children (a tree built to a
    /// depth) it is the level itself; in a tree built to a tolerance, shallower leaves
    /// stand in where no deeper node was needed. Beyond the deepest level, the leaves.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{Length, shapes};
    /// use sphaera_query::Surface;
    /// use sphaera_spheretree::{SphereTreeOptions, build};
    ///
    /// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
    /// let tree = build(&surface, &SphereTreeOptions::default().with_depth(2).with_branch(4))?;
    /// let cut: Vec<usize> = tree.cut_at(1);
    /// assert_eq!(cut.len(), tree.level(1).len());
    /// assert_eq!(tree.cut_at(7), tree.leaves());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn cut_at(&self, level: usize) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| {
                let node = &self.nodes[i];
                let depth = node.level as usize;
                depth == level || (depth < level && node.children.is_empty())
            })
            .collect()
    }

    /// The spheres of [`SphereTree::cut_at`]`(level)`.
    #[must_use]
    pub fn cut_spheres(&self, level: usize) -> Vec<Sphere> {
        self.cut_at(level)
            .into_iter()
            .map(|i| self.nodes[i].sphere)
            .collect()
    }

    /// The children of node `index`.
    #[must_use]
    pub fn children(&self, index: usize) -> &[TreeNode] {
        self.nodes.get(index).map_or(&[], |n| {
            &self.nodes[n.children.start as usize..n.children.end as usize]
        })
    }
}

/// What makes a sphere-tree inconsistent, in [`SphereTreeError::InvalidTree`]: found by
/// [`SphereTree::from_levels`] or by the JSON reader.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TreeDefect {
    /// The branching factor is 0.
    #[error("branch must be at least 1")]
    NoBranch,
    /// There is no node.
    #[error("the tree has no nodes")]
    NoNodes,
    /// The first level is not the root alone.
    #[error("level 0 must hold exactly the root, node 0")]
    NotSingleRoot,
    /// A level holds no node.
    #[error("level {level} is empty")]
    EmptyLevel {
        /// The level.
        level: usize,
    },
    /// More nodes than 32-bit indices name.
    #[error("{count} nodes: more than 32-bit indices can name")]
    TooManyNodes {
        /// The node count.
        count: usize,
    },
    /// A node is missing.
    #[error("node {node}: missing")]
    MissingNode {
        /// The node.
        node: usize,
    },
    /// A node's sphere has radius 0: a node stands for part of a surface, which a point
    /// cannot bound.
    #[error("node {node}: its sphere has radius 0, but a node stands for part of a surface")]
    ZeroRadius {
        /// The node.
        node: usize,
    },
    /// A node's error is NaN or infinite.
    #[error("node {node}: error {error} is not finite")]
    NonFiniteError {
        /// The node.
        node: usize,
        /// Its error.
        error: f64,
    },
    /// A node's `level` field disagrees with the level it is stored in.
    #[error("node {node}: level is {field}, but it is stored in level {stored}")]
    WrongLevel {
        /// The node.
        node: usize,
        /// Its `level` field.
        field: u32,
        /// The level it is stored in.
        stored: usize,
    },
    /// A node's parent is not in the level above.
    #[error("node {node}: parent {parent} is not in level {level}")]
    ParentNotAbove {
        /// The node.
        node: usize,
        /// Its parent.
        parent: usize,
        /// The level above.
        level: usize,
    },
    /// A node's parent does not list it among its children.
    #[error("node {node}: parent {parent} does not list it as a child")]
    NotListedByParent {
        /// The node.
        node: usize,
        /// Its parent.
        parent: usize,
    },
    /// A node below the root has no parent.
    #[error("node {node}: only the root may have no parent")]
    NoParent {
        /// The node.
        node: usize,
    },
    /// The root has a parent.
    #[error("node {node}: the root cannot have a parent")]
    RootWithParent {
        /// The node.
        node: usize,
    },
    /// A node's `children` range decreases.
    #[error("node {node}: children {start}..{end} is not a range")]
    ChildrenNotARange {
        /// The node.
        node: usize,
        /// The range's start.
        start: u32,
        /// The range's end.
        end: u32,
    },
    /// A node has more children than the branching factor.
    #[error("node {node}: {children} children, more than the branching factor {branch}")]
    TooManyChildren {
        /// The node.
        node: usize,
        /// Its children.
        children: usize,
        /// The branching factor.
        branch: usize,
    },
    /// A child is not in the level below.
    #[error("node {node}: child {child} is not in level {level}")]
    ChildNotBelow {
        /// The node.
        node: usize,
        /// The child.
        child: usize,
        /// The level below.
        level: usize,
    },
    /// A child does not name the node as its parent.
    #[error("node {node}: child {child} does not name it as its parent")]
    ChildDisowns {
        /// The node.
        node: usize,
        /// The child.
        child: usize,
    },
    /// JSON: the children of a node are not consecutive increasing indices.
    #[error("node {node}: children are not consecutive increasing indices")]
    NonConsecutiveChildren {
        /// The node.
        node: usize,
    },
    /// JSON: the format tag is not this crate's.
    #[error("format is {found:?}, expected \"sphaera-spheretree\"")]
    WrongFormat {
        /// The tag found.
        found: String,
    },
    /// JSON: a version this reader does not read.
    #[error("version {version} is not supported (this reader reads version 1)")]
    UnsupportedVersion {
        /// The version found.
        version: u32,
    },
    /// JSON: the levels do not tile the nodes in order.
    #[error(
        "level {level} starts at node {first} with {count} nodes; expected a non-empty level starting at node {expected}"
    )]
    LevelTiling {
        /// The level.
        level: usize,
        /// Its first node.
        first: usize,
        /// Its node count.
        count: usize,
        /// Where it should start.
        expected: usize,
    },
    /// JSON: the levels hold a different number of nodes than the node list.
    #[error("the levels hold {levels} nodes but there are {nodes}")]
    NodeCountMismatch {
        /// Nodes the levels hold.
        levels: usize,
        /// Nodes listed.
        nodes: usize,
    },
    /// JSON: a level's `worst_error` is not its largest node error.
    #[error("level {level} has worst_error {stored} but its largest node error is {actual}")]
    WorstErrorMismatch {
        /// The level.
        level: usize,
        /// The `worst_error` written.
        stored: f64,
        /// The largest node error.
        actual: f64,
    },
}
