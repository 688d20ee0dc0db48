//! The volume-sampling baseline of the `robot_protrusion_vs_spheres` experiment and the
//! `robot_spheres` bench: spheres for a robot link of the kind motion planners ship
//! (voxelize the link, cluster the voxels, one enclosing sphere per cluster), written
//! here from that description.
//!
//! 1. **Voxelize** the link's mesh (in its frame) on a grid of cubes whose longest side
//!    of the bounding box is [`VoxelOptions::resolution`] cells: a voxel is occupied when
//!    its centre is inside the mesh (`Surface::is_inside`, the generalized winding
//!    number, so open meshes such as the Panda's `link6` work) or when the surface passes
//!    through it. The surface is found by sampling every triangle on a barycentric
//!    lattice finer than half a cell (the "subdivide until the edges are shorter than
//!    the pitch" voxelization of mesh libraries), so every triangle marks the voxels its
//!    lattice points fall in.
//! 2. **Cluster** the occupied voxel centres into `N` clusters by k-means: seeds by
//!    farthest-point sampling from a fixed start (the first occupied voxel in grid
//!    order), then [`VoxelOptions::lloyd_iterations`] Lloyd iterations (ties to the lower
//!    index; an emptied cluster keeps its centre and yields no sphere). Deterministic.
//! 3. **Enclose** each cluster by the smallest sphere around the corners of its voxel
//!    cubes (`minimum_enclosing_ball`), so the sphere holds every voxel of the cluster.
//!
//! The spheres cover every occupied voxel, hence every part of the surface inside an
//! occupied voxel; a thin part whose lattice points all miss a voxel it crosses can be
//! left out. Coverage is therefore **not certified**: the experiment measures it on dense
//! surface samples, and measures the protrusion with the same certified evaluator as
//! Sphaera's spheres.
//!
//! # Examples
//!
//! ```
//! use sphaera::mesh::{Surface, shapes};
//! use sphaera_eval::experiments::voxel::{VoxelOptions, Voxels};
//!
//! let mesh = shapes::cube(2.0, 2)?;
//! let surface = Surface::new(&mesh)?;
//! let voxels = Voxels::new(&surface, &VoxelOptions::default().with_resolution(16))?;
//! assert_eq!(voxels.occupied(), 16 * 16 * 16);
//! let spheres = voxels.spheres(8, 10)?;
//! assert_eq!(spheres.len(), 8);
//! // Every corner of the cube is inside a sphere.
//! let corner = sphaera::mesh::DVec3::splat(1.0);
//! assert!(spheres.iter().any(|s| s.center.distance(corner) <= s.radius + 1e-9));
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::collections::BTreeSet;

use anyhow::{Context, Result, bail};
use sphaera::mesh::geometry::minimum_enclosing_ball;
use sphaera::mesh::{DVec3, Sphere, Surface};
use sphaera::robot::LinkGeometry;

/// How the baseline voxelizes and clusters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelOptions {
    /// Cells along the longest side of the link's bounding box (default 64; planners'
    /// tools use 32 to 64).
    pub resolution: usize,
    /// Lloyd iterations of the k-means (default 20).
    pub lloyd_iterations: usize,
}

impl Default for VoxelOptions {
    fn default() -> Self {
        Self {
            resolution: 64,
            lloyd_iterations: 20,
        }
    }
}

impl VoxelOptions {
    /// With `resolution` cells along the longest side.
    #[must_use]
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }
}

/// The occupied voxels of one link.
#[derive(Clone, Debug)]
pub struct Voxels {
    /// The grid's lowest corner.
    origin: DVec3,
    /// The side of a voxel.
    cell: f64,
    /// The grid indices of the occupied voxels, in grid order (x fastest).
    cells: Vec<[u32; 3]>,
}

