//! A mesh prepared as the boundary of a solid ([`Surface`]): its inside test (generalized
//! winding number), its exact closest points (the [`TriangleTree`]), both together
//! ([`Surface::signed_closest`]), checked once for a meaningful inside and certified once,
//! when it is, as an embedded solid.
//!
//! # Signed closest points
//!
//! Callers that need the closest point **and** the side of the same point (sphere-tree
//! evaluation, signed distances) ask [`Surface::signed_closest`]. On a mesh that
//! [`Surface::is_embedded_solid`] certifies, the side comes from the pseudo-normal test of
//! Bærentzen and Aanæs (2005, *Signed distance computation using the angle weighted
//! pseudonormal*, IEEE TVCG 11(3)), decided exactly: the query point lies strictly on the
//! same side of every triangle through its closest point, by Shewchuk's orientation
//! predicate. That costs a closest-point query and a few orientation tests. Where the
//! planes do not agree (a query between the planes of a sharp edge or a saddle vertex),
//! the pseudo-normal is evaluated in floating point and taken where its rigorous error
//! bound leaves no doubt. What that cannot decide (a query on the medial axis, on a
//! triangle's plane, within rounding of the surface), and every query on a mesh that is
//! not certified, is left to the certified winding number
//! ([`Surface::is_inside_certified`]). Either way the answer is the exact winding number's,
//! for every query point not within rounding of the surface.
//!
//! On the shared meshes that are certified, the pseudo-normal test decides all but a
//! handful of random points of the bounding box (`report_certificates_and_timings` in the
//! crate's `tests/signed_closest.rs` prints the counts and timings), so a signed closest
//! point costs about what a closest point costs.
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_query::Surface;
//!
//! let surface = Surface::new(&shapes::torus(1.0, 0.3, 32)?)?;
//! assert!(surface.is_embedded_solid());
//! for p in [DVec3::ZERO, DVec3::new(1.1, 0.0, 0.1), DVec3::new(0.0, 2.0, 0.5)] {
//!     let answer = surface.signed_closest(p)?;
//!     assert_eq!(answer.inside, surface.is_inside_certified(p));
//!     assert_eq!(answer.closest, surface.closest(p)?);
//! }
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```
//!
//! # The embedded-solid certificate
//!
//! Built once by [`Surface::from_mesh`], exactly (integer topology and exact orientation
//! predicates, no tolerance): the mesh must be a closed, consistently oriented 2-manifold
//! (every edge used by two triangles in opposite directions, one fan of triangles per
//! vertex), without degenerate triangles or two vertices at one position, whose triangles
//! meet only in the vertices and edges they share (no crossing, touching or coplanar
//! overlap, no fold across a shared edge), and whose winding number is 0 in front of and
//! 1 behind the triangles of every component (no inward-oriented or nested shell). The
//! first defect is kept ([`Surface::embedding_defect`], an [`EmbeddingDefect`]).
//!
//! A mesh that is not a closed oriented manifold is refused after a linear pass over its
//! edges; otherwise the contact search tests the pairs of triangles whose boxes touch,
//! `O(n log n)` with the closest-point tree's boxes, on every core with the `parallel`
//! feature (the same answer either way).

mod contacts;
mod embedding;
mod intersect;
mod pseudo_normal;
mod signed;
#[cfg(test)]
mod tests;

use glam::DVec3;

use crate::QueryError;
use crate::closest::{ClosestPoint, TriangleTree};
use crate::sampling;
use crate::winding::{CertifiedSide, WindingBoundary, WindingNumber};
use sphaera_mesh::TriMesh;

pub use signed::{SideMethod, SignedClosest};

/// Why a [`Surface`] is not certified as an embedded solid ([`Surface::embedding_defect`]):
/// the first defect the certificate met, with where it is. Such a surface still answers
/// [`Surface::signed_closest`] exactly, with the certified winding number for the side.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh, shapes};
/// use sphaera_query::{Surface, surface::EmbeddingDefect};
///
/// // Two cubes overlapping: a closed manifold mesh, but its shells cross.
/// let cube = shapes::cube(2.0, 1)?;
/// let mut positions = cube.positions().to_vec();
/// positions.extend(cube.positions().iter().map(|&p| p + DVec3::splat(1.0)));
/// let mut triangles = cube.triangles().to_vec();
/// triangles.extend(cube.triangles().iter().map(|t| t.map(|v| v + 8)));
/// let surface = Surface::new(&TriMesh::new(positions, triangles)?)?;
/// assert!(matches!(
///     surface.embedding_defect(),
///     Some(EmbeddingDefect::SelfIntersection { .. })
/// ));
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum EmbeddingDefect {
    /// The surface is a shell ([`Surface::shell`]): it bounds no solid.
    #[error("the surface is a shell, without an inside")]
    Shell,
    /// A coordinate is outside the range where the exact predicates stay exact: non-zero
    /// magnitudes must lie in `[2^-250, 2^250]` (about `5.5e-76` to `1.8e75`).
    #[error("vertex {vertex} has a coordinate beyond the range of exact predicates")]
    CoordinateRange {
        /// The vertex.
        vertex: u32,
    },
    /// A triangle repeats a vertex or has collinear corners (zero area).
    #[error("triangle {triangle} is degenerate (a repeated vertex or collinear corners)")]
    DegenerateTriangle {
        /// The triangle.
        triangle: u32,
    },
    /// Two vertices used by triangles are at the same position (weld them first).
    #[error("vertices {first} and {second} are at the same position")]
    DuplicatePosition {
        /// The smaller vertex index of the first such pair found.
        first: u32,
        /// The other vertex.
        second: u32,
    },
    /// An edge is used by a number of triangles other than two (a hole or a
    /// non-manifold edge).
    #[error("edge ({v0}, {v1}) is used by {triangles} triangles instead of 2")]
    OpenOrNonManifoldEdge {
        /// The smaller vertex index of the edge.
        v0: u32,
        /// The larger one.
        v1: u32,
        /// The number of triangles using it.
        triangles: usize,
    },
    /// The two triangles of an edge traverse it in the same direction.
    #[error("the two triangles of edge ({v0}, {v1}) are oriented inconsistently")]
    InconsistentOrientation {
        /// The smaller vertex index of the edge.
        v0: u32,
        /// The larger one.
        v1: u32,
    },
    /// The triangles around a vertex form several fans (the surface is pinched there).
    #[error("vertex {vertex} is non-manifold (its triangles form several fans)")]
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
    },
    /// Two triangles meet in more than the vertices they share: they cross, touch,
    /// overlap in a common plane, or fold onto each other across their common edge.
    #[error("triangles {first} and {second} intersect")]
    SelfIntersection {
        /// The smaller triangle index of the smallest such pair.
        first: u32,
        /// The other triangle.
        second: u32,
    },
    /// The winding number is not 0 just in front of and 1 just behind this triangle (its
    /// component is inward oriented or nested in another shell), or no probe beside it
    /// could be certified to see only its component.
    #[error("the winding number is not 0 in front of and 1 behind triangle {triangle}")]
    NotOutward {
        /// The triangle probed (the largest of its component).
        triangle: u32,
    },
}

/// Probes used to decide whether the mesh has an inside.
const INSIDE_PROBES: usize = 256;

/// Fraction of probes that must show a clear inside/outside jump across the surface.
const INSIDE_QUORUM: f64 = 0.5;

/// A mesh prepared as the boundary of a solid: the generalized winding number decides
/// inside and outside (robust to holes, non-manifold edges and open parts), and a
/// [`TriangleTree`] gives exact closest points. It keeps the mesh, so whatever needs the
/// surface (the medial approximation, sphere-tree construction and evaluation) takes a
/// `Surface` alone. Immutable and `Sync`: threads share it.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_query::Surface;
///
/// let mesh = shapes::sphere(1.0, 12)?;
/// let surface = Surface::new(&mesh)?;
/// assert!(surface.is_inside(DVec3::ZERO));
/// assert!(!surface.is_inside(DVec3::splat(2.0)));
/// let closest = surface.closest(DVec3::ZERO)?;
/// // The inscribed polyhedron: within 1, its faces a little closer.
/// assert!(closest.distance <= 1.0 && closest.distance > 0.9);
/// assert_eq!(surface.mesh().triangle_count(), mesh.triangle_count());
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Debug)]
pub struct Surface {
    mesh: TriMesh,
    winding: WindingNumber,
    tree: TriangleTree,
    diagonal: f64,
    /// The largest coordinate magnitude of the referenced vertices (the scale of the
    /// rounding of closest distances).
    scale: f64,
    /// The embedded-solid certificate.
    embedding: Result<(), EmbeddingDefect>,
    /// The vertices' pseudo-normals (empty unless certified).
    normals: pseudo_normal::VertexNormals,
    /// Whether the mesh bounds a solid; a shell ([`Surface::shell`]) has no inside.
    solid: bool,
    /// The boundary chain (the holes), built on first use.
    boundary: std::sync::OnceLock<WindingBoundary>,
}

impl Surface {
    /// Prepares a copy of `mesh` (see [`Surface::from_mesh`] to hand it over instead).
    ///
    /// # Errors
    ///
    /// As [`Surface::from_mesh`].
    pub fn new(mesh: &TriMesh) -> Result<Self, QueryError> {
        Self::from_mesh(mesh.clone())
    }

    /// Prepares `mesh`, keeping it (no copy; [`Surface::new`] copies).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let surface = Surface::from_mesh(shapes::torus(1.0, 0.3, 24)?)?;
    /// assert!(surface.is_inside(DVec3::new(1.0, 0.0, 0.0)));
    /// assert!(!surface.is_inside(DVec3::ZERO)); // the hole
    /// // The inner equator is 0.7 from the centre, up to the tessellation.
    /// let inner = surface.closest(DVec3::ZERO)?.distance;
    /// assert!((inner - 0.7).abs() < 0.05, "{inner}");
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] for a mesh without triangles,
    /// [`QueryError::InwardOrientation`] for a closed mesh whose triangles face inward (flip
    /// them), and [`QueryError::NoInside`] when inside is meaningless: a flat sheet, a
    /// single open patch, a mesh whose winding number does not jump from about 1 to about
    /// 0 across most of its surface.
    ///
    /// # Performance
    ///
    /// One `O(n log n)` box-tree build over the `n` triangles, shared by the closest-point
    /// tree and the winding number's (refined to its smaller leaves), the winding
    /// number's expansions and 512 winding-number probes (the preparation of the
    /// 69k-triangle bunny is timed in the section *Adaptive medial approximation
    /// (`sphaera-medial`)* of `docs/benchmarks.md` in the repository). Then the
    /// embedded-solid certificate (see the [module documentation](self)): a linear pass
    /// that refuses meshes that are not closed oriented manifolds, and for the
    /// others an `O(n log n)` contact search over the closest-point tree (parallel with
    /// the `parallel` feature) and two certified winding numbers per component.
    pub fn from_mesh(mesh: TriMesh) -> Result<Self, QueryError> {
        let mut surface = Self::prepare(mesh)?;
        surface.check_inside()?;
        surface.certify();
        Ok(surface)
    }

    /// Prepares a copy of `mesh` as a **shell**: a surface without an inside (a sign, a
    /// cloth, a plate modelled as one sheet, an open patch), every point of space lying
    /// outside it. Closest points are those of [`Surface::new`]; [`Surface::is_inside`],
    /// [`Surface::is_inside_certified`] and [`Surface::signed_closest`] answer "outside"
    /// everywhere, so a sphere's error (how far it reaches from the surface) counts every
    /// point of it. Use [`Surface::solid_or_shell`] to take the solid when there is one.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh};
    /// use sphaera_query::Surface;
    ///
    /// // A unit square in the plane z = 0: no inside, so Surface::new refuses it.
    /// let square = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// assert!(Surface::new(&square).is_err());
    /// let shell = Surface::shell(&square)?;
    /// assert!(!shell.has_inside());
    /// let below = shell.signed_closest(DVec3::new(0.5, 0.5, -0.25))?;
    /// assert!(!below.inside && below.signed_distance() == 0.25);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] for a mesh without triangles.
    pub fn shell(mesh: &TriMesh) -> Result<Self, QueryError> {
        let mut surface = Self::prepare(mesh.clone())?;
        surface.solid = false;
        surface.embedding = Err(EmbeddingDefect::Shell);
        Ok(surface)
    }

    /// Prepares a copy of `mesh` as a solid when it has a meaningful inside (as
    /// [`Surface::new`]), else as a shell ([`Surface::shell`]): the choice of a caller that
    /// must handle flat sheets and open patches as well as solids.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh, shapes};
    /// use sphaera_query::Surface;
    ///
    /// assert!(Surface::solid_or_shell(&shapes::cube(1.0, 1)?)?.has_inside());
    /// let sheet = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
    /// assert!(!Surface::solid_or_shell(&sheet)?.has_inside());
    /// // A cube whose triangles face inward is a mistake, not a sheet.
    /// let cube = shapes::cube(1.0, 1)?;
    /// let flipped: Vec<[u32; 3]> = cube.triangles().iter().map(|&[a, b, c]| [a, c, b]).collect();
    /// let inward = TriMesh::new(cube.positions().to_vec(), flipped)?;
    /// assert!(matches!(
    ///     Surface::solid_or_shell(&inward),
    ///     Err(sphaera_query::QueryError::InwardOrientation { .. })
    /// ));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] for a mesh without triangles, and
    /// [`QueryError::InwardOrientation`] for a closed mesh whose triangles face inward (a
    /// solid oriented the wrong way is not a shell: flip its triangles).
    pub fn solid_or_shell(mesh: &TriMesh) -> Result<Self, QueryError> {
        let mut surface = Self::prepare(mesh.clone())?;
        match surface.check_inside() {
            Ok(()) => surface.certify(),
            Err(QueryError::NoInside { .. }) => {
                surface.solid = false;
                surface.embedding = Err(EmbeddingDefect::Shell);
            }
            Err(e) => return Err(e),
        }
        Ok(surface)
    }

    /// Whether the surface bounds a solid (it was prepared by [`Surface::new`], or by
    /// [`Surface::solid_or_shell`] from a mesh with an inside); `false` for a shell.
    #[must_use]
    pub fn has_inside(&self) -> bool {
        self.solid
    }

    /// The embedded-solid certificate and, when it holds, the pseudo-normals.
    fn certify(&mut self) {
        self.embedding = embedding::certify(&self.mesh, &self.tree, &self.winding, self.scale);
        if self.embedding.is_ok() {
            self.normals = pseudo_normal::VertexNormals::new(&self.mesh);
        }
    }

    /// The trees and measures of `mesh`, not yet checked for an inside or certified.
    fn prepare(mesh: TriMesh) -> Result<Self, QueryError> {
        if mesh.triangle_count() == 0 {
            return Err(QueryError::EmptyMesh);
        }
        // Both trees split the same boxes the same way, the winding number's to smaller
        // leaves: one build, refined for it.
        let boxes = crate::closest::triangle_boxes(&mesh);
        let coarse = crate::bvh::BoxTree::build(&boxes, crate::closest::LEAF_SIZE)?;
        let fine = coarse.refined(&boxes, crate::winding::LEAF_SIZE);
        drop(boxes);
        // The two trees' own parts are independent: built side by side with `parallel`.
        #[cfg(feature = "parallel")]
        let (winding, tree) = rayon::join(
            || WindingNumber::with_boxes(&mesh, &fine),
            || TriangleTree::with_boxes(&mesh, coarse),
        );
        #[cfg(not(feature = "parallel"))]
        let (winding, tree) = (
            WindingNumber::with_boxes(&mesh, &fine),
            TriangleTree::with_boxes(&mesh, coarse),
        );
        let winding = winding?;
        let diagonal = mesh.bounding_box_diagonal();
        let bounds = mesh.bounding_box();
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
        Ok(Self {
            mesh,
            winding,
            tree,
            diagonal,
            scale,
            embedding: Ok(()),
            normals: pseudo_normal::VertexNormals::default(),
            solid: true,
            boundary: std::sync::OnceLock::new(),
        })
    }

    /// Probes pairs of points just inside and just outside the surface (along the normals
    /// of random surface samples): on a solid the winding number is about 1 inside and 0
    /// outside; on a sheet about ±½ on both sides; on a solid whose triangles face inward,
    /// about 0 behind them and −1 in front ([`QueryError::InwardOrientation`], which
    /// [`Surface::solid_or_shell`] does not take for a shell).
    fn check_inside(&self) -> Result<(), QueryError> {
        let probes = sampling::random(&self.mesh, INSIDE_PROBES, 0x1D5E)?;
        let offset = 1e-4 * self.diagonal;
        let mut clear = 0_usize;
        let mut inverted = 0_usize;
        let mut inner_windings = Vec::with_capacity(probes.len());
        for s in &probes {
            if s.normal == DVec3::ZERO {
                continue;
            }
            let inner = self.winding.winding_number(s.position - offset * s.normal);
            let outer = self.winding.winding_number(s.position + offset * s.normal);
            inner_windings.push(inner);
            if inner > 0.75 && outer.abs() < 0.25 {
                clear += 1;
            }
            if outer < -0.75 && inner.abs() < 0.25 {
                inverted += 1;
            }
        }
        let counted = inner_windings.len();
        let share = |n: usize| {
            if counted == 0 {
                0.0
            } else {
                n as f64 / counted as f64
            }
        };
        if share(clear) >= INSIDE_QUORUM {
            return Ok(());
        }
        if share(inverted) >= INSIDE_QUORUM {
            inner_windings.sort_by(f64::total_cmp);
            return Err(QueryError::InwardOrientation {
                median_inner_winding: inner_windings[counted / 2],
            });
        }
        Err(QueryError::NoInside {
            fraction: share(clear),
        })
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// Whether `p` is inside (generalized winding number above ½; never for a shell).
    #[must_use]
    pub fn is_inside(&self, p: DVec3) -> bool {
        self.solid && self.winding.is_inside(p)
    }

    /// [`Surface::is_inside`] with the answer of the exact generalized winding number
    /// ([`WindingNumber::is_inside_certified`]): where the fast value's error bound cannot
    /// decide, the point is evaluated again more finely, and exactly as a last resort.
    /// Exact except within rounding of the surface itself.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
    /// assert!(surface.is_inside_certified(DVec3::new(0.0, 0.0, 0.9)));
    /// assert!(!surface.is_inside_certified(DVec3::new(0.0, 0.0, 1.01)));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Performance
    ///
    /// Several times the cost of [`Surface::is_inside`] on random points, more very near
    /// the surface; the rates of both are in the section *Inside/outside (generalized
    /// winding number)* of `docs/benchmarks.md` in the repository.
    #[must_use]
    pub fn is_inside_certified(&self, p: DVec3) -> bool {
        self.solid && self.winding.is_inside_certified(p)
    }

    /// [`Surface::is_inside_certified`]'s answer with a certified margin of the winding
    /// number from ½ ([`WindingNumber::side_with_margin`], refined while the margin is
    /// below `wanted`), or `None` when the certified traversals do not decide (no exact
    /// evaluation is made). A shell answers outside with an infinite margin: no point of
    /// space is inside it.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
    /// let side = surface.side_with_margin(DVec3::new(0.0, 0.0, 0.5), 0.25).expect("decided");
    /// assert!(side.inside && side.margin >= 0.25);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn side_with_margin(&self, p: DVec3, wanted: f64) -> Option<CertifiedSide> {
        if self.solid {
            let boundary = self.winding_boundary();
            if boundary.is_empty() {
                self.winding.side_with_margin(p, wanted)
            } else {
                self.winding.side_with_boundary(p, boundary, wanted)
            }
        } else {
            Some(CertifiedSide {
                inside: false,
                margin: f64::INFINITY,
            })
        }
    }

    /// On a mesh with holes taken as a solid: the integer winding number at `p` of the
    /// mesh closed by the caps of its [`Surface::winding_boundary`], and the side and
    /// margin it gives ([`WindingNumber::capped_side`]). `None` for a closed mesh or a
    /// shell, and where it does not decide.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let cube = shapes::cube(2.0, 1)?;
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// let (closed, side) = Surface::new(&open)?.capped_side(DVec3::ZERO).expect("decided");
    /// assert!(side.inside && closed == 1.0);
    /// assert!(Surface::new(&cube)?.capped_side(DVec3::ZERO).is_none());
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn capped_side(&self, p: DVec3) -> Option<(f64, CertifiedSide)> {
        if !self.solid {
            return None;
        }
        self.winding.capped_side(p, self.winding_boundary())
    }

    /// The boundary chain of the mesh (the rims of its holes, [`WindingBoundary`]), which
    /// bounds how fast the winding number varies off the mesh: empty for a closed mesh.
    /// Built on the first call (linear in the triangles) and kept; a certified embedded
    /// solid ([`Surface::is_embedded_solid`]) has none and costs nothing.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_query::Surface;
    /// use sphaera_mesh::{TriMesh, shapes};
    ///
    /// let cube = shapes::cube(2.0, 1)?;
    /// assert!(Surface::new(&cube)?.winding_boundary().is_empty());
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// assert_eq!(Surface::new(&open)?.winding_boundary().edge_count(), 3);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn winding_boundary(&self) -> &WindingBoundary {
        self.boundary.get_or_init(|| {
            if self.embedding.is_ok() {
                WindingBoundary::default()
            } else {
                WindingBoundary::new(&self.mesh)
            }
        })
    }

    /// The bounding-box diagonal of the mesh.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The number of triangles of the mesh.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// The exact closest point of the surface to `p`.
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for a NaN or infinite coordinate.
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, QueryError> {
        self.tree.closest(p)
    }

    /// The closest-point tree over the mesh's triangles.
    #[must_use]
    pub fn tree(&self) -> &TriangleTree {
        &self.tree
    }

    /// Whether the mesh is certified as the boundary of an embedded solid (see the
    /// [module documentation](self)): then [`Surface::signed_closest`] decides most sides
    /// by the exact pseudo-normal test instead of the winding number.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_query::Surface;
    /// use sphaera_mesh::shapes;
    ///
    /// assert!(Surface::new(&shapes::capsule(0.5, 2.0, 16)?)?.is_embedded_solid());
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn is_embedded_solid(&self) -> bool {
        self.embedding.is_ok()
    }

    /// Why the mesh is not certified as an embedded solid, or `None` when it is.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_query::{Surface, surface::EmbeddingDefect};
    /// use sphaera_mesh::{TriMesh, shapes};
    ///
    /// // A cube with one triangle missing is open.
    /// let cube = shapes::cube(2.0, 1)?;
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// let defect = Surface::new(&open)?.embedding_defect();
    /// assert!(matches!(defect, Some(EmbeddingDefect::OpenOrNonManifoldEdge { triangles: 1, .. })));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn embedding_defect(&self) -> Option<EmbeddingDefect> {
        self.embedding.err()
    }

    /// The exact closest point of the surface to `p` (as [`Surface::closest`]) and
    /// whether `p` is inside, as [`Surface::is_inside_certified`] answers: exact for every
    /// point not within rounding of the surface.
    ///
    /// On a certified embedded solid ([`Surface::is_embedded_solid`]) the side is decided
    /// by the pseudo-normal test ([`SideMethod::PseudoNormal`], see the
    /// [module documentation](self)) wherever it is certain, and otherwise, and on other
    /// meshes, by the certified winding number ([`SideMethod::CertifiedWinding`]).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::{Surface, closest::Feature, surface::SideMethod};
    ///
    /// let surface = Surface::new(&shapes::cube(2.0, 1)?)?; // the cube [-1, 1]³
    /// let corner = surface.signed_closest(DVec3::splat(1.5))?;
    /// assert!(!corner.inside);
    /// assert_eq!(corner.closest.point, DVec3::ONE);
    /// assert!(matches!(corner.closest.feature, Feature::Vertex(_)));
    /// assert_eq!(corner.method, SideMethod::PseudoNormal);
    /// let centre = surface.signed_closest(DVec3::new(0.1, 0.2, 0.3))?;
    /// assert!(centre.inside && centre.signed_distance() < 0.0);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for a NaN or infinite coordinate.
    ///
    /// # Performance
    ///
    /// A closest-point descent with a slightly wider bound than [`Surface::closest`]'s and
    /// one orientation test per triangle through the closest point (a few more products
    /// at sharp edges and saddle vertices), so about the cost of [`Surface::closest`]
    /// alone on a certified mesh, where [`Surface::closest`] plus
    /// [`Surface::is_inside_certified`] costs several times more. Queries the
    /// pseudo-normal test cannot decide, and every query on a mesh that is not certified,
    /// pay for the certified winding number as well.
    pub fn signed_closest(&self, p: DVec3) -> Result<SignedClosest, QueryError> {
        self.signed(p, true)
    }

    /// [`Surface::signed_closest`] with the fast winding number ([`Surface::is_inside`],
    /// [`SideMethod::FastWinding`]) where the pseudo-normal test does not decide: faster on
    /// meshes that are not certified, and not certified near the surface there.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
    /// assert!(surface.signed_closest_approx(DVec3::new(0.0, 0.3, 0.0))?.inside);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for a NaN or infinite coordinate.
    pub fn signed_closest_approx(&self, p: DVec3) -> Result<SignedClosest, QueryError> {
        self.signed(p, false)
    }

    /// [`Surface::signed_closest`] for every point of `points`, in order, on every core
    /// with the `parallel` feature (the same answers either way).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::Surface;
    ///
    /// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
    /// let answers = surface.signed_closest_many(&[DVec3::ZERO, DVec3::splat(2.0)])?;
    /// assert_eq!(answers.iter().map(|a| a.inside).collect::<Vec<_>>(), [true, false]);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for the first non-finite point.
    pub fn signed_closest_many(&self, points: &[DVec3]) -> Result<Vec<SignedClosest>, QueryError> {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            points.par_iter().map(|&p| self.signed_closest(p)).collect()
        }
        #[cfg(not(feature = "parallel"))]
        {
            points.iter().map(|&p| self.signed_closest(p)).collect()
        }
    }

    /// The signed closest point, with the certified (`certified`) or the fast winding
    /// number where the planes do not decide.
    fn signed(&self, p: DVec3, certified: bool) -> Result<SignedClosest, QueryError> {
        let (closest, side) = if self.embedding.is_ok() {
            let (closest, ties) = signed::closest_with_ties(&self.tree, p, self.scale)?;
            let side = signed::side_of_ties(&self.tree, &ties, p).or_else(|| {
                pseudo_normal::side(
                    &self.tree,
                    &self.normals,
                    &closest,
                    &ties,
                    p,
                    signed::absolute_slack(self.scale, p),
                    signed::TIE_SLACK,
                )
            });
            (closest, side)
        } else {
            (self.tree.closest(p)?, None)
        };
        let (inside, method) = match side {
            _ if !self.solid => (false, SideMethod::Shell),
            Some(inside) => (inside, SideMethod::PseudoNormal),
            None if certified => (
                self.winding.is_inside_certified(p),
                SideMethod::CertifiedWinding,
            ),
            None => (self.winding.is_inside(p), SideMethod::FastWinding),
        };
        Ok(SignedClosest {
            closest,
            inside,
            method,
        })
    }
}
