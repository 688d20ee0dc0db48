//! Object File Format (OFF) reader.
//!
//! The header keyword is `OFF` with the optional prefixes of the Geomview family
//! (`ST`, `C`, `N`: `COFF`, `NOFF`, `CNOFF`, `STCNOFF`...). The counts `vertices faces
//! [edges]` follow, on the keyword's line or the next one. Each vertex line holds at least
//! three coordinates (extra values such as normals, colours or texture coordinates are
//! ignored); each face line holds `n` and `n` 0-based indices (a trailing colour is
//! ignored). `#` starts a comment. Binary OFF and 4D/`nOFF` variants are refused with
//! [`ParseReason::Unsupported`].

use super::builder::MeshBuilder;
use super::parse_error::token_text;
use super::text::{Lines, is_blank, parse_i64, parse_xyz, strip_comment, tokens};
use super::{Format, LoadedMesh, Location, ParseReason};
use crate::IoError;

fn error(line: usize, reason: ParseReason) -> IoError {
    IoError::Parse {
        path: None,
        format: Format::Off,
        location: Location::Line(line),
        reason,
    }
}

/// Whether `token` is an OFF header keyword; `Err` for the variants this reader refuses.
pub(crate) fn header_keyword(token: &[u8]) -> Option<Result<(), &'static str>> {
    let mut rest = token;
    rest = rest.strip_prefix(b"ST").unwrap_or(rest);
    rest = rest.strip_prefix(b"C").unwrap_or(rest);
    rest = rest.strip_prefix(b"N").unwrap_or(rest);
    let four = rest.strip_prefix(b"4");
    rest = four.unwrap_or(rest);
    let dims = rest.strip_prefix(b"n");
    rest = dims.unwrap_or(rest);
    (rest == b"OFF").then_some(if four.is_some() || dims.is_some() {
        Err("4D and n-dimensional OFF")
    } else {
        Ok(())
    })
}

