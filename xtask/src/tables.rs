//! `cargo xtask tables [--check]`: the markdown tables of the docs, generated from the
//! experiments' CSVs, so that no figure in a table is typed by hand.
//!
//! # The format
//!
//! In any markdown file of the repository (`docs/`, `README.md`, the crates' READMEs,
//! markdown that rustdoc includes; `target/` and hidden folders are skipped), a
//! generated table sits between two marker comments, each alone on its line:
//!
//! ```text
//! <!-- table: NAME -->
//! | … written by `cargo xtask tables` … |
//! <!-- /table -->
//! ```
//!
//! `NAME` names an entry of [`TABLES`], generated from `docs/charts/CSV.csv` ([`Table::csv`],
//! usually `NAME` itself; the CSV an experiment of `sphaera-eval` writes: a header line,
//! then comma-separated fields, a field holding a comma, a quote or a line break in double
//! quotes with its quotes doubled, as RFC 4180 says). Everything between the markers is
//! replaced, the rest of the file is left as it is; the same table may appear in several
//! files. An entry says:
//!
//! - `key`: the CSV columns naming one table row. CSV rows with equal values there merge
//!   into one table row, in the order of their first appearance (so one row can show,
//!   e.g., every method's figure at one mesh and sphere count);
//! - `keep`: which CSV rows take part (a predicate on a row's fields);
//! - `columns`: per table column its header, the CSV column it shows, optionally only
//!   from the merged CSV rows whose columns equal given values ([`Column::from`]; the
//!   first such row that has the field, or the last with [`Column::last`]), optionally
//!   multiplied by a factor ([`Column::times`]) or divided by another field
//!   ([`Column::over`]), and its [`Format`]. A field that is absent or empty shows as an
//!   empty cell.
//!
//! `cargo xtask tables` rewrites every marked table; `--check` (run by `cargo xtask ci`
//! beside `charts --check`) rewrites nothing and fails, naming the file and the table,
//! when one differs: "run `cargo xtask tables` and commit". An unknown name, a marker
//! without its end or a CSV without a column the spec names fails both.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// How a table cell shows its CSV field. The numeric formats show a field that is not a
/// number as written.
#[derive(Clone, Copy)]
pub enum Format {
    /// As written, left-aligned.
    Text,
    /// The last component of a path (`robots/x/link1.obj` → `link1.obj`), left-aligned.
    FileName,
    /// As [`Format::FileName`], in backticks: for tables that rustdoc includes, where a
    /// bare `bunny_lowres.obj` fails clippy's `doc_markdown`.
    CodeFileName,
    /// The file name without its extension (`shapes/spot.obj` → `spot`), left-aligned.
    FileStem,
    /// The text paired with the field (`(field, shown)`; a field not listed is shown as
    /// written), left-aligned.
    Label(&'static [(&'static str, &'static str)]),
    /// A number with this many decimals, right-aligned.
    Decimals(usize),
    /// A number with this many decimals and its thousands grouped by commas (`13,472`),
    /// right-aligned.
    Grouped(usize),
    /// A number to this many significant digits (`0.18`, `0.000054`, `14.2`; never fewer
    /// integer digits), right-aligned.
    Significant(usize),
    /// A number in scientific notation with this many decimals (`5.00e-4`), right-aligned.
    Scientific(usize),
    /// A factor with this many decimals, its thousands grouped, followed by `×` (`2.47×`,
    /// `6,211×`), right-aligned.
    Times(usize),
    /// A rate to about three digits with `k` or `M` (`605k`, `11.6k`, `0.7k`, `2.05M`),
    /// right-aligned.
    Rate,
    /// As written, right-aligned (counts).
    Right,
}

/// Conditions on a CSV row: every column `.0` equals `.1` (empty: every row).
pub type Filter = &'static [(&'static str, &'static str)];

/// No condition.
const ANY: Filter = &[];

/// One column of a table.
pub struct Column {
    /// The header.
    pub header: &'static str,
    /// The CSV column shown.
    pub field: &'static str,
    /// Take the field only from the merged CSV rows that pass this filter.
    pub from: Filter,
    /// Take it from the last such row that has it (`false`: the first).
    pub from_last: bool,
    /// A number is multiplied by this (1: shown as it is; 100: a fraction as a percentage).
    pub scale: f64,
    /// Divide the number by this field, taken from the merged rows that pass this filter
    /// (first or last as [`Column::from_last`] says).
    pub divisor: Option<(&'static str, Filter)>,
    /// How it is written.
    pub format: Format,
}

impl Column {
    /// The column with its number multiplied by `scale`.
    const fn times(self, scale: f64) -> Self {
        Self { scale, ..self }
    }

