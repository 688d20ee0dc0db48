//! A mesh prepared as the boundary of a solid: its inside test (generalized winding
//! number) and its exact closest points (the [`TriangleTree`]), checked once for a
//! meaningful inside.

use glam::DVec3;

use crate::closest::{ClosestPoint, TriangleTree};
use crate::winding::WindingNumber;
use crate::{MeshError, TriMesh, sampling};

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
/// use sphaera_mesh::{DVec3, Surface, shapes};
///
/// let mesh = shapes::sphere(1.0, 12)?;
/// let surface = Surface::new(&mesh)?;
/// assert!(surface.is_inside(DVec3::ZERO));
/// assert!(!surface.is_inside(DVec3::splat(2.0)));
/// let closest = surface.closest(DVec3::ZERO)?;
/// // The inscribed polyhedron: within 1, its faces a little closer.
/// assert!(closest.distance <= 1.0 && closest.distance > 0.9);
/// assert_eq!(surface.mesh().triangle_count(), mesh.triangle_count());
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Debug)]
pub struct Surface {
    mesh: TriMesh,
    winding: WindingNumber,
    tree: TriangleTree,
    diagonal: f64,
}

impl Surface {
    /// Prepares a copy of `mesh` (see [`Surface::from_mesh`] to hand it over instead).
    ///
    /// # Errors
    ///
    /// As [`Surface::from_mesh`].
    pub fn new(mesh: &TriMesh) -> Result<Self, MeshError> {
        Self::from_mesh(mesh.clone())
    }

    /// Prepares `mesh`, keeping it (no copy; [`Surface::new`] copies).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, Surface, shapes};
    ///
    /// let surface = Surface::from_mesh(shapes::torus(1.0, 0.3, 24)?)?;
    /// assert!(surface.is_inside(DVec3::new(1.0, 0.0, 0.0)));
    /// assert!(!surface.is_inside(DVec3::ZERO)); // the hole
    /// // The inner equator is 0.7 from the centre, up to the tessellation.
    /// let inner = surface.closest(DVec3::ZERO)?.distance;
    /// assert!((inner - 0.7).abs() < 0.05, "{inner}");
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`MeshError::EmptyMesh`] for a mesh without triangles, and [`MeshError::NoInside`]
    /// when inside is meaningless: a flat sheet, a single open patch, a mesh whose winding
    /// number does not jump from about 1 to about 0 across most of its surface (an
    /// inside-out mesh is reported the same way).
    ///
    /// # Performance
    ///
    /// Two `O(n log n)` tree builds over the `n` triangles (the winding number's and the
    /// closest-point tree) and 512 winding-number probes: about 0.15 s for the
    /// 69k-triangle bunny.
    pub fn from_mesh(mesh: TriMesh) -> Result<Self, MeshError> {
        // The two trees are independent: built side by side with `parallel`.
        #[cfg(feature = "parallel")]
        let (winding, tree) =
            rayon::join(|| WindingNumber::new(&mesh), || TriangleTree::new(&mesh));
        #[cfg(not(feature = "parallel"))]
        let (winding, tree) = (WindingNumber::new(&mesh), TriangleTree::new(&mesh));
        let (winding, tree) = (winding?, tree?);
        let diagonal = mesh.bounding_box_diagonal();
        let surface = Self {
            mesh,
            winding,
            tree,
            diagonal,
        };
        surface.check_inside()?;
        Ok(surface)
    }

    /// Probes pairs of points just inside and just outside the surface (along the normals
    /// of random surface samples): on a solid the winding number is about 1 inside and 0
    /// outside; on a sheet about ±½ on both sides.
    fn check_inside(&self) -> Result<(), MeshError> {
        let probes = sampling::random(&self.mesh, INSIDE_PROBES, 0x1D5E)?;
        let offset = 1e-4 * self.diagonal;
        let mut clear = 0_usize;
        let mut counted = 0_usize;
        for s in &probes {
            if s.normal == DVec3::ZERO {
                continue;
            }
            counted += 1;
            let inner = self.winding.winding_number(s.position - offset * s.normal);
            let outer = self.winding.winding_number(s.position + offset * s.normal);
            if inner > 0.75 && outer.abs() < 0.25 {
                clear += 1;
            }
        }
        let fraction = if counted == 0 {
            0.0
        } else {
            clear as f64 / counted as f64
        };
        if fraction < INSIDE_QUORUM {
            return Err(MeshError::NoInside { fraction });
        }
        Ok(())
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// Whether `p` is inside (generalized winding number above ½).
    #[must_use]
    pub fn is_inside(&self, p: DVec3) -> bool {
        self.winding.is_inside(p)
    }

    /// [`Surface::is_inside`] with the answer of the exact generalized winding number
    /// ([`WindingNumber::is_inside_certified`]): where the fast value's error bound cannot
    /// decide, the point is evaluated again more finely, and exactly as a last resort.
    /// Exact except within rounding of the surface itself.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, Surface, shapes};
    ///
    /// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
    /// assert!(surface.is_inside_certified(DVec3::new(0.0, 0.0, 0.9)));
    /// assert!(!surface.is_inside_certified(DVec3::new(0.0, 0.0, 1.01)));
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Performance
    ///
    /// 4 to 15 times the cost of [`Surface::is_inside`] on random points, more very near
    /// the surface.
    #[must_use]
    pub fn is_inside_certified(&self, p: DVec3) -> bool {
        self.winding.is_inside_certified(p)
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
    /// [`MeshError::NonFiniteQuery`] for a NaN or infinite coordinate.
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, MeshError> {
        self.tree.closest(p)
    }

    /// The closest-point tree over the mesh's triangles.
    #[must_use]
    pub fn tree(&self) -> &TriangleTree {
        &self.tree
    }
}
