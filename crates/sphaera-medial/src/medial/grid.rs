//! A uniform grid over the surface samples for "samples inside this ball" queries.

use glam::DVec3;

/// Samples bucketed in a uniform grid (compressed rows: `starts[c]..starts[c+1]` of
/// `ids` are in cell `c`).
#[derive(Debug, Clone)]
pub(crate) struct SampleGrid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    starts: Vec<u32>,
    ids: Vec<u32>,
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
            if dims.iter().product::<usize>() <= 4 * points.len().max(64) {
                break dims;
            }
            cell *= 1.26;
        };
        let cells = dims.iter().product::<usize>();
        let index = |p: DVec3| {
            let k = ((p - lo) / cell).floor();
            let clamp = |v: f64, d: usize| (v.max(0.0) as usize).min(d - 1);
            clamp(k.x, dims[0]) + dims[0] * (clamp(k.y, dims[1]) + dims[1] * clamp(k.z, dims[2]))
        };
        let mut starts = vec![0_u32; cells + 1];
        for &p in points {
            starts[index(p) + 1] += 1;
        }
        for c in 0..cells {
            starts[c + 1] += starts[c];
        }
        let mut fill = starts.clone();
        let mut ids = vec![0_u32; points.len()];
        for (i, &p) in points.iter().enumerate() {
            let c = index(p);
            ids[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        Self {
            origin: lo,
            cell,
            dims,
            starts,
            ids,
        }
    }

    /// Appends to `out` the samples within distance `radius` of `center`, in increasing
    /// index order.
    pub(crate) fn within(&self, points: &[DVec3], center: DVec3, radius: f64, out: &mut Vec<u32>) {
        let start = out.len();
        let r2 = radius * radius;
        let lo = ((center - DVec3::splat(radius) - self.origin) / self.cell).floor();
        let hi = ((center + DVec3::splat(radius) - self.origin) / self.cell).floor();
        let range = |l: f64, h: f64, d: usize| -> Option<(usize, usize)> {
            if h < 0.0 || l > (d - 1) as f64 {
                return None;
            }
            Some(((l.max(0.0)) as usize, (h.min((d - 1) as f64)) as usize))
        };
        let (Some(x), Some(y), Some(z)) = (
            range(lo.x, hi.x, self.dims[0]),
            range(lo.y, hi.y, self.dims[1]),
            range(lo.z, hi.z, self.dims[2]),
        ) else {
            return;
        };
        let cells = (x.1 - x.0 + 1) * (y.1 - y.0 + 1) * (z.1 - z.0 + 1);
        if cells > self.ids.len() {
            for (i, &p) in points.iter().enumerate() {
                if (p - center).length_squared() <= r2 {
                    out.push(i as u32);
                }
            }
            return;
        }
        for k in z.0..=z.1 {
            for j in y.0..=y.1 {
                let row = self.dims[0] * (j + self.dims[1] * k);
                let (a, b) = (
                    self.starts[row + x.0] as usize,
                    self.starts[row + x.1 + 1] as usize,
                );
                for &i in &self.ids[a..b] {
                    if (points[i as usize] - center).length_squared() <= r2 {
                        out.push(i);
                    }
                }
            }
        }
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
