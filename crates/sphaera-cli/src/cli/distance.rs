//! Arguments of `sphaera distance`.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;

use super::{OutputArgs, parse_length};
/// Arguments of `sphaera distance`.
#[derive(Debug, Args)]
pub struct DistanceArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    /// A text file of query points, one `x y z` per line (spaces or commas; `#` starts a
    /// comment).
    #[arg(long, conflicts_with = "random")]
    pub points: Option<PathBuf>,

    /// Query this many points drawn uniformly in the bounding box scaled 1.5x (the default,
    /// with 1,000, when no `--points` file is given).
    #[arg(long)]
    pub random: Option<usize>,

    /// The seed of `--random`.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Stop each query once its certified interval is at most this wide: an absolute
    /// distance (`0.001`) or a percentage of the bounding-box diagonal (`0.1%`). Without
    /// it, every answer is exact.
    #[arg(long, value_parser = parse_length)]
    pub tolerance: Option<Length>,

    #[command(flatten)]
    pub print: OutputArgs,
}
