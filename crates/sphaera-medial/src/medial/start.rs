//! The start of the approximation: a few samples spread by farthest-point selection,
//! and their Delaunay tetrahedralization.

use glam::DVec3;

use crate::{Delaunay, DelaunayError, MedialError};

/// The Delaunay tetrahedralization of `initial` samples spread by farthest-point
/// selection; more are taken if those are flat.
pub(super) fn initial_diagram(samples: &[DVec3], initial: usize) -> Result<Delaunay, MedialError> {
    let mut want = initial.max(4).min(samples.len());
    loop {
        let chosen = farthest_points(samples, want);
        let points: Vec<DVec3> = chosen.iter().map(|&i| samples[i as usize]).collect();
        match Delaunay::new(&points) {
            Ok(d) => return Ok(d),
            Err(e @ (DelaunayError::Flat { .. } | DelaunayError::TooFewPoints { .. }))
                if want < samples.len() =>
            {
                let _ = e;
                want = (want * 2).min(samples.len());
            }
            Err(e) => return Err(MedialError::TooFewSamples(e)),
        }
    }
}

/// `k` samples by farthest-point selection, starting from the one farthest from the
/// centroid; deterministic.
fn farthest_points(samples: &[DVec3], k: usize) -> Vec<u32> {
    if samples.is_empty() || k == 0 {
        return Vec::new();
    }
    let centroid = samples.iter().copied().sum::<DVec3>() / samples.len() as f64;
    let first = (0..samples.len())
        .max_by(|&a, &b| {
            (samples[a] - centroid)
                .length_squared()
                .total_cmp(&(samples[b] - centroid).length_squared())
                .then(b.cmp(&a))
        })
        .unwrap_or(0);
    let mut distance: Vec<f64> = samples
        .iter()
        .map(|p| (*p - samples[first]).length_squared())
        .collect();
    let mut chosen = vec![first as u32];
    while chosen.len() < k.min(samples.len()) {
        let (next, d) =
            distance
                .iter()
                .enumerate()
                .fold((0, f64::NEG_INFINITY), |best, (i, &d)| {
                    if d > best.1 { (i, d) } else { best }
                });
        if d <= 0.0 {
            break;
        }
        chosen.push(next as u32);
        for (i, p) in samples.iter().enumerate() {
            distance[i] = distance[i].min((*p - samples[next]).length_squared());
        }
    }
    chosen
}
