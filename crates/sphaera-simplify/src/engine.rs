//! The greedy collapse loop: a priority queue of per-vertex best collapses, ordered by the
//! error-sphere radius they would need, re-evaluated around every applied collapse.
//!
//! # Performance
//!
//! After each collapse `u → v` the kept vertex `v` and its neighbours are re-evaluated
//! (about 9 vertices on a mesh of valence 6); each re-evaluation builds the projected fan
//! once ([`Fan`]) and prunes targets by lower bounds, so it costs `O(d²)` arithmetic for
//! valence `d` plus a few ring walks, and the candidate queue ([`queue`]) holds one entry
//! per vertex. The initial evaluation of all vertices runs on `rayon` with the `parallel`
//! feature (same candidates, so the same result). Measured on the 69k-triangle bunny at
//! 10 %: about 20 µs of CPU per applied collapse on the 2-core reference machine, the
//! time going to fan construction (loading the neighbours' positions), the lifts of `u`,
//! the spoke crossings and the topology checks in roughly equal parts.

mod queue;

use smallvec::SmallVec;
use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

use crate::edge_radius::edge_collapse_radius;
use crate::quadric::{Quadric, optimal_position, vertex_quadrics};
use crate::record::Recorder;
use crate::simplifier::{LockReport, SimplifyProgress};
use crate::spheres::{BoundaryPolicy, Fan, collapse_radius, edge_radius, simple_map_radius};
use crate::weights::Weights;
use glam::DVec3;
use queue::Queue;

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

/// The cheapest legal collapse out of `u`: `(radius, half-edge)`, ties to the lowest
/// half-edge.
///
/// For an interior vertex the fan is projected once and shared by all targets, and only
/// the targets that can still win are evaluated in full ([`Fan::best`]); the result is the
/// minimum of [`collapse_radius`] over the half-edges that pass
/// [`HalfEdgeMesh::check_collapse`], bit for bit.
///
/// `fan` is scratch space (any content), reused between calls.
fn best_collapse(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    u: VertexId,
    policy: Policy<'_>,
    fan: &mut Fan,
) -> Option<(f64, HalfEdgeId)> {
    if !removable(mesh, u, policy.boundary) {
        return None;
    }
    let weight = policy.weight(mesh, u)?;
    let legal = |g: HalfEdgeId| mesh.check_collapse(g).is_ok();
    let mut best = best_subset_collapse(mesh, radii, u, policy.boundary, fan, legal);
    if let Some(quadrics) = policy.quadrics
        && let Some((g, target)) = quadric_edge(mesh, quadrics, u, legal)
        && let Some(r) = edge_collapse_radius(mesh, radii, g, target)
        && best.is_none_or(|(c, b)| r.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt())
    {
        best = Some((r, g));
    }
    best.map(|(r, g)| (r / weight, g))
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

/// The best collapse of every vertex, in vertex order (in parallel with the `parallel`
/// feature; each entry is a pure function of the mesh, so the result is the same).
fn initial_candidates(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    policy: Policy<'_>,
) -> Vec<Option<(f64, HalfEdgeId)>> {
    let n = mesh.vertex_count() as u32;
    let evaluate = |fan: &mut Fan, u: u32| best_collapse(mesh, radii, VertexId(u), policy, fan);
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n)
            .into_par_iter()
            .map_init(Fan::empty, evaluate)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut fan = Fan::empty();
        (0..n).map(|u| evaluate(&mut fan, u)).collect()
    }
}

/// Re-evaluates `u` and makes its best collapse its current candidate (`fan`: scratch).
fn refresh(
    queue: &mut Queue,
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    u: VertexId,
    policy: Policy<'_>,
    fan: &mut Fan,
) {
    let best = best_collapse(mesh, radii, u, policy, fan);
    let same = match (best, queue.get(u.0)) {
        (Some((c, h)), Some((d, g))) => c.total_cmp(&d).is_eq() && h == g,
        (None, None) => true,
        _ => false,
    };
    if !same {
        queue.set(u.0, best);
    }
}

/// Runs the greedy simplification of `mesh` (whose radii all start at 0).
pub(crate) fn run(
    mut mesh: HalfEdgeMesh,
    stop: Stop,
    weights: Option<&Weights>,
    optimal: bool,
    progress: &(dyn Fn(&SimplifyProgress) + Sync),
    mut recorder: Option<&mut Recorder>,
) -> Outcome {
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

    let mut queue = Queue::new(&initial_candidates(
        &mesh,
        &radii,
        Policy::new(stop.boundary, weights, quadrics.as_deref()),
    ));
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
        let Some(top) = queue.pop() else { break };
        if top.cost > stop.max_radius {
            break;
        }
        let u = VertexId(top.vertex);
        let policy = Policy::new(stop.boundary, weights, quadrics.as_deref());
        // Re-check the candidate: a change two rings away can alter the link condition
        // without re-evaluating u.
        let h = HalfEdgeId(top.halfedge);
        let fresh = mesh
            .check_collapse(h)
            .ok()
            .and_then(|()| policy.key(&mesh, &radii, h));
        let Some((_, radius, target_position)) =
            fresh.filter(|(key, _, _)| key.total_cmp(&top.cost).is_eq())
        else {
            refresh(&mut queue, &mesh, &radii, u, policy, &mut fan);
            continue;
        };
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
        let policy = Policy::new(stop.boundary, weights, quadrics.as_deref());
        // Re-evaluate v and its neighbours (u is gone, and popping it unqueued it).
        let ring: SmallVec<[VertexId; 16]> = std::iter::once(v).chain(mesh.neighbors(v)).collect();
        for x in ring {
            refresh(&mut queue, &mesh, &radii, x, policy, &mut fan);
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
