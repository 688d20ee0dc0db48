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
    /// The name users type and reports show (`"euclidean"`, …), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Euclidean => "euclidean",
            Self::Chamfer => "chamfer",
        }
    }
}

impl std::fmt::Display for DistanceTransform {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for DistanceTransform {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "euclidean" => Ok(Self::Euclidean),
            "chamfer" => Ok(Self::Chamfer),
            _ => Err(sphaera_mesh::ParseNameError::new(
                "distance transform",
                s,
                "euclidean or chamfer",
            )),
        }
    }
}

impl DistanceTransform {
    /// The distances of `object` (`true` for an object pixel), `width × height`, row-major.
    ///
    /// # Panics
    ///
    /// If `object.len() != width * height`.
    #[must_use]
    pub fn apply(self, object: &[bool], width: usize, height: usize) -> Vec<f32> {
        let mut distances = Vec::new();
        self.apply_into(
            object,
            width,
            height,
            &mut Workspace::default(),
            &mut distances,
        );
        distances
    }

    /// [`DistanceTransform::apply`] into `distances` (resized), with buffers from
    /// `workspace` (reused from image to image).
    pub(crate) fn apply_into(
        self,
        object: &[bool],
        width: usize,
        height: usize,
        workspace: &mut Workspace,
        distances: &mut Vec<f32>,
    ) {
        assert_eq!(
            Some(object.len()),
            width.checked_mul(height),
            "the image is width × height"
        );
        match self {
            Self::Euclidean => euclidean(object, width, height, workspace, distances),
            Self::Chamfer => *distances = chamfer(object, width, height),
        }
    }
}

/// Buffers of the Euclidean transform, kept from image to image.
#[derive(Clone, Debug, Default)]
pub(crate) struct Workspace {
    /// Per pixel: the distance to the nearest background pixel of its column.
    column: Vec<u32>,
    /// The sites `(p, f(p))` of one run's lower envelope, left to right.
    sites: Vec<(i64, i64)>,
    /// The breakpoints between consecutive sites, as fractions (numerator, positive
    /// denominator).
    breaks: Vec<(i64, i64)>,
}

/// One run of object pixels of a row, at positions `0..n`, between background pixels (or
/// the image's edges) at `−1` and `n`: the distances of its pixels into `out`, from the
/// lower envelope of the parabolas `(x − p)² + f(p)`, with `f(p)` the square of
/// `column[p]` (the distance along the column), and 0 at the two background sites.
///
/// The breakpoints of the envelope are fractions of integers, compared exactly by cross
/// multiplication: for a side of `n` pixels the terms are about `4n³` at most, far within `i64`
/// for any grid that fits in memory.
fn envelope(
    column: &[u32],
    out: &mut [f32],
    sites: &mut Vec<(i64, i64)>,
    breaks: &mut Vec<(i64, i64)>,
) {
    let n = column.len() as i64;
    sites.clear();
    breaks.clear();
    sites.push((-1, 0));
    let object = (0..)
        .zip(column)
        .map(|(p, &c)| (p, i64::from(c) * i64::from(c)));
    for (q, fq) in object.chain([(n, 0)]) {
        // Where the parabola of q overtakes that of site (p, f(p)) (q > p).
        let breakpoint = |(p, fp): (i64, i64)| ((fq + q * q) - (fp + p * p), 2 * (q - p));
        // Invariant: `sites` holds one more site than `breaks` (at least the one at −1),
        // so its last index is valid.
        let mut s = breakpoint(sites[sites.len() - 1]);
        // The last site is hidden when q overtakes it no later than it overtook the one
        // before it.
        while let Some(&(num, den)) = breaks.last()
            && s.0 * den <= num * s.1
        {
            sites.pop();
            breaks.pop();
            s = breakpoint(sites[sites.len() - 1]);
        }
        breaks.push(s);
        sites.push((q, fq));
    }
    let mut k = 0;
    for (x, d) in (0..).zip(out) {
        while let Some(&(num, den)) = breaks.get(k)
            && num < x * den
        {
            k += 1;
        }
        let (p, fp) = sites[k];
        // Exact: an integer below 2⁵³.
        *d = (((x - p) * (x - p) + fp) as f64).sqrt() as f32;
    }
}

/// Exact Euclidean distance transform: first, along every column, the distance to the
/// nearest background pixel of the column (two sweeps over whole rows, so memory is read
/// in order); then, along every row, the lower envelope of the parabolas of those squared
/// distances (Felzenszwalb and Huttenlocher). A background pixel hides every parabola
/// beyond it from the pixels on its other side, so each run of object pixels of a row is
/// enveloped on its own, between the background pixels (or the image's edges) that bound
/// it.
fn euclidean(
    object: &[bool],
    width: usize,
    height: usize,
    workspace: &mut Workspace,
    distances: &mut Vec<f32>,
) {
    // Column distances (in pixels, background beyond the top and bottom rows).
    let column = &mut workspace.column;
    column.clear();
    column.resize(width * height, 0);
    for y in 0..height {
        for x in 0..width {
            let i = y * width + x;
            column[i] = if object[i] {
                if y == 0 { 1 } else { column[i - width] + 1 }
            } else {
                0
            };
        }
    }
    for y in (0..height).rev() {
        for x in 0..width {
            let i = y * width + x;
            // Background lies beyond the bottom row too.
            let below = if y + 1 == height {
                1
            } else {
                column[i + width] + 1
            };
            if below < column[i] {
                column[i] = below;
            }
        }
    }
    distances.clear();
    distances.resize(width * height, 0.0);
    for (line, out) in column
        .chunks_exact(width)
        .zip(distances.chunks_exact_mut(width))
    {
        let mut x = 0;
        while x < width {
            if line[x] == 0 {
                x += 1;
                continue;
            }
            let end = line[x..]
                .iter()
                .position(|&c| c == 0)
                .map_or(width, |n| x + n);
            envelope(
                &line[x..end],
                &mut out[x..end],
                &mut workspace.sites,
                &mut workspace.breaks,
            );
            x = end;
        }
    }
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
