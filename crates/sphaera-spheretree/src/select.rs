//! Model no more than a scene needs: the shallowest level, or the smallest cut through
//! the tree, whose worst error meets a tolerance.
//!
//! The error of a node is its construction error, [`TreeNode::error`]: how far the
//! node's sphere reaches beyond the object. Tolerances are in the tree's units (the
//! mesh's); for an object placed in a scene with a uniform scale `s`, divide a scene
//! tolerance by `s`.
//!
//! A negative or NaN tolerance is met by no node.
//!
//! [`TreeNode::error`]: crate::TreeNode::error

use sphaera_mesh::Sphere;

use crate::SphereTree;

/// The worst (largest) node error of each level, root first.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::select::level_worst_errors;
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
/// let worst = level_worst_errors(&tree);
/// assert_eq!(worst.len(), tree.level_count());
/// assert!(worst[1] < worst[0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
#[must_use]
pub fn level_worst_errors(tree: &SphereTree) -> Vec<f64> {
    (0..tree.level_count())
        .map(|level| {
            tree.level(level)
                .iter()
                .map(|n| n.error)
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

/// The shallowest level whose worst node error is at most `tolerance`; `None` when no
/// level meets it (nor for a negative or NaN tolerance).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::select::{level_for_tolerance, level_worst_errors};
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
/// let worst = level_worst_errors(&tree);
/// assert_eq!(level_for_tolerance(&tree, worst[0]), Some(0));
/// assert_eq!(level_for_tolerance(&tree, worst[1]), Some(1));
/// assert_eq!(level_for_tolerance(&tree, worst[1] / 2.0), None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
#[must_use]
pub fn level_for_tolerance(tree: &SphereTree, tolerance: f64) -> Option<usize> {
    level_worst_errors(tree)
        .iter()
        .position(|&worst| worst <= tolerance)
}

/// The spheres of [`level_for_tolerance`]'s level; `None` when no level meets
/// `tolerance`.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::select::spheres_for_tolerance;
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
/// assert_eq!(spheres_for_tolerance(&tree, f64::INFINITY), Some(tree.level_spheres(0)));
/// assert_eq!(spheres_for_tolerance(&tree, -1.0), None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
#[must_use]
pub fn spheres_for_tolerance(tree: &SphereTree, tolerance: f64) -> Option<Vec<Sphere>> {
    level_for_tolerance(tree, tolerance).map(|level| tree.level_spheres(level))
}

/// A cut through a sphere-tree: a set of nodes, possibly of different levels, such that
/// every path from the root to a leaf holds exactly one of them. Its spheres cover what
/// every level covers: the union of a node's children's regions is the node's region.
#[derive(Clone, Debug, PartialEq)]
pub struct Cut {
    /// The nodes (indices into [`SphereTree::nodes`]), in increasing order.
    pub nodes: Vec<usize>,
    /// The largest error of the cut's nodes (`-∞` for an empty tree).
    pub worst_error: f64,
    /// Whether every node meets the tolerance (a leaf that does not is kept anyway).
    pub meets_tolerance: bool,
}

impl Cut {
    /// The cut's spheres, in the order of [`Cut::nodes`].
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::select::cut_for_tolerance;
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
    /// let cut = cut_for_tolerance(&tree, f64::INFINITY);
    /// assert_eq!(cut.spheres(&tree), tree.level_spheres(0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never (indices beyond `tree`'s nodes, from a cut of another tree, are skipped).
    #[must_use]
    pub fn spheres(&self, tree: &SphereTree) -> Vec<Sphere> {
        self.nodes
            .iter()
            .filter_map(|&i| tree.nodes().get(i).map(|n| n.sphere))
            .collect()
    }
}

/// The smallest cut whose nodes all meet `tolerance`: from the root down, a node is kept
/// when its error is at most `tolerance`, else replaced by its children (a leaf is kept
/// whatever its error, and [`Cut::meets_tolerance`] is then false).
///
/// It is the cut with the fewest nodes among those whose nodes meet the tolerance (each
/// kept node is the shallowest on its paths that meets it, and a subtree holds at least
/// one node of any cut). When every node above the deepest level has children (as
/// [`build`](crate::build) makes them), it never has more spheres than
/// [`level_for_tolerance`]'s level: it may mix a coarse sphere where the object is simple with fine ones where it
/// is not.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::select::{cut_for_tolerance, level_worst_errors};
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
/// let worst = level_worst_errors(&tree);
///
/// let cut = cut_for_tolerance(&tree, worst[1]);
/// assert!(cut.meets_tolerance && cut.worst_error <= worst[1]);
/// assert!(cut.nodes.len() <= tree.level(1).len());
///
/// let too_tight = cut_for_tolerance(&tree, 0.0);
/// assert!(!too_tight.meets_tolerance);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
#[must_use]
pub fn cut_for_tolerance(tree: &SphereTree, tolerance: f64) -> Cut {
    let nodes = tree.nodes();
    let mut kept = Vec::new();
    let mut stack: Vec<usize> = (0..tree.level(0).len()).collect();
    while let Some(i) = stack.pop() {
        let Some(node) = nodes.get(i) else { continue };
        let end = (node.children.end as usize).min(nodes.len());
        let start = (node.children.start as usize).min(end);
        if node.error <= tolerance || start == end {
            kept.push(i);
        } else {
            stack.extend(start..end);
        }
    }
    kept.sort_unstable();
    let worst_error = kept
        .iter()
        .filter_map(|&i| nodes.get(i))
        .map(|n| n.error)
        .fold(f64::NEG_INFINITY, f64::max);
    let meets_tolerance = kept
        .iter()
        .filter_map(|&i| nodes.get(i))
        .all(|n| n.error <= tolerance);
    Cut {
        nodes: kept,
        worst_error,
        meets_tolerance,
    }
}
