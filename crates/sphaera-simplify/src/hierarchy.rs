//! The progressive hierarchy recorded by a simplification, in the array form of
//! Meshsweeper (Guéziec 2000, section 4.2): fixed tables shared by every user, and per-collapse
//! error radii.

use std::sync::Arc;

use glam::DVec3;
use sphaera_mesh::topology::HalfEdgeMesh;

use crate::record::{NONE, Recorder};
use crate::simplifier::{LockReport, Placement};
use crate::{Refinement, Simplified};

/// A compressed list of lists (`offsets.len()` = rows + 1).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Lists {
    offsets: Vec<u32>,
    items: Vec<u32>,
}

impl Lists {
    fn from_rows<I: IntoIterator<Item = u32>>(rows: impl IntoIterator<Item = I>) -> Self {
        let mut offsets = vec![0];
        let mut items = Vec::new();
        for row in rows {
            items.extend(row);
            offsets.push(items.len() as u32);
        }
        Self { offsets, items }
    }

    /// Row `i`, empty when out of range.
    pub fn row(&self, i: usize) -> &[u32] {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) => self.items.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        }
    }

    fn bytes(&self) -> usize {
        4 * (self.offsets.len() + self.items.len())
    }
}

/// The fixed tables: the finest mesh, the collapse sequence and its dependencies. Never
/// modified after the build; shared (through an `Arc`) by every [`Hierarchy`] made from
/// the same build by [`Hierarchy::replay`] or [`Hierarchy::inflate`].
#[derive(Debug, PartialEq)]
pub(crate) struct Tables {
    /// Corners of every triangle of the finest mesh (hierarchy vertex ids).
    pub triangles: Vec<[u32; 3]>,
    /// Input triangle of each hierarchy triangle.
    pub original_triangle: Vec<u32>,
    /// Input vertex of each hierarchy vertex.
    pub original_vertex: Vec<u32>,
    /// Vertices and triangles of the input mesh.
    pub input_counts: (usize, usize),
    /// Per collapse: removed vertex.
    pub removed: Vec<u32>,
    /// Per collapse: the vertex it was collapsed into.
    pub parent: Vec<u32>,
    /// Per collapse: "triangles added by split", the dying faces first.
    pub added: Lists,
    /// Per collapse: how many of `added` die on collapse (revive on split).
    pub dying: Vec<u8>,
    /// Per collapse: "triangles affected by split".
    pub affected: Lists,
    /// Per collapse: "split before", the later collapses to undo first.
    pub split_before: Lists,
    /// Per vertex: the collapse that removed it, or `NONE`.
    pub collapse_of: Vec<u32>,
    /// Per vertex: "vertex splits with", the collapses into it in build order.
    pub splits_with: Lists,
    /// Triangles of the finest mesh live before any collapse.
    pub finest_triangle_count: usize,
    /// What the build locked.
    pub locked: LockReport,
    /// The build's placement.
    pub placement: Placement,
}

/// The geometry of a hierarchy: positions and radii. [`Hierarchy::replay`] and
/// [`Hierarchy::inflate`] make new geometry over the same [`Tables`].
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Geometry {
    /// Position of every hierarchy vertex in the finest mesh.
    pub positions: Vec<DVec3>,
    /// Per collapse: the parent's position after it (empty for Subset placement, where
    /// it does not move).
    pub placed: Vec<DVec3>,
    /// Per collapse: the parent's radius after it.
    pub radii: Vec<f64>,
    /// Per vertex: added to every radius of the vertex (empty: all 0). Set by
    /// [`Hierarchy::inflate`].
    pub offsets: Vec<f64>,
}

