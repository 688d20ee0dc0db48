//! # sphaera-hal
//!
//! HAL trees — *hierarchical approximation and localization* — after Veltkamp
//! (*Hierarchical approximation and localization*, `shared/papers/hal-trees-veltkamp.md`): an outline
//! kept as a binary tree whose every level is an approximation by a subset of its own
//! vertices, and whose every node bounds its part of the outline by the intersection of
//! two discs through the part's ends.
//!
//! Status: both halves of the paper. In 2D (section 3, and section 5's point inclusion and
//! intersection detection, carried on to localisation), with `sphaera hal` for polygons:
//! single outlines ([`HalTree2`]) and polygons with holes and multipolygons
//! ([`HalMultiPolygon2`]: a country with its islands and lakes, one tree per ring, one
//! answer as GEOS gives it), inclusion that says where ([`HalMultiPolygon2::locate`]), the
//! nearest edge and its distance, and every pair of intersecting edges. In 3D (section 4):
//! [`GenusZeroSurface`] (validation, the root ball touching three vertices, deterministic
//! shortest edge paths, the patches they cut) and [`HalTree3`] (Algorithm 2: splits at
//! `v_q`/`v_r` or at sides below π/4 propagated to the neighbours, Definition 5's balls,
//! levels and adaptive approximations as watertight meshes, exact point inclusion with the
//! bounds culling an axis ray's crossing count (the ray moved symbolically off every edge
//! and vertex, so every point off the surface gets an exact answer), intersection
//! detection under a similarity and every pair of intersecting faces, the nearest face).
//! Two places where the paper's 3D claims do not hold, and what is done instead:
//! - Discarding the triangles whose paths coalesce leaves holes in a level, so a level is
//!   not the closed polyhedron section 5.1's shortcut needs; levels and approximations are
//!   closed by filling each hole with a fan, and point inclusion stays exact by culling
//!   only (see [`HalTree3::contains`] for the measured alternative).
//! - A union of two balls through one circle is not convex and need not hold the faces
//!   between the patch's vertices (a cube patch shows it); intersection detection bounds
//!   such a patch by the ball around both balls.
//!
//! # Quick start
//!
//! ```
//! use glam::DVec2;
//! use sphaera_hal::{HalTree2, Containment, Polyline2};
//!
//! // A star: ten vertices alternating between radius 1 and 0.4.
//! let points: Vec<DVec2> = (0..10)
//!     .map(|i| {
//!         let angle = std::f64::consts::TAU * f64::from(i) / 10.0;
//!         DVec2::from_angle(angle) * if i % 2 == 0 { 1.0 } else { 0.4 }
//!     })
//!     .collect();
//! let star = HalTree2::build(&Polyline2::polygon(points)?)?;
//! // Level 0 is a chord between two tips; the full depth gives every vertex back.
//! assert_eq!(star.level(0).len(), 2);
//! assert_eq!(star.level(star.depth()).len(), 10);
//! // Refine only where a part's bounding area is wider than 0.5.
//! let coarse = star.approximate(0.5);
//! assert!(coarse.width <= 0.5 && coarse.vertices.len() < 10);
//! assert_eq!(star.contains(DVec2::ZERO)?, Containment::Inside);
//! # Ok::<(), sphaera_hal::HalError>(())
//! ```
//!
//! # The method in brief
//!
//! - **Bounding areas** ([`Lens`]): for a polyline from `v_p` to `v_s`, the vertices left
//!   of the chord lie in a smallest disc through `v_p` and `v_s` (through the vertex
//!   `v_q` that sees the chord under the smallest angle), those on the right in another
//!   (through `v_r`); the bounding area is their intersection, or a disc and a half-plane
//!   when one side is empty (Definitions 1–3). Half-planes are represented exactly.
//! - **The tree** ([`HalTree2`]): the root is the smallest disc around all vertices and
//!   the chord between the two vertices on it farthest apart; each polyline is split at
//!   whichever of `v_q`, `v_r` has the larger signed radius (Algorithm 1). One node per
//!   vertex (Theorem 3).
//! - **Approximation**: a level, or adaptively only where a part's widths `w₁, w₂`
//!   (Definition 4) exceed a tolerance.
//! - **Point inclusion**: the crossing number, with every part whose bounding area does not
//!   contain the point replaced by its chord. Each node also keeps its part's bounding box,
//!   tested first (coordinate comparisons, exact): a part above, below or left of the
//!   point crosses nothing, one right of it as often as its chord. In front of the
//!   hierarchy, a cell grid over the ring (about 4 cells per edge) answers most queries:
//!   a cell no edge touches is wholly inside or outside, and in a cell a few edges cross,
//!   the crossings of the segment from the cell's centre decide, with exact
//!   orientations; whatever the grid cannot decide exactly goes to the hierarchy
//!   ([`HalTree2::contains_by_hierarchy`] is the paper's method alone).
//! - **Intersection detection**: pairs of parts whose bounding areas and boxes may meet are
//!   refined down to pairs of edges, tested exactly; [`HalTree2::intersecting_edges`]
//!   returns every such pair. A closed outline is a region, an open one a curve, as in
//!   GEOS: a polyline inside a polygon intersects it.
//! - **Localisation**: [`HalTree2::nearest_edge`] by branch and bound, a part's lower bound
//!   the larger of its distances to its box and to its lens's discs.
//! - **Several rings** ([`HalMultiPolygon2`]): a box hierarchy over the rings sends a query
//!   only to the rings whose boxes hold it; `MultiPolygon2::from_rings` takes GeoJSON's
//!   layout (the `sphaera-io` crate reads GeoJSON and WKT files into it).
//!
//! # Errors
//!
//! [`HalError`]: too few vertices, NaN or infinite coordinates, point inclusion asked of
//! an open polyline, unreadable or malformed polygon files; for multipolygons, the
//! polygon and ring at fault ([`HalError::Ring`]), an open ring, no polygon at all.
//!
//! # Performance, and where the scheme is weak
//!
//! Measured on the Natural Earth outlines (one thread; `cargo run --release -p
//! sphaera-eval -- --out docs/charts --only hal`, and against GEOS's prepared geometry,
//! what shapely and PostGIS run, by `cargo bench -p sphaera-eval --features geos --bench
//! hal2_vs_geos`): point inclusion is orders of magnitude faster than the brute-force
//! crossing test and than `geo`'s `contains` on large outlines, and the build grows about
//! as `N log N`. The lenses alone localise poorly on real coastlines: a lens must pass
//! through both ends of its chord, so a part that folds back beyond them (a fjord) forces
//! a large disc, and the split rule grows the tree far deeper than `log₂ N`; Ballard's
//! strip tree's strips are far tighter per depth. Each node's box makes up for it (the box
//! alone is twice as slow as box and lens: the lens earns its place). Storage: the
//! paper's one node per vertex (Theorem 3), each 48 bytes, plus 64 bytes of what a query
//! reads (box, lens, split, children) and the vertices in outline order.
//!
//! In 3D (`cargo bench -p sphaera-eval --bench hal3_vs_parry`, with libigl's fast winding
//! number as a Python peer on the same points): point inclusion is exact and several times
//! faster than parry3d-f64's `contains_point` and libigl's on every mesh measured, the
//! closed 69k-triangle bunny included. Balls through a thin triangle's corners are huge and
//! cull little, so each node also keeps its patch's box, and the tree is laid out flat
//! for queries (children side by side, the axis ray meeting a child's box in five
//! comparisons before it is pushed). As a simplification a HAL approximation is far
//! farther from the surface than `sphaera-simplify`'s at the same triangle count.
//! Every figure (the 2D queries and builds, the tree depths, the 3D builds and queries,
//! the comparison with `sphaera-simplify`) is in the section *HAL trees (`sphaera-hal`,
//! issue 17)* of `docs/benchmarks.md` in the repository.
//!
//! # See also
//!
//! [`sphaera-spheretree`](https://docs.rs/sphaera-spheretree) for 3D bounding-sphere
//! hierarchies; [`sphaera_mesh`] for the meshes a [`GenusZeroSurface`] is made from;
//! the facade `sphaera` (as `sphaera::hal`) and the `sphaera hal` command of
//! `sphaera-cli`. The paper: R. C. Veltkamp, *Hierarchical approximation and
//! localization* (Utrecht University).

