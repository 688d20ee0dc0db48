//! Arguments of `sphaera spheretree` and its construction methods.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;
use sphaera::spheretree::{Effort, Method};

use super::choice::Choice;
use super::{OutputArgs, parse_length};

/// Arguments of `sphaera spheretree`.
#[derive(Debug, Args)]
pub struct SpheretreeArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted. A
    /// mesh that encloses a volume is a solid (holes and non-manifold edges are fine); one
    /// that does not (a flat sheet, an open patch) is a shell, which only the minimax
    /// method (auto) covers.
    pub mesh: Option<PathBuf>,

    /// How the tree is built.
    #[arg(long, default_value = "auto", value_parser = Choice::of(METHODS))]
    pub method: Method,

    /// Levels below the root.
    #[arg(long, default_value_t = 3)]
    pub depth: usize,

    /// Children per node at most.
    #[arg(long, default_value_t = 8)]
    pub branch: usize,

    /// Exactly N spheres in one level: a one-level minimax tree (depth 1, branch N, at
    /// most 10,000), reported with its certified error (minimax and auto only).
    #[arg(long, value_name = "N", conflicts_with_all = ["depth", "tolerance", "branch"])]
    pub spheres: Option<usize>,

    /// Surface samples standing for the surface (Poisson-disk, reproducible; the medial
    /// methods and the baselines: minimax works on the triangles themselves).
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,

    /// Spheres of the initial medial approximation (merge, burst, expand, combined).
    #[arg(long, default_value_t = 500)]
    pub initial_spheres: usize,

    /// Medial spheres each node's region is refined to before reduction (merge, burst,
    /// expand, combined).
    #[arg(long, default_value_t = 100)]
    pub min_spheres_per_node: usize,

    /// A node's medial spheres are refined until their worst error is at most this
    /// fraction of the parent's (merge, burst, expand, combined; the paper: ½ to ¼).
    /// Smaller is tighter at levels 2 and 3 and slower.
    #[arg(long, default_value_t = 0.125)]
    pub error_fraction: f64,

    /// Forming points of Hubbard's static medial approximation (hubbard only).
    #[arg(long, default_value_t = 600)]
    pub forming_points: usize,

    /// Build until every leaf's certified error is at most this, refining only the nodes
    /// that exceed it, each into the fewest children (at most `--branch`) that meet it,
    /// as deep as needed (minimax and auto only; instead of `--depth`): an absolute
    /// distance (`0.002`) or a percentage of the bounding-box diagonal (`2%`). Leaves
    /// then end at different depths, so each level is reported as its cut: the level's
    /// nodes and the leaves above it, which together cover the surface.
    #[arg(long, value_parser = parse_length, conflicts_with = "depth")]
    pub tolerance: Option<Length>,

    /// With `--tolerance`: the most nodes (spheres of every level together) the tree may
    /// have (at most 2^21). A tolerance that needs more is refused, before the work
    /// where the count is known in advance, with the figures reached; never more nodes.
    #[arg(long, value_name = "N", requires = "tolerance")]
    pub max_nodes: Option<usize>,

    /// How hard the minimax method works for tighter spheres (minimax and auto only).
    #[arg(long, default_value = "default", value_parser = Choice::of(EFFORTS))]
    pub effort: Effort,

    /// Skip the certified evaluation of every level (worst error by branch and bound,
    /// coverage on 100,000 independent samples); report the construction error only.
    #[arg(long)]
    pub no_evaluation: bool,

    /// Seed of the surface sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Write the tree, atomically: `.json` (levels, spheres, errors, parents, children,
    /// coverage certificates), `.sph` (the classic sphere-tree format: a complete
    /// `branch`-ary tree with a slot for every possible node, so a deep tree may not fit)
    /// or `.yaml` (a motion planner's `collision_spheres` list: the tree's leaves, which
    /// meet `--tolerance` when it is given).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--method`: the minimax construction, the paper's reducers, and the classic baselines
/// for comparison (every [`Method`], in the order `--help` lists them).
pub const METHODS: &[(Method, &str)] = &[
    (
        Method::Minimax,
        "The minimax construction: each region tiled by triangle pieces and divided between \
         the children whose worst error is least; builds to a depth, a tolerance or a sphere \
         count, and covers sheets (surfaces without inside)",
    ),
    (
        Method::Auto,
        "The default: the best method for the surface, today minimax",
    ),
    (
        Method::Merge,
        "The paper's reducer: merge neighbouring medial spheres, tightest result first",
    ),
    (
        Method::Burst,
        "The paper's reducer: burst medial spheres, handing their points to the spheres \
         closest to covering them",
    ),
    (
        Method::Expand,
        "The paper's reducer: expand the medial spheres to a common standoff and select a \
         covering subset",
    ),
    (
        Method::Combined,
        "The paper's best: merge and expand per node, keeping the tighter",
    ),
    (
        Method::Octree,
        "Baseline: an octree's occupied cells, each in its circumscribed sphere",
    ),
    (
        Method::Grid,
        "Baseline: per level a regular grid of about branch^level occupied cells",
    ),
    (
        Method::Hubbard,
        "Baseline: Hubbard's static medial spheres merged by enclosing spheres",
    ),
];

/// `--effort`: every [`Effort`].
pub const EFFORTS: &[(Effort, &str)] = &[
    (
        Effort::Quick,
        "One start per division, one round of refinement: for previews",
    ),
    (
        Effort::Default,
        "Several starts, four rounds of refinement, swaps at the root",
    ),
    (
        Effort::Thorough,
        "Twice the starts, six rounds; never looser than the default's tree",
    ),
];
