//! Incremental 3D Delaunay tetrahedralization (Bowyer–Watson) with exact predicates and a
//! symbolic perturbation, and its Voronoi dual.
//!
//! # Representation
//!
//! Tetrahedra live in flat arrays indexed by [`TetId`]: four vertex indices and, per
//! corner, the neighbour across the face opposite it. The convex hull is closed by *ghost*
//! tetrahedra that share the vertex [`INFINITE`], so every finite face has two sides and
//! a point outside the hull is inserted like any other. Every tetrahedron is stored
//! positively oriented; a ghost is oriented as if [`INFINITE`] were a point beyond its
//! hull facet.
//!
//! # Robustness
//!
//! Orientation and in-sphere signs are exact (`robust`), and in-sphere ties are broken by
//! a symbolic perturbation that depends on the points only (see the `predicates` module),
//! so cospherical and coplanar input (grids, spheres, cylinders) yields a valid, unique
//! tetrahedralization with no flat tetrahedra, and the result does not depend on the
//! insertion order. Point location is a visibility walk from the last created
//! tetrahedron with a guard that falls back to a scan, so it cannot loop.

mod edge_map;
mod insert;
mod integer;
mod order;
mod predicates;
mod validate;
mod voronoi;

use glam::DVec3;

pub use insert::Insertion;
pub use voronoi::VoronoiCell;

use crate::DelaunayError;
use edge_map::EdgeMap;

/// Index of a tetrahedron. Ids of removed tetrahedra are recycled by later insertions.
pub type TetId = u32;

/// The vertex at infinity that every ghost (hull) tetrahedron shares.
pub const INFINITE: u32 = u32::MAX;

/// Marks a removed tetrahedron in the vertex array.
const DEAD: u32 = u32::MAX - 1;

/// "No tetrahedron".
const NONE: u32 = u32::MAX;

/// Seed of the insertion-order shuffle: the order is a function of the points only.
const ORDER_SEED: u64 = 0x5EED_DE1A_0A11_0001;

/// A Delaunay tetrahedralization of a set of points in 3D, built incrementally.
///
/// # Examples
///
/// ```
/// use sphaera_medial::{DVec3, Delaunay};
///
/// // The eight corners of a cube are cospherical: the perturbation still gives a valid
/// // tetrahedralization (a cube splits into 5 or 6 tetrahedra).
/// let corners: Vec<DVec3> = (0..8)
///     .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
///     .collect();
/// let mut delaunay = Delaunay::new(&corners)?;
/// assert!((5..=6).contains(&delaunay.tetrahedron_count()));
/// delaunay.validate()?;
///
/// // Insert the centre: the tetrahedra whose circumsphere contains it are replaced.
/// let report = delaunay.insert(DVec3::splat(0.5))?;
/// assert_eq!(report.vertex, 8);
/// assert!(!report.removed.is_empty() && !report.created.is_empty());
/// assert_eq!(delaunay.tetrahedron_count(), 12);
/// delaunay.validate()?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Delaunay {
    points: Vec<DVec3>,
    tets: Vec<[u32; 4]>,
    adjacent: Vec<[TetId; 4]>,
    free: Vec<TetId>,
    /// One live tetrahedron incident to each vertex; `NONE` for duplicates.
    vertex_tet: Vec<TetId>,
    /// For each vertex, the earlier vertex at the same position, or `NONE`.
    duplicate_of: Vec<u32>,
    finite_count: usize,
    /// Where the next walk starts.
    hint: TetId,
    /// Deterministic state for the walk's face order.
    walk_state: u32,
    /// Walks that hit the step guard and fell back to a scan (never seen in practice).
    fallback_scans: usize,
    scratch: Scratch,
}

/// Per-insertion working memory, kept between insertions.
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// Per tetrahedron: `2·epoch` if in the cavity, `2·epoch + 1` if tested and not.
    marks: Vec<u32>,
    epoch: u32,
    cavity: Vec<TetId>,
    /// Boundary faces of the cavity: (cavity tet, its slot, outside tet, the outside
    /// tet's slot facing it).
    boundary: Vec<(TetId, u8, TetId, u8)>,
    created: Vec<TetId>,
    /// The new tetrahedra to create: vertices, the slot facing outside, the outside
    /// tetrahedron and its slot facing in.
    faces: Vec<([u32; 4], u8, TetId, u8)>,
    edges: EdgeMap,
}

