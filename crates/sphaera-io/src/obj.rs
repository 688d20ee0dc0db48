//! Wavefront OBJ reader.
//!
//! Reads `v` (the first three numbers; a `w` or vertex colours are ignored) and `f` records
//! (`v`, `v/vt`, `v//vn`, `v/vt/vn`; 1-based, negative indices count back from the last
//! vertex read). Everything else (`vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, `p`,
//! comments) is skipped. A line ending in `\` continues on the next line. A face may refer
//! to a vertex defined later in the file; such forward references are checked at the end.

use std::borrow::Cow;

use super::builder::MeshBuilder;
use super::parse_error::token_text;
use super::text::{Lines, is_blank, parse_i64, parse_xyz, strip_comment, tokens};
use super::{Format, LoadedMesh, Location, ParseReason};
use crate::IoError;

fn error(line: usize, reason: ParseReason) -> IoError {
    IoError::Parse {
        path: None,
        format: Format::Obj,
        location: Location::Line(line),
        reason,
    }
}

/// Logical lines: physical lines joined where one ends in a backslash.
struct LogicalLines<'a> {
    lines: Lines<'a>,
}

impl<'a> Iterator for LogicalLines<'a> {
    type Item = (usize, Cow<'a, [u8]>);

    fn next(&mut self) -> Option<Self::Item> {
        let (number, first) = self.lines.next()?;
        let Some(stripped) = first.strip_suffix(b"\\") else {
            return Some((number, Cow::Borrowed(first)));
        };
        let mut joined = stripped.to_vec();
        joined.push(b' ');
        for (_, next) in self.lines.by_ref() {
            match next.strip_suffix(b"\\") {
                Some(part) => {
                    joined.extend_from_slice(part);
                    joined.push(b' ');
                }
                None => {
                    joined.extend_from_slice(next);
                    break;
                }
            }
        }
        Some((number, Cow::Owned(joined)))
    }
}

/// Parses OBJ data.
pub(crate) fn read_obj(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    let mut builder = MeshBuilder::default();
    // Rough capacity guess: about 30 bytes per vertex line, two faces per vertex.
    builder.positions.reserve(bytes.len() / 90);
    builder.reserve_triangles(bytes.len() / 45);
    let mut face: Vec<u32> = Vec::with_capacity(8);
    // Positive indices that pointed past the vertices read so far: (line, index).
    let mut forward: Vec<(usize, i64)> = Vec::new();
    let mut any_record = false;
    let lines = LogicalLines {
        lines: Lines::new(bytes, 1),
    };
    for (line, content) in lines {
        let content = strip_comment(&content);
        let mut toks = tokens(content);
        let Some(keyword) = toks.next() else { continue };
        match keyword {
            b"v" => {
                any_record = true;
                parse_xyz(&mut toks)
                    .and_then(|xyz| builder.push_vertex(xyz))
                    .map_err(|reason| error(line, reason))?;
            }
            b"f" | b"fo" => {
                any_record = true;
                face.clear();
                let count = builder.positions.len();
                for tok in toks {
                    let index_part = tok.split(|&b| b == b'/').next().unwrap_or(tok);
                    let raw = parse_i64(index_part).ok_or_else(|| {
                        error(
                            line,
                            ParseReason::InvalidNumber {
                                expected: "a vertex index",
                                found: token_text(tok),
                            },
                        )
                    })?;
                    let resolved = match raw {
                        0 => return Err(error(line, ParseReason::ZeroIndex)),
                        r if r < 0 => {
                            let back = r.unsigned_abs();
                            if back > count as u64 {
                                return Err(error(
                                    line,
                                    ParseReason::IndexOutOfRange {
                                        index: r,
                                        vertex_count: count,
                                    },
                                ));
                            }
                            count as u64 - back
                        }
                        r => {
                            let zero_based = r.unsigned_abs() - 1;
                            if zero_based >= count as u64 {
                                if zero_based >= u64::from(u32::MAX) {
                                    return Err(error(
                                        line,
                                        ParseReason::IndexOutOfRange {
                                            index: r,
                                            vertex_count: count,
                                        },
                                    ));
                                }
                                forward.push((line, r));
                            }
                            zero_based
                        }
                    };
                    // Both branches bound `resolved` below u32::MAX (checked above).
                    face.push(u32::try_from(resolved).unwrap_or(u32::MAX));
                }
                builder
                    .push_face(&face)
                    .map_err(|reason| error(line, reason))?;
            }
            _ => {}
        }
    }
    if !any_record {
        let last_line = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
        let line = if is_blank(bytes) { 1 } else { last_line };
        return Err(error(line, ParseReason::EmptyFile));
    }
    let count = builder.positions.len();
    if let Some(&(line, index)) = forward
        .iter()
        .find(|(_, i)| i.unsigned_abs() > count as u64)
    {
        return Err(error(
            line,
            ParseReason::IndexOutOfRange {
                index,
                vertex_count: count,
            },
        ));
    }
    let report = MeshBuilder::report(Format::Obj, count);
    builder.finish(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reason(bytes: &[u8]) -> (Location, ParseReason) {
        super::super::tests::parse_error(bytes, Format::Obj)
    }

    #[test]
    fn all_face_index_forms_and_negative_indices() {
        let obj = b"# comment\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1 1.0\nvt 0 0\nvn 0 0 1\n\
            g group\no object\ns 1\nusemtl m\nmtllib a.mtl\n\
            f 1 2 3\nf 1/1 2/1 4/1\nf 1//1 3//1 4//1\nf 2/1/1 3/1/1 4/1/1\nf -4 -3 -1 # tail\n";
        let loaded = read_obj(obj).unwrap();
        assert_eq!(loaded.mesh.vertex_count(), 4);
        assert_eq!(
            loaded.mesh.triangles(),
            &[[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3], [0, 1, 3]]
        );
        assert_eq!(loaded.report.faces_in_file, 5);
    }

    #[test]
    fn line_continuation_joins_lines() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n 2 \\\n3\nv 0 0 1\nf 1 2 4\n";
        let loaded = read_obj(obj).unwrap();
        assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 1, 3]]);
    }

    #[test]
    fn forward_references_are_allowed_and_checked() {
        let ok = read_obj(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(ok.mesh.triangle_count(), 1);
        let (loc, why) = reason(b"v 0 0 0\nf 1 2 3\nv 1 0 0\nf 1 2 9\nv 0 1 0\n");
        assert_eq!(loc, Location::Line(4));
        assert_eq!(
            why,
            ParseReason::IndexOutOfRange {
                index: 9,
                vertex_count: 3
            }
        );
    }

    #[test]
    fn errors_carry_line_numbers() {
        assert_eq!(
            reason(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 0\n"),
            (Location::Line(5), ParseReason::ZeroIndex)
        );
        assert_eq!(
            reason(b"v 0 0 0\nf 1 -2 1\n"),
            (
                Location::Line(2),
                ParseReason::IndexOutOfRange {
                    index: -2,
                    vertex_count: 1
                }
            )
        );
        assert_eq!(
            reason(b"v 0 0\n"),
            (
                Location::Line(1),
                ParseReason::MissingValues {
                    expected: 3,
                    found: 2
                }
            )
        );
        assert!(matches!(
            reason(b"v 0 0 0\nv 0 nan 0\n"),
            (
                Location::Line(2),
                ParseReason::NonFiniteCoordinate {
                    vertex: 1,
                    axis: 'y',
                    ..
                }
            )
        ));
        assert!(matches!(
            reason(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"),
            (Location::Line(4), ParseReason::InvalidNumber { .. })
        ));
        assert_eq!(
            reason(b"v 0 0 0\nv 1 0 0\nf 1 2\n"),
            (
                Location::Line(3),
                ParseReason::TooFewFaceVertices { count: 2 }
            )
        );
        assert_eq!(reason(b""), (Location::Line(1), ParseReason::EmptyFile));
        assert_eq!(
            reason(b"# only\n# comments\n"),
            (Location::Line(3), ParseReason::EmptyFile)
        );
    }

    #[test]
    fn quads_are_triangulated_in_place() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n";
        let loaded = read_obj(obj).unwrap();
        assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 2, 3], [0, 1, 2]]);
        assert_eq!(loaded.report.polygons_triangulated, 1);
        assert_eq!(loaded.report.faces_in_file, 2);
    }
}
