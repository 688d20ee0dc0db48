//! Insertion order: biased randomized insertion order (BRIO, Amenta, Choi and Rote 2003)
//! with every round sorted along a Hilbert curve.
//!
//! A random order bounds the expected work of incremental construction; sorting each round
//! along a space-filling curve makes consecutive points close, so the walk from the last
//! created tetrahedron to the next point is short and the touched memory stays in cache.
//! The shuffle uses a fixed seed: the order is a function of the points only.

use glam::DVec3;
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;

/// Bits per axis of the Hilbert key (the grid has `2^BITS` cells per axis).
const BITS: u32 = 10;

/// Rounds smaller than this are not split further.
const SMALLEST_ROUND: usize = 1_000;

/// The BRIO order of `indices` into `points`: a seeded shuffle cut into rounds that double in
/// size, each round sorted by Hilbert key.
pub(crate) fn brio(points: &[DVec3], mut indices: Vec<u32>, seed: u64) -> Vec<u32> {
    if indices.len() < 2 {
        return indices;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    indices.shuffle(&mut rng);
    let (lo, hi) = bounds(points, &indices);
    let mut keys: Vec<(u32, u32)> = indices
        .iter()
        .map(|&i| (hilbert_key(points[i as usize], lo, hi), i))
        .collect();
    // Round ends from the back: n, n/2, n/4, … down to SMALLEST_ROUND.
    let mut ends = vec![keys.len()];
    let mut end = keys.len();
    while end / 2 >= SMALLEST_ROUND {
        end /= 2;
        ends.push(end);
    }
    ends.push(0);
    ends.reverse();
    for round in ends.windows(2) {
        keys[round[0]..round[1]].sort_unstable();
    }
    keys.into_iter().map(|(_, i)| i).collect()
}

fn bounds(points: &[DVec3], indices: &[u32]) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for &i in indices {
        lo = lo.min(points[i as usize]);
        hi = hi.max(points[i as usize]);
    }
    (lo, hi)
}

/// The Hilbert key of `p` in the box `[lo, hi]` on a `2^BITS` grid per axis.
fn hilbert_key(p: DVec3, lo: DVec3, hi: DVec3) -> u32 {
    let cells = f64::from(1_u32 << BITS);
    let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let quantize = |v: f64, l: f64| ((v - l) / extent * cells).clamp(0.0, cells - 1.0) as u32;
    hilbert_index(
        [
            quantize(p.x, lo.x),
            quantize(p.y, lo.y),
            quantize(p.z, lo.z),
        ],
        BITS,
    )
}

/// The position along the 3D Hilbert curve of the grid cell `cell` (`bits` bits per axis),
/// by Skilling's transpose method (*Programming the Hilbert curve*, 2004): undo the
/// rotations and reflections level by level, Gray-code, then interleave the bits.
pub(crate) fn hilbert_index(mut x: [u32; 3], bits: u32) -> u32 {
    let top = 1_u32 << (bits - 1);
    let mut q = top;
    while q > 1 {
        let low = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= low;
            } else {
                let swap = (x[0] ^ x[i]) & low;
                x[0] ^= swap;
                x[i] ^= swap;
            }
        }
        q >>= 1;
    }
    x[1] ^= x[0];
    x[2] ^= x[1];
    let mut flip = 0;
    q = top;
    while q > 1 {
        if x[2] & q != 0 {
            flip ^= q - 1;
        }
        q >>= 1;
    }
    for v in &mut x {
        *v ^= flip;
    }
    let mut key = 0;
    for bit in (0..bits).rev() {
        for v in x {
            key = (key << 1) | ((v >> bit) & 1);
        }
    }
    key
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consecutive_hilbert_cells_are_face_neighbours() {
        for bits in 1..=4 {
            let n = 1_u32 << bits;
            let mut cells: Vec<(u32, [u32; 3])> = Vec::new();
            for x in 0..n {
                for y in 0..n {
                    for z in 0..n {
                        cells.push((hilbert_index([x, y, z], bits), [x, y, z]));
                    }
                }
            }
            cells.sort_unstable();
            for (i, (key, _)) in cells.iter().enumerate() {
                assert_eq!(*key as usize, i, "keys are a permutation");
            }
            for w in cells.windows(2) {
                let step: u32 = (0..3).map(|k| w[0].1[k].abs_diff(w[1].1[k])).sum();
                assert_eq!(step, 1, "bits {bits}: {:?} -> {:?}", w[0].1, w[1].1);
            }
        }
    }

    #[test]
    fn brio_is_a_deterministic_permutation() {
        let points: Vec<DVec3> = (0..5_000)
            .map(|i| {
                let t = f64::from(i);
                DVec3::new((t * 0.37).sin(), (t * 0.11).cos(), (t * 0.071).sin())
            })
            .collect();
        let order = brio(&points, (0..5_000).collect(), 7);
        assert_eq!(order, brio(&points, (0..5_000).collect(), 7));
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..5_000).collect::<Vec<u32>>());
    }
}
