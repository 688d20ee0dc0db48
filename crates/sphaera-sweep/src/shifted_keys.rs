//! Priority keys stored shifted by the total motion of the query point (paper section
//! 5.1), shared by the mesh and the polyline sessions.
//!
//! An interval computed for an earlier query point widens by the motion since: its lower
//! end drops by as much. Storing `key = lower + G₀` (`G₀`: the total motion when it was
//! computed) and reading `lower = key − G` (`G`: the total motion now) applies that to
//! every entry at once without reordering the queue. Entries also carry the generation
//! they were computed at, so a stale one is recognised and re-evaluated when it reaches
//! the front.

/// The relative rounding of a shifted key (a few ulps of the total motion), subtracted
/// from every lower bound so it stays conservative however the shift rounded.
pub(crate) const MOTION_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// A session resets when the total motion since its last reset passes this many times the
/// bounding-box diagonal, so the shifted keys keep their precision (the rounding slack
/// stays below `1e-13` of the diagonal).
const MAX_MOTION_IN_DIAGONALS: f64 = 64.0;

/// The total motion since the last reset and the current generation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ShiftedKeys {
    motion: f64,
    generation: u32,
}

impl ShiftedKeys {
    /// The key to store for an interval whose lower end is `lower` now.
    pub(crate) fn key(self, lower: f64) -> f64 {
        lower + self.motion
    }

    /// The lower end now of the interval stored with `key`.
    pub(crate) fn lower(self, key: f64) -> f64 {
        key - self.motion - MOTION_ROUNDING * self.motion
    }

    /// The generation to stamp a fresh entry with.
    pub(crate) fn stamp(self) -> u32 {
        self.generation
    }

    /// Whether the keys can no longer absorb a move by `jump` (the motion would pass
    /// [`MAX_MOTION_IN_DIAGONALS`] diagonals, or the generations would wrap): reset first.
    pub(crate) fn exhausted(self, jump: f64, diagonal: f64) -> bool {
        self.motion + jump > MAX_MOTION_IN_DIAGONALS * diagonal || self.generation >= u32::MAX - 1
    }

    /// A move by `amount`: every interval widens by it, every entry becomes stale.
    pub(crate) fn widen(&mut self, amount: f64) {
        self.motion += amount;
        self.generation += 1;
    }

    /// A fresh start (after a reset): no motion, a new generation.
    pub(crate) fn restart(&mut self) {
        self.motion = 0.0;
        self.generation = self.generation.wrapping_add(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_widen_by_the_motion_and_stay_conservative() {
        let mut keys = ShiftedKeys::default();
        keys.restart();
        let stored = keys.key(1.0);
        let stamp = keys.stamp();
        keys.widen(0.25);
        assert!(keys.lower(stored) <= 0.75 && keys.lower(stored) > 0.75 - 1e-15);
        assert_ne!(keys.stamp(), stamp);
        assert!(!keys.exhausted(1.0, 1.0));
        assert!(keys.exhausted(64.0, 1.0));
    }
}
