//! The tree laid out for queries: one flat array of nodes, each with its patch's
//! bounding box, whose children sit next to each other (a node's block of children is
//! placed just before its children's own blocks, depth first, so that a subtree is
//! mostly contiguous); the bounding volumes in a parallel array; the leaves' triangles
//! by value, in the order of the leaves.

use glam::DVec3;

use super::HalTree3;
use crate::intersect3::{Region, bound_regions};

/// One node of the query layout.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FlatNode {
    /// The lower corner of the patch's bounding box.
    pub(crate) lo: [f64; 3],
    /// The upper corner.
    pub(crate) hi: [f64; 3],
    /// The first child (an index into [`Layout::nodes`]) or, for a leaf, its slot in
    /// [`Layout::triangles`] and [`Layout::faces`].
    pub(crate) first: u32,
    /// The number of children; 0 for a leaf (one face).
    pub(crate) count: u32,
}

/// The query layout of a [`HalTree3`] (see the module's docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Layout {
    /// The nodes; the roots are the first [`Layout::root_count`].
    pub(crate) nodes: Vec<FlatNode>,
    /// Per node, the two convex regions holding its patch (everything for a leaf).
    pub(crate) regions: Vec<[Region; 2]>,
    /// Per leaf slot, the face's corners.
    pub(crate) triangles: Vec<[DVec3; 3]>,
    /// Per leaf slot, the face (a mesh triangle index).
    pub(crate) faces: Vec<u32>,
    /// The number of roots.
    pub(crate) root_count: u32,
}

impl Layout {
    /// Lays out `tree` (its nodes, roots and mesh already built). A node without children
    /// but with several faces (a patch no split could divide) gets one leaf per face.
    pub(crate) fn new(tree: &HalTree3) -> Self {
        let mesh = tree.surface.mesh();
        let positions = mesh.positions();
        let corners = |f: u32| mesh.triangles()[f as usize].map(|v| positions[v as usize]);
        let mut layout = Self::default();
        // What each flat node stands for: a tree node, or one face of a childless patch.
        #[derive(Clone, Copy)]
        enum Item {
            Node(u32),
            Face(u32),
        }
        let mut items: Vec<Item> = Vec::new();
        let place = |layout: &mut Self, items: &mut Vec<Item>, item: Item| -> u32 {
            layout.nodes.push(FlatNode {
                lo: [0.0; 3],
                hi: [0.0; 3],
                first: 0,
                count: 0,
            });
            layout.regions.push([Region::Everything; 2]);
            items.push(item);
            (layout.nodes.len() - 1) as u32
        };
        let roots: Vec<u32> = tree
            .roots
            .iter()
            .map(|&r| place(&mut layout, &mut items, Item::Node(r)))
            .collect();
        layout.root_count = roots.len() as u32;
        // Depth first: a node's children are placed as one block when it is expanded.
        let mut stack: Vec<u32> = roots.into_iter().rev().collect();
        while let Some(at) = stack.pop() {
            let children: Vec<Item> = match items[at as usize] {
                Item::Face(_) => Vec::new(),
                Item::Node(n) => {
                    let node = &tree.nodes[n as usize];
                    if !node.children.is_empty() {
                        node.children.iter().map(|&c| Item::Node(c)).collect()
                    } else if node.faces.len() > 1 {
                        node.faces.iter().map(|&f| Item::Face(f)).collect()
                    } else {
                        Vec::new()
                    }
                }
            };
            if children.is_empty() {
                let face = match items[at as usize] {
                    Item::Face(f) => f,
                    // A leaf holds one face (a tree's patch is never empty).
                    Item::Node(n) => tree.nodes[n as usize].faces.first().copied().unwrap_or(0),
                };
                let slot = layout.triangles.len() as u32;
                layout.triangles.push(corners(face));
                layout.faces.push(face);
                layout.nodes[at as usize].first = slot;
                continue;
            }
            let first = layout.nodes.len() as u32;
            for &item in &children {
                place(&mut layout, &mut items, item);
            }
            let node = &mut layout.nodes[at as usize];
            node.first = first;
            node.count = children.len() as u32;
            stack.extend((first..first + children.len() as u32).rev());
        }
        // Boxes bottom up (children always come after their parent), volumes per node.
        for at in (0..layout.nodes.len()).rev() {
            let node = layout.nodes[at];
            let (lo, hi) = if node.count == 0 {
                let t = layout.triangles[node.first as usize];
                (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]))
            } else {
                (node.first..node.first + node.count).fold(
                    (DVec3::INFINITY, DVec3::NEG_INFINITY),
                    |(lo, hi), c| {
                        let child = &layout.nodes[c as usize];
                        (
                            lo.min(DVec3::from_array(child.lo)),
                            hi.max(DVec3::from_array(child.hi)),
                        )
                    },
                )
            };
            layout.nodes[at].lo = lo.to_array();
            layout.nodes[at].hi = hi.to_array();
            if let (Item::Node(n), true) = (items[at], node.count > 0) {
                let tree_node = &tree.nodes[n as usize];
                if let Some(bound) = tree_node.bound {
                    layout.regions[at] =
                        bound_regions(&bound, tree_node.corners.map(|v| positions[v as usize]));
                }
            }
        }
        layout
    }
}
