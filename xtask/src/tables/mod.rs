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
//! `NAME` names an entry of [`catalog::all`], generated from `docs/charts/CSV.csv` ([`Table::csv`],
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
//!   from the merged CSV rows whose columns equal given values ([`Column::from`](spec::Column::from); the
//!   first such row that has the field, or the last with [`Column::last`](spec::Column::last)), optionally
//!   multiplied by a factor ([`Column::times`](spec::Column::times)) or divided by another field
//!   ([`Column::over`](spec::Column::over)), and its [`Format`]. A field that is absent or empty shows as an
//!   empty cell. Instead of one row's field a column may show an [`Aggregate`] over
//!   every merged row that passes its filter ([`Column::over_rows`](spec::Column::over_rows)):
//!   the largest over the smallest (a spread) or both (a range).
//!
//! `cargo xtask tables` rewrites every marked table; `--check` (run by `cargo xtask ci`
//! beside `charts --check`) rewrites nothing and fails, naming the file and the table,
//! when one differs: "run `cargo xtask tables` and commit". An unknown name, a marker
//! without its end or a CSV without a column the spec names fails both.
//!
//! Both also check the tables typed by hand in `docs/benchmarks.md` ([`snapshots`]): each
//! must follow a marker `<!-- snapshot: YYYY-MM-DD; COMMAND -->` saying when it was
//! measured and which command produced its figures.

mod catalog;
mod snapshots;
mod spec;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

pub use spec::{Aggregate, Filter, Format, Record, Table};

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
    let typed = snapshots::check(Path::new("."))?;
    eprintln!(
        "  ({typed} typed tables in {}: dated snapshots with their command, ok)",
        snapshots::FILES.join(", ")
    );
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
        let Some(table) = catalog::all().find(|t| t.name == name) else {
            bail!("no generated table named `{name}` (xtask/src/tables/catalog/ lists them)");
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
    if let Some(c) = table
        .columns
        .iter()
        .find(|c| c.aggregate.is_some() && c.divisor.is_some())
    {
        bail!(
            "the column `{}` of the table `{}` has both an aggregate and a divisor",
            c.header,
            table.name
        );
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
        let row = table
            .columns
            .iter()
            .map(|c| {
                if let Some(aggregate) = c.aggregate {
                    let fields = members
                        .iter()
                        .map(|&i| record(i))
                        .filter(|r| r.passes(c.from))
                        .filter_map(|r| r.get(c.field).filter(|f| !f.is_empty()));
                    return aggregate_fields(fields, aggregate, c.scale, c.format).with_context(
                        || format!("in the column `{}` of the table `{}`", c.header, table.name),
                    );
                }
                let Some(field) = pick(c.field, c.from, c.from_last) else {
                    return Ok(String::new());
                };
                Ok(match c.divisor {
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
                })
            })
            .collect::<Result<Vec<String>>>()?;
        out.push_str(&cells(row));
    }
    Ok(out)
}

/// `aggregate` of the numbers `fields` (at least one: none gives an empty cell), each
/// multiplied by `scale` first, written as `format` says. Fails on a field that is not a
/// number.
fn aggregate_fields<'a>(
    fields: impl Iterator<Item = &'a str>,
    aggregate: Aggregate,
    scale: f64,
    format: Format,
) -> Result<String> {
    let mut bounds: Option<(f64, f64)> = None;
    for field in fields {
        let v = field
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .with_context(|| format!("`{field}` is not a number"))?
            * scale;
        bounds = Some(bounds.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v))));
    }
    let Some((lo, hi)) = bounds else {
        return Ok(String::new());
    };
    Ok(match aggregate {
        Aggregate::Spread if lo == 0.0 => String::new(),
        Aggregate::Spread => format_number(hi / lo, format),
        Aggregate::Range => format!(
            "{}–{}",
            format_number(lo, format),
            format_number(hi, format)
        ),
    })
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
    use super::spec::{ANY, col};
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

    /// A spread and a range over the merged rows that pass the filter, skipping empty
    /// fields; no field gives an empty cell, a field that is not a number fails.
    #[test]
    fn columns_aggregate_over_the_merged_rows() -> Result<()> {
        const TABLE: Table = Table {
            name: "spread",
            csv: "spread",
            key: &["mesh"],
            keep: |_| true,
            columns: &[
                col("mesh", "mesh", ANY, Format::Text),
                col("L1 spread", "worst", &[("level", "1")], Format::Decimals(3))
                    .over_rows(Aggregate::Spread),
                col("L1 range", "worst", &[("level", "1")], Format::Decimals(2))
                    .over_rows(Aggregate::Range),
                col("L2 range", "worst", &[("level", "2")], Format::Decimals(1))
                    .over_rows(Aggregate::Range)
                    .times(10.0),
            ],
        };
        let dir = std::env::temp_dir().join(format!("xtask-spread-{}", std::process::id()));
        std::fs::create_dir_all(&dir)?;
        std::fs::write(
            dir.join("spread.csv"),
            "mesh,transform,level,worst\ncube,0,1,11.7882\ncube,0,2,5.4858\n\
             cube,1,1,11.8034\ncube,1,2,\ncube,2,1,11.75\ncube,2,2,5.5\n\
             bunny,0,1,0\nbunny,1,1,2\n",
        )?;
        let markdown = render(&TABLE, &dir);
        std::fs::write(dir.join("spread.csv"), "mesh,level,worst\ncube,1,n/a\n")?;
        let not_a_number = render(&TABLE, &dir);
        std::fs::remove_dir_all(&dir)?;
        assert_eq!(
            markdown?,
            "| mesh | L1 spread | L1 range | L2 range |\n| --- | ---: | ---: | ---: |\n\
             | cube | 1.005 | 11.75–11.80 | 54.9–55.0 |\n| bunny |  | 0.00–2.00 |  |\n"
        );
        let error = format!("{:#}", not_a_number.err().context("`n/a` must fail")?);
        assert!(error.contains("`n/a` is not a number"), "{error}");
        assert!(error.contains("L1 spread"), "{error}");
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
