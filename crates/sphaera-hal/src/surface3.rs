//! The ground work of the 3D HAL tree (section 4.2 of the paper): a closed genus-0 mesh,
//! validated; the root ball touching three vertices; shortest edge paths; and the patches
//! paths cut the surface into.

use std::collections::{BinaryHeap, HashMap, HashSet};

use glam::DVec3;
use sphaera_mesh::geometry::minimum_enclosing_ball_with_support;
use sphaera_mesh::heap::TotalF64;
use sphaera_mesh::topology::analyze;
use sphaera_mesh::{Sphere, TriMesh};

use crate::HalError;

/// A triangle mesh that HAL trees can represent: closed, manifold, consistently oriented,
/// one component, genus 0 (the paper: "it works only for objects of genus zero"), with
/// its edge graph for shortest paths.
#[derive(Clone, Debug)]
pub struct GenusZeroSurface {
    mesh: TriMesh,
    /// Per vertex: its neighbours along edges, with the edge lengths, by neighbour index.
    neighbours: Vec<Vec<(u32, f64)>>,
}

/// The root of a 3D HAL tree: a ball touching three vertices and containing every vertex
/// (the smallest enclosing ball when it touches three; else the ball through its two
/// support vertices moved until it touches a third).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootBall {
    /// The three vertices on the ball, ascending.
    pub vertices: [u32; 3],
    /// The ball.
    pub sphere: Sphere,
}

