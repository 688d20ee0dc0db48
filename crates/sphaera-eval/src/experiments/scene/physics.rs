//! The falling-objects simulation in rapier: the same bodies, masses and start poses with
//! three kinds of colliders, timed per step, and the contacts it ends with measured on the
//! true meshes.

use std::time::Instant;

use anyhow::{Context, Result};
use rapier3d_f64::prelude::*;
use sphaera::mesh::geometry::Similarity;
use sphaera::mesh::{DVec3, Sphere, Surface, TriMesh};

/// Bodies dropped into the box.
pub(super) const BODIES: usize = 200;

/// Simulated steps (at 60 Hz: four seconds, enough for the pile to settle).
pub(super) const STEPS: usize = 240;

/// Half the inner width of the box, in object sizes (every object is scaled to a
/// bounding-box diagonal of 1).
const HALF_WIDTH: f64 = 3.2;

/// One kind of object: its mesh scaled to a diagonal of 1 and centred, with what the
/// measurement needs.
pub(super) struct Object {
    /// The mesh in the body's frame (diagonal 1, centre of its bounding box at the origin).
    pub(super) mesh: TriMesh,
    /// Its inside test and exact closest points.
    pub(super) surface: Surface,
    /// A sphere around it.
    pub(super) bound: Sphere,
    /// The same mass properties for every collider of it.
    pub(super) mass: MassProperties,
}

impl Object {
    /// `mesh` scaled to a diagonal of 1 and centred.
    pub(super) fn new(name: &str, mesh: &TriMesh) -> Result<Self> {
        let mesh = crate::rapier_shapes::unit_size(mesh)?;
        let surface = Surface::new(&mesh).with_context(|| format!("{name}: no inside"))?;
        let bound = sphaera::mesh::geometry::minimum_enclosing_ball(mesh.positions())?;
        // A solid box of the mesh's extent, of density 1: the same dynamics for every
        // collider, so only the contact geometry differs between runs.
        let extent = mesh.bounding_box().max - mesh.bounding_box().min;
        let mass = extent.x * extent.y * extent.z;
        let inertia = DVec3::new(
            extent.y * extent.y + extent.z * extent.z,
            extent.x * extent.x + extent.z * extent.z,
            extent.x * extent.x + extent.y * extent.y,
        ) * (mass / 12.0);
        Ok(Self {
            mesh,
            surface,
            bound,
            mass: MassProperties::new(DVec3::ZERO, mass, inertia),
        })
    }
}

/// Where body `i` starts: a column of layers over the box, each turned at random (a fixed
/// sequence), and which object it is.
pub(super) fn start_poses(objects: usize) -> Vec<(usize, Pose)> {
    let per_side = 5;
    let spacing = 1.15;
    let mut rng = sphaera_tests::random::SplitMix64::new(0x9e37_79b9_7f4a_7c15);
    let mut next = || rng.unit_by_max();
    (0..BODIES)
        .map(|i| {
            let (layer, k) = (i / (per_side * per_side), i % (per_side * per_side));
            let x = (k % per_side) as f64 - (per_side - 1) as f64 / 2.0;
            let z = (k / per_side) as f64 - (per_side - 1) as f64 / 2.0;
            let translation = DVec3::new(x * spacing, 1.0 + layer as f64 * spacing, z * spacing);
            let axis = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5)
                .try_normalize()
                .unwrap_or(DVec3::Y);
            let angle = next() * std::f64::consts::TAU;
            (i % objects, Pose::new(translation, axis * angle))
        })
        .collect()
}

/// What one simulation gave.
pub(super) struct Run {
    /// Mean wall time of a step, in milliseconds.
    pub(super) step_ms: f64,
    /// The bodies' final poses.
    pub(super) poses: Vec<Pose>,
    /// Pairs of bodies in contact at the end (`None`: the floor).
    pub(super) contacts: Vec<(usize, Option<usize>)>,
}

