//! The support-set pivoting shared by the minimum enclosing ball of points and of balls.
//!
//! Both problems minimise, over centres `c`, the largest "extent" of the items from `c`
//! (squared distance for a point, reach `|c − cᵢ| + rᵢ` for a ball). The method is the same
//! for both: keep a support set of at most four items and the centre it determines; find the
//! item with the largest extent from the centre; if it sticks out, replace the centre by the
//! best one for the support set plus that item (at most five items), found by trying every
//! subset of at most four of them as the boundary set and scoring each candidate centre by
//! the largest extent of all five. The score grows strictly at every step and only finitely
//! many support sets exist, so the loop ends; no recursion, no randomness.
//!
//! Scoring candidates by the extent of all five items (never by a candidate's own radius)
//! means a nearly degenerate boundary set can never produce a too-small ball: it simply loses
//! to a better candidate. The final radius is derived from the largest extent from the final
//! centre, so every item is inside the returned ball.
//!
//! Squared extents overflow for coordinates beyond about 1e154 and underflow for extents
//! below about 1e-154. Inputs whose bounding box is larger than 1e100 or smaller than 1e-100
//! are therefore translated to their box centre and scaled by a power of two to unit size,
//! solved there, and mapped back (the power-of-two scaling is exact; the final radius is
//! measured against the original items). Other inputs are solved as given, so their results
//! are unchanged bit for bit.

use glam::DVec3;
use smallvec::SmallVec;

use super::EnclosingBall;
use crate::Sphere;

/// Bound on the number of pivot steps; never reached in practice (a few dozen steps are
/// typical even for 100,000 items), it only guards against pathological rounding cycles.
const MAX_PIVOT_STEPS: usize = 100_000;

/// An item to enclose: a point or a ball.
pub(super) trait Item: Copy {
    /// How far the item extends from `center`, in a measure that increases with the radius a
    /// ball centred at `center` needs to contain it (squared distance for a point, reach for a
    /// ball). Non-negative for finite input.
    fn extent_from(&self, center: DVec3) -> f64;

    /// The item's own centre: the centre of the initial one-item support set.
    fn center(&self) -> DVec3;

    /// Centres of the smallest balls with all of `boundary` (1 to 4 items) on their
    /// boundary; empty for a degenerate set. Several candidates may be returned: each is
    /// scored, so a wrong one only costs time.
    fn boundary_centers(boundary: &[Self]) -> SmallVec<[DVec3; 2]>;

    /// The smallest radius that contains an item of extent `extent` from the centre (in
    /// floating point).
    fn radius_for_extent(extent: f64) -> f64;

    /// Half the item's bounding box, `(min / 2, max / 2)`, computed without overflow.
    fn half_bounds(&self) -> (DVec3, DVec3);

    /// The item translated by `-offset` and scaled by `scale` (a power of two).
    fn mapped(&self, offset: DVec3, scale: f64) -> Self;
}

/// Boxes larger than this (or smaller than [`MIN_UNSCALED_EXTENT`]) are solved rescaled.
const MAX_UNSCALED_EXTENT: f64 = 1e100;
/// See [`MAX_UNSCALED_EXTENT`].
const MIN_UNSCALED_EXTENT: f64 = 1e-100;

/// The minimum enclosing ball of `items` with its support, or `None` when `items` is empty.
/// The items must be finite (validated by the caller). The radius is infinite when the ball
/// is too large for `f64` (callers report that as an error).
pub(super) fn solve<T: Item>(items: &[T]) -> Option<EnclosingBall> {
    let Some((offset, scale)) = rescaling(items) else {
        return solve_as_given(items);
    };
    let mapped: Vec<T> = items
        .iter()
        .map(|item| item.mapped(offset, scale))
        .collect();
    let ball = solve_as_given(&mapped)?;
    // Division by a power of two is exact (barring overflow, which gives an infinite radius).
    let center = ball.sphere.center / scale + offset;
    // Measure the radius against the original items from the mapped-back centre, in the
    // scaled frame (exact power-of-two scaling, no overflow), so rounding in the mapping
    // cannot leave an item outside.
    let far_extent = items
        .iter()
        .map(|item| item.mapped(center, scale).extent_from(DVec3::ZERO))
        .fold(0.0, f64::max);
    Some(EnclosingBall {
        sphere: Sphere::new(center, T::radius_for_extent(far_extent) / scale),
        support: ball.support,
    })
}