impl GenusZeroSurface {
    /// Checks `mesh` and keeps it with its edge graph.
    ///
    /// # Errors
    ///
    /// [`HalError::NotClosed`], [`HalError::NonManifold`], [`HalError::NotOriented`],
    /// [`HalError::Components`] or [`HalError::NotGenusZero`], in that order, naming
    /// what was found.
    pub fn new(mesh: &TriMesh) -> Result<Self, HalError> {
        let report = analyze(mesh);
        if report.triangle_count == 0 || report.boundary_edge_count > 0 {
            return Err(HalError::NotClosed {
                boundary_edges: report.boundary_edge_count,
            });
        }
        // Without a boundary a mesh fails to be closed only by being non-manifold: say so.
        if !report.is_manifold {
            return Err(HalError::NonManifold {
                edges: report.non_manifold_edge_count,
                vertices: report.non_manifold_vertex_count,
            });
        }
        if !report.is_closed {
            return Err(HalError::NotClosed {
                boundary_edges: report.boundary_edge_count,
            });
        }
        if !report.is_oriented {
            return Err(HalError::NotOriented {
                edges: report.inconsistent_edge_count,
            });
        }
        if report.component_count != 1 {
            return Err(HalError::Components {
                count: report.component_count,
            });
        }
        match report.genus {
            Some(0) => {}
            genus => {
                return Err(HalError::NotGenusZero {
                    genus: genus.unwrap_or_default(),
                });
            }
        }
        let positions = mesh.positions();
        let mut neighbours: Vec<Vec<(u32, f64)>> = vec![Vec::new(); positions.len()];
        for &[a, b, c] in mesh.triangles() {
            for (u, v) in [(a, b), (b, c), (c, a)] {
                let length = positions[u as usize].distance(positions[v as usize]);
                neighbours[u as usize].push((v, length));
                neighbours[v as usize].push((u, length));
            }
        }
        for list in &mut neighbours {
            list.sort_by_key(|&(v, _)| v);
            list.dedup_by_key(|&mut (v, _)| v);
        }
        Ok(Self {
            mesh: mesh.clone(),
            neighbours,
        })
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// The root ball ([`RootBall`]).
    ///
    /// When the smallest enclosing ball touches only two vertices `a` and `b`, its centre
    /// is moved along the direction, in the plane bisecting `a b`, away from the vertex
    /// nearest to its boundary, until that (or another) vertex is on it: a ball through
    /// three vertices holding all, slightly larger than the smallest (the paper allows
    /// that: "it need not be the smallest bounding ball").
    ///
    /// # Errors
    ///
    /// [`HalError::Mesh`] when the enclosing ball cannot be computed.
    pub fn root(&self) -> Result<RootBall, HalError> {
        let used = self.used_vertices();
        let points: Vec<DVec3> = used
            .iter()
            .map(|&v| self.mesh.positions()[v as usize])
            .collect();
        let ball = minimum_enclosing_ball_with_support(&points)?;
        let support: Vec<u32> = ball.support.iter().map(|&i| used[i]).collect();
        if support.len() >= 3 {
            let mut three = [support[0], support[1], support[2]];
            three.sort_unstable();
            return Ok(RootBall {
                vertices: three,
                sphere: ball.sphere,
            });
        }
        // Two support vertices: a diametral ball. Move its centre in the bisecting plane.
        let at = |v: u32| self.mesh.positions()[v as usize];
        let (a, b) = (support[0], support.get(1).copied().unwrap_or(support[0]));
        let (pa, pb) = (at(a), at(b));
        let middle = pa.midpoint(pb);
        let axis = (pb - pa).normalize_or_zero();
        let h2 = 0.25 * pa.distance_squared(pb);
        let across = |p: DVec3| {
            let v = p - middle;
            v - axis * v.dot(axis)
        };
        // The vertex nearest the boundary (farthest from the centre) decides the direction.
        let nearest = used
            .iter()
            .copied()
            .filter(|&v| v != a && v != b && across(at(v)).length() > 0.0)
            .max_by(|&u, &v| {
                at(u)
                    .distance_squared(middle)
                    .total_cmp(&at(v).distance_squared(middle))
                    .then(v.cmp(&u))
            })
            .ok_or(HalError::Degenerate)?;
        let direction = -across(at(nearest)).normalize();
        // Centre m + s·u holds x while |x − m|² − h² ≤ 2 s (x − m)·u.
        let (mut s, mut third) = (f64::INFINITY, nearest);
        for &v in &used {
            if v == a || v == b {
                continue;
            }
            let x = at(v) - middle;
            let toward = x.dot(direction);
            if toward < 0.0 {
                let limit = (x.length_squared() - h2) / (2.0 * toward);
                // Ascending vertices: the lowest index wins a tie.
                if limit < s {
                    (s, third) = (limit, v);
                }
            }
        }
        let s = s.max(0.0);
        let center = middle + direction * s;
        let radius = (h2 + s * s).sqrt().max(
            used.iter()
                .map(|&v| at(v).distance(center))
                .fold(0.0, f64::max),
        );
        let mut three = [a, b, third];
        three.sort_unstable();
        Ok(RootBall {
            vertices: three,
            sphere: Sphere::new(center, radius),
        })
    }

    /// Vertices referenced by a triangle, ascending.
    fn used_vertices(&self) -> Vec<u32> {
        (0..self.neighbours.len() as u32)
            .filter(|&v| !self.neighbours[v as usize].is_empty())
            .collect()
    }

    /// The shortest path along edges from `a` to `b` (Dijkstra), as vertices from `a` to
    /// `b`. Deterministic: it always runs from the lower index of the two (the paper's
    /// rule), settling vertices in order of distance then index, and a vertex keeps the
    /// first predecessor that reached it at its final distance.
    ///
    /// # Panics
    ///
    /// If `a` or `b` is not a vertex of the mesh.
    #[must_use]
    pub fn shortest_path(&self, a: u32, b: u32) -> Vec<u32> {
        self.dijkstra(a, b, |_, _| true)
    }

    /// [`GenusZeroSurface::shortest_path`] along the edges of the triangles `faces` only
    /// (a patch): the path stays in the patch. `[a]` when `b` cannot be reached.
    #[must_use]
    pub fn shortest_path_within(&self, faces: &[u32], a: u32, b: u32) -> Vec<u32> {
        let triangles = self.mesh.triangles();
        let mut edges = HashSet::new();
        for &f in faces {
            let [x, y, z] = triangles[f as usize];
            for (u, v) in [(x, y), (y, z), (z, x)] {
                edges.insert((u.min(v), u.max(v)));
            }
        }
        self.dijkstra(a, b, |u, v| edges.contains(&(u.min(v), u.max(v))))
    }

    /// Dijkstra from the lower of `a`, `b` over the edges `usable` accepts, as the path
    /// from `a` to `b`. Its state is kept for the vertices it reaches only (a map, not an
    /// array over the mesh), so a path inside a small patch costs the patch, not the
    /// mesh: the build's many short paths stay near the paper's bound.
    fn dijkstra(&self, a: u32, b: u32, usable: impl Fn(u32, u32) -> bool) -> Vec<u32> {
        let (from, to) = (a.min(b), a.max(b));
        // Per reached vertex: its distance so far and its predecessor (none for `from`).
        let mut reached: HashMap<u32, (f64, u32)> = HashMap::new();
        let mut heap = BinaryHeap::new();
        reached.insert(from, (0.0, u32::MAX));
        heap.push(std::cmp::Reverse((TotalF64(0.0), from)));
        while let Some(std::cmp::Reverse((TotalF64(d), v))) = heap.pop() {
            if reached.get(&v).is_some_and(|&(best, _)| d > best) {
                continue;
            }
            if v == to {
                break;
            }
            for &(w, length) in &self.neighbours[v as usize] {
                if !usable(v, w) {
                    continue;
                }
                let next = d + length;
                if reached.get(&w).is_none_or(|&(best, _)| next < best) {
                    reached.insert(w, (next, v));
                    heap.push(std::cmp::Reverse((TotalF64(next), w)));
                }
            }
        }
        let previous = |v: u32| reached.get(&v).map_or(u32::MAX, |&(_, p)| p);
        let mut path = vec![to];
        let mut v = to;
        while v != from && previous(v) != u32::MAX {
            v = previous(v);
            path.push(v);
        }
        // From `to` back to `from`: reverse when the caller asked from the lower index.
        if a == from {
            path.reverse();
        }
        path
    }

    /// The patches the closed edge paths `paths` cut the surface into: faces connected
    /// across edges on no path, each patch's faces ascending, patches ordered by their
    /// first face.
    #[must_use]
    pub fn patches(&self, paths: &[&[u32]]) -> Vec<Vec<u32>> {
        let mut cut = HashSet::new();
        for path in paths {
            for pair in path.windows(2) {
                cut.insert((pair[0].min(pair[1]), pair[0].max(pair[1])));
            }
        }
        let all: Vec<u32> = (0..self.mesh.triangle_count() as u32).collect();
        self.regions(&all, &cut).0
    }

    /// The regions of `faces` connected across edges not in `cut` (undirected, lower index
    /// first): each region's faces ascending, regions ordered by their first face, and
    /// each face's region.
    pub(crate) fn regions(
        &self,
        faces: &[u32],
        cut: &HashSet<(u32, u32)>,
    ) -> (Vec<Vec<u32>>, HashMap<u32, u32>) {
        let triangles = self.mesh.triangles();
        let mut by_edge: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        for &f in faces {
            let [a, b, c] = triangles[f as usize];
            for (u, v) in [(a, b), (b, c), (c, a)] {
                by_edge.entry((u.min(v), u.max(v))).or_default().push(f);
            }
        }
        let mut sorted = faces.to_vec();
        sorted.sort_unstable();
        let mut region_of: HashMap<u32, u32> = HashMap::new();
        let mut regions = Vec::new();
        for start in sorted {
            if region_of.contains_key(&start) {
                continue;
            }
            let id = regions.len() as u32;
            region_of.insert(start, id);
            let mut members = vec![start];
            let mut stack = vec![start];
            while let Some(f) = stack.pop() {
                let [a, b, c] = triangles[f as usize];
                for (u, v) in [(a, b), (b, c), (c, a)] {
                    let key = (u.min(v), u.max(v));
                    if cut.contains(&key) {
                        continue;
                    }
                    for &g in &by_edge[&key] {
                        if let std::collections::hash_map::Entry::Vacant(e) = region_of.entry(g) {
                            e.insert(id);
                            members.push(g);
                            stack.push(g);
                        }
                    }
                }
            }
            members.sort_unstable();
            regions.push(members);
        }
        (regions, region_of)
    }
}
