//! Selective refinement: the changing state over a [`Hierarchy`].

use sphaera_mesh::{DVec3, TriMesh};

use crate::{Hierarchy, Simplified, SimplifyError};

/// The high bit of a vertex's state word: the vertex is removed.
const REMOVED: u32 = 1 << 31;

/// A selectively refined state of a [`Hierarchy`]: which collapses are applied. Starts at
/// the base mesh ([`Hierarchy::refinement`]); vertices are split on demand
/// ([`Refinement::split_vertex`]); [`Refinement::reset`] coarsens back to the base mesh.
///
/// The state is one word per vertex (how many collapses into it are applied, and whether
/// it is removed), one per collapse (a visit mark) and the list of collapses undone since
/// the last reset. Radii and positions come from the hierarchy's tables in constant time.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyOptions, Hierarchy};
///
/// let torus = shapes::torus(1.0, 0.3, 16)?;
/// let hierarchy = Hierarchy::build(&torus, &SimplifyOptions::default().with_target_triangles(32))?;
/// let mut refinement = hierarchy.refinement();
/// let before = refinement.live_triangle_count();
/// // Split vertex by vertex, keeping a triangle set in sync from the reports.
/// let mut live: std::collections::BTreeSet<u32> = refinement.live_triangles().collect();
/// for v in 0..hierarchy.vertex_count() as u32 {
///     if refinement.is_present(v) && refinement.radius(v) > 0.0 {
///         for c in refinement.split_vertex(v)? {
///             for &t in hierarchy.triangles_removed_by_split(c) {
///                 assert!(live.remove(&t));
///             }
///             live.extend(hierarchy.triangles_added_by_split(c));
///         }
///     }
/// }
/// assert_eq!(live, refinement.live_triangles().collect());
/// assert!(refinement.live_triangle_count() > before);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Refinement<'h> {
    hierarchy: &'h Hierarchy,
    /// Per vertex: applied collapses into it, with [`REMOVED`] when it is removed.
    state: Vec<u32>,
    /// Per collapse: the generation of the last visit (for the dependency search).
    mark: Vec<u32>,
    generation: u32,
    /// Collapses undone since the base mesh, in order.
    undone: Vec<u32>,
    /// Live triangle count.
    live: usize,
    /// Reused stack of the dependency search.
    scratch: Vec<u32>,
}

impl<'h> Refinement<'h> {
    /// The state with the first `k` collapses applied.
    pub(crate) fn at_prefix(hierarchy: &'h Hierarchy, k: usize) -> Self {
        let tables = &hierarchy.tables;
        let mut state = vec![0_u32; hierarchy.vertex_count()];
        let mut live = tables.finest_triangle_count;
        for c in 0..k.min(hierarchy.collapse_count()) {
            state[tables.removed[c] as usize] |= REMOVED;
            state[tables.parent[c] as usize] += 1;
            live -= usize::from(tables.dying[c]);
        }
        Self {
            hierarchy,
            state,
            mark: vec![0; hierarchy.collapse_count()],
            generation: 0,
            undone: Vec::new(),
            live,
            scratch: Vec::new(),
        }
    }

