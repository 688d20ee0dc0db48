//! Exact predicates in 128-bit integer arithmetic for points on a common binary grid.
//!
//! Grid input (voxel centres, CAD models in exact units, the cube-surface benchmark) is
//! where exact ties are common, and an exact zero is the slowest answer for an adaptive
//! floating-point predicate: it has to run every stage. When all coordinates of a
//! predicate's points are integer multiples of one power of two and, scaled to integers,
//! below `2^BITS` in magnitude, the determinant fits in an `i128` and is computed exactly
//! in a few dozen multiplications instead.

use glam::DVec3;

/// Scaled coordinates must be below `2^BITS` in magnitude. With differences below
/// `2^(BITS+1)`, the in-sphere determinant's terms are below `3·2^(5·BITS+5)`, and their
/// sum (24 terms) below `2^(5·BITS+12) ≤ 2^122`.
const BITS: i32 = 22;

/// The points as integers on their common binary grid, if there is one within range.
fn to_grid<const N: usize>(points: [DVec3; N]) -> Option<[[i64; 3]; N]> {
    // The finest binary grid step needed: 2^-shift.
    let mut shift: i32 = i32::MIN;
    let mut top: i32 = i32::MIN;
    for p in points {
        for v in p.to_array() {
            if v == 0.0 {
                continue;
            }
            let bits = v.to_bits();
            let biased = ((bits >> 52) & 0x7ff) as i32;
            if biased == 0 {
                return None; // subnormal
            }
            let mantissa = (bits & ((1 << 52) - 1)) | (1 << 52);
            let trailing = mantissa.trailing_zeros() as i32;
            // v = odd × 2^exponent, odd < 2^(53 − trailing).
            let exponent = biased - 1075 + trailing;
            shift = shift.max(-exponent);
            top = top.max(biased - 1023 + 1); // |v| < 2^top
            if top.saturating_add(shift) > BITS {
                return None;
            }
        }
    }
    if shift == i32::MIN {
        return Some([[0; 3]; N]); // all zero
    }
    // Scaled magnitudes are below 2^(top + shift).
    if top.saturating_add(shift) > BITS || !(-1000..=1000).contains(&shift) {
        return None;
    }
    let scale = 2f64.powi(shift);
    Some(points.map(|p| p.to_array().map(|v| (v * scale) as i64)))
}

fn sub(a: [i64; 3], b: [i64; 3]) -> [i128; 3] {
    [
        i128::from(a[0] - b[0]),
        i128::from(a[1] - b[1]),
        i128::from(a[2] - b[2]),
    ]
}

/// The sign of `robust::orient3d(a, b, c, d)`, exactly, or `None` off a small binary grid.
pub(crate) fn orient_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Option<i8> {
    let [a, b, c, d] = to_grid([a, b, c, d])?;
    let (u, v, w) = (sub(a, d), sub(b, d), sub(c, d));
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    Some(det.signum() as i8)
}

/// The sign of `robust::insphere(a, b, c, d, e)`, exactly, or `None` off a small binary
/// grid.
pub(crate) fn insphere_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Option<i8> {
    let [a, b, c, d, e] = to_grid([a, b, c, d, e])?;
    let rows = [sub(a, e), sub(b, e), sub(c, e), sub(d, e)];
    let lift = |r: [i128; 3]| r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let [r0, r1, r2, r3] = rows;
    // 2×2 minors of the first two columns, then the Laplace expansion along them.
    let m = |p: [i128; 3], q: [i128; 3]| p[0] * q[1] - p[1] * q[0];
    let n = |p: [i128; 3], q: [i128; 3]| p[2] * lift(q) - lift(p) * q[2];
    let det = m(r0, r1) * n(r2, r3) - m(r0, r2) * n(r1, r3)
        + m(r0, r3) * n(r1, r2)
        + m(r1, r2) * n(r0, r3)
        - m(r1, r3) * n(r0, r2)
        + m(r2, r3) * n(r0, r1);
    Some(det.signum() as i8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn coord(p: DVec3) -> robust::Coord3D<f64> {
        robust::Coord3D {
            x: p.x,
            y: p.y,
            z: p.z,
        }
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

    fn point() -> impl Strategy<Value = DVec3> {
        (-6_i32..6, -6_i32..6, -6_i32..6, 0..3_i32).prop_map(|(x, y, z, s)| {
            DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * 0.5f64.powi(s)
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(2_000)))]

        #[test]
        fn integer_predicates_agree_with_robust(
            a in point(), b in point(), c in point(), d in point(), e in point(),
            scale in -3_i32..3,
        ) {
            let s = 2f64.powi(scale * 7);
            let [a, b, c, d, e] = [a, b, c, d, e].map(|p| p * s);
            prop_assert_eq!(
                orient_sign(a, b, c, d),
                Some(sign(robust::orient3d(coord(a), coord(b), coord(c), coord(d))))
            );
            prop_assert_eq!(
                insphere_sign(a, b, c, d, e),
                Some(sign(robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(e))))
            );
        }
    }

    #[test]
    fn off_grid_points_are_left_to_robust() {
        let p = DVec3::new(0.1, 0.2, 0.3);
        assert_eq!(orient_sign(p, p, p, p), None);
        let big = DVec3::splat(f64::from((1 << 23) + 1));
        assert_eq!(orient_sign(big, big, big, big), None);
        let tiny = DVec3::splat(1e-310);
        assert_eq!(orient_sign(tiny, tiny, tiny, tiny), None);
    }
}
