//! The minimax construction ([`Method::Minimax`](crate::Method::Minimax), the default):
//! each node's part of the surface divided between children chosen to make the worst
//! child's error as small as possible, on the exact surface.
//!
//! # The problem
//!
//! A node must cover its part of the surface, its *region*, with at most `branch` child
//! spheres, so that the largest error among the children is as small as it can be; the
//! error of a sphere is the paper's eq. 2, `radius − depth(center)` (the signed distance
//! from the centre to the surface, positive inside), an upper bound on how far the sphere
//! pokes out of the object that is exact for convex parts. For fixed centres, the best
//! assignment gives every bit of surface to the sphere that covers it with the least
//! error; so the problem is a `k`-centre problem whose distance is `|x − c| − depth(c)`.
//!
//! # The method
//!
//! 1. **Pieces.** The region is represented exactly, by triangles tiling it (the mesh's
//!    triangles, split at their longest edge until about 12,000 tile the region). A
//!    sphere containing a piece's corners contains the piece, so covering the pieces'
//!    corners covers the surface itself, not only samples of it.
//! 2. **Candidates.** Centres worth trying are medial balls: for a few hundred pieces, the
//!    largest empty ball tangent at the piece's centroid, found by shrinking against the
//!    exact surface (`candidates.rs`). On a shell (a surface without inside) the pieces'
//!    centroids themselves.
//! 3. **Search.** Every candidate is expanded to a common standoff `e` beyond the surface
//!    (the paper's expand step); a depth-first search on the most constrained piece
//!    decides whether `k` of them cover a subset of representative pieces, and bisection
//!    finds the smallest such `e` (`search.rs`).
//! 4. **Lloyd's iteration** on the representatives: every piece to its cheapest sphere,
//!    every sphere to its best candidate, while the worst error falls; children are added
//!    by splitting the worst when the search chose fewer than asked.
//! 5. **Exact refinement** on every piece: each centre moves off the candidates, by
//!    Nelder–Mead on its exact error over its own pieces (exact farthest corner, exact
//!    signed distance), and the pieces are reassigned, while the worst error falls.
//! 6. A few **starts** (different representatives and candidates) for large regions; the
//!    best division is kept.
//!
//! The tree is built top down, level by level. To a depth, every node is divided into
//! `branch` children; with a tolerance, only the nodes whose certified error exceeds it,
//! each into the fewest children (at most `branch`) that meet it, as deep as needed. The
//! children of a node cover the node's pieces, so every cut through the tree covers the
//! whole surface.

mod candidates;
mod cluster;
mod node;
mod pieces;
mod polish;
mod search;
mod swap;
mod tree;

pub use tree::MAX_TREE_NODES;
pub(crate) use tree::minimax_tree;

/// The paper's eq. 2 for a sphere of radius `radius` whose centre has signed depth
/// `depth` (positive inside): how far at most it reaches beyond the surface (0 for a
/// sphere inside the object).
pub(crate) fn eq2(radius: f64, depth: f64) -> f64 {
    (radius - depth).max(0.0)
}
