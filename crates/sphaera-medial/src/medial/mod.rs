//! The adaptive medial-axis approximation (Bradshaw and O'Sullivan 2004, section 4).
//!
//! Surface samples are the forming points of a Voronoi diagram (the dual of
//! [`Delaunay`]); the Voronoi vertices inside the object approximate its medial axis, and
//! the sphere around each, through its four forming points, touches the surface there.
//!
//! 1. **Start** from a few samples spread by farthest-point selection.
//! 2. **Complete coverage**: every surface sample must lie in some sphere. An uncovered
//!    sample lies in the Voronoi cell of its nearest forming point, and the spheres around
//!    that cell's vertices cover the cell; one of them (smallest error, or largest
//!    coverage: [`CoverCriterion`]) joins the set as a *cover* sphere. If the cell is
//!    unbounded and none contains it, the sample itself becomes a forming point (then the
//!    spheres of its cell pass through it). So coverage of every sample is guaranteed.
//! 3. **Improve**: the worst sphere (largest error) is replaced by inserting the surface
//!    point closest to its centre as a new forming point: the spheres of its new cell pass
//!    through that point, so the error there drops to zero. Repeat from 2 until the target
//!    count or error is reached — for the whole object
//!    ([`MedialApproximation::build`]) or for a region
//!    ([`MedialApproximation::refine_region`]).
//!
//! **Error** (the paper's eq. 2): for a centre `v` inside, `e = r − ‖q − v‖` with `q` the
//! closest surface point (exact, from the mesh's [`sphaera_query::closest::TriangleTree`]): any point of the sphere outside the
//! object is at most `e` from the surface, since the radius through it crosses the surface
//! at least `‖q − v‖` from `v`. For a centre outside (cover spheres), `e = r + ‖q − v‖`:
//! every point of the sphere is within `r` of `v`, which is within `‖q − v‖` of the surface.

mod grid;
mod options;
mod sphere;
mod start;

use glam::DVec3;

pub use options::{CoverCriterion, MedialOptions, RegionOptions};
pub use sphere::{MedialSphere, SphereKind};

use crate::{Delaunay, MedialError, Surface, TetId};
use grid::SampleGrid;
use options::validate_options;
use start::initial_diagram;

const NONE: u32 = u32::MAX;

/// Coverage tolerance relative to the bounding-box diagonal (forming points lie on their
/// spheres up to rounding).
const COVER_TOLERANCE: f64 = 1e-9;

/// Fewest new spheres worth measuring on several threads.
#[cfg(feature = "parallel")]
const PARALLEL_MIN_SPHERES: usize = 8;

/// One Voronoi vertex's sphere.
#[derive(Debug, Clone)]
struct Record {
    center: DVec3,
    radius: f64,
    error: f64,
    closest: DVec3,
    inside: bool,
    /// Set membership: `None` outside the set.
    member: Option<SphereKind>,
    /// Covered samples, for members.
    covers: Vec<u32>,
    /// Its closest point is already a forming point: inserting it changes nothing.
    stuck: bool,
}

/// Counters of the work done.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct MedialStats {
    /// Improvement steps (each inserted the closest point of the worst sphere).
    pub improvements: usize,
    /// Samples inserted as forming points to complete coverage (unbounded cells).
    pub coverage_insertions: usize,
    /// Cover spheres added (some were later replaced).
    pub cover_spheres_added: usize,
    /// Worst spheres that could not be improved (their closest point was already a
    /// forming point).
    pub stuck: usize,
}

/// Progress of [`MedialApproximation::build_with_progress`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MedialProgress {
    /// Spheres in the set now.
    pub spheres: usize,
    /// The largest error in the set now.
    pub worst_error: f64,
    /// Improvement steps so far.
    pub improvements: usize,
}

