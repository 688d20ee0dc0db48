//! The generated tables of scenes and silhouettes.

use super::super::spec::{ANY, Format, Table, col};
#[allow(clippy::wildcard_imports)]
use super::filters::*;

/// The tables of this group.
pub(super) const TABLES: &[Table] = &[
    // docs/benchmarks.md, "Falling objects in rapier: time against error": per collider.
    Table {
        name: "scene_time_vs_error",
        csv: "scene_time_vs_error",
        key: &["method"],
        keep: |_| true,
        columns: &[
            col("collider", "method", ANY, Format::Label(SCENE_COLLIDERS)),
            col(
                "balls / triangles / parts per body",
                "parts_per_body",
                ANY,
                Format::Grouped(0),
            ),
            col(
                "certified error %",
                "certified_error_pct",
                ANY,
                Format::Decimals(3),
            ),
            col("ms per step", "ms_per_step", ANY, Format::Decimals(1)),
            col(
                "steps per second",
                "steps_per_second",
                ANY,
                Format::Decimals(0),
            ),
            col(
                "deepest penetration %",
                "max_penetration_pct",
                ANY,
                Format::Decimals(3),
            ),
            col("mean gap %", "mean_gap_pct", ANY, Format::Decimals(3)),
            col("largest gap %", "max_gap_pct", ANY, Format::Decimals(3)),
        ],
    },
    // docs/benchmarks.md, "Timing like the paper's Tables 1–2": per mesh.
    Table {
        name: "silhouette_time_vs_faces",
        csv: "silhouette_time_vs_faces",
        key: &["mesh"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::CodeFileName),
            col("faces", "faces", ANY, Format::Grouped(0)),
            col("labels s (2 cores)", "labels_s", ANY, Format::Decimals(2)),
            col(
                "hierarchy s (2 cores)",
                "hierarchy_s",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "extraction from scratch ms",
                "extract_scratch_ms",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "from the previous frame ms",
                "extract_next_ms",
                ANY,
                Format::Decimals(2),
            ),
            col("triangles out", "triangles_out", ANY, Format::Grouped(0)),
            col(
                "lookup, nearest µs",
                "lookup_nearest_ms",
                ANY,
                Format::Decimals(1),
            )
            .times(1000.0),
            col(
                "nearest share %",
                "share_nearest_percent",
                ANY,
                Format::Decimals(2),
            ),
            col(
                "lookup, 4 nearest µs",
                "lookup_4_nearest_ms",
                ANY,
                Format::Decimals(1),
            )
            .times(1000.0),
            col(
                "4 nearest share %",
                "share_4_nearest_percent",
                ANY,
                Format::Decimals(2),
            ),
        ],
    },
    // docs/benchmarks.md, "Guided against the plain simplifier": per mesh and error, the
    // defaults' wrong pixels against the plain simplifier's at as many triangles, and the
    // paper's rule's ratios.
    Table {
        name: "silhouette_vs_simplify",
        csv: "silhouette_vs_simplify",
        key: &["mesh", "error_rel_diagonal"],
        keep: |row| row.get("error_rel_diagonal") != Some("0.02"),
        columns: &[
            col("mesh", "mesh", ANY, Format::Text),
            col("e %", "error_rel_diagonal", ANY, Format::Decimals(2)).times(100.0),
            col(
                "triangles",
                "mean_triangles_guided",
                GUIDED_DEFAULT,
                Format::Grouped(0),
            ),
            col(
                "wrong px, guided",
                "given_view_pixels_guided",
                GUIDED_DEFAULT,
                Format::Decimals(1),
            ),
            col(
                "wrong px, plain",
                "given_view_pixels_plain",
                GUIDED_DEFAULT,
                Format::Decimals(1),
            ),
            col(
                "ratio at the view",
                "given_view_ratio",
                GUIDED_DEFAULT,
                Format::Decimals(2),
            ),
            col(
                "ratio 7.5° around",
                "around_ratio",
                GUIDED_DEFAULT,
                Format::Decimals(2),
            ),
            col("verdict", "verdict", GUIDED_DEFAULT, Format::Text),
            col(
                "paper's rule: ratio at the view",
                "given_view_ratio",
                GUIDED_PAPER,
                Format::Decimals(2),
            ),
            col("around", "around_ratio", GUIDED_PAPER, Format::Decimals(2)),
        ],
    },
    // docs/benchmarks.md, "Guided against the plain simplifier": every variant's ratio at
    // the view, at e = 1 %.
    Table {
        name: "silhouette_vs_simplify_variants",
        csv: "silhouette_vs_simplify",
        key: &["mesh"],
        keep: |row| row.get("error_rel_diagonal") == Some("0.01"),
        columns: &[
            col("mesh", "mesh", ANY, Format::Text),
            col(
                "defaults",
                "given_view_ratio",
                GUIDED_DEFAULT,
                Format::Decimals(2),
            ),
            col(
                "corners, 1/4 cell",
                "given_view_ratio",
                GUIDED_CORNERS_CELL,
                Format::Decimals(2),
            ),
            col(
                "certified, 1/4 cell",
                "given_view_ratio",
                GUIDED_CERTIFIED,
                Format::Decimals(2),
            ),
            col(
                "internal silhouettes too",
                "given_view_ratio",
                GUIDED_INTERNAL,
                Format::Decimals(2),
            ),
            col(
                "the scene's labels (30°, 128²)",
                "given_view_ratio",
                GUIDED_SCENE_LABELS,
                Format::Decimals(2),
            ),
            col(
                "paper: f = 0.25",
                "given_view_ratio",
                GUIDED_PAPER,
                Format::Decimals(2),
            ),
            col(
                "widened, f = 0.1",
                "given_view_ratio",
                GUIDED_F_01,
                Format::Decimals(2),
            ),
            col(
                "widened, f = 0.5",
                "given_view_ratio",
                GUIDED_F_05,
                Format::Decimals(2),
            ),
        ],
    },
    // docs/benchmarks.md, "Guided against the plain simplifier": popping along an orbit.
    Table {
        name: "silhouette_temporal",
        csv: "silhouette_temporal",
        key: &["mesh", "interpolation"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", ANY, Format::Text),
            col("labels", "interpolation", ANY, Format::Text),
            col(
                "popping px a frame",
                "mean_popping_pixels",
                ANY,
                Format::Decimals(2),
            ),
            col("largest", "largest_popping_pixels", ANY, Format::Right),
            col("wrong px", "mean_wrong_pixels", ANY, Format::Decimals(1)),
            col("triangles", "mean_triangles", ANY, Format::Grouped(0)),
        ],
    },
    // docs/benchmarks.md, "Does the level of detail keep the outline?": per mesh, views
    // and error, the unweighted level's wrong pixels over the guided one's, per labelling.
    Table {
        name: "silhouette_error_vs_triangles",
        csv: "silhouette_error_vs_triangles",
        key: &["mesh", "views", "error_rel_diagonal"],
        keep: |row| match row.get("views") {
            Some("at cameras") => row.get("error_rel_diagonal") == Some("0.005"),
            Some("between cameras") => matches!(
                row.get("error_rel_diagonal"),
                Some("0.005" | "0.01" | "0.04")
            ),
            _ => false,
        },
        columns: &[
            col("mesh", "mesh", ANY, Format::CodeFileName),
            col("views", "views", ANY, Format::Text),
            col(
                "`e` (% of diagonal)",
                "error_rel_diagonal",
                ANY,
                Format::Significant(1),
            )
            .times(100.0),
            col(
                "triangles",
                "mean_triangles",
                OUTLINE_NEAREST,
                Format::Grouped(0),
            ),
            col(
                "outline labels, nearest camera, 2 cells",
                "mean_pixels_unweighted",
                OUTLINE_NEAREST,
                Format::Times(2),
            )
            .over("mean_pixels_labels", OUTLINE_NEAREST),
            col(
                "outline and internal labels (the paper's default)",
                "mean_pixels_unweighted",
                OUTLINE_AND_INTERNAL,
                Format::Times(2),
            )
            .over("mean_pixels_labels", OUTLINE_AND_INTERNAL),
            col(
                "outline, mean of 4 nearest",
                "mean_pixels_unweighted",
                OUTLINE_MEAN_4,
                Format::Times(2),
            )
            .over("mean_pixels_labels", OUTLINE_MEAN_4),
        ],
    },
    // docs/benchmarks.md, "Object space: the certified bound of the contour region is
    // tight": per mesh at the finest and the coarsest error.
    Table {
        name: "silhouette_object_error",
        csv: "silhouette_object_error",
        key: &["mesh", "error_rel_diagonal"],
        keep: |row| matches!(row.get("error_rel_diagonal"), Some("0.005" | "0.04")),
        columns: &[
            col("mesh", "mesh", ANY, Format::CodeFileName),
            col("`e` %", "error_rel_diagonal", ANY, Format::Significant(1)).times(100.0),
            col(
                "contour region: bound",
                "contour_bound_rel",
                ANY,
                Format::Scientific(2),
            ),
            col(
                "measured from",
                "contour_measured_lower_rel",
                ANY,
                Format::Scientific(2),
            ),
            col(
                "to",
                "contour_measured_upper_rel",
                ANY,
                Format::Scientific(2),
            ),
            col(
                "% of the bound",
                "contour_measured_lower_rel",
                ANY,
                Format::Decimals(0),
            )
            .over("contour_bound_rel", ANY)
            .times(100.0),
            col(
                "elsewhere: bound",
                "other_bound_rel",
                ANY,
                Format::Scientific(2),
            ),
            col(
                "measured from",
                "other_measured_lower_rel",
                ANY,
                Format::Scientific(2),
            ),
            col("to", "other_measured_upper_rel", ANY, Format::Scientific(2)),
            col(
                "% of the bound",
                "other_measured_lower_rel",
                ANY,
                Format::Decimals(0),
            )
            .over("other_bound_rel", ANY)
            .times(100.0),
            col(
                "paper's direction: contour vertices",
                "contour_from_original_rel",
                ANY,
                Format::Scientific(2),
            ),
            col(
                "other vertices",
                "other_from_original_rel",
                ANY,
                Format::Scientific(2),
            ),
        ],
    },
];
