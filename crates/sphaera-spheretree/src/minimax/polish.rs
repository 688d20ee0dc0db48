//! The continuous step: moving one sphere's centre to where its eq. 2 error over its own
//! pieces is least, by Nelder–Mead on `reach(x) − depth(x)`.
//!
//! `reach(x)` (the largest distance from `x` to a corner of the sphere's pieces) is exact:
//! the corners are sorted by their distance `d_i` from the starting centre `x₀`, and the
//! scan stops once `d_i + |x − x₀|` (a bound on every remaining distance from `x`) cannot
//! beat the largest found. `depth(x)` is the signed distance to the surface
//! ([`super::candidates::signed_depth_fast`]); the centre finally kept is measured with the
//! certified side.

use std::cell::OnceCell;

use glam::DVec3;
use sphaera_query::Surface;

use super::candidates::{signed_depth, signed_depth_fast};
use super::pieces::Piece;
use crate::SphereTreeError;

/// Function evaluations of one polish at most.
const EVALUATIONS: usize = 36;

/// The initial simplex's size, as a fraction of the sphere's eq. 2 scale (its radius).
const STEP: f64 = 0.06;

/// The corners of a set of pieces arranged for exact farthest-point queries near a
/// centre: those that can be the farthest from a point within [`NEAR`] times the largest
/// distance of the origin, sorted farthest first, and all of them (gathered when first
/// needed) for points beyond.
pub(crate) struct Reach<'a> {
    origin: DVec3,
    /// The largest distance from the origin to a corner.
    largest: f64,
    /// `(distance from origin, corner)` of the corners at least `(1 − 2·NEAR)·largest`
    /// from the origin, each once, farthest first.
    outer: Vec<(f64, DVec3)>,
    pieces: &'a [Piece],
    corners: &'a Corners,
    members: &'a [u32],
    /// Every corner, each once: only a point beyond [`NEAR`] asks for them.
    all: OnceCell<Vec<DVec3>>,
}

/// How far from its origin (as a fraction of the largest distance) a [`Reach`] answers
/// from its outer corners alone.
const NEAR: f64 = 0.25;

impl<'a> Reach<'a> {
    /// The corners of `members` (indices into `pieces`, whose corners are numbered by
    /// `corners`), about `origin`.
    pub(crate) fn new(
        pieces: &'a [Piece],
        corners: &'a Corners,
        members: &'a [u32],
        origin: DVec3,
    ) -> Self {
        let all_corners = || members.iter().flat_map(|&m| pieces[m as usize]);
        // A corner counted twice changes no maximum.
        let largest = all_corners()
            .map(|p| p.distance_squared(origin))
            .fold(0.0, f64::max)
            .sqrt();
        // A corner within (1 − 2·NEAR)·largest of the origin is nearer to any point within
        // NEAR·largest of it than the farthest corner is.
        let inner = (1.0 - 2.0 * NEAR) * largest;
        // Below this squared distance a corner is surely within `inner` (its rounded
        // distance too): skipped without its square root.
        let surely_within = (inner * (1.0 - 1e-6)).powi(2);
        let mut seen = corners.none_seen();
        let mut outer: Vec<(f64, DVec3)> = Vec::new();
        for &m in members {
            for (p, id) in pieces[m as usize].into_iter().zip(corners.ids[m as usize]) {
                let squared = p.distance_squared(origin);
                if squared < surely_within {
                    continue;
                }
                // `distance` is the square root of `distance_squared`.
                let d = squared.sqrt();
                if d >= inner && first_sight(&mut seen, id) {
                    outer.push((d, p));
                }
            }
        }
        // The outer corners in the order of their first appearance, as sorted always.
        outer.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
        Self {
            origin,
            largest,
            outer,
            pieces,
            corners,
            members,
            all: OnceCell::new(),
        }
    }