/// What [`MedialApproximation::refine_region`] reached.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RegionOutcome {
    /// The spheres of the set that cover at least one sample of the region, ordered by
    /// their Voronoi vertex.
    pub spheres: Vec<MedialSphere>,
    /// The largest error among them.
    pub worst_error: f64,
    /// Whether the goal was met (else the iteration cap or a stuck sphere stopped it).
    pub reached: bool,
    /// Improvement steps taken.
    pub improvements: usize,
}

/// An adaptive medial-axis approximation: spheres centred on Voronoi vertices of surface
/// samples, covering every sample.
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling;
/// use sphaera_mesh::shapes;
/// use sphaera_medial::{MedialApproximation, MedialOptions, Surface};
///
/// let mesh = shapes::capsule(0.5, 2.0, 12)?;
/// let surface = Surface::new(&mesh)?;
/// let samples: Vec<_> = sampling::poisson_disk(&mesh, 2_000, 1)?
///     .samples
///     .iter()
///     .map(|s| s.position)
///     .collect();
/// // Improve until no sphere reaches more than 0.05 beyond the surface.
/// let options = MedialOptions::default().with_max_error(0.05);
/// let medial = MedialApproximation::build(&surface, &samples, &options)?;
/// assert!(medial.worst_error() <= 0.05);
/// // Every sample is covered by some sphere.
/// assert!(medial.uncovered_samples().is_empty());
/// for sphere in medial.spheres() {
///     for &s in &sphere.covers {
///         assert!((samples[s as usize] - sphere.center).length() <= sphere.radius + 1e-9);
///     }
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct MedialApproximation<'s> {
    surface: &'s Surface,
    samples: Vec<DVec3>,
    grid: SampleGrid,
    delaunay: Delaunay,
    records: Vec<Option<Record>>,
    members: Vec<TetId>,
    member_slot: Vec<u32>,
    cover_count: Vec<u32>,
    uncovered: Vec<u32>,
    tolerance: f64,
    cover: CoverCriterion,
    nearest_hint: u32,
    /// Members that joined, recorded while a region is refined.
    journal: Option<Vec<TetId>>,
    stats: MedialStats,
}

impl<'s> MedialApproximation<'s> {
    /// Builds the adaptive approximation of `surface` covering `samples` (points on the
    /// surface, e.g. from [`sphaera_query::sampling::poisson_disk`]), improved until
    /// `options`' target is reached (the first of [`MedialOptions::target_spheres`] and
    /// [`MedialOptions::max_error`]; with neither, coverage only).
    ///
    /// # Errors
    ///
    /// [`MedialError::NonFiniteSample`], [`MedialError::TooFewSamples`] (fewer than four
    /// distinct non-coplanar samples), [`MedialError::InvalidParameter`].
    ///
    /// # Panics
    ///
    /// Never.
    pub fn build(
        surface: &'s Surface,
        samples: &[DVec3],
        options: &MedialOptions,
    ) -> Result<Self, MedialError> {
        Self::build_with_progress(surface, samples, options, &|_| {})
    }

    /// [`MedialApproximation::build`], calling `progress` after coverage and then every
    /// few improvement steps (for progress bars).
    ///
    /// # Errors
    ///
    /// As [`MedialApproximation::build`].
    pub fn build_with_progress(
        surface: &'s Surface,
        samples: &[DVec3],
        options: &MedialOptions,
        progress: &(dyn Fn(&MedialProgress) + Sync),
    ) -> Result<Self, MedialError> {
        validate_options(options)?;
        let mut medial = Self::start(surface, samples, options.initial_points, options.cover)?;
        medial.ensure_coverage()?;
        medial.improve(options, progress)?;
        Ok(medial)
    }