    /// The column with its number divided by the field `field` of the merged rows that
    /// pass `from`.
    const fn over(self, field: &'static str, from: Filter) -> Self {
        Self {
            divisor: Some((field, from)),
            ..self
        }
    }

    /// The column taken from the last merged row that passes its filter and has the field.
    const fn last(self) -> Self {
        Self {
            from_last: true,
            ..self
        }
    }
}

/// One CSV row, by column name.
pub struct Record<'a> {
    header: &'a [String],
    fields: &'a [String],
}

impl<'a> Record<'a> {
    /// The field of column `name` (`None` when the CSV has no such column or the row is
    /// short).
    #[must_use]
    pub fn get(&self, name: &str) -> Option<&'a str> {
        let i = self.header.iter().position(|h| h == name)?;
        self.fields.get(i).map(String::as_str)
    }

    /// Whether the row passes `filter`.
    fn passes(&self, filter: Filter) -> bool {
        filter.iter().all(|&(k, v)| self.get(k) == Some(v))
    }
}

/// One generated table: `docs/charts/CSV.csv` shown as [`Table::columns`] say.
pub struct Table {
    /// The marker's name.
    pub name: &'static str,
    /// The CSV's name, without `.csv` (the same as the marker's unless one CSV gives
    /// several tables).
    pub csv: &'static str,
    /// The CSV columns naming one table row.
    pub key: &'static [&'static str],
    /// Which CSV rows take part.
    pub keep: fn(&Record<'_>) -> bool,
    /// The columns.
    pub columns: &'static [Column],
}

/// Shorthand for a column of the tables below.
const fn col(header: &'static str, field: &'static str, from: Filter, format: Format) -> Column {
    Column {
        header,
        field,
        from,
        from_last: false,
        scale: 1.0,
        divisor: None,
        format,
    }
}

/// The Sphaera row of `spheres_vs_count.csv`.
const SPHAERA: Filter = &[("method", "sphaera")];
/// morphit-rs as it returns its spheres.
const RAW: Filter = &[("method", "morphit_raw")];
/// morphit-rs grown to cover.
const GROWN: Filter = &[("method", "morphit_grown")];

