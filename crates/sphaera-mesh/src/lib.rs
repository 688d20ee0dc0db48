//! Indexed triangle meshes for Sphaera (crate docs are written at the end of the foundation issue).

#![cfg_attr(docsrs, feature(doc_cfg))]

mod aabb;
mod error;
pub mod geometry;
pub mod io;
mod mesh;
pub mod sampling;
pub mod shapes;
mod sphere;
pub mod topology;
pub mod winding;

pub use aabb::Aabb;
pub use error::MeshError;
pub use glam;
pub use glam::DVec3;
pub use mesh::TriMesh;
pub use sphere::Sphere;
