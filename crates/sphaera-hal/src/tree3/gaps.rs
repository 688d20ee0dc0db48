//! Closing the gaps of an extracted level with fans on the unmatched edge loops.

use std::collections::HashMap;
/// Closes the gaps of a triangle set: the directed edges without an opposite partner
/// (counted with multiplicity) are chained into loops, and each loop is filled by a fan
/// from its first vertex, oriented to balance them. Deterministic: loops start at the
/// lowest unmatched edge and turn to the lowest next vertex.
pub(super) fn close_gaps(triangles: &mut Vec<[u32; 3]>) {
    // Net count per undirected edge: + for (low, high), − for (high, low).
    let mut net: HashMap<(u32, u32), i64> = HashMap::new();
    for &[a, b, c] in triangles.iter() {
        for (u, v) in [(a, b), (b, c), (c, a)] {
            if u == v {
                continue;
            }
            *net.entry((u.min(v), u.max(v))).or_default() += if u < v { 1 } else { -1 };
        }
    }
    // The edges the filling must provide, as outgoing lists per vertex.
    let mut needed: std::collections::BTreeMap<u32, Vec<u32>> = std::collections::BTreeMap::new();
    let mut pending = 0_usize;
    for (&(low, high), &count) in &net {
        // count > 0: the set has (low, high) too often, so the fill needs (high, low).
        let (from, to) = if count > 0 { (high, low) } else { (low, high) };
        for _ in 0..count.unsigned_abs() {
            needed.entry(from).or_default().push(to);
            pending += 1;
        }
    }
    for list in needed.values_mut() {
        list.sort_unstable_by(|a, b| b.cmp(a));
    }
    while pending > 0 {
        let Some((&start, _)) = needed.iter().find(|(_, list)| !list.is_empty()) else {
            break;
        };
        let mut lasso = vec![start];
        let mut at = start;
        while let Some(next) = needed.get_mut(&at).and_then(Vec::pop) {
            pending -= 1;
            if let Some(position) = lasso.iter().position(|&v| v == next) {
                // A loop closed: fill it and keep walking from where it began.
                let ring: Vec<u32> = lasso.split_off(position);
                for k in 1..ring.len().saturating_sub(1) {
                    triangles.push([ring[0], ring[k], ring[k + 1]]);
                }
                lasso.push(next);
                if lasso.len() == 1 && needed.get(&next).is_none_or(Vec::is_empty) {
                    break;
                }
            } else {
                lasso.push(next);
            }
            at = next;
        }
    }
}
