//! Deformation support (Meshsweeper section 5.3): error radii for new vertex positions by
//! replaying the recorded collapses, and conservative inflation from per-vertex
//! displacement bounds without any geometric work.

use glam::DVec3;
use sphaera_mesh::TriMesh;
use sphaera_mesh::topology::{FaceId, HalfEdgeMesh, VertexId};

use crate::hierarchy::Geometry;
use crate::spheres::{BoundaryPolicy, collapse_radius};
use crate::{Hierarchy, Placement, SimplifyError};

/// Relative safety margin against rounding for the simple-map radius (as the engine's).
const ROUNDING_MARGIN: f64 = 1e-12;

impl Hierarchy {
    /// The same hierarchy (same collapses, same tables) for new positions of the input
    /// vertices, with every error radius recomputed by replaying the collapse sequence —
    /// for key-frames of a deformation.
    ///
    /// Each collapse gets the tight radius of the build when its projected map is still
    /// injective for the new positions, and otherwise the radius of the simple map that
    /// sends the removed vertex onto its parent (`r_u + |u − v|`), which is valid for any
    /// positions (flipped triangles included). So the result always satisfies both
    /// error-sphere invariants for the new geometry, in every refinement state. No
    /// collapse is chosen or refused: only radii change.
    ///
    /// # Errors
    ///
    /// [`SimplifyError::LengthMismatch`] if `positions` does not have one entry per input
    /// vertex; [`SimplifyError::Mesh`] if a position is not finite;
    /// [`SimplifyError::NeedsSubsetPlacement`] for an optimal-placement hierarchy.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// One radius evaluation per collapse (a fraction of the build's time, which evaluates
    /// every candidate many times).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 12)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default().with_target_ratio(0.1))?;
    /// // Stretch along x by 50 %.
    /// let stretched: Vec<_> = sphere.positions().iter().map(|p| p * glam::DVec3::new(1.5, 1.0, 1.0)).collect();
    /// let frame = hierarchy.replay(&stretched)?;
    /// assert_eq!(frame.collapse_count(), hierarchy.collapse_count());
    /// assert!(frame.base().error_bound > hierarchy.base().error_bound);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn replay(&self, positions: &[DVec3]) -> Result<Hierarchy, SimplifyError> {
        self.require_subset("replay")?;
        let (input_vertices, _) = self.tables.input_counts;
        if positions.len() != input_vertices {
            return Err(SimplifyError::LengthMismatch {
                name: "positions",
                actual: positions.len(),
                expected: input_vertices,
            });
        }
        let mut mesh = self.finest_half_edges(positions)?;
        let mut radii = vec![0.0; mesh.vertex_count()];
        let mut out = Vec::with_capacity(self.collapse_count());
        for c in 0..self.collapse_count() {
            let (u, v) = (self.tables.removed[c], self.tables.parent[c]);
            let edge = mesh
                .outgoing(VertexId(u))
                .find(|&g| mesh.target(g) == VertexId(v))
                .ok_or(SimplifyError::Internal {
                    what: "a recorded collapse edge is missing in the replay",
                })?;
            let (pu, pv) = (mesh.position(VertexId(u)), mesh.position(VertexId(v)));
            let (ru, rv) = (radii[u as usize], radii[v as usize]);
            let simple = {
                let r = f64::max(rv, ru + (pu - pv).length());
                r + ROUNDING_MARGIN * r.max(pu.abs().max_element()).max(pv.abs().max_element())
            };
            let policy = if mesh.is_boundary_vertex(VertexId(u)) {
                BoundaryPolicy::Collapse
            } else {
                BoundaryPolicy::Lock
            };
            let tight = collapse_radius(&mesh, &radii, edge, policy).unwrap_or(f64::INFINITY);
            let r = tight.min(simple);
            mesh.collapse_edge(edge, pv)?;
            radii[v as usize] = r;
            out.push(r);
        }
        Ok(Hierarchy {
            tables: self.tables.clone(),
            geometry: Geometry {
                positions: (0..mesh.vertex_count() as u32)
                    .map(|x| mesh.position(VertexId(x)))
                    .collect(),
                placed: Vec::new(),
                radii: out,
                offsets: Vec::new(),
            },
        })
    }

    /// The same hierarchy with every radius enlarged so that it stays valid while each
    /// input vertex `i` moves by at most `displacement[i]` from its position here — the
    /// second method of Meshsweeper's section 5.3, with no geometric computation.
    ///
    /// The collapses are walked in order, tracking for every triangle the largest
    /// displacement over the part of the input surface it stands for; a vertex's offset is
    /// twice the largest such value over the triangles it ever bounds (a point of a
    /// simplified triangle and the input point it covers each move by at most that much).
    /// Offsets are per vertex and the same in every refinement state, and they are added to
    /// the radii ([`Hierarchy::radius_after`], [`Refinement::radius`](crate::Refinement::radius)).
    /// Positions are unchanged: the caller tracks the moving vertices. Inflating an
    /// inflated hierarchy adds the offsets.
    ///
    /// # Errors
    ///
    /// [`SimplifyError::LengthMismatch`] for a wrong length;
    /// [`SimplifyError::InvalidVertexValue`] for a NaN, infinite or negative displacement;
    /// [`SimplifyError::NeedsSubsetPlacement`] for an optimal-placement hierarchy.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// Linear in the total size of the fans of the collapses; no square roots.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 12)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default().with_target_ratio(0.1))?;
    /// let moving = hierarchy.inflate(&vec![0.01; sphere.vertex_count()])?;
    /// let (a, b) = (hierarchy.base(), moving.base());
    /// assert!((b.error_bound - a.error_bound - 0.02).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn inflate(&self, displacement: &[f64]) -> Result<Hierarchy, SimplifyError> {
        self.require_subset("inflate")?;
        let (input_vertices, _) = self.tables.input_counts;
        if displacement.len() != input_vertices {
            return Err(SimplifyError::LengthMismatch {
                name: "displacement",
                actual: displacement.len(),
                expected: input_vertices,
            });
        }
        if let Some((index, &value)) = displacement
            .iter()
            .enumerate()
            .find(|(_, d)| !(d.is_finite() && **d >= 0.0))
        {
            return Err(SimplifyError::InvalidVertexValue {
                name: "displacement",
                index,
                value,
                requirement: "finite and non-negative",
            });
        }
        let delta = |x: u32| {
            self.original_vertex(x)
                .and_then(|i| displacement.get(i as usize))
                .copied()
                .unwrap_or(0.0)
        };
        let mut corners = self.tables.triangles.clone();
        let mut moved: Vec<f64> = corners
            .iter()
            .map(|t| t.iter().fold(0.0_f64, |m, &x| m.max(delta(x))))
            .collect();
        let mut offsets = vec![0.0_f64; self.vertex_count()];
        for c in 0..self.collapse_count() as u32 {
            let (u, v) = (
                self.tables.removed[c as usize],
                self.tables.parent[c as usize],
            );
            let fan = self.triangles_added_by_split(c);
            let worst = fan.iter().fold(0.0_f64, |m, &t| m.max(moved[t as usize]));
            for &t in self.triangles_removed_by_split(c) {
                let t = t as usize;
                moved[t] = worst;
                for x in &mut corners[t] {
                    if *x == u {
                        *x = v;
                    }
                    offsets[*x as usize] = offsets[*x as usize].max(2.0 * worst);
                }
            }
        }
        for (o, &old) in offsets.iter_mut().zip(&self.geometry.offsets) {
            *o += old;
        }
        Ok(Hierarchy {
            tables: self.tables.clone(),
            geometry: Geometry {
                offsets,
                ..self.geometry.clone()
            },
        })
    }

    fn require_subset(&self, operation: &'static str) -> Result<(), SimplifyError> {
        if self.placement() == Placement::Subset {
            Ok(())
        } else {
            Err(SimplifyError::NeedsSubsetPlacement { operation })
        }
    }

    /// The finest half-edge mesh for `positions` (one per input vertex), checked against
    /// the tables.
    fn finest_half_edges(&self, positions: &[DVec3]) -> Result<HalfEdgeMesh, SimplifyError> {
        let triangles: Vec<[u32; 3]> = self
            .tables
            .triangles
            .iter()
            .map(|t| t.map(|x| self.original_vertex(x).unwrap_or(x)))
            .collect();
        let mesh = HalfEdgeMesh::from_trimesh(&TriMesh::new(positions.to_vec(), triangles)?);
        let same = mesh.vertex_count() == self.vertex_count()
            && mesh.face_count() == self.triangle_count()
            && (0..mesh.face_count() as u32)
                .all(|f| Some(mesh.face_vertices(FaceId(f)).map(|x| x.0)) == self.triangle(f));
        if same {
            Ok(mesh)
        } else {
            Err(SimplifyError::Internal {
                what: "the rebuilt finest mesh differs from the recorded one",
            })
        }
    }
}
