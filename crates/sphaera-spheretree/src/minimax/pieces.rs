//! Pieces of the surface: triangles that tile the mesh's triangles, split as finely as a
//! node needs, in space-filling (Morton) order.
//!
//! A sphere containing the three corners of a piece contains the whole piece (a ball is
//! convex), so a node whose sphere contains the corners of every piece of its region
//! covers that part of the surface exactly, not only at samples.

use glam::DVec3;
use sphaera_mesh::TriMesh;

use crate::SphereTreeError;

/// A piece of the surface: a triangle, given by its corners.
pub(crate) type Piece = [DVec3; 3];

/// The most pieces one node's region may be split into (32 bytes × 3 per piece: about
/// 1.6 GB). Checked before the pieces are made.
pub(crate) const MAX_PIECES: usize = 1 << 24;

/// The centroid of a piece.
pub(crate) fn centroid(piece: &Piece) -> DVec3 {
    (piece[0] + piece[1] + piece[2]) / 3.0
}

/// The largest squared distance from `center` to a corner of `piece`: a sphere about
/// `center` contains the piece exactly when its squared radius is at least this.
#[inline]
pub(crate) fn reach_squared(piece: &Piece, center: DVec3) -> f64 {
    piece[0]
        .distance_squared(center)
        .max(piece[1].distance_squared(center))
        .max(piece[2].distance_squared(center))
}

/// The area of a piece.
pub(crate) fn area(piece: &Piece) -> f64 {
    0.5 * (piece[1] - piece[0]).cross(piece[2] - piece[0]).length()
}

/// The mesh's triangles as pieces, in Morton order of their centroids (ties by triangle
/// index, so the order is deterministic).
pub(crate) fn mesh_pieces(mesh: &TriMesh) -> Vec<Piece> {
    let positions = mesh.positions();
    let mut pieces: Vec<Piece> = mesh
        .triangles()
        .iter()
        .map(|t| t.map(|v| positions[v as usize]))
        .collect();
    let bounds = mesh.bounding_box();
    let origin = bounds.min;
    let extent = (bounds.max - bounds.min).max_element();
    let scale = if extent > 0.0 && extent.is_finite() {
        f64::from(MORTON_CELLS - 1) / extent
    } else {
        0.0
    };
    let mut keyed: Vec<(u64, usize)> = pieces
        .iter()
        .enumerate()
        .map(|(i, p)| (morton(centroid(p), origin, scale), i))
        .collect();
    keyed.sort_unstable();
    let sorted = keyed.iter().map(|&(_, i)| pieces[i]).collect();
    pieces.clear();
    sorted
}

/// Cells per axis of the Morton code (21 bits each, 63 bits in all).
const MORTON_CELLS: u32 = 1 << 21;

/// The Morton code of `p` on a grid of [`MORTON_CELLS`] cells per axis from `origin`.
fn morton(p: DVec3, origin: DVec3, scale: f64) -> u64 {
    let cell = |v: f64| {
        let c = (v * scale).clamp(0.0, f64::from(MORTON_CELLS - 1));
        // NaN clamps to NaN; `as` turns it into 0.
        spread(c as u64)
    };
    let q = p - origin;
    cell(q.x) | cell(q.y) << 1 | cell(q.z) << 2
}

/// The low 21 bits of `v`, two zero bits after each.
fn spread(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

/// How many pieces splitting every piece of `pieces` until its longest edge is at most
/// `h` makes (each split halves the longest edge), counting no further than just past
/// `limit`.
pub(crate) fn refined_count(pieces: &[Piece], h: f64, limit: usize) -> usize {
    let mut count = 0_usize;
    let mut stack: Vec<Piece> = Vec::new();
    for piece in pieces {
        stack.push(*piece);
        while let Some(p) = stack.pop() {
            match halves(&p, h) {
                Some([a, b]) => stack.extend([a, b]),
                None => count += 1,
            }
            if count > limit {
                return count;
            }
        }
    }
    count
}

/// Splits `pieces` until every longest edge is at most `h`, keeping each piece's parts
/// where the piece was (so the order stays spatially coherent).
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] when that would make more than [`MAX_PIECES`]
/// pieces (checked before any is made).
pub(crate) fn refine(pieces: &[Piece], h: f64) -> Result<Vec<Piece>, SphereTreeError> {
    let count = refined_count(pieces, h, MAX_PIECES);
    if count > MAX_PIECES {
        return Err(SphereTreeError::InvalidParameter {
            name: "pieces",
            value: count as f64,
            requirement: "at most 2^24 surface pieces per node (a tolerance far below the mesh's size)",
        });
    }
    let mut out = Vec::with_capacity(count);
    let mut stack: Vec<Piece> = Vec::new();
    for piece in pieces {
        stack.push(*piece);
        while let Some(p) = stack.pop() {
            match halves(&p, h) {
                Some([a, b]) => {
                    // The second half is pushed first so that the first comes out first.
                    stack.push(b);
                    stack.push(a);
                }
                None => out.push(p),
            }
        }
    }
    Ok(out)
}

/// The two halves of `piece` split at the midpoint of its longest edge, or `None` when
/// that edge is at most `h` (or not finite).
fn halves(piece: &Piece, h: f64) -> Option<[Piece; 2]> {
    let [a, b, c] = *piece;
    let (ab, bc, ca) = (
        a.distance_squared(b),
        b.distance_squared(c),
        c.distance_squared(a),
    );
    let longest = ab.max(bc).max(ca);
    if !longest.is_finite() || longest <= h * h {
        return None;
    }
    Some(if ab >= bc && ab >= ca {
        let m = 0.5 * (a + b);
        [[a, m, c], [m, b, c]]
    } else if bc >= ca {
        let m = 0.5 * (b + c);
        [[a, b, m], [a, m, c]]
    } else {
        let m = 0.5 * (c + a);
        [[a, b, m], [m, b, c]]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refined_pieces_tile_the_piece_and_meet_the_size() {
        let piece = [
            DVec3::ZERO,
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(0.5, 2.0, 0.0),
        ];
        let h = 0.4;
        let parts = refine(&[piece], h).unwrap_or_default();
        assert_eq!(parts.len(), refined_count(&[piece], h, usize::MAX));
        let total: f64 = parts.iter().map(area).sum();
        assert!((total - area(&piece)).abs() < 1e-12 * area(&piece));
        for p in &parts {
            let longest = p[0]
                .distance(p[1])
                .max(p[1].distance(p[2]))
                .max(p[2].distance(p[0]));
            assert!(longest <= h * (1.0 + 1e-12));
        }
    }

    #[test]
    fn too_many_pieces_are_refused_before_they_are_made() {
        let piece = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!(matches!(
            refine(&[piece], 1e-6),
            Err(SphereTreeError::InvalidParameter { name: "pieces", .. })
        ));
    }

    #[test]
    fn spread_interleaves_bits() {
        assert_eq!(spread(0b1), 0b1);
        assert_eq!(spread(0b11), 0b1001);
        assert_eq!(spread(0x1f_ffff).count_ones(), 21);
    }
}
