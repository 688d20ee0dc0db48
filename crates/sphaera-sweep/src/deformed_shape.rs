//! Deformed geometry of a sweeper's mesh (Meshsweeper section 5.3): true vertex positions
//! and error radii proven valid for them.

use glam::DVec3;
use sphaera_simplify::Hierarchy;

use crate::SweepError;

/// A deformed shape of the mesh a [`Sweeper`](crate::Sweeper) was built on: where every
/// vertex is now, and error radii that are valid there, for
/// [`Session::deform`](crate::Session::deform).
///
/// A shape holds radii (a [`Hierarchy`] sharing the sweeper's tables) proven valid for
/// *any* positions within a per-vertex allowance of reference positions, and the true
/// positions now, which the session evaluates the input triangles on (so answers stay
/// exact). Three ways to make one, the paper's two methods and their common case:
///
/// - [`DeformedShape::keyframe`]: a key-frame from [`Hierarchy::replay`] (exact radii, allowance
///   0);
/// - [`DeformedShape::between`]: positions interpolated linearly between two key-frames;
/// - [`DeformedShape::inflated`]: radii inflated ([`Hierarchy::inflate`]) for displacement bounds,
///   then [`DeformedShape::set_positions`] for each step of the motion within them.
///
/// # Key-frames: why the radii are not interpolated linearly
///
/// The paper interpolates the radii of two key-frames linearly. That is sound when both
/// key-frames' radii come from the *same* collapse maps: a map is a correspondence between
/// the fans before and after each collapse, the same at both frames, so at time `t` a point
/// and its image move linearly, and the condition `r_new(φ(p)) ≥ |p − φ(p)| + r_old(p)` is
/// a convex function of `t` (a norm of a linear function plus linear radii) that holds at
/// `t = 0` and `t = 1`, hence in between. The simple map (`r_u + |u − v|`) is such a map.
/// But [`Hierarchy::replay`] uses the tight projected map wherever it is injective, and
/// its cells (the crossings of projected spokes) and projection plane depend on the
/// positions: the two key-frames' radii satisfy the conditions of *different* maps, and
/// neither map's condition is known to hold at the other frame. So linear interpolation is
/// not proven for these radii, and is not used. Instead, [`DeformedShape::between`] takes the
/// radii of the nearer key-frame inflated by how far the interpolated positions are from
/// it ([`Hierarchy::inflate`], which is proven for any motion within the bounds): valid,
/// equal to the key-frame's at `t = 0` and `t = 1`, and never inflated by more than twice
/// half the key-frames' displacement.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_sweep::{DeformedShape, Sweeper, build_hierarchy};
///
/// let sphere = shapes::sphere(1.0, 12)?;
/// let hierarchy = build_hierarchy(&sphere)?;
/// let sweeper = Sweeper::new(&hierarchy)?;
/// // Two key-frames: the sphere, and the sphere stretched 20 % along z.
/// let stretched: Vec<DVec3> =
///     sphere.positions().iter().map(|p| *p * DVec3::new(1.0, 1.0, 1.2)).collect();
/// let end = hierarchy.replay(&stretched)?;
///
/// let mut session = sweeper.session();
/// session.deform(DeformedShape::between(&hierarchy, &end, 0.5)?)?;
/// let answer = session.closest(DVec3::new(0.0, 0.0, 3.0))?;
/// // Half-way, the top vertex is at z = 1.1.
/// assert!((answer.distance - 1.9).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct DeformedShape {
    /// Radii valid for every position within `allowance` of `reference`.
    radii: Hierarchy,
    /// Per input vertex: the positions the radii were computed or inflated for.
    reference: Vec<DVec3>,
    /// Per input vertex: how far it may be from its reference.
    allowance: Vec<f64>,
    /// Per hierarchy vertex: the true position now.
    positions: Vec<DVec3>,
}