    /// Hubbard's static approximation, the paper's baseline: the Voronoi diagram of
    /// `forming` samples (spread by farthest-point selection), its internal spheres, and
    /// no improvement. With `cover: None` coverage is not completed (as Hubbard), so
    /// [`MedialApproximation::uncovered_samples`] shows the gaps; with a criterion it is
    /// completed like the adaptive method.
    ///
    /// # Errors
    ///
    /// As [`MedialApproximation::build`].
    pub fn build_static(
        surface: &'s Surface,
        samples: &[DVec3],
        forming: usize,
        cover: Option<CoverCriterion>,
    ) -> Result<Self, MedialError> {
        let mut medial = Self::start(surface, samples, forming.max(4), cover.unwrap_or_default())?;
        if cover.is_some() {
            medial.ensure_coverage()?;
        }
        Ok(medial)
    }

    fn start(
        surface: &'s Surface,
        samples: &[DVec3],
        initial: usize,
        cover: CoverCriterion,
    ) -> Result<Self, MedialError> {
        if let Some(index) = samples.iter().position(|p| !p.is_finite()) {
            return Err(MedialError::NonFiniteSample { index });
        }
        if samples.len() >= u32::MAX as usize {
            return Err(MedialError::TooManySamples {
                count: samples.len(),
            });
        }
        let delaunay = initial_diagram(samples, initial)?;
        let mut medial = Self {
            surface,
            samples: samples.to_vec(),
            grid: SampleGrid::new(samples),
            delaunay,
            records: Vec::new(),
            members: Vec::new(),
            member_slot: Vec::new(),
            cover_count: vec![0; samples.len()],
            uncovered: (0..samples.len() as u32).rev().collect(),
            tolerance: COVER_TOLERANCE * surface.diagonal(),
            cover,
            nearest_hint: 0,
            journal: None,
            stats: MedialStats::default(),
        };
        let tets: Vec<TetId> = medial
            .delaunay
            .tetrahedra()
            .map(|(t, _)| t)
            .filter(|&t| medial.delaunay.is_finite(t))
            .collect();
        medial.evaluate_all(&tets);
        Ok(medial)
    }

    /// The spheres of the set (internal and cover), ordered by their Voronoi vertex.
    #[must_use]
    pub fn spheres(&self) -> Vec<MedialSphere> {
        let mut ids = self.members.clone();
        ids.sort_unstable();
        ids.iter().filter_map(|&t| self.sphere(t)).collect()
    }

    /// Every finite Voronoi vertex's sphere, members or not ([`SphereKind::External`] for
    /// external vertices outside the set; their `covers` is empty).
    #[must_use]
    pub fn voronoi_spheres(&self) -> Vec<MedialSphere> {
        (0..self.records.len() as TetId)
            .filter_map(|t| self.sphere(t))
            .collect()
    }

    fn sphere(&self, t: TetId) -> Option<MedialSphere> {
        let r = self.records.get(t as usize)?.as_ref()?;
        Some(MedialSphere {
            center: r.center,
            radius: r.radius,
            error: r.error,
            closest: r.closest,
            kind: r.member.unwrap_or(if r.inside {
                SphereKind::Internal
            } else {
                SphereKind::External
            }),
            covers: r.covers.clone(),
        })
    }

    /// The number of spheres in the set.
    #[must_use]
    pub fn sphere_count(&self) -> usize {
        self.members.len()
    }

    /// The largest error in the set (0 for an empty set).
    #[must_use]
    pub fn worst_error(&self) -> f64 {
        self.members
            .iter()
            .filter_map(|&t| self.record(t))
            .map(|r| r.error)
            .fold(0.0, f64::max)
    }

    /// Samples no sphere of the set covers (empty after [`MedialApproximation::build`]).
    #[must_use]
    pub fn uncovered_samples(&self) -> Vec<u32> {
        (0..self.samples.len() as u32)
            .filter(|&s| self.cover_count[s as usize] == 0)
            .collect()
    }

    /// The surface samples, by index.
    #[must_use]
    pub fn samples(&self) -> &[DVec3] {
        &self.samples
    }

    /// The Voronoi diagram's dual: the tetrahedralization of the forming points.
    #[must_use]
    pub fn delaunay(&self) -> &Delaunay {
        &self.delaunay
    }

