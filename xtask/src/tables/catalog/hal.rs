//! The generated tables of hAL trees.

use super::super::spec::{ANY, Format, Table, col};
#[allow(clippy::wildcard_imports)]
use super::filters::*;

/// The tables of this group.
pub(super) const TABLES: &[Table] = &[
    // docs/benchmarks.md, "HAL trees", "Point inclusion": per outline, µs per query, on
    // points spread over the bounding box and on points near the outline.
    Table {
        name: "hal_query_speed",
        csv: "hal_query_speed",
        key: &["polygon"],
        keep: |row| row.get("points") == Some("box"),
        columns: QUERY_SPEED_COLUMNS,
    },
    Table {
        name: "hal_query_speed_near",
        csv: "hal_query_speed",
        key: &["polygon"],
        keep: |row| row.get("points") == Some("near"),
        columns: QUERY_SPEED_COLUMNS,
    },
    // docs/benchmarks.md, "HAL trees", "Multipolygons": per country, µs per query.
    Table {
        name: "hal_multipolygon_speed",
        csv: "hal_multipolygon_speed",
        key: &["country"],
        keep: |_| true,
        columns: &[
            col("country", "country", ANY, Format::Text),
            col("polygons", "polygons", ANY, Format::Grouped(0)),
            col("rings", "rings", ANY, Format::Grouped(0)),
            col("vertices", "vertices", ANY, Format::Grouped(0)),
            col(
                "HAL build ms",
                "build_seconds",
                HAL_MULTIPOLYGON,
                Format::Decimals(2),
            )
            .times(1000.0),
            col(
                "HAL",
                "microseconds_per_query",
                HAL_MULTIPOLYGON,
                Format::Grouped(2),
            ),
            col(
                "brute force",
                "microseconds_per_query",
                BRUTE_FORCE,
                Format::Grouped(2),
            ),
            col(
                "geo `contains`",
                "microseconds_per_query",
                &[("method", "geo contains")],
                Format::Grouped(2),
            ),
            col(
                "brute / HAL",
                "microseconds_per_query",
                BRUTE_FORCE,
                Format::Times(0),
            )
            .over("microseconds_per_query", HAL_MULTIPOLYGON),
        ],
    },
    // docs/benchmarks.md, "HAL trees", "Approximation": the 2D outlines' adaptive
    // approximation at 2^-10 of the diagonal.
    Table {
        name: "hal_width_vs_size_2d",
        csv: "hal_width_vs_size",
        key: &["polygon"],
        keep: |row| {
            row.get("polygon")
                .is_some_and(|p| p.starts_with("polygons/"))
        },
        columns: &[
            col("outline", "polygon", ANY, Format::Label(HAL_OUTLINES)),
            col("vertices", "vertices", UNIFORM, Format::Grouped(0)).last(),
            col(
                "adaptive approximation at tolerance 2⁻¹⁰ of the diagonal: vertices",
                "vertices",
                &[
                    ("approximation", "adaptive"),
                    ("level_or_tolerance", "2^-10"),
                ],
                Format::Grouped(0),
            ),
        ],
    },
    // docs/benchmarks.md, "HAL trees", "3D widths": the meshes' adaptive approximations.
    Table {
        name: "hal_width_vs_size_3d",
        csv: "hal_width_vs_size",
        key: &["polygon"],
        keep: |row| {
            row.get("polygon")
                .is_some_and(|p| !p.starts_with("polygons/"))
        },
        columns: &[
            col("mesh", "polygon", ANY, Format::FileStem),
            col("triangles", "vertices", UNIFORM, Format::Grouped(0)).last(),
            col(
                "adaptive at 2⁻⁵ of the diagonal (width ≤ 3.1 %): triangles",
                "vertices",
                &[
                    ("approximation", "adaptive"),
                    ("level_or_tolerance", "2^-5"),
                ],
                Format::Grouped(0),
            ),
            col(
                "adaptive at 2⁻⁷ (≤ 0.78 %): triangles",
                "vertices",
                &[
                    ("approximation", "adaptive"),
                    ("level_or_tolerance", "2^-7"),
                ],
                Format::Grouped(0),
            ),
        ],
    },
    // docs/benchmarks.md, "Is HAL a good simplifier?": per mesh at 2^-5 and 2^-7.
    Table {
        name: "hal_vs_simplify",
        csv: "hal_vs_simplify",
        key: &["mesh", "hal_tolerance"],
        keep: |row| matches!(row.get("hal_tolerance"), Some("2^-5" | "2^-7")),
        columns: &[
            col("mesh", "mesh", ANY, Format::FileStem),
            col(
                "HAL tolerance",
                "hal_tolerance",
                ANY,
                Format::Label(&[("2^-5", "2⁻⁵"), ("2^-7", "2⁻⁷")]),
            ),
            col("triangles", "triangles", ANY, Format::Grouped(0)),
            col(
                "HAL width",
                "hal_width_pct_diagonal",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "HAL Hausdorff",
                "hal_hausdorff_pct_diagonal",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "`sphaera-simplify` Hausdorff",
                "simplify_hausdorff_pct_diagonal",
                ANY,
                Format::Significant(2),
            ),
            col(
                "its bound",
                "simplify_bound_pct_diagonal",
                ANY,
                Format::Significant(2),
            ),
        ],
    },
];

/// The columns of both point-inclusion tables.
const QUERY_SPEED_COLUMNS: &[super::super::spec::Column] = &[
    col("outline", "polygon", ANY, Format::Label(HAL_OUTLINES)),
    col("vertices", "vertices", ANY, Format::Grouped(0)),
    col(
        "HAL build ms",
        "build_seconds",
        HAL_TREE,
        Format::Decimals(2),
    )
    .times(1000.0),
    col(
        "HAL",
        "microseconds_per_query",
        HAL_TREE,
        Format::Grouped(3),
    ),
    col(
        "HAL hierarchy",
        "microseconds_per_query",
        &[("method", "HAL hierarchy")],
        Format::Grouped(3),
    ),
    col(
        "strip tree",
        "microseconds_per_query",
        &[("method", "strip tree")],
        Format::Grouped(3),
    ),
    col(
        "box tree",
        "microseconds_per_query",
        &[("method", "box tree")],
        Format::Grouped(3),
    ),
    col(
        "brute force",
        "microseconds_per_query",
        BRUTE_FORCE,
        Format::Grouped(2),
    ),
    col(
        "geo `contains`",
        "microseconds_per_query",
        &[("method", "geo contains")],
        Format::Grouped(2),
    ),
    col(
        "brute / HAL",
        "microseconds_per_query",
        BRUTE_FORCE,
        Format::Times(0),
    )
    .over("microseconds_per_query", HAL_TREE),
];
