//! The greedy collapse loop: a priority queue of per-vertex best collapses, ordered by the
//! error-sphere radius they would need, re-evaluated lazily with version stamps.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

use crate::record::Recorder;
use crate::simplifier::{LockReport, Progress};
use crate::spheres::{BoundaryPolicy, collapse_radius};

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

/// A queued candidate: the cheapest collapse out of `vertex` when it was evaluated.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    cost: f64,
    vertex: u32,
    halfedge: u32,
    stamp: u32,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Candidate {}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Candidate {
    /// Reversed (the heap is a max-heap): the lowest cost first, then the lowest vertex,
    /// half-edge and stamp, so the order is total and deterministic.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .cost
            .total_cmp(&self.cost)
            .then(other.vertex.cmp(&self.vertex))
            .then(other.halfedge.cmp(&self.halfedge))
            .then(other.stamp.cmp(&self.stamp))
    }
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
fn best_collapse(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    u: VertexId,
    boundary: BoundaryPolicy,
) -> Option<(f64, HalfEdgeId)> {
    if !removable(mesh, u, boundary) {
        return None;
    }
    let mut best: Option<(f64, HalfEdgeId)> = None;
    for g in mesh.outgoing(u) {
        if mesh.check_collapse(g).is_err() {
            continue;
        }
        if let Some(r) = collapse_radius(mesh, radii, g, boundary) {
            let better = best.is_none_or(|(c, b)| r.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt());
            if better {
                best = Some((r, g));
            }
        }
    }
    best
}

/// Runs the greedy simplification of `mesh` (whose radii all start at 0).
pub(crate) fn run(
    mut mesh: HalfEdgeMesh,
    stop: Stop,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
    mut recorder: Option<&mut Recorder>,
) -> Outcome {
    let n = mesh.vertex_count();
    let mut radii = vec![0.0; n];
    let mut stamps = vec![0_u32; n];
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

    let mut heap = BinaryHeap::new();
    let push = |heap: &mut BinaryHeap<Candidate>,
                mesh: &HalfEdgeMesh,
                radii: &[f64],
                u: u32,
                stamp: u32| {
        if let Some((cost, h)) = best_collapse(mesh, radii, VertexId(u), stop.boundary) {
            heap.push(Candidate {
                cost,
                vertex: u,
                halfedge: h.0,
                stamp,
            });
        }
    };
    for u in 0..n as u32 {
        push(&mut heap, &mesh, &radii, u, 0);
    }

    let mut collapses = 0;
    let start_faces = mesh.live_face_count();
    let to_remove = start_faces.saturating_sub(stop.triangles);
    let report_every = (to_remove / 256).max(1);
    let mut next_report = 0;
    let report = |faces: usize| {
        if let Some(callback) = progress {
            callback(Progress {
                removed: start_faces - faces,
                to_remove,
            });
        }
    };
    while mesh.live_face_count() > stop.triangles {
        let removed = start_faces - mesh.live_face_count();
        if removed >= next_report {
            report(mesh.live_face_count());
            next_report = removed + report_every;
        }
        let Some(top) = heap.pop() else { break };
        let u = top.vertex as usize;
        if stamps.get(u) != Some(&top.stamp) {
            continue;
        }
        if top.cost > stop.max_radius {
            break;
        }
        // Re-check the candidate: a change two rings away can alter the link condition
        // without bumping u's stamp.
        let h = HalfEdgeId(top.halfedge);
        let fresh = mesh
            .check_collapse(h)
            .ok()
            .and_then(|()| collapse_radius(&mesh, &radii, h, stop.boundary));
        let Some(radius) = fresh.filter(|r| r.total_cmp(&top.cost).is_eq()) else {
            stamps[u] = stamps[u].wrapping_add(1);
            push(&mut heap, &mesh, &radii, top.vertex, stamps[u]);
            continue;
        };
        let v = mesh.target(h);
        let target_position = mesh.position(v);
        if let Some(recorder) = recorder.as_deref_mut() {
            recorder.before(&mesh, h);
        }
        if mesh.collapse_edge(h, target_position).is_err() {
            // The checks above passed, so this does not happen; skip the vertex if it does.
            stamps[u] = stamps[u].wrapping_add(1);
            continue;
        }
        collapses += 1;
        if let Some(r) = radii.get_mut(v.0 as usize) {
            *r = radius;
        }
        if let Some(recorder) = recorder.as_deref_mut() {
            recorder.after(&mesh, radius);
        }
        stamps[u] = stamps[u].wrapping_add(1);
        let ring: Vec<VertexId> = std::iter::once(v).chain(mesh.neighbors(v)).collect();
        for x in ring {
            let i = x.0 as usize;
            stamps[i] = stamps[i].wrapping_add(1);
            push(&mut heap, &mesh, &radii, x.0, stamps[i]);
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
