//! Mesh mapping (section 3.1.1): every face rasterized conservatively onto a square grid
//! over the image of the bounding sphere, each cell recording the faces that touch it.

use glam::DVec2;

/// A square grid of `resolution²` cells over `[−1, 1]²`, cell `(i, j)` (column, row from
/// the bottom) at index `j · resolution + i`, with the faces touching each cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceGrid {
    resolution: usize,
    /// Cell `c`'s faces are `faces[start[c]..start[c + 1]]`, ascending.
    start: Vec<u32>,
    faces: Vec<u32>,
}

/// The cell span `[lo, hi]` (clamped) that the interval `[a, b]` of image coordinates
/// touches.
fn span(a: f64, b: f64, resolution: usize) -> Option<(usize, usize)> {
    let scale = resolution as f64 / 2.0;
    let (lo, hi) = ((a + 1.0) * scale, (b + 1.0) * scale);
    let last = resolution as f64 - 1.0;
    if hi < 0.0 || lo > resolution as f64 {
        return None;
    }
    Some((lo.clamp(0.0, last) as usize, hi.clamp(0.0, last) as usize))
}

/// The x-extent of the closed triangle `t` within the horizontal band `[lo, hi]` (`None`
/// when it misses the band): the triangle's part in the band is convex, so it covers
/// every x between the extremes of its corners in the band and its edges' crossings of
/// the band's two lines.
fn extent_in_band(t: [DVec2; 3], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |x: f64| {
        min = min.min(x);
        max = max.max(x);
    };
    for k in 0..3 {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        if a.y >= lo && a.y <= hi {
            take(a.x);
        }
        // A horizontal edge adds only its ends (taken as corners).
        if (b.y - a.y).abs() > 0.0 {
            for y in [lo, hi] {
                if y >= a.y.min(b.y) && y <= a.y.max(b.y) {
                    take(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
                }
            }
        }
    }
    (min <= max).then_some((min, max))
}

/// The cell of image point `p` on a `resolution²` grid over `[−1, 1]²` (clamped).
pub(crate) fn cell_index(p: DVec2, resolution: usize) -> usize {
    let scale = resolution as f64 / 2.0;
    // Clamped first, so truncation is the floor.
    let index = |x: f64| ((x + 1.0) * scale).clamp(0.0, resolution as f64 - 1.0) as usize;
    index(p.y) * resolution + index(p.x)
}

/// The cells a projected triangle touches (conservatively), ascending.
pub(crate) fn cells_of_triangle(t: [DVec2; 3], resolution: usize) -> Vec<usize> {
    let mut cells = Vec::new();
    cells_of_triangle_into(t, resolution, &mut cells);
    cells
}

/// [`cells_of_triangle`] into `cells` (cleared first).
pub(crate) fn cells_of_triangle_into(t: [DVec2; 3], resolution: usize, cells: &mut Vec<usize>) {
    cells.clear();
    let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    let (Some((i0, i1)), Some((j0, j1))) =
        (span(lo.x, hi.x, resolution), span(lo.y, hi.y, resolution))
    else {
        return;
    };
    let size = 2.0 / resolution as f64;
    if i0 == i1 && j0 == j1 {
        // Within one cell's span: it touches that cell.
        cells.push(j0 * resolution + i0);
        return;
    }
    // Row by row: the cells the triangle's extent in the row's band reaches, widened by a
    // relative margin on the side of touching.
    let margin = 1e-12 * (1.0 + hi.abs().max(lo.abs()).max_element());
    for j in j0..=j1 {
        let band = -1.0 + j as f64 * size;
        let Some((x0, x1)) = extent_in_band(t, band - margin, band + size + margin) else {
            continue;
        };
        let Some((a, b)) = span(x0 - margin, x1 + margin, resolution) else {
            continue;
        };
        cells.extend((a.max(i0)..=b.min(i1)).map(|i| j * resolution + i));
    }
}

impl FaceGrid {
    /// The grid of the projected triangles `triangles` (image coordinates).
    #[must_use]
    pub fn new(triangles: &[[DVec2; 3]], resolution: usize) -> Self {
        let cells = resolution * resolution;
        let per_face: Vec<Vec<usize>> = triangles
            .iter()
            .map(|&t| cells_of_triangle(t, resolution))
            .collect();
        let mut count = vec![0_u32; cells + 1];
        for list in &per_face {
            for &c in list {
                count[c + 1] += 1;
            }
        }
        for c in 0..cells {
            count[c + 1] += count[c];
        }
        let mut fill = count.clone();
        let mut faces = vec![0_u32; count[cells] as usize];
        for (f, list) in per_face.iter().enumerate() {
            for &c in list {
                faces[fill[c] as usize] = f as u32;
                fill[c] += 1;
            }
        }
        Self {
            resolution,
            start: count,
            faces,
        }
    }

    /// Cells a side.
    #[must_use]
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The faces touching cell `c`, ascending.
    #[must_use]
    pub fn faces(&self, c: usize) -> &[u32] {
        &self.faces[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The cell holding image point `p` (clamped to the grid).
    #[must_use]
    pub fn cell_of(&self, p: DVec2) -> usize {
        cell_index(p, self.resolution)
    }
}
