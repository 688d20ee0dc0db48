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

use super::integer;

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
    let fast = robust_filter_orient(a, b, c, d);
    if fast != 0.0 {
        return fast;
    }
    match integer::orient_sign(a, b, c, d) {
        Some(sign) => f64::from(sign),
        None => robust::orient3d(coord(a), coord(b), coord(c), coord(d)),
    }
}

/// The floating-point orientation when its sign is certain (Shewchuk's first-stage error
/// bound), else 0.
#[inline]
fn robust_filter_orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let (u, v, w) = (a - d, b - d, c - d);
    let (vw0, vw1, vw2) = (v.y * w.z, v.z * w.y, v.z * w.x);
    let (wv0, wv1, wv2) = (v.x * w.z, v.x * w.y, v.y * w.x);
    let det = u.x * (vw0 - vw1) + u.y * (vw2 - wv0) + u.z * (wv1 - wv2);
    let permanent = (vw0.abs() + vw1.abs()) * u.x.abs()
        + (vw2.abs() + wv0.abs()) * u.y.abs()
        + (wv1.abs() + wv2.abs()) * u.z.abs();
    // (7 + 56ε)ε, Shewchuk's o3derrboundA.
    let epsilon = f64::EPSILON / 2.0;
    let bound = (7.0 + 56.0 * epsilon) * epsilon * permanent;
    if det > bound || -det > bound {
        det
    } else {
        0.0
    }
}

/// Whether `p` lies strictly inside the circumsphere of the positive tetrahedron
/// `(a, b, c, d)`, with ties broken by the symbolic perturbation of the module docs.
/// `p` must differ from the four corners.
pub(crate) fn in_sphere(corners: [DVec3; 4], p: DVec3) -> bool {
    let [a, b, c, d] = corners;
    let mut det = filtered_insphere(a, b, c, d, p);
    if det == 0.0 {
        det = match integer::insphere_sign(a, b, c, d, p) {
            Some(sign) => f64::from(sign),
            None => robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(p)),
        };
    }
    if det != 0.0 {
        return det > 0.0;
    }
    perturbed_in_sphere([a, b, c, d, p])
}

/// The floating-point in-sphere determinant when its sign is certain (Shewchuk's
/// first-stage error bound, `isperrboundA`), else 0.
#[inline]
fn filtered_insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> f64 {
    let (ae, be, ce, de) = (a - e, b - e, c - e, d - e);
    let (aexbey, bexaey) = (ae.x * be.y, be.x * ae.y);
    let (bexcey, cexbey) = (be.x * ce.y, ce.x * be.y);
    let (cexdey, dexcey) = (ce.x * de.y, de.x * ce.y);
    let (dexaey, aexdey) = (de.x * ae.y, ae.x * de.y);
    let (aexcey, cexaey) = (ae.x * ce.y, ce.x * ae.y);
    let (bexdey, dexbey) = (be.x * de.y, de.x * be.y);
    let ab = aexbey - bexaey;
    let bc = bexcey - cexbey;
    let cd = cexdey - dexcey;
    let da = dexaey - aexdey;
    let ac = aexcey - cexaey;
    let bd = bexdey - dexbey;
    let abc = ae.z * bc - be.z * ac + ce.z * ab;
    let bcd = be.z * cd - ce.z * bd + de.z * bc;
    let cda = ce.z * da + de.z * ac + ae.z * cd;
    let dab = de.z * ab + ae.z * bd + be.z * da;
    let (alift, blift) = (ae.length_squared(), be.length_squared());
    let (clift, dlift) = (ce.length_squared(), de.length_squared());
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    let (aez, bez, cez, dez) = (ae.z.abs(), be.z.abs(), ce.z.abs(), de.z.abs());
    let (aexbey, bexaey) = (aexbey.abs(), bexaey.abs());
    let (bexcey, cexbey) = (bexcey.abs(), cexbey.abs());
    let (cexdey, dexcey) = (cexdey.abs(), dexcey.abs());
    let (dexaey, aexdey) = (dexaey.abs(), aexdey.abs());
    let (aexcey, cexaey) = (aexcey.abs(), cexaey.abs());
    let (bexdey, dexbey) = (bexdey.abs(), dexbey.abs());
    let permanent = ((cexdey + dexcey) * bez + (dexbey + bexdey) * cez + (bexcey + cexbey) * dez)
        * alift
        + ((dexaey + aexdey) * cez + (aexcey + cexaey) * dez + (cexdey + dexcey) * aez) * blift
        + ((aexbey + bexaey) * dez + (bexdey + dexbey) * aez + (dexaey + aexdey) * bez) * clift
        + ((bexcey + cexbey) * aez + (cexaey + aexcey) * bez + (aexbey + bexaey) * cez) * dlift;
    let epsilon = f64::EPSILON / 2.0;
    let bound = (16.0 + 224.0 * epsilon) * epsilon * permanent;
    if det > bound || -det > bound {
        det
    } else {
        0.0
    }
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

    fn sign(v: f64) -> i8 {
        if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(sphaera_tests::cases(3_000)))]

        #[test]
        fn filters_agree_with_robust_when_they_answer(
            raw in proptest::collection::vec(-1.0..1.0_f64, 15),
            near in 0..3_usize,
        ) {
            let mut p: Vec<DVec3> = raw.chunks(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
            // Push some cases close to a tie so the filter has to abstain.
            if near == 1 {
                p[4] = p[0] + (p[1] - p[0]) * 0.5 + DVec3::splat(1e-15);
            } else if near == 2 {
                p[3] = (p[0] + p[1] + p[2]) / 3.0;
            }
            let (a, b, c, d, e) = (p[0], p[1], p[2], p[3], p[4]);
            let fast = robust_filter_orient(a, b, c, d);
            if fast != 0.0 {
                proptest::prop_assert_eq!(sign(fast), sign(robust::orient3d(coord(a), coord(b), coord(c), coord(d))));
            }
            proptest::prop_assert_eq!(sign(orient(a, b, c, d)), sign(robust::orient3d(coord(a), coord(b), coord(c), coord(d))));
            let fast = filtered_insphere(a, b, c, d, e);
            let exact = robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(e));
            if fast != 0.0 {
                proptest::prop_assert_eq!(sign(fast), sign(exact));
            }
        }
    }

    #[test]
    fn lexicographic_order_is_total_on_distinct_points() {
        let a = DVec3::new(0.0, 1.0, 2.0);
        let b = DVec3::new(0.0, 1.0, 3.0);
        assert_eq!(lexicographic(a, b), std::cmp::Ordering::Less);
        assert_eq!(lexicographic(b, a), std::cmp::Ordering::Greater);
    }
}
