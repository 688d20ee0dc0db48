//! The generated tables of closest points, Hausdorff distances and the medial approximation.

use super::super::spec::{ANY, Format, Table, col};
#[allow(clippy::wildcard_imports)]
use super::filters::*;

/// The tables of this group.
pub(super) const TABLES: &[Table] = &[
    // docs/benchmarks.md, "Hausdorff distance": seconds per engine and tolerance on the
    // 69k bunny against its 15 % simplification.
    Table {
        name: "hausdorff_gap_vs_time",
        csv: "hausdorff_gap_vs_time",
        key: &["method"],
        keep: |row| {
            row.get("file") == Some("stanford-bunny.obj") && row.get("method") != Some("naive")
        },
        columns: &[
            col(
                "bunny 69k vs qem15, seconds",
                "method",
                ANY,
                Format::Label(HAUSDORFF_ENGINES),
            ),
            col(
                "1e-3",
                "seconds",
                &[("tolerance_relative", "1.000000e-3")],
                Format::Decimals(3),
            ),
            col(
                "1e-4",
                "seconds",
                &[("tolerance_relative", "1.000000e-4")],
                Format::Decimals(3),
            ),
            col(
                "1e-5",
                "seconds",
                &[("tolerance_relative", "1.000000e-5")],
                Format::Decimals(3),
            ),
            col(
                "1e-6",
                "seconds",
                &[("tolerance_relative", "1.000000e-6")],
                Format::Decimals(3),
            ),
        ],
    },
    // docs/benchmarks.md, "Coherence against the step length": per mesh and step (every
    // decade), each engine's speed relative to parry.
    Table {
        name: "sweep_speedup_vs_step",
        csv: "sweep_speedup_vs_step",
        key: &["mesh", "step_rel_diagonal"],
        keep: |row| {
            row.get("step_rel_diagonal")
                .is_some_and(|s| s.starts_with("1e"))
        },
        columns: &[
            col("mesh", "mesh", ANY, Format::CodeFileName),
            col(
                "step (of the diagonal)",
                "step_rel_diagonal",
                ANY,
                Format::Right,
            ),
            col(
                "cursor × parry",
                "speed_relative_to_parry",
                &[("method", "tree_cursor")],
                Format::Decimals(2),
            ),
            col(
                "tree × parry",
                "speed_relative_to_parry",
                &[("method", "triangle_tree")],
                Format::Decimals(2),
            ),
            col(
                "session × parry",
                "speed_relative_to_parry",
                &[("method", "meshsweeper_session")],
                Format::Decimals(2),
            ),
        ],
    },
    // docs/benchmarks.md, "Queries per second, one thread": per query set, every engine on
    // the 69k bunny and the 871k dragon.
    Table {
        name: "sweep_throughput",
        csv: "sweep_throughput",
        key: &["query_set"],
        keep: |row| {
            matches!(
                row.get("file"),
                Some("stanford-bunny.obj" | "dragon_vrip.ply")
            )
        },
        columns: &[
            col("", "query_set", ANY, Format::Text),
            col(
                "bunny 69k: tree",
                "queries_per_second",
                &[("file", "stanford-bunny.obj"), ("method", "triangle_tree")],
                Format::Rate,
            ),
            col(
                "cursor",
                "queries_per_second",
                &[("file", "stanford-bunny.obj"), ("method", "tree_cursor")],
                Format::Rate,
            ),
            col(
                "tree anytime 1 %",
                "queries_per_second",
                &[
                    ("file", "stanford-bunny.obj"),
                    ("method", "tree_anytime_1%"),
                ],
                Format::Rate,
            ),
            col(
                "paper's session",
                "queries_per_second",
                &[
                    ("file", "stanford-bunny.obj"),
                    ("method", "meshsweeper_session"),
                ],
                Format::Rate,
            ),
            col(
                "paper's anytime 1 %",
                "queries_per_second",
                &[
                    ("file", "stanford-bunny.obj"),
                    ("method", "meshsweeper_anytime_1%"),
                ],
                Format::Rate,
            ),
            col(
                "parry",
                "queries_per_second",
                &[("file", "stanford-bunny.obj"), ("method", "parry3d")],
                Format::Rate,
            ),
            col(
                "dragon 871k: tree",
                "queries_per_second",
                &[("file", "dragon_vrip.ply"), ("method", "triangle_tree")],
                Format::Rate,
            ),
            col(
                "cursor",
                "queries_per_second",
                &[("file", "dragon_vrip.ply"), ("method", "tree_cursor")],
                Format::Rate,
            ),
            col(
                "tree anytime 1 %",
                "queries_per_second",
                &[("file", "dragon_vrip.ply"), ("method", "tree_anytime_1%")],
                Format::Rate,
            ),
            col(
                "paper's session",
                "queries_per_second",
                &[
                    ("file", "dragon_vrip.ply"),
                    ("method", "meshsweeper_session"),
                ],
                Format::Rate,
            ),
            col(
                "paper's anytime 1 %",
                "queries_per_second",
                &[
                    ("file", "dragon_vrip.ply"),
                    ("method", "meshsweeper_anytime_1%"),
                ],
                Format::Rate,
            ),
            col(
                "parry",
                "queries_per_second",
                &[("file", "dragon_vrip.ply"), ("method", "parry3d")],
                Format::Rate,
            ),
        ],
    },
    // docs/benchmarks.md, "Static against adaptive (the paper's Figs. 10–13)": per mesh
    // and method, four of the six sizes.
    Table {
        name: "medial_static_vs_adaptive",
        csv: "medial_static_vs_adaptive",
        key: &["file", "method", "parameter"],
        keep: |row| match row.get("method") {
            Some("adaptive") => {
                matches!(row.get("parameter"), Some("100" | "400" | "1600" | "3200"))
            }
            _ => matches!(row.get("parameter"), Some("40" | "160" | "640" | "1280")),
        },
        columns: &[
            col("mesh", "file", ANY, Format::CodeFileName),
            col("method", "method", ANY, Format::Label(MEDIAL_METHODS)),
            col(
                "target / forming points",
                "parameter",
                ANY,
                Format::Grouped(0),
            ),
            col("spheres", "spheres", ANY, Format::Grouped(0)),
            col(
                "worst error",
                "worst_error_pct_diag",
                ANY,
                Format::Significant(3),
            ),
            col(
                "uncovered surface %",
                "uncovered_surface_pct",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "largest gap",
                "largest_gap_pct_diag",
                ANY,
                Format::Decimals(2),
            ),
        ],
    },
];
