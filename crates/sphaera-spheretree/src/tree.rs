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
    /// minus the centre's distance to the surface; for one outside, radius plus it).
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
    /// use sphaera_spheretree::{DVec3, Sphere, SphereTree, SphereTreeError, TreeNode};
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
    /// assert!(matches!(broken, Err(SphereTreeError::InvalidTree(m)) if m.contains("node 0: child 2")));
    /// # Ok::<(), SphereTreeError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// - [`SphereTreeError::InvalidTree`] naming what is wrong (and the node, by index): a
    ///   branching factor of 0, no nodes, a first level that is not a single root, an
    ///   empty level, a non-finite error, a `level` field other than the level the node is
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
        let bad = |message: String| Err(SphereTreeError::InvalidTree(message));
        if branch == 0 {
            return bad("branch must be at least 1".into());
        }
        if levels.iter().all(Vec::is_empty) {
            return bad("the tree has no nodes".into());
        }
        if levels.first().map(Vec::len) != Some(1) {
            return bad("level 0 must hold exactly the root, node 0".into());
        }
        if let Some(k) = levels.iter().position(Vec::is_empty) {
            return bad(format!("level {k} is empty"));
        }
        let mut level_starts = Vec::with_capacity(levels.len() + 1);
        let mut next = 0_usize;
        for level in &levels {
            level_starts.push(next);
            next += level.len();
        }
        level_starts.push(next);
        if u32::try_from(next).is_err() {
            return bad(format!("{next} nodes: more than 32-bit indices can name"));
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
        let bad = |message: String| {
            Err(SphereTreeError::InvalidTree(format!(
                "node {index}: {message}"
            )))
        };
        let Some(node) = self.nodes.get(index) else {
            return bad("missing".into());
        };
        if !node.sphere.is_valid() {
            return Err(SphereTreeError::InvalidSphere { index });
        }
        if !node.error.is_finite() {
            return bad(format!("error {} is not finite", node.error));
        }
        if node.level as usize != level {
            return bad(format!(
                "level is {}, but it is stored in level {level}",
                node.level
            ));
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
                    return bad(format!("parent {parent} is not in level {above}"));
                }
                let listed = self.nodes.get(parent).is_some_and(|p| {
                    p.children.start as usize <= index && index < p.children.end as usize
                });
                if !listed {
                    return bad(format!("parent {parent} does not list it as a child"));
                }
            }
            (None, Some(_)) => return bad("only the root may have no parent".into()),
            (Some(_), None) => return bad("the root cannot have a parent".into()),
        }
        let children = node.children.clone();
        if children.start > children.end {
            return bad(format!(
                "children {}..{} is not a range",
                children.start, children.end
            ));
        }
        if children.len() > self.branch {
            return bad(format!(
                "{} children, more than the branching factor {}",
                children.len(),
                self.branch
            ));
        }
        let below = range_of(level + 1);
        for child in children {
            let child = child as usize;
            if !below.contains(&child) {
                return bad(format!("child {child} is not in level {}", level + 1));
            }
            if self.nodes.get(child).and_then(|c| c.parent) != u32::try_from(index).ok() {
                return bad(format!("child {child} does not name it as its parent"));
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

    /// The children of node `index`.
    #[must_use]
    pub fn children(&self, index: usize) -> &[TreeNode] {
        self.nodes.get(index).map_or(&[], |n| {
            &self.nodes[n.children.start as usize..n.children.end as usize]
        })
    }
}
