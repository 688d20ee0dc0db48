//! Poisson-disk sampling by sample elimination (Yuksel 2015).

use glam::DVec3;

use super::grid::{Grid, map_indices, min_distance};
use sphaera_mesh::heap::{HeapItem, IndexedHeap, Priority, TotalF64};

/// A candidate of sample elimination in its heap: the heaviest (most crowded) first,
/// ties by the higher sample index (any fixed order keeps it deterministic).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    weight: f64,
    sample: u32,
}

impl Priority for Candidate {
    type Key = (TotalF64, u32);

    fn priority(&self) -> Self::Key {
        (TotalF64(self.weight), self.sample)
    }
}

impl HeapItem for Candidate {
    fn id(&self) -> u32 {
        self.sample
    }
}
use super::{SurfaceSample, check_count, random};
use crate::QueryError;
use sphaera_mesh::TriMesh;

/// Options of [`poisson_disk_with`].
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling::PoissonDiskOptions;
/// let options = PoissonDiskOptions::default().with_oversampling(8.0);
/// assert_eq!(options.oversampling, 8.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PoissonDiskOptions {
    /// Draw `oversampling · n` random candidates to eliminate down to `n` (at least 1;
    /// larger is more even and slower: 3 is quick, 5 the default, 10 barely better).
    pub oversampling: f64,
}

impl Default for PoissonDiskOptions {
    /// Oversampling 5, the value Yuksel recommends.
    fn default() -> Self {
        Self { oversampling: 5.0 }
    }
}

impl PoissonDiskOptions {
    /// With the given oversampling factor.
    #[must_use]
    pub fn with_oversampling(mut self, oversampling: f64) -> Self {
        self.oversampling = oversampling;
        self
    }
}

/// The result of [`poisson_disk`]: the samples and how evenly they are spread.
#[derive(Clone, Debug, PartialEq)]
pub struct PoissonDiskSamples {
    /// Exactly `n` points, in the order they were drawn as candidates.
    pub samples: Vec<SurfaceSample>,
    /// The smallest Euclidean distance between two samples (`f64::INFINITY` for fewer
    /// than two).
    pub min_distance: f64,
    /// The ideal spacing of `n` points on this area: the distance between neighbours of
    /// a hexagonal packing, `√(2 A / (√3 n))`. No set of `n` points on a flat surface of
    /// area `A` has a larger minimum distance (asymptotically).
    pub ideal_spacing: f64,
}

impl PoissonDiskSamples {
    /// `min_distance / ideal_spacing`: 1 would be a perfect hexagonal packing; sample
    /// elimination typically reaches 0.6 to 0.75 on smooth surfaces, uniform random points
    /// about `1/√n`.
    pub fn relative_min_distance(&self) -> f64 {
        self.min_distance / self.ideal_spacing
    }
}

