//! The command line, declared with clap.

mod choice;
mod distance;
mod hal;
mod hausdorff;
mod medial;
mod scene;
mod silhouette;
mod simplify;
mod spheretree;
mod urdf;
mod view;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use sphaera::mesh::Length;

pub use distance::DistanceArgs;
pub use hal::HalArgs;
pub use hausdorff::{HausdorffArgs, HausdorffEngineArg};
pub use medial::MedialArgs;
pub use scene::SceneArgs;
pub use silhouette::SilhouetteArgs;
pub use simplify::SimplifyArgs;
pub use spheretree::SpheretreeArgs;
pub use urdf::UrdfArgs;
pub use view::ViewArgs;

/// Hierarchical sphere-based approximation of triangle meshes.
///
/// Every MESH argument may be omitted: the embedded low-resolution Stanford bunny
/// (public domain, 3,674 triangles) is used instead. Supported formats: OBJ, PLY (ASCII
/// and binary), STL (ASCII and binary), OFF, glTF 2.0 (`.gltf` with its buffer files or
/// `data:` URIs, binary `.glb`; the default scene's triangle meshes, placed by their node
/// transforms and merged).
#[derive(Debug, Parser)]
#[command(name = "sphaera", version)]
pub struct Cli {
    /// Hide progress bars.
    #[arg(long, short, global = true)]
    pub quiet: bool,

