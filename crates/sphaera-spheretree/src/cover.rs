//! Certified coverage of the surface itself, not only of the samples.
//!
//! Covering every surface sample leaves gaps between samples (measured on the low-res
//! bunny's level 3, for the original toolkit and for a plain reduction alike; the
//! toolkit's share of bare surface is in the section *Sphere-trees
//! (`sphaera-spheretree`)* of `docs/benchmarks.md` in the repository).
//! [`certify_coverage`] closes them: every triangle is split (into four, at its edge
//! midpoints) until each piece lies inside a single sphere. A ball is convex, so a sphere
//! containing a piece's three corners contains the whole piece. A piece that is still not
//! contained once its longest edge is below the resolution is handed to the sphere that
//! needs the least growth to contain its corners, which grows by exactly that. Afterwards
//! every point of every triangle is inside some sphere, up to floating-point rounding of
//! the containment predicate.
//!
//! The work is done in two passes: the pieces needing growth are found for every
//! triangle against the spheres as they were (in parallel with the `parallel` feature),
//! then grown in triangle order, skipping a piece that an earlier growth already
//! covers. The result is deterministic and the same with and without `parallel`.

use glam::DVec3;
use sphaera_mesh::{Sphere, TriMesh};
use sphaera_query::grid::UniformGrid;

/// What [`certify_coverage`] did to one set of spheres.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct CoverageCertificate {
    /// Triangle pieces found inside a single sphere (the certificate's size).
    pub pieces: usize,
    /// Spheres grown to contain a piece no sphere contained.
    pub grown_spheres: usize,
    /// The largest radius growth.
    pub largest_growth: f64,
}

/// A triangle piece.
type Piece = [DVec3; 3];

/// Certifies every level of `tree` ([`certify_coverage`] per level, at `resolution`),
/// raising each grown node's error bound by its growth, and records the certificates
/// in the tree. A level is certified as the cut at its depth
/// ([`SphereTree::cut_at`](crate::SphereTree::cut_at)): its nodes and the leaves above it,
/// which together stand for the whole surface in a tree whose leaves are not all at the
/// deepest level (a tree built to a tolerance); in a tree built to a depth, the level
/// itself.
pub(crate) fn certify_tree(
    surface: &sphaera_query::Surface,
    tree: &mut crate::SphereTree,
    resolution: f64,
) {
    let mut certificates = Vec::with_capacity(tree.level_count());
    for level in 0..tree.level_count() {
        let cut = tree.cut_at(level);
        let mut spheres: Vec<Sphere> = cut.iter().map(|&i| tree.nodes[i].sphere).collect();
        let (certificate, growth) = certify_coverage(surface.mesh(), &mut spheres, resolution);
        for ((&index, sphere), g) in cut.iter().zip(spheres).zip(growth) {
            if g > 0.0 {
                // Eq. 2 is the radius plus a term of the centre alone, and the centre
                // did not move: the bound grows by exactly the growth.
                let node = &mut tree.nodes[index];
                node.error += g;
                node.sphere = sphere;
            }
        }
        certificates.push(certificate);
    }
    tree.coverage = certificates;
}

/// The certificates of a tree whose nodes cover their regions by construction (the
/// minimax method: every node's sphere contains the corners of the triangle pieces
/// tiling its region): per cut, its pieces, and nothing grown.
pub(crate) fn by_construction(tree: &crate::SphereTree) -> Vec<CoverageCertificate> {
    (0..tree.level_count())
        .map(|level| CoverageCertificate {
            pieces: tree
                .cut_at(level)
                .iter()
                .map(|&i| tree.nodes[i].region_samples as usize)
                .sum(),
            grown_spheres: 0,
            largest_growth: 0.0,
        })
        .collect()
}

