//! Point location and the Bowyer–Watson step: find the tetrahedra whose (perturbed)
//! circumsphere contains the new point, remove them, and connect the point to the
//! boundary of the hole.

use glam::DVec3;

use super::predicates::{in_sphere, orient};
use super::{DEAD, Delaunay, INFINITE, NONE, TetId};
use crate::DelaunayError;

/// What [`Delaunay::insert`] changed.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Insertion {
    /// The vertex id of the point (for a duplicate: the id of the earlier vertex at the
    /// same position).
    pub vertex: u32,
    /// Whether the point repeated an existing vertex (then nothing changed).
    pub duplicate: bool,
    /// Tetrahedra removed (finite and ghost). Their ids may be reused in `created`.
    pub removed: Vec<TetId>,
    /// Tetrahedra created (finite and ghost), all incident to the new vertex.
    pub created: Vec<TetId>,
}

/// Where a walk ended.
enum Location {
    /// In the closed finite tetrahedron.
    Inside(TetId),
    /// At an existing vertex.
    Vertex(u32),
    /// Strictly beyond the hull facet of this ghost.
    Outside(TetId),
}

impl Delaunay {
    /// Inserts `point`, updating the tetrahedralization locally, and reports the
    /// tetrahedra (Voronoi vertices) removed and created.
    ///
    /// # Errors
    ///
    /// [`DelaunayError::NonFinite`] for a NaN or infinite coordinate (nothing changes).
    ///
    /// # Panics
    ///
    /// Never.
    pub fn insert(&mut self, point: DVec3) -> Result<Insertion, DelaunayError> {
        if !point.is_finite() {
            return Err(DelaunayError::NonFinite {
                index: self.points.len(),
            });
        }
        if self.points.len() >= u32::MAX as usize - 2 {
            return Err(DelaunayError::TooManyPoints {
                count: self.points.len() + 1,
            });
        }
        let v = self.points.len() as u32;
        self.points.push(point);
        self.vertex_tet.push(NONE);
        self.duplicate_of.push(NONE);
        let removed_count = self.insert_vertex(v);
        if let Some(earlier) = self.duplicate_of(v) {
            // A duplicate gets no vertex id of its own.
            self.points.pop();
            self.vertex_tet.pop();
            self.duplicate_of.pop();
            return Ok(Insertion {
                vertex: earlier,
                duplicate: true,
                removed: Vec::new(),
                created: Vec::new(),
            });
        }
        debug_assert_eq!(removed_count, self.scratch.cavity.len());
        Ok(Insertion {
            vertex: v,
            duplicate: false,
            removed: self.scratch.cavity.clone(),
            created: self.scratch.created.clone(),
        })
    }

    /// Inserts existing vertex `v`; returns the number of removed tetrahedra (0 for a
    /// duplicate, which is recorded in `duplicate_of`).
    pub(super) fn insert_vertex(&mut self, v: u32) -> usize {
        let p = self.points[v as usize];
        let start = match self.locate(p) {
            Location::Vertex(u) => {
                self.duplicate_of[v as usize] = u;
                self.scratch.cavity.clear();
                self.scratch.created.clear();
                return 0;
            }
            Location::Inside(t) | Location::Outside(t) => t,
        };
        self.dig_cavity(start, p);
        self.fill_cavity(v);
        self.scratch.cavity.len()
    }

    /// A visibility walk from the hint, visiting faces in a pseudo-random order (so that it
    /// terminates on any triangulation), with a step guard and a scan as the fallback.
    fn locate(&mut self, p: DVec3) -> Location {
        let mut t = self.hint;
        if !self.is_live(t) {
            t = self.any_finite();
        }
        if let Some(slot) = self.tets[t as usize].iter().position(|&v| v == INFINITE) {
            t = self.adjacent[t as usize][slot];
        }
        let mut previous = NONE;
        let guard = 64 + 4 * self.tets.len();
        for _ in 0..guard {
            let vertices = self.tets[t as usize];
            let corners = self.corners(vertices);
            let start = self.next_random() & 3;
            let mut next = NONE;
            for k in 0..4 {
                let i = (start + k) & 3;
                let neighbour = self.adjacent[t as usize][i];
                if neighbour == previous {
                    continue;
                }
                let mut q = corners;
                q[i] = p;
                if orient(q[0], q[1], q[2], q[3]) < 0.0 {
                    next = neighbour;
                    break;
                }
            }
            if next == NONE {
                return self.inside_or_vertex(t, p);
            }
            if self.tets[next as usize].contains(&INFINITE) {
                return Location::Outside(next);
            }
            previous = t;
            t = next;
        }
        self.fallback_scans += 1;
        self.scan(p)
    }

    fn inside_or_vertex(&self, t: TetId, p: DVec3) -> Location {
        match self.tets[t as usize]
            .iter()
            .find(|&&v| self.points[v as usize] == p)
        {
            Some(&v) => Location::Vertex(v),
            None => Location::Inside(t),
        }
    }

    /// Location by testing every tetrahedron (the walk's fallback).
    #[cold]
    fn scan(&self, p: DVec3) -> Location {
        for (t, &vertices) in self.tets.iter().enumerate() {
            if vertices[0] == DEAD {
                continue;
            }
            let t = t as TetId;
            if let Some(slot) = vertices.iter().position(|&v| v == INFINITE) {
                if self.ghost_sees(t, slot, p) {
                    return Location::Outside(t);
                }
                continue;
            }
            let corners = self.corners(vertices);
            let inside = (0..4).all(|i| {
                let mut q = corners;
                q[i] = p;
                orient(q[0], q[1], q[2], q[3]) >= 0.0
            });
            if inside {
                return self.inside_or_vertex(t, p);
            }
        }
        // Unreachable: the finite tetrahedra and the ghosts' open half-spaces cover space.
        Location::Inside(self.any_finite())
    }

