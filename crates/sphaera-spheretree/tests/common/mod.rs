//! What several of this crate's tests build: small trees of procedural shapes.

use sphaera_mesh::TriMesh;
use sphaera_spheretree::{SphereTree, SphereTreeOptions, Surface, build};

/// Small construction options: depth 2, branch 4, 1,200 samples, 120 initial spheres,
/// at least 30 per node (the default method).
pub fn small_options() -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_depth(2)
        .with_branch(4)
        .with_samples(1_200)
        .with_initial_spheres(120)
        .with_min_spheres_per_node(30)
}

/// The tree of `mesh` with [`small_options`].
///
/// # Panics
///
/// If the mesh has no inside or the build fails.
pub fn small_tree(mesh: &TriMesh) -> SphereTree {
    let surface = Surface::new(mesh).expect("the mesh has an inside");
    build(&surface, &small_options()).expect("builds")
}