    /// Counters of the work done.
    #[must_use]
    pub fn stats(&self) -> MedialStats {
        self.stats
    }

    /// Improves the spheres covering `region` (indices of surface samples) until at least
    /// `options.min_spheres` of them cover some region sample and their worst error is at
    /// most `options.max_error` (when given), replacing the worst of them each step;
    /// coverage of all samples is kept. This is the per-node step of sphere-tree
    /// construction.
    ///
    /// # Errors
    ///
    /// [`MedialError::RegionOutOfRange`] for a bad sample index,
    /// [`MedialError::InvalidParameter`] for a NaN or negative `max_error`.
    pub fn refine_region(
        &mut self,
        region: &[u32],
        options: &RegionOptions,
    ) -> Result<RegionOutcome, MedialError> {
        if let Some(&index) = region.iter().find(|&&s| s as usize >= self.samples.len()) {
            return Err(MedialError::RegionOutOfRange {
                index,
                count: self.samples.len(),
            });
        }
        let max_error = options.max_error.unwrap_or(f64::INFINITY);
        if max_error.is_nan() || max_error < 0.0 {
            return Err(MedialError::InvalidParameter {
                name: "max_error",
                value: max_error,
                requirement: "non-negative",
            });
        }
        let mut in_region = vec![false; self.samples.len()];
        for &s in region {
            in_region[s as usize] = true;
        }
        // The region's spheres, kept up to date from the journal of members that joined
        // since (ids of removed tetrahedra are reused, so every joiner is re-checked).
        let mut spheres: Vec<TetId> = self
            .members
            .iter()
            .copied()
            .filter(|&t| self.covers_region(t, &in_region))
            .collect();
        self.journal = Some(Vec::new());
        let mut improvements = 0;
        let outcome = loop {
            let joined = self.journal.replace(Vec::new()).unwrap_or_default();
            if !joined.is_empty() {
                spheres.extend(joined);
                spheres.sort_unstable();
                spheres.dedup();
            }
            spheres.retain(|&t| self.covers_region(t, &in_region));
            let mut worst: Option<(TetId, f64)> = None;
            let mut worst_error = 0.0_f64;
            for &t in &spheres {
                let Some(r) = self.record(t) else { continue };
                worst_error = worst_error.max(r.error);
                if !r.stuck && worst.is_none_or(|(_, e)| r.error > e) {
                    worst = Some((t, r.error));
                }
            }
            let reached = spheres.len() >= options.min_spheres && worst_error <= max_error;
            let stop = reached || improvements >= options.max_iterations;
            let Some((t, _)) = worst.filter(|_| !stop) else {
                spheres.sort_unstable();
                break RegionOutcome {
                    spheres: spheres.iter().filter_map(|&t| self.sphere(t)).collect(),
                    worst_error,
                    reached,
                    improvements,
                };
            };
            if let Err(e) = self.replace(t) {
                self.journal = None;
                return Err(e);
            }
            improvements += 1;
        };
        self.journal = None;
        Ok(outcome)
    }

    /// Whether `t` is a member covering at least one marked sample.
    fn covers_region(&self, t: TetId, in_region: &[bool]) -> bool {
        self.record(t)
            .is_some_and(|r| r.member.is_some() && r.covers.iter().any(|&s| in_region[s as usize]))
    }

    fn record(&self, t: TetId) -> Option<&Record> {
        self.records.get(t as usize)?.as_ref()
    }