/// `n` evenly spread points on the surface of `mesh` (a Poisson-disk set), reproducible
/// from `seed`, with the default [`PoissonDiskOptions`].
///
/// Sample elimination (Yuksel 2015): draw `k·n` candidates with [`random`] (`k` =
/// oversampling, 5 by default), give each candidate the weight
/// `Σ (1 − d̂ᵢⱼ / d_max)⁸` over the candidates `j` closer than `d_max` (the ideal spacing
/// of `n` points, with `d̂ᵢⱼ` the distance clamped from below to
/// `d_max · 0.65 · (1 − k^−1.5)` so clusters do not dominate), then repeatedly remove the
/// heaviest candidate and lighten its neighbours until `n` remain. Ties are broken by a
/// fixed order (position in the grid), so the result is deterministic; the neighbour
/// search runs in parallel
/// with the `parallel` feature and gives the same result without it. `n = 0` gives an
/// empty set.
///
/// Distances are Euclidean, so the method assumes the ideal spacing is well below the
/// thickness of the shape's thin parts: with 100 points on a tube whose wall is 0.4 times
/// the ideal spacing, points on opposite walls crowd each other and the weight limiting
/// (all distances below `0.59 d_max` weigh the same) can no longer tell near from very
/// near — the set is still exactly `n` points, but `relative_min_distance` drops to a few
/// percent. Ask for more points, or check [`PoissonDiskSamples::relative_min_distance`].
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling;
/// use sphaera_mesh::shapes;
///
/// let mesh = shapes::torus(1.0, 0.3, 48)?;
/// let set = sampling::poisson_disk(&mesh, 2000, 1)?;
/// assert_eq!(set.samples.len(), 2000);
/// assert!(set.relative_min_distance() > 0.5);
/// assert_eq!(set, sampling::poisson_disk(&mesh, 2000, 1)?);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Errors
///
/// As [`random`]; also [`QueryError::InvalidParameter`] if `n` times the oversampling
/// exceeds [`super::MAX_SAMPLES`].
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// About `O(T + k n log n)` (memory: about 150 bytes per candidate). The time for
/// 10,000 points on the 69k-triangle bunny is in the section *Adaptive medial
/// approximation* of `docs/benchmarks.md` in the repository.
pub fn poisson_disk(mesh: &TriMesh, n: usize, seed: u64) -> Result<PoissonDiskSamples, QueryError> {
    poisson_disk_with(mesh, n, seed, &PoissonDiskOptions::default())
}

/// [`poisson_disk`] with explicit options.
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling::{self, PoissonDiskOptions};
/// use sphaera_mesh::shapes;
///
/// let mesh = shapes::sphere(1.0, 32)?;
/// let quick = PoissonDiskOptions::default().with_oversampling(3.0);
/// let set = sampling::poisson_disk_with(&mesh, 500, 9, &quick)?;
/// assert_eq!(set.samples.len(), 500);
///
/// let bad = PoissonDiskOptions::default().with_oversampling(0.5);
/// assert!(sampling::poisson_disk_with(&mesh, 500, 9, &bad).is_err());
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Errors
///
/// As [`poisson_disk`]; [`QueryError::InvalidParameter`] if the oversampling is not finite
/// or below 1.
///
/// # Panics
///
/// Never.
pub fn poisson_disk_with(
    mesh: &TriMesh,
    n: usize,
    seed: u64,
    options: &PoissonDiskOptions,
) -> Result<PoissonDiskSamples, QueryError> {
    let k = options.oversampling;
    if !(k.is_finite() && k >= 1.0) {
        return Err(QueryError::InvalidParameter {
            name: "oversampling",
            value: k,
            requirement: "finite and at least 1",
        });
    }
    check_count("n", n)?;
    let candidate_count = (k * n as f64).ceil();
    if candidate_count > super::MAX_SAMPLES as f64 {
        return Err(QueryError::InvalidParameter {
            name: "n × oversampling",
            value: candidate_count,
            requirement: "at most `sampling::MAX_SAMPLES` (2^24)",
        });
    }
    // Validates the mesh even for n = 0 (candidate_count ≤ MAX_SAMPLES, so the cast is exact).
    let candidates = random(mesh, candidate_count as usize, seed)?;
    let area = mesh.surface_area();
    let ideal_spacing = (2.0 * area / (3f64.sqrt() * n as f64)).sqrt();
    if n == 0 {
        return Ok(PoissonDiskSamples {
            samples: Vec::new(),
            min_distance: f64::INFINITY,
            ideal_spacing,
        });
    }
    let keep = eliminate(&candidates, n, ideal_spacing);
    let samples: Vec<SurfaceSample> = keep.into_iter().map(|i| candidates[i]).collect();
    let positions: Vec<DVec3> = samples.iter().map(|s| s.position).collect();
    Ok(PoissonDiskSamples {
        min_distance: min_distance(&positions, ideal_spacing),
        samples,
        ideal_spacing,
    })
}