/// Every generated table.
pub const TABLES: &[Table] = &[
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
        ],
    },
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
    // docs/benchmarks.md, "HAL trees", "Point inclusion": per outline, µs per query.
    Table {
        name: "hal_query_speed",
        csv: "hal_query_speed",
        key: &["polygon"],
        keep: |_| true,
        columns: &[
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
                Format::Grouped(2),
            ),
            col(
                "strip tree",
                "microseconds_per_query",
                &[("method", "strip tree")],
                Format::Grouped(2),
            ),
            col(
                "box tree",
                "microseconds_per_query",
                &[("method", "box tree")],
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
            .over("microseconds_per_query", HAL_TREE),
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

/// The colliders of `scene_time_vs_error.csv`, as the table names them.
const SCENE_COLLIDERS: &[(&str, &str)] = &[
    ("sphaera 10%", "Sphaera, tree level for 10%"),
    ("sphaera 5%", "Sphaera, tree level for 5%"),
    ("sphaera 2%", "Sphaera, tree level for 2%"),
    (
        "sphaera 1%",
        "Sphaera, tree level for 1% (the 2 % run's colliders)",
    ),
    (
        "sphaera 0.5%",
        "Sphaera, tree level for 0.5% (the 2 % run's colliders)",
    ),
    ("sphaera 2px", "Sphaera, tree level for 2px"),
    ("sphaera cut 10%", "Sphaera, smallest tree cut for 10%"),
    ("sphaera cut 5%", "Sphaera, smallest tree cut for 5%"),
    ("sphaera cut 2%", "Sphaera, smallest tree cut for 2%"),
];
/// The silhouette labellings of `silhouette_error_vs_triangles.csv`.
const OUTLINE_NEAREST: Filter = &[("method", "outline, nearest camera, 2 cells")];
/// With the internal silhouettes (the paper's default).
const OUTLINE_AND_INTERNAL: Filter = &[("method", "outline and internal, nearest camera, 2 cells")];
/// The outline, the mean of the 4 nearest cameras.
const OUTLINE_MEAN_4: Filter = &[("method", "outline, mean of 4 nearest, 2 cells")];
/// The engines of `hausdorff_gap_vs_time.csv`.
const HAUSDORFF_ENGINES: &[(&str, &str)] = &[
    ("sphaera", "Sphaera, all told, 2 cores"),
    ("meshsweeper", "Meshsweeper (paper), hierarchies not timed"),
    ("cascading_upper_bounds", "cascading-upper-bounds"),
];
/// The methods of `medial_static_vs_adaptive.csv`.
const MEDIAL_METHODS: &[(&str, &str)] = &[("static+cover", "static + coverage")];
/// The outlines of the HAL experiments.
const HAL_OUTLINES: &[(&str, &str)] = &[
    ("polygons/luxembourg.txt", "Luxembourg"),
    ("polygons/netherlands.txt", "Netherlands"),
    ("polygons/belgium.txt", "Belgium"),
    ("polygons/united-kingdom.txt", "United Kingdom"),
    ("polygons/norway.txt", "Norway"),
    ("polygons/afro-eurasia.txt", "Afro-Eurasia"),
    ("polygons/americas.txt", "Americas"),
    ("polygons/americas.txt refined ×16", "Americas refined ×16"),
];
/// The HAL tree's rows of `hal_query_speed.csv`.
const HAL_TREE: Filter = &[("method", "HAL tree")];
/// Brute force's.
const BRUTE_FORCE: Filter = &[("method", "brute force")];
/// The uniform levels of `hal_width_vs_size.csv`.
const UNIFORM: Filter = &[("approximation", "uniform")];

/// The Panda's rows of `robot_budgets.csv`.
const PANDA: Filter = &[("robot", "robots/urdf/franka_panda/panda.urdf")];
/// The KUKA's.
const KUKA: Filter = &[("robot", "robots/urdf/kuka_iiwa/model.urdf")];
/// Sphaera's rows of `robot_protrusion_vs_spheres.csv`.
const ROBOT_SPHAERA: Filter = &[("method", "sphaera")];
/// The voxel baseline's.
const VOXELS: Filter = &[("method", "voxel_kmeans")];

/// The CSV row of tree level 1 (2, 3) of the sphere-tree tables.
const LEVEL_1: Filter = &[("level", "1")];
/// Level 2.
const LEVEL_2: Filter = &[("level", "2")];
/// Level 3.
const LEVEL_3: Filter = &[("level", "3")];

/// Rewrites (or, with `check`, checks) every marked table of every markdown file under
/// the current directory (the project root).
pub fn tables(check: bool) -> Result<()> {
    let mut stale = Vec::new();
    let mut count = 0;
    for file in markdown_files(Path::new("."))? {
        let text = std::fs::read_to_string(&file)
            .with_context(|| format!("cannot read {}", file.display()))?;
        if !text.contains(OPEN) {
            continue;
        }
        let (updated, names) = rewrite(&text).with_context(|| format!("in {}", file.display()))?;
        count += names.len();
        if updated != text {
            if check {
                stale.push(format!("{} ({})", file.display(), names.join(", ")));
            } else {
                std::fs::write(&file, updated)
                    .with_context(|| format!("cannot write {}", file.display()))?;
                eprintln!("  {}: {} written", file.display(), names.join(", "));
            }
        }
    }
    if !stale.is_empty() {
        bail!(
            "generated tables differ from their CSVs in {}; run `cargo xtask tables` and commit",
            stale.join(", ")
        );
    }
    eprintln!("  ({count} generated tables: ok)");
    Ok(())
}

/// The opening marker's start.
const OPEN: &str = "<!-- table:";
/// The closing marker.
const CLOSE: &str = "<!-- /table -->";

/// `text` with every marked table regenerated, and the tables' names.
fn rewrite(text: &str) -> Result<(String, Vec<String>)> {
    let mut out = String::with_capacity(text.len());
    let mut names = Vec::new();
    let mut lines = text.split_inclusive('\n');
    while let Some(line) = lines.next() {
        out.push_str(line);
        let trimmed = line.trim();
        let Some(name) = trimmed
            .strip_prefix(OPEN)
            .and_then(|rest| rest.strip_suffix("-->"))
            .map(str::trim)
        else {
            continue;
        };
        if !line.ends_with('\n') {
            out.push('\n');
        }
        let Some(table) = TABLES.iter().find(|t| t.name == name) else {
            bail!("no generated table named `{name}` (xtask/src/tables.rs lists them)");
        };
        out.push_str(&render(table, Path::new("docs/charts"))?);
        let mut closed = false;
        for skipped in lines.by_ref() {
            if skipped.trim() == CLOSE {
                out.push_str(skipped);
                closed = true;
                break;
            }
        }
        if !closed {
            bail!("the table `{name}` has no closing `{CLOSE}`");
        }
        names.push(name.to_owned());
    }
    Ok((out, names))
}

/// The markdown of `table` from `dir/CSV.csv`, one line per row, ending in a newline.
fn render(table: &Table, dir: &Path) -> Result<String> {
    let path = dir.join(format!("{}.csv", table.csv));
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read {} (run `cargo xtask charts`)", path.display()))?;
    let mut records = parse_csv(&text)
        .with_context(|| format!("cannot parse {}", path.display()))?
        .into_iter();
    let header = records
        .next()
        .with_context(|| format!("{} is empty", path.display()))?;
    let filters = |filter: Filter| filter.iter().map(|f| &f.0);
    let wanted = table.key.iter().chain(table.columns.iter().flat_map(|c| {
        std::iter::once(&c.field).chain(filters(c.from)).chain(
            c.divisor
                .iter()
                .flat_map(|d| std::iter::once(&d.0).chain(filters(d.1))),
        )
    }));
    for name in wanted {
        if !header.iter().any(|h| h == name) {
            bail!("{} has no column `{name}`", path.display());
        }
    }
    let rows: Vec<Vec<String>> = records.collect();
    let record = |i: usize| Record {
        header: &header,
        fields: &rows[i],
    };
    // Merge the kept rows by key, in order of first appearance.
    let mut groups: Vec<(Vec<String>, Vec<usize>)> = Vec::new();
    for i in 0..rows.len() {
        let r = record(i);
        if !(table.keep)(&r) {
            continue;
        }
        let key: Vec<String> = table
            .key
            .iter()
            .map(|k| r.get(k).unwrap_or_default().to_owned())
            .collect();
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, members)) => members.push(i),
            None => groups.push((key, vec![i])),
        }
    }
    let mut out = String::new();
    let cells = |items: Vec<String>| format!("| {} |\n", items.join(" | "));
    out.push_str(&cells(
        table.columns.iter().map(|c| c.header.to_owned()).collect(),
    ));
    out.push_str(&cells(
        table
            .columns
            .iter()
            .map(|c| if c.format.is_left() { "---" } else { "---:" }.to_owned())
            .collect(),
    ));
    for (_, members) in &groups {
        // The field `field` of the first (last) merged row passing `from` that has it.
        let pick = |field: &str, from: Filter, last: bool| {
            let mut found = members
                .iter()
                .map(|&i| record(i))
                .filter(|r| r.passes(from))
                .filter_map(|r| r.get(field).filter(|f| !f.is_empty()));
            if last {
                found.next_back()
            } else {
                found.next()
            }
        };
        let row: Vec<String> = table
            .columns
            .iter()
            .map(|c| {
                let Some(field) = pick(c.field, c.from, c.from_last) else {
                    return String::new();
                };
                match c.divisor {
                    None => format_field(field, c.scale, c.format),
                    Some((divisor, from)) => {
                        let number = |f: &str| f.parse::<f64>().ok();
                        match (
                            number(field),
                            pick(divisor, from, c.from_last).and_then(number),
                        ) {
                            (Some(n), Some(d)) if d != 0.0 => {
                                format_number(n / d * c.scale, c.format)
                            }
                            _ => String::new(),
                        }
                    }
                }
            })
            .collect();
        out.push_str(&cells(row));
    }
    Ok(out)
}