/// Makes `spheres` cover every point of `mesh`'s triangles: splits each triangle until
/// every piece lies in one sphere, growing the sphere needing the least growth for a
/// piece whose longest edge is at most `resolution` and that no sphere contains. Returns
/// the certificate and, per sphere, its radius growth (0 for most).
///
/// Nothing is done (an empty certificate) when `spheres` is empty.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, Sphere, shapes};
/// use sphaera_spheretree::cover::certify_coverage;
///
/// let cube = shapes::cube(2.0, 1)?;
/// // Two spheres that almost cover the cube: the corners poke out.
/// let mut spheres = vec![
///     Sphere::new(DVec3::new(-0.25, 0.0, 0.0), 0.8),
///     Sphere::new(DVec3::new(0.25, 0.0, 0.0), 0.8),
/// ];
/// let (certificate, growth) = certify_coverage(&cube, &mut spheres, 0.01);
/// assert!(certificate.grown_spheres > 0 && growth.iter().any(|&g| g > 0.0));
/// // Now every corner of the cube is inside a sphere.
/// for &corner in cube.positions() {
///     assert!(spheres.iter().any(|s| s.center.distance(corner) <= s.radius));
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Per triangle, a scan of the spheres near it, then one containment test per piece
/// against them; pieces shrink geometrically, so a triangle needs about
/// `(its size / resolution)` pieces along a sphere boundary it crosses, and one when a
/// sphere contains it.
pub fn certify_coverage(
    mesh: &TriMesh,
    spheres: &mut [Sphere],
    resolution: f64,
) -> (CoverageCertificate, Vec<f64>) {
    let mut growth = vec![0.0; spheres.len()];
    if spheres.is_empty() {
        return (CoverageCertificate::default(), growth);
    }
    let resolution = resolution.max(0.0);
    let positions = mesh.positions();
    let corners = |t: &[u32; 3]| t.map(|i| positions[i as usize]);
    let triangles: Vec<Piece> = mesh.triangles().iter().map(corners).collect();
    let frozen: &[Sphere] = spheres;
    let grid = SphereGrid::new(mesh.bounding_box(), frozen);
    let one = |triangle: &Piece| uncovered_pieces(triangle, frozen, &grid, resolution);
    #[cfg(feature = "parallel")]
    let found: Vec<(usize, Vec<Piece>)> = {
        use rayon::prelude::*;
        triangles.par_iter().map(one).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let found: Vec<(usize, Vec<Piece>)> = triangles.iter().map(one).collect();
    let mut certificate = CoverageCertificate {
        pieces: found.iter().map(|(n, _)| n).sum(),
        ..CoverageCertificate::default()
    };
    for piece in found.iter().flat_map(|(_, pieces)| pieces) {
        certificate.pieces += 1;
        if spheres.iter().any(|s| contains_piece(s, piece)) {
            continue;
        }
        let (index, radius) = least_growth(spheres, piece);
        if let (Some(sphere), Some(g)) = (spheres.get_mut(index), growth.get_mut(index)) {
            *g += radius - sphere.radius;
            certificate.largest_growth = certificate.largest_growth.max(*g);
            sphere.radius = radius;
        }
    }
    certificate.grown_spheres = growth.iter().filter(|&&g| g > 0.0).count();
    (certificate, growth)
}

/// Whether `sphere` contains every corner of `piece` (so, being convex, the piece).
fn contains_piece(sphere: &Sphere, piece: &Piece) -> bool {
    piece
        .iter()
        .all(|p| p.distance(sphere.center) <= sphere.radius)
}

/// The sphere needing the least growth to contain `piece`, and the radius it needs
/// (`spheres` is not empty; ties: the lowest index).
fn least_growth(spheres: &[Sphere], piece: &Piece) -> (usize, f64) {
    let mut best = (0, f64::INFINITY, f64::INFINITY);
    for (i, s) in spheres.iter().enumerate() {
        let needed = piece
            .iter()
            .map(|p| p.distance(s.center))
            .fold(s.radius, f64::max);
        let extra = needed - s.radius;
        if extra < best.1 {
            best = (i, extra, needed);
        }
    }
    (best.0, best.2)
}

/// Splits `triangle` against `spheres`: the number of pieces found inside a sphere, and
/// the pieces no sphere contains whose longest edge is at most `resolution`.
fn uncovered_pieces(
    triangle: &Piece,
    spheres: &[Sphere],
    grid: &SphereGrid,
    resolution: f64,
) -> (usize, Vec<Piece>) {
    // Most triangles lie whole in a sphere, which is among those of a corner's cell.
    let whole = grid
        .at(triangle[0])
        .iter()
        .filter_map(|&i| spheres.get(i as usize))
        .any(|s| contains_piece(s, triangle));
    if whole {
        return (1, Vec::new());
    }
    // The spheres that can contain part of the triangle: those meeting its bounding box
    // (found through the grid, in ascending order).
    let lo = triangle[0].min(triangle[1]).min(triangle[2]);
    let hi = triangle[0].max(triangle[1]).max(triangle[2]);
    let near: Vec<&Sphere> = grid
        .meeting(lo, hi)
        .into_iter()
        .filter_map(|i| spheres.get(i as usize))
        .filter(|s| s.center.clamp(lo, hi).distance(s.center) <= s.radius)
        .collect();
    let mut covered = 0;
    let mut left = Vec::new();
    let mut stack = vec![*triangle];
    // The sphere that contained the last piece: neighbouring pieces usually share it.
    let mut last = 0;
    while let Some(piece) = stack.pop() {
        let hit = near
            .get(last)
            .filter(|s| contains_piece(s, &piece))
            .map(|_| last)
            .or_else(|| near.iter().position(|s| contains_piece(s, &piece)));
        if let Some(i) = hit {
            last = i;
            covered += 1;
            continue;
        }
        let [a, b, c] = piece;
        let longest = a
            .distance_squared(b)
            .max(b.distance_squared(c))
            .max(c.distance_squared(a))
            .sqrt();
        if longest <= resolution || !longest.is_finite() {
            left.push(piece);
            continue;
        }
        let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
        stack.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    (covered, left)
}

/// Cells along the longest side of the grid.
const GRID_CELLS: f64 = 16.0;

/// Which spheres can meet a box: per cell of a uniform grid over the mesh's bounding box
/// (`sphaera-query`'s), the spheres meeting the cell (points outside the box fall in the
/// nearest cell).
struct SphereGrid(UniformGrid);

impl SphereGrid {
    fn new(bounds: sphaera_mesh::Aabb, spheres: &[Sphere]) -> Self {
        let extent = bounds.max - bounds.min;
        let cell = (extent.max_element() / GRID_CELLS).max(f64::MIN_POSITIVE);
        let most = GRID_CELLS as usize;
        let dims =
            [extent.x, extent.y, extent.z].map(|e| ((e / cell).ceil() as usize).clamp(1, most));
        let boxes = || {
            spheres.iter().map(|s| {
                let reach = DVec3::splat(s.radius);
                Some((s.center - reach, s.center + reach))
            })
        };
        // A mesh without a finite box (no triangles), or more listings than 32-bit indices
        // address (a million spheres each in thousands of cells), fall back to one cell,
        // which lists each sphere once.
        UniformGrid::new(bounds.min, cell, dims, boxes())
            .or_else(|_| UniformGrid::new(DVec3::ZERO, 1.0, [1, 1, 1], boxes()))
            .map(Self)
            // Invariant: one cell of edge 1 lists each sphere once, and sphere indices are
            // u32 throughout the tree.
            .expect("a one-cell grid of the spheres")
    }

    /// The spheres listed in the cell of `p`: every sphere containing `p` is among them.
    fn at(&self, p: DVec3) -> &[u32] {
        self.0.items_at(p)
    }

    /// The spheres listed in the cells the box `[lo, hi]` meets, ascending and once each:
    /// every sphere meeting the box is among them.
    fn meeting(&self, lo: DVec3, hi: DVec3) -> Vec<u32> {
        let mut out = Vec::new();
        self.0.items_meeting(lo, hi, &mut out);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_triangle() -> TriMesh {
        TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap_or_default()
    }

    /// The grid lists every sphere meeting a box (against a scan of all spheres), for
    /// boxes inside and outside the grid.
    #[test]
    fn the_grid_lists_every_sphere_meeting_a_box() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut unit = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut point = || DVec3::new(unit(), unit(), unit()) * 3.0 - DVec3::splat(1.0);
        let bounds = sphaera_mesh::Aabb::new(DVec3::ZERO, DVec3::new(1.0, 0.5, 0.25));
        let spheres: Vec<Sphere> = (0..200)
            .map(|i| Sphere::new(point(), 0.002 + 0.4 * f64::from(i % 7) / 7.0))
            .collect();
        let grid = SphereGrid::new(bounds, &spheres);
        for _ in 0..500 {
            let (a, b) = (point(), point());
            let (lo, hi) = (a.min(b) * 0.3, a.min(b) * 0.3 + (b - a).abs() * 0.1);
            let listed = grid.meeting(lo, hi);
            for (i, s) in spheres.iter().enumerate() {
                if s.center.clamp(lo, hi).distance(s.center) <= s.radius {
                    assert!(listed.binary_search(&(i as u32)).is_ok(), "sphere {i}");
                }
            }
            let p = lo;
            for (i, s) in spheres.iter().enumerate() {
                if s.center.distance(p) <= s.radius {
                    assert!(grid.at(p).contains(&(i as u32)), "sphere {i} at {p}");
                }
            }
        }
    }

    #[test]
    fn a_containing_sphere_needs_one_piece() {
        let mut spheres = [Sphere::new(DVec3::splat(0.3), 1.0)];
        let (c, growth) = certify_coverage(&one_triangle(), &mut spheres, 1e-3);
        assert_eq!((c.pieces, c.grown_spheres), (1, 0));
        assert_eq!(growth, vec![0.0]);
    }

    #[test]
    fn two_overlapping_spheres_cover_without_growth() {
        // Each corner region is inside one sphere and they overlap widely in between.
        let mut spheres = [
            Sphere::new(DVec3::new(0.0, 0.0, 0.0), 0.8),
            Sphere::new(DVec3::new(0.6, 0.6, 0.0), 0.75),
        ];
        let (c, _) = certify_coverage(&one_triangle(), &mut spheres, 1e-3);
        assert_eq!(c.grown_spheres, 0);
        assert!(c.pieces > 1);
    }

    #[test]
    fn a_gap_is_closed_by_the_least_growth() {
        // Two spheres missing the middle of the long edge.
        let mesh = TriMesh::new(
            vec![
                DVec3::ZERO,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(1.0, 0.1, 0.0),
            ],
            vec![[0, 1, 2]],
        )
        .unwrap_or_default();
        let mut spheres = [
            Sphere::new(DVec3::ZERO, 0.9),
            Sphere::new(DVec3::new(2.0, 0.0, 0.0), 0.95),
        ];
        let (c, growth) = certify_coverage(&mesh, &mut spheres, 1e-3);
        assert!(c.grown_spheres >= 1);
        assert!(c.largest_growth > 0.0 && c.largest_growth < 0.2, "{c:?}");
        assert!(growth.iter().all(|&g| g >= 0.0));
        // Dense points of the triangle are now covered.
        for i in 0..=200 {
            let t = f64::from(i) / 200.0;
            let p = DVec3::new(2.0 * t, 0.0, 0.0);
            assert!(
                spheres.iter().any(|s| s.center.distance(p) <= s.radius),
                "{p}"
            );
        }
    }
}
