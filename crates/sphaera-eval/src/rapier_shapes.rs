//! What the rapier comparisons share (the `scene_time_vs_error` experiment and the
//! `scene_vs_rapier` bench): meshes scaled to a size of 1, and sphere sets as rapier
//! colliders.

use anyhow::Result;
use rapier3d_f64::prelude::{Pose, SharedShape};
use sphaera::mesh::{Sphere, TriMesh};

/// `mesh` scaled to a bounding-box diagonal of 1, the centre of its bounding box at the
/// origin.
///
/// # Errors
///
/// When the scaled mesh is not valid (an empty mesh, or one of zero size).
pub fn unit_size(mesh: &TriMesh) -> Result<TriMesh> {
    let center = mesh.bounding_box().center();
    let scale = 1.0 / mesh.bounding_box_diagonal();
    let positions = mesh
        .positions()
        .iter()
        .map(|&p| (p - center) * scale)
        .collect();
    Ok(TriMesh::new(positions, mesh.triangles().to_vec())?)
}

/// `spheres` as one rapier compound of balls.
#[must_use]
pub fn ball_compound(spheres: &[Sphere]) -> SharedShape {
    SharedShape::compound(
        spheres
            .iter()
            .map(|s| {
                (
                    Pose::from_translation(s.center),
                    SharedShape::ball(s.radius),
                )
            })
            .collect(),
    )
}