    /// Improvement steps until the target.
    fn improve(
        &mut self,
        options: &MedialOptions,
        progress: &(dyn Fn(&MedialProgress) + Sync),
    ) -> Result<(), MedialError> {
        if options.target_spheres.is_none() && options.max_error.is_none() {
            return Ok(());
        }
        for step in 0..options.max_iterations {
            if step % 16 == 0 {
                progress(&MedialProgress {
                    spheres: self.members.len(),
                    worst_error: self.worst_error(),
                    improvements: self.stats.improvements,
                });
            }
            let count_reached = options
                .target_spheres
                .is_some_and(|n| self.members.len() >= n);
            let error_reached = options.max_error.is_some_and(|e| self.worst_error() <= e);
            if count_reached || error_reached {
                break;
            }
            let Some(worst) = self.worst_improvable() else {
                break;
            };
            self.replace(worst)?;
        }
        Ok(())
    }

    fn worst_improvable(&self) -> Option<TetId> {
        let mut best: Option<(TetId, f64)> = None;
        for &t in &self.members {
            if let Some(r) = self.record(t)
                && !r.stuck
                && best.is_none_or(|(_, e)| r.error > e)
            {
                best = Some((t, r.error));
            }
        }
        best.map(|(t, _)| t)
    }

    /// Replaces sphere `t` by inserting the surface point closest to its centre, then
    /// restores coverage.
    fn replace(&mut self, t: TetId) -> Result<(), MedialError> {
        let Some(record) = self.record(t) else {
            return Ok(());
        };
        let q = record.closest;
        // Fallback when q is already a forming point (an external centre whose closest
        // surface point is one of its own forming points): the covered sample deepest
        // inside the sphere, which the sphere's tetrahedron conflicts with.
        let deepest = record
            .covers
            .iter()
            .map(|&s| (s, (self.samples[s as usize] - record.center).length()))
            .filter(|&(_, d)| d < record.radius - self.tolerance)
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
            .map(|(s, _)| self.samples[s as usize]);
        if self.insert_point(q)? || deepest.is_some_and(|p| self.insert_point(p).unwrap_or(false)) {
            self.stats.improvements += 1;
        } else if let Some(Some(r)) = self.records.get_mut(t as usize) {
            r.stuck = true;
            self.stats.stuck += 1;
        }
        self.ensure_coverage()
    }

    /// Inserts a forming point and updates the spheres; `false` if it already was one.
    fn insert_point(&mut self, p: DVec3) -> Result<bool, MedialError> {
        let report = self
            .delaunay
            .insert(p)
            .map_err(MedialError::TooFewSamples)?;
        if report.duplicate {
            return Ok(false);
        }
        for &t in &report.removed {
            self.remove_member(t);
            if let Some(slot) = self.records.get_mut(t as usize) {
                *slot = None;
            }
        }
        let created: Vec<TetId> = report
            .created
            .iter()
            .copied()
            .filter(|&t| self.delaunay.is_finite(t))
            .collect();
        self.evaluate_all(&created);
        Ok(true)
    }

    /// Computes the spheres of finite tetrahedra `tets` (on all cores with the `parallel`
    /// feature; each is a pure function of the diagram, so the result is the same); the
    /// internal ones join the set, in the order given.
    fn evaluate_all(&mut self, tets: &[TetId]) {
        let measure = |&t: &TetId| {
            let (center, radius) = self.delaunay.circumsphere(t)?;
            Some((t, measure_sphere(self.surface, center, radius)))
        };
        #[cfg(feature = "parallel")]
        let measured: Vec<Option<(TetId, Record)>> = {
            use rayon::prelude::*;
            if tets.len() >= PARALLEL_MIN_SPHERES {
                tets.par_iter().map(measure).collect()
            } else {
                tets.iter().map(measure).collect()
            }
        };
        #[cfg(not(feature = "parallel"))]
        let measured: Vec<Option<(TetId, Record)>> = tets.iter().map(measure).collect();
        for (t, record) in measured.into_iter().flatten() {
            if self.records.len() <= t as usize {
                self.records.resize(t as usize + 1, None);
            }
            let inside = record.inside;
            self.records[t as usize] = Some(record);
            if inside {
                self.add_member(t, SphereKind::Internal);
            }
        }
    }