/// The records of a CSV `text` as RFC 4180 says: fields separated by commas, records by
/// LF or CRLF; a field that starts with a double quote runs to the next lone quote and
/// may hold commas, line breaks and doubled quotes (each read as one). Empty lines are
/// skipped. Fails on an unclosed quote or text after a closing quote.
fn parse_csv(text: &str) -> Result<Vec<Vec<String>>> {
    let mut records = Vec::new();
    let mut record = Vec::new();
    let mut field = String::new();
    // Whether the current record has begun (so that a blank line yields no record).
    let mut started = false;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if field.is_empty() => {
                started = true;
                loop {
                    match chars.next() {
                        Some('"') if chars.peek() == Some(&'"') => {
                            chars.next();
                            field.push('"');
                        }
                        Some('"') => break,
                        Some(inner) => field.push(inner),
                        None => bail!("a quoted field is not closed: `\"{field}`"),
                    }
                }
                match chars.peek() {
                    None | Some(',' | '\n' | '\r') => {}
                    Some(after) => bail!("`{after}` after the quoted field `{field}`"),
                }
            }
            ',' => {
                started = true;
                record.push(std::mem::take(&mut field));
            }
            '\r' if chars.peek() == Some(&'\n') => {}
            '\n' => {
                if started {
                    record.push(std::mem::take(&mut field));
                    records.push(std::mem::take(&mut record));
                }
                started = false;
            }
            other => {
                started = true;
                field.push(other);
            }
        }
    }
    if started {
        record.push(field);
        records.push(record);
    }
    Ok(records)
}

