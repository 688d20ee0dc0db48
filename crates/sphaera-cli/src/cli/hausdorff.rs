//! Arguments of `sphaera hausdorff` and its engines.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use sphaera::mesh::Length;

use super::{OutputArgs, parse_length};
/// `sphaera hausdorff --engine`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HausdorffEngineArg {
    /// `sphaera_sweep::hausdorff`: triangle trees, every core.
    Trees,
    /// `sphaera_sweep::meshsweeper_hausdorff`: the paper's engine on hierarchies.
    Meshsweeper,
}

/// Arguments of `sphaera hausdorff`.
#[derive(Debug, Args)]
pub struct HausdorffArgs {
    /// The first mesh (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub a: Option<PathBuf>,

    /// The second mesh; when omitted, the first mesh simplified to 15 % of its triangles
    /// (then the simplifier's certified error bound is reported beside the distance).
    pub b: Option<PathBuf>,

    /// Stop once `upper − lower` is at most this: an absolute distance (`1e-4`) or a
    /// percentage of the bounding-box diagonal of both meshes (`0.001%`).
    #[arg(long, value_parser = parse_length, default_value = "0.001%")]
    pub tolerance: Length,

    /// Only the one-sided distance from A to B (default: symmetric).
    #[arg(long)]
    pub one_sided: bool,

    /// Stop refining after this many samples (the bounds stay certified, only wider).
    #[arg(long, default_value_t = 20_000_000)]
    pub max_samples: usize,

    /// The engine: `trees` (exact queries from triangle trees, every core; the fastest)
    /// or `meshsweeper` (the paper's, on hierarchies of error spheres, one thread).
    #[arg(long, value_enum, default_value_t = HausdorffEngineArg::Trees)]
    pub engine: HausdorffEngineArg,

    /// Write mesh A as a PLY whose vertices are coloured by their distance to B, blue
    /// (0) to red (the largest), written atomically.
    #[arg(long)]
    pub colors: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}
