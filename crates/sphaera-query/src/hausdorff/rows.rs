//! Compressed rows of `u32` items.

/// Rows of `u32` items in compressed form (row `i` is `items[offsets[i]..offsets[i + 1]]`):
/// the triangles around each vertex, for the engines' local bounds and walks.
///
/// # Examples
///
/// ```
/// use sphaera_query::hausdorff::Rows;
///
/// let rows = Rows::from_pairs(3, vec![(2, 7), (0, 5), (2, 1), (2, 7), (9, 9)]);
/// assert_eq!(rows.row(0), &[5]);
/// assert!(rows.row(1).is_empty());
/// assert_eq!(rows.row(2), &[1, 7]);
/// assert!(rows.row(3).is_empty());
/// ```
#[derive(Clone, Debug)]
pub struct Rows {
    offsets: Vec<usize>,
    items: Vec<u32>,
}

impl Rows {
    /// The rows of the `(row, item)` pairs (sorted and deduplicated here; pairs of a row
    /// beyond `rows` are dropped). Memory follows the pairs, not `rows`: the rows after
    /// the last one with a pair are empty and not stored.
    pub fn from_pairs(rows: usize, mut pairs: Vec<(u32, u32)>) -> Self {
        pairs.retain(|&(r, _)| (r as usize) < rows);
        pairs.sort_unstable();
        pairs.dedup();
        // Rows past the last pair's are empty, as [`Rows::row`] answers for unknown rows.
        let rows = pairs.last().map_or(0, |&(r, _)| r as usize + 1);
        let mut offsets = vec![0; rows + 1];
        for &(r, _) in &pairs {
            offsets[r as usize + 1] += 1;
        }
        for i in 0..rows {
            offsets[i + 1] += offsets[i];
        }
        Self {
            offsets,
            items: pairs.into_iter().map(|(_, item)| item).collect(),
        }
    }

    /// Row `r` (empty for an unknown row).
    #[must_use]
    pub fn row(&self, r: u32) -> &[u32] {
        let r = r as usize;
        match (self.offsets.get(r), self.offsets.get(r + 1)) {
            (Some(&a), Some(&b)) => self.items.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }
}
