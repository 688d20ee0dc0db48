//! Spiral "peel" paths over a mesh's vertices (paper section 6, Fig. 8), so that
//! successive closest-point queries are coherent.
//!
//! Each connected component is peeled from a pivot (its lowest vertex index): the walk
//! keeps to the ring of vertices at the smallest topological distance from the pivot that
//! is not finished, stepping to an unvisited neighbour on that ring whenever there is one,
//! so it spirals outwards ring by ring. When the ring has no unvisited neighbour left at
//! the current vertex, it jumps to the next unvisited vertex of the lowest unfinished ring.

use std::collections::VecDeque;

use super::target::Rows;

/// The vertices `0..vertex_count` in peel order (every vertex once, isolated vertices
/// last in index order), and the neighbours of every vertex. Deterministic.
///
/// # Performance
///
/// `O(V + T)` time and memory, for `V` vertices and `T` triangles.
pub(crate) fn peel_order(vertex_count: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Rows) {
    let neighbours = adjacency(vertex_count, triangles);
    let mut ring = vec![u32::MAX; vertex_count];
    let mut order = Vec::with_capacity(vertex_count);
    let mut visited = vec![false; vertex_count];
    for pivot in 0..vertex_count {
        if ring[pivot] != u32::MAX || neighbours.row(pivot as u32).is_empty() {
            continue;
        }
        let rings = rings_from(pivot, &neighbours, &mut ring);
        walk(&rings, &neighbours, &ring, &mut visited, &mut order);
    }
    order.extend((0..vertex_count).filter(|&v| !visited[v]).map(|v| v as u32));
    (order, neighbours)
}

/// Visits the vertices of one component ring by ring, stepping along each ring.
fn walk(
    rings: &[Vec<u32>],
    neighbours: &Rows,
    ring: &[u32],
    visited: &mut [bool],
    order: &mut Vec<u32>,
) {
    for (level, members) in rings.iter().enumerate() {
        let mut next_in_ring = 0;
        loop {
            // Start from the next unvisited vertex of this ring.
            while next_in_ring < members.len() && visited[members[next_in_ring] as usize] {
                next_in_ring += 1;
            }
            let Some(&start) = members.get(next_in_ring) else {
                break;
            };
            let mut current = start as usize;
            loop {
                visited[current] = true;
                order.push(current as u32);
                let step = neighbours
                    .row(current as u32)
                    .iter()
                    .map(|&n| n as usize)
                    .find(|&n| !visited[n] && ring[n] as usize == level);
                match step {
                    Some(n) => current = n,
                    None => break,
                }
            }
        }
    }
}

/// Breadth-first rings of `pivot`'s component; writes each vertex's ring into `ring`.
fn rings_from(pivot: usize, neighbours: &Rows, ring: &mut [u32]) -> Vec<Vec<u32>> {
    let mut rings: Vec<Vec<u32>> = Vec::new();
    let mut queue = VecDeque::from([pivot]);
    ring[pivot] = 0;
    while let Some(v) = queue.pop_front() {
        let level = ring[v] as usize;
        if rings.len() <= level {
            rings.push(Vec::new());
        }
        rings[level].push(v as u32);
        for &n in neighbours.row(v as u32) {
            if ring[n as usize] == u32::MAX {
                ring[n as usize] = ring[v] + 1;
                queue.push_back(n as usize);
            }
        }
    }
    rings
}

/// The neighbours of every vertex through the triangles' edges, each row sorted.
fn adjacency(vertex_count: usize, triangles: &[[u32; 3]]) -> Rows {
    let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(6 * triangles.len());
    for t in triangles {
        if t.iter().any(|&v| v as usize >= vertex_count) {
            continue;
        }
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            if a != b {
                pairs.push((a, b));
                pairs.push((b, a));
            }
        }
    }
    Rows::from_pairs(vertex_count, pairs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::shapes;

    #[test]
    fn every_vertex_once_and_mostly_adjacent_steps() {
        let mesh = shapes::sphere(1.0, 24).unwrap();
        let triangles = mesh.triangles().to_vec();
        let (order, neighbours) = peel_order(mesh.vertex_count() + 3, &triangles);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(
            sorted,
            (0..mesh.vertex_count() as u32 + 3).collect::<Vec<_>>()
        );
        let adjacent = order[..mesh.vertex_count()]
            .windows(2)
            .filter(|w| neighbours.row(w[0]).contains(&w[1]))
            .count();
        assert!(
            adjacent * 10 >= 8 * mesh.vertex_count(),
            "{adjacent} of {}",
            mesh.vertex_count()
        );
    }

    #[test]
    fn two_components_and_no_triangles() {
        assert_eq!(peel_order(3, &[]).0, vec![0, 1, 2]);
        let (order, _) = peel_order(6, &[[0, 1, 2], [3, 4, 5]]);
        assert_eq!(order.len(), 6);
        assert_eq!(order[0], 0);
    }
}
