//! Certified Hausdorff distances between two meshes: see [`hausdorff`] (triangle trees,
//! every core; `sphaera-query`'s engine, with this crate's errors) and
//! [`meshsweeper_hausdorff`] (the paper's, section 6, on hierarchies). The types and the
//! upper bounds are `sphaera-query`'s.

mod peel;
mod side;
mod target;

use std::cmp::Reverse;

use sphaera_mesh::TriMesh;
use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};

use sphaera_query::QueryError;
pub use sphaera_query::hausdorff::{
    DirectedHausdorff, Direction, HausdorffDistance, HausdorffOptions, HausdorffProgress,
    MAX_HAUSDORFF_SAMPLES,
};

use crate::{SweepError, Sweeper};
use side::Side;

/// The Hausdorff distance between meshes `a` and `b`, bracketed by certified bounds as
/// `options` say: `sphaera-query`'s engine (a triangle tree of each mesh, every core; see
/// [`sphaera_query::hausdorff::hausdorff`] and [`HausdorffOptions`] for the method), with
/// this crate's errors.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{Length, shapes};
/// use sphaera_sweep::{HausdorffOptions, hausdorff};
///
/// let (small, large) = (shapes::sphere(1.0, 32)?, shapes::sphere(1.1, 32)?);
/// let options = HausdorffOptions::default().with_tolerance(Length::Absolute(1e-9));
/// let h = hausdorff(&small, &large, &options)?;
/// assert!(h.lower <= h.upper && h.gap() <= 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SweepError::InvalidParameter`] for a negative or non-finite tolerance or a sample
/// budget above [`MAX_HAUSDORFF_SAMPLES`]; [`SweepError::EmptyMesh`] if a mesh has no
/// triangle.
///
/// # Performance
///
/// A triangle tree per mesh, an exact query per used vertex and per midpoint, a bound per
/// triangle of samples. The 69k-triangle bunny against its 10k-triangle simplification to
/// 1e-5 of the diagonal: see the section *Hausdorff distance (`sphaera-sweep`)* of
/// `docs/benchmarks.md` in the repository. Memory about 100 bytes per sample.
pub fn hausdorff(
    a: &TriMesh,
    b: &TriMesh,
    options: &HausdorffOptions,
) -> Result<HausdorffDistance, SweepError> {
    hausdorff_with_progress(a, b, options, &|_| {})
}

/// [`hausdorff`], calling `progress` after the vertices and after every round of
/// refinement (from the calling thread).
///
/// # Errors
///
/// As [`hausdorff`].
pub fn hausdorff_with_progress(
    a: &TriMesh,
    b: &TriMesh,
    options: &HausdorffOptions,
    progress: &(dyn Fn(&HausdorffProgress) + Sync),
) -> Result<HausdorffDistance, SweepError> {
    sphaera_query::hausdorff::hausdorff_with_progress(a, b, options, progress).map_err(sweep_error)
}

/// A query error as this crate names it.
pub(crate) fn sweep_error(error: QueryError) -> SweepError {
    match error {
        QueryError::EmptyMesh => SweepError::EmptyMesh,
        QueryError::InvalidParameter {
            name,
            value,
            requirement,
        } => SweepError::InvalidParameter {
            name,
            value,
            requirement,
        },
        QueryError::NonFiniteQuery { x, y, z } => SweepError::NonFiniteQuery { x, y, z },
        other => SweepError::Tree(other),
    }
}

/// The error of the target's level of detail used for bounds, as a fraction of the lower
/// bound after the vertices.
const LEVEL_FRACTION: f64 = 0.5;

/// The Hausdorff distance between the meshes of sweepers `a` and `b` by the paper's
/// engine (section 6), bracketed by certified bounds as `options` say (see
/// [`HausdorffOptions`]); [`hausdorff`] is faster.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_sweep::{HausdorffOptions, Sweeper, build_hierarchy, meshsweeper_hausdorff};
///
/// let cube = shapes::cube(2.0, 4)?;
/// let h = build_hierarchy(&cube)?;
/// let s = Sweeper::new(&h)?;
/// let same = meshsweeper_hausdorff(&s, &s, &HausdorffOptions::default())?;
/// assert_eq!((same.lower, same.upper), (0.0, 0.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SweepError::InvalidParameter`] for a negative or non-finite tolerance or a sample
/// budget above [`MAX_HAUSDORFF_SAMPLES`].
///
/// # Performance
///
/// One closest-point query per vertex of `A` (coherent, along peel paths), then a few per
/// refined triangle; memory about 64 bytes per sample. Symmetric: both directions, but
/// only the dominating direction is refined once the other's upper bound falls below the
/// lower bound.
pub fn meshsweeper_hausdorff(
    a: &Sweeper<'_>,
    b: &Sweeper<'_>,
    options: &HausdorffOptions,
) -> Result<HausdorffDistance, SweepError> {
    meshsweeper_hausdorff_with_progress(a, b, options, &|_| {})
}

/// [`meshsweeper_hausdorff`], calling `progress` every few thousand samples (from the
/// calling thread).
///
/// # Errors
///
/// As [`meshsweeper_hausdorff`].
pub fn meshsweeper_hausdorff_with_progress(
    a: &Sweeper<'_>,
    b: &Sweeper<'_>,
    options: &HausdorffOptions,
    progress: &(dyn Fn(&HausdorffProgress) + Sync),
) -> Result<HausdorffDistance, SweepError> {
    Run {
        a,
        b,
        options,
        progress,
    }
    .run()
}

/// One computation.
struct Run<'r, 's> {
    a: &'r Sweeper<'s>,
    b: &'r Sweeper<'s>,
    options: &'r HausdorffOptions,
    progress: &'r (dyn Fn(&HausdorffProgress) + Sync),
}

