//! Inside/outside of triangle meshes by the generalized winding number, hierarchically
//! accelerated.
//!
//! The **generalized winding number** of a surface at a point `p` is the signed solid angle
//! the surface subtends at `p`, divided by `4π` (Jacobson, Kavan and Sorkine-Hornung 2013,
//! *Robust Inside-Outside Segmentation using Generalized Winding Numbers*). For a closed,
//! outward-oriented mesh it is exactly 1 inside and 0 outside (2 inside two nested shells,
//! −1 inside an inward-oriented one). For real meshes — scans with holes, non-manifold
//! edges, duplicated or self-intersecting triangles, several overlapping shells — it
//! degrades gracefully: it stays close to 1 well inside and close to 0 well outside, and
//! varies smoothly near the holes. Thresholding it at ½ is the robust inside test this
//! crate uses everywhere ([`WindingNumber::is_inside`]).
//!
//! # Quick start
//!
//! ```
//! use glam::DVec3;
//! use sphaera_mesh::TriMesh;
//! use sphaera_query::winding::WindingNumber;
//!
//! // The unit cube [0, 1]³, outward oriented (vertex i is at (i & 1, i >> 1 & 1, i >> 2)).
//! let positions: Vec<DVec3> = (0..8u32)
//!     .map(|i| DVec3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2)))
//!     .collect();
//! let mut triangles = vec![
//!     [0, 2, 3], [0, 3, 1], // z = 0
//!     [0, 1, 5], [0, 5, 4], // y = 0
//!     [2, 6, 7], [2, 7, 3], // y = 1
//!     [0, 4, 6], [0, 6, 2], // x = 0
//!     [1, 3, 7], [1, 7, 5], // x = 1
//!     [4, 5, 7], [4, 7, 6], // z = 1
//! ];
//! let cube = TriMesh::new(positions.clone(), triangles.clone())?;
//! let winding = WindingNumber::new(&cube)?;
//! assert!((winding.winding_number(DVec3::splat(0.5)) - 1.0).abs() < 1e-9);
//! assert!(winding.winding_number(DVec3::new(2.0, 0.5, 0.5)).abs() < 1e-2);
//! assert_eq!(
//!     winding.classify(&[DVec3::splat(0.25), DVec3::splat(-0.25)]),
//!     vec![true, false]
//! );
//! assert!(winding.check_solid().is_ok());
//!
//! // Remove the top face: the box is open, but its centre still sees 5/6 of the sphere
//! // covered, so it is still inside.
//! triangles.truncate(10);
//! let open_box = WindingNumber::new(&TriMesh::new(positions, triangles)?)?;
//! assert!((open_box.winding_number(DVec3::splat(0.5)) - 5.0 / 6.0).abs() < 1e-2);
//! assert!(open_box.is_inside(DVec3::splat(0.5)));
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```
//!
//! # Method
//!
//! **Solid angle of a triangle.** [`triangle_solid_angle`] uses the formula of Van Oosterom
//! and Strackee (1983, *The solid angle of a plane triangle*) with `atan2`, which is accurate
//! for every configuration and never NaN for finite input. Summing it over all triangles is
//! the exact reference [`winding_number_brute`] (`O(n)` per point).
//!
//! **Fast winding numbers.** [`WindingNumber`] implements Barill, Dickson, Schmidt, Levin and
//! Jacobson (2018), *Fast Winding Numbers for Soups and Clouds* (ACM Transactions on
//! Graphics 37(4)). The solid angle of a triangle is `∫ n · K(x − p) dA` with the kernel
//! `K(y) = y / |y|³`. A binary bounding-volume hierarchy is built over the triangles
//! (deterministically: median split of the centroids along the longest axis, ties broken by
//! triangle index, at most 8 triangles per leaf). Each node stores, about its centre `c`
//! (the area-weighted mean of its centroids) and with `r` the largest distance from `c`
//! to a corner of its triangles, the moments of the Taylor expansion of `K` about `c`:
//!
//! - the dipole `Σ area · n` ([`Expansion::FirstOrder`]),
//! - plus the first moments `Σ (centroid − c) ⊗ area · n` ([`Expansion::SecondOrder`]),
//! - plus the second moments `Σ area · n ⊗ E[(x − c)(x − c)ᵀ]`, integrated exactly over each
//!   triangle ([`Expansion::ThirdOrder`], the default, as in the paper).
//!
//! A query descends the tree; a node whose centre is farther than **`beta · r`** from the
//! query (the *far field*, [`WindingOptions::with_beta`], default 2) contributes its expansion,
//! other nodes are opened, and the triangles of the leaves that are reached are summed
//! exactly. `beta = ∞` ([`WindingNumber::exact`]) disables the approximation.
//!
//! # Accuracy
//!
//! Largest and mean `|w_fast − w_brute|` over random points of the test shapes (tetrahedron,
//! cube, octahedron, sphere, torus, sphere with a hole, flat sheet, nested spheres), for
//! points at least `10⁻³ · diagonal` from the surface
//! (`cargo test -p sphaera-query --lib winding::tests::error_table -- --ignored --nocapture`):
//!
//! | expansion | beta | mean error | max error |
//! |---|---:|---:|---:|
//! | first order | 2 | 5.0e-3 | 6.2e-2 |
//! | first order | 4 | 9.8e-4 | 1.1e-2 |
//! | second order | 2 | 2.7e-3 | 5.9e-2 |
//! | **third order** | 1.5 | 1.5e-3 | 3.4e-2 |
//! | **third order** | **2** | **4.2e-4** | **8.4e-3** |
//! | third order | 3 | 6.2e-5 | 1.3e-3 |
//! | third order | 4 | 1.6e-5 | 1.5e-4 |
//!
//! The tests assert the documented tolerance **`|w_fast − w_brute| ≤ 2·10⁻²`** for the
//! default options (the worst case seen is 1.4e-2, at the centre of nested spheres, where
//! the truncation errors of all nodes add up with the same sign), and that the
//! classification agrees **exactly** with ray parity ([`inside_by_ray_parity`]) on closed
//! meshes for points away from the surface. On the real meshes (bunny, dragon) the errors
//! against brute force, measured by a scratch program, stay within that tolerance.
//!
//! Near the surface `w` crosses ½, and an approximation error could flip a point lying
//! within about `10⁻³` of the local triangle size. When that matters, use
//! [`WindingNumber::is_inside_certified`]: every expansion also carries a rigorous
//! truncation bound (a Taylor remainder bound,
//! [`WindingNumber::winding_number_with_bound`]), and where the bounds cannot decide, the
//! expansions with the largest bounds are refined first, down to the triangles' exact
//! solid angles if needed. Its answer is the exact
//! winding number's. In the performance measurements (see below), it never differed
//! from the plain classification.
//!
//! # Meshes that do not enclose a volume
//!
//! For a lone open sheet `|w| ≤ ½` everywhere, so "inside" is empty and meaningless.
//! [`WindingNumber::check_solid`] probes the winding number just behind and in front of up
//! to 64 triangles and returns [`QueryError::NotSolid`](crate::QueryError::NotSolid) when no
//! probe reaches `|w| ≥ 0.75`, and
//! [`QueryError::InwardOrientation`](crate::QueryError::InwardOrientation) when the triangles
//! face inward; [`WindingNumber::solidity`] returns the measurements ([`SolidityReport`]).
//! The open Stanford bunny (five holes) and the non-manifold dragon pass with median
//! `w ≈ 0.99` behind their triangles; at the centre of the bunny's bounding box,
//! `w = 0.9915` (brute force; 0.9929 with the default options).
//!
//! # Performance
//!
//! Building is `O(n log n)`, and a query away from the surface `O(log n)`. No bench
//! times the build or [`WindingNumber::is_inside`] and [`WindingNumber::classify`] on
//! their own yet (the figures of a scratch program were dropped from the section
//! *Inside/outside (generalized winding number)* of `docs/benchmarks.md` in the
//! repository); [`WindingNumber::is_inside_certified`] is timed by `cargo bench -p
//! sphaera-eval --bench hal3_vs_parry`. Query cost grows with `beta`. Memory is linear in
//! the triangles: the reordered corners plus one 384-byte node for every few triangles.
//! The batch methods
//! ([`WindingNumber::winding_numbers`], [`WindingNumber::classify`],
//! [`WindingNumber::classify_certified`]) use all cores with the `parallel` feature, and
//! return the same bits with or without it (each point is evaluated independently, in a
//! fixed traversal order).

mod boundary;
mod certified;
mod evaluator;
mod expansion;
mod ray_parity;
mod solid_angle;
mod solidity;
#[cfg(test)]
mod tests;
mod tree;

pub use boundary::WindingBoundary;
pub use certified::CertifiedSide;
pub use evaluator::{WindingEstimate, WindingNumber, WindingOptions};
pub use expansion::Expansion;
pub use ray_parity::inside_by_ray_parity;
pub use solid_angle::{triangle_solid_angle, winding_number_brute};
pub use solidity::{INWARD_THRESHOLD, SOLID_THRESHOLD, SolidityReport};
pub(crate) use tree::LEAF_SIZE;
