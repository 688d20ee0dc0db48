//! The topology report: closedness, manifoldness, orientation, genus, defects.

use glam::DVec3;

use super::edge_table::{EdgeTable, halfedge_vertices};
use super::union_find::UnionFind;
use super::weld::identical_position_representatives;
use crate::TriMesh;

/// Options of [`analyze_with`].
///
/// # Examples
///
/// ```
/// use sphaera_mesh::topology::TopologyOptions;
///
/// let options = TopologyOptions::default();
/// assert!(options.merge_identical_positions);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct TopologyOptions {
    /// Whether vertices with identical coordinates are treated as one vertex before the
    /// topology is computed (default `true`). OBJ exporters split vertices at uv and
    /// normal seams; merging them gives the topology of the surface, and the numbers of
    /// `shared/data/README.md` (trimesh / pymeshlab). Coordinates are compared as numbers,
    /// so `-0.0` and `0.0` are identical.
    pub merge_identical_positions: bool,
}

impl Default for TopologyOptions {
    fn default() -> Self {
        Self {
            merge_identical_positions: true,
        }
    }
}

impl TopologyOptions {
    /// Options that take the triangle indices as they are (no merging).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::topology::TopologyOptions;
    ///
    /// assert!(!TopologyOptions::indices_as_given().merge_identical_positions);
    /// ```
    pub fn indices_as_given() -> Self {
        Self::default().with_merge_identical_positions(false)
    }

    /// With identical positions merged (`true`) or indices taken as given (`false`).
    #[must_use]
    pub fn with_merge_identical_positions(mut self, merge: bool) -> Self {
        self.merge_identical_positions = merge;
        self
    }
}

/// What [`analyze`] found out about a mesh's connectivity.
///
/// Vocabulary: an *edge* is an unordered pair of distinct-or-equal vertex indices used by
/// some triangle side; a triangle with a repeated index contributes a self-loop edge
/// (`a == a`), exactly as trimesh's `edges_unique` does, so `V − E + F` matches it.
/// Counts refer to the merged vertices when [`TopologyOptions::merge_identical_positions`]
/// is set (the default).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// // A tetrahedron: closed, manifold, oriented, genus 0.
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// let report = topology::analyze(&mesh);
/// assert!(report.is_closed && report.is_manifold && report.is_oriented);
/// assert_eq!(report.euler_characteristic, 2);
/// assert_eq!(report.genus, Some(0));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct TopologyReport {
    /// Vertex records of the input mesh (referenced or not, before merging).
    pub vertex_count: usize,
    /// Vertex records that were merged into an identical earlier one (0 without merging).
    pub merged_vertex_count: usize,
    /// Distinct (merged) vertices used by at least one triangle: the `V` of `χ`.
    pub referenced_vertex_count: usize,
    /// Vertex records no triangle names, counted before merging: a record counts even
    /// when its position equals that of a record a triangle does name.
    pub unreferenced_vertex_count: usize,
    /// Triangles: the `F` of `χ`.
    pub triangle_count: usize,
    /// Distinct undirected edges: the `E` of `χ`.
    pub edge_count: usize,
    /// Edges with exactly one incident triangle side.
    pub boundary_edge_count: usize,
    /// Edges with more than two incident triangle sides.
    pub non_manifold_edge_count: usize,
    /// Edges traversed twice or more in the same direction (two faces disagree on the
    /// orientation, or the edge is non-manifold with three or more faces).
    pub inconsistent_edge_count: usize,
    /// Vertices whose incident triangles form more than one fan (triangles connected
    /// through shared edges at the vertex), such as the tip of two cones. A vertex whose
    /// only defect is a non-manifold edge through it is counted among the non-manifold
    /// edges, not here (as pymeshlab does).
    pub non_manifold_vertex_count: usize,
    /// Connected components of the graph of boundary edges (for a manifold mesh: the
    /// number of holes).
    pub boundary_loop_count: usize,
    /// Connected components, triangles being connected when they share an edge (any
    /// edge, manifold or not), as pymeshlab counts them. Two shells touching at a single
    /// vertex are two components (and that vertex is non-manifold).
    pub component_count: usize,
    /// Euler characteristic `χ = V − E + F`, over the referenced (merged) vertices.
    pub euler_characteristic: i64,
    /// At least one triangle, no boundary edge and no non-manifold edge (a mesh without
    /// triangles encloses nothing, so it is not closed).
    pub is_closed: bool,
    /// No non-manifold edge and no non-manifold vertex (pymeshlab's 2-manifold). True
    /// for a mesh without triangles (vacuously: it has no defect).
    pub is_manifold: bool,
    /// No edge is traversed twice in the same direction.
    pub is_oriented: bool,
    /// The genus, summed over components and counting holes: `Σ (2 − χ_c − b_c) / 2`
    /// with `b_c` the boundary loops of component `c`. `None` unless the mesh is manifold
    /// and oriented (the genus of a non-orientable surface is a different number), and
    /// `None` for a mesh without triangles (no surface).
    pub genus: Option<u64>,
    /// Triangles with a repeated vertex index (after merging).
    pub repeated_index_triangle_count: usize,
    /// Triangles with three distinct indices but exactly zero area (collinear corners).
    pub zero_area_triangle_count: usize,
    /// Triangles with the same vertex set as an earlier triangle (either orientation).
    pub duplicate_triangle_count: usize,
}