impl Delaunay {
    /// Tetrahedralizes `points`. Vertex `i` of the result is `points[i]`; a point equal to
    /// an earlier one becomes a duplicate (see [`Delaunay::duplicate_of`]) and takes no
    /// part.
    ///
    /// # Errors
    ///
    /// [`DelaunayError::NonFinite`] for a NaN or infinite coordinate,
    /// [`DelaunayError::TooFewPoints`] for fewer than four distinct points, and
    /// [`DelaunayError::Flat`] when all points lie on one plane, line or point.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// Expected `O(n log n)`: a biased randomized insertion order sorted along a Hilbert
    /// curve, a walk from the last created tetrahedron, and a local cavity per point.
    pub fn new(points: &[DVec3]) -> Result<Self, DelaunayError> {
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(DelaunayError::NonFinite { index });
        }
        if points.len() >= u32::MAX as usize - 2 {
            return Err(DelaunayError::TooManyPoints {
                count: points.len(),
            });
        }
        let order = order::brio(points, (0..points.len() as u32).collect(), ORDER_SEED);
        let first = initial_simplex(points, &order)?;
        let mut delaunay = Self {
            points: points.to_vec(),
            tets: Vec::with_capacity(points.len() * 7),
            adjacent: Vec::with_capacity(points.len() * 7),
            free: Vec::new(),
            vertex_tet: vec![NONE; points.len()],
            duplicate_of: vec![NONE; points.len()],
            finite_count: 0,
            hint: 0,
            walk_state: 0x9E37_79B9,
            fallback_scans: 0,
            scratch: Scratch::default(),
        };
        delaunay.start(first);
        for &v in &order {
            if !first.contains(&v) {
                delaunay.insert_vertex(v);
            }
        }
        Ok(delaunay)
    }

    /// The number of vertices, duplicates included (vertex ids are `0..vertex_count()`).
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.points.len()
    }

    /// The position of vertex `v`.
    ///
    /// # Panics
    ///
    /// If `v` is not a vertex id.
    #[must_use]
    pub fn point(&self, v: u32) -> DVec3 {
        self.points[v as usize]
    }

    /// All vertex positions, by vertex id.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The earlier vertex at the same position as `v`, if `v` is a duplicate (duplicates
    /// are not part of the tetrahedralization).
    #[must_use]
    pub fn duplicate_of(&self, v: u32) -> Option<u32> {
        self.duplicate_of
            .get(v as usize)
            .copied()
            .filter(|&d| d != NONE)
    }

    /// The number of finite tetrahedra.
    #[must_use]
    pub fn tetrahedron_count(&self) -> usize {
        self.finite_count
    }

    /// The finite tetrahedra with their vertex ids, in id order.
    pub fn tetrahedra(&self) -> impl Iterator<Item = (TetId, [u32; 4])> + '_ {
        self.tets
            .iter()
            .enumerate()
            .filter(|(_, t)| t[0] != DEAD && !t.contains(&INFINITE))
            .map(|(i, t)| (i as TetId, *t))
    }

    /// Whether `t` is a live tetrahedron (finite or ghost).
    #[must_use]
    pub fn is_live(&self, t: TetId) -> bool {
        self.tets.get(t as usize).is_some_and(|v| v[0] != DEAD)
    }

    /// Whether `t` is a live finite tetrahedron.
    #[must_use]
    pub fn is_finite(&self, t: TetId) -> bool {
        self.tets
            .get(t as usize)
            .is_some_and(|v| v[0] != DEAD && !v.contains(&INFINITE))
    }

    /// The four vertices of tetrahedron `t` ([`INFINITE`] for a ghost's apex), positively
    /// oriented.
    ///
    /// # Panics
    ///
    /// If `t` is not a tetrahedron id.
    #[must_use]
    pub fn vertices(&self, t: TetId) -> [u32; 4] {
        self.tets[t as usize]
    }

    /// The neighbours of `t`: entry `i` is across the face opposite vertex `i` (a ghost
    /// beyond the hull).
    ///
    /// # Panics
    ///
    /// If `t` is not a tetrahedron id.
    #[must_use]
    pub fn neighbors(&self, t: TetId) -> [TetId; 4] {
        self.adjacent[t as usize]
    }

    /// How many point locations fell back to a scan of all tetrahedra (a guard against a
    /// looping walk; zero in every test and benchmark so far).
    #[must_use]
    pub fn fallback_scans(&self) -> usize {
        self.fallback_scans
    }

    fn corners(&self, t: [u32; 4]) -> [DVec3; 4] {
        t.map(|v| self.points[v as usize])
    }

    fn allocate(&mut self, vertices: [u32; 4]) -> TetId {
        if !vertices.contains(&INFINITE) {
            self.finite_count += 1;
        }
        if let Some(t) = self.free.pop() {
            self.tets[t as usize] = vertices;
            self.adjacent[t as usize] = [NONE; 4];
            t
        } else {
            self.tets.push(vertices);
            self.adjacent.push([NONE; 4]);
            self.scratch.marks.push(0);
            (self.tets.len() - 1) as TetId
        }
    }

    fn release(&mut self, t: TetId) {
        if !self.tets[t as usize].contains(&INFINITE) {
            self.finite_count -= 1;
        }
        self.tets[t as usize] = [DEAD; 4];
        self.free.push(t);
    }

    /// The first tetrahedron and its four ghosts.
    fn start(&mut self, [a, b, c, d]: [u32; 4]) {
        let p = self.points.as_slice();
        let first =
            if predicates::orient(p[a as usize], p[b as usize], p[c as usize], p[d as usize]) > 0.0
            {
                [a, b, c, d]
            } else {
                [b, a, c, d]
            };
        let t = self.allocate(first);
        let mut ghosts = [0; 4];
        for (i, ghost) in ghosts.iter_mut().enumerate() {
            // INFINITE stands beyond the facet, on the side opposite first[i]: replacing
            // first[i] by it flips the orientation, which one swap restores.
            let mut vertices = first;
            vertices[i] = INFINITE;
            vertices.swap((i + 1) % 4, (i + 2) % 4);
            *ghost = self.allocate(vertices);
        }
        for (i, &ghost) in ghosts.iter().enumerate() {
            self.adjacent[t as usize][i] = ghost;
            self.adjacent[ghost as usize][i] = t;
        }
        // Ghost–ghost faces: the face of ghost i opposite a finite vertex u is shared with
        // the ghost that replaced u.
        for (i, &ghost) in ghosts.iter().enumerate() {
            for slot in 0..4 {
                if slot == i {
                    continue;
                }
                let u = self.tets[ghost as usize][slot];
                let k = first.iter().position(|&x| x == u).unwrap_or(0);
                self.adjacent[ghost as usize][slot] = ghosts[k];
            }
        }
        for v in first {
            self.vertex_tet[v as usize] = t;
        }
        self.hint = t;
    }
}