    fn add_member(&mut self, t: TetId, kind: SphereKind) {
        let Some(Some(record)) = self.records.get(t as usize) else {
            return;
        };
        if record.member.is_some() {
            return;
        }
        let (center, radius) = (record.center, record.radius);
        let mut covers = Vec::new();
        if radius.is_finite() {
            self.grid
                .within(&self.samples, center, radius + self.tolerance, &mut covers);
        }
        for &s in &covers {
            self.cover_count[s as usize] += 1;
        }
        if let Some(Some(record)) = self.records.get_mut(t as usize) {
            record.member = Some(kind);
            record.covers = covers;
        }
        if self.member_slot.len() <= t as usize {
            self.member_slot.resize(t as usize + 1, NONE);
        }
        self.member_slot[t as usize] = self.members.len() as u32;
        self.members.push(t);
        if let Some(journal) = &mut self.journal {
            journal.push(t);
        }
    }

    fn remove_member(&mut self, t: TetId) {
        let Some(&slot) = self.member_slot.get(t as usize) else {
            return;
        };
        if slot == NONE {
            return;
        }
        self.member_slot[t as usize] = NONE;
        self.members.swap_remove(slot as usize);
        if let Some(&moved) = self.members.get(slot as usize) {
            self.member_slot[moved as usize] = slot;
        }
        if let Some(Some(record)) = self.records.get_mut(t as usize) {
            record.member = None;
            for &s in &record.covers {
                let count = &mut self.cover_count[s as usize];
                *count -= 1;
                if *count == 0 {
                    self.uncovered.push(s);
                }
            }
            record.covers.clear();
        }
    }

    /// Covers every sample (section 4.1).
    fn ensure_coverage(&mut self) -> Result<(), MedialError> {
        let mut cell = crate::VoronoiCell::default();
        while let Some(s) = self.uncovered.pop() {
            if self.cover_count[s as usize] > 0 {
                continue;
            }
            let p = self.samples[s as usize];
            let Some(f) = self.nearest_forming_point(p) else {
                continue;
            };
            self.delaunay.voronoi_cell_into(f, &mut cell);
            let is_forming = self.delaunay.point(f) == p;
            // Spheres larger than the object (around nearly flat tetrahedra at the hull)
            // are a last resort: the sample becomes a forming point instead.
            let sane = self.surface.diagonal();
            let mut candidates: Vec<TetId> = cell
                .tetrahedra
                .iter()
                .copied()
                .filter(|&t| {
                    self.record(t).is_some_and(|r| {
                        r.member.is_none()
                            && r.radius <= sane
                            && (is_forming || (p - r.center).length() <= r.radius + self.tolerance)
                    })
                })
                .collect();
            if candidates.is_empty() && is_forming {
                candidates = cell
                    .tetrahedra
                    .iter()
                    .copied()
                    .filter(|&t| self.record(t).is_some_and(|r| r.member.is_none()))
                    .collect();
            }
            if candidates.is_empty() {
                if !is_forming && self.insert_point(p)? {
                    self.stats.coverage_insertions += 1;
                    self.uncovered.push(s);
                }
                continue;
            }
            let best = self.choose_cover(&candidates);
            // A cover sphere worse than every current sphere would set the worst error:
            // refine there instead (the sample becomes a forming point), as the
            // improvement step would do next anyway.
            let best_error = self.record(best).map_or(f64::INFINITY, |r| r.error);
            if !is_forming && best_error > self.worst_error() {
                if self.insert_point(p)? {
                    self.stats.coverage_insertions += 1;
                }
                self.uncovered.push(s);
                continue;
            }
            self.add_member(best, SphereKind::Cover);
            self.stats.cover_spheres_added += 1;
            if self.cover_count[s as usize] == 0 {
                // Rounding left it out of the chosen sphere: make it a forming point.
                if !is_forming && self.insert_point(p)? {
                    self.stats.coverage_insertions += 1;
                }
                self.uncovered.push(s);
            }
        }
        Ok(())
    }

