//! Scalar-to-colour ramps for per-vertex colours (distance plots).
//!
//! The ramp runs blue → cyan → green → yellow → red in four linear segments, so small
//! values are blue and large ones red. Pair it with [`super::write_ply`] to look at a
//! distance field in any mesh viewer (`MeshLab`, Blender, `ParaView`).

/// The colour for `t` in `[0, 1]` on the blue → red ramp (values outside are clamped; NaN
/// gives mid grey `[128, 128, 128]`).
///
/// # Examples
///
/// ```
/// use sphaera_io::colormap::blue_to_red;
///
/// assert_eq!(blue_to_red(0.0), [0, 0, 255]);
/// assert_eq!(blue_to_red(0.5), [0, 255, 0]);
/// assert_eq!(blue_to_red(1.0), [255, 0, 0]);
/// assert_eq!(blue_to_red(7.0), [255, 0, 0]);
/// assert_eq!(blue_to_red(f64::NAN), [128, 128, 128]);
/// ```
///
/// # Panics
///
/// Never.
pub fn blue_to_red(t: f64) -> [u8; 3] {
    if t.is_nan() {
        return [128, 128, 128];
    }
    let t = t.clamp(0.0, 1.0) * 4.0;
    // Position inside the segment, scaled to 0..=255 (the cast saturates, and the value is
    // already within range).
    let ramp = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    match t {
        t if t < 1.0 => [0, ramp(t), 255],
        t if t < 2.0 => [0, 255, ramp(2.0 - t)],
        t if t < 3.0 => [ramp(t - 2.0), 255, 0],
        t => [255, ramp(4.0 - t), 0],
    }
}

/// One colour per value: `values` mapped linearly from `range` (or, when `None`, from the
/// minimum and maximum of the finite values) onto [`blue_to_red`]. Non-finite values are
/// grey; when the range is empty (all values equal) every finite value is blue.
///
/// # Examples
///
/// ```
/// use sphaera_io::colormap::scalars_to_colors;
///
/// let colors = scalars_to_colors(&[0.0, 1.0, 2.0, f64::NAN], None);
/// assert_eq!(colors, vec![[0, 0, 255], [0, 255, 0], [255, 0, 0], [128, 128, 128]]);
/// // A fixed range makes several plots comparable; values beyond it are clamped.
/// assert_eq!(scalars_to_colors(&[5.0], Some((0.0, 1.0))), vec![[255, 0, 0]]);
/// ```
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Two passes over `values`, no allocation besides the result.
pub fn scalars_to_colors(values: &[f64], range: Option<(f64, f64)>) -> Vec<[u8; 3]> {
    let (low, high) = range.unwrap_or_else(|| {
        values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    });
    let span = high - low;
    values
        .iter()
        .map(|&v| {
            if !v.is_finite() {
                [128, 128, 128]
            } else if span > 0.0 && span.is_finite() {
                blue_to_red((v - low) / span)
            } else {
                blue_to_red(0.0)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The ramp is continuous: nearby inputs give nearby colours.
        #[test]
        fn ramp_is_continuous(t in 0.0f64..1.0) {
            let a = blue_to_red(t);
            let b = blue_to_red((t + 1e-4).min(1.0));
            for k in 0..3 {
                prop_assert!((i32::from(a[k]) - i32::from(b[k])).abs() <= 1);
            }
        }
    }
}
