//! The search for contacts between triangles: every pair of triangles whose boxes touch,
//! found with the closest-point tree's boxes, goes to the exact
//! [`improper_contact`] predicate.

use glam::DVec3;
use smallvec::SmallVec;

use super::intersect::improper_contact;
use crate::closest::TriangleTree;
use sphaera_mesh::Aabb;

/// The first pair of mesh triangles (smallest `(first, second)`, `first < second`) that
/// meet in more than the vertices they share, or `None`.
///
/// Each leaf of the tree looks for the leaves at or after it (in tree order) whose boxes
/// touch its own, so every pair of triangles with touching boxes is tested once. The
/// leaves are searched in parallel with the `parallel` feature; the smallest pair is
/// reported either way, so the answer does not depend on it.
pub(crate) fn first_contact(tree: &TriangleTree) -> Option<(u32, u32)> {
    let boxes = tree.boxes();
    let nodes = boxes.nodes();
    let search = Search {
        tree,
        triangle_boxes: tree
            .corners()
            .iter()
            .map(|&c| Aabb::from_points(c))
            .collect(),
    };
    let leaves: Vec<usize> = (0..nodes.len()).filter(|&n| nodes[n].is_leaf()).collect();
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        leaves
            .par_iter()
            .with_max_len(64)
            .filter_map(|&leaf| search.contact_at_or_after(leaf))
            .min()
    }
    #[cfg(not(feature = "parallel"))]
    {
        leaves
            .iter()
            .filter_map(|&leaf| search.contact_at_or_after(leaf))
            .min()
    }
}

/// What every leaf's search reads.
struct Search<'a> {
    tree: &'a TriangleTree,
    /// The box of each triangle, in tree order.
    triangle_boxes: Vec<Aabb>,
}

impl Search<'_> {
    /// The smallest contact between a triangle of `leaf` and a triangle at or after it in
    /// tree order.
    fn contact_at_or_after(&self, leaf: usize) -> Option<(u32, u32)> {
        let nodes = self.tree.boxes().nodes();
        let own = nodes.get(leaf)?;
        let mine = own.items();
        let mut first: Option<(u32, u32)> = None;
        let mut stack: SmallVec<[usize; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let Some(node) = nodes.get(n) else {
                continue;
            };
            if node.items().end <= mine.start || !touch(&node.bounds, &own.bounds) {
                continue;
            }
            match node.right() {
                Some(right) => {
                    stack.push(right);
                    stack.push(n + 1);
                }
                None => {
                    for i in mine.clone() {
                        for j in node.items().filter(|&j| j > i) {
                            if let Some(pair) = self.contact(i, j) {
                                first = Some(first.map_or(pair, |f| f.min(pair)));
                            }
                        }
                    }
                }
            }
        }
        first
    }

    /// The mesh triangle pair at tree positions `i` and `j` if their boxes touch and they
    /// meet improperly.
    fn contact(&self, i: usize, j: usize) -> Option<(u32, u32)> {
        if !touch(self.triangle_boxes.get(i)?, self.triangle_boxes.get(j)?) {
            return None;
        }
        let corners = self.tree.corners();
        let vertices = self.tree.vertices();
        let (pi, pj): ([DVec3; 3], [DVec3; 3]) = (*corners.get(i)?, *corners.get(j)?);
        if !improper_contact(pi, *vertices.get(i)?, pj, *vertices.get(j)?) {
            return None;
        }
        let order = self.tree.boxes().order();
        let (a, b) = (*order.get(i)?, *order.get(j)?);
        Some((a.min(b), a.max(b)))
    }
}

/// Whether two closed boxes share a point.
fn touch(a: &Aabb, b: &Aabb) -> bool {
    a.min.cmple(b.max).all() && b.min.cmple(a.max).all()
}
