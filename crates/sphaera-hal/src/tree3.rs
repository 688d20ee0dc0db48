//! The 3D HAL tree (section 4 of the paper): a closed genus-0 mesh kept as a tree of
//! triangles on its own vertices, each standing for a patch of the surface bounded by
//! three shortest edge paths, refined level by level (Algorithm 2).

mod bound;
mod gaps;
mod layout;
mod placement;
mod refine;

use sphaera_mesh::{Aabb, Sphere, TriMesh};

use crate::HalError;
use crate::surface3::{GenusZeroSurface, RootBall};

pub use bound::Bound3;
pub(crate) use bound::circle;
use gaps::close_gaps;
pub(crate) use layout::{FlatNode, Layout};

/// Angles below this are not split: such a triangle is split at its sides instead (the
/// paper's "arbitrarily set to π/4").
pub const SMALLEST_SPLIT_ANGLE: f64 = std::f64::consts::FRAC_PI_4;

/// One node of a [`HalTree3`]: an approximating triangle and the patch it stands for.
#[derive(Clone, Debug, PartialEq)]
pub struct Node3 {
    /// The corners (mesh vertex indices), counter-clockwise seen from outside.
    pub corners: [u32; 3],
    /// The level: the two root triangles are at level 0.
    pub level: u32,
    /// The patch's faces (mesh triangle indices, ascending).
    pub faces: Vec<u32>,
    /// The bounding volume; `None` for a leaf (an original face).
    pub bound: Option<Bound3>,
    /// `max(w₁, w₂)` (0 for a leaf).
    pub width: f64,
    /// The children (empty for a leaf).
    pub children: Vec<u32>,
    /// The node's three sides (ids shared with the neighbours across them).
    sides: [u32; 3],
}

/// A side of an approximating triangle: its ends and the shortest edge path between them
/// (from `from` to `to`), shared by the two triangles on either side.
#[derive(Clone, Debug)]
struct Side {
    path: Vec<u32>,
    /// Once split: the vertex and the two halves (from `path[0]`, then to its end).
    halves: Option<(u32, [u32; 2])>,
}

/// A hierarchical approximation and localization tree of a closed genus-0 mesh.
#[derive(Clone, Debug)]
pub struct HalTree3 {
    surface: GenusZeroSurface,
    root: RootBall,
    nodes: Vec<Node3>,
    /// The root triangles (one or two).
    roots: Vec<u32>,
    sides: Vec<Side>,
    /// The mesh's bounding box, kept so that no query scans the mesh.
    bounds: Aabb,
    /// The nodes laid out for queries: per node its patch's bounding box (a cheap, tight
    /// first cull before the bounding volume's) and its volume, children contiguous, the
    /// leaves' triangles by value.
    layout: Layout,
}

impl HalTree3 {
    /// Builds the complete tree (Algorithm 2).
    ///
    /// # Errors
    ///
    /// As [`GenusZeroSurface::new`] and [`GenusZeroSurface::root`].
    pub fn build(mesh: &TriMesh) -> Result<Self, HalError> {
        let surface = GenusZeroSurface::new(mesh)?;
        let root = surface.root()?;
        let [i, j, k] = root.vertices;
        let bounds = surface.mesh().bounding_box();
        let mut tree = Self {
            surface,
            root,
            nodes: Vec::new(),
            roots: Vec::new(),
            sides: Vec::new(),
            bounds,
            layout: Layout::default(),
        };
        let ij = tree.new_side(tree.surface.shortest_path(i, j));
        let jk = tree.new_side(tree.surface.shortest_path(j, k));
        let ki = tree.new_side(tree.surface.shortest_path(k, i));
        let all: Vec<u32> = (0..tree.surface.mesh().triangle_count() as u32).collect();
        let candidates = vec![([i, j, k], [ij, jk, ki]), ([i, k, j], [ki, jk, ij])];
        let level: Vec<u32> = tree.place(&all, &candidates, 0);
        tree.roots = level.clone();
        let mut frontier = level;
        while !frontier.is_empty() {
            frontier = tree.refine(&frontier);
        }
        tree.layout = Layout::new(&tree);
        Ok(tree)
    }

    /// The query layout.
    pub(crate) fn layout(&self) -> &Layout {
        &self.layout
    }

    fn new_side(&mut self, path: Vec<u32>) -> u32 {
        self.sides.push(Side { path, halves: None });
        (self.sides.len() - 1) as u32
    }

