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
//! `NAME` names an entry of [`TABLES`], generated from `docs/charts/NAME.csv` (the CSV an
//! experiment of `sphaera-eval` writes: a header line, then comma-separated fields without
//! quoting). Everything between the markers is replaced, the rest of the file is left as
//! it is; the same table may appear in several files. An entry says:
//!
//! - `key`: the CSV columns naming one table row. CSV rows with equal values there merge
//!   into one table row, in the order of their first appearance (so one row can show,
//!   e.g., every method's figure at one mesh and sphere count);
//! - `keep`: which CSV rows take part (a predicate on a row's fields);
//! - `columns`: per table column its header, the CSV column it shows, optionally only
//!   from the merged CSV row whose column `C` equals `V` ([`Column::from`]), and its
//!   [`Format`]. A field that is absent or empty shows as an empty cell.
//!
//! `cargo xtask tables` rewrites every marked table; `--check` (run by `cargo xtask ci`
//! beside `charts --check`) rewrites nothing and fails, naming the file and the table,
//! when one differs: "run `cargo xtask tables` and commit". An unknown name, a marker
//! without its end or a CSV without a column the spec names fails both.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// How a table cell shows its CSV field.
#[derive(Clone, Copy)]
pub enum Format {
    /// As written, left-aligned.
    Text,
    /// The last component of a path (`robots/x/link1.obj` → `link1.obj`), left-aligned.
    FileName,
    /// As [`Format::FileName`], in backticks: for tables that rustdoc includes, where a
    /// bare `bunny_lowres.obj` fails clippy's `doc_markdown`.
    CodeFileName,
    /// A number with this many decimals, right-aligned (a field that is not a number is
    /// shown as written).
    Decimals(usize),
    /// As written, right-aligned (counts).
    Right,
}

/// One column of a table.
pub struct Column {
    /// The header.
    pub header: &'static str,
    /// The CSV column shown.
    pub field: &'static str,
    /// Take the field only from the merged CSV row whose column `.0` equals `.1`
    /// (`None`: from the first merged row that has it).
    pub from: Option<(&'static str, &'static str)>,
    /// How it is written.
    pub format: Format,
}

/// One CSV row, by column name.
pub struct Record<'a> {
    header: &'a [String],
    fields: &'a [String],
}

impl Record<'_> {
    /// The field of column `name` (`None` when the CSV has no such column or the row is
    /// short).
    #[must_use]
    pub fn get(&self, name: &str) -> Option<&str> {
        let i = self.header.iter().position(|h| h == name)?;
        self.fields.get(i).map(String::as_str)
    }
}

/// One generated table: `docs/charts/NAME.csv` shown as [`Table::columns`] say.
pub struct Table {
    /// The marker's name and the CSV's.
    pub name: &'static str,
    /// The CSV columns naming one table row.
    pub key: &'static [&'static str],
    /// Which CSV rows take part.
    pub keep: fn(&Record<'_>) -> bool,
    /// The columns.
    pub columns: &'static [Column],
}

/// Shorthand for a column of the tables below.
const fn col(
    header: &'static str,
    field: &'static str,
    from: Option<(&'static str, &'static str)>,
    format: Format,
) -> Column {
    Column {
        header,
        field,
        from,
        format,
    }
}

/// The Sphaera row of `spheres_vs_count.csv`.
const SPHAERA: Option<(&str, &str)> = Some(("method", "sphaera"));
/// morphit-rs as it returns its spheres.
const RAW: Option<(&str, &str)> = Some(("method", "morphit_raw"));
/// morphit-rs grown to cover.
const GROWN: Option<(&str, &str)> = Some(("method", "morphit_grown"));

