//! The greedy collapse loop: a priority queue of per-vertex best collapses, ordered by the
//! error-sphere radius they would need, re-evaluated in batches around the applied
//! collapses.
//!
//! # The loop
//!
//! The queue holds one candidate per vertex ([`queue`]). A collapse `u → v` makes `v` and
//! its neighbours *stale*: their candidates were computed on a fan that changed. The loop
//! applies the first candidate as long as it is not stale; every candidate it applies is
//! therefore exactly what a fresh evaluation would give (its radius is certified, never
//! estimated; only its topology is re-checked, as a change two rings away can alter the
//! link condition).
//!
//! With the strict order every stale vertex is re-evaluated right after each collapse.
//! With the batched order:
//! - a stale vertex whose queued key is more than [`LAZY_FACTOR`] times the front's waits
//!   until it reaches the front; the others join the *batch*;
//! - when the first candidate is stale, it is re-evaluated alone while the batch holds
//!   fewer than [`MIN_BATCH`] vertices (and than a [`BATCH_FRACTION`] of the live
//!   ones); otherwise the whole batch is re-evaluated at once, on every core with the `parallel` feature (each evaluation is a pure function
//!   of the mesh, so the result does not depend on the thread count);
//! - before the loop stops at the error bound, every stale vertex is re-evaluated, so
//!   that none is left out by its stale key.
//!
//! In both orders a batch evaluation skips the topology check ([`Topology::Deferred`]):
//! its radius is then at most the legal one, and the check is made once, when the
//! candidate reaches the front, so the strict order is exactly the greedy one. The batched
//! order drifts a little from it (a stale key is not a bound on the fresh one).
//!
//! # Performance
//!
//! Each evaluation builds the projected fan once ([`Fan`]) and prunes targets by lower
//! bounds, so it costs `O(d²)` arithmetic for valence `d` plus a ring walk, most of it
//! loading the neighbours (cache misses on large meshes). The batched order makes fewer
//! evaluations per applied collapse than the strict one. The time per evaluation is in
//! the section *Issue 20: batched re-evaluation on every core (2026-11-27)* of
//! `docs/benchmarks.md` in the repository.

mod queue;

use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

use crate::edge_radius::edge_collapse_radius;
use crate::quadric::{Quadric, optimal_position, vertex_quadrics};
use crate::record::Recorder;
use crate::simplifier::{LockReport, SimplifyProgress};
use crate::spheres::{BoundaryPolicy, Fan, collapse_radius, edge_radius, simple_map_radius};
use crate::weights::Weights;
use glam::DVec3;
use queue::{Entry, Queue};

/// When to stop.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stop {
    /// Stop once the live triangle count is at most this.
    pub triangles: usize,
    /// Never apply a collapse whose resulting radius exceeds this.
    pub max_radius: f64,
    /// Whether boundary vertices may be removed.
    pub boundary: BoundaryPolicy,
}

/// How candidates are costed and ordered.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings<'w> {
    /// Per-vertex tolerance weights (`None`: all 1).
    pub weights: Option<&'w Weights>,
    /// Whether placement is optimal (full-edge collapses tried too).
    pub optimal: bool,
    /// The strict greedy order ([`Order::Strict`](crate::Order::Strict)): every stale
    /// vertex re-evaluated right after each collapse.
    pub strict: bool,
}

/// The state after the loop.
pub(crate) struct Outcome {
    pub mesh: HalfEdgeMesh,
    /// Error radius per half-edge-mesh vertex.
    pub radii: Vec<f64>,
    pub collapses: usize,
    pub locked: LockReport,
}

/// Whether `u` may ever be removed: live, manifold, unlocked and (unless the policy allows
/// it) not on the boundary.
fn removable(mesh: &HalfEdgeMesh, u: VertexId, boundary: BoundaryPolicy) -> bool {
    !mesh.is_deleted_vertex(u)
        && !mesh.is_non_manifold_vertex(u)
        && !mesh.is_locked(u)
        && (boundary == BoundaryPolicy::Collapse || !mesh.is_boundary_vertex(u))
        && mesh.vertex_halfedge(u).is_some()
}

