//! Golden fingerprints of the parallelisable computations.
//!
//! `cargo xtask test` runs the crate's tests with and without the `parallel` feature; these
//! hard-coded hashes make the two builds compare against each other (and against earlier
//! runs), which comparing two runs of the same build cannot. A changed fingerprint means
//! the output changed bit for bit: if that is intended (an algorithm change), paste the
//! values from the failure message into the constants; if it only happens with or without
//! `parallel`, or on another x86-64 machine, it is a determinism bug.

use glam::DVec3;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_query::sampling;
use sphaera_query::winding::WindingNumber;

/// 64-bit FNV-1a over a stream of `u64` words (little-endian bytes).
#[derive(Clone, Copy)]
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn word(mut self, word: u64) -> Self {
        for byte in word.to_le_bytes() {
            self.0 ^= u64::from(byte);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
        self
    }

    fn float(self, x: f64) -> Self {
        self.word(x.to_bits())
    }

    fn point(self, p: DVec3) -> Self {
        self.float(p.x).float(p.y).float(p.z)
    }
}

fn torus() -> TriMesh {
    shapes::torus(1.0, 0.3, 48).unwrap()
}

fn samples_fingerprint(samples: &[sampling::SurfaceSample]) -> u64 {
    samples
        .iter()
        .fold(Fnv1a::new(), |h, s| {
            let [u, v, w] = s.barycentric;
            h.point(s.position)
                .word(s.triangle as u64)
                .float(u)
                .float(v)
                .float(w)
                .point(s.normal)
        })
        .0
}

/// A fixed, irregular set of query points around the torus (no randomness involved).
fn query_points() -> Vec<DVec3> {
    (0..2000u32)
        .map(|i| {
            let t = f64::from(i);
            DVec3::new(
                1.6 * ((t * 0.618_033_988_749_895).fract() - 0.5) * 2.0,
                1.6 * ((t * 0.414_213_562_373_095).fract() - 0.5) * 2.0,
                0.5 * ((t * 0.732_050_807_568_877).fract() - 0.5) * 2.0,
            )
        })
        .collect()
}

/// Checks each `(name, actual, expected)`; a failure lists every actual value, so that an
/// intended update needs one run.
fn check(fingerprints: &[(&str, u64, u64)]) {
    let all: Vec<String> = fingerprints
        .iter()
        .map(|(name, actual, _)| format!("{name}: {actual:#018x}"))
        .collect();
    for &(name, actual, expected) in fingerprints {
        assert_eq!(
            actual, expected,
            "fingerprint of {name} changed (expected {expected:#018x}); all values: {all:?}"
        );
    }
}

#[test]
fn poisson_disk_positions_match_golden() {
    let result = sampling::poisson_disk(&torus(), 3000, 11).unwrap();
    assert_eq!(result.samples.len(), 3000);
    let positions = result
        .samples
        .iter()
        .fold(Fnv1a::new(), |h, s| h.point(s.position))
        .0;
    let spacing = Fnv1a::new()
        .float(result.min_distance)
        .float(result.ideal_spacing)
        .0;
    check(&[
        ("poisson_disk positions", positions, 0xfb5a_5224_ea6b_97f7),
        (
            "poisson_disk samples",
            samples_fingerprint(&result.samples),
            0x6031_8b0f_888d_759f,
        ),
        ("poisson_disk spacing", spacing, 0x8b7b_9a8d_9ced_e573),
    ]);
}

#[test]
fn random_samples_match_golden() {
    let samples = sampling::random(&torus(), 5000, 3).unwrap();
    check(&[(
        "random samples",
        samples_fingerprint(&samples),
        0xf78d_920c_5108_5b6b,
    )]);
}

#[test]
fn winding_numbers_and_classification_match_golden() {
    let winding = WindingNumber::new(&torus()).unwrap();
    let points = query_points();
    let numbers = winding.winding_numbers(&points);
    let inside = winding.classify(&points);
    let inside_count = inside.iter().filter(|&&b| b).count();
    // The set straddles the surface, so the classification fingerprint is meaningful.
    assert!(inside_count > 50 && inside_count < 1950, "{inside_count}");
    let numbers = numbers.iter().fold(Fnv1a::new(), |h, &w| h.float(w)).0;
    let inside = inside
        .iter()
        .fold(Fnv1a::new(), |h, &b| h.word(u64::from(b)))
        .0;
    check(&[
        ("winding_numbers", numbers, 0x43fe_0150_ed44_2d32),
        ("classify", inside, 0x8b72_dce0_953f_55c4),
    ]);
}