    /// The largest file read, in bytes: meshes, points, polygons, trees, scenes, URDFs and
    /// the files they name (2 GiB by default). A larger file is refused with its size
    /// before it is read; devices, named pipes and folders are refused whatever the cap.
    #[arg(long, global = true, value_name = "BYTES", value_parser = file_cap)]
    pub max_file_bytes: Option<u64>,

    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands: one per capability.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Describe a mesh: counts, bounding box, topology (closed, manifold, genus,
    /// components, boundary loops), degenerate and duplicate triangles.
    Info(InfoArgs),
    /// Simplify a mesh by edge collapses, with an error bound that holds both ways: every
    /// input point is within the bound of the output and every output point within the
    /// bound of the input.
    Simplify(SimplifyArgs),
    /// Exact closest points on a mesh (Meshsweeper): for points read from a file or drawn
    /// at random in the mesh's bounding box scaled 1.5x.
    Distance(DistanceArgs),
    /// Certified Hausdorff distance between two meshes (Meshsweeper, section 6): a lower
    /// and an upper bound at most `--tolerance` apart, where the maximum is reached, and
    /// optionally a PLY of the first mesh coloured by its distance to the second.
    Hausdorff(HausdorffArgs),
    /// Spheres around a mesh from its medial axis. `--spheres N` gives exactly N spheres
    /// covering the whole surface (certified by construction): the minimax cover, whose
    /// centres are medial candidates moved on the exact surface; it also covers flat
    /// sheets. Otherwise the adaptive medial-axis approximation (Bradshaw and O'Sullivan
    /// 2004, section 4): spheres on the internal Voronoi vertices of surface samples, plus
    /// cover spheres, so that every sample is covered, improved by replacing the worst
    /// sphere until `--medial-target` spheres (500 by default; the set then has at least
    /// that many) or `--max-error` is reached, then certified to cover the whole surface,
    /// not only the samples, growing the few spheres that must grow (as every sphere-tree
    /// level is); `--samples-only` skips that.
    Medial(MedialArgs),
    /// Sphere-tree for collision detection: the root is the mesh's minimum enclosing ball
    /// and each node's part of the surface is divided between at most `--branch`
    /// children, to `--depth` levels, or only where needed until every leaf is within
    /// `--tolerance` (as deep as that takes), or into exactly `--spheres` N spheres in one
    /// level. The default method (auto, today minimax) also covers flat sheets and open
    /// patches; the paper's methods (Bradshaw and O'Sullivan 2004) need a solid. The
    /// minimax and the paper's methods certify that every level covers the whole surface;
    /// the baselines (octree, grid, hubbard) do not: their coverage is measured on samples
    /// and reported. Every level's worst error is bounded by branch and bound and
    /// reported. The main job: with no arguments it builds the embedded bunny's tree.
    Spheretree(SpheretreeArgs),
    /// HAL tree (Veltkamp): a polygon kept as a binary tree of approximations by its own
    /// vertices, each part bounded by the intersection of two discs through its ends.
    /// Reports vertices and covering width per level, an adaptive approximation to
    /// `--tolerance`, point inclusion for a file of points; draws the approximation with
    /// its bounding areas as SVG. A mesh file (OBJ, PLY, STL, OFF, glTF/GLB; closed, genus 0) gets
    /// the 3D tree: triangles and width per level, an adaptive approximation written as a
    /// mesh.
    Hal(HalArgs),
    /// Silhouette-preserving level of detail (Mata, Pastor and Rodríguez): distance labels
    /// from a camera every `--step` degrees say how far each vertex lies from the
    /// silhouette; the mesh's progressive hierarchy is refined for one view so that the
    /// contour region keeps `--factor` times the error allowed elsewhere, each region with
    /// its certified bound. Pictures: the labels as grey levels seen from the view, and the
    /// silhouettes of the original and the result overlaid.
    Silhouette(SilhouetteArgs),
    /// Model no more than a scene needs, and no less. Reads a scene file (JSON: meshes,
    /// instances with poses, a camera) or mesh files (one instance each, side by side),
    /// builds each mesh's model once (a base sphere-tree and a simplification
    /// hierarchy), then gives every instance the coarsest sphere-tree cut and mesh level
    /// whose certified error meets `--tolerance` (pixels on the camera's image, a
    /// percentage of each object, or world units): a model whose trees do not reach
    /// that builds a minimax tree to it, once, refined only where needed. Then finds
    /// every contact within `--budget` (a broad phase, then every close pair's finest
    /// trees descended together, level by level). Reports the choices, their certified
    /// errors, the trees built, and the spheres and triangles saved against full
    /// detail; a tolerance that cannot be met is an error naming the model and the
    /// figures. With no input: eight embedded bunnies going away from the camera, two
    /// of them touching.
    Scene(SceneArgs),
    /// Whole-robot sphere models for motion planners (also `sphaera robot`). Reads a URDF,
    /// loads every link's collision (or `--visual`) meshes in the link's frame with their
    /// origins and scales (`package://` against the URDF's folder, relative paths against
    /// the URDF), and spherizes the links in parallel: meshes (solids, or shells when open
    /// or flat) by a minimax sphere-tree whose spheres cover every point of the surface by
    /// construction and whose protrusion is certified, boxes, cylinders, spheres and
    /// capsules analytically. Exactly `--spheres-per-link N` spheres per link, a
    /// `--budget N` divided among the links summing to N, or a `--tolerance` every link
    /// meets with as few spheres as it needs (fewer spheres than asked only where a link
    /// cannot use them, and the report says why). Writes the spherized URDF, MoveIt's SRDF
    /// sphere approximations, cuRobo's collision-sphere YAML or JSON (`-o`, the format from
    /// the extension or `--format`), and reports per link the spheres, the certified worst
    /// and the 95th-percentile protrusion, the coverage and the time (`--json` for JSON).
    #[command(visible_alias = "robot")]
    Urdf(UrdfArgs),
    /// One self-contained HTML page (three.js inlined, opens offline in any browser)
    /// showing the mesh and its sphere-tree: a level slider, the spheres translucent,
    /// each level's worst sphere in red, and every level's certified error in a side
    /// panel. The tree is built as the main job builds it, or read with `--tree`. Also
    /// the rungs of a simplification (`--simplify`), HAL approximations (`--hal`), the
    /// distance to another mesh as colours (`--hausdorff`) and silhouette labels in grey
    /// levels (`--silhouette`). With no arguments: the embedded bunny.
    View(ViewArgs),
}

/// A length on the command line: an absolute distance (`0.002`) or a percentage of the
/// bounding-box diagonal (`2%`), as [`Length`]'s `FromStr` reads it.
fn parse_length(text: &str) -> Result<Length, String> {
    text.parse()
        .map_err(|e: sphaera::mesh::ParseLengthError| e.to_string())
}

/// Arguments of `sphaera info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    #[command(flatten)]
    pub output: OutputArgs,
}

/// How a result is printed; shared by every subcommand.
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Print the result as one JSON document on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

/// A file size cap: a whole number of bytes, at least one.
fn file_cap(text: &str) -> Result<u64, String> {
    match text.parse::<u64>() {
        Ok(0) => Err("a file cap of 0 bytes would refuse every file; give at least 1".to_owned()),
        Ok(bytes) => Ok(bytes),
        Err(error) => Err(format!("not a whole number of bytes ({error})")),
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn max_error_takes_distances_and_percentages() {
        assert_eq!(parse_length("0.002"), Ok(Length::Absolute(0.002)));
        assert_eq!(parse_length("0.5%"), Ok(Length::RelativeToDiagonal(0.005)));
        assert!(parse_length("abc").is_err());
        assert!(parse_length("-1").is_err());
        assert!(parse_length("NaN%").is_err());
    }
}