/// The topology of `mesh`, after merging identical positions (the default options).
///
/// Works on any mesh: open, non-manifold, with degenerate or duplicate triangles and
/// unreferenced vertices. See [`TopologyReport`] for the definition of every number.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// // Two triangles sharing an edge, the shared vertices duplicated (as an OBJ seam).
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, DVec3::Y, DVec3::ONE],
///     vec![[0, 1, 2], [3, 5, 4]],
/// )?;
/// let report = topology::analyze(&mesh);
/// assert_eq!(report.merged_vertex_count, 2);
/// assert_eq!(report.edge_count, 5);
/// assert_eq!(report.boundary_edge_count, 4);
/// assert_eq!(report.boundary_loop_count, 1);
/// assert_eq!(report.genus, Some(0));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Performance
///
/// `O(n log n)` for `n` vertices (a sort of the positions, for merging), then linear:
/// a counting sort of the half-edges and a few union-find passes. The time on the
/// 871k-triangle Stanford dragon is in the section *Loading and topology
/// (`sphaera-mesh`)* of `docs/benchmarks.md` in the repository (`cargo bench -p
/// sphaera-io --bench load_topology`).
pub fn analyze(mesh: &TriMesh) -> TopologyReport {
    analyze_with(mesh, &TopologyOptions::default())
}

/// The topology of `mesh` with explicit options.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology::{self, TopologyOptions}};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, DVec3::Y, DVec3::ONE],
///     vec![[0, 1, 2], [3, 5, 4]],
/// )?;
/// // Without merging, the two triangles are separate components.
/// let report = topology::analyze_with(&mesh, &TopologyOptions::indices_as_given());
/// assert_eq!(report.component_count, 2);
/// assert_eq!(report.euler_characteristic, 2);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
pub fn analyze_with(mesh: &TriMesh, options: &TopologyOptions) -> TopologyReport {
    let vertex_count = mesh.vertex_count();
    let (triangles, merged_vertex_count) = if options.merge_identical_positions {
        let rep = identical_position_representatives(mesh.positions());
        let merged = rep
            .iter()
            .enumerate()
            .filter(|&(i, &r)| r as usize != i)
            .count();
        let tris: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .map(|t| t.map(|v| rep[v as usize]))
            .collect();
        (tris, merged)
    } else {
        (mesh.triangles().to_vec(), 0)
    };
    report_of(mesh, &triangles, vertex_count, merged_vertex_count)
}