/// The cheapest collapse out of `u`, as a queue [`Entry`]; ties to the lowest half-edge.
///
/// For an interior vertex the fan is projected once and shared by all targets, and only
/// the targets that can still win are evaluated in full ([`Fan::best`]); the result is the
/// minimum of [`collapse_radius`] over the candidate half-edges, bit for bit.
///
/// With [`Topology::Checked`] the candidates are the half-edges that pass
/// [`HalfEdgeMesh::check_collapse`]. With [`Topology::Deferred`] (subset placement only;
/// optimal placement always checks, as its full-edge choice depends on it) the check is
/// left to the loop, which makes it when the entry reaches the front: the entry's radius
/// is then at most the legal one, so taking it for a key keeps the greedy order.
///
/// `fan` is scratch space (any content), reused between calls.
fn best_collapse(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    u: VertexId,
    policy: Policy<'_>,
    topology: Topology,
    fan: &mut Fan,
) -> Option<Entry> {
    if !removable(mesh, u, policy.boundary) {
        return None;
    }
    let weight = policy.weight(mesh, u)?;
    let check = topology == Topology::Checked || policy.quadrics.is_some();
    let legal = |g: HalfEdgeId| !check || mesh.check_collapse(g).is_ok();
    let mut best = best_subset_collapse(mesh, radii, u, policy.boundary, fan, legal);
    if let Some(quadrics) = policy.quadrics
        && let Some((g, target)) = quadric_edge(mesh, quadrics, u, legal)
        && let Some(r) = edge_collapse_radius(mesh, radii, g, target)
        && best.is_none_or(|(c, b)| r.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt())
    {
        best = Some((r, g));
    }
    best.map(|(radius, halfedge)| Entry {
        key: radius / weight,
        radius,
        halfedge,
        checked: check,
    })
}

/// Whether [`best_collapse`] checks the topology of its candidates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Topology {
    /// Only legal collapses.
    Checked,
    /// Every collapse, the check left to the loop (subset placement).
    Deferred,
}

/// The cheapest legal half-edge collapse out of the removable vertex `u` (see
/// [`best_collapse`]).
fn best_subset_collapse(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    u: VertexId,
    boundary: BoundaryPolicy,
    fan: &mut Fan,
    legal: impl Fn(HalfEdgeId) -> bool + Copy,
) -> Option<(f64, HalfEdgeId)> {
    let better = |r: f64, g: HalfEdgeId, best: Option<(f64, HalfEdgeId)>| {
        best.is_none_or(|(c, b)| r.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt())
    };
    let mut best: Option<(f64, HalfEdgeId)> = None;
    if mesh.is_boundary_vertex(u) {
        for g in mesh.outgoing(u) {
            if !legal(g) {
                continue;
            }
            if let Some(r) = collapse_radius(mesh, radii, g, boundary)
                && better(r, g, best)
            {
                best = Some((r, g));
            }
        }
    } else {
        if fan.rebuild(mesh, radii, u) {
            best = fan.best(legal);
        }
        // The simple map where it beats the tight one (see `edge_radius`); its radius is
        // at least `r_u + |u − v|`, which prunes most targets without any work.
        let ru = radii.get(u.0 as usize).copied().unwrap_or(f64::INFINITY);
        let pu = mesh.position(u);
        for g in mesh.outgoing(u) {
            let bound = ru + (mesh.position(mesh.target(g)) - pu).length();
            if best.is_some_and(|(c, _)| bound > c) || !legal(g) {
                continue;
            }
            if let Some(r) = simple_map_radius(mesh, radii, g)
                && better(r, g, best)
            {
                best = Some((r, g));
            }
        }
    }
    best
}