    /// The largest distance from `x` to a corner.
    pub(crate) fn at(&self, x: DVec3) -> f64 {
        let shift = x.distance(self.origin);
        if shift > NEAR * self.largest {
            return self
                .all
                .get_or_init(|| self.corners.unique(self.pieces, self.members))
                .iter()
                .map(|p| p.distance_squared(x))
                .fold(0.0, f64::max)
                .sqrt();
        }
        let mut best = 0.0_f64;
        for &(d, p) in &self.outer {
            if d + shift <= best {
                break;
            }
            best = best.max(p.distance(x));
        }
        best
    }
}

/// The corners of a region's pieces numbered, the same number for the same point:
/// neighbouring pieces share corners bit for bit (split midpoints are computed from the
/// same two corners), so most corners appear several times, and a [`Reach`] takes each
/// once without hashing it again.
pub(crate) struct Corners {
    /// Per piece, its corners' numbers.
    ids: Vec<[u32; 3]>,
    /// Distinct corners.
    count: usize,
}

impl Corners {
    /// The corners of `pieces`, numbered in order of first appearance.
    pub(crate) fn of(pieces: &[Piece]) -> Self {
        let mut set = CornerSet::with_capacity(3 * pieces.len());
        let ids = pieces
            .iter()
            .map(|piece| piece.map(|p| set.insert(p)))
            .collect();
        Self {
            ids,
            count: set.points.len(),
        }
    }

    /// A mark per corner, none set.
    fn none_seen(&self) -> Vec<u64> {
        vec![0; self.count.div_ceil(64)]
    }

    /// The corners of the pieces `members`, each once, in order of first appearance.
    fn unique(&self, pieces: &[Piece], members: &[u32]) -> Vec<DVec3> {
        let mut seen = self.none_seen();
        let mut out = Vec::new();
        for &m in members {
            for (p, id) in pieces[m as usize].into_iter().zip(self.ids[m as usize]) {
                if first_sight(&mut seen, id) {
                    out.push(p);
                }
            }
        }
        out
    }
}

/// Marks corner `id` in `seen`; whether it was not marked yet.
fn first_sight(seen: &mut [u64], id: u32) -> bool {
    let (word, bit) = ((id / 64) as usize, 1_u64 << (id % 64));
    let new = seen[word] & bit == 0;
    seen[word] |= bit;
    new
}

/// A set of points by their bits (open addressing over indices into the points kept),
/// for at most the capacity it was made with.
struct CornerSet {
    /// Per slot, 1 + the index of its point in `points`, or 0 when free.
    slots: Vec<u32>,
    points: Vec<DVec3>,
    shift: u32,
}

impl CornerSet {
    fn with_capacity(capacity: usize) -> Self {
        // At most half full.
        let size = (2 * capacity).next_power_of_two().max(16);
        Self {
            slots: vec![0; size],
            points: Vec::new(),
            shift: 64 - size.trailing_zeros(),
        }
    }