/// The progressive hierarchy recorded by [`Hierarchy::build`]:
/// the collapse sequence from the finest mesh (the input) to the base mesh (where the
/// simplification stopped), with everything needed to undo collapses selectively.
///
/// This is the array form of Meshsweeper (section 4.2). Vertices and triangles are
/// numbered as in the input (see [`Hierarchy::original_vertex`] for the copies made at
/// non-manifold vertices); a triangle's identity never changes, only its corners: in any
/// state, a triangle's corners are its input corners with each removed vertex replaced by
/// its parent, repeatedly, and it is live when the three are distinct. Each collapse is
/// identified by its index in the build order and removes exactly one vertex.
///
/// The fixed tables:
///
/// - **vertex parent** ([`Hierarchy::parent`]) and, per collapse, the parent's radius
///   after it ([`Hierarchy::radius_after`]); [`Hierarchy::vertex_errors`] gives the paper's
///   two values per removed vertex;
/// - **vertex splits with** ([`Hierarchy::splits_with`]): the collapses into a vertex;
/// - **triangles added by split** ([`Hierarchy::triangles_added_by_split`]), of which the
///   **removed** ones ([`Hierarchy::triangles_removed_by_split`]) are a subset;
/// - **triangles affected by split** ([`Hierarchy::triangles_affected_by_split`]);
/// - **split before** ([`Hierarchy::split_before`]).
///
/// A collapse depends on the latest earlier collapses that wrote what it read (radii of
/// the removed vertex's one-ring, faces around both ends); "split before" is the inverse
/// relation. Undoing only collapses whose dependants are undone keeps every reachable
/// state locally identical to a state of the build sequence, so every radius, face list
/// and position stored here is exact in every state, and both error-sphere invariants hold
/// in every state. [`Refinement`] is that changing state.
///
/// `Hierarchy` is `Send + Sync` and cheap to clone (the tables are shared).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyOptions, Hierarchy};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default().with_target_triangles(20))?;
/// let base = hierarchy.base();
/// assert!(base.mesh.triangle_count() <= 21);
///
/// // Split the vertex with the largest radius, and everything that must go first.
/// let mut refinement = hierarchy.refinement();
/// let worst = (0..hierarchy.vertex_count() as u32)
///     .filter(|&v| refinement.is_present(v))
///     .max_by(|&a, &b| refinement.radius(a).total_cmp(&refinement.radius(b)))
///     .unwrap();
/// let undone = refinement.split_vertex(worst)?;
/// assert!(!undone.is_empty());
/// assert!(refinement.radius(worst) < base.error_bound);
/// let triangles = refinement.live_triangle_count();
/// assert!(triangles > base.mesh.triangle_count());
///
/// // Back to the base mesh, in time proportional to the change.
/// refinement.reset();
/// assert_eq!(refinement.live_triangle_count(), base.mesh.triangle_count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Hierarchy {
    pub(crate) tables: Arc<Tables>,
    pub(crate) geometry: Geometry,
}

impl Hierarchy {
    /// Assembles the tables from the half-edge mesh as it was before the run and the
    /// recorded sequence.
    pub(crate) fn from_record(
        finest: &HalfEdgeMesh,
        recorder: Recorder,
        input_counts: (usize, usize),
        locked: LockReport,
        placement: Placement,
    ) -> Self {
        let n = finest.vertex_count();
        let entries = recorder.entries;
        let mut collapse_of = vec![NONE; n];
        let mut into: Vec<Vec<u32>> = vec![Vec::new(); n];
        let mut dependants: Vec<Vec<u32>> = vec![Vec::new(); entries.len()];
        for (c, e) in entries.iter().enumerate() {
            collapse_of[e.removed as usize] = c as u32;
            into[e.parent as usize].push(c as u32);
            for &d in &e.depends_on {
                dependants[d as usize].push(c as u32);
            }
        }
        let triangles = (0..finest.face_count() as u32)
            .map(|f| {
                finest
                    .face_vertices(sphaera_mesh::topology::FaceId(f))
                    .map(|v| v.0)
            })
            .collect();
        let tables = Tables {
            triangles,
            original_triangle: (0..finest.face_count() as u32)
                .map(|f| finest.original_face(sphaera_mesh::topology::FaceId(f)))
                .collect(),
            original_vertex: (0..n as u32)
                .map(|v| finest.original_vertex(sphaera_mesh::topology::VertexId(v)))
                .collect(),
            input_counts,
            removed: entries.iter().map(|e| e.removed).collect(),
            parent: entries.iter().map(|e| e.parent).collect(),
            added: Lists::from_rows(entries.iter().map(|e| e.fan.iter().copied())),
            dying: entries.iter().map(|e| e.dying).collect(),
            affected: Lists::from_rows(entries.iter().map(|e| e.affected.iter().copied())),
            split_before: Lists::from_rows(dependants),
            collapse_of,
            splits_with: Lists::from_rows(into),
            finest_triangle_count: finest.live_face_count(),
            locked,
            placement,
        };
        let placed = match placement {
            Placement::Optimal => entries.iter().map(|e| e.position).collect(),
            _ => Vec::new(),
        };
        let geometry = Geometry {
            positions: (0..n as u32)
                .map(|v| finest.position(sphaera_mesh::topology::VertexId(v)))
                .collect(),
            placed,
            radii: entries.iter().map(|e| e.radius).collect(),
            offsets: Vec::new(),
        };
        Self {
            tables: Arc::new(tables),
            geometry,
        }
    }