fn report_of(
    mesh: &TriMesh,
    triangles: &[[u32; 3]],
    vertex_count: usize,
    merged_vertex_count: usize,
) -> TopologyReport {
    let positions = mesh.positions();
    // Referenced vertices (merged indices) and unreferenced records.
    let mut used = vec![false; vertex_count];
    for &v in triangles.iter().flatten() {
        used[v as usize] = true;
    }
    let referenced_vertex_count = used.iter().filter(|&&u| u).count();
    let mut named = vec![false; vertex_count];
    for &v in mesh.triangles().iter().flatten() {
        named[v as usize] = true;
    }
    let unreferenced_vertex_count = named.iter().filter(|&&u| !u).count();

    let table = EdgeTable::new(triangles, vertex_count);
    let mut boundary_edge_count = 0;
    let mut non_manifold_edge_count = 0;
    let mut inconsistent_edge_count = 0;
    let mut faces = UnionFind::new(triangles.len());
    let mut corners = UnionFind::new(triangles.len() * 3);
    let mut loops = UnionFind::new(vertex_count);
    let mut boundary_vertex = vec![false; vertex_count];
    let mut duplicate = vec![false; triangles.len()];
    for group in table.iter() {
        let (a, b) = halfedge_vertices(triangles, group[0]);
        let (lo, hi) = (a.min(b), a.max(b));
        match group.len() {
            1 => {
                boundary_edge_count += 1;
                loops.union(lo, hi);
                boundary_vertex[lo as usize] = true;
                boundary_vertex[hi as usize] = true;
                continue;
            }
            2 => {}
            _ => non_manifold_edge_count += 1,
        }
        // Corner `he` holds the half-edge's origin, corner `next(he)` its target.
        let corners_of = |he: u32| -> (bool, u32, u32) {
            let next = he - he % 3 + (he % 3 + 1) % 3;
            let forward = halfedge_vertices(triangles, he).0 == lo;
            // (forward, corner at lo, corner at hi)
            if forward {
                (true, he, next)
            } else {
                (false, next, he)
            }
        };
        let (first_forward, first_lo, first_hi) = corners_of(group[0]);
        let mut forward = usize::from(first_forward);
        for &he in &group[1..] {
            let (f, c_lo, c_hi) = corners_of(he);
            forward += usize::from(f);
            faces.union(group[0] / 3, he / 3);
            corners.union(first_lo, c_lo);
            corners.union(first_hi, c_hi);
        }
        if forward > 1 || group.len() - forward > 1 {
            inconsistent_edge_count += 1;
        }
        mark_duplicates(triangles, group, &mut duplicate);
    }

    // Non-manifold vertices: corners of one vertex in more than one fan.
    let mut first_root = vec![u32::MAX; vertex_count];
    let mut non_manifold_vertex = vec![false; vertex_count];
    for (c, &v) in triangles.iter().flatten().enumerate() {
        let root = corners.find(c as u32);
        let slot = &mut first_root[v as usize];
        if *slot == u32::MAX {
            *slot = root;
        } else if *slot != root {
            non_manifold_vertex[v as usize] = true;
        }
    }
    let non_manifold_vertex_count = non_manifold_vertex.iter().filter(|&&b| b).count();

    // Components: triangles sharing an edge.
    let component_count = (0..triangles.len() as u32)
        .filter(|&t| faces.find(t) == t)
        .count();
    let boundary_loop_count = (0..vertex_count as u32)
        .filter(|&v| boundary_vertex[v as usize] && loops.find(v) == v)
        .count();

    let triangle_count = triangles.len();
    let edge_count = table.edge_count();
    let euler_characteristic =
        referenced_vertex_count as i64 - edge_count as i64 + triangle_count as i64;
    let is_closed = triangle_count > 0 && boundary_edge_count == 0 && non_manifold_edge_count == 0;
    let is_manifold = non_manifold_edge_count == 0 && non_manifold_vertex_count == 0;
    let is_oriented = inconsistent_edge_count == 0;
    let genus = if is_manifold && is_oriented && triangle_count > 0 {
        // Σ_c (2 − χ_c − b_c) / 2 = (2 C − χ − B) / 2.
        let twice = 2 * component_count as i64 - euler_characteristic - boundary_loop_count as i64;
        u64::try_from(twice / 2).ok().filter(|_| twice % 2 == 0)
    } else {
        None
    };

    let mut repeated_index_triangle_count = 0;
    let mut zero_area_triangle_count = 0;
    for tri in triangles {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            repeated_index_triangle_count += 1;
        } else if is_zero_area(positions, *tri) {
            zero_area_triangle_count += 1;
        }
    }
    // Triangles with three distinct indices were compared through their shared edges;
    // those with a repeated index (few) are compared by sorting.
    let degenerate: Vec<[u32; 3]> = triangles
        .iter()
        .filter(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        .copied()
        .collect();
    let duplicate_triangle_count =
        duplicate.iter().filter(|&&d| d).count() + count_duplicates(&degenerate);

    TopologyReport {
        vertex_count,
        merged_vertex_count,
        referenced_vertex_count,
        unreferenced_vertex_count,
        triangle_count,
        edge_count,
        boundary_edge_count,
        non_manifold_edge_count,
        inconsistent_edge_count,
        non_manifold_vertex_count,
        boundary_loop_count,
        component_count,
        euler_characteristic,
        is_closed,
        is_manifold,
        is_oriented,
        genus,
        repeated_index_triangle_count,
        zero_area_triangle_count,
        duplicate_triangle_count,
    }
}