impl Format {
    /// Whether the column is left-aligned (text) rather than right-aligned (numbers).
    const fn is_left(self) -> bool {
        matches!(
            self,
            Self::Text | Self::FileName | Self::CodeFileName | Self::FileStem | Self::Label(_)
        )
    }
}

/// `field` written as `format` says, a number multiplied by `scale` first.
fn format_field(field: &str, scale: f64, format: Format) -> String {
    match format {
        Format::Text | Format::Right => field.to_owned(),
        Format::FileName => field.rsplit('/').next().unwrap_or(field).to_owned(),
        Format::CodeFileName => format!("`{}`", format_field(field, scale, Format::FileName)),
        Format::FileStem => {
            let name = format_field(field, scale, Format::FileName);
            match name.rsplit_once('.') {
                Some((stem, _)) if !stem.is_empty() => stem.to_owned(),
                _ => name,
            }
        }
        Format::Label(labels) => labels
            .iter()
            .find(|(raw, _)| *raw == field)
            .map_or(field, |(_, shown)| shown)
            .to_owned(),
        Format::Decimals(_)
        | Format::Grouped(_)
        | Format::Significant(_)
        | Format::Scientific(_)
        | Format::Times(_)
        | Format::Rate => field
            .parse::<f64>()
            .map_or_else(|_| field.to_owned(), |v| format_number(v * scale, format)),
    }
}