/// The translation and power-of-two scale bringing `items` to unit size, or `None` when
/// their bounding box is of moderate size (or a single point) and they are solved as given.
fn rescaling<T: Item>(items: &[T]) -> Option<(DVec3, f64)> {
    let (lo, hi) = items.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), item| {
            let (item_lo, item_hi) = item.half_bounds();
            (lo.min(item_lo), hi.max(item_hi))
        },
    );
    // Half the largest side of the box; finite because every half coordinate is at most
    // f64::MAX / 2 in magnitude.
    let half_extent = (hi - lo).max_element();
    let moderate = (0.5 * MIN_UNSCALED_EXTENT..=0.5 * MAX_UNSCALED_EXTENT).contains(&half_extent);
    if !half_extent.is_normal() || moderate {
        return None;
    }
    // The binary exponent of a normal f64, clamped so that 2^-exponent is a normal f64.
    let exponent = i64::try_from((half_extent.to_bits() >> 52) & 0x7ff).unwrap_or(1023) - 1023;
    let biased = u64::try_from(1023 - exponent.min(1022)).unwrap_or(1023);
    Some((lo + hi, f64::from_bits(biased << 52)))
}

/// [`solve`] without rescaling.
pub(super) fn solve_as_given<T: Item>(items: &[T]) -> Option<EnclosingBall> {
    let first = items.first()?;
    let mut support: SmallVec<[usize; 4]> = SmallVec::new();
    support.push(0);
    let mut center = first.center();
    // 0 for a point, its radius for a ball.
    let mut extent = first.extent_from(center);
    for _ in 0..MAX_PIVOT_STEPS {
        let (far, far_extent) = farthest(items, center);
        if far_extent <= extent {
            break;
        }
        let Some((next_support, next_center, next_extent)) = best_with(items, &support, far) else {
            break;
        };
        if next_extent.is_nan() || next_extent <= extent {
            // No progress: rounding noise; the final pass makes the ball contain everything.
            break;
        }
        support = next_support;
        center = next_center;
        extent = next_extent;
    }
    // The radius covers the largest extent from the centre, so every item is inside.
    let (_, far_extent) = farthest(items, center);
    support.sort_unstable();
    Some(EnclosingBall {
        sphere: Sphere::new(center, T::radius_for_extent(far_extent)),
        support,
    })
}

/// The index of the first item extending farthest from `center`, and its extent.
fn farthest<T: Item>(items: &[T], center: DVec3) -> (usize, f64) {
    let mut best = (0, f64::NEG_INFINITY);
    for (index, item) in items.iter().enumerate() {
        let extent = item.extent_from(center);
        if extent > best.1 {
            best = (index, extent);
        }
    }
    best
}

/// The best centre for `support ∪ {extra}` (at most five items), found by scoring the
/// boundary centres of every subset of at most four items by the largest extent of all
/// five. Returns the chosen subset (as input indices), centre and score.
fn best_with<T: Item>(
    items: &[T],
    support: &[usize],
    extra: usize,
) -> Option<(SmallVec<[usize; 4]>, DVec3, f64)> {
    let mut candidates: SmallVec<[usize; 5]> = SmallVec::from_slice(support);
    candidates.push(extra);
    let mut set: SmallVec<[T; 5]> = SmallVec::new();
    for &index in &candidates {
        set.push(*items.get(index)?);
    }
    let mut best: Option<(u32, DVec3, f64)> = None;
    for mask in 1u32..(1 << set.len()) {
        if mask.count_ones() > 4 {
            continue;
        }
        let boundary: SmallVec<[T; 4]> = select(&set, mask).collect();
        for center in T::boundary_centers(&boundary) {
            let score = set
                .iter()
                .map(|item| item.extent_from(center))
                .fold(0.0, f64::max);
            if best.is_none_or(|(_, _, best_score)| score < best_score) {
                best = Some((mask, center, score));
            }
        }
    }
    let (mask, center, score) = best?;
    Some((select(&candidates, mask).collect(), center, score))
}

/// The elements of `values` whose position has its bit set in `mask`, in order.
fn select<V: Copy>(values: &[V], mask: u32) -> impl Iterator<Item = V> + '_ {
    values
        .iter()
        .enumerate()
        .filter(move |(i, _)| mask & (1 << i) != 0)
        .map(|(_, &value)| value)
}