/// Indices (ascending) of the `n` candidates that survive weighted sample elimination.
///
/// `n ≥ 1`; returns every candidate if there are no more than `n`.
fn eliminate(candidates: &[SurfaceSample], n: usize, d_max: f64) -> Vec<usize> {
    let m = candidates.len();
    if m <= n || !(d_max.is_finite() && d_max > 0.0) {
        return (0..m.min(n)).collect();
    }
    let grid = Grid::new(
        &candidates.iter().map(|s| s.position).collect::<Vec<_>>(),
        d_max,
    );
    // Positions in slot order (cache-friendly: neighbours are near in memory).
    let points: Vec<DVec3> = grid
        .slots
        .iter()
        .map(|&i| candidates[i as usize].position)
        .collect();
    // (n / m)^1.5 and (1 - d / d_max)^8 with plain multiplications and `sqrt` (correctly
    // rounded everywhere), not `powf` / `powi`, whose results may differ between libms.
    let ratio = n as f64 / m as f64;
    let d_min = d_max * 0.65 * (1.0 - ratio * ratio.sqrt());
    let weight = |a: DVec3, b: DVec3| {
        let d = a.distance(b).max(d_min);
        let x2 = (1.0 - d / d_max) * (1.0 - d / d_max);
        let x4 = x2 * x2;
        x4 * x4
    };

    // Neighbour lists in slot space, per occupied cell (in parallel), then flattened.
    let per_cell = map_indices(grid.cell_count(), |c| {
        let ranges = grid.neighbourhood(c);
        grid.cell_slots(c)
            .map(|s| {
                let p = points[s];
                ranges
                    .iter()
                    .flat_map(Clone::clone)
                    .filter(|&t| t != s && p.distance_squared(points[t]) < d_max * d_max)
                    .map(|t| t as u32)
                    .collect::<Vec<u32>>()
            })
            .collect::<Vec<_>>()
    });
    let mut offsets = Vec::with_capacity(m + 1);
    offsets.push(0usize);
    let mut neighbours = Vec::new();
    for list in per_cell.into_iter().flatten() {
        neighbours.extend_from_slice(&list);
        offsets.push(neighbours.len());
    }
    let near = |s: usize| &neighbours[offsets[s]..offsets[s + 1]];

    let mut weights: Vec<f64> = (0..m)
        .map(|s| {
            near(s)
                .iter()
                .map(|&t| weight(points[s], points[t as usize]))
                .sum()
        })
        .collect();
    let mut heap = IndexedHeap::from_items(
        m,
        weights.iter().enumerate().map(|(s, &weight)| Candidate {
            weight,
            sample: s as u32,
        }),
    );
    let mut alive = vec![true; m];
    for _ in n..m {
        // The heap holds every live candidate, and more than `n ≥ 1` are alive here, so
        // it is not empty (invariant); stopping early would only return extra points.
        let Some(Candidate { sample: s, .. }) = heap.pop() else {
            break;
        };
        let s = s as usize;
        alive[s] = false;
        for &t in near(s) {
            if alive[t as usize] {
                weights[t as usize] -= weight(points[s], points[t as usize]);
                heap.set(Candidate {
                    weight: weights[t as usize],
                    sample: t,
                });
            }
        }
    }
    let mut keep: Vec<usize> = (0..m)
        .filter(|&s| alive[s])
        .map(|s| grid.slots[s] as usize)
        .collect();
    keep.sort_unstable();
    keep
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The elimination order: the heaviest candidate first, equal weights by the higher
    /// sample index, and a lowered weight moves a candidate back.
    #[test]
    fn candidates_leave_heaviest_first_ties_to_the_higher_index() {
        let weights = [1.0, 3.0, 2.0, 3.0, 0.5, 2.0];
        let mut heap = IndexedHeap::from_items(
            weights.len(),
            weights.iter().enumerate().map(|(s, &weight)| Candidate {
                weight,
                sample: s as u32,
            }),
        );
        let first = heap.pop().map(|c| c.sample);
        assert_eq!(first, Some(3));
        heap.set(Candidate {
            weight: 0.25,
            sample: 1,
        });
        let order: Vec<u32> = std::iter::from_fn(|| heap.pop().map(|c| c.sample)).collect();
        assert_eq!(order, [5, 2, 0, 4, 1]);
    }
}
