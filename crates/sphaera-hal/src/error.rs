//! What can go wrong building or querying a HAL tree.

use std::path::PathBuf;

/// Why a HAL tree cannot be built or asked something.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HalError {
    /// Too few vertices: a polygon needs three, a polyline two.
    #[error("a {shape} needs at least {needed} vertices, got {count}")]
    TooFewVertices {
        /// `"polygon"` or `"polyline"`.
        shape: &'static str,
        /// The vertices given.
        count: usize,
        /// The vertices needed.
        needed: usize,
    },
    /// More vertices than 32-bit indices address.
    #[error("{count} vertices are more than a HAL tree indexes (at most u32::MAX − 1)")]
    TooManyVertices {
        /// The vertices given.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y})")]
    NonFinite {
        /// The vertex's index.
        vertex: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// Point inclusion asked of an open polyline, which has no inside.
    #[error("an open polyline has no inside: point inclusion needs a closed polygon")]
    OpenPolyline,
    /// A ring of a polygon with holes is an open polyline.
    #[error("ring {ring} of the polygon is an open polyline: a polygon's rings are closed")]
    OpenRing {
        /// The ring (0 the exterior, `k` the hole `k − 1`).
        ring: usize,
    },
    /// A multipolygon with no polygon.
    #[error("the multipolygon has no polygon")]
    EmptyMultiPolygon,
    /// A ring of a multipolygon is not a valid outline.
    #[error("polygon {polygon}, {}: {source}", ring_name(*ring))]
    Ring {
        /// The polygon's index (from 0).
        polygon: usize,
        /// The ring (0 the exterior, `k` the hole `k − 1`).
        ring: usize,
        /// What is wrong with it.
        source: Box<HalError>,
    },
    /// A polygon file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A line of a points file is not two (2D) or three (3D) finite numbers.
    #[error("line {line}: expected {columns} finite numbers (`x y` or `x y z`), found `{text}`")]
    Parse {
        /// The line number (from 1).
        line: usize,
        /// How many numbers a line needs.
        columns: usize,
        /// The line's text.
        text: String,
    },
    /// A 3D HAL tree needs a closed surface.
    #[error(
        "the mesh is not closed ({boundary_edges} boundary edges): a HAL tree needs a closed surface of genus 0; close the holes first (sphaera-mesh's repair), or use a sphere-tree, which takes open meshes"
    )]
    NotClosed {
        /// Edges with one triangle.
        boundary_edges: usize,
    },
    /// A 3D HAL tree needs a manifold surface.
    #[error(
        "the mesh is not manifold ({edges} edges with more than two triangles, {vertices} pinched vertices): a HAL tree needs a closed manifold surface of genus 0"
    )]
    NonManifold {
        /// Edges shared by more than two triangles.
        edges: usize,
        /// Vertices whose triangles do not form one fan.
        vertices: usize,
    },
    /// A 3D HAL tree needs consistently oriented triangles.
    #[error(
        "the mesh's triangles are not consistently oriented ({edges} edges traversed the same way by both triangles): orient them first (sphaera-mesh's repair)"
    )]
    NotOriented {
        /// Edges whose two triangles traverse them the same way.
        edges: usize,
    },
    /// A 3D HAL tree represents one closed surface.
    #[error(
        "the mesh has {count} components: a HAL tree represents one closed surface; build one tree per component"
    )]
    Components {
        /// The connected components.
        count: usize,
    },
    /// The paper: "it works only for objects of genus zero".
    #[error(
        "the surface has genus {genus} ({genus} handle(s), like a torus): HAL trees work only for genus 0 (the paper's own limit); for collision or distance use a sphere-tree (`sphaera spheretree`) or Meshsweeper (`sphaera distance`), which take any genus"
    )]
    NotGenusZero {
        /// The genus found.
        genus: u64,
    },
    /// A placement that is not a proper similarity.
    #[error(
        "the placement is not a rotation with a uniform scale and a translation (linear part {matrix:?}, column-major): shears, uneven scales and mirrors do not map discs to discs of the same bulge"
    )]
    InvalidPlacement {
        /// The linear part, column-major.
        matrix: [f64; 4],
    },
    /// Every vertex lies on one line: no ball touches three of them.
    #[error("every vertex of the mesh lies on one line: no ball touches three of them")]
    Degenerate,
    /// An error of the mesh crate (the smallest bounding disc or ball).
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
}

/// "the exterior" or "hole k" (from 0) for ring `ring` of a polygon.
fn ring_name(ring: usize) -> String {
    if ring == 0 {
        "the exterior".to_owned()
    } else {
        format!("hole {}", ring - 1)
    }
}
