//! A derivative-free search for the largest (or smallest) value of a function over a
//! triangle, in barycentric coordinates: a grid, then a pattern search from its best
//! point.
//!
//! The function takes the triangle's barycentric coordinates `(u, v)` (`u, v ≥ 0`,
//! `u + v ≤ 1`; the caller maps them to a point). The search
//!
//! 1. evaluates the grid `(i / g, j / g)` for `i` in `0..=g`, `j` in `0..=g − i` (in that
//!    order; `g` = [`PatternSearch::grid`]); the first grid point is the starting best;
//! 2. polls the best point's neighbours `best + step · direction` for each of
//!    [`PatternSearch::directions`] in order, starting with `step = 1 / g`; a poll point
//!    replaces the best only when it is strictly better; a round without improvement
//!    halves the step;
//! 3. stops when the step is at most [`PatternSearch::min_step`] or the
//!    [`SearchBudget`] is spent (checked before each round, so the last round may overshoot an
//!    evaluation budget by up to one evaluation per direction).
//!
//! Every value it returns was measured at a point of the triangle, so the maximum it
//! finds is a lower bound of the true maximum (and the minimum an upper bound of the true
//! minimum), whatever the function. Deterministic: no randomness, a fixed order.
//!
//! It is shared by [`crate::hausdorff`] (the refinement of the sampled Hausdorff distance:
//! maximise the distance to the other mesh, six directions, skip poll points outside the
//! triangle) and the simplifier's brute-force check of its error spheres
//! (`sphaera-simplify`'s `edge_radius_tests.rs`: minimise a convex function, twelve
//! directions, clamp negative coordinates). It takes and returns plain numbers only, so
//! unit tests of any crate may use it (see the [crate documentation](crate)).
//!
//! # Examples
//!
//! ```
//! use sphaera_tests::pattern_search::{Boundary, SearchBudget, PatternSearch, SIX_DIRECTIONS};
//!
//! // The largest value of −(u − 0.3)² − (v − 0.2)², at (0.3, 0.2).
//! let search = PatternSearch {
//!     grid: 4,
//!     directions: &SIX_DIRECTIONS,
//!     min_step: 1e-9,
//!     budget: SearchBudget::Evaluations(10_000),
//!     boundary: Boundary::Skip,
//! };
//! let best = search.maximise(|u, v| -(u - 0.3).powi(2) - (v - 0.2).powi(2));
//! assert!((best.u - 0.3).abs() < 1e-8 && (best.v - 0.2).abs() < 1e-8);
//! assert!(best.value <= 0.0 && best.value > -1e-15);
//! ```

/// The six poll directions of a triangular lattice: `±u`, `±v` and `±(u − v)`.
pub const SIX_DIRECTIONS: [(f64, f64); 6] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (0.0, 1.0),
    (0.0, -1.0),
    (1.0, -1.0),
    (-1.0, 1.0),
];

/// Twelve poll directions: [`SIX_DIRECTIONS`], `±(u + v)`, and the four knight moves
/// `±(2u − v)`, `±(u − 2v)`, which help along narrow valleys.
pub const TWELVE_DIRECTIONS: [(f64, f64); 12] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (0.0, 1.0),
    (0.0, -1.0),
    (1.0, -1.0),
    (-1.0, 1.0),
    (1.0, 1.0),
    (-1.0, -1.0),
    (2.0, -1.0),
    (-2.0, 1.0),
    (1.0, -2.0),
    (-1.0, 2.0),
];

/// When the pattern search stops, besides its step reaching [`PatternSearch::min_step`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchBudget {
    /// No new round once this many evaluations were made (the grid included).
    Evaluations(usize),
    /// At most this many polling rounds after the grid.
    Rounds(usize),
}

/// What to do with a poll point outside the triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Skip it.
    Skip,
    /// Raise a negative coordinate to 0 (onto the edge `u = 0` or `v = 0`); skip the point
    /// if it is then still beyond the edge `u + v = 1`.
    ClampNegative,
}

