//! A uniform grid over the surface samples for "samples inside this ball" queries.

use glam::DVec3;
use sphaera_query::grid::{MAX_GRID_CELLS, UniformGrid};

/// Samples bucketed in a uniform grid (`sphaera-query`'s, one cell size chosen here).
#[derive(Debug, Clone)]
pub(crate) struct SampleGrid {
    grid: UniformGrid,
    count: usize,
}

impl SampleGrid {
    /// A grid with about one cell per sample along the surface.
    pub(crate) fn new(points: &[DVec3]) -> Self {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &p in points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if points.is_empty() {
            lo = DVec3::ZERO;
            hi = DVec3::ZERO;
        }
        let extent = (hi - lo).max(DVec3::splat(1e-300));
        // Surface area of the box as a proxy for the sampled area.
        let area = 2.0 * (extent.x * extent.y + extent.y * extent.z + extent.z * extent.x);
        let n = points.len().max(1) as f64;
        let mut cell = (area / n).sqrt().max(extent.max_element() / 1024.0) * 2.0;
        let dims = loop {
            let dims = (extent / cell)
                .floor()
                .as_uvec3()
                .to_array()
                .map(|d| d as usize + 1);
            // Within the grid's cap too (only more than 2²⁴ samples reach it; the cell size
            // changes no answer, only the time).
            if dims.iter().product::<usize>() <= (4 * points.len().max(64)).min(MAX_GRID_CELLS) {
                break dims;
            }
            cell *= 1.26;
        };
        // Invariant: the cell is positive and finite (at least 1e-300 / 1024 · 2), there are
        // at most min(4 · max(n, 64), MAX_GRID_CELLS) cells and every sample (fewer than 2³², as their u32 ids)
        // is listed once, so the grid cannot be refused.
        let grid = UniformGrid::new(lo, cell, dims, points.iter().map(|&p| Some((p, p))))
            .expect("a valid sample grid (invariant above)");
        Self {
            grid,
            count: points.len(),
        }
    }

    /// Appends to `out` the samples within distance `radius` of `center`, in increasing
    /// index order.
    pub(crate) fn within(&self, points: &[DVec3], center: DVec3, radius: f64, out: &mut Vec<u32>) {
        let start = out.len();
        let r2 = radius * radius;
        let (lo, hi) = (center - DVec3::splat(radius), center + DVec3::splat(radius));
        if self.grid.cells_meeting(lo, hi) > self.count {
            for (i, &p) in points.iter().enumerate() {
                if (p - center).length_squared() <= r2 {
                    out.push(i as u32);
                }
            }
            return;
        }
        self.grid.visit_meeting(lo, hi, |i| {
            if (points[i as usize] - center).length_squared() <= r2 {
                out.push(i);
            }
        });
        out[start..].sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ball_queries_match_brute_force() {
        let points = sphaera_tests::point_sets::random_in_cube(3_000, 4);
        let grid = SampleGrid::new(&points);
        for (k, &c) in sphaera_tests::point_sets::random_in_cube(50, 9)
            .iter()
            .enumerate()
        {
            let r = 0.02 + 0.03 * k as f64;
            let mut got = Vec::new();
            grid.within(&points, c, r, &mut got);
            let want: Vec<u32> = (0..points.len() as u32)
                .filter(|&i| (points[i as usize] - c).length() <= r)
                .collect();
            assert_eq!(got, want);
        }
    }
}