/// [`Placement::Optimal`](crate::Placement::Optimal)'s one full-edge candidate out of `u`:
/// the legal edge whose merged quadric is smallest at the best of its two ends and its
/// midpoint (a cheap stand-in for the optimum; ties to the lowest half-edge), with the
/// quadric-optimal position on it. Only this edge is tried as a full-edge
/// collapse ([`edge_collapse_radius`] costs about six half-edge evaluations), every edge
/// as a half-edge collapse.
fn quadric_edge(
    mesh: &HalfEdgeMesh,
    quadrics: &[Quadric],
    u: VertexId,
    legal: impl Fn(HalfEdgeId) -> bool,
) -> Option<(HalfEdgeId, DVec3)> {
    let qu = *quadrics.get(u.0 as usize)?;
    let pu = mesh.position(u);
    let mut best: Option<(f64, HalfEdgeId, Quadric, DVec3)> = None;
    for g in mesh.outgoing(u) {
        let v = mesh.target(g);
        let Some(&qv) = quadrics.get(v.0 as usize) else {
            continue;
        };
        let q = qu + qv;
        let pv = mesh.position(v);
        let cost = q
            .evaluate(pu)
            .min(q.evaluate(pv))
            .min(q.evaluate(0.5 * (pu + pv)));
        if best.is_none_or(|(c, b, _, _)| cost.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt())
            && legal(g)
        {
            best = Some((cost, g, q, pv));
        }
    }
    best.map(|(_, g, q, pv)| (g, optimal_position(&q, pu, pv)))
}

/// [`Placement::Optimal`](crate::Placement::Optimal): the half-edge collapse `h` onto its
/// target ([`edge_radius`]), or, when `h` is its origin's [`quadric_edge`] and that is
/// strictly better, the full-edge collapse to the quadric-optimal position
/// ([`edge_collapse_radius`]), as `(radius, position of the kept vertex)`. The same choice
/// [`best_collapse`] makes for `h`, so re-validating a popped candidate reproduces its key.
fn optimal_choice(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    quadrics: &[Quadric],
    h: HalfEdgeId,
    boundary: BoundaryPolicy,
) -> Option<(f64, DVec3)> {
    let u = mesh.origin(h);
    let subset = edge_radius(mesh, radii, h, boundary).map(|r| (r, mesh.position(mesh.target(h))));
    let legal = |g: HalfEdgeId| mesh.check_collapse(g).is_ok();
    let full = quadric_edge(mesh, quadrics, u, legal)
        .filter(|&(g, _)| g == h)
        .and_then(|(_, target)| edge_collapse_radius(mesh, radii, h, target).map(|r| (r, target)));
    match (subset, full) {
        (Some(a), Some(b)) => Some(if b.0 < a.0 { b } else { a }),
        (a, b) => a.or(b),
    }
}

/// How candidates are costed: the boundary policy, the optional tolerance weights and, for
/// optimal placement, the vertex quadrics.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Policy<'w> {
    /// Whether boundary vertices may be removed.
    pub boundary: BoundaryPolicy,
    /// Per-vertex tolerance weights (`None`: all 1).
    pub weights: Option<&'w Weights>,
    /// Per-vertex quadrics (`Some` for optimal placement).
    pub quadrics: Option<&'w [Quadric]>,
}

impl<'w> Policy<'w> {
    fn new(
        boundary: BoundaryPolicy,
        weights: Option<&'w Weights>,
        quadrics: Option<&'w [Quadric]>,
    ) -> Self {
        Self {
            boundary,
            weights,
            quadrics,
        }
    }

    /// The weight of every collapse out of `u` (the smallest over its closed one-ring), or
    /// `None` when it is 0 (the collapse is forbidden).
    fn weight(&self, mesh: &HalfEdgeMesh, u: VertexId) -> Option<f64> {
        let w = self.weights.map_or(1.0, |w| w.of_vertex(mesh, u));
        (w > 0.0).then_some(w)
    }

