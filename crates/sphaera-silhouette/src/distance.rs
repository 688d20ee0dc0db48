//! Distance transforms of a binary image (section 3.1.3): each object pixel gets its
//! distance, in pixels between centres, to the nearest background pixel; background
//! pixels get 0. Pixels beyond the image's edge count as background (the grid holds the
//! whole image of the bounding sphere, so beyond it there is nothing).

/// Which distance transform to run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DistanceTransform {
    /// Exact Euclidean distances (the separable linear-time algorithm of Felzenszwalb and
    /// Huttenlocher: distances along columns, then the lower envelope of parabolas along
    /// rows).
    #[default]
    Euclidean,
    /// The paper's two-pass propagation (Rosenfeld and Pfaltz) with Borgefors' 3–4
    /// chamfer weights, divided by 3: within 8 % of the Euclidean distance.
    Chamfer,
}

impl DistanceTransform {
    /// The distances of `object` (`true` for an object pixel), `width × height`, row-major.
    ///
    /// # Panics
    ///
    /// If `object.len() != width * height`.
    #[must_use]
    pub fn apply(self, object: &[bool], width: usize, height: usize) -> Vec<f32> {
        assert_eq!(object.len(), width * height, "the image is width × height");
        match self {
            Self::Euclidean => euclidean(object, width, height),
            Self::Chamfer => chamfer(object, width, height),
        }
    }
}

/// Squared distance along one line: `f` in (0 for background, infinite for object, or
/// the squared distances of the first pass), the lower envelope of the parabolas
/// `(x − p)² + f(p)` out, with background beyond both ends (virtual sites at `−1` and
/// `n`).
fn envelope(
    f: &[f64],
    out: &mut [f64],
    sites: &mut Vec<(f64, f64)>,
    v: &mut Vec<usize>,
    z: &mut Vec<f64>,
) {
    let n = f.len();
    sites.clear();
    sites.push((-1.0, 0.0));
    sites.extend(
        f.iter()
            .enumerate()
            .filter(|(_, value)| value.is_finite())
            .map(|(p, &value)| (p as f64, value)),
    );
    sites.push((n as f64, 0.0));
    v.clear();
    z.clear();
    v.push(0);
    z.push(f64::NEG_INFINITY);
    z.push(f64::INFINITY);
    for q in 1..sites.len() {
        let (pq, fq) = sites[q];
        let mut s;
        loop {
            // Invariant: `v` starts with the virtual site at −1 and the loop below pops
            // only while more than one site is left, so it is never empty.
            let (pv, fv) = sites[*v.last().expect("the first site stays")];
            s = ((fq + pq * pq) - (fv + pv * pv)) / (2.0 * (pq - pv));
            if s <= z[v.len() - 1] && v.len() > 1 {
                v.pop();
                z.pop();
            } else {
                break;
            }
        }
        // z[v.len()] is the right end of the last parabola: it becomes s.
        let last = v.len();
        z[last] = s;
        v.push(q);
        z.push(f64::INFINITY);
    }
    let mut k = 0;
    for (x, slot) in out.iter_mut().enumerate() {
        let x = x as f64;
        while z[k + 1] < x {
            k += 1;
        }
        let (p, fp) = sites[v[k]];
        *slot = (x - p) * (x - p) + fp;
    }
}

/// Exact Euclidean distance transform: first, along every column, the distance to the
/// nearest background pixel of the column (two sweeps over whole rows, so memory is read
/// in order); then, along every row, the lower envelope of the parabolas of those squared
/// distances.
fn euclidean(object: &[bool], width: usize, height: usize) -> Vec<f32> {
    // Column distances (in pixels, background beyond the top and bottom rows).
    let mut column = vec![0.0_f64; width * height];
    for y in 0..height {
        for x in 0..width {
            let i = y * width + x;
            column[i] = if object[i] {
                if y == 0 { 1.0 } else { column[i - width] + 1.0 }
            } else {
                0.0
            };
        }
    }
    for y in (0..height).rev() {
        for x in 0..width {
            let i = y * width + x;
            // Background lies beyond the bottom row too.
            let below = if y + 1 == height {
                1.0
            } else {
                column[i + width] + 1.0
            };
            if below < column[i] {
                column[i] = below;
            }
        }
    }
    let (mut sites, mut v, mut z) = (Vec::new(), Vec::new(), Vec::new());
    let mut row = vec![0.0; width];
    let mut out = vec![0.0; width];
    let mut distances = vec![0.0_f32; width * height];
    for y in 0..height {
        for (slot, &c) in row.iter_mut().zip(&column[y * width..(y + 1) * width]) {
            *slot = c * c;
        }
        envelope(&row, &mut out, &mut sites, &mut v, &mut z);
        for (d, &squared) in distances[y * width..(y + 1) * width].iter_mut().zip(&out) {
            *d = squared.sqrt() as f32;
        }
    }
    distances
}

/// The 3–4 chamfer transform, two passes, divided by 3.
fn chamfer(object: &[bool], width: usize, height: usize) -> Vec<f32> {
    const EDGE: u32 = 3;
    const DIAGONAL: u32 = 4;
    let at = |d: &[u32], x: isize, y: isize| -> u32 {
        if x < 0 || y < 0 || x >= width as isize || y >= height as isize {
            0
        } else {
            d[y as usize * width + x as usize]
        }
    };
    let mut d: Vec<u32> = object
        .iter()
        .map(|&o| if o { u32::MAX / 2 } else { 0 })
        .collect();
    for y in 0..height as isize {
        for x in 0..width as isize {
            let i = y as usize * width + x as usize;
            if d[i] == 0 {
                continue;
            }
            let best = (at(&d, x - 1, y) + EDGE)
                .min(at(&d, x, y - 1) + EDGE)
                .min(at(&d, x - 1, y - 1) + DIAGONAL)
                .min(at(&d, x + 1, y - 1) + DIAGONAL);
            d[i] = d[i].min(best);
        }
    }
    for y in (0..height as isize).rev() {
        for x in (0..width as isize).rev() {
            let i = y as usize * width + x as usize;
            if d[i] == 0 {
                continue;
            }
            let best = (at(&d, x + 1, y) + EDGE)
                .min(at(&d, x, y + 1) + EDGE)
                .min(at(&d, x + 1, y + 1) + DIAGONAL)
                .min(at(&d, x - 1, y + 1) + DIAGONAL);
            d[i] = d[i].min(best);
        }
    }
    d.into_iter().map(|v| v as f32 / EDGE as f32).collect()
}
