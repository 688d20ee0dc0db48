//! Undirected edges of a triangle soup, matched in linear time by bucketing half-edges on
//! their lower vertex index (a counting sort), then sorting each small bucket.

/// The vertices of half-edge `he`: half-edge `3 t + i` of triangle `t` goes from corner `i`
/// to corner `(i + 1) % 3`.
///
/// # Panics
///
/// If `he` is not below `3 × triangles.len()` (the half-edges of an [`EdgeTable`] of the
/// same triangles always are).
#[inline]
pub fn halfedge_vertices(triangles: &[[u32; 3]], he: u32) -> (u32, u32) {
    let tri = triangles[(he / 3) as usize];
    let i = (he % 3) as usize;
    (tri[i], tri[(i + 1) % 3])
}

/// Every undirected edge of a triangle list, with the half-edges that lie on it.
///
/// Edges are ordered by `(low vertex, high vertex)`; the half-edges of one edge are in
/// increasing half-edge index (so in triangle order). Self-loops (`a == b`, from a triangle
/// with a repeated index) are edges like any other.
#[derive(Clone, Debug)]
pub struct EdgeTable {
    /// `halfedges[starts[e]..starts[e + 1]]` are the half-edges of edge `e`.
    pub(crate) starts: Vec<u32>,
    /// Half-edge indices (`3 t + i`), grouped by edge.
    pub(crate) halfedges: Vec<u32>,
}

impl EdgeTable {
    /// Matches the half-edges of `triangles`. `vertex_count` is the number of vertices
    /// they index (a larger index only costs a longer count array).
    ///
    /// Linear time and memory: one counting pass, one fill pass, and a sort of each
    /// vertex's bucket (a handful of entries).
    pub fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Self {
        let vertex_count = triangles
            .iter()
            .flatten()
            .map(|&v| v as usize + 1)
            .max()
            .unwrap_or(0)
            .max(vertex_count);
        let he_count = triangles.len() * 3;
        let mut offsets = vec![0u32; vertex_count + 1];
        for tri in triangles {
            for i in 0..3 {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                offsets[a.min(b) as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            offsets[v + 1] += offsets[v];
        }
        let mut cursor = offsets.clone();
        // Entries are (high vertex, half-edge), so sorting a bucket groups its edges and
        // keeps half-edges in index order within an edge.
        let mut slots = vec![(0u32, 0u32); he_count];
        for (t, tri) in triangles.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                let lo = a.min(b) as usize;
                slots[cursor[lo] as usize] = (a.max(b), (3 * t + i) as u32);
                cursor[lo] += 1;
            }
        }
        let mut starts = Vec::with_capacity(he_count / 2 + 2);
        for v in 0..vertex_count {
            let bucket = &mut slots[offsets[v] as usize..offsets[v + 1] as usize];
            insertion_sort(bucket);
            let base = offsets[v];
            for k in 0..bucket.len() {
                if k == 0 || bucket[k].0 != bucket[k - 1].0 {
                    starts.push(base + k as u32);
                }
            }
        }
        starts.push(he_count as u32);
        let halfedges = slots.into_iter().map(|(_, he)| he).collect();
        Self { starts, halfedges }
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.starts.len() - 1
    }

    /// The half-edges of edge `e` (`e < edge_count()`).
    pub fn edge(&self, e: usize) -> &[u32] {
        &self.halfedges[self.starts[e] as usize..self.starts[e + 1] as usize]
    }

    /// Iterator over the half-edge groups, one per edge.
    pub fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.edge_count()).map(|e| self.edge(e))
    }
}

/// Sorts a short slice (a vertex's bucket holds about six entries, where insertion sort
/// beats the general-purpose sort); falls back to the library sort for long buckets.
fn insertion_sort(bucket: &mut [(u32, u32)]) {
    if bucket.len() > 32 {
        bucket.sort_unstable();
        return;
    }
    for i in 1..bucket.len() {
        let item = bucket[i];
        let mut j = i;
        while j > 0 && bucket[j - 1] > item {
            bucket[j] = bucket[j - 1];
            j -= 1;
        }
        bucket[j] = item;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedron_has_six_edges_of_two_halfedges() {
        let tris = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let table = EdgeTable::new(&tris, 4);
        assert_eq!(table.edge_count(), 6);
        for group in table.iter() {
            assert_eq!(group.len(), 2);
            let (a, b) = halfedge_vertices(&tris, group[0]);
            let (c, d) = halfedge_vertices(&tris, group[1]);
            assert_eq!((a, b), (d, c));
        }
    }

    #[test]
    fn repeated_index_gives_self_loop_edge() {
        let tris = [[0, 0, 1]];
        let table = EdgeTable::new(&tris, 2);
        // (0,0) and the two half-edges 0->1, 1->0 of the same triangle.
        assert_eq!(table.edge_count(), 2);
        assert_eq!(table.edge(0), &[0]);
        assert_eq!(table.edge(1), &[1, 2]);
    }
}