impl Run<'_, '_> {
    fn run(self) -> Result<HausdorffDistance, SweepError> {
        let symmetric = self.options.symmetric;
        let allowed = self
            .options
            .allowed_gap(
                self.a.hierarchy().positions(),
                self.b.hierarchy().positions(),
            )
            .map_err(sweep_error)?;
        let mut sides = vec![Side::new(self.a, self.b)];
        if symmetric {
            sides.push(Side::new(self.b, self.a));
        }
        let vertices: usize = sides.iter().map(|s| s.source().vertex_count()).sum();
        let mut tracker = Tracker {
            report: self.progress,
            vertices,
            vertices_done: 0,
            next_report: 0,
        };
        let mut floor = 0.0_f64;
        for side in &mut sides {
            side.floor = floor;
            side.query_vertices(self.options.exact_vertex_distances, &mut tracker)?;
            floor = floor.max(side.lower);
        }
        // A level of detail of each target at a quarter of the lower bound: its larger
        // triangles bound whole source triangles where input triangles cannot.
        let lower = sides.iter().map(|s| s.lower).fold(0.0_f64, f64::max);
        if lower > 0.0 {
            for side in &mut sides {
                side.attach_level(LEVEL_FRACTION * lower);
            }
        }
        let mut queue = MaxHeap::new();
        let mut nodes = Vec::new();
        for (index, side) in sides.iter().enumerate() {
            for t in 0..side.source().triangle_count() as u32 {
                if let Some(corners) = side.source().triangle(t) {
                    push(&mut queue, &mut nodes, &sides, index, corners);
                }
            }
        }
        let converged = refine(
            &mut sides,
            &mut queue,
            &mut nodes,
            allowed,
            self.options.max_samples,
            &mut tracker,
        )?;
        // Each direction's upper bound: its own lower bound, or its largest queued bound.
        let mut uppers: Vec<f64> = sides.iter().map(|s| s.lower).collect();
        for entry in queue.iter() {
            if let Some(node) = nodes.get(entry.node)
                && let Some(u) = uppers.get_mut(usize::from(node.side))
            {
                *u = u.max(entry.upper);
            }
        }
        let directed = sides
            .into_iter()
            .zip(uppers)
            .map(|(side, upper)| side.finish(upper));
        HausdorffDistance::from_directions(directed, converged).map_err(sweep_error)
    }
}

/// Splits the triangle with the largest upper bound until that bound is within `allowed`
/// of the lower bound (`true`) or the sample budget runs out (`false`).
fn refine(
    sides: &mut [Side<'_>],
    queue: &mut MaxHeap<Queued>,
    nodes: &mut Vec<Node>,
    allowed: f64,
    max_samples: usize,
    tracker: &mut Tracker<'_>,
) -> Result<bool, SweepError> {
    loop {
        let lower = sides.iter().map(|s| s.lower).fold(0.0_f64, f64::max);
        let samples: usize = sides.iter().map(Side::sample_count).sum();
        let Some(top) = queue.peek().copied() else {
            return Ok(true);
        };
        tracker.tick(samples, lower, top.upper.max(lower));
        if top.upper <= lower + allowed {
            return Ok(true);
        }
        if samples >= max_samples {
            return Ok(false);
        }
        queue.pop();
        let Some(&Node {
            corners: [a, b, c],
            side,
        }) = nodes.get(top.node)
        else {
            continue;
        };
        let index = usize::from(side);
        let Some(source) = sides.get_mut(index) else {
            continue;
        };
        source.refined += 1;
        source.floor = lower;
        let ab = source.midpoint(a, b)?;
        let bc = source.midpoint(b, c)?;
        let ca = source.midpoint(c, a)?;
        for corners in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            push(queue, nodes, sides, index, corners);
        }
    }
}

/// Queues the triangle of samples `corners` of side `index` with its upper bound.
fn push(
    queue: &mut MaxHeap<Queued>,
    nodes: &mut Vec<Node>,
    sides: &[Side<'_>],
    index: usize,
    corners: [u32; 3],
) {
    let Some(side) = sides.get(index) else {
        return;
    };
    let Some(upper) = side.upper_bound(corners) else {
        return;
    };
    queue.push(Queued {
        upper,
        node: nodes.len(),
    });
    nodes.push(Node {
        corners,
        side: u8::from(index == 1),
    });
}

/// A triangle of samples waiting in the queue.
#[derive(Clone, Copy, Debug)]
struct Node {
    corners: [u32; 3],
    side: u8,
}

/// A queue entry: a node and its upper bound (a max-heap on the bound, ties by node).
#[derive(Clone, Copy, Debug)]
struct Queued {
    upper: f64,
    node: usize,
}

impl Priority for Queued {
    type Key = (TotalF64, Reverse<usize>);

    fn priority(&self) -> Self::Key {
        (TotalF64(self.upper), Reverse(self.node))
    }
}

/// Calls the progress callback now and then.
struct Tracker<'a> {
    report: &'a (dyn Fn(&HausdorffProgress) + Sync),
    vertices: usize,
    vertices_done: usize,
    next_report: usize,
}

impl Tracker<'_> {
    /// One more vertex has a point found.
    fn vertex_done(&mut self, lower: f64) {
        self.vertices_done += 1;
        if self.vertices_done.is_multiple_of(4096) {
            self.tick(self.vertices_done, lower, f64::INFINITY);
        }
    }

    fn tick(&mut self, samples: usize, lower: f64, upper: f64) {
        if samples < self.next_report {
            return;
        }
        self.next_report = samples + 4096;
        (self.report)(&HausdorffProgress::new(
            self.vertices_done,
            self.vertices,
            samples,
            lower,
            upper,
        ));
    }
}