    /// The path of side `side` walked from corner `from`.
    fn side_path(&self, side: u32, from: u32) -> Vec<u32> {
        let path = &self.sides[side as usize].path;
        if path.first() == Some(&from) {
            path.clone()
        } else {
            path.iter().rev().copied().collect()
        }
    }

    /// The mesh the tree was built on.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        self.surface.mesh()
    }

    /// The nodes.
    #[must_use]
    pub fn nodes(&self) -> &[Node3] {
        &self.nodes
    }

    /// The root triangles (one or two: the three root paths may leave one patch).
    #[must_use]
    pub fn roots(&self) -> &[u32] {
        &self.roots
    }

    /// The root ball.
    #[must_use]
    pub fn root_ball(&self) -> Sphere {
        self.root.sphere
    }

    /// The mesh's bounding box (kept from the build).
    #[must_use]
    pub fn bounding_box(&self) -> Aabb {
        self.bounds
    }

    /// The deepest level.
    #[must_use]
    pub fn depth(&self) -> u32 {
        self.nodes.iter().map(|n| n.level).max().unwrap_or(0)
    }

    /// The approximation at `level`: the triangles of that level, and the leaves above
    /// it, as a watertight mesh on the input's vertices: every edge is used as often in
    /// one direction as in the other (where a filled gap meets the level, an edge can
    /// carry four triangles). The deepest level is the input mesh.
    ///
    /// Two things open gaps in a level, both from the paper's construction: a triangle
    /// whose paths coalesce is discarded (it approximates no face), and a patch that cannot
    /// be split as the paper says is split at its most central vertex, or into its faces,
    /// without the side splits its neighbours made. Each gap's boundary is a loop of the
    /// level's edges; it is closed by a fan of triangles on the loop's vertices (for a
    /// discarded triangle, that triangle itself), so that every edge has as many
    /// triangles on one side as on the other.
    ///
    /// # Errors
    ///
    /// As [`TriMesh::new`] (cannot fail for a tree's own vertices).
    pub fn level(&self, level: u32) -> Result<TriMesh, HalError> {
        self.extract(|node| node.level < level)
    }

    /// The adaptive approximation (section 4.3): a triangle is refined only when its own
    /// width (Definition 6) exceeds `tolerance`. Where a neighbour refined past a shared
    /// side (a T-junction) and where a level has gaps, the gap is closed as in
    /// [`HalTree3::level`]: the mesh is watertight.
    ///
    /// # Errors
    ///
    /// As [`HalTree3::level`].
    pub fn approximate(&self, tolerance: f64) -> Result<TriMesh, HalError> {
        self.extract(|node| node.width > tolerance)
    }

    /// The covering error of the approximation that refines the nodes `refine` accepts
    /// (through refined parents): the largest width of the triangles it keeps (0 for
    /// original faces). `|n| n.level < level` gives [`HalTree3::level`]'s, `|n| n.width >
    /// tolerance` [`HalTree3::approximate`]'s.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::HalTree3;
    ///
    /// let tree = HalTree3::build(&sphaera_mesh::shapes::sphere(1.0, 12)?)?;
    /// assert_eq!(tree.kept_width(|_| true), 0.0);
    /// assert!(tree.kept_width(|_| false) > 0.0);
    /// // The adaptive approximation keeps only triangles within its tolerance.
    /// assert!(tree.kept_width(|n| n.width > 0.05) <= 0.05);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn kept_width(&self, refine: impl Fn(&Node3) -> bool) -> f64 {
        let mut stack: Vec<u32> = self.roots.clone();
        let mut largest: f64 = 0.0;
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if node.children.is_empty() || !refine(node) {
                largest = largest.max(node.width);
            } else {
                stack.extend(node.children.iter().copied());
            }
        }
        largest
    }

    /// The triangles reached from the roots, descending where `refine` says so, with the
    /// gaps closed.
    fn extract(&self, refine: impl Fn(&Node3) -> bool) -> Result<TriMesh, HalError> {
        let mut triangles = Vec::new();
        let mut stack: Vec<u32> = self.roots.clone();
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if node.children.is_empty() || !refine(node) {
                triangles.push(node.corners);
            } else {
                stack.extend(node.children.iter().copied());
            }
        }
        triangles.sort_unstable();
        close_gaps(&mut triangles);
        Ok(TriMesh::new(
            self.surface.mesh().positions().to_vec(),
            triangles,
        )?)
    }
}