/// Flags the later of two non-degenerate triangles on the edge `group` whose third
/// vertices agree (same vertex set). Quadratic in the group size, which is 2 except on
/// non-manifold edges.
fn mark_duplicates(triangles: &[[u32; 3]], group: &[u32], duplicate: &mut [bool]) {
    let opposite = |he: u32| triangles[(he / 3) as usize][((he % 3 + 2) % 3) as usize];
    let distinct = |he: u32| {
        let t = triangles[(he / 3) as usize];
        t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
    };
    for (i, &x) in group.iter().enumerate() {
        if !distinct(x) {
            continue;
        }
        for &y in &group[i + 1..] {
            // Half-edges of one group are in increasing order, so y's triangle is later.
            if x / 3 != y / 3 && distinct(y) && opposite(x) == opposite(y) {
                duplicate[(y / 3) as usize] = true;
            }
        }
    }
}

fn is_zero_area(positions: &[DVec3], [a, b, c]: [u32; 3]) -> bool {
    let (pa, pb, pc) = (
        positions[a as usize],
        positions[b as usize],
        positions[c as usize],
    );
    (pb - pa).cross(pc - pa) == DVec3::ZERO
}

/// Triangles whose sorted vertex triple equals an earlier triangle's.
pub(crate) fn count_duplicates(triangles: &[[u32; 3]]) -> usize {
    duplicate_flags(triangles).iter().filter(|&&d| d).count()
}