    fn choose_cover(&self, candidates: &[TetId]) -> TetId {
        let score = |t: TetId| -> f64 {
            let Some(r) = self.record(t) else {
                return f64::NEG_INFINITY;
            };
            match self.cover {
                CoverCriterion::SmallestError => -r.error,
                CoverCriterion::LargestCoverage => {
                    let mut inside = Vec::new();
                    self.grid.within(
                        &self.samples,
                        r.center,
                        r.radius + self.tolerance,
                        &mut inside,
                    );
                    inside
                        .iter()
                        .filter(|&&s| self.cover_count[s as usize] == 0)
                        .count() as f64
                }
            }
        };
        let mut best = candidates[0];
        let mut best_score = score(best);
        for &t in &candidates[1..] {
            let v = score(t);
            if v > best_score {
                best = t;
                best_score = v;
            }
        }
        best
    }

    fn nearest_forming_point(&mut self, p: DVec3) -> Option<u32> {
        let start = if self.delaunay.duplicate_of(self.nearest_hint).is_none()
            && (self.nearest_hint as usize) < self.delaunay.vertex_count()
        {
            self.nearest_hint
        } else {
            (0..self.delaunay.vertex_count() as u32)
                .find(|&v| self.delaunay.duplicate_of(v).is_none())?
        };
        let nearest = self.delaunay.nearest_vertex(p, start)?;
        self.nearest_hint = nearest;
        Some(nearest)
    }
}

/// The paper's eq. 2: how far a sphere of radius `radius` reaches beyond the solid, at
/// most, when its center is `depth` from the surface, inside the solid or not: `r − d`
/// for a center inside (0 when the whole sphere is inside), `r + d` outside. The one
/// formula every crate uses for a sphere's error.
///
/// # Examples
///
/// ```
/// use sphaera_medial::eq2_error;
///
/// assert_eq!(eq2_error(1.0, 0.25, true), 0.75);
/// assert_eq!(eq2_error(0.1, 0.25, true), 0.0);
/// assert_eq!(eq2_error(1.0, 0.25, false), 1.25);
/// ```
#[must_use]
pub fn eq2_error(radius: f64, depth: f64, inside: bool) -> f64 {
    if inside {
        (radius - depth).max(0.0)
    } else {
        radius + depth
    }
}

/// [`eq2_error`] of the sphere `(center, radius)` as the medial approximation measures it:
/// the surface's inside test and exact closest point (infinite for a non-finite sphere).
///
/// # Examples
///
/// ```
/// use sphaera_medial::{DVec3, Surface, surface_eq2_error};
///
/// let surface = Surface::new(&sphaera_mesh::shapes::cube(2.0, 1)?)?;
/// assert_eq!(surface_eq2_error(&surface, DVec3::ZERO, 0.5), 0.0);
/// assert_eq!(surface_eq2_error(&surface, DVec3::ZERO, 1.5), 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[must_use]
pub fn surface_eq2_error(surface: &Surface, center: DVec3, radius: f64) -> f64 {
    measure_sphere(surface, center, radius).error
}

/// The record of the sphere `(center, radius)`: inside or not, its error and closest
/// surface point; not a member yet.
fn measure_sphere(surface: &Surface, center: DVec3, radius: f64) -> Record {
    let (inside, error, closest) = if center.is_finite() && radius.is_finite() {
        let inside = surface.is_inside(center);
        match surface.closest(center) {
            Ok(answer) => (
                inside,
                eq2_error(radius, answer.distance, inside),
                answer.point,
            ),
            Err(_) => (false, f64::INFINITY, center),
        }
    } else {
        (false, f64::INFINITY, center)
    };
    Record {
        center,
        radius,
        error,
        closest,
        inside,
        member: None,
        covers: Vec::new(),
        stuck: false,
    }
}
