//! The embedded-solid certificate of a [`Surface`](crate::Surface): the mesh is a closed,
//! consistently oriented 2-manifold without self-contact, with the winding number 0 in
//! front of and 1 behind every triangle. Every step is exact (integer topology, exact
//! orientation predicates); the first defect found, in a fixed order, is reported.

use glam::DVec3;

use super::EmbeddingDefect;
use super::contacts::first_contact;
use super::intersect::{collinear, in_exact_range};
use super::signed::{closest_with_ties, side_of_ties};
use crate::closest::TriangleTree;
use crate::winding::WindingNumber;
use sphaera_mesh::TriMesh;
use sphaera_mesh::topology::{EdgeTable, halfedge_vertices};

/// How many times a side probe moves closer to its triangle before giving up.
const PROBE_ATTEMPTS: usize = 6;

/// Certifies `mesh` (with its closest-point `tree` and `winding` number) as the boundary of
/// an embedded solid, or returns the first defect.
///
/// The steps, cheapest first so that meshes that are not closed manifolds are refused in
/// linear time: coordinates in the exact range and no repeated index in a triangle; every
/// edge used twice, in opposite directions; one fan per vertex; no collinear triangle; no
/// two vertices at one position; no contact between triangles beyond what they share
/// (pairs of overlapping boxes in `tree`); per edge-connected component, probes just in
/// front of and behind one triangle read winding numbers 0 and 1.
pub(crate) fn certify(
    mesh: &TriMesh,
    tree: &TriangleTree,
    winding: &WindingNumber,
    scale: f64,
) -> Result<(), EmbeddingDefect> {
    let positions = mesh.positions();
    let triangles = mesh.triangles();
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        if a == b || b == c || c == a {
            return Err(EmbeddingDefect::DegenerateTriangle { triangle: index(t) });
        }
        for v in [a, b, c] {
            if !in_exact_range(positions[v as usize]) {
                return Err(EmbeddingDefect::CoordinateRange { vertex: v });
            }
        }
    }
    let twins = twins(triangles, positions.len())?;
    check_fans(triangles, &twins, positions.len())?;
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        let [a, b, c] = [a, b, c].map(|v| positions[v as usize]);
        if collinear(a, b, c) {
            return Err(EmbeddingDefect::DegenerateTriangle { triangle: index(t) });
        }
    }
    check_distinct_positions(mesh)?;
    if let Some((first, second)) = first_contact(tree) {
        return Err(EmbeddingDefect::SelfIntersection { first, second });
    }
    let components = components(triangles.len(), &twins);
    for &(triangle, _) in &representatives(mesh, &components) {
        check_sides(mesh, tree, winding, scale, &components, triangle)?;
    }
    Ok(())
}

/// `t` as a triangle index (the mesh has fewer than `u32::MAX` triangles).
fn index(t: usize) -> u32 {
    u32::try_from(t).unwrap_or(u32::MAX)
}

/// The twin of every half-edge (`3 t + i` runs from corner `i` to corner `i + 1` of
/// triangle `t`), if every edge is used by exactly two triangles in opposite directions.
fn twins(triangles: &[[u32; 3]], vertex_count: usize) -> Result<Vec<u32>, EmbeddingDefect> {
    let table = EdgeTable::new(triangles, vertex_count);
    let mut twins = vec![u32::MAX; 3 * triangles.len()];
    for group in table.iter() {
        let (a, b) = halfedge_vertices(triangles, group[0]);
        let &[first, second] = group else {
            return Err(EmbeddingDefect::OpenOrNonManifoldEdge {
                v0: a.min(b),
                v1: a.max(b),
                triangles: group.len(),
            });
        };
        if halfedge_vertices(triangles, second) != (b, a) {
            return Err(EmbeddingDefect::InconsistentOrientation {
                v0: a.min(b),
                v1: a.max(b),
            });
        }
        twins[first as usize] = second;
        twins[second as usize] = first;
    }
    Ok(twins)
}

/// Checks that the triangles around every vertex form one fan (a single cycle of
/// half-edges turning about it), so that no vertex pinches two sheets together.
fn check_fans(
    triangles: &[[u32; 3]],
    twins: &[u32],
    vertex_count: usize,
) -> Result<(), EmbeddingDefect> {
    let mut visited = vec![false; twins.len()];
    let mut has_fan = vec![false; vertex_count];
    for start in 0..twins.len() {
        if visited[start] {
            continue;
        }
        let vertex = triangles[start / 3][start % 3];
        if std::mem::replace(&mut has_fan[vertex as usize], true) {
            return Err(EmbeddingDefect::NonManifoldVertex { vertex });
        }
        let mut h = start;
        loop {
            visited[h] = true;
            // The next outgoing half-edge about the vertex: the one after the twin.
            let twin = twins[h] as usize;
            h = 3 * (twin / 3) + (twin % 3 + 1) % 3;
            if h == start || visited[h] {
                break;
            }
        }
    }
    Ok(())
}

