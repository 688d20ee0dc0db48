//! Arguments of `sphaera simplify`: the collapse order and the placements offered.

use std::path::PathBuf;

use clap::{Args, ValueEnum, builder::PossibleValue};
use sphaera::mesh::Length;
use sphaera::simplify::{Order, Placement};

use super::{OutputArgs, parse_length};
/// `--order`: the simplifier's collapse order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OrderArg {
    /// Strict below 32,768 vertices, batched above.
    Auto,
    /// The greedy order: the smallest radius first, always (one core).
    Strict,
    /// Stale candidates re-evaluated in batches on every core (faster on large meshes).
    Batched,
}

impl OrderArg {
    /// The simplifier's order.
    pub fn order(self) -> Order {
        match self {
            Self::Auto => Order::Auto,
            Self::Strict => Order::Strict,
            Self::Batched => Order::Batched,
        }
    }

    /// The name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Strict => "strict",
            Self::Batched => "batched",
        }
    }
}

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
    #[arg(long, value_enum, default_value = PLACEMENTS[0].0)]
    pub placement: PlacementArg,

    /// In which order collapses are applied (the bound is certified with each).
    #[arg(long, value_enum, default_value_t = OrderArg::Auto)]
    pub order: OrderArg,

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

/// The placements offered by `--placement`: name, placement, help. The first is the
/// default. One line per placement.
pub const PLACEMENTS: &[(&str, Placement, &str)] = &[
    (
        "subset",
        Placement::Subset,
        "half-edge collapses: every output vertex is an input vertex",
    ),
    (
        "optimal",
        Placement::Optimal,
        "full-edge collapses to the quadric-optimal position (when its certified error is smaller)",
    ),
];

/// A `--placement` value: an index into [`PLACEMENTS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlacementArg(usize);

/// Every `--placement` value, in the order of [`PLACEMENTS`].
static PLACEMENT_ARGS: [PlacementArg; PLACEMENTS.len()] = {
    let mut all = [PlacementArg(0); PLACEMENTS.len()];
    let mut i = 0;
    while i < all.len() {
        all[i] = PlacementArg(i);
        i += 1;
    }
    all
};

impl PlacementArg {
    /// The placement's name on the command line and in reports.
    pub fn name(self) -> &'static str {
        PLACEMENTS.get(self.0).map_or(PLACEMENTS[0].0, |p| p.0)
    }

    /// The simplifier's placement.
    pub fn placement(self) -> Placement {
        PLACEMENTS.get(self.0).map_or(PLACEMENTS[0].1, |p| p.1)
    }
}

impl ValueEnum for PlacementArg {
    fn value_variants<'a>() -> &'a [Self] {
        &PLACEMENT_ARGS
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        PLACEMENTS
            .get(self.0)
            .map(|&(name, _, help)| PossibleValue::new(name).help(help))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placements_parse_by_name() {
        for (i, &(name, placement, _)) in PLACEMENTS.iter().enumerate() {
            let parsed = PlacementArg::from_str(name, false).expect("a known placement");
            assert_eq!(parsed, PlacementArg(i));
            assert_eq!(parsed.name(), name);
            assert_eq!(parsed.placement(), placement);
        }
        assert!(PlacementArg::from_str("nowhere", false).is_err());
    }
}
