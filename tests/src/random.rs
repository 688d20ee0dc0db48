//! Small deterministic pseudo-random generators for tests, the same on every platform and
//! every run: [`SplitMix64`] and [`Lcg64`].
//!
//! They replace the copies that tests used to write for themselves. Each copy mapped the
//! generator's words to numbers in its own way; every mapping is kept here under a name
//! that says what it does, so each test still draws exactly the numbers it drew before
//! (and so still tests the same inputs):
//!
//! | mapping | method |
//! |---|---|
//! | the 64-bit word | [`SplitMix64::next_u64`] |
//! | the top 53 bits over 2⁵³, in `[0, 1)` | [`SplitMix64::unit`] |
//! | the word divided by `u64::MAX`, in `[0, 1]` | [`SplitMix64::unit_by_max`] |
//! | `lo + (hi − lo) · unit` | [`SplitMix64::range`] |
//! | `⌊unit · n⌋ mod n` | [`SplitMix64::index`] |
//! | `word mod n` | [`SplitMix64::below`] |
//!
//! Nothing here exposes a workspace crate's type ([`DVec3`] is glam's), so unit tests of
//! any crate may use them (see the [crate documentation](crate)).
//!
//! # Examples
//!
//! ```
//! use sphaera_tests::random::SplitMix64;
//!
//! let mut rng = SplitMix64::new(7);
//! let x = rng.unit();
//! assert!((0.0..1.0).contains(&x));
//! // The same seed gives the same sequence.
//! assert_eq!(SplitMix64::new(7).unit(), x);
//! let d = rng.direction();
//! assert!((d.length() - 1.0).abs() < 1e-12);
//! ```

use sphaera_mesh::DVec3;

/// The increment of `SplitMix64` (2⁶⁴ divided by the golden ratio).
const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// Steele, Lea and Flood's `SplitMix64`: a 64-bit state advanced by a constant, and a
/// mixing function of the state as output. Fast, statistically sound for tests, not
/// cryptographic.
///
/// The first output is the mix of `seed + 0x9E37_79B9_7F4A_7C15`.
///
/// # Examples
///
/// ```
/// use sphaera_tests::random::SplitMix64;
///
/// // The reference sequence for seed 0 (Vigna's `splitmix64.c`).
/// let mut rng = SplitMix64::new(0);
/// assert_eq!(rng.next_u64(), 0xE220_A839_7B1D_CDAF);
/// assert_eq!(rng.next_u64(), 0x6E78_9E6A_A1B9_65F4);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator starting from `seed`.
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64-bit word.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`: the top 53 bits of the next word over 2⁵³ (every value a
    /// multiple of 2⁻⁵³).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_tests::random::SplitMix64;
    ///
    /// let (mut a, mut b) = (SplitMix64::new(3), SplitMix64::new(3));
    /// assert_eq!(a.unit(), (b.next_u64() >> 11) as f64 / (1_u64 << 53) as f64);
    /// ```
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1_u64 << 53) as f64
    }

    /// In `[0, 1]`: the next word divided by `u64::MAX` (rounded to the nearest `f64`,
    /// so the largest words give exactly 1). The mapping of the simplifier's unit tests;
    /// prefer [`unit`](Self::unit) in new code.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_tests::random::SplitMix64;
    ///
    /// let (mut a, mut b) = (SplitMix64::new(3), SplitMix64::new(3));
    /// assert_eq!(a.unit_by_max(), b.next_u64() as f64 / u64::MAX as f64);
    /// ```
    pub fn unit_by_max(&mut self) -> f64 {
        self.next_u64() as f64 / u64::MAX as f64
    }

    /// Uniform in `[lo, hi)`: `lo + (hi − lo) · unit()`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `[0, n)` (0 for `n = 0`): `⌊unit() · n⌋ mod n`.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_tests::random::SplitMix64;
    ///
    /// let mut rng = SplitMix64::new(1);
    /// assert!((0..100).all(|_| rng.index(7) < 7));
    /// assert_eq!(rng.index(0), 0);
    /// ```
    pub fn index(&mut self, n: usize) -> usize {
        (self.unit() * n as f64) as usize % n.max(1)
    }

    /// The next word modulo `n` (slightly biased towards small values unless `n` is a
    /// power of two).
    ///
    /// # Panics
    ///
    /// If `n` is 0.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// A uniformly random unit vector: three [`range`](Self::range)`(−1, 1)` coordinates,
    /// redrawn until their length is in `(10⁻³, 1]`, then normalised.
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                return v / l;
            }
        }
    }

    /// A point of the cube `[−1, 1]³`: `2u − 1` per coordinate (x first), with `u` from
    /// [`unit_by_max`](Self::unit_by_max). The vectors of the simplifier's unit tests.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_tests::random::SplitMix64;
    ///
    /// let (mut a, mut b) = (SplitMix64::new(5), SplitMix64::new(5));
    /// let v = a.vector_by_max();
    /// let (x, y, z) = (b.unit_by_max(), b.unit_by_max(), b.unit_by_max());
    /// assert_eq!(v.to_array(), [2.0 * x - 1.0, 2.0 * y - 1.0, 2.0 * z - 1.0]);
    /// ```
    pub fn vector_by_max(&mut self) -> DVec3 {
        DVec3::new(self.unit_by_max(), self.unit_by_max(), self.unit_by_max()) * 2.0 - 1.0
    }
}

/// The 64-bit linear congruential generator with Knuth's MMIX constants
/// (`state ← 6364136223846793005 · state + 1442695040888963407`), for tests that only need
/// a cheap stream of indices. Its low bits are weak, so both outputs use the high ones.
///
/// # Examples
///
/// ```
/// use sphaera_tests::random::Lcg64;
///
/// let mut rng = Lcg64::new(11);
/// let word = rng.next_high31();
/// assert!(word < 1 << 31);
/// let x = rng.unit();
/// assert!((0.0..1.0).contains(&x));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Lcg64 {
    state: u64,
    increment: u64,
}

impl Lcg64 {
    /// Knuth's MMIX increment.
    const MMIX_INCREMENT: u64 = 1_442_695_040_888_963_407;

    /// A generator starting from `seed` (the first output comes from the state after one
    /// step), with Knuth's MMIX increment.
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self::with_increment(seed, Self::MMIX_INCREMENT)
    }

    /// A generator starting from `seed` with another (odd) increment; some older tests
    /// drew their inputs with increment 1.
    #[must_use]
    pub const fn with_increment(seed: u64, increment: u64) -> Self {
        Self {
            state: seed,
            increment,
        }
    }

    fn step(&mut self) -> u64 {
        self.state = self
            .state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.increment);
        self.state
    }

    /// The top 31 bits of the next state (`state >> 33`).
    pub fn next_high31(&mut self) -> u64 {
        self.step() >> 33
    }

    /// Uniform in `[0, 1)`: the top 53 bits of the next state over 2⁵³.
    pub fn unit(&mut self) -> f64 {
        (self.step() >> 11) as f64 / (1_u64 << 53) as f64
    }

    /// A point uniform in the unit cube `[0, 1)³`: the next three values as x, y, z.
    pub fn unit_cube(&mut self) -> DVec3 {
        let x = self.unit();
        let y = self.unit();
        DVec3::new(x, y, self.unit())
    }
}
