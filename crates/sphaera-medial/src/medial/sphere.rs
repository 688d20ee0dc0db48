//! One sphere of a medial approximation.

use glam::DVec3;

/// Where a sphere comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum SphereKind {
    /// Centred on an internal Voronoi vertex: a medial sphere.
    Internal,
    /// Centred on an external Voronoi vertex, not part of the set (only listed by
    /// [`MedialApproximation::voronoi_spheres`](crate::MedialApproximation::voronoi_spheres)).
    External,
    /// Centred on an external Voronoi vertex and added to cover samples no medial sphere
    /// covers.
    Cover,
}

/// A sphere of the approximation.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MedialSphere {
    /// The centre: a Voronoi vertex (circumcentre of a Delaunay tetrahedron of samples).
    pub centre: DVec3,
    /// The radius: the distance to its four forming samples.
    pub radius: f64,
    /// How far the sphere can reach beyond the surface: `r − d` for a centre inside
    /// (the paper's eq. 2, `d` the distance from the centre to the surface), `r + d` for a
    /// centre outside. An upper bound of the largest distance from a point of the sphere
    /// outside the object to the surface.
    pub error: f64,
    /// The closest surface point to the centre (where a new sample goes to replace it).
    pub closest: DVec3,
    /// Internal, external or cover.
    pub kind: SphereKind,
    /// Indices of the surface samples it covers.
    pub covers: Vec<u32>,
}