/// Parses OFF data.
pub(crate) fn read_off(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    if is_blank(bytes) {
        return Err(error(1, ParseReason::EmptyFile));
    }
    let mut lines = Lines::new(bytes, 1)
        .map(|(n, l)| (n, strip_comment(l)))
        .filter(|(_, l)| !is_blank(l));
    let Some((header_line, header)) = lines.next() else {
        return Err(error(1, ParseReason::EmptyFile));
    };
    let mut toks = tokens(header);
    match toks.next().and_then(header_keyword) {
        Some(Ok(())) => {}
        Some(Err(feature)) => {
            return Err(error(header_line, ParseReason::Unsupported { feature }));
        }
        None => {
            return Err(error(
                header_line,
                ParseReason::BadMagic { expected: "OFF" },
            ));
        }
    }
    let mut count_tokens: Vec<&[u8]> = toks.collect();
    if count_tokens.first() == Some(&&b"BINARY"[..]) {
        return Err(error(
            header_line,
            ParseReason::Unsupported {
                feature: "binary OFF",
            },
        ));
    }
    let mut counts_line = header_line;
    if count_tokens.is_empty() {
        let Some((line, content)) = lines.next() else {
            return Err(error(
                header_line,
                ParseReason::UnexpectedEnd {
                    expected: "the vertex and face counts",
                },
            ));
        };
        counts_line = line;
        count_tokens = tokens(content).collect();
    }
    let mut counts = [0usize; 2];
    for (k, slot) in counts.iter_mut().enumerate() {
        let Some(tok) = count_tokens.get(k) else {
            return Err(error(
                counts_line,
                ParseReason::MissingValues {
                    expected: 2,
                    found: k,
                },
            ));
        };
        let value = parse_i64(tok).ok_or_else(|| {
            error(
                counts_line,
                ParseReason::InvalidNumber {
                    expected: "a count",
                    found: token_text(tok),
                },
            )
        })?;
        *slot = usize::try_from(value).map_err(|_| {
            error(
                counts_line,
                ParseReason::InvalidCount {
                    what: "count",
                    value: value as f64,
                },
            )
        })?;
    }
    let [vertex_count, face_count] = counts;
    if vertex_count > u32::MAX as usize {
        return Err(error(
            counts_line,
            ParseReason::TooManyVertices {
                count: vertex_count as u64,
            },
        ));
    }
    let mut builder = MeshBuilder::default();
    builder.positions.reserve(vertex_count.min(bytes.len() / 6));
    builder.reserve_triangles(face_count.min(bytes.len() / 8));
    let mut last_line = counts_line;
    let missing = |element: &str, expected: usize, found: usize, line: usize| {
        error(
            line,
            ParseReason::MissingRecords {
                element: element.to_owned(),
                expected,
                found,
            },
        )
    };
    for vertex in 0..vertex_count {
        let Some((line, content)) = lines.next() else {
            return Err(missing("vertex", vertex_count, vertex, last_line));
        };
        last_line = line;
        parse_xyz(&mut tokens(content))
            .and_then(|xyz| builder.push_vertex(xyz))
            .map_err(|reason| error(line, reason))?;
    }
    let mut face: Vec<u32> = Vec::with_capacity(8);
    for index in 0..face_count {
        let Some((line, content)) = lines.next() else {
            return Err(missing("face", face_count, index, last_line));
        };
        last_line = line;
        let mut toks = tokens(content);
        let invalid = |tok: &[u8], expected: &'static str| {
            error(
                line,
                ParseReason::InvalidNumber {
                    expected,
                    found: token_text(tok),
                },
            )
        };
        let Some(n_tok) = toks.next() else {
            continue; // Unreachable: blank lines were filtered out.
        };
        let n = parse_i64(n_tok).ok_or_else(|| invalid(n_tok, "a face vertex count"))?;
        // Each index takes at least two bytes (a digit and a separator), so a count above
        // the line's length cannot be honoured: it is invalid, not a list of missing values.
        let n = match usize::try_from(n) {
            Ok(n) if n <= content.len() => n,
            _ => {
                return Err(error(
                    line,
                    ParseReason::InvalidCount {
                        what: "face vertex count",
                        value: n as f64,
                    },
                ));
            }
        };
        if n < 3 {
            return Err(error(line, ParseReason::TooFewFaceVertices { count: n }));
        }
        face.clear();
        for k in 0..n {
            let Some(tok) = toks.next() else {
                return Err(error(
                    line,
                    ParseReason::MissingValues {
                        expected: n + 1,
                        found: k + 1,
                    },
                ));
            };
            let value = parse_i64(tok).ok_or_else(|| invalid(tok, "a vertex index"))?;
            match u32::try_from(value) {
                Ok(i) if (i as usize) < vertex_count => face.push(i),
                _ => {
                    return Err(error(
                        line,
                        ParseReason::IndexOutOfRange {
                            index: value,
                            vertex_count,
                        },
                    ));
                }
            }
        }
        builder
            .push_face(&face)
            .map_err(|reason| error(line, reason))?;
    }
    builder.finish(MeshBuilder::report(Format::Off, vertex_count))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_error(bytes: &[u8]) -> (Location, ParseReason) {
        super::super::tests::parse_error(bytes, Format::Off)
    }

    #[test]
    fn variants_comments_and_polygons() {
        let off = b"# a square and a triangle\nCOFF\n# counts\n5 2 0\n0 0 0 255 0 0\n1 0 0\n1 1 0\n0 1 0\n\n2 2 2\n4 0 1 2 3 1 0 0\n3 1 4 2\n";
        let loaded = read_off(off).unwrap();
        assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 2, 3], [1, 4, 2]]);
        assert_eq!(loaded.report.vertex_records, 5);
        assert_eq!(loaded.report.faces_in_file, 2);
        assert_eq!(loaded.report.polygons_triangulated, 1);
        let inline = read_off(b"OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(inline.mesh.triangle_count(), 1);
        assert!(read_off(b"NOFF\n3 1 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n").is_ok());
    }

    #[test]
    fn errors_have_lines() {
        assert_eq!(
            parse_error(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            (
                Location::Line(6),
                ParseReason::IndexOutOfRange {
                    index: 3,
                    vertex_count: 3
                }
            )
        );
        assert_eq!(
            parse_error(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            (
                Location::Line(6),
                ParseReason::TooFewFaceVertices { count: 2 }
            )
        );
        assert_eq!(
            parse_error(b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            (
                Location::Line(6),
                ParseReason::MissingRecords {
                    element: "face".to_owned(),
                    expected: 2,
                    found: 1
                }
            )
        );
        assert!(matches!(
            parse_error(b"OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"),
            (
                Location::Line(4),
                ParseReason::NonFiniteCoordinate {
                    vertex: 1,
                    axis: 'y',
                    ..
                }
            )
        ));
        assert_eq!(
            parse_error(b"PFF\n"),
            (Location::Line(1), ParseReason::BadMagic { expected: "OFF" })
        );
        assert_eq!(
            parse_error(b"OFF BINARY\n"),
            (
                Location::Line(1),
                ParseReason::Unsupported {
                    feature: "binary OFF"
                }
            )
        );
        assert_eq!(
            parse_error(b"  \n"),
            (Location::Line(1), ParseReason::EmptyFile)
        );
    }

    #[test]
    fn negative_or_huge_face_vertex_counts_are_invalid_counts() {
        let head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
        for (face, value) in [("-3 0 1 2", -3.0), ("9200000000000000000 0 1 2", 9.2e18)] {
            assert_eq!(
                parse_error(format!("{head}{face}\n").as_bytes()),
                (
                    Location::Line(6),
                    ParseReason::InvalidCount {
                        what: "face vertex count",
                        value
                    }
                ),
                "{face}"
            );
        }
        // A count the line could hold is a list of missing values.
        assert_eq!(
            parse_error(format!("{head}5 0 1 2\n").as_bytes()),
            (
                Location::Line(6),
                ParseReason::MissingValues {
                    expected: 6,
                    found: 4
                }
            )
        );
    }
}