    /// The queue key of collapsing `h` now (its radius over its weight), the radius, and
    /// where the kept vertex goes.
    fn key(&self, mesh: &HalfEdgeMesh, radii: &[f64], h: HalfEdgeId) -> Option<(f64, f64, DVec3)> {
        let weight = self.weight(mesh, mesh.origin(h))?;
        let (r, target) = match self.quadrics {
            Some(quadrics) => optimal_choice(mesh, radii, quadrics, h, self.boundary)?,
            None => (
                edge_radius(mesh, radii, h, self.boundary)?,
                mesh.position(mesh.target(h)),
            ),
        };
        Some((r / weight, r, target))
    }
}

/// The best collapse of each vertex of `vertices`, in order, with the topology check
/// deferred (in parallel with the `parallel` feature: each is a pure function of the mesh
/// and radii, so the result does not depend on the thread count).
fn evaluate_all(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    vertices: &[u32],
    policy: Policy<'_>,
) -> Vec<Option<Entry>> {
    let evaluate = |fan: &mut Fan, &u: &u32| {
        best_collapse(mesh, radii, VertexId(u), policy, Topology::Deferred, fan)
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        // Below this many, one thread is faster than sharing the work.
        const SERIAL_BELOW: usize = 64;
        if vertices.len() >= SERIAL_BELOW {
            return vertices
                .par_iter()
                .with_min_len(16)
                .map_init(Fan::empty, evaluate)
                .collect();
        }
    }
    let mut fan = Fan::empty();
    vertices.iter().map(|u| evaluate(&mut fan, u)).collect()
}

/// The vertices whose queued candidates are out of date.
///
/// A stale vertex is re-evaluated either in the next batch (`list`, all at once and on
/// every core) or, if its queued key was far behind the front when it went stale
/// ([`LAZY_FACTOR`]), only once it reaches the front.
#[derive(Debug)]
struct Stale {
    /// Per vertex: up to date, stale, or stale and in `list`.
    state: Vec<Staleness>,
    /// The stale vertices of the next batch, in the order they went stale.
    list: Vec<u32>,
}

/// Whether a vertex's queued candidate is up to date.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Staleness {
    Fresh,
    /// Re-evaluated when it reaches the front.
    Waiting,
    /// Re-evaluated in the next batch.
    Batched,
}

impl Stale {
    fn new(n: usize) -> Self {
        Self {
            state: vec![Staleness::Fresh; n],
            list: Vec::new(),
        }
    }

    /// Marks `u` stale, for the next batch when `now`, else for when it reaches the front.
    fn mark(&mut self, u: VertexId, now: bool) {
        if let Some(s) = self.state.get_mut(u.0 as usize)
            && *s != Staleness::Batched
        {
            if now {
                *s = Staleness::Batched;
                self.list.push(u.0);
            } else {
                *s = Staleness::Waiting;
            }
        }
    }

    /// Puts every waiting vertex into the next batch; `false` if there was none.
    fn batch_waiting(&mut self) -> bool {
        let before = self.list.len();
        for (u, s) in self.state.iter_mut().enumerate() {
            if *s == Staleness::Waiting {
                *s = Staleness::Batched;
                self.list.push(u as u32);
            }
        }
        self.list.len() > before
    }

    fn contains(&self, u: u32) -> bool {
        self.state
            .get(u as usize)
            .is_some_and(|&s| s != Staleness::Fresh)
    }

    /// Re-evaluates `front` (a stale vertex at the front of the queue) alone while the
    /// batch is smaller than [`MIN_BATCH`] and than the live vertices over
    /// [`BATCH_FRACTION`]; otherwise, or without a front, re-evaluates the batch and the
    /// front together, queueing the new candidates in the order they went stale.
    fn refresh(
        &mut self,
        front: Option<u32>,
        queue: &mut Queue,
        mesh: &HalfEdgeMesh,
        radii: &[f64],
        policy: Policy<'_>,
    ) {
        if let Some(u) = front
            && self.list.len() < MIN_BATCH.min(mesh.live_vertex_count() / BATCH_FRACTION)
        {
            // The front alone; the batch waits until it is large enough to share.
            let best = evaluate_all(mesh, radii, &[u], policy);
            queue.set(u, best.into_iter().next().flatten());
            if let Some(s) = self.state.get_mut(u as usize) {
                *s = Staleness::Fresh;
            }
            self.list.retain(|&x| x != u);
            return;
        }
        if let Some(u) = front {
            self.mark(VertexId(u), true);
        }
        let fresh = evaluate_all(mesh, radii, &self.list, policy);
        for (&u, best) in self.list.iter().zip(fresh) {
            queue.set(u, best);
            if let Some(s) = self.state.get_mut(u as usize) {
                *s = Staleness::Fresh;
            }
        }
        self.list.clear();
    }
}