mod cell_grid;
mod error;
mod intersect3;
mod lens;
mod multipolygon;
mod nearest2;
mod polyline;
mod query2;
mod query3;
mod ring_index;
mod surface3;
mod svg;
mod tree2;
mod tree3;

pub use error::HalError;
pub use intersect3::{intersects3_brute, triangles_meet};
pub use lens::{CONTAINMENT_SLACK, Lens, LensKind, SignedDisc, vertex_bulge};
pub use multipolygon::{
    HalMultiPolygon2, Location2, MultiPolygon2, NearestRingEdge, Polygon2, RingEdge, RingId,
};
pub use nearest2::{NearestEdge, closest_on_segment, nearest_edge_brute};
pub use polyline::{Polyline2, parse_points, parse_points3};
pub use query2::{
    Containment, contains_brute, intersecting_edges_brute, intersects_brute, ray_crossing,
    segments_intersect,
};
/// The old name of [`Containment`] (renamed so that `sphaera-io`'s `Location`, where in a
/// file, is the workspace's only `Location`).
#[deprecated(since = "0.2.0", note = "renamed `Containment`")]
pub type Location = Containment;
pub use query3::{NearestFace, contains3_brute};
pub use surface3::{GenusZeroSurface, RootBall};
pub use svg::approximation_svg;
pub use tree2::{Approximation, Chain, HalTree2, LevelSummary, Node2};
pub use tree3::{Bound3, HalTree3, Node3, SMALLEST_SPLIT_ANGLE};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
