//! A small open-addressing map from an edge of the cavity boundary to the new tetrahedron
//! face waiting for its twin, cleared in O(1) between insertions by an epoch stamp.

/// Maps an unordered vertex pair to `(tetrahedron, slot)`; each key is seen exactly twice
/// per insertion, so the second sighting takes the entry out.
#[derive(Debug, Clone, Default)]
pub(crate) struct EdgeMap {
    keys: Vec<u64>,
    values: Vec<(u32, u8)>,
    stamps: Vec<u32>,
    epoch: u32,
}

impl EdgeMap {
    /// Empties the map and makes room for `expected` keys at load ≤ ½.
    pub(crate) fn reset(&mut self, expected: usize) {
        let wanted = (expected * 2).next_power_of_two().max(64);
        if wanted > self.keys.len() {
            self.keys = vec![0; wanted];
            self.values = vec![(0, 0); wanted];
            self.stamps = vec![0; wanted];
            self.epoch = 0;
        }
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamps.fill(0);
            self.epoch = 1;
        }
    }

    /// Returns the waiting face of the same edge and removes it, or records `value` and
    /// returns `None`.
    pub(crate) fn pair(&mut self, u: u32, w: u32, value: (u32, u8)) -> Option<(u32, u8)> {
        let key = if u < w {
            (u64::from(u) << 32) | u64::from(w)
        } else {
            (u64::from(w) << 32) | u64::from(u)
        };
        let mask = self.keys.len() - 1;
        let mut slot = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as usize & mask;
        loop {
            if self.stamps[slot] != self.epoch {
                self.stamps[slot] = self.epoch;
                self.keys[slot] = key;
                self.values[slot] = value;
                return None;
            }
            if self.keys[slot] == key {
                // A tombstone keeps probe chains intact: the key can never come back.
                self.keys[slot] = u64::MAX;
                return Some(self.values[slot]);
            }
            slot = (slot + 1) & mask;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_each_edge_once_in_either_orientation() {
        let mut map = EdgeMap::default();
        map.reset(10);
        assert_eq!(map.pair(3, 7, (1, 0)), None);
        assert_eq!(map.pair(9, 2, (2, 1)), None);
        assert_eq!(map.pair(7, 3, (5, 2)), Some((1, 0)));
        assert_eq!(map.pair(2, 9, (6, 3)), Some((2, 1)));
        map.reset(10);
        assert_eq!(map.pair(3, 7, (1, 0)), None);
    }
}
