//! The generated tables of the sphere-trees, the main job, the robots and the peer morphit-rs.

use super::super::spec::{ANY, Aggregate, Column, Filter, Format, Table, col};
#[allow(clippy::wildcard_imports)]
use super::filters::*;

/// The Sphaera row of `spheres_vs_count.csv`.
const SPHAERA: Filter = &[("method", "sphaera")];
/// morphit-rs as it returns its spheres.
const RAW: Filter = &[("method", "morphit_raw")];
/// morphit-rs grown to cover.
const GROWN: Filter = &[("method", "morphit_grown")];

/// The upper end of the worst error at one level of `spheretree_similarity.csv`, over
/// the trees of one mesh: their spread (largest / smallest) or their range.
const fn similarity(header: &'static str, level: Filter, aggregate: Aggregate) -> Column {
    let format = match aggregate {
        Aggregate::Spread => Format::Decimals(3),
        Aggregate::Range => Format::Decimals(2),
    };
    col(header, "worst_error_upper_pct_diag", level, format).over_rows(aggregate)
}

/// The tables of this group.
pub(super) const TABLES: &[Table] = &[
    // docs/benchmarks.md, "Spheres against morphit-rs (issue 36)": per mesh and N,
    // Sphaera against the peer raw and grown.
    Table {
        name: "spheres_vs_count",
        csv: "spheres_vs_count",
        key: &["mesh", "requested"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::FileName),
            col("N", "requested", ANY, Format::Right),
            col("Sphaera spheres", "spheres", SPHAERA, Format::Right),
            col(
                "Sphaera worst %",
                "worst_upper_pct",
                SPHAERA,
                Format::Decimals(2),
            ),
            col(
                "Sphaera uncovered %",
                "uncovered_pct",
                SPHAERA,
                Format::Decimals(1),
            ),
            col("morphit spheres", "spheres", RAW, Format::Right),
            col("raw worst %", "worst_upper_pct", RAW, Format::Decimals(2)),
            col("raw uncovered %", "uncovered_pct", RAW, Format::Decimals(1)),
            col(
                "grown worst %",
                "worst_upper_pct",
                GROWN,
                Format::Decimals(2),
            ),
            col(
                "Sphaera / grown",
                "protrusion_vs_grown",
                SPHAERA,
                Format::Decimals(2),
            ),
            col("Sphaera s", "seconds", SPHAERA, Format::Decimals(2)),
            col("morphit s", "seconds", RAW, Format::Decimals(2)),
            col("time ratio", "time_vs_peer", SPHAERA, Format::Decimals(2)),
            col("verdict", "verdict", SPHAERA, Format::Text),
        ],
    },
    // crates/sphaera-spheretree/src/performance.md (the crate docs), its README and
    // docs/benchmarks.md, "The main job": the default tree of three meshes, built and
    // certified as the CLI does.
    Table {
        name: "main_job",
        csv: "main_job",
        key: &["mesh"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::CodeFileName),
            col("triangles", "triangles", ANY, Format::Right),
            col("build s", "build_seconds", ANY, Format::Decimals(2)),
            col(
                "certified evaluation s",
                "evaluation_seconds",
                ANY,
                Format::Decimals(2),
            ),
            col("total s", "total_seconds", ANY, Format::Decimals(2)),
            col(
                "L1 worst %",
                "worst_upper_pct",
                LEVEL_1,
                Format::Decimals(2),
            ),
            col(
                "L2 worst %",
                "worst_upper_pct",
                LEVEL_2,
                Format::Decimals(2),
            ),
            col(
                "L3 worst %",
                "worst_upper_pct",
                LEVEL_3,
                Format::Decimals(2),
            ),
            col("L3 spheres", "spheres", LEVEL_3, Format::Right),
            col(
                "L1 check %",
                "check_upper_pct",
                LEVEL_1,
                Format::Decimals(2),
            ),
            col(
                "L2 check %",
                "check_upper_pct",
                LEVEL_2,
                Format::Decimals(2),
            ),
            col(
                "L3 check %",
                "check_upper_pct",
                LEVEL_3,
                Format::Decimals(2),
            ),
        ],
    },
    // docs/benchmarks.md, "Trees to a tolerance": per mesh and tolerance.
    Table {
        name: "tolerance_trees",
        csv: "tolerance_trees",
        key: &["mesh", "tolerance_pct"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::FileName),
            col("tolerance %", "tolerance_pct", ANY, Format::Right),
            col("leaves", "leaves", ANY, Format::Right),
            col("nodes", "nodes", ANY, Format::Right),
            col("levels", "levels", ANY, Format::Right),
            col(
                "worst leaf bound %",
                "leaf_bound_pct",
                ANY,
                Format::Decimals(3),
            ),
            col(
                "evaluated worst %",
                "evaluated_upper_pct",
                ANY,
                Format::Decimals(3),
            ),
            col("met", "met", ANY, Format::Text),
            col(
                "check without bounds %",
                "check_interval_pct",
                ANY,
                Format::Text,
            ),
            col("build s", "build_seconds", ANY, Format::Decimals(2)),
        ],
    },
    // docs/benchmarks.md, "Sphere-trees", "Charts": per mesh and method the certified worst
    // error per level, with the toolkit's figures and issue 36's target on the bunny.
    Table {
        name: "spheretree_error_vs_level",
        csv: "spheretree_error_vs_level",
        key: &["file", "method"],
        keep: |_| true,
        columns: &[
            col("mesh", "file", ANY, Format::FileName),
            col("method", "method", ANY, Format::Text),
            col("source", "source", ANY, Format::Text),
            col(
                "L1 worst %",
                "worst_error_upper_pct_diag",
                LEVEL_1,
                Format::Decimals(2),
            ),
            col(
                "L2 worst %",
                "worst_error_upper_pct_diag",
                LEVEL_2,
                Format::Decimals(2),
            ),
            col(
                "L3 worst %",
                "worst_error_upper_pct_diag",
                LEVEL_3,
                Format::Decimals(2),
            ),
            col("L3 spheres", "spheres", LEVEL_3, Format::Right),
            col("build s", "build_seconds", ANY, Format::Decimals(2)),
        ],
    },
    // crates/sphaera-robot/src/performance.md (the crate docs), its README and
    // docs/benchmarks.md, "Whole robots": per budget, both robots.
    Table {
        name: "robot_budgets",
        csv: "robot_budgets",
        key: &["budget"],
        keep: |_| true,
        columns: &[
            col("budget", "budget", ANY, Format::Text),
            col("Panda spheres", "spheres", PANDA, Format::Right),
            col(
                "Panda worst mm",
                "worst_protrusion_mm",
                PANDA,
                Format::Decimals(1),
            ),
            col(
                "Panda % of a link",
                "worst_share_pct",
                PANDA,
                Format::Decimals(1),
            ),
            col("Panda s", "seconds", PANDA, Format::Decimals(1)),
            col("KUKA spheres", "spheres", KUKA, Format::Right),
            col(
                "KUKA worst mm",
                "worst_protrusion_mm",
                KUKA,
                Format::Decimals(1),
            ),
            col(
                "KUKA % of a link",
                "worst_share_pct",
                KUKA,
                Format::Decimals(1),
            ),
            col("KUKA s", "seconds", KUKA, Format::Decimals(1)),
        ],
    },
    // docs/benchmarks.md, "Worst protrusion against spheres per link": every link at 40
    // spheres, Sphaera against the voxel baseline.
    Table {
        name: "robot_protrusion_vs_spheres",
        csv: "robot_protrusion_vs_spheres",
        key: &["robot", "link"],
        keep: |row| row.get("spheres_per_link") == Some("40"),
        columns: &[
            col("robot", "robot", ANY, Format::FileName),
            col("link", "link", ANY, Format::Text),
            col("Sphaera spheres", "spheres", ROBOT_SPHAERA, Format::Right),
            col(
                "worst mm",
                "worst_protrusion_mm",
                ROBOT_SPHAERA,
                Format::Decimals(2),
            ),
            col(
                "% of diagonal",
                "protrusion_pct_of_diagonal",
                ROBOT_SPHAERA,
                Format::Decimals(2),
            ),
            col("baseline spheres", "spheres", VOXELS, Format::Right),
            col(
                "baseline worst mm",
                "worst_protrusion_mm",
                VOXELS,
                Format::Decimals(2),
            ),
            col(
                "Sphaera / baseline",
                "worst_vs_baseline",
                ROBOT_SPHAERA,
                Format::Decimals(2),
            ),
        ],
    },
    // docs/benchmarks.md, "Whole robots against morphit-rs": per robot and count, the
    // whole-robot rows (link `(robot)`).
    Table {
        name: "robot_vs_morphit",
        csv: "robot_vs_morphit",
        key: &["robot", "spheres_per_link"],
        keep: |row| row.get("link") == Some("(robot)"),
        columns: &[
            col("robot", "robot", ANY, Format::Text),
            col("per link", "spheres_per_link", ANY, Format::Right),
            col(
                "Sphaera worst mm",
                "worst_protrusion_mm",
                ROBOT_SPHAERA,
                Format::Decimals(1),
            ),
            col(
                "Sphaera uncovered %",
                "uncovered_pct",
                ROBOT_SPHAERA,
                Format::Decimals(1),
            ),
            col("Sphaera s", "seconds", ROBOT_SPHAERA, Format::Decimals(2)),
            col(
                "morphit worst mm",
                "worst_protrusion_mm",
                MORPHIT_RAW,
                Format::Decimals(1),
            ),
            col(
                "morphit uncovered %",
                "uncovered_pct",
                MORPHIT_RAW,
                Format::Decimals(1),
            ),
            col(
                "morphit grown worst mm",
                "worst_protrusion_mm",
                MORPHIT_GROWN,
                Format::Decimals(1),
            ),
            col("morphit s", "seconds", MORPHIT_RAW, Format::Decimals(2)),
        ],
    },
    // docs/benchmarks.md, "Stability under similarity transforms": per mesh and level, the
    // spread of the certified worst error (upper end) over the tree of the mesh as given
    // and its 20 transformed copies, and its smallest and largest value.
    Table {
        name: "spheretree_similarity",
        csv: "spheretree_similarity",
        key: &["mesh"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::Label(SIMILARITY_MESHES)),
            similarity("L1 spread", LEVEL_1, Aggregate::Spread),
            similarity("L1 worst %, min–max", LEVEL_1, Aggregate::Range),
            similarity("L2 spread", LEVEL_2, Aggregate::Spread),
            similarity("L2 worst %, min–max", LEVEL_2, Aggregate::Range),
            similarity("L3 spread", LEVEL_3, Aggregate::Spread),
            similarity("L3 worst %, min–max", LEVEL_3, Aggregate::Range),
        ],
    },
];