/// The parameters of a grid-then-pattern search over a triangle (see the [module
/// documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatternSearch<'a> {
    /// Grid steps per triangle side (0 is taken as 1); the first poll step is `1 / grid`.
    pub grid: u32,
    /// The poll directions, in `(u, v)`, tried in this order.
    pub directions: &'a [(f64, f64)],
    /// The search stops once the step is at most this.
    pub min_step: f64,
    /// The search also stops when this is spent.
    pub budget: SearchBudget,
    /// Poll points outside the triangle.
    pub boundary: Boundary,
}

/// The best point a [`PatternSearch`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchResult {
    /// The best value found (the largest for [`PatternSearch::maximise`], the smallest
    /// for [`PatternSearch::minimise`]).
    pub value: f64,
    /// The first barycentric coordinate where it was found.
    pub u: f64,
    /// The second barycentric coordinate where it was found.
    pub v: f64,
    /// How many times the function was evaluated.
    pub evaluations: usize,
}

impl PatternSearch<'_> {
    /// The largest value of `f` found over the triangle, where, and at what cost.
    ///
    /// # Examples
    ///
    /// See the [module documentation](self).
    #[inline]
    pub fn maximise(&self, f: impl FnMut(f64, f64) -> f64) -> SearchResult {
        self.search(1.0, f)
    }

    /// The search for the largest value of `sign · f` (`sign` is ±1, and multiplying by
    /// it is exact, so `−1` searches for the smallest value of `f` with the same
    /// comparisons); the values recorded are `f`'s own.
    #[inline]
    fn search(&self, sign: f64, mut f: impl FnMut(f64, f64) -> f64) -> SearchResult {
        let grid = self.grid.max(1);
        let steps = f64::from(grid);
        let mut best = SearchResult {
            value: f64::NEG_INFINITY,
            u: 0.0,
            v: 0.0,
            evaluations: 0,
        };
        let mut evaluations = 0;
        for i in 0..=grid {
            for j in 0..=(grid - i) {
                let (u, v) = (f64::from(i) / steps, f64::from(j) / steps);
                let value = f(u, v);
                evaluations += 1;
                // The first grid point starts the search, whatever its value.
                if evaluations == 1 || sign * value > sign * best.value {
                    (best.value, best.u, best.v) = (value, u, v);
                }
            }
        }
        let mut step = 1.0 / steps;
        let mut rounds = 0;
        loop {
            let spent = match self.budget {
                SearchBudget::Evaluations(n) => evaluations >= n,
                SearchBudget::Rounds(n) => rounds >= n,
            };
            if step <= self.min_step || spent {
                break;
            }
            rounds += 1;
            let mut improved = false;
            for &(du, dv) in self.directions {
                let (mut u, mut v) = (best.u + du * step, best.v + dv * step);
                match self.boundary {
                    Boundary::Skip => {
                        if u < 0.0 || v < 0.0 || u + v > 1.0 {
                            continue;
                        }
                    }
                    Boundary::ClampNegative => {
                        (u, v) = (u.max(0.0), v.max(0.0));
                        if u + v > 1.0 {
                            continue;
                        }
                    }
                }
                let value = f(u, v);
                evaluations += 1;
                if sign * value > sign * best.value {
                    (best.value, best.u, best.v) = (value, u, v);
                    improved = true;
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        best.evaluations = evaluations;
        best
    }

    /// The smallest value of `f` found over the triangle: [`maximise`](Self::maximise)
    /// of `−f` (a point is better when its value is strictly smaller), with `f`'s values.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_tests::pattern_search::{Boundary, SearchBudget, PatternSearch, TWELVE_DIRECTIONS};
    ///
    /// // |(u, v) − (0.25, 0.25)| is smallest, 0, at (0.25, 0.25).
    /// let search = PatternSearch {
    ///     grid: 16,
    ///     directions: &TWELVE_DIRECTIONS,
    ///     min_step: 1e-13,
    ///     budget: SearchBudget::Rounds(3_000),
    ///     boundary: Boundary::ClampNegative,
    /// };
    /// let best = search.minimise(|u, v| (u - 0.25).hypot(v - 0.25));
    /// assert_eq!((best.value, best.u, best.v), (0.0, 0.25, 0.25)); // a grid point
    /// ```
    #[inline]
    pub fn minimise(&self, f: impl FnMut(f64, f64) -> f64) -> SearchResult {
        self.search(-1.0, f)
    }
}