impl DeformedShape {
    /// A key-frame: the positions and exact radii of `frame` (a hierarchy from
    /// [`Hierarchy::replay`], or the sweeper's own, to go back to rest).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_sweep::{DeformedShape, build_hierarchy};
    ///
    /// let cube = shapes::cube(2.0, 2)?;
    /// let hierarchy = build_hierarchy(&cube)?;
    /// let rest = DeformedShape::keyframe(&hierarchy);
    /// assert_eq!(rest.positions(), hierarchy.positions());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// Copies the frame's geometry (`O(vertices)`); the tables are shared.
    pub fn keyframe(frame: &Hierarchy) -> Self {
        let reference = reference_positions(frame);
        Self {
            allowance: vec![0.0; reference.len()],
            reference,
            positions: frame.positions().to_vec(),
            radii: frame.clone(),
        }
    }

    /// The shape at time `t ∈ [0, 1]` between key-frames `a` (`t = 0`) and `b` (`t = 1`):
    /// every vertex at `a + t (b − a)`, radii from the nearer key-frame inflated by each
    /// vertex's distance from it (see the type's docs for why the radii are not
    /// interpolated linearly).
    ///
    /// # Errors
    ///
    /// [`SweepError::ForeignHierarchy`] if `a` and `b` do not share their tables;
    /// [`SweepError::InvalidParameter`] if `t` is NaN or outside `[0, 1]`;
    /// [`SweepError::Deformation`] for optimal-placement hierarchies.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// One [`Hierarchy::inflate`] (linear, no geometry) and one pass over the vertices.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{DeformedShape, build_hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 8)?;
    /// let a = build_hierarchy(&sphere)?;
    /// let moved: Vec<DVec3> = sphere.positions().iter().map(|p| *p * 1.5).collect();
    /// let b = a.replay(&moved)?;
    /// let quarter = DeformedShape::between(&a, &b, 0.25)?;
    /// assert!((quarter.positions()[0] - sphere.positions()[0] * 1.125).length() < 1e-12);
    /// assert!(DeformedShape::between(&a, &b, 1.5).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn between(a: &Hierarchy, b: &Hierarchy, t: f64) -> Result<Self, SweepError> {
        if !a.shares_tables(b) {
            return Err(SweepError::ForeignHierarchy);
        }
        if !(0.0..=1.0).contains(&t) {
            return Err(SweepError::InvalidParameter {
                name: "t",
                value: t,
                requirement: "in [0, 1]",
            });
        }
        let (from, to) = (reference_positions(a), reference_positions(b));
        let now: Vec<DVec3> = from
            .iter()
            .zip(&to)
            .map(|(&p, &q)| p + (q - p) * t)
            .collect();
        let (near, reference) = if t <= 0.5 { (a, from) } else { (b, to) };
        let allowance: Vec<f64> = now
            .iter()
            .zip(&reference)
            .map(|(p, r)| (*p - *r).length())
            .collect();
        let radii = near.inflate(&allowance)?;
        let positions = hierarchy_positions(&radii, &now);
        Ok(Self {
            radii,
            reference,
            allowance,
            positions,
        })
    }

    /// Radii inflated ([`Hierarchy::inflate`]) so they stay valid while each input vertex
    /// `i` moves at most `displacement[i]` from its position in `reference` (the paper's
    /// second method: exaggerate the bounds, inflate once, and move the vertices for
    /// several steps with [`DeformedShape::set_positions`] or
    /// [`Session::move_vertices`](crate::Session::move_vertices)). The positions start at
    /// the reference's.
    ///
    /// # Errors
    ///
    /// [`SweepError::LengthMismatch`] if `displacement` does not have one entry per input
    /// vertex; [`SweepError::InvalidVertexValue`] for a NaN, infinite or negative entry;
    /// [`SweepError::Deformation`] for optimal-placement hierarchies.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{DeformedShape, build_hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 8)?;
    /// let hierarchy = build_hierarchy(&sphere)?;
    /// let mut shape = DeformedShape::inflated(&hierarchy, &vec![0.1; sphere.vertex_count()])?;
    /// let nudged: Vec<DVec3> = sphere.positions().iter().map(|p| *p * 1.05).collect();
    /// shape.set_positions(&nudged)?; // every vertex moves by 0.05 ≤ 0.1
    /// let far: Vec<DVec3> = sphere.positions().iter().map(|p| *p * 1.2).collect();
    /// assert!(shape.set_positions(&far).is_err()); // 0.2 > 0.1
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn inflated(reference: &Hierarchy, displacement: &[f64]) -> Result<Self, SweepError> {
        let radii = reference.inflate(displacement)?;
        Ok(Self {
            reference: reference_positions(reference),
            allowance: displacement.to_vec(),
            positions: reference.positions().to_vec(),
            radii,
        })
    }

    /// Moves the vertices to `positions` (one per input vertex), within the allowance the
    /// radii were made for.
    ///
    /// # Errors
    ///
    /// [`SweepError::LengthMismatch`] for a wrong length; [`SweepError::InvalidVertexValue`]
    /// for a non-finite position or one farther from its reference than allowed (the
    /// error's value is that distance). On error the shape is unchanged.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Examples
    ///
    /// See [`DeformedShape::inflated`].
    pub fn set_positions(&mut self, positions: &[DVec3]) -> Result<(), SweepError> {
        self.positions = self.checked_positions(positions)?;
        Ok(())
    }

    /// The true position of every hierarchy vertex now (one per input vertex, plus the
    /// copies of non-manifold vertices; see
    /// [`Hierarchy::original_vertex`]).
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The hierarchy whose radii the shape uses (it shares the tables it was made from).
    pub fn radii(&self) -> &Hierarchy {
        &self.radii
    }

    /// `positions` (per input vertex) validated against the allowance, per hierarchy
    /// vertex.
    pub(crate) fn checked_positions(&self, positions: &[DVec3]) -> Result<Vec<DVec3>, SweepError> {
        if positions.len() != self.reference.len() {
            return Err(SweepError::LengthMismatch {
                name: "positions",
                actual: positions.len(),
                expected: self.reference.len(),
            });
        }
        for (index, ((p, r), &allowed)) in positions
            .iter()
            .zip(&self.reference)
            .zip(&self.allowance)
            .enumerate()
        {
            if !p.is_finite() {
                return Err(SweepError::InvalidVertexValue {
                    name: "positions",
                    index,
                    value: p.abs().max_element(),
                    requirement: "finite",
                });
            }
            let moved = (*p - *r).length();
            if moved > allowed {
                return Err(SweepError::InvalidVertexValue {
                    name: "positions",
                    index,
                    value: moved,
                    requirement: "within the displacement bound of the reference position",
                });
            }
        }
        Ok(hierarchy_positions(&self.radii, positions))
    }

    /// Replaces the positions (per hierarchy vertex, already checked).
    pub(crate) fn replace_positions(&mut self, positions: Vec<DVec3>) {
        self.positions = positions;
    }

    /// Bytes of the shape's own data (positions, reference, allowance and the radii's
    /// geometry; the tables are shared).
    pub(crate) fn bytes(&self) -> usize {
        24 * (self.positions.capacity() + self.reference.capacity())
            + 8 * self.allowance.capacity()
            + self.radii.memory().geometry
    }
}