/// Drops the bodies with `shapes[i]` as body `i`'s collider and simulates [`STEPS`] steps
/// on one thread.
pub(super) fn simulate(
    objects: &[Object],
    starts: &[(usize, Pose)],
    shapes: Vec<SharedShape>,
) -> Result<Run> {
    let mut world = PhysicsWorld::new();
    // The box: a floor whose top is y = 0 and four walls.
    let wall = 0.5;
    let height = 12.0;
    let floor = ColliderBuilder::cuboid(HALF_WIDTH + wall, wall, HALF_WIDTH + wall)
        .translation(DVec3::new(0.0, -wall, 0.0));
    let floor_handle = world.colliders.insert(floor);
    for (x, z, hx, hz) in [
        (HALF_WIDTH + wall, 0.0, wall, HALF_WIDTH),
        (-HALF_WIDTH - wall, 0.0, wall, HALF_WIDTH),
        (0.0, HALF_WIDTH + wall, HALF_WIDTH, wall),
        (0.0, -HALF_WIDTH - wall, HALF_WIDTH, wall),
    ] {
        world.colliders.insert(
            ColliderBuilder::cuboid(hx, height / 2.0, hz).translation(DVec3::new(
                x,
                height / 2.0,
                z,
            )),
        );
    }
    let mut handles = Vec::with_capacity(starts.len());
    for (&(object, pose), shape) in starts.iter().zip(shapes) {
        let body = RigidBodyBuilder::dynamic().pose(pose);
        let collider = ColliderBuilder::new(shape)
            .mass_properties(objects[object].mass)
            .friction(0.6);
        let (handle, collider) = world.insert(body, collider);
        handles.push((handle, collider));
    }
    let started = Instant::now();
    for _ in 0..STEPS {
        world.step();
    }
    let step_ms = started.elapsed().as_secs_f64() * 1e3 / STEPS as f64;
    let body_of = |c: ColliderHandle| handles.iter().position(|&(_, h)| h == c);
    let mut contacts = Vec::new();
    for pair in world.narrow_phase.contact_pairs() {
        if !pair.has_any_active_contact() {
            continue;
        }
        match (body_of(pair.collider1), body_of(pair.collider2)) {
            (Some(a), Some(b)) => contacts.push((a.min(b), Some(a.max(b)))),
            (Some(a), None) | (None, Some(a))
                if pair.collider1 == floor_handle || pair.collider2 == floor_handle =>
            {
                contacts.push((a, None));
            }
            _ => {}
        }
    }
    contacts.sort_unstable();
    let poses = handles
        .iter()
        .map(|&(h, _)| {
            world
                .bodies
                .get(h)
                .map_or(Pose::IDENTITY, |b| *b.position())
        })
        .collect();
    Ok(Run {
        step_ms,
        poses,
        contacts,
    })
}

/// How the true meshes relate where the simulation says bodies touch.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Errors {
    /// The deepest penetration of one true mesh into another (or below the floor), in
    /// object sizes.
    pub(super) max_penetration: f64,
    /// The mean gap between true meshes over contacts where they do not touch, in object
    /// sizes: the over-approximation the colliders showed.
    pub(super) mean_gap: f64,
    /// The largest such gap.
    pub(super) max_gap: f64,
    /// Contacts measured.
    pub(super) contacts: usize,
}

/// The penetration or the gap of every contact of `run`, on the true meshes.
pub(super) fn measure(objects: &[Object], starts: &[(usize, Pose)], run: &Run) -> Result<Errors> {
    let mut errors = Errors::default();
    let mut gaps = 0.0;
    let mut gap_count = 0usize;
    let posed = |i: usize| -> (usize, Similarity) {
        let (object, _) = starts[i];
        let pose = run.poses[i];
        let similarity = Similarity::from_rotation_translation(pose.rotation, pose.translation)
            .unwrap_or(Similarity::IDENTITY);
        (object, similarity)
    };
    for &(a, b) in &run.contacts {
        let (oa, pa) = posed(a);
        let (depth, gap) = match b {
            None => {
                let lowest = objects[oa]
                    .mesh
                    .positions()
                    .iter()
                    .map(|&p| pa.point(p).y)
                    .fold(f64::INFINITY, f64::min);
                ((-lowest).max(0.0), lowest.max(0.0))
            }
            Some(b) => {
                let (ob, pb) = posed(b);
                let ab = relation(&objects[oa], &pa, &objects[ob], &pb)?;
                let ba = relation(&objects[ob], &pb, &objects[oa], &pa)?;
                (ab.0.max(ba.0), ab.1.min(ba.1))
            }
        };
        errors.contacts += 1;
        errors.max_penetration = errors.max_penetration.max(depth);
        if depth == 0.0 {
            gaps += gap;
            gap_count += 1;
            errors.max_gap = errors.max_gap.max(gap);
        }
    }
    errors.mean_gap = if gap_count == 0 {
        0.0
    } else {
        gaps / gap_count as f64
    };
    Ok(errors)
}

/// How far the vertices of `a` reach into `b` (the deepest one inside, 0 if none) and how
/// close they come to it (the nearest one outside: at least the true gap, and within the
/// meshes' vertex spacing of it), both posed.
fn relation(a: &Object, pa: &Similarity, b: &Object, pb: &Similarity) -> Result<(f64, f64)> {
    let b_bound = pb.sphere(&b.bound);
    let world_to_b = |p: DVec3| {
        let q = p - pb.translation();
        pb.rotation().inverse() * q / pb.scale()
    };
    let mut deepest: f64 = 0.0;
    let mut nearest = f64::INFINITY;
    for &p in a.mesh.positions() {
        let world = pa.point(p);
        // Outside `b`'s bounding sphere: not inside, and no nearer than the sphere.
        let outside_bound = world.distance(b_bound.center) - b_bound.radius;
        if outside_bound > 0.0 && outside_bound >= nearest {
            continue;
        }
        let local = world_to_b(world);
        let distance = b.surface.closest(local)?.distance;
        if b.surface.is_inside(local) {
            deepest = deepest.max(distance);
        } else {
            nearest = nearest.min(distance);
        }
    }
    Ok((deepest, nearest))
}
