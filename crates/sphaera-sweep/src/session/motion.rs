//! Motion of the mesh in a [`Session`]: rigid poses and deformations (paper sections
//! 5.2–5.3).

use glam::{DAffine3, DVec3};

use super::{Session, bounding_box};
use crate::deformed_shape::{check_tables, max_displacement};
use crate::pose::Pose;
use crate::shifted_keys::MOTION_ROUNDING;
use crate::{DeformedShape, SweepError};

impl Session<'_> {
    /// Moves the mesh rigidly: from now on it stands at `pose` (mesh coordinates to world
    /// coordinates, a rotation then a translation; the identity at first). Queries take
    /// and answers give world coordinates; the hierarchy stays in mesh coordinates.
    ///
    /// Nothing is recomputed (paper section 5.2). A query point is taken into mesh
    /// coordinates, so a pose change moves it there, and the usual widening of the
    /// intervals by the query's displacement applies. When the mesh moves less than the
    /// local query point would — a rotation seen from far away — the intervals are
    /// instead widened once by a bound on how far the mesh moved: the largest displacement
    /// of a corner of the mesh's bounding box, at least the paper's δ (the largest vertex
    /// displacement; the displacement of an affine map is convex, so no point of the box
    /// moves farther than its farthest corner). So the widening is the smaller of the two,
    /// without reordering the queue. The safe ball of the last answer stays valid: it
    /// lives in mesh coordinates, where nothing moved.
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFinitePose`] for a NaN or infinite entry; [`SweepError::NotRigid`]
    /// if the linear part is farther than `1e-9` from a rotation (largest entry of
    /// `|MᵀM − I|`, or `|det M − 1|`: scales, shears and reflections). The pose is then
    /// unchanged. A valid pose is snapped to the nearest exact rotation.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// Constant.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::glam::{DAffine3, DQuat};
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{Sweeper, build_hierarchy};
    ///
    /// let cube = shapes::cube(2.0, 4)?; // corners at ±1
    /// let hierarchy = build_hierarchy(&cube)?;
    /// let sweeper = Sweeper::new(&hierarchy)?;
    /// let mut session = sweeper.session();
    ///
    /// // Turn the cube a quarter turn about z and move it 10 along x.
    /// let pose = DAffine3::from_rotation_translation(
    ///     DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
    ///     DVec3::new(10.0, 0.0, 0.0),
    /// );
    /// session.move_mesh(pose)?;
    /// let answer = session.closest(DVec3::new(13.0, 0.5, 0.0))?;
    /// assert!((answer.distance - 2.0).abs() < 1e-12);
    /// assert!((answer.point - DVec3::new(11.0, 0.5, 0.0)).length() < 1e-12);
    ///
    /// // Scaling is not a rigid motion.
    /// assert!(session.move_mesh(DAffine3::from_scale(DVec3::splat(2.0))).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn move_mesh(&mut self, pose: DAffine3) -> Result<(), SweepError> {
        self.warm_up();
        let next = Pose::new(pose)?;
        if let Some(q) = self.query {
            // The same world point, in the new mesh coordinates.
            let moved = next.to_local(self.pose.to_world(q));
            let (lo, hi) = self.bounds;
            let mesh_moved = self.pose.box_displacement(next, lo, hi);
            if mesh_moved < (moved - q).length() {
                self.widen(mesh_moved);
                if self.query.is_some() {
                    self.query = Some(moved);
                }
            }
        }
        self.pose = next;
        Ok(())
    }

    /// The mesh's pose (mesh coordinates to world coordinates; the identity until
    /// [`Session::move_mesh`]).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::glam::DAffine3;
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{Sweeper, build_hierarchy};
    ///
    /// let hierarchy = build_hierarchy(&shapes::cube(1.0, 1)?)?;
    /// let sweeper = Sweeper::new(&hierarchy)?;
    /// let mut session = sweeper.session();
    /// assert_eq!(session.pose(), DAffine3::IDENTITY);
    /// session.move_mesh(DAffine3::from_translation(DVec3::X))?;
    /// assert_eq!(session.pose().translation, DVec3::X);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn pose(&self) -> DAffine3 {
        self.pose.affine()
    }

    /// Deforms the mesh: from now on its vertices are at `shape`'s positions, with
    /// `shape`'s radii (paper section 5.3; see [`DeformedShape`] for the key-frame and inflation
    /// methods and why each bound holds). The pose still applies on top.
    ///
    /// The refined mesh is kept. Every cached interval is stale, and is widened, without
    /// reordering, by `Δ + ρ`: `Δ` the largest vertex displacement, `ρ` the largest
    /// increase of a present vertex's radius. A stored lower bound `d − ε` bounds the
    /// distance to the triangle's tolerance volume (the union of the balls `B(λ·P,
    /// λ·R)`); each ball's center moves by at most `Δ` and its radius grows by at most
    /// `ρ`, so the new volume is no nearer than `d − ε − Δ − ρ` — whichever triangle now
    /// covers which part of the input surface, every live triangle's bound holds, which is
    /// all the sweep needs. Stale intervals are re-evaluated when they reach the front, as
    /// after a query move. When `Δ + ρ` exceeds [`SessionOptions::jump_factor`](crate::SessionOptions::jump_factor) times the
    /// last answer's distance, the session resets instead (as for a query jump).
    ///
    /// # Errors
    ///
    /// [`SweepError::ForeignHierarchy`] if the shape's radii do not share the sweeper's
    /// tables. The session is then unchanged.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// `O(vertices)`: the displacement and radius scans.
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
    /// let mut session = sweeper.session();
    /// let p = DVec3::new(0.0, 0.0, 3.0);
    /// assert!((session.closest(p)?.distance - 2.0).abs() < 1e-12);
    ///
    /// // A key-frame: the sphere grown to radius 2.
    /// let grown: Vec<DVec3> = sphere.positions().iter().map(|q| *q * 2.0).collect();
    /// session.deform(DeformedShape::keyframe(&hierarchy.replay(&grown)?))?;
    /// assert!((session.closest(p)?.distance - 1.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn deform(&mut self, shape: DeformedShape) -> Result<(), SweepError> {
        self.warm_up();
        check_tables(self.hierarchy, &shape)?;
        let moved = match &self.shape {
            Some(old) => max_displacement(old.positions(), shape.positions()),
            None => max_displacement(self.hierarchy.positions(), shape.positions()),
        };
        let grown = (0..self.hierarchy.vertex_count() as u32)
            .filter(|&v| self.refinement.is_present(v))
            .fold(0.0_f64, |m, v| {
                let now = self
                    .refinement
                    .radius_in(v, shape.radii())
                    .unwrap_or(f64::INFINITY);
                m.max(now - self.radius(v))
            });
        self.bounds = bounding_box(shape.positions());
        self.shape = Some(shape);
        self.safe = None;
        self.widen(moved + grown);
        Ok(())
    }

    /// Moves the vertices of the current [`DeformedShape`] to `positions` (one per input vertex)
    /// within the displacement bounds its radii were inflated for ([`DeformedShape::inflated`]):
    /// the paper's second method, one inflation for several steps. Stale intervals are
    /// widened by the largest vertex displacement, as in [`Session::deform`].
    ///
    /// # Errors
    ///
    /// As [`DeformedShape::set_positions`] (a wrong length, a non-finite position, a vertex beyond
    /// its bound — for a session that was never deformed, or deformed to a key-frame, the
    /// bound is 0). The session is then unchanged.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// `O(vertices)`.
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
    /// let mut session = sweeper.session();
    /// session.deform(DeformedShape::inflated(&hierarchy, &vec![0.15; sphere.vertex_count()])?)?;
    /// for step in 1..=10 {
    ///     let s = 1.0 + 0.01 * f64::from(step);
    ///     let positions: Vec<DVec3> = sphere.positions().iter().map(|q| *q * s).collect();
    ///     session.move_vertices(&positions)?;
    ///     let answer = session.closest(DVec3::new(0.0, 0.0, 3.0))?;
    ///     assert!((answer.distance - (3.0 - s)).abs() < 1e-12);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn move_vertices(&mut self, positions: &[DVec3]) -> Result<(), SweepError> {
        self.warm_up();
        let had_shape = self.shape.is_some();
        let mut shape = match self.shape.take() {
            Some(shape) => shape,
            None => DeformedShape::keyframe(self.hierarchy),
        };
        let checked = match shape.checked_positions(positions) {
            Ok(checked) => checked,
            Err(error) => {
                // Put back what was there (nothing, for a session never deformed).
                self.shape = had_shape.then_some(shape);
                return Err(error);
            }
        };
        let moved = max_displacement(shape.positions(), &checked);
        shape.replace_positions(checked);
        self.bounds = bounding_box(shape.positions());
        self.shape = Some(shape);
        self.safe = None;
        self.widen(moved);
        Ok(())
    }

    /// The current deformed shape (`None` until [`Session::deform`] or
    /// [`Session::move_vertices`]).
    pub fn deformed_shape(&self) -> Option<&DeformedShape> {
        self.shape.as_ref()
    }

    /// Widens every interval by `amount` (a motion of the mesh), or resets when that is a
    /// jump per [`SessionOptions::jump_factor`](crate::SessionOptions::jump_factor).
    pub(super) fn widen(&mut self, amount: f64) {
        if self.query.is_none() || self.queue.len() == 0 {
            return;
        }
        let amount = amount * (1.0 + MOTION_ROUNDING);
        let far = amount > self.options.jump_factor * self.last_distance;
        if far || self.keys.exhausted(amount, self.diagonal) {
            self.reset();
        } else if amount > 0.0 {
            self.keys.widen(amount);
            self.best_upper += amount;
        }
    }
}
