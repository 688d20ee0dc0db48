//! Exact orientation and in-sphere predicates, with the symbolic perturbation that breaks
//! every in-sphere tie.
//!
//! Orientation and in-sphere signs come from Shewchuk's adaptive-precision predicates (the
//! `robust` crate): their *signs* are exact for any `f64` input. A tetrahedron
//! `(a, b, c, d)` is *positive* when `orient(a, b, c, d) > 0`.
//!
//! # The perturbation
//!
//! Ties (five cospherical points) are broken as if every point's lifted coordinate
//! `w = x² + y² + z²` were raised by `ε^k`, with `k` the point's rank in decreasing
//! lexicographic order of `(x, y, z)` (the largest point gets the largest raise) and `ε`
//! infinitesimal. The in-sphere determinant is linear in the lifted column, so the
//! perturbed determinant is `D + Σ ε^k C_k`, where `C_k` is the cofactor of point `k`'s
//! lifted entry: a signed orientation of the other four points. Its sign is the sign of
//! `D` if `D ≠ 0`, else of the first non-zero cofactor in rank order. The query point's
//! own cofactor is `−orient(a, b, c, d) ≠ 0`, so the scan always ends.
//!
//! The ranks depend on the points only (not on insertion order or on which tetrahedron
//! asks), so the perturbed point set is one fixed, generic set: its Delaunay
//! tetrahedralization is unique, and every incremental step agrees with every other.
//! Restricted to four coplanar points the same rule is the perturbed in-circle test of
//! their plane, which is what makes hull facets with cocircular points consistent.

use glam::DVec3;
use robust::Coord3D;

fn coord(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// The orientation of `(a, b, c, d)`: positive, negative or zero, exactly (the sign is
/// exact; the magnitude is six times the signed volume, approximately).
#[inline]
pub(crate) fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(coord(a), coord(b), coord(c), coord(d))
}

/// Whether `p` lies strictly inside the circumsphere of the positive tetrahedron
/// `(a, b, c, d)`, with ties broken by the symbolic perturbation of the module docs.
/// `p` must differ from the four corners.
pub(crate) fn in_sphere(corners: [DVec3; 4], p: DVec3) -> bool {
    let [a, b, c, d] = corners;
    let det = robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(p));
    if det != 0.0 {
        return det > 0.0;
    }
    perturbed_in_sphere([a, b, c, d, p])
}

/// The sign of the perturbed in-sphere determinant when the exact one is zero.
#[cold]
fn perturbed_in_sphere(rows: [DVec3; 5]) -> bool {
    let mut order = [0_usize, 1, 2, 3, 4];
    order.sort_unstable_by(|&i, &j| lexicographic(rows[j], rows[i]));
    for k in order {
        let mut others = [DVec3::ZERO; 4];
        let mut n = 0;
        for (i, &row) in rows.iter().enumerate() {
            if i != k {
                others[n] = row;
                n += 1;
            }
        }
        let minor = orient(others[0], others[1], others[2], others[3]);
        if minor != 0.0 {
            // Cofactor sign of entry (k, 3) in a 5×5 determinant: (−1)^(k+3).
            let cofactor = if k % 2 == 1 { minor } else { -minor };
            return cofactor > 0.0;
        }
    }
    // Unreachable for a positive tetrahedron: the query's cofactor is −orient(a,b,c,d).
    false
}

/// Lexicographic order of `(x, y, z)`.
pub(crate) fn lexicographic(a: DVec3, b: DVec3) -> std::cmp::Ordering {
    a.x.total_cmp(&b.x)
        .then(a.y.total_cmp(&b.y))
        .then(a.z.total_cmp(&b.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn positive(mut t: [DVec3; 4]) -> [DVec3; 4] {
        if orient(t[0], t[1], t[2], t[3]) < 0.0 {
            t.swap(0, 1);
        }
        t
    }

    #[test]
    fn in_sphere_agrees_with_the_circumsphere_off_ties() {
        let t = positive([
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ]);
        assert!(in_sphere(t, DVec3::new(0.1, 0.1, 0.1)));
        assert!(!in_sphere(t, DVec3::new(2.0, 0.0, 0.0)));
    }

    #[test]
    fn ties_are_broken_the_same_way_for_every_tetrahedron_of_five_cospherical_points() {
        // Five points on the unit sphere: the perturbed Delaunay tetrahedralization of
        // five points in convex position has two or three tetrahedra, and each either
        // contains the fifth point in its (perturbed) circumsphere or not, consistently:
        // exactly the tetrahedra of one of the two triangulations are empty.
        let p = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let mut empty = 0;
        for skip in 0..5 {
            let mut t = [DVec3::ZERO; 4];
            let mut n = 0;
            for (i, &q) in p.iter().enumerate() {
                if i != skip {
                    t[n] = q;
                    n += 1;
                }
            }
            if orient(t[0], t[1], t[2], t[3]) == 0.0 {
                continue;
            }
            if !in_sphere(positive(t), p[skip]) {
                empty += 1;
            }
        }
        // The square base (±x, ±y) is coplanar, so only four of the five 4-subsets are
        // tetrahedra; the perturbation picks one diagonal: two empty tetrahedra.
        assert_eq!(empty, 2);
    }

    #[test]
    fn lexicographic_order_is_total_on_distinct_points() {
        let a = DVec3::new(0.0, 1.0, 2.0);
        let b = DVec3::new(0.0, 1.0, 3.0);
        assert_eq!(lexicographic(a, b), std::cmp::Ordering::Less);
        assert_eq!(lexicographic(b, a), std::cmp::Ordering::Greater);
    }
}