/// A vertex made stale by a collapse waits for the front of the queue, instead of being
/// put in the next batch, when its queued key exceeds the front's by this factor.
///
/// Measured on the 69k bunny at 10 % (two cores, [`MIN_BATCH`] 512; times noisy), factor:
/// time, bound and certified Hausdorff distance (% of the diagonal): `∞` (every stale
/// vertex batched): 0.49 s, 0.213, 0.167; 4: 0.32–0.36 s, 0.214, 0.167; **2**: 0.20–0.25 s,
/// 0.222, 0.182; 1.5: 0.16 s, 0.238, 0.178; 1: 0.25 s, 0.261, 0.189. A stale key is not a
/// lower bound of the new one (a collapse nearby can make a vertex cheaper), so the
/// lazier, the further the order drifts from the greedy one, and the looser the bound.
const LAZY_FACTOR: f64 = 2.0;

/// A stale front is re-evaluated alone while fewer stale vertices than this wait for a
/// batch: smaller batches do not pay for waking the other cores. On the bunny at 10 %,
/// 512 against re-evaluating the whole batch at every stale front: 20–30 % faster, bound
/// 0.222 % against 0.219 %; on the dragon at 2 %, 25 % faster, bound 0.2288 % against
/// 0.2279 %.
const MIN_BATCH: usize = 512;

/// A batch waits for at most this fraction of the live vertices (one in 64) before it is
/// re-evaluated, so that on a mesh simplified far the order stays close to the greedy
/// one. On the bunny at 2 % it brings the bound from 1.13 % of the diagonal (a fixed 512)
/// to 1.00 % (strict order: 0.96 %), the certified distance from 0.81 % to 0.69 %.
const BATCH_FRACTION: usize = 64;