/// For each triangle, whether an earlier triangle has the same vertex set.
pub(crate) fn duplicate_flags(triangles: &[[u32; 3]]) -> Vec<bool> {
    let mut keyed: Vec<([u32; 3], u32)> = triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let mut k = *tri;
            k.sort_unstable();
            (k, t as u32)
        })
        .collect();
    keyed.sort_unstable();
    let mut flags = vec![false; triangles.len()];
    for w in keyed.windows(2) {
        if w[0].0 == w[1].0 {
            flags[w[1].1 as usize] = true;
        }
    }
    flags
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};

    use proptest::prelude::*;

    use super::*;
    use crate::shapes::fixtures;

    /// Every number of the report, computed naively (maps, BFS, quadratic loops).
    fn brute_force(mesh: &TriMesh, merge: bool) -> TopologyReport {
        let p = mesh.positions();
        let n = p.len();
        let rep: Vec<u32> = (0..n)
            .map(|v| {
                if merge {
                    (0..n).find(|&u| p[u] == p[v]).unwrap() as u32
                } else {
                    v as u32
                }
            })
            .collect();
        let tris: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .map(|t| t.map(|v| rep[v as usize]))
            .collect();
        let mut groups: BTreeMap<(u32, u32), Vec<(usize, usize)>> = BTreeMap::new();
        for (t, tri) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                groups.entry((a.min(b), a.max(b))).or_default().push((t, k));
            }
        }
        let boundary: Vec<(u32, u32)> = groups
            .iter()
            .filter(|(_, g)| g.len() == 1)
            .map(|(&e, _)| e)
            .collect();
        let inconsistent = groups
            .iter()
            .filter(|&(&(lo, _), g)| {
                let fwd = g.iter().filter(|&&(t, k)| tris[t][k] == lo).count();
                fwd > 1 || g.len() - fwd > 1
            })
            .count();
        // Corner adjacency through shared edges.
        let mut corner_edges: Vec<((usize, usize), (usize, usize))> = Vec::new();
        for (&(lo, hi), g) in &groups {
            if g.len() < 2 {
                continue;
            }
            let at = |&(t, k): &(usize, usize), x: u32, first: bool| {
                let (o, d) = ((t, k), (t, (k + 1) % 3));
                if first {
                    if tris[t][k] == x { o } else { d }
                } else if tris[t][(k + 1) % 3] == x {
                    d
                } else {
                    o
                }
            };
            for s in g {
                for s2 in g {
                    corner_edges.push((at(s, lo, true), at(s2, lo, true)));
                    corner_edges.push((at(s, hi, false), at(s2, hi, false)));
                }
            }
        }
        let mut non_manifold_vertex_count = 0;
        for v in 0..n as u32 {
            let corners: Vec<(usize, usize)> = (0..tris.len())
                .flat_map(|t| (0..3).map(move |k| (t, k)))
                .filter(|&(t, k)| tris[t][k] == v)
                .collect();
            if corners.is_empty() {
                continue;
            }
            let mut seen = BTreeSet::from([corners[0]]);
            let mut stack = vec![corners[0]];
            while let Some(c) = stack.pop() {
                for &(a, b) in &corner_edges {
                    if a == c && seen.insert(b) {
                        stack.push(b);
                    }
                }
            }
            if seen.len() < corners.len() {
                non_manifold_vertex_count += 1;
            }
        }
        // Edge-connected components.
        let mut label = vec![usize::MAX; tris.len()];
        let mut component_count = 0;
        for start in 0..tris.len() {
            if label[start] != usize::MAX {
                continue;
            }
            label[start] = component_count;
            let mut stack = vec![start];
            while let Some(t) = stack.pop() {
                for g in groups
                    .values()
                    .filter(|g| g.len() > 1 && g.iter().any(|s| s.0 == t))
                {
                    for &(s, _) in g {
                        if label[s] == usize::MAX {
                            label[s] = component_count;
                            stack.push(s);
                        }
                    }
                }
            }
            component_count += 1;
        }
        // Boundary loops: components of the boundary-edge graph.
        let mut loop_vertices: BTreeSet<u32> = boundary.iter().flat_map(|&(a, b)| [a, b]).collect();
        let mut boundary_loop_count = 0;
        while let Some(&start) = loop_vertices.iter().next() {
            boundary_loop_count += 1;
            let mut stack = vec![start];
            loop_vertices.remove(&start);
            while let Some(v) = stack.pop() {
                for &(a, b) in &boundary {
                    for (x, y) in [(a, b), (b, a)] {
                        if x == v && loop_vertices.remove(&y) {
                            stack.push(y);
                        }
                    }
                }
            }
        }
        let used: BTreeSet<u32> = tris.iter().flatten().copied().collect();
        let named: BTreeSet<u32> = mesh.triangles().iter().flatten().copied().collect();
        let non_manifold_edge_count = groups.values().filter(|g| g.len() > 2).count();
        let chi = used.len() as i64 - groups.len() as i64 + tris.len() as i64;
        let is_manifold = non_manifold_edge_count == 0 && non_manifold_vertex_count == 0;
        let genus = (is_manifold && inconsistent == 0 && !tris.is_empty()).then(|| {
            let twice = 2 * component_count as i64 - chi - boundary_loop_count as i64;
            u64::try_from(twice / 2).unwrap()
        });
        let repeated = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
        let sorted = |t: &[u32; 3]| {
            let mut s = *t;
            s.sort_unstable();
            s
        };
        TopologyReport {
            vertex_count: n,
            merged_vertex_count: rep
                .iter()
                .enumerate()
                .filter(|&(i, &r)| r as usize != i)
                .count(),
            referenced_vertex_count: used.len(),
            unreferenced_vertex_count: n - named.len(),
            triangle_count: tris.len(),
            edge_count: groups.len(),
            boundary_edge_count: boundary.len(),
            non_manifold_edge_count,
            inconsistent_edge_count: inconsistent,
            non_manifold_vertex_count,
            boundary_loop_count,
            component_count,
            euler_characteristic: chi,
            is_closed: !tris.is_empty() && boundary.is_empty() && non_manifold_edge_count == 0,
            is_manifold,
            is_oriented: inconsistent == 0,
            genus,
            repeated_index_triangle_count: tris.iter().filter(|t| repeated(t)).count(),
            zero_area_triangle_count: tris
                .iter()
                .filter(|t| !repeated(t) && is_zero_area(p, **t))
                .count(),
            duplicate_triangle_count: (0..tris.len())
                .filter(|&t| (0..t).any(|s| sorted(&tris[s]) == sorted(&tris[t])))
                .count(),
        }
    }

    #[test]
    fn closed_solids_have_expected_genus() {
        for (mesh, chi, genus, components) in [
            (fixtures::tetrahedron(), 2, 0, 1),
            (fixtures::octahedron(), 2, 0, 1),
            (fixtures::unit_cube(), 2, 0, 1),
            (fixtures::torus(6, 4), 0, 1, 1),
            (
                fixtures::union(
                    &fixtures::torus(5, 3),
                    &fixtures::shifted(&fixtures::torus(4, 4), 9.0),
                ),
                0,
                2,
                2,
            ),
            (
                fixtures::union(
                    &fixtures::unit_cube(),
                    &fixtures::shifted(&fixtures::octahedron(), 5.0),
                ),
                4,
                0,
                2,
            ),
        ] {
            let r = analyze(&mesh);
            assert!(r.is_closed && r.is_manifold && r.is_oriented, "{r:?}");
            assert_eq!(r.euler_characteristic, chi);
            assert_eq!(r.genus, Some(genus));
            assert_eq!(r.component_count, components);
            assert_eq!(r, brute_force(&mesh, true));
        }
    }

    #[test]
    fn open_grid_is_a_disc() {
        let r = analyze(&fixtures::grid(4, 3));
        assert_eq!(r.boundary_edge_count, 14);
        assert_eq!(r.boundary_loop_count, 1);
        assert_eq!((r.euler_characteristic, r.genus), (1, Some(0)));
    }

    #[test]
    fn flipped_face_is_inconsistent_and_has_no_genus() {
        let (p, mut t) = fixtures::octahedron().into_parts();
        t[0] = [t[0][0], t[0][2], t[0][1]];
        let r = analyze(&TriMesh::new(p, t).unwrap());
        assert_eq!(r.inconsistent_edge_count, 3);
        assert!(r.is_manifold && !r.is_oriented);
        assert_eq!(r.genus, None);
    }

    #[test]
    fn three_faces_on_an_edge_are_non_manifold() {
        let mesh = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y],
            vec![[0, 1, 2], [1, 0, 3], [1, 0, 4]],
        )
        .unwrap();
        let r = analyze(&mesh);
        assert_eq!(r.non_manifold_edge_count, 1);
        assert!(!r.is_closed && !r.is_manifold);
        assert_eq!(r.component_count, 1);
        assert_eq!(r, brute_force(&mesh, true));
    }

    #[test]
    fn empty_mesh_is_not_closed_and_has_no_genus() {
        for mesh in [
            TriMesh::default(),
            TriMesh::new(vec![DVec3::ZERO, DVec3::X], Vec::new()).unwrap(),
        ] {
            let r = analyze(&mesh);
            assert_eq!(r.component_count, 0);
            assert_eq!(r.euler_characteristic, 0);
            assert!(!r.is_closed);
            assert!(r.is_manifold && r.is_oriented);
            assert_eq!(r.genus, None);
        }
    }

    fn small_mesh() -> impl Strategy<Value = TriMesh> {
        (1usize..9).prop_flat_map(|n| {
            (
                prop::collection::vec((0u8..2, 0u8..3, 0u8..2), n),
                prop::collection::vec((0..n as u32, 0..n as u32, 0..n as u32), 0..14),
            )
                .prop_map(|(points, tris)| {
                    let p = points
                        .into_iter()
                        .map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
                        .collect();
                    let t = tris.into_iter().map(|(a, b, c)| [a, b, c]).collect();
                    TriMesh::new(p, t).unwrap()
                })
        })
    }

    proptest! {
        #[test]
        fn report_matches_brute_force(mesh in small_mesh()) {
            prop_assert_eq!(analyze(&mesh), brute_force(&mesh, true));
            prop_assert_eq!(
                analyze_with(&mesh, &TopologyOptions::indices_as_given()),
                brute_force(&mesh, false)
            );
        }
    }
}