/// The number `v` written as the numeric `format` says (a text format: as `{v}`).
fn format_number(v: f64, format: Format) -> String {
    match format {
        Format::Decimals(digits) => format!("{v:.digits$}"),
        Format::Grouped(digits) => group_thousands(&format!("{v:.digits$}")),
        Format::Significant(digits) => {
            let magnitude = if v == 0.0 || !v.is_finite() {
                0
            } else {
                // The exponent of a finite f64 fits an i64 (|log10| ≤ 324).
                #[allow(clippy::cast_possible_truncation)]
                let exponent = v.abs().log10().floor() as i64;
                exponent
            };
            let decimals = usize::try_from(
                i64::try_from(digits)
                    .unwrap_or(i64::MAX)
                    .saturating_sub(1 + magnitude),
            )
            .unwrap_or(0);
            format!("{v:.decimals$}")
        }
        Format::Scientific(digits) => format!("{v:.digits$e}"),
        Format::Times(digits) => format!("{}×", group_thousands(&format!("{v:.digits$}"))),
        Format::Rate => {
            if v.abs() >= 999_500.0 {
                format!("{:.2}M", v / 1e6)
            } else if v.abs() >= 99_950.0 {
                format!("{:.0}k", v / 1e3)
            } else {
                format!("{:.1}k", v / 1e3)
            }
        }
        Format::Text
        | Format::FileName
        | Format::CodeFileName
        | Format::FileStem
        | Format::Label(_)
        | Format::Right => format!("{v}"),
    }
}

/// `number` (as `-1234.5`) with its integer digits grouped by commas (`-1,234.5`).
fn group_thousands(number: &str) -> String {
    let (sign, unsigned) = number
        .strip_prefix('-')
        .map_or(("", number), |rest| ("-", rest));
    let (integer, fraction) = unsigned
        .find('.')
        .map_or((unsigned, ""), |dot| unsigned.split_at(dot));
    if !integer.bytes().all(|b| b.is_ascii_digit()) {
        return number.to_owned();
    }
    let mut grouped = String::with_capacity(number.len() + integer.len() / 3);
    for (i, digit) in integer.chars().enumerate() {
        if i > 0 && (integer.len() - i) % 3 == 0 {
            grouped.push(',');
        }
        grouped.push(digit);
    }
    format!("{sign}{grouped}{fraction}")
}

