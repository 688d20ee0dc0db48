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
    /// The center: a Voronoi vertex (circumcentre of a Delaunay tetrahedron of samples).
    /// Serialized as `center`; files that say `centre` (written before 0.2) read too.
    #[serde(alias = "centre")]
    pub center: DVec3,
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

#[cfg(test)]
mod tests {
    use super::{MedialSphere, SphereKind};
    use glam::DVec3;

    #[test]
    fn the_center_is_written_center_and_read_under_either_spelling() {
        let sphere = MedialSphere {
            center: DVec3::new(1.0, 2.0, 3.0),
            radius: 0.5,
            error: 0.25,
            closest: DVec3::ZERO,
            kind: SphereKind::Internal,
            covers: vec![1, 2],
        };
        let text = serde_json::to_string(&sphere).expect("serializable");
        assert!(
            text.contains("\"center\"") && !text.contains("centre"),
            "{text}"
        );
        let old = text.replace("\"center\"", "\"centre\"");
        let read: MedialSphere = serde_json::from_str(&old).expect("the old spelling reads");
        assert_eq!(read, sphere);
    }
}
