//! The sphere-tree: nodes stored level by level, each with its sphere, its construction
//! error, its parent and its children.

use sphaera_mesh::Sphere;

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