/// Checks that `shape`'s radii share `hierarchy`'s tables.
pub(crate) fn check_tables(hierarchy: &Hierarchy, shape: &DeformedShape) -> Result<(), SweepError> {
    if hierarchy.shares_tables(&shape.radii) {
        Ok(())
    } else {
        Err(SweepError::ForeignHierarchy)
    }
}

/// The largest distance between two position lists (the paper's δ of a deformation).
pub(crate) fn max_displacement(a: &[DVec3], b: &[DVec3]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (p, q)| m.max((*p - *q).length()))
}

/// The position of every input vertex in `hierarchy` (copies of non-manifold vertices
/// share their original's).
fn reference_positions(hierarchy: &Hierarchy) -> Vec<DVec3> {
    let mut out = vec![DVec3::ZERO; hierarchy.input_vertex_count()];
    for (x, &p) in hierarchy.positions().iter().enumerate() {
        let i = hierarchy.original_vertex(x as u32).unwrap_or(x as u32) as usize;
        if let Some(slot) = out.get_mut(i) {
            *slot = p;
        }
    }
    out
}

/// Per hierarchy vertex, the position of its input vertex in `input`.
fn hierarchy_positions(hierarchy: &Hierarchy, input: &[DVec3]) -> Vec<DVec3> {
    (0..hierarchy.vertex_count() as u32)
        .map(|x| {
            let i = hierarchy.original_vertex(x).unwrap_or(x) as usize;
            input.get(i).copied().unwrap_or(DVec3::ZERO)
        })
        .collect()
}