/// Checks that no two referenced vertices share a position (`-0.0` equals `0.0`).
fn check_distinct_positions(mesh: &TriMesh) -> Result<(), EmbeddingDefect> {
    let positions = mesh.positions();
    let mut referenced = vec![false; positions.len()];
    for &v in mesh.triangles().iter().flatten() {
        referenced[v as usize] = true;
    }
    // Adding zero turns -0.0 into 0.0, so that numerically equal coordinates compare equal.
    let key = |v: u32| {
        let p = positions[v as usize] + DVec3::ZERO;
        (p.x, p.y, p.z, v)
    };
    let mut keys: Vec<(f64, f64, f64, u32)> = (0..positions.len())
        .filter(|&v| referenced[v])
        .map(|v| key(index(v)))
        .collect();
    let compare = |a: &(f64, f64, f64, u32), b: &(f64, f64, f64, u32)| {
        a.0.total_cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.total_cmp(&b.2))
            .then(a.3.cmp(&b.3))
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::slice::ParallelSliceMut;
        keys.par_sort_unstable_by(compare);
    }
    #[cfg(not(feature = "parallel"))]
    keys.sort_unstable_by(compare);
    for pair in keys.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if (a.0, a.1, a.2) == (b.0, b.1, b.2) {
            return Err(EmbeddingDefect::DuplicatePosition {
                first: a.3,
                second: b.3,
            });
        }
    }
    Ok(())
}

/// The edge-connected component of every triangle, numbered by their first triangle.
fn components(triangle_count: usize, twins: &[u32]) -> Vec<u32> {
    let mut component = vec![u32::MAX; triangle_count];
    let mut stack = Vec::new();
    let mut next = 0_u32;
    for seed in 0..triangle_count {
        if component[seed] != u32::MAX {
            continue;
        }
        component[seed] = next;
        stack.push(seed);
        while let Some(t) = stack.pop() {
            for &twin in &twins[3 * t..3 * t + 3] {
                let neighbour = twin as usize / 3;
                if component[neighbour] == u32::MAX {
                    component[neighbour] = next;
                    stack.push(neighbour);
                }
            }
        }
        next += 1;
    }
    component
}

/// For each component, its triangle of largest area (the first of equal ones) and that
/// area: the probes beside it have the most room.
fn representatives(mesh: &TriMesh, components: &[u32]) -> Vec<(usize, f64)> {
    let count = components.iter().max().map_or(0, |&c| c as usize + 1);
    let mut best: Vec<(usize, f64)> = vec![(usize::MAX, -1.0); count];
    for (t, triangle) in mesh.triangle_iter().enumerate() {
        let area = triangle.scaled_normal().length();
        let slot = &mut best[components[t] as usize];
        if area > slot.1 {
            *slot = (t, area);
        }
    }
    best
}

/// Probes a point in front of and one behind `triangle`, each certified by the plane test
/// to lie on that side of the triangle's component (every near tie in the component, all
/// planes agreeing), and asks the certified winding number: 0 in front and 1 behind, or
/// the component is refused (an inward-oriented or nested shell).
fn check_sides(
    mesh: &TriMesh,
    tree: &TriangleTree,
    winding: &WindingNumber,
    scale: f64,
    components: &[u32],
    triangle: usize,
) -> Result<(), EmbeddingDefect> {
    let refused = EmbeddingDefect::NotOutward {
        triangle: index(triangle),
    };
    let Some(t) = mesh.triangle(triangle) else {
        return Err(refused);
    };
    let normal = t.scaled_normal();
    let perimeter = (t.b - t.a).length() + (t.c - t.b).length() + (t.a - t.c).length();
    let Some(unit) = normal.try_normalize() else {
        return Err(refused);
    };
    let center = t.centroid();
    let order = tree.boxes().order();
    let component = components[triangle];
    for behind in [false, true] {
        // A quarter of the inradius, then closer if something else is as near.
        let mut offset = 0.25 * normal.length() / perimeter;
        let mut placed = false;
        for _ in 0..PROBE_ATTEMPTS {
            let probe = if behind {
                center - offset * unit
            } else {
                center + offset * unit
            };
            offset *= 0.125;
            let Ok((_, ties)) = closest_with_ties(tree, probe, scale) else {
                continue;
            };
            let same_component = ties.iter().all(|&i| {
                order
                    .get(i as usize)
                    .is_some_and(|&t| components[t as usize] == component)
            });
            if same_component && side_of_ties(tree, &ties, probe) == Some(behind) {
                if winding.is_inside_certified(probe) != behind {
                    return Err(refused);
                }
                placed = true;
                break;
            }
        }
        if !placed {
            return Err(refused);
        }
    }
    Ok(())
}
