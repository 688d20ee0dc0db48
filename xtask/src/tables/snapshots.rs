//! The typed tables of `docs/benchmarks.md`: each a dated snapshot naming its command.
//!
//! A markdown table there that is not generated (between `<!-- table: NAME -->` and
//! `<!-- /table -->`, see the [module](super)) was typed from a run: criterion benches,
//! historic before/after comparisons, CLI runs. It must say when and how, in a marker
//! comment alone on its line above it:
//!
//! ```text
//! <!-- snapshot: 2026-11-21; cargo bench -p sphaera-io --bench load_topology -->
//! | mesh | step | time |
//! |---|---|---:|
//! ```
//!
//! with a valid date and a non-empty command. The marker may stand up to [`REACH`] lines of
//! prose, blank lines, pictures or code above the table; it serves every following table
//! of its section (up to the next heading, generated table or marker) while each stands
//! within [`REACH`] lines of the one before. A table is a line starting with `|` followed
//! by a separator line (`|---|---:|`, `| --- |`), indented or not; fenced code is skipped.
//! A marker serving no table, or malformed, fails too.

use std::path::Path;

use anyhow::{Context, Result, bail};

use super::{CLOSE, OPEN};

/// The files whose typed tables must be snapshots.
pub const FILES: &[&str] = &["docs/benchmarks.md"];

/// The marker's start.
const MARKER: &str = "<!-- snapshot:";

/// How many lines a marker (or the table it serves) may stand above a table.
pub const REACH: usize = 40;

/// Checks every file of [`FILES`] under `root`, returning how many typed tables they
/// hold; fails naming the file and line of every unmarked table and malformed or
/// unused marker.
pub fn check(root: &Path) -> Result<usize> {
    let mut count = 0;
    let mut problems = Vec::new();
    for file in FILES {
        let path = root.join(file);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let report = scan(&text);
        count += report.tables;
        problems.extend(
            report
                .problems
                .into_iter()
                .map(|(line, problem)| format!("{file}:{line}: {problem}")),
        );
    }
    if !problems.is_empty() {
        bail!(
            "{} problem(s) with the typed tables (each must be a dated snapshot: \
             `{MARKER} YYYY-MM-DD; COMMAND -->` alone on a line above it, COMMAND the \
             command that produced its figures; or generate it, `{OPEN} NAME -->`):\n  {}",
            problems.len(),
            problems.join("\n  ")
        );
    }
    Ok(count)
}

/// What [`scan`] found.
#[derive(Debug, Default, PartialEq, Eq)]
struct Report {
    /// The typed tables.
    tables: usize,
    /// Per problem its line (from 1) and what is wrong.
    problems: Vec<(usize, String)>,
}

/// A marker above the tables being read.
struct Serving {
    /// Its line (from 1).
    line: usize,
    /// The lines since it, or since the last table it served.
    since: usize,
    /// Whether it served a table.
    used: bool,
}

