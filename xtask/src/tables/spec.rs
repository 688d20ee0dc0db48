//! What a generated table is: its columns, their CSV fields and formats.

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

/// A figure computed over every merged CSV row that passes a column's filter and has its
/// field (a number; an empty field is skipped), instead of the field of one row.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Aggregate {
    /// The largest over the smallest (no factor applies; empty when the smallest is 0).
    Spread,
    /// The smallest and the largest, each written as the format says, joined by `–`
    /// (`11.78–11.83`).
    Range,
}

/// Conditions on a CSV row: every column `.0` equals `.1` (empty: every row).
pub type Filter = &'static [(&'static str, &'static str)];

/// No condition.
pub(crate) const ANY: Filter = &[];

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
    /// Show this over the merged rows that pass [`Column::from`] rather than one row's
    /// field (`None`: one row's, as [`Column::from_last`] says). Not with a divisor.
    pub aggregate: Option<Aggregate>,
    /// How it is written.
    pub format: Format,
}

impl Column {
    /// The column with its number multiplied by `scale`.
    pub(crate) const fn times(self, scale: f64) -> Self {
        Self { scale, ..self }
    }

    /// The column with its number divided by the field `field` of the merged rows that
    /// pass `from`.
    pub(crate) const fn over(self, field: &'static str, from: Filter) -> Self {
        Self {
            divisor: Some((field, from)),
            ..self
        }
    }

    /// The column taken from the last merged row that passes its filter and has the field.
    pub(crate) const fn last(self) -> Self {
        Self {
            from_last: true,
            ..self
        }
    }

    /// The column showing `aggregate` of the field over the merged rows that pass its
    /// filter.
    pub(crate) const fn over_rows(self, aggregate: Aggregate) -> Self {
        Self {
            aggregate: Some(aggregate),
            ..self
        }
    }
}

/// One CSV row, by column name.
pub struct Record<'a> {
    /// The CSV's column names.
    pub(crate) header: &'a [String],
    /// This row's fields, in the same order.
    pub(crate) fields: &'a [String],
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
    pub(crate) fn passes(&self, filter: Filter) -> bool {
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
pub(crate) const fn col(
    header: &'static str,
    field: &'static str,
    from: Filter,
    format: Format,
) -> Column {
    Column {
        header,
        field,
        from,
        from_last: false,
        scale: 1.0,
        divisor: None,
        aggregate: None,
        format,
    }
}