    /// Whether `p` lies strictly beyond the hull facet of ghost `t` (apex at `slot`).
    fn ghost_sees(&self, t: TetId, slot: usize, p: DVec3) -> bool {
        let vertices = self.tets[t as usize];
        let mut q = [DVec3::ZERO; 4];
        for i in 0..4 {
            q[i] = if i == slot {
                p
            } else {
                self.points[vertices[i] as usize]
            };
        }
        orient(q[0], q[1], q[2], q[3]) > 0.0
    }

    fn any_finite(&self) -> TetId {
        self.tets
            .iter()
            .position(|t| t[0] != DEAD && !t.contains(&INFINITE))
            .map_or(0, |t| t as TetId)
    }

    fn next_random(&mut self) -> usize {
        // xorshift32: deterministic, cheap.
        let mut x = self.walk_state;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.walk_state = x;
        (x >> 7) as usize
    }

    /// Whether `p` is in conflict with tetrahedron `t`: inside its perturbed circumsphere,
    /// or, for a ghost, beyond its hull facet (or on the facet's plane and in conflict with
    /// the finite tetrahedron behind it).
    pub(super) fn conflicts(&self, t: TetId, p: DVec3) -> bool {
        let vertices = self.tets[t as usize];
        match vertices.iter().position(|&v| v == INFINITE) {
            None => in_sphere(self.corners(vertices), p),
            Some(slot) => {
                let mut q = [DVec3::ZERO; 4];
                for i in 0..4 {
                    q[i] = if i == slot {
                        p
                    } else {
                        self.points[vertices[i] as usize]
                    };
                }
                let side = orient(q[0], q[1], q[2], q[3]);
                if side != 0.0 {
                    return side > 0.0;
                }
                let behind = self.adjacent[t as usize][slot];
                in_sphere(self.corners(self.tets[behind as usize]), p)
            }
        }
    }

    /// Collects the conflict region (connected, containing `start`) and its boundary.
    fn dig_cavity(&mut self, start: TetId, p: DVec3) {
        let scratch = &mut self.scratch;
        scratch.epoch = scratch.epoch.wrapping_add(1);
        if scratch.epoch >= u32::MAX / 2 {
            scratch.marks.fill(0);
            scratch.epoch = 1;
        }
        let inside = 2 * scratch.epoch;
        let outside = inside + 1;
        scratch.cavity.clear();
        scratch.boundary.clear();
        scratch.cavity.push(start);
        scratch.marks[start as usize] = inside;
        let mut next = 0;
        while next < self.scratch.cavity.len() {
            let t = self.scratch.cavity[next];
            next += 1;
            for i in 0..4 {
                let n = self.adjacent[t as usize][i];
                let mark = self.scratch.marks[n as usize];
                if mark == inside {
                    continue;
                }
                if mark != outside {
                    if self.conflicts(n, p) {
                        self.scratch.marks[n as usize] = inside;
                        self.scratch.cavity.push(n);
                        continue;
                    }
                    self.scratch.marks[n as usize] = outside;
                }
                let back = self.adjacent[n as usize]
                    .iter()
                    .position(|&x| x == t)
                    .unwrap_or(0) as u8;
                self.scratch.boundary.push((t, i as u8, n, back));
            }
        }
    }

    /// Replaces the cavity by the cone from vertex `v` to its boundary.
    fn fill_cavity(&mut self, v: u32) {
        let boundary = std::mem::take(&mut self.scratch.boundary);
        let cavity = std::mem::take(&mut self.scratch.cavity);
        // Read the boundary faces before any cavity id is recycled.
        let mut faces = std::mem::take(&mut self.scratch.faces);
        faces.clear();
        for &(t, slot, outside, back) in &boundary {
            let mut vertices = self.tets[t as usize];
            vertices[slot as usize] = v;
            faces.push((vertices, slot, outside, back));
        }
        for &t in &cavity {
            self.release(t);
        }
        self.scratch.created.clear();
        self.scratch.edges.reset(faces.len() * 3 / 2);
        for &(vertices, slot, outside, back) in &faces {
            let t = self.allocate(vertices);
            self.scratch.created.push(t);
            self.adjacent[t as usize][slot as usize] = outside;
            self.adjacent[outside as usize][back as usize] = t;
            for j in 0..4 {
                if j == slot as usize {
                    continue;
                }
                // The face opposite j holds v and the two vertices at the other slots.
                let mut others = (0..4).filter(|&k| k != j && k != slot as usize);
                let (Some(a), Some(b)) = (others.next(), others.next()) else {
                    continue;
                };
                if let Some((twin, twin_slot)) =
                    self.scratch
                        .edges
                        .pair(vertices[a], vertices[b], (t, j as u8))
                {
                    self.adjacent[t as usize][j] = twin;
                    self.adjacent[twin as usize][twin_slot as usize] = t;
                }
            }
            for &u in &vertices {
                if u != INFINITE {
                    self.vertex_tet[u as usize] = t;
                }
            }
            if !vertices.contains(&INFINITE) {
                self.hint = t;
            }
        }
        self.scratch.boundary = boundary;
        self.scratch.cavity = cavity;
        self.scratch.faces = faces;
    }
}