    /// Adds `p`: its number, the count of points before it when it is new.
    fn insert(&mut self, p: DVec3) -> u32 {
        let bits = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        // Split midpoints are dyadic: their low bits are mostly zero, so the words are
        // multiplied up and the slot taken from the high bits.
        let mixed = bits[0].wrapping_mul(0x9e37_79b9_7f4a_7c15)
            ^ bits[1].wrapping_mul(0xbf58_476d_1ce4_e5b9).rotate_left(21)
            ^ bits[2].wrapping_mul(0x94d0_49bb_1331_11eb).rotate_left(42);
        let mixed = (mixed ^ (mixed >> 29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        let mask = self.slots.len() - 1;
        let mut slot = (mixed >> self.shift) as usize & mask;
        loop {
            match self.slots[slot] {
                0 => {
                    self.points.push(p);
                    // Lossless: a region has far fewer than 2³² corners (its pieces are
                    // capped).
                    self.slots[slot] = self.points.len() as u32;
                    return self.slots[slot] - 1;
                }
                k if self.points[k as usize - 1].to_array().map(f64::to_bits) == bits => {
                    return k - 1;
                }
                _ => slot = (slot + 1) & mask,
            }
        }
    }
}

/// A sphere's centre moved to lower its eq. 2 error over `members`: the centre, its
/// certified signed depth and the radius reaching every corner. `start` is the centre to
/// start from; the result is never worse than `start` measured the same way.
///
/// # Errors
///
/// A closest-point query that fails (a non-finite centre).
pub(crate) fn polish(
    surface: &Surface,
    pieces: &[Piece],
    corners: &Corners,
    members: &[u32],
    start: DVec3,
) -> Result<(DVec3, f64, f64), SphereTreeError> {
    let reach = Reach::new(pieces, corners, members, start);
    let mut failure = None;
    // Points closer to the start than its distance to the surface are on its side: the
    // segment between them crosses no surface. Only the others ask for their side.
    let origin = signed_depth_fast(surface, start)?;
    let mut cost = |x: DVec3| -> f64 {
        let shift = x.distance(start);
        let depth = if shift < 0.5 * origin.abs() {
            // The distance is 1-Lipschitz: the start's bounds it, pruning the descent.
            let bound = (origin.abs() + shift) * (1.0 + 1e-9);
            match surface.tree().closest_within(x, bound) {
                Ok(Some(c)) => Ok(c.distance.copysign(origin)),
                Ok(None) => surface
                    .closest(x)
                    .map(|c| c.distance.copysign(origin))
                    .map_err(SphereTreeError::from),
                Err(e) => Err(SphereTreeError::from(e)),
            }
        } else {
            signed_depth_fast(surface, x)
        };
        match depth {
            Ok(depth) => reach.at(x) - depth,
            Err(e) => {
                failure = Some(e);
                f64::INFINITY
            }
        }
    };
    let f0 = reach.at(start) - origin;
    let scale = reach.at(start).max(f64::MIN_POSITIVE);
    let (best, _) = nelder_mead(&mut cost, start, f0, STEP * scale, EVALUATIONS);
    if let Some(e) = failure {
        return Err(e);
    }
    // Measure both with the certified side and keep the better.
    let measured = |x: DVec3| -> Result<(DVec3, f64, f64), SphereTreeError> {
        let depth = signed_depth(surface, x)?;
        Ok((x, depth, reach.at(x)))
    };
    let first = measured(start)?;
    if best == start {
        return Ok(first);
    }
    let moved = measured(best)?;
    Ok(if moved.2 - moved.1 < first.2 - first.1 {
        moved
    } else {
        first
    })
}

/// Nelder–Mead in 3D from `start` (where `f` is `f0`) with an initial simplex of size
/// `step`, at most `evaluations` evaluations: the best point and its value.
pub(crate) fn nelder_mead(
    f: &mut impl FnMut(DVec3) -> f64,
    start: DVec3,
    f0: f64,
    step: f64,
    evaluations: usize,
) -> (DVec3, f64) {
    // A regular tetrahedron about the start, in a fixed orientation (deterministic).
    let offsets = [
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(-1.0, 1.0, -1.0),
    ];
    let mut simplex: [(DVec3, f64); 4] = [(start, f0); 4];
    let mut used = 0;
    for (slot, offset) in simplex[1..].iter_mut().zip(offsets) {
        let p = start + offset * (step / 3.0_f64.sqrt());
        *slot = (p, f(p));
        used += 1;
    }
    let order = |s: &mut [(DVec3, f64); 4]| s.sort_by(|a, b| a.1.total_cmp(&b.1));
    while used + 2 <= evaluations {
        order(&mut simplex);
        let size = simplex[1..]
            .iter()
            .map(|s| s.0.distance(simplex[0].0))
            .fold(0.0, f64::max);
        if size.is_nan() || size <= 1e-4 * step {
            break;
        }
        let centroid = (simplex[0].0 + simplex[1].0 + simplex[2].0) / 3.0;
        let worst = simplex[3];
        let reflected = centroid + (centroid - worst.0);
        let fr = f(reflected);
        used += 1;
        if fr < simplex[0].1 {
            let expanded = centroid + 2.0 * (centroid - worst.0);
            let fe = f(expanded);
            used += 1;
            simplex[3] = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < simplex[2].1 {
            simplex[3] = (reflected, fr);
        } else {
            let contracted = if fr < worst.1 {
                centroid + 0.5 * (reflected - centroid)
            } else {
                centroid + 0.5 * (worst.0 - centroid)
            };
            let fc = f(contracted);
            used += 1;
            if fc < worst.1.min(fr) {
                simplex[3] = (contracted, fc);
            } else {
                let best = simplex[0].0;
                for slot in &mut simplex[1..] {
                    slot.0 = best + 0.5 * (slot.0 - best);
                    slot.1 = f(slot.0);
                    used += 1;
                }
            }
        }
    }
    order(&mut simplex);
    simplex[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nelder_mead_finds_a_quadratic_minimum() {
        let target = DVec3::new(0.3, -0.2, 0.5);
        let mut f = |x: DVec3| x.distance_squared(target);
        let (best, value) = nelder_mead(&mut f, DVec3::ZERO, target.length_squared(), 0.5, 400);
        assert!(value < 1e-8, "{best} {value}");
    }

    #[test]
    fn reach_is_the_farthest_corner_near_its_origin_and_away_from_it() {
        let pieces: Vec<Piece> = (0..50)
            .map(|i| {
                let t = f64::from(i);
                let a = DVec3::new(t.sin(), (0.3 * t).cos(), 0.1 * t);
                [a, a + DVec3::X * 0.1, a + DVec3::Y * 0.1]
            })
            .collect();
        let members: Vec<u32> = (0..50).collect();
        let corners = Corners::of(&pieces);
        let reach = Reach::new(&pieces, &corners, &members, DVec3::ZERO);
        for x in [
            DVec3::ZERO,
            DVec3::new(0.2, 0.1, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
        ] {
            let brute = pieces
                .iter()
                .flatten()
                .map(|p| p.distance(x))
                .fold(0.0, f64::max);
            assert_eq!(reach.at(x).to_bits(), brute.to_bits(), "{x}");
        }
    }

    #[test]
    fn reach_counts_shared_corners_once_and_answers_as_brute_force() {
        // A strip of triangles sharing their corners, and the same triangles split apart.
        let corner = |i: u32| {
            let t = f64::from(i);
            DVec3::new(0.1 * t, (0.7 * t).sin(), 0.2 * f64::from(i % 2))
        };
        let pieces: Vec<Piece> = (0..200)
            .map(|i| [corner(i), corner(i + 1), corner(i + 2)])
            .collect();
        let members: Vec<u32> = (0..200).step_by(3).chain((1..200).step_by(3)).collect();
        for origin in [DVec3::ZERO, DVec3::new(10.0, 0.0, 0.1)] {
            let corners = Corners::of(&pieces);
            let reach = Reach::new(&pieces, &corners, &members, origin);
            let mut firsts: Vec<DVec3> = Vec::new();
            for &m in &members {
                for p in pieces[m as usize] {
                    if !firsts.contains(&p) {
                        firsts.push(p);
                    }
                }
            }
            let outer = reach.outer.iter().map(|&(_, p)| p).collect::<Vec<_>>();
            for (i, p) in outer.iter().enumerate() {
                assert!(!outer[..i].contains(p), "{p} twice");
            }
            assert!(outer.iter().all(|p| firsts.contains(p)));
            assert_eq!(corners.unique(&pieces, &members), firsts);
            for k in 0..40 {
                let t = f64::from(k);
                let x = origin + DVec3::new(t.cos(), (1.3 * t).sin(), 0.1 * t.sin()) * (0.05 * t);
                let brute = firsts.iter().map(|p| p.distance(x)).fold(0.0, f64::max);
                assert_eq!(reach.at(x).to_bits(), brute.to_bits(), "{x}");
            }
        }
    }
}