    /// Vertices of the hierarchy: the input's, plus one per extra copy of a non-manifold
    /// vertex.
    pub fn vertex_count(&self) -> usize {
        self.tables.collapse_of.len()
    }

    /// Vertices of the input mesh (the length [`Hierarchy::replay`] and
    /// [`Hierarchy::inflate`] expect).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let cube = shapes::cube(1.0, 2)?;
    /// let hierarchy = Hierarchy::build(&cube, &SimplifyOptions::default())?;
    /// assert_eq!(hierarchy.input_vertex_count(), cube.vertex_count());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn input_vertex_count(&self) -> usize {
        self.tables.input_counts.0
    }

    /// Whether `other` shares this hierarchy's fixed tables (the same build, through
    /// clones, [`Hierarchy::replay`] or [`Hierarchy::inflate`]): then a [`Refinement`] of
    /// one is a valid state of the other ([`Refinement::radius_in`]). A pointer comparison.
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
    /// assert!(hierarchy.shares_tables(&moving));
    /// let rebuilt = Hierarchy::build(&sphere, &SimplifyOptions::default())?;
    /// assert!(!hierarchy.shares_tables(&rebuilt));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn shares_tables(&self, other: &Hierarchy) -> bool {
        Arc::ptr_eq(&self.tables, &other.tables)
    }

    /// Triangles of the finest mesh (the input's, minus those with a repeated vertex
    /// index).
    pub fn triangle_count(&self) -> usize {
        self.tables.triangles.len()
    }

    /// Collapses recorded (one per removed vertex).
    pub fn collapse_count(&self) -> usize {
        self.tables.removed.len()
    }

    /// The corners of triangle `t` in the finest mesh, or `None` if out of range.
    pub fn triangle(&self, t: u32) -> Option<[u32; 3]> {
        self.tables.triangles.get(t as usize).copied()
    }

    /// Positions of the vertices in the finest mesh.
    pub fn positions(&self) -> &[DVec3] {
        &self.geometry.positions
    }

    /// The input vertex of hierarchy vertex `v` (itself except for copies of non-manifold
    /// vertices), or `None` if out of range.
    pub fn original_vertex(&self, v: u32) -> Option<u32> {
        self.tables.original_vertex.get(v as usize).copied()
    }

    /// The input triangle of hierarchy triangle `t`, or `None` if out of range.
    pub fn original_triangle(&self, t: u32) -> Option<u32> {
        self.tables.original_triangle.get(t as usize).copied()
    }

    /// The placement used by the build.
    pub fn placement(&self) -> Placement {
        self.tables.placement
    }

    /// What the build could not simplify.
    pub fn locked(&self) -> LockReport {
        self.tables.locked
    }

    /// "Vertex parent": the vertex `v` is collapsed into, or `None` if `v` is in the base
    /// mesh (or out of range).
    pub fn parent(&self, v: u32) -> Option<u32> {
        let c = self.collapse_of(v)?;
        self.tables.parent.get(c as usize).copied()
    }

    /// The collapse that removes `v`, or `None` if `v` is in the base mesh.
    pub fn collapse_of(&self, v: u32) -> Option<u32> {
        self.tables
            .collapse_of
            .get(v as usize)
            .copied()
            .filter(|&c| c != NONE)
    }

    /// The vertex collapse `c` removes, or `None` if out of range.
    pub fn removed_vertex(&self, c: u32) -> Option<u32> {
        self.tables.removed.get(c as usize).copied()
    }

    /// The vertex collapse `c` merges into (the removed vertex's parent).
    pub fn kept_vertex(&self, c: u32) -> Option<u32> {
        self.tables.parent.get(c as usize).copied()
    }

    /// The parent's error radius right after collapse `c`.
    pub fn radius_after(&self, c: u32) -> Option<f64> {
        let parent = self.kept_vertex(c)?;
        Some(self.geometry.radii.get(c as usize)? + self.offset(parent))
    }

    /// The parent's position right after collapse `c` (its old position under
    /// [`Placement::Subset`]).
    pub fn position_after(&self, c: u32) -> Option<DVec3> {
        match self.geometry.placed.get(c as usize) {
            Some(&p) => Some(p),
            None => {
                let parent = self.kept_vertex(c)?;
                self.geometry.positions.get(parent as usize).copied()
            }
        }
    }

    /// The paper's two "vertex error" values of a removed vertex `v`: its own radius when
    /// it was removed, and its parent's radius just before the collapse (restored when `v`
    /// is split). `None` if `v` is in the base mesh.
    pub fn vertex_errors(&self, v: u32) -> Option<(f64, f64)> {
        let c = self.collapse_of(v)?;
        let parent = self.kept_vertex(c)?;
        Some((
            self.radius_at_level(v, self.level_before(v, c)),
            self.radius_at_level(parent, self.level_before(parent, c)),
        ))
    }

    /// "Vertex splits with": the collapses into `v`, in build order (a refinement undoes
    /// them from the last).
    pub fn splits_with(&self, v: u32) -> &[u32] {
        self.tables.splits_with.row(v as usize)
    }

    /// "Triangles added by split": the triangles live right after undoing collapse `c`
    /// that contain its removed vertex (its whole fan). The first
    /// [`Hierarchy::triangles_revived_by_split`] of them were dead before the split; the
    /// others ([`Hierarchy::triangles_removed_by_split`]) were live with the parent as a
    /// corner and change shape.
    pub fn triangles_added_by_split(&self, c: u32) -> &[u32] {
        self.tables.added.row(c as usize)
    }

    /// The triangles that come back to life when collapse `c` is undone (the one or two on
    /// the collapsed edge).
    pub fn triangles_revived_by_split(&self, c: u32) -> &[u32] {
        let all = self.triangles_added_by_split(c);
        let dying = self.tables.dying.get(c as usize).copied().unwrap_or(0);
        all.get(..usize::from(dying)).unwrap_or(&[])
    }

    /// The triangles a split of collapse `c` removes from a priority queue (they are added
    /// back with new corners): [`Hierarchy::triangles_added_by_split`] minus the revived
    /// ones.
    pub fn triangles_removed_by_split(&self, c: u32) -> &[u32] {
        let all = self.triangles_added_by_split(c);
        let dying = self.tables.dying.get(c as usize).copied().unwrap_or(0);
        all.get(usize::from(dying)..).unwrap_or(&[])
    }

    /// "Triangles affected by split": the other triangles around the parent of collapse
    /// `c`, whose bounding volumes shrink when the parent's radius is restored.
    pub fn triangles_affected_by_split(&self, c: u32) -> &[u32] {
        self.tables.affected.row(c as usize)
    }

    /// "Split before": the later collapses that must be undone before collapse `c` can be.
    pub fn split_before(&self, c: u32) -> &[u32] {
        self.tables.split_before.row(c as usize)
    }

    /// Live triangles of the finest mesh.
    pub fn finest_triangle_count(&self) -> usize {
        self.tables.finest_triangle_count
    }

    /// A new changing state at the base mesh.
    pub fn refinement(&self) -> Refinement<'_> {
        Refinement::at_base(self)
    }

    /// A new changing state with every collapse undone: the input mesh, whose live
    /// triangles ([`Refinement::live_triangles`]) are the input's, by hierarchy id.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, Hierarchy};
    ///
    /// let sphere = shapes::sphere(1.0, 8)?;
    /// let hierarchy = Hierarchy::build(&sphere, &SimplifyOptions::default())?;
    /// let finest = hierarchy.finest_refinement();
    /// assert_eq!(finest.live_triangle_count(), sphere.triangle_count());
    /// assert_eq!(finest.live_triangles().count(), sphere.triangle_count());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn finest_refinement(&self) -> Refinement<'_> {
        Refinement::at_prefix(self, 0)
    }

    /// The base mesh (every collapse applied): the same result as
    /// [`simplify`](crate::simplify) with the same options.
    pub fn base(&self) -> Simplified {
        Refinement::at_prefix(self, self.collapse_count()).to_simplified()
    }

    /// The level of detail the build passed through when it first had at most `n`
    /// triangles (the base mesh if it never got that low, the finest if `n` is at least
    /// its count): exactly what the simplifier returns for a target `n` below the input's
    /// triangle count (at or above it, the simplifier returns the input as given, while
    /// this drops triangles with a repeated vertex index and unreferenced vertices).
    pub fn level_by_triangles(&self, n: usize) -> Simplified {
        let mut live = self.tables.finest_triangle_count;
        let mut k = 0;
        while live > n && k < self.collapse_count() {
            live -= usize::from(self.tables.dying[k]);
            k += 1;
        }
        Refinement::at_prefix(self, k).to_simplified()
    }

    /// The coarsest selectively refined mesh whose radii are all at most `bound`: starting
    /// from the base mesh, every vertex with a larger radius is split (with what must go
    /// first) until none is left. Radii that cannot go lower (offsets from
    /// [`Hierarchy::inflate`] on unsplittable vertices) stay.
    pub fn level_by_error(&self, bound: f64) -> Simplified {
        let mut refinement = self.refinement();
        refinement.refine_to_error(bound);
        refinement.to_simplified()
    }

    /// Memory of the fixed tables and the geometry, in bytes (see [`MemoryUse`]).
    pub fn memory(&self) -> MemoryUse {
        let t = &self.tables;
        let fixed = 12 * t.triangles.len()
            + 4 * (t.original_triangle.len() + t.original_vertex.len())
            + 4 * (t.removed.len() + t.parent.len() + t.collapse_of.len())
            + t.dying.len()
            + t.added.bytes()
            + t.affected.bytes()
            + t.split_before.bytes()
            + t.splits_with.bytes();
        let g = &self.geometry;
        let geometry =
            24 * (g.positions.len() + g.placed.len()) + 8 * (g.radii.len() + g.offsets.len());
        MemoryUse {
            fixed_tables: fixed,
            geometry,
            refinement_state: Refinement::state_bytes(self),
            triangles: self.tables.finest_triangle_count,
        }
    }

    /// The radius of `v` once `level` collapses into it are applied (plus its offset).
    pub(crate) fn radius_at_level(&self, v: u32, level: u32) -> f64 {
        let base = match level {
            0 => 0.0,
            l => self
                .splits_with(v)
                .get(l as usize - 1)
                .and_then(|&c| self.geometry.radii.get(c as usize))
                .copied()
                .unwrap_or(0.0),
        };
        base + self.offset(v)
    }

    /// The position of `v` once `level` collapses into it are applied.
    pub(crate) fn position_at_level(&self, v: u32, level: u32) -> DVec3 {
        let finest = self
            .geometry
            .positions
            .get(v as usize)
            .copied()
            .unwrap_or(DVec3::ZERO);
        if level == 0 || self.geometry.placed.is_empty() {
            return finest;
        }
        self.splits_with(v)
            .get(level as usize - 1)
            .and_then(|&c| self.geometry.placed.get(c as usize))
            .copied()
            .unwrap_or(finest)
    }

    /// How many collapses into `v` come before collapse `c`.
    fn level_before(&self, v: u32, c: u32) -> u32 {
        self.splits_with(v).partition_point(|&x| x < c) as u32
    }

    fn offset(&self, v: u32) -> f64 {
        self.geometry
            .offsets
            .get(v as usize)
            .copied()
            .unwrap_or(0.0)
    }
}

/// Memory used by a [`Hierarchy`], from [`Hierarchy::memory`].
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyOptions, Hierarchy};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let memory = Hierarchy::build(&sphere, &SimplifyOptions::default())?.memory();
/// assert!(memory.fixed_tables > 0);
/// assert!(memory.bytes_per_triangle(memory.refinement_state) < 16.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct MemoryUse {
    /// The fixed tables (shareable between threads and deformed copies).
    pub fixed_tables: usize,
    /// Positions and radii.
    pub geometry: usize,
    /// One [`Refinement`] (the changing state, without any caller's priority queue).
    pub refinement_state: usize,
    /// Triangles of the finest mesh (the denominator of
    /// [`MemoryUse::bytes_per_triangle`]).
    pub triangles: usize,
}

impl MemoryUse {
    /// `bytes` per triangle of the finest mesh.
    pub fn bytes_per_triangle(&self, bytes: usize) -> f64 {
        bytes as f64 / self.triangles.max(1) as f64
    }
}

#[cfg(test)]
mod tests;
