//! Certified coverage of the whole surface by the medial spheres.
//!
//! [`certify_coverage`] (the sphere-tree's certificate) does the work. It scans every
//! sphere for every triangle before testing containment, which is most of its cost on a
//! large mesh whose triangles are small beside the spheres. Most triangles lie whole in
//! one sphere, and for such a triangle it does nothing but count one piece; so they are
//! found first here, through a grid of the spheres, and only the others are handed to it.
//! The spheres, the growth and the certificate are the same as when the whole mesh is
//! handed over: a contained triangle leaves no piece to grow for, and the others keep
//! their order. The unit test below checks that equality, so a change of the containment
//! predicate in `cover.rs` shows up here. (The better home of this speed-up is
//! `certify_coverage` itself, for the sphere-tree's sake too.)

use sphaera::{
    medial::Surface,
    mesh::{Aabb, DVec3, Sphere, TriMesh},
    spheretree::{CoverageCertificate, cover::certify_coverage},
};

/// Grid cells along the longest side of the mesh's bounding box.
const GRID_CELLS: f64 = 16.0;

/// Makes `spheres` cover every point of `surface`'s triangles at `resolution`, as
/// [`certify_coverage`] does on the whole mesh. Returns the certificate and, per sphere,
/// its radius growth (0 for most).
pub(super) fn certify_surface(
    surface: &Surface,
    spheres: &mut [Sphere],
    resolution: f64,
) -> (CoverageCertificate, Vec<f64>) {
    let mesh = surface.mesh();
    let grid = SphereGrid::new(mesh.bounding_box(), spheres);
    let positions = mesh.positions();
    let mut rest = Vec::new();
    let mut last = None;
    for triangle in mesh.triangles() {
        let corners = triangle.map(|i| positions.get(i as usize).copied());
        let [Some(a), Some(b), Some(c)] = corners else {
            rest.push(*triangle);
            continue;
        };
        // The predicate `certify_coverage` uses: every corner within the radius.
        let contains = |index: usize| {
            spheres.get(index).is_some_and(|sphere| {
                [a, b, c]
                    .iter()
                    .all(|p| p.distance(sphere.center) <= sphere.radius)
            })
        };
        // Neighbouring triangles usually share the sphere that contained the last one.
        let hit = last.filter(|&s| contains(s)).or_else(|| {
            grid.near(a)
                .iter()
                .map(|&s| s as usize)
                .find(|&s| contains(s))
        });
        match hit {
            Some(s) => last = Some(s),
            None => rest.push(*triangle),
        }
    }
    let contained = mesh.triangle_count() - rest.len();
    if rest.is_empty() || spheres.is_empty() {
        let certificate = CoverageCertificate {
            pieces: if spheres.is_empty() { 0 } else { contained },
            ..CoverageCertificate::default()
        };
        return (certificate, vec![0.0; spheres.len()]);
    }
    let (mut certificate, growth) = match TriMesh::new(positions.to_vec(), rest) {
        Ok(rest) => certify_coverage(&rest, spheres, resolution),
        // Unreachable (the triangles are the mesh's own); certify the whole mesh then.
        Err(_) => return certify_coverage(mesh, spheres, resolution),
    };
    certificate.pieces += contained;
    (certificate, growth)
}

/// Which spheres can contain a point: per cell of a uniform grid over the mesh's bounding
/// box, the spheres meeting the cell, ascending.
struct SphereGrid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    /// Cell `i`'s spheres are `spheres[starts[i]..starts[i + 1]]`.
    starts: Vec<usize>,
    spheres: Vec<u32>,
}

impl SphereGrid {
    fn new(bounds: Aabb, spheres: &[Sphere]) -> Self {
        let extent = bounds.max - bounds.min;
        let cell = (extent.max_element() / GRID_CELLS).max(f64::MIN_POSITIVE);
        let most = GRID_CELLS as usize;
        let dims =
            [extent.x, extent.y, extent.z].map(|e| ((e / cell).ceil() as usize).clamp(1, most));
        let mut grid = Self {
            origin: bounds.min,
            cell,
            dims,
            starts: Vec::new(),
            spheres: Vec::new(),
        };
        let mut per_cell: Vec<Vec<u32>> = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        for (index, sphere) in spheres.iter().enumerate() {
            if !(sphere.radius >= 0.0 && sphere.center.is_finite()) {
                continue;
            }
            let lo = grid.coordinates(sphere.center - DVec3::splat(sphere.radius));
            let hi = grid.coordinates(sphere.center + DVec3::splat(sphere.radius));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let min = grid.origin + DVec3::new(x as f64, y as f64, z as f64) * cell;
                        let nearest = sphere.center.clamp(min, min + DVec3::splat(cell));
                        if nearest.distance(sphere.center) <= sphere.radius
                            && let Some(list) = per_cell.get_mut(grid.index([x, y, z]))
                        {
                            list.push(index as u32);
                        }
                    }
                }
            }
        }
        grid.starts.reserve(per_cell.len() + 1);
        grid.starts.push(0);
        for list in per_cell {
            grid.spheres.extend(list);
            grid.starts.push(grid.spheres.len());
        }
        grid
    }

    /// The cell coordinates of `p`, clamped to the grid.
    fn coordinates(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.origin) / self.cell;
        let clamp = |v: f64, n: usize| {
            if v.is_nan() {
                0
            } else {
                (v.max(0.0) as usize).min(n - 1)
            }
        };
        [
            clamp(q.x, self.dims[0]),
            clamp(q.y, self.dims[1]),
            clamp(q.z, self.dims[2]),
        ]
    }

    fn index(&self, [x, y, z]: [usize; 3]) -> usize {
        (z * self.dims[1] + y) * self.dims[0] + x
    }

    /// The spheres meeting the cell of `p` (every sphere containing `p` is among them).
    fn near(&self, p: DVec3) -> &[u32] {
        let i = self.index(self.coordinates(p));
        match (self.starts.get(i), self.starts.get(i + 1)) {
            (Some(&start), Some(&end)) => self.spheres.get(start..end).unwrap_or_default(),
            _ => &[],
        }
    }
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::{sampling, shapes};

    use super::*;

    /// The pre-filter changes nothing: same spheres, growth and certificate as the whole
    /// mesh handed to `certify_coverage`.
    #[test]
    fn prefiltered_certificate_equals_the_whole_mesh_certificate() {
        let mesh = shapes::torus(1.0, 0.3, 24).expect("a torus");
        let surface = Surface::new(&mesh).expect("a solid");
        // Spheres around random surface points, too small to cover everything.
        let spheres: Vec<Sphere> = sampling::random(&mesh, 60, 3)
            .expect("samples")
            .iter()
            .map(|s| Sphere::new(s.position - 0.1 * s.normal, 0.3))
            .collect();
        let resolution = 1e-3 * mesh.bounding_box_diagonal();
        let mut ours = spheres.clone();
        let mut theirs = spheres;
        let (ours_certificate, ours_growth) = certify_surface(&surface, &mut ours, resolution);
        let (theirs_certificate, theirs_growth) = certify_coverage(&mesh, &mut theirs, resolution);
        assert_eq!(ours_certificate, theirs_certificate);
        assert_eq!(ours_growth, theirs_growth);
        assert_eq!(ours, theirs);
        assert!(ours_certificate.grown_spheres > 0);
    }
}