/// Every markdown file under `root`, sorted, skipping `target` and hidden folders.
fn markdown_files(root: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder)
            .with_context(|| format!("cannot list {}", folder.display()))?
        {
            let path = entry?.path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if path.is_dir() {
                if name != "target" && !name.starts_with('.') && name != "node_modules" {
                    folders.push(path);
                }
            } else if name.ends_with(".md") {
                files.push(
                    path.strip_prefix(root)
                        .map_or_else(|_| path.clone(), Path::to_path_buf),
                );
            }
        }
    }
    files.sort();
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fields `sphaera-eval`'s `write_csv` quotes, written as it writes them (its own
    /// test checks the same text), read back as they were.
    #[test]
    fn quoted_fields_round_trip() -> Result<()> {
        let text = "mesh,method,value\n\
                    bunny.obj,\"outline, nearest camera, 2 cells\",0.5\n\
                    \"say \"\"hi\"\"\",\"two\nlines\",\"cr\r\"\n\
                    ,plain,\"a,\"\"b\"\"\"\n";
        let fields = |items: &[&str]| items.iter().map(|&f| f.to_owned()).collect::<Vec<_>>();
        assert_eq!(
            parse_csv(text)?,
            vec![
                fields(&["mesh", "method", "value"]),
                fields(&["bunny.obj", "outline, nearest camera, 2 cells", "0.5"]),
                fields(&["say \"hi\"", "two\nlines", "cr\r"]),
                fields(&["", "plain", "a,\"b\""]),
            ]
        );
        // CRLF line ends, empty lines and a last line without its end.
        assert_eq!(
            parse_csv("a,b\r\n\r\n1,\"\"\n\n2,3")?,
            vec![fields(&["a", "b"]), fields(&["1", ""]), fields(&["2", "3"])]
        );
        assert!(parse_csv("a,\"b\n").is_err());
        assert!(parse_csv("a,\"b\"c\n").is_err());
        Ok(())
    }

    #[test]
    fn numbers_are_written_as_their_format_says() {
        let cases: &[(&str, f64, Format, &str)] = &[
            ("0.184483", 1.0, Format::Significant(2), "0.18"),
            ("0.000054", 1.0, Format::Significant(2), "0.000054"),
            ("14.186969", 1.0, Format::Significant(3), "14.2"),
            ("0.005", 100.0, Format::Significant(1), "0.5"),
            ("1604", 1.0, Format::Significant(3), "1604"),
            ("1061664", 1.0, Format::Grouped(0), "1,061,664"),
            ("-4985.5018", 1.0, Format::Grouped(2), "-4,985.50"),
            ("999", 1.0, Format::Grouped(0), "999"),
            ("4.9981e-4", 1.0, Format::Scientific(2), "5.00e-4"),
            ("6211.4", 1.0, Format::Times(0), "6,211×"),
            ("722.3", 1.0, Format::Rate, "0.7k"),
            ("23231.4", 1.0, Format::Rate, "23.2k"),
            ("604988.5", 1.0, Format::Rate, "605k"),
            ("2046349.8", 1.0, Format::Rate, "2.05M"),
            ("0.0026", 1000.0, Format::Decimals(1), "2.6"),
            ("n/a", 100.0, Format::Decimals(1), "n/a"),
            ("polygons/norway.txt", 1.0, Format::FileStem, "norway"),
            (
                "spot.obj",
                1.0,
                Format::Label(&[("spot.obj", "spot")]),
                "spot",
            ),
            (
                "cow.obj",
                1.0,
                Format::Label(&[("spot.obj", "spot")]),
                "cow.obj",
            ),
        ];
        for &(field, scale, format, shown) in cases {
            assert_eq!(format_field(field, scale, format), shown, "{field}");
        }
    }

    /// Several conditions, the last matching row, a factor and a divisor.
    #[test]
    fn columns_filter_scale_and_divide() -> Result<()> {
        const TABLE: Table = Table {
            name: "ratios",
            csv: "ratios",
            key: &["mesh"],
            keep: |_| true,
            columns: &[
                col("mesh", "mesh", ANY, Format::Text),
                col("first", "n", &[("kind", "u")], Format::Right),
                col("last", "n", &[("kind", "u")], Format::Right).last(),
                col("b at x", "n", &[("kind", "b"), ("at", "x")], Format::Right),
                col(
                    "b/u %",
                    "n",
                    &[("kind", "b"), ("at", "y")],
                    Format::Decimals(0),
                )
                .over("n", &[("kind", "u")])
                .times(100.0),
            ],
        };
        let dir = std::env::temp_dir().join(format!("xtask-ratios-{}", std::process::id()));
        std::fs::create_dir_all(&dir)?;
        std::fs::write(
            dir.join("ratios.csv"),
            "mesh,kind,at,n\nm,u,x,4\nm,b,x,1\nm,u,y,8\nm,b,y,3\nk,u,x,0\nk,b,y,1\n",
        )?;
        let markdown = render(&TABLE, &dir);
        std::fs::remove_dir_all(&dir)?;
        assert_eq!(
            markdown?,
            "| mesh | first | last | b at x | b/u % |\n| --- | ---: | ---: | ---: | ---: |\n\
             | m | 4 | 8 | 1 | 75 |\n| k | 0 | 0 |  |  |\n"
        );
        Ok(())
    }

    /// A quoted field with commas is one cell of the table and a key of its row.
    #[test]
    fn tables_show_quoted_fields_as_one_cell() -> Result<()> {
        let dir = std::env::temp_dir().join(format!("xtask-tables-{}", std::process::id()));
        std::fs::create_dir_all(&dir)?;
        std::fs::write(
            dir.join("quoted.csv"),
            "method,x,y\n\"a, b\",1,0.123\n\"say \"\"c\"\"\",2,4\n",
        )?;
        const TABLE: Table = Table {
            name: "quoted",
            csv: "quoted",
            key: &["method"],
            keep: |row| row.get("x") != Some("3"),
            columns: &[
                col("method", "method", ANY, Format::Text),
                col("x", "x", ANY, Format::Right),
                col("y", "y", ANY, Format::Decimals(2)),
            ],
        };
        let markdown = render(&TABLE, &dir);
        std::fs::remove_dir_all(&dir)?;
        assert_eq!(
            markdown?,
            "| method | x | y |\n| --- | ---: | ---: |\n| a, b | 1 | 0.12 |\n| say \"c\" | 2 | 4.00 |\n"
        );
        Ok(())
    }
}