/// Every generated table.
pub const TABLES: &[Table] = &[
    // docs/benchmarks.md, "Spheres against morphit-rs (issue 36)": per mesh and N,
    // Sphaera against the peer raw and grown.
    Table {
        name: "spheres_vs_count",
        key: &["mesh", "requested"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", None, Format::FileName),
            col("N", "requested", None, Format::Right),
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
        key: &["mesh"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", None, Format::CodeFileName),
            col("triangles", "triangles", None, Format::Right),
            col("build s", "build_seconds", None, Format::Decimals(2)),
            col(
                "certified evaluation s",
                "evaluation_seconds",
                None,
                Format::Decimals(2),
            ),
            col("total s", "total_seconds", None, Format::Decimals(2)),
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
        key: &["mesh", "tolerance_pct"],
        keep: |_| true,
        columns: &[
            col("mesh", "mesh", None, Format::FileName),
            col("tolerance %", "tolerance_pct", None, Format::Right),
            col("leaves", "leaves", None, Format::Right),
            col("nodes", "nodes", None, Format::Right),
            col("levels", "levels", None, Format::Right),
            col(
                "worst leaf bound %",
                "leaf_bound_pct",
                None,
                Format::Decimals(3),
            ),
            col(
                "evaluated worst %",
                "evaluated_upper_pct",
                None,
                Format::Decimals(3),
            ),
            col("met", "met", None, Format::Text),
            col(
                "check without bounds %",
                "check_interval_pct",
                None,
                Format::Text,
            ),
            col("build s", "build_seconds", None, Format::Decimals(2)),
        ],
    },
    // docs/benchmarks.md, "Sphere-trees", "Charts": per mesh and method the certified worst
    // error per level, with the toolkit's figures and issue 36's target on the bunny.
    Table {
        name: "spheretree_error_vs_level",
        key: &["file", "method"],
        keep: |_| true,
        columns: &[
            col("mesh", "file", None, Format::FileName),
            col("method", "method", None, Format::Text),
            col("source", "source", None, Format::Text),
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
            col("build s", "build_seconds", None, Format::Decimals(2)),
        ],
    },
    // crates/sphaera-robot/src/performance.md (the crate docs), its README and
    // docs/benchmarks.md, "Whole robots": per budget, both robots.
    Table {
        name: "robot_budgets",
        key: &["budget"],
        keep: |_| true,
        columns: &[
            col("budget", "budget", None, Format::Text),
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
        key: &["robot", "link"],
        keep: |row| row.get("spheres_per_link") == Some("40"),
        columns: &[
            col("robot", "robot", None, Format::FileName),
            col("link", "link", None, Format::Text),
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
];

/// The Panda's rows of `robot_budgets.csv`.
const PANDA: Option<(&str, &str)> = Some(("robot", "robots/urdf/franka_panda/panda.urdf"));
/// The KUKA's.
const KUKA: Option<(&str, &str)> = Some(("robot", "robots/urdf/kuka_iiwa/model.urdf"));
/// Sphaera's rows of `robot_protrusion_vs_spheres.csv`.
const ROBOT_SPHAERA: Option<(&str, &str)> = Some(("method", "sphaera"));
/// The voxel baseline's.
const VOXELS: Option<(&str, &str)> = Some(("method", "voxel_kmeans"));

/// The CSV row of tree level 1 (2, 3) of the sphere-tree tables.
const LEVEL_1: Option<(&str, &str)> = Some(("level", "1"));
/// Level 2.
const LEVEL_2: Option<(&str, &str)> = Some(("level", "2"));
/// Level 3.
const LEVEL_3: Option<(&str, &str)> = Some(("level", "3"));

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

/// The markdown of `table` from `dir/NAME.csv`, one line per row, ending in a newline.
fn render(table: &Table, dir: &Path) -> Result<String> {
    let path = dir.join(format!("{}.csv", table.name));
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read {} (run `cargo xtask charts`)", path.display()))?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<String> = lines
        .next()
        .with_context(|| format!("{} is empty", path.display()))?
        .split(',')
        .map(str::to_owned)
        .collect();
    let wanted = table
        .key
        .iter()
        .chain(table.columns.iter().map(|c| &c.field))
        .chain(
            table
                .columns
                .iter()
                .filter_map(|c| c.from.as_ref().map(|f| &f.0)),
        );
    for name in wanted {
        if !header.iter().any(|h| h == name) {
            bail!("{} has no column `{name}`", path.display());
        }
    }
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    // Merge the kept rows by key, in order of first appearance.
    let mut groups: Vec<(Vec<String>, Vec<usize>)> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let r = Record {
            header: &header,
            fields: row,
        };
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
            .map(|c| match c.format {
                Format::Text | Format::FileName | Format::CodeFileName => "---".to_owned(),
                Format::Decimals(_) | Format::Right => "---:".to_owned(),
            })
            .collect(),
    ));
    for (_, members) in &groups {
        let row: Vec<String> = table
            .columns
            .iter()
            .map(|c| {
                let field = members.iter().find_map(|&i| {
                    let r = Record {
                        header: &header,
                        fields: &rows[i],
                    };
                    let matches = c.from.is_none_or(|(k, v)| r.get(k) == Some(v));
                    r.get(c.field)
                        .filter(|f| matches && !f.is_empty())
                        .map(str::to_owned)
                });
                field.map_or_else(String::new, |f| format_field(&f, c.format))
            })
            .collect();
        out.push_str(&cells(row));
    }
    Ok(out)
}

/// `field` written as `format` says.
fn format_field(field: &str, format: Format) -> String {
    match format {
        Format::Text | Format::Right => field.to_owned(),
        Format::FileName => field.rsplit('/').next().unwrap_or(field).to_owned(),
        Format::CodeFileName => format!("`{}`", format_field(field, Format::FileName)),
        Format::Decimals(digits) => field
            .parse::<f64>()
            .map_or_else(|_| field.to_owned(), |v| format!("{v:.digits$}")),
    }
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
