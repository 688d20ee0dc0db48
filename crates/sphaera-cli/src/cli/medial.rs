//! Arguments of `sphaera medial` and its cover criteria.

use std::path::PathBuf;

use clap::Args;
use sphaera::medial::CoverCriterion;
use sphaera::mesh::Length;

use super::choice::Choice;
use super::{OutputArgs, parse_length};
/// Arguments of `sphaera medial`.
#[derive(Debug, Args)]
pub struct MedialArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted. The
    /// adaptive approximation needs a mesh that encloses a volume (holes and non-manifold
    /// edges are fine; a flat sheet is not); `--spheres` covers sheets too.
    pub mesh: Option<PathBuf>,

    /// Exactly N spheres covering the whole surface (certified by construction), at most
    /// 10,000: the minimax cover (a one-level minimax sphere-tree), each sphere's centre a
    /// medial candidate moved on the exact surface so that the worst sphere's error is
    /// least. Without it: the adaptive approximation (`--medial-target`, `--max-error`).
    #[arg(
        long,
        value_name = "N",
        conflicts_with_all = [
            "medial_target", "max_error", "static_points", "samples", "cover",
            "samples_only", "seed",
        ]
    )]
    pub spheres: Option<usize>,

    /// The adaptive approximation: improve until the set has at least this many spheres
    /// (its cover spheres can add more; default 500 when neither `--spheres` nor
    /// `--max-error` is given).
    #[arg(long, value_name = "M", conflicts_with = "max_error")]
    pub medial_target: Option<usize>,

    /// The adaptive approximation: improve until no sphere reaches farther than this
    /// beyond the surface: an absolute distance (`0.002`) or a percentage of the
    /// bounding-box diagonal (`1%`). It bounds the medial spheres; the surface
    /// certificate's growth can add to a few of them (the report gives the error before
    /// and after; more `--samples` shrink the growth).
    #[arg(long, value_parser = parse_length)]
    pub max_error: Option<Length>,

    /// Surface samples that must be covered (Poisson-disk, reproducible).
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,

    /// How an uncovered sample chooses its cover sphere.
    #[arg(long, default_value = "smallest-error", value_parser = Choice::of(COVERS))]
    pub cover: CoverCriterion,

    /// Hubbard's static baseline instead: the Voronoi diagram of this many samples, no
    /// improvement, coverage of the samples not completed (the surface certificate still
    /// grows spheres to cover the whole surface, unless `--samples-only`).
    #[arg(long, conflicts_with_all = ["medial_target", "max_error"])]
    pub static_points: Option<usize>,

    /// Skip the surface certificate: the spheres then cover the surface samples only, and
    /// parts of the surface between samples may lie outside every sphere. By default every
    /// point of every triangle is certified to lie in some sphere: each triangle is split
    /// until every piece lies in one sphere, and where a piece 1/1000 of the bounding-box
    /// diagonal long lies in none, the sphere needing the least growth grows to contain
    /// it (raising that sphere's error, which can take the worst error past
    /// `--max-error`).
    #[arg(long)]
    pub samples_only: bool,

    /// Seed of the surface sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Write the spheres as JSON (the coverage guarantee and certificate; per sphere its
    /// centre, radius, error, kind, covered sample count and certificate growth),
    /// atomically.
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--cover`: the paper's two criteria (every [`CoverCriterion`]).
pub const COVERS: &[(CoverCriterion, &str)] = &[
    (
        CoverCriterion::SmallestError,
        "The candidate sphere with the smallest error (tighter)",
    ),
    (
        CoverCriterion::LargestCoverage,
        "The candidate sphere covering the most uncovered samples (fewer cover spheres)",
    ),
];