/// The typed tables of `text` and what is wrong with their markers.
fn scan(text: &str) -> Report {
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let mut report = Report::default();
    let mut serving: Option<Serving> = None;
    // Ends the reach of the marker being read (a heading, a generated table, a new marker,
    // the end), reporting it if it served nothing.
    let end = |serving: &mut Option<Serving>, report: &mut Report| {
        if let Some(s) = serving.take().filter(|s| !s.used) {
            report.problems.push((
                s.line,
                format!(
                    "this snapshot marker serves no table (a table must follow within \
                     {REACH} lines, in the same section)"
                ),
            ));
        }
    };
    let mut fence: Option<&str> = None;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let number = i + 1;
        i += 1;
        if let Some(open) = fence {
            if line.starts_with(open) {
                fence = None;
            }
            bump(&mut serving);
            continue;
        }
        if let Some(open) = ["```", "~~~"].into_iter().find(|f| line.starts_with(f)) {
            fence = Some(open);
            bump(&mut serving);
            continue;
        }
        if line.starts_with(OPEN) {
            // A generated table: skipped to its end, which ends the marker's reach.
            end(&mut serving, &mut report);
            while i < lines.len() && lines[i] != CLOSE {
                i += 1;
            }
            i += 1;
            continue;
        }
        if line.starts_with('#') {
            end(&mut serving, &mut report);
            continue;
        }
        if line.starts_with(MARKER) {
            end(&mut serving, &mut report);
            if let Err(e) = parse_marker(line) {
                report
                    .problems
                    .push((number, format!("`{line}` is not a snapshot marker: {e:#}")));
            }
            serving = Some(Serving {
                line: number,
                since: 0,
                used: false,
            });
            continue;
        }
        if line.starts_with('|') && lines.get(i).is_some_and(|next| is_separator(next)) {
            report.tables += 1;
            match serving.as_mut().filter(|s| s.since <= REACH) {
                Some(s) => {
                    s.used = true;
                    s.since = 0;
                }
                None => {
                    end(&mut serving, &mut report);
                    report.problems.push((
                        number,
                        format!(
                            "a typed table without a snapshot marker within {REACH} lines \
                             above it in its section; add `{MARKER} YYYY-MM-DD; COMMAND -->` \
                             (the date of the run and the command that produced its \
                             figures) on its own line above it"
                        ),
                    ));
                }
            }
            // Its rows.
            while i < lines.len() && lines[i].starts_with('|') {
                i += 1;
            }
            continue;
        }
        bump(&mut serving);
    }
    end(&mut serving, &mut report);
    report
}

/// One more line between the marker being read and the next table.
fn bump(serving: &mut Option<Serving>) {
    if let Some(s) = serving {
        s.since += 1;
    }
}

/// Whether `line` (trimmed) is a table's separator line: `|`, then only `|`, `-`, `:` and
/// spaces, with a `-`.
fn is_separator(line: &str) -> bool {
    line.starts_with('|')
        && line.contains('-')
        && line
            .chars()
            .all(|c| matches!(c, '|' | '-' | ':' | ' ' | '\t'))
}

/// The date and command of a marker line (trimmed).
fn parse_marker(line: &str) -> Result<(&str, &str)> {
    let inner = line
        .strip_prefix(MARKER)
        .and_then(|rest| rest.strip_suffix("-->"))
        .context("it must end in `-->` on the same line")?;
    let (date, command) = inner
        .split_once(';')
        .context("it must be `DATE; COMMAND`")?;
    let (date, command) = (date.trim(), command.trim());
    if !is_date(date) {
        bail!("`{date}` is not a date YYYY-MM-DD");
    }
    if command.is_empty() {
        bail!("the command that produced the figures is missing");
    }
    Ok((date, command))
}