/// Four affinely independent points, taken in insertion order.
fn initial_simplex(points: &[DVec3], order: &[u32]) -> Result<[u32; 4], DelaunayError> {
    let at = |i: u32| points[i as usize];
    let Some(&a) = order.first() else {
        return Err(DelaunayError::TooFewPoints { distinct: 0 });
    };
    let Some(&b) = order.iter().find(|&&i| at(i) != at(a)) else {
        return Err(too_few_or_flat(points, 0));
    };
    let Some(&c) = order.iter().find(|&&i| !collinear(at(a), at(b), at(i))) else {
        return Err(too_few_or_flat(points, 1));
    };
    let Some(&d) = order
        .iter()
        .find(|&&i| predicates::orient(at(a), at(b), at(c), at(i)) != 0.0)
    else {
        return Err(too_few_or_flat(points, 2));
    };
    Ok([a, b, c, d])
}

fn too_few_or_flat(points: &[DVec3], dimension: usize) -> DelaunayError {
    let mut sorted: Vec<DVec3> = points.to_vec();
    sorted.sort_unstable_by(|a, b| predicates::lexicographic(*a, *b));
    sorted.dedup();
    if sorted.len() < 4 {
        DelaunayError::TooFewPoints {
            distinct: sorted.len(),
        }
    } else {
        DelaunayError::Flat { dimension }
    }
}

/// Exact collinearity: the three coordinate projections are all degenerate.
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let flat = |pa: [f64; 2], pb: [f64; 2], pc: [f64; 2]| {
        let coord = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
        robust::orient2d(coord(pa), coord(pb), coord(pc)) == 0.0
    };
    flat([a.x, a.y], [b.x, b.y], [c.x, c.y])
        && flat([a.y, a.z], [b.y, b.z], [c.y, c.z])
        && flat([a.z, a.x], [b.z, b.x], [c.z, c.x])
}
