//! # sphaera-simplify
//!
//! Triangle-mesh simplification by half-edge collapses, with a **certified two-sided error
//! bound**: every vertex of the simplified mesh carries an *error sphere* radius, and the
//! simplified triangles swept by those spheres enclose the original surface while every
//! simplified point stays within its radius of the original surface. This is the
//! simplification behind the Meshsweeper hierarchy of A. Guéziec, *Meshsweeper: Dynamic
//! Point-to-Polygonal-Mesh Distance and Applications*, IEEE TVCG 7(1), 2001 (sections 4.1–4.2
//! on error spheres, 5.3 on deformation). Besides the simplified mesh, it records the
//! collapses as a progressive [`Hierarchy`] in the paper's array form, refined selectively
//! by a [`Refinement`] (the changing state of a distance query), and updated for deforming
//! meshes by [`Hierarchy::replay`] and [`Hierarchy::inflate`].
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{Length, shapes};
//! use sphaera_simplify::{SimplifyOptions, simplify};
//!
//! let sphere = shapes::sphere(1.0, 24)?;
//! let out = simplify(&sphere, &SimplifyOptions::default().with_target_ratio(0.1))?;
//! assert!(out.mesh.triangle_count() <= sphere.triangle_count() / 10 + 1);
//! assert!(out.error_bound >= 0.0);
//! assert_eq!(out.vertex_radii.len(), out.mesh.vertex_count());
//! // Subset placement: every output vertex is an input vertex.
//! for (i, &o) in out.original_vertex.iter().enumerate() {
//!     assert_eq!(out.mesh.positions()[i], sphere.positions()[o as usize]);
//! }
//!
//! // Or stop at an error bound (relative to the bounding-box diagonal).
//! let fine = simplify(
//!     &sphere,
//!     &SimplifyOptions::default().with_max_error(Length::RelativeToDiagonal(0.005)),
//! )?;
//! assert!(fine.error_bound <= 0.005 * sphere.bounding_box_diagonal());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Algorithm
//!
//! Every vertex carries a radius `r`, 0 for original vertices. The *tolerance volume* of a
//! simplified triangle with corners `P = (a, b, c)` and radii `R = (ra, rb, rc)` is the union,
//! over barycentric weights `λ`, of the balls `B(λ·P, λ·R)`. Two invariants hold after
//! every collapse:
//!
//! - **(A)** every point of the original surface lies in the tolerance volume of some
//!   simplified triangle;
//! - **(B)** every point `y` of a simplified triangle is within `r(y)` (its interpolated
//!   radius) of the original surface.
//!
//! A half-edge collapse `u → v` replaces the fan of triangles around `u` by a fan around
//! `v` over the same link polygon. If `φ` is a bijection from the old fan onto the new fan
//! that fixes the link polygon and is affine on each cell of a common refinement of the
//! two triangulations, then requiring `r_new(φ(p)) ≥ |p − φ(p)| + r_old(p)` at every point
//! `p` carries both invariants over: for (A), `B(p, r_old(p)) ⊂ B(φ(p), r_new(φ(p)))`; for
//! (B), `dist(φ(p), M0) ≤ |φ(p) − p| + dist(p, M0) ≤ |φ(p) − p| + r_old(p)`. The slack
//! `|p − φ(p)| + r_old(p) − r_new(φ(p))` is convex on each cell (the norm of an affine map
//! plus an affine map), so it suffices to check it at the cell vertices.
//!
//! The map used is the tight one: both fans are projected onto the plane of the old fan's
//! area-weighted normal; when both projections are injective (every projected triangle
//! positively oriented and the angles around `u` summing to one turn), `φ` pairs points
//! with the same projection. The cell vertices are the fan vertices and the crossings of
//! the old spokes `u–w_i` with the new spokes `v–w_j`; at each, the needed radius of `v` is
//! `(|p − φ| + r_old(p) − Σ_{j≠v} λ_j r_j) / λ_v`, and the new `r_v` is the maximum of
//! these and the old `r_v` (plus a tiny margin against rounding). Raising `r_v` only grows
//! the tolerance volumes of `v`'s other triangles, so the invariants hold there too. On a
//! flat region the collapse costs nothing, unlike the simple map that sends `u` to `v`
//! (which needs `r_v ≥ r_u + |u − v|`).
//!
//! Where the projection folds, or where the tight map is worse (steep or thin fans, where
//! it is ill-conditioned), the simple map is used instead: both are rigorous, and the
//! engine keeps the smaller radius. Collapses that flip a triangle's normal (more than
//! 90°) or create a sliver are refused. By default boundary vertices are never removed
//! (interior vertices may collapse onto them); with
//! [`SimplifyOptions::with_lock_boundary`]`(false)` they may collapse along boundary edges, with the
//! simple map sending `u` to `v` (rigorous, but it needs `r_v ≥ r_u + |u − v|`).
//! With [`Placement::Optimal`] each vertex's edge with the smallest merged error quadric
//! is also tried as a full-edge collapse, the kept vertex moving to the quadric's minimum;
//! the region is then both stars, whose overlay with the new fan is checked the same way
//! (over three projection planes, or the simple map sending both ends to the new
//! position), and whichever collapse needs the smaller radius wins.
//!
//! Non-manifold vertices and their edges are never touched; the topology guards of
//! [`HalfEdgeMesh::check_collapse`](sphaera_mesh::topology::HalfEdgeMesh::check_collapse)
//! (link condition, tetrahedron) apply. What stayed locked is in [`Simplified::locked`].
//!
//! The order is error-driven: a priority queue (one entry per vertex) holds each vertex's
//! cheapest legal collapse, keyed by the radius it would give `v` divided by the smallest
//! [tolerance weight](SimplifyOptions::with_weights) of the vertices it changes (ties
//! broken by vertex and half-edge index, so the result is deterministic). A collapse makes
//! the kept vertex and its neighbours stale. With [`Order::Strict`] they are re-evaluated
//! right after it, so every collapse is the cheapest one of the moment; with
//! [`Order::Batched`] collapses are applied while the cheapest candidate is up to date,
//! then the stale vertices are re-evaluated together on every core (those far behind the
//! front only when they reach it). Either way every applied collapse has its radius
//! computed on the mesh as it is, so the bound is certified; the batched order drifts a
//! little from the greedy one. [`Order::Auto`], the default, is strict below
//! [`Order::STRICT_BELOW`] vertices and batched above. The result does not depend on the
//! thread count.
//!
//! # The progressive hierarchy
//!
//! [`Hierarchy::build`] records every collapse: the removed vertex, its parent,
//! the parent's new radius, the faces around both, and what the collapse *read* (the radii
//! of the removed vertex's one-ring and the faces around both ends). A collapse depends on
//! the latest earlier collapses that wrote what it read; "split before" is the inverse
//! relation. A [`Refinement`] undoes a collapse only after undoing its applied dependants
//! (in decreasing build order, a topological order), so every reachable state is locally
//! identical to a state of the build sequence: radii, corners and the triangle lists of
//! each split are exact, and both invariants hold in every state (property-tested by
//! replaying each refined state's collapses in build order and comparing). Triangles keep
//! their input index for life (a triangle's corners are its input corners with removed
//! vertices replaced by their parents), so a caller's priority queue keys on stable ids.
//!
//! # Deformation
//!
//! [`Hierarchy::replay`] recomputes every radius for new positions by applying the same
//! collapses (tight map where its projection is still injective, the simple map
//! elsewhere): exact radii for a key-frame. [`Hierarchy::inflate`] needs only an upper
//! bound of each vertex's displacement: walking the collapses, it tracks for each triangle
//! the largest displacement over the input surface it stands for, and adds twice that to
//! the radius of every vertex of the triangle (a point of the simplified triangle and the
//! input point it covers each move by at most that much). No geometry is computed.
//!
//! # Errors
//!
//! [`simplify`] returns [`SimplifyError`] for an empty mesh or parameters out of
//! their domain (NaN, negative bounds, a ratio outside `(0, 1]`). It never panics.
//!
//! # Performance
//!
//! The work per collapse is bounded by the valences around the kept vertex (each
//! re-evaluation is `O(d²)` for valence `d`, with the fan projected once per vertex and
//! targets pruned by a lower bound), so the whole run is `O(T log T)` for `T` triangles
//! on meshes of bounded valence. With the default `parallel` feature the initial
//! evaluation and every batch run on all cores (identical results without it). Sphaera is
//! slower than meshoptimizer, which certifies nothing, and its output is closer to the
//! input. The times against meshoptimizer in the same run (the 69k-triangle bunny, the
//! 871k-triangle dragon, the bunny's full hierarchy), the measured errors of both and
//! what was tried are in the section *Issue 20: batched re-evaluation on every core
//! (2026-11-27)* of `docs/benchmarks.md` in the repository (`cargo bench -p sphaera-eval
//! --bench simplify_vs_meshopt`).
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! - [`sphaera_mesh::topology::HalfEdgeMesh`]: the editable mesh and its collapse
//!   records.
//! - `sphaera-sweep`: Meshsweeper's closest-point queries and certified Hausdorff
//!   distances on the [`Hierarchy`] (the Hausdorff distance measures how tight
//!   [`Simplified::error_bound`] is).
//! - `sphaera-silhouette`: silhouette-preserving level of detail extracted from the
//!   [`Hierarchy`] view by view, and per-vertex weights for
//!   [`SimplifyOptions::with_weights`].
//! - The facade `sphaera` (as `sphaera::simplify`) and the `sphaera simplify` command of
//!   `sphaera-cli`.

mod deform;
mod edge_radius;
mod engine;
mod error;
mod hierarchy;
mod quadric;
mod record;
mod refine;
mod simplifier;
mod spheres;
mod weights;

pub use error::SimplifyError;
pub use hierarchy::{Hierarchy, MemoryUse};
pub use refine::Refinement;
pub use simplifier::{
    LockReport, Order, Placement, Simplified, SimplifyOptions, SimplifyProgress, simplify,
    simplify_with_progress,
};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
