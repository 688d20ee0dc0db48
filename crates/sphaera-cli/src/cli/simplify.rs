//! Arguments of `sphaera simplify`: the collapse order and the placements offered.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;
use sphaera::simplify::{Order, Placement};

use super::choice::Choice;
use super::{OutputArgs, parse_length};
/// `--order`: the simplifier's collapse orders (every [`Order`]).
pub const ORDERS: &[(Order, &str)] = &[
    (Order::Auto, "Strict below 32,768 vertices, batched above"),
    (
        Order::Strict,
        "The greedy order: the smallest radius first, always (one core)",
    ),
    (
        Order::Batched,
        "Stale candidates re-evaluated in batches on every core (faster on large meshes)",
    ),
];

/// Arguments of `sphaera simplify`.
#[derive(Debug, Args)]
pub struct SimplifyArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    /// Where to write the simplified mesh (`.obj` or `.ply`, written atomically). Without
    /// it, only the figures are printed.
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// Stop at this many triangles.
    #[arg(long, conflicts_with = "ratio")]
    pub triangles: Option<usize>,

    /// Stop at this fraction of the input's triangles, in (0, 1].
    #[arg(long)]
    pub ratio: Option<f64>,

    /// Stop before the error bound exceeds this: an absolute distance (`0.002`) or a
    /// percentage of the bounding-box diagonal (`0.5%`).
    #[arg(long, value_parser = parse_length)]
    pub max_error: Option<Length>,

    /// Keep every boundary vertex in place (the default; gives the tightest bound).
    #[arg(long, conflicts_with = "free_boundary")]
    pub lock_boundary: bool,

    /// Let boundary vertices collapse along boundary edges (looser bound near holes).
    #[arg(long)]
    pub free_boundary: bool,

    /// Where the kept vertex of each collapse goes.
    #[arg(long, default_value = "subset", value_parser = Choice::of(PLACEMENTS))]
    pub placement: Placement,

    /// In which order collapses are applied (the bound is certified with each).
    #[arg(long, default_value = "auto", value_parser = Choice::of(ORDERS))]
    pub order: Order,

    /// After simplifying, also measure the symmetric Hausdorff distance between input and
    /// output: the largest distance from every vertex, edge midpoint and 100,000 random
    /// points of each surface to the other. It is a sampled LOWER bound of the true
    /// distance (the error bound is the certified UPPER bound), and costs about as much as
    /// reading the mesh again.
    #[arg(long)]
    pub measure: bool,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--placement`: where the kept vertex of each collapse goes (every [`Placement`]).
pub const PLACEMENTS: &[(Placement, &str)] = &[
    (
        Placement::Subset,
        "half-edge collapses: every output vertex is an input vertex",
    ),
    (
        Placement::Optimal,
        "full-edge collapses to the quadric-optimal position (when its certified error is smaller)",
    ),
];