/// Runs the greedy simplification of `mesh` (whose radii all start at 0).
pub(crate) fn run(
    mut mesh: HalfEdgeMesh,
    stop: Stop,
    settings: Settings<'_>,
    progress: &(dyn Fn(&SimplifyProgress) + Sync),
    mut recorder: Option<&mut Recorder>,
) -> Outcome {
    let Settings {
        weights,
        optimal,
        strict,
    } = settings;
    let mut quadrics = optimal.then(|| vertex_quadrics(&mesh, 0.0));
    let n = mesh.vertex_count();
    let mut radii = vec![0.0; n];
    let mut locked = LockReport::default();
    for x in 0..n {
        let x = VertexId(x as u32);
        if mesh.is_deleted_vertex(x) || mesh.vertex_halfedge(x).is_none() {
            continue;
        }
        if mesh.is_non_manifold_vertex(x) {
            locked.non_manifold += 1;
        } else if stop.boundary == BoundaryPolicy::Lock && mesh.is_boundary_vertex(x) {
            locked.boundary += 1;
        }
    }

    let all: Vec<u32> = (0..n as u32).collect();
    let mut queue = Queue::new(&evaluate_all(
        &mesh,
        &radii,
        &all,
        Policy::new(stop.boundary, weights, quadrics.as_deref()),
    ));
    drop(all);
    let mut stale = Stale::new(n);
    // Whether stale vertices far behind the front may wait (batched order, until the
    // error bound is reached).
    let mut lazy = !strict;
    let mut fan = Fan::empty();

    let mut collapses = 0;
    let start_faces = mesh.live_face_count();
    let to_remove = start_faces.saturating_sub(stop.triangles);
    let report_every = (to_remove / 256).max(1);
    let mut next_report = 0;
    let report = |faces: usize| {
        progress(&SimplifyProgress {
            removed: start_faces - faces,
            to_remove,
        });
    };
    while mesh.live_face_count() > stop.triangles {
        let removed = start_faces - mesh.live_face_count();
        if removed >= next_report {
            report(mesh.live_face_count());
            next_report = removed + report_every;
        }
        let policy = Policy::new(stop.boundary, weights, quadrics.as_deref());
        // Collapses are applied while the first candidate is up to date; when it is not,
        // or the queue ends or passes the bound, the batch of stale vertices is
        // re-evaluated (on every core).
        let top = queue.first();
        let front_is_stale = top.is_some_and(|(t, _)| stale.contains(t));
        if top.is_none_or(|(_, key)| front_is_stale || key > stop.max_radius) {
            if stale.list.is_empty() && !front_is_stale {
                // At the error bound (or out of candidates): the waiting vertices are
                // re-evaluated first, then no vertex waits any more, so that none is
                // left out by its stale key.
                if lazy && stale.batch_waiting() {
                    lazy = false;
                } else {
                    break;
                }
            }
            let front = top.map(|(t, _)| t).filter(|_| front_is_stale);
            stale.refresh(front, &mut queue, &mesh, &radii, policy);
            continue;
        }
        let Some((vertex, entry)) = queue.pop() else {
            break;
        };
        let u = VertexId(vertex);
        let h = entry.halfedge;
        // The candidate is up to date except for its topology, which a change two rings
        // away can alter without making u stale (and which an entry may have deferred).
        if mesh.check_collapse(h).is_err() {
            let best = best_collapse(&mesh, &radii, u, policy, Topology::Checked, &mut fan);
            queue.set(vertex, best);
            continue;
        }
        let (radius, target_position) = match policy.quadrics {
            None => (entry.radius, mesh.position(mesh.target(h))),
            Some(_) => match policy.key(&mesh, &radii, h) {
                Some((key, radius, position)) if key.total_cmp(&entry.key).is_eq() => {
                    (radius, position)
                }
                // Not expected (u is up to date); re-evaluate it if it happens.
                _ => {
                    stale.mark(u, true);
                    continue;
                }
            },
        };
        debug_assert_eq!(
            policy.key(&mesh, &radii, h).map(|k| k.0.to_bits()),
            Some(entry.key.to_bits()),
            "a queued candidate that is not stale is up to date"
        );
        let v = mesh.target(h);
        if let Some(recorder) = recorder.as_deref_mut() {
            recorder.before(&mesh, h, target_position != mesh.position(v));
        }
        if mesh.collapse_edge(h, target_position).is_err() {
            // The checks above passed, so this does not happen; skip the vertex if it does
            // (popping it unqueued it).
            continue;
        }
        collapses += 1;
        if let Some(r) = radii.get_mut(v.0 as usize) {
            *r = radius;
        }
        if let Some(recorder) = recorder.as_deref_mut() {
            recorder.after(&mesh, radius);
        }
        if let Some(q) = quadrics.as_mut()
            && let Some(&qu) = q.get(u.0 as usize)
            && let Some(qv) = q.get_mut(v.0 as usize)
        {
            *qv += qu;
        }
        // v and its neighbours are out of date (u is gone, and popping it unqueued it);
        // those far behind the front wait until they reach it.
        let front = queue.first().map_or(f64::INFINITY, |(_, key)| key);
        stale.mark(v, true);
        for x in mesh.neighbors(v) {
            let far = lazy && queue.key(x.0).is_some_and(|key| key > LAZY_FACTOR * front);
            stale.mark(x, !far);
        }
        if strict {
            let policy = Policy::new(stop.boundary, weights, quadrics.as_deref());
            stale.refresh(None, &mut queue, &mesh, &radii, policy);
        }
    }
    report(mesh.live_face_count());
    Outcome {
        mesh,
        radii,
        collapses,
        locked,
    }
}