impl Voxels {
    /// Voxelizes the mesh of `surface` (see the module documentation).
    ///
    /// # Errors
    ///
    /// A zero resolution, a mesh with an empty or non-finite bounding box, or a grid too
    /// large to index.
    pub fn new(surface: &Surface, options: &VoxelOptions) -> Result<Self> {
        if options.resolution == 0 {
            bail!("the voxel resolution must be at least 1");
        }
        let mesh = surface.mesh();
        let bounds = mesh.bounding_box();
        let extent = bounds.max - bounds.min;
        let longest = extent.max_element();
        if !(longest > 0.0 && longest.is_finite()) {
            bail!("cannot voxelize a mesh whose bounding box is empty or not finite");
        }
        let cell = longest / options.resolution as f64;
        let dims = [extent.x, extent.y, extent.z].map(|e| ((e / cell).ceil() as usize).max(1));
        let total = dims[0]
            .checked_mul(dims[1])
            .and_then(|n| n.checked_mul(dims[2]))
            .filter(|&n| n <= u32::MAX as usize)
            .context("the voxel grid is too large")?;
        let origin = bounds.min;
        let index = |i: usize, j: usize, k: usize| i + dims[0] * (j + dims[1] * k);
        let mut occupied = vec![false; total];
        // Voxels whose centre is inside.
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let center = origin + (DVec3::new(i as f64, j as f64, k as f64) + 0.5) * cell;
                    if surface.is_inside(center) {
                        occupied[index(i, j, k)] = true;
                    }
                }
            }
        }
        // Voxels the surface passes through: a barycentric lattice on every triangle with
        // a spacing below half a cell.
        let cell_of = |p: DVec3| {
            let q = (p - origin) / cell;
            let clamp = |v: f64, d: usize| (v.floor().max(0.0) as usize).min(d - 1);
            (
                clamp(q.x, dims[0]),
                clamp(q.y, dims[1]),
                clamp(q.z, dims[2]),
            )
        };
        for t in mesh.triangle_iter() {
            let longest_edge = (t.b - t.a)
                .length()
                .max((t.c - t.b).length())
                .max((t.a - t.c).length());
            if !longest_edge.is_finite() {
                continue;
            }
            let steps = ((2.0 * longest_edge / cell).ceil() as usize).max(1);
            for a in 0..=steps {
                for b in 0..=(steps - a) {
                    let (u, v) = (a as f64 / steps as f64, b as f64 / steps as f64);
                    let p = t.a + (t.b - t.a) * u + (t.c - t.a) * v;
                    let (i, j, k) = cell_of(p);
                    occupied[index(i, j, k)] = true;
                }
            }
        }
        let mut cells = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    if occupied[index(i, j, k)] {
                        // Each index is below its dimension, whose product fits a u32.
                        cells.push([i as u32, j as u32, k as u32]);
                    }
                }
            }
        }
        if cells.is_empty() {
            bail!("no voxel is occupied");
        }
        Ok(Self {
            origin,
            cell,
            cells,
        })
    }

    /// The number of occupied voxels.
    #[must_use]
    pub fn occupied(&self) -> usize {
        self.cells.len()
    }

    /// The side of a voxel.
    #[must_use]
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// The centre of the occupied voxel `cell`.
    fn center(&self, cell: [u32; 3]) -> DVec3 {
        self.origin
            + (DVec3::new(f64::from(cell[0]), f64::from(cell[1]), f64::from(cell[2])) + 0.5)
                * self.cell
    }

    /// The spheres of `count` k-means clusters of the occupied voxels (fewer when fewer
    /// voxels are occupied, or when a cluster empties), each the smallest sphere around
    /// its voxels' corners.
    ///
    /// # Errors
    ///
    /// A zero `count`; the enclosing ball failing (non-finite coordinates).
    pub fn spheres(&self, count: usize, lloyd_iterations: usize) -> Result<Vec<Sphere>> {
        if count == 0 {
            bail!("the baseline needs at least one sphere");
        }
        let points: Vec<DVec3> = self.cells.iter().map(|&c| self.center(c)).collect();
        let k = count.min(points.len());
        // Farthest-point seeding from the first occupied voxel.
        let mut centers = vec![points[0]];
        let mut nearest: Vec<f64> = points
            .iter()
            .map(|p| p.distance_squared(points[0]))
            .collect();
        while centers.len() < k {
            let (far, _) =
                nearest
                    .iter()
                    .enumerate()
                    .fold((0, f64::NEG_INFINITY), |best, (i, &d)| {
                        if d > best.1 { (i, d) } else { best }
                    });
            let seed = points[far];
            centers.push(seed);
            for (d, p) in nearest.iter_mut().zip(&points) {
                *d = d.min(p.distance_squared(seed));
            }
        }
        // Lloyd iterations.
        let mut label = vec![0usize; points.len()];
        for iteration in 0..=lloyd_iterations {
            let mut changed = false;
            for (l, p) in label.iter_mut().zip(&points) {
                let (best, _) =
                    centers
                        .iter()
                        .enumerate()
                        .fold((0, f64::INFINITY), |best, (i, c)| {
                            let d = p.distance_squared(*c);
                            if d < best.1 { (i, d) } else { best }
                        });
                changed |= *l != best;
                *l = best;
            }
            if iteration == lloyd_iterations || (iteration > 0 && !changed) {
                break;
            }
            let mut sums = vec![(DVec3::ZERO, 0usize); k];
            for (&l, p) in label.iter().zip(&points) {
                sums[l].0 += *p;
                sums[l].1 += 1;
            }
            for (c, (sum, n)) in centers.iter_mut().zip(sums) {
                if n > 0 {
                    *c = sum / n as f64;
                }
            }
        }
        // One enclosing sphere per non-empty cluster, around its voxels' corners.
        let mut corners: Vec<BTreeSet<[u32; 3]>> = vec![BTreeSet::new(); k];
        for (&l, &[i, j, m]) in label.iter().zip(&self.cells) {
            for d in 0..8u32 {
                corners[l].insert([i + (d & 1), j + ((d >> 1) & 1), m + ((d >> 2) & 1)]);
            }
        }
        corners
            .iter()
            .filter(|set| !set.is_empty())
            .map(|set| {
                let points: Vec<DVec3> = set
                    .iter()
                    .map(|c| {
                        self.origin
                            + DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]))
                                * self.cell
                    })
                    .collect();
                minimum_enclosing_ball(&points).context("the enclosing sphere of a cluster")
            })
            .collect()
    }
}