/// Whether `date` is a valid date written `YYYY-MM-DD`.
fn is_date(date: &str) -> bool {
    let bytes = date.as_bytes();
    let digits = |range: std::ops::Range<usize>| {
        bytes[range.clone()].iter().all(u8::is_ascii_digit) && !range.is_empty()
    };
    if bytes.len() != 10 || bytes[4] != b'-' || bytes[7] != b'-' {
        return false;
    }
    if !(digits(0..4) && digits(5..7) && digits(8..10)) {
        return false;
    }
    let number = |range: std::ops::Range<usize>| date[range].parse::<u32>().unwrap_or(0);
    let (year, month, day) = (number(0..4), number(5..7), number(8..10));
    let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
    let days = match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => return false,
    };
    (1..=days).contains(&day)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lines of the problems `text` has.
    fn problem_lines(text: &str) -> Vec<usize> {
        scan(text).problems.into_iter().map(|(l, _)| l).collect()
    }

    const TABLE: &str = "| a | b |\n|---|---:|\n| x | 1 |\n";

    #[test]
    fn a_marked_table_passes() {
        let text = format!(
            "# T\n\nProse.\n\n<!-- snapshot: 2026-11-21; cargo bench -p x --bench y -->\n\n\
             More prose.\n\n{TABLE}"
        );
        assert_eq!(
            scan(&text),
            Report {
                tables: 1,
                problems: vec![]
            }
        );
    }

    #[test]
    fn an_unmarked_table_fails_at_its_line() {
        let text = format!("# T\n\nProse.\n\n{TABLE}");
        let report = scan(&text);
        assert_eq!(report.tables, 1);
        assert_eq!(problem_lines(&text), vec![5]);
        assert!(
            report.problems[0]
                .1
                .contains("<!-- snapshot: YYYY-MM-DD; COMMAND -->")
        );
        // Indented (in a list item), with spaced separators.
        let text = "- item\n\n  | a | b |\n  | --- | :---: |\n  | x | 1 |\n";
        assert_eq!(problem_lines(text), vec![3]);
    }

    #[test]
    fn generated_tables_and_code_are_exempt() {
        let text = format!(
            "# T\n\n<!-- table: name -->\n{TABLE}<!-- /table -->\n\n```text\n{TABLE}```\n\n\
             | not a table |\nprose\n"
        );
        assert_eq!(
            scan(&text),
            Report {
                tables: 0,
                problems: vec![]
            }
        );
    }

    #[test]
    fn bad_markers_fail() {
        for marker in [
            "<!-- snapshot: 2026-02-30; cargo bench -->",
            "<!-- snapshot: 2026-13-01; cargo bench -->",
            "<!-- snapshot: 26-11-21; cargo bench -->",
            "<!-- snapshot: yesterday; cargo bench -->",
            "<!-- snapshot: 2026-11-21; -->",
            "<!-- snapshot: 2026-11-21 cargo bench -->",
            "<!-- snapshot: 2026-11-21; cargo bench",
        ] {
            let text = format!("{marker}\n{TABLE}");
            assert_eq!(problem_lines(&text), vec![1], "{marker}");
        }
        assert!(is_date("2024-02-29") && !is_date("2100-02-29") && is_date("2000-02-29"));
    }

    #[test]
    fn a_marker_serves_the_tables_of_its_section_only() {
        let marker = "<!-- snapshot: 2026-11-21; cargo bench -->\n";
        // Two tables of one section, one marker.
        let text = format!("{marker}{TABLE}\nProse between.\n\n{TABLE}");
        assert_eq!(scan(&text).tables, 2);
        assert_eq!(problem_lines(&text), Vec::<usize>::new());
        // Not past a heading (the marker then serves nothing either) ...
        let text = format!("{marker}\n## Next\n\n{TABLE}");
        assert_eq!(problem_lines(&text), vec![1, 5]);
        // ... nor a heading after a table it served.
        let text = format!("{marker}{TABLE}\n### Next\n\n{TABLE}");
        assert_eq!(problem_lines(&text), vec![8]);
        // Nor past a generated table.
        let text = format!("{marker}{TABLE}<!-- table: t -->\n{TABLE}<!-- /table -->\n{TABLE}");
        assert_eq!(problem_lines(&text), vec![10]);
        // A `#` in fenced code is no heading.
        let text = format!("{marker}```sh\n# comment\n```\n{TABLE}");
        assert_eq!(problem_lines(&text), Vec::<usize>::new());
    }

    #[test]
    fn a_marker_reaches_so_far() {
        let marker = "<!-- snapshot: 2026-11-21; cargo bench -->\n";
        let near = format!("{marker}{}{TABLE}", "prose\n".repeat(REACH));
        assert_eq!(problem_lines(&near), Vec::<usize>::new());
        let far = format!("{marker}{}{TABLE}", "prose\n".repeat(REACH + 1));
        assert_eq!(problem_lines(&far), vec![1, REACH + 3]);
    }
}