    /// A placeholder that holds no state: no vertex present, no triangle live, nothing to
    /// split. For a caller that creates the real state ([`Hierarchy::refinement`]) only
    /// when it first needs it; it allocates nothing, where a real state costs a pass over
    /// the collapses and four bytes per vertex and per collapse.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{Hierarchy, Refinement, SimplifyOptions};
    ///
    /// let hierarchy = Hierarchy::build(&shapes::sphere(1.0, 8)?, &SimplifyOptions::default())?;
    /// let mut state = Refinement::placeholder(&hierarchy);
    /// assert_eq!(state.live_triangle_count(), 0);
    /// assert!(!state.is_present(0));
    /// state = hierarchy.refinement();
    /// assert!(state.live_triangle_count() > 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn placeholder(hierarchy: &'h Hierarchy) -> Self {
        Self {
            hierarchy,
            state: Vec::new(),
            mark: Vec::new(),
            generation: 0,
            undone: Vec::new(),
            live: 0,
            scratch: Vec::new(),
        }
    }

    /// The base mesh.
    pub(crate) fn at_base(hierarchy: &'h Hierarchy) -> Self {
        Self::at_prefix(hierarchy, hierarchy.collapse_count())
    }

    /// Bytes of the changing state of a refinement of `hierarchy` (without the undo list).
    pub(crate) fn state_bytes(hierarchy: &Hierarchy) -> usize {
        4 * (hierarchy.vertex_count() + hierarchy.collapse_count())
    }

    /// The hierarchy this state refines.
    pub fn hierarchy(&self) -> &'h Hierarchy {
        self.hierarchy
    }

    /// Whether `v` is a vertex of the current mesh (false if out of range).
    pub fn is_present(&self, v: u32) -> bool {
        self.state.get(v as usize).is_some_and(|s| s & REMOVED == 0)
    }

    /// Whether `v` is present and has an applied collapse to undo.
    pub fn can_split(&self, v: u32) -> bool {
        self.state
            .get(v as usize)
            .is_some_and(|&s| s & REMOVED == 0 && s > 0)
    }

    /// The current error radius of `v` (meaningful when present; 0 if out of range).
    pub fn radius(&self, v: u32) -> f64 {
        self.level(v)
            .map_or(0.0, |l| self.hierarchy.radius_at_level(v, l))
    }

    /// The radius `v` has in the current state under another geometry of the same tables
    /// (a key-frame from [`Hierarchy::replay`], an inflation from [`Hierarchy::inflate`]):
    /// the state is shared, only the radii differ. `None` if `geometry` does not share
    /// this refinement's tables ([`Hierarchy::shares_tables`]) or `v` is out of range.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 8)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default())?;
    /// let moving = hierarchy.inflate(&vec![0.1; sphere.vertex_count()])?;
    /// let refinement = hierarchy.refinement();
    /// let v = (0..hierarchy.vertex_count() as u32).find(|&v| refinement.is_present(v)).unwrap();
    /// let inflated = refinement.radius_in(v, &moving).unwrap();
    /// assert!(inflated >= refinement.radius(v) + 0.2 - 1e-12);
    /// let other = Hierarchy::build(&sphere, &SimplifyOptions::default())?;
    /// assert_eq!(refinement.radius_in(v, &other), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn radius_in(&self, v: u32, geometry: &Hierarchy) -> Option<f64> {
        if !self.hierarchy.shares_tables(geometry) {
            return None;
        }
        self.level(v).map(|l| geometry.radius_at_level(v, l))
    }

    /// The current position of `v` (its finest position under
    /// [`Placement::Subset`](crate::Placement::Subset); `DVec3::ZERO` if out of range).
    pub fn position(&self, v: u32) -> DVec3 {
        self.level(v)
            .map_or(DVec3::ZERO, |l| self.hierarchy.position_at_level(v, l))
    }

    /// The present vertex that stands for `v` now: `v` itself, or its parent's (and so on)
    /// if `v` is removed. `None` if out of range.
    pub fn representative(&self, mut v: u32) -> Option<u32> {
        loop {
            let s = *self.state.get(v as usize)?;
            if s & REMOVED == 0 {
                return Some(v);
            }
            v = self.hierarchy.parent(v)?;
        }
    }

    /// The current corners of triangle `t`, or `None` if it is not live (or out of range).
    pub fn corners(&self, t: u32) -> Option<[u32; 3]> {
        let [a, b, c] = self.hierarchy.triangle(t)?;
        let corners = [
            self.representative(a)?,
            self.representative(b)?,
            self.representative(c)?,
        ];
        (corners[0] != corners[1] && corners[1] != corners[2] && corners[0] != corners[2])
            .then_some(corners)
    }

    /// Live triangles now.
    pub fn live_triangle_count(&self) -> usize {
        self.live
    }

    /// The live triangles, by id (a scan of every triangle: `O(T × depth)`).
    pub fn live_triangles(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.hierarchy.triangle_count() as u32).filter(|&t| self.corners(t).is_some())
    }

    /// How many collapses have been undone since the base mesh.
    pub fn undone_count(&self) -> usize {
        self.undone.len()
    }

    /// Splits `v`: undoes the last applied collapse into it, first undoing (in
    /// topological order) every applied collapse that must be split before it. Returns
    /// the collapses undone, in order; for each, the hierarchy's tables say which
    /// triangles left ([`Hierarchy::triangles_removed_by_split`]), came in
    /// ([`Hierarchy::triangles_added_by_split`]) and changed radius
    /// ([`Hierarchy::triangles_affected_by_split`]). Empty if `v` has nothing to split.
    ///
    /// # Errors
    ///
    /// [`SimplifyError::VertexNotPresent`] if `v` is out of range or removed.
    ///
    /// # Performance
    ///
    /// Proportional to the collapses undone and their dependency lists.
    pub fn split_vertex(&mut self, v: u32) -> Result<Vec<u32>, SimplifyError> {
        let mut out = Vec::new();
        self.split_vertex_into(v, &mut out)?;
        Ok(out)
    }

    /// [`Refinement::split_vertex`] appending to `out` (no allocation once `out` has
    /// grown).
    ///
    /// # Errors
    ///
    /// As [`Refinement::split_vertex`].
    pub fn split_vertex_into(&mut self, v: u32, out: &mut Vec<u32>) -> Result<(), SimplifyError> {
        if !self.is_present(v) {
            return Err(SimplifyError::VertexNotPresent { vertex: v });
        }
        let level = self.level(v).unwrap_or(0);
        if level == 0 {
            return Ok(());
        }
        let Some(&c) = self.hierarchy.splits_with(v).get(level as usize - 1) else {
            return Ok(());
        };
        self.undo(c, out);
        Ok(())
    }

    /// Undoes collapse `c` (and first what must be split before it) if it is applied;
    /// appends what was undone to `out`.
    ///
    /// # Errors
    ///
    /// [`SimplifyError::InvalidParameter`] if `c` is out of range.
    pub fn undo_collapse(&mut self, c: u32, out: &mut Vec<u32>) -> Result<(), SimplifyError> {
        if c as usize >= self.hierarchy.collapse_count() {
            return Err(SimplifyError::InvalidParameter {
                name: "collapse",
                value: f64::from(c),
                requirement: "a collapse index of the hierarchy",
            });
        }
        self.undo(c, out);
        Ok(())
    }

    /// Whether collapse `c` is applied now.
    pub fn is_applied(&self, c: u32) -> bool {
        self.hierarchy
            .removed_vertex(c)
            .is_some_and(|u| !self.is_present(u))
    }

    /// Splits every present vertex whose radius exceeds `bound` (and what must go first),
    /// until none is left or nothing more can be split.
    pub fn refine_to_error(&mut self, bound: f64) {
        let mut work: Vec<u32> = (0..self.state.len() as u32)
            .filter(|&v| self.can_split(v) && self.radius(v) > bound)
            .collect();
        let mut undone = Vec::new();
        while let Some(v) = work.pop() {
            if !(self.can_split(v) && self.radius(v) > bound) {
                continue;
            }
            undone.clear();
            self.undo_last_into(v, &mut undone);
            for &c in &undone {
                let tables = &self.hierarchy.tables;
                for x in [tables.removed[c as usize], tables.parent[c as usize]] {
                    if self.can_split(x) && self.radius(x) > bound {
                        work.push(x);
                    }
                }
            }
        }
    }

    /// Back to the base mesh, re-applying the undone collapses in reverse order:
    /// `O(changed)`.
    pub fn reset(&mut self) {
        self.reset_to(0);
    }

    /// Back to the state this refinement had when [`Refinement::undone_count`] was
    /// `undone` (re-applying the collapses undone since, in reverse order): a warm start
    /// kept as a prefix of the undo history. Does nothing if fewer have been undone.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 12)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default().with_target_triangles(20))?;
    /// let mut refinement = hierarchy.refinement();
    /// refinement.refine_to_error(0.1);
    /// let (kept, live) = (refinement.undone_count(), refinement.live_triangle_count());
    /// refinement.refine_to_error(0.01);
    /// assert!(refinement.live_triangle_count() > live);
    /// refinement.reset_to(kept);
    /// assert_eq!(refinement.live_triangle_count(), live);
    /// assert_eq!(refinement.undone_count(), kept);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// `O(undone_count − undone)`.
    pub fn reset_to(&mut self, undone: usize) {
        let tables = &self.hierarchy.tables;
        while self.undone.len() > undone {
            let Some(c) = self.undone.pop() else {
                break;
            };
            let c = c as usize;
            self.state[tables.removed[c] as usize] |= REMOVED;
            self.state[tables.parent[c] as usize] += 1;
            self.live -= usize::from(tables.dying[c]);
        }
    }

    /// The current mesh: live triangles (compacted, unreferenced vertices dropped), radii
    /// and input vertex of each output vertex.
    pub fn to_simplified(&self) -> Simplified {
        let live: Vec<[u32; 3]> = (0..self.hierarchy.triangle_count() as u32)
            .filter_map(|t| self.corners(t))
            .collect();
        self.simplified_from(&live)
    }

    /// The current mesh from a caller who tracks the live triangles (from
    /// [`Refinement::live_triangles`] once, then the split reports): the given triangles
    /// that are live, in increasing id order, with [`Refinement::to_simplified`]'s
    /// vertices, radii and input vertices. Equal to [`Refinement::to_simplified`] when
    /// `triangles` holds every live triangle; ids that are not live (or repeated) are
    /// skipped.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 12)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default().with_target_triangles(20))?;
    /// let mut refinement = hierarchy.refinement();
    /// let mut live: Vec<u32> = refinement.live_triangles().collect();
    /// let v = (0..hierarchy.vertex_count() as u32).find(|&v| refinement.can_split(v)).unwrap();
    /// for c in refinement.split_vertex(v)? {
    ///     live.extend(hierarchy.triangles_added_by_split(c));
    /// }
    /// assert_eq!(refinement.simplified_of(&live), refinement.to_simplified());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// `O(triangles · log + vertices)`, without [`Refinement::to_simplified`]'s scan of
    /// every triangle of the hierarchy.
    pub fn simplified_of(&self, triangles: &[u32]) -> Simplified {
        let mut ids = triangles.to_vec();
        ids.sort_unstable();
        ids.dedup();
        let live: Vec<[u32; 3]> = ids.into_iter().filter_map(|t| self.corners(t)).collect();
        self.simplified_from(&live)
    }

    /// The mesh of `live` (current corners of live triangles, in increasing id order).
    fn simplified_from(&self, live: &[[u32; 3]]) -> Simplified {
        let n = self.hierarchy.vertex_count();
        // Output vertices in increasing hierarchy order, copies of a non-manifold vertex
        // merged into one (they are never collapsed, so they agree), as
        // `HalfEdgeMesh::to_trimesh` does.
        let mut used = vec![false; n];
        for &x in live.iter().flatten() {
            used[x as usize] = true;
        }
        let mut by_original = vec![u32::MAX; n.max(self.hierarchy.tables.input_counts.0)];
        let mut index = vec![u32::MAX; n];
        let mut positions = Vec::new();
        let mut radii = Vec::new();
        let mut original = Vec::new();
        for x in (0..n as u32).filter(|&x| used[x as usize]) {
            let source = self.hierarchy.original_vertex(x).unwrap_or(x);
            let slot = &mut by_original[source as usize];
            if *slot == u32::MAX {
                *slot = positions.len() as u32;
                positions.push(self.position(x));
                radii.push(self.radius(x));
                original.push(source);
            }
            index[x as usize] = *slot;
        }
        let triangles: Vec<[u32; 3]> = live
            .iter()
            .map(|corners| corners.map(|x| index[x as usize]))
            .collect();
        let error_bound = radii.iter().fold(0.0_f64, |m, &r| m.max(r));
        // Positions come from a valid mesh and indices from the loop above, so this
        // cannot fail (invariant); fall back to an empty mesh rather than panic.
        let mesh = TriMesh::new(positions, triangles).unwrap_or_default();
        let applied = self.hierarchy.collapse_count() - self.undone.len();
        Simplified {
            mesh,
            vertex_radii: radii,
            error_bound,
            original_vertex: original,
            collapses: applied,
            locked: self.hierarchy.locked(),
        }
    }

    fn level(&self, v: u32) -> Option<u32> {
        self.state.get(v as usize).map(|s| s & !REMOVED)
    }

    /// Splits the last applied collapse into `v` (which must be splittable).
    fn undo_last_into(&mut self, v: u32, out: &mut Vec<u32>) {
        let level = self.level(v).unwrap_or(0);
        if let Some(&c) = level
            .checked_sub(1)
            .and_then(|l| self.hierarchy.splits_with(v).get(l as usize))
        {
            self.undo(c, out);
        }
    }

    /// Undoes `c` and its applied dependants, latest first (the build order is a
    /// topological order of the dependencies, so decreasing index is valid).
    fn undo(&mut self, c: u32, out: &mut Vec<u32>) {
        if !self.is_applied(c) {
            return;
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.mark.fill(0);
            self.generation = 1;
        }
        let mut stack = std::mem::take(&mut self.scratch);
        stack.clear();
        stack.push(c);
        self.mark[c as usize] = self.generation;
        let mut i = 0;
        while let Some(&x) = stack.get(i) {
            i += 1;
            for &d in self.hierarchy.split_before(x) {
                if self.mark[d as usize] != self.generation && self.is_applied(d) {
                    self.mark[d as usize] = self.generation;
                    stack.push(d);
                }
            }
        }
        stack.sort_unstable_by(|a, b| b.cmp(a));
        let tables = &self.hierarchy.tables;
        for &x in &stack {
            let x = x as usize;
            self.state[tables.removed[x] as usize] &= !REMOVED;
            self.state[tables.parent[x] as usize] -= 1;
            self.live += usize::from(tables.dying[x]);
        }
        self.undone.extend_from_slice(&stack);
        out.extend_from_slice(&stack);
        self.scratch = stack;
    }
}