/// The baseline on a link's mesh: voxelized with `options`, `count` clusters.
///
/// # Errors
///
/// As [`Voxels::new`] and [`Voxels::spheres`].
pub fn link_spheres(
    surface: &Surface,
    count: usize,
    options: &VoxelOptions,
) -> Result<Vec<Sphere>> {
    Voxels::new(surface, options)?.spheres(count, options.lloyd_iterations)
}

/// The baseline on every link of a robot with a mesh (links with only primitives or
/// nothing are left out: the baseline is for meshes), `count` spheres per link, one link
/// after the other: `(link, spheres)` in link order.
///
/// # Errors
///
/// A link whose mesh cannot be made a [`Surface`]; as [`link_spheres`].
pub fn robot_spheres(
    geometry: &[LinkGeometry],
    count: usize,
    options: &VoxelOptions,
) -> Result<Vec<(String, Vec<Sphere>)>> {
    geometry
        .iter()
        .filter_map(|g| g.mesh.as_ref().map(|mesh| (&g.link, mesh)))
        .map(|(link, mesh)| {
            let surface = Surface::new(mesh).with_context(|| format!("link {link}"))?;
            let spheres =
                link_spheres(&surface, count, options).with_context(|| format!("link {link}"))?;
            Ok((link.clone(), spheres))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera::mesh::shapes;

    #[test]
    fn spheres_cover_every_vertex_and_repeat() -> Result<()> {
        let mesh = shapes::torus(1.0, 0.3, 24)?;
        let surface = Surface::new(&mesh)?;
        let options = VoxelOptions::default().with_resolution(24);
        let voxels = Voxels::new(&surface, &options)?;
        // The hole of the torus stays empty.
        assert!(voxels.occupied() < 24 * 24 * 8);
        let spheres = voxels.spheres(12, options.lloyd_iterations)?;
        assert_eq!(spheres.len(), 12);
        for &p in mesh.positions() {
            assert!(
                spheres
                    .iter()
                    .any(|s| s.center.distance(p) <= s.radius + 1e-9)
            );
        }
        assert_eq!(spheres, link_spheres(&surface, 12, &options)?);
        assert!(voxels.spheres(0, 5).is_err());
        Ok(())
    }
}
