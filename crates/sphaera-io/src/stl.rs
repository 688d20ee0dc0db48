//! STL reader (ASCII and binary), with vertex welding.
//!
//! **Binary or ASCII?** A binary STL is an 80-byte header, a little-endian `u32` facet
//! count `n`, and `n` records of 50 bytes, so its size is `84 + 50 n`. Binary exporters
//! often start the free-form header with `solid`, so the keyword alone proves nothing.
//! The rule is: data whose size is exactly `84 + 50 n` are binary; otherwise data are
//! ASCII only if they start with `solid` (after whitespace) **and** their first
//! [`TEXT_WINDOW`] bytes are text (no NUL or other control byte besides whitespace)
//! **and** those bytes hold the keyword `facet` or `endsolid` (or are the whole file);
//! everything else is binary. So a truncated binary file whose header starts with `solid`
//! gets a size error, never an empty mesh.
//!
//! **Size of a binary file.** Fewer than `84 + 50 n` bytes is a truncation error
//! ([`ParseReason::SizeMismatch`] at the end of the data). A tail of fewer than 50 extra
//! bytes (padding some exporters add) is ignored; a tail of 50 bytes or more could hold
//! facets the count does not announce, so it is a [`ParseReason::SizeMismatch`] error at
//! the first extra byte rather than data silently dropped.
//!
//! **ASCII checks.** An ASCII file must end its solid with `endsolid`, and must not hold
//! binary bytes ([`ParseReason::BinaryByte`]), so a binary blob that happens to start with
//! `solid` is never read as an empty ASCII solid.
//!
//! **Welding.** STL stores three positions per facet and no indices. The reader merges
//! positions whose coordinates are bit-identical (with `-0.0` taken as `0.0`), in order of
//! first appearance, so the mesh is indexed and its topology can be built. Nothing is
//! merged by distance. The number of merged records is [`LoadReport::welded_vertices`].
//!
//! Facet normals and attribute bytes are ignored; ASCII loops with more than three
//! vertices are triangulated like any polygon.
//!
//! [`LoadReport::welded_vertices`]: super::LoadReport::welded_vertices

use std::collections::HashMap;

use glam::DVec3;

use super::builder::{MeshBuilder, finite_point};
use super::parse_error::token_text;
use super::text::{Lines, is_blank, parse_xyz, tokens};
use super::{Format, LoadedMesh, Location, ParseReason};
use crate::IoError;

fn error(location: Location, reason: ParseReason) -> IoError {
    IoError::Parse {
        path: None,
        format: Format::Stl,
        location,
        reason,
    }
}

/// How many leading bytes the ASCII/binary decision looks at.
pub(crate) const TEXT_WINDOW: usize = 512;

/// Whether `byte` can appear in a text file: printable, whitespace, or non-ASCII (UTF-8
/// names); NUL and the other control bytes cannot.
#[inline]
pub(crate) fn is_text_byte(byte: u8) -> bool {
    byte >= 0x20 && byte != 0x7f || matches!(byte, b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

/// Whether `haystack` contains `word`, ignoring ASCII case.
fn contains_keyword(haystack: &[u8], word: &[u8]) -> bool {
    haystack
        .windows(word.len())
        .any(|w| w.eq_ignore_ascii_case(word))
}

/// Whether the data are binary STL (see the module docs for the rule).
pub(crate) fn is_binary(bytes: &[u8]) -> bool {
    if let Some(count) = bytes.get(80..84) {
        let n = u64::from(u32::from_le_bytes([count[0], count[1], count[2], count[3]]));
        if 84 + 50 * n == bytes.len() as u64 {
            return true;
        }
    }
    let window = &bytes[..bytes.len().min(TEXT_WINDOW)];
    let ascii = starts_with_solid(bytes)
        && window.iter().all(|&b| is_text_byte(b))
        && (window.len() == bytes.len()
            || contains_keyword(window, b"facet")
            || contains_keyword(window, b"endsolid"));
    !ascii
}

/// Whether the data start (after whitespace) with the keyword `solid`.
pub(crate) fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    bytes
        .get(start..start + 5)
        .is_some_and(|word| word.eq_ignore_ascii_case(b"solid"))
}

/// [`ParseReason::NonFiniteFacetCoordinate`] for corner `corner` of facet `facet`, if a
/// coordinate of `xyz` is NaN or infinite.
#[inline]
fn finite_corner(xyz: [f64; 3], facet: usize, corner: usize) -> Result<DVec3, ParseReason> {
    match finite_point(xyz, 0) {
        Ok(p) => Ok(p),
        Err(ParseReason::NonFiniteCoordinate { axis, value, .. }) => {
            Err(ParseReason::NonFiniteFacetCoordinate {
                facet,
                corner,
                axis,
                value,
            })
        }
        Err(other) => Err(other),
    }
}

/// Merges bit-identical positions.
struct Welder {
    builder: MeshBuilder,
    map: HashMap<[u64; 3], u32>,
    records: usize,
}

impl Welder {
    fn new(facets_hint: usize) -> Self {
        let mut builder = MeshBuilder::default();
        builder.reserve_triangles(facets_hint);
        builder.positions.reserve(facets_hint / 2 + 3);
        Self {
            builder,
            map: HashMap::with_capacity(facets_hint / 2 + 3),
            records: 0,
        }
    }

    /// Index of `p` (finite), or `None` when the vertex count overflows a `u32`.
    fn index(&mut self, p: DVec3) -> Option<u32> {
        self.records += 1;
        // `+ 0.0` turns -0.0 into 0.0, so the two zeros weld.
        let key = [
            (p.x + 0.0).to_bits(),
            (p.y + 0.0).to_bits(),
            (p.z + 0.0).to_bits(),
        ];
        let next = u32::try_from(self.builder.positions.len()).ok()?;
        let index = *self.map.entry(key).or_insert(next);
        if index == next {
            self.builder.positions.push(p);
        }
        Some(index)
    }

    fn finish(self) -> Result<LoadedMesh, IoError> {
        let unique = self.builder.positions.len();
        let mut report = MeshBuilder::report(Format::Stl, self.records);
        report.welded_vertices = self.records - unique;
        self.builder.finish(report)
    }
}

/// Parses STL data, binary or ASCII.
pub(crate) fn read_stl(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    if is_blank(bytes) {
        return Err(error(Location::Byte(0), ParseReason::EmptyFile));
    }
    if is_binary(bytes) {
        read_binary(bytes)
    } else {
        read_ascii(bytes)
    }
}

fn read_binary(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    let Some(count) = bytes.get(80..84) else {
        return Err(error(
            Location::Byte(bytes.len() as u64),
            ParseReason::SizeMismatch {
                expected: 84,
                found: bytes.len() as u64,
            },
        ));
    };
    let n = u32::from_le_bytes([count[0], count[1], count[2], count[3]]) as usize;
    let expected = 84 + 50 * n as u64;
    let found = bytes.len() as u64;
    if found < expected {
        return Err(error(
            Location::Byte(found),
            ParseReason::SizeMismatch { expected, found },
        ));
    }
    if found - expected >= 50 {
        // Room for facets the count does not announce: refuse rather than drop them.
        return Err(error(
            Location::Byte(expected),
            ParseReason::SizeMismatch { expected, found },
        ));
    }
    let mut welder = Welder::new(n);
    let mut face = [0u32; 3];
    for (facet, record) in bytes[84..].chunks_exact(50).take(n).enumerate() {
        let offset = 84 + 50 * facet as u64;
        for (corner, slot) in face.iter_mut().enumerate() {
            let base = 12 + 12 * corner;
            let mut xyz = [0.0; 3];
            for (axis, value) in xyz.iter_mut().enumerate() {
                let at = base + 4 * axis;
                let raw = [record[at], record[at + 1], record[at + 2], record[at + 3]];
                *value = f64::from(f32::from_le_bytes(raw));
            }
            let p = finite_corner(xyz, facet, corner)
                .map_err(|reason| error(Location::Byte(offset + base as u64), reason))?;
            *slot = welder.index(p).ok_or_else(|| {
                error(
                    Location::Byte(offset),
                    ParseReason::TooManyVertices {
                        count: u64::from(u32::MAX) + 1,
                    },
                )
            })?;
        }
        welder
            .builder
            .push_face(&face)
            .map_err(|reason| error(Location::Byte(offset), reason))?;
    }
    welder.finish()
}

fn read_ascii(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    if let Some(at) = bytes.iter().position(|&b| !is_text_byte(b)) {
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        return Err(error(
            Location::Line(line),
            ParseReason::BinaryByte { byte: bytes[at] },
        ));
    }
    let mut welder = Welder::new(bytes.len() / 250);
    let lines = Lines::new(bytes, 1);
    let mut face: Vec<u32> = Vec::with_capacity(4);
    // Line of the current `outer loop`, if one is open.
    let mut open_loop: Option<usize> = None;
    let mut seen_solid = false;
    let mut ended = false;
    let mut last_line = 1;
    for (line, content) in lines {
        last_line = line;
        let at = Location::Line(line);
        let mut toks = tokens(content);
        let Some(keyword) = toks.next() else { continue };
        // Keywords are matched case-insensitively (some CAD exporters write `FACET NORMAL`).
        let mut lower = [0u8; 8];
        let keyword_lower: &[u8] = match lower.get_mut(..keyword.len()) {
            Some(buffer) => {
                buffer.copy_from_slice(keyword);
                buffer.make_ascii_lowercase();
                buffer
            }
            None => keyword,
        };
        let unexpected = |expected: &'static str, found: &[u8]| {
            error(
                at,
                ParseReason::UnexpectedToken {
                    expected,
                    found: token_text(found),
                },
            )
        };
        match keyword_lower {
            b"solid" if open_loop.is_none() => {
                seen_solid = true;
                ended = false;
            }
            _ if !seen_solid => return Err(error(at, ParseReason::BadMagic { expected: "solid" })),
            b"endsolid" if open_loop.is_none() => {
                seen_solid = false;
                ended = true;
            }
            b"facet" => {
                if toks
                    .next()
                    .is_some_and(|t| t.eq_ignore_ascii_case(b"normal"))
                {
                    parse_xyz(&mut toks).map_err(|reason| error(at, reason))?;
                }
            }
            b"outer" if open_loop.is_none() => {
                open_loop = Some(line);
                face.clear();
            }
            b"vertex" if open_loop.is_some() => {
                let facet = welder.builder.faces;
                let p = parse_xyz(&mut toks)
                    .and_then(|xyz| finite_corner(xyz, facet, face.len()))
                    .map_err(|reason| error(at, reason))?;
                let index = welder.index(p).ok_or_else(|| {
                    error(
                        at,
                        ParseReason::TooManyVertices {
                            count: u64::from(u32::MAX) + 1,
                        },
                    )
                })?;
                face.push(index);
            }
            b"endloop" => match open_loop.take() {
                Some(start) => welder
                    .builder
                    .push_face(&face)
                    .map_err(|reason| error(Location::Line(start), reason))?,
                None => return Err(unexpected("`outer loop` before `endloop`", keyword)),
            },
            b"endfacet" if open_loop.is_none() => {}
            _ => {
                return Err(unexpected(
                    "an STL keyword (solid, facet, outer, vertex, endloop, endfacet, endsolid)",
                    keyword,
                ));
            }
        }
    }
    if let Some(start) = open_loop {
        return Err(error(
            Location::Line(start),
            ParseReason::UnexpectedEnd {
                expected: "a facet loop (no `endloop`)",
            },
        ));
    }
    if !ended {
        return Err(error(
            Location::Line(last_line),
            ParseReason::UnexpectedEnd {
                expected: "a solid (no `endsolid`)",
            },
        ));
    }
    welder.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary(triangles: &[[[f32; 3]; 3]], header: &[u8]) -> Vec<u8> {
        let mut bytes = vec![0u8; 80];
        bytes[..header.len()].copy_from_slice(header);
        bytes.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for tri in triangles {
            bytes.extend_from_slice(&[0u8; 12]);
            for corner in tri {
                for c in corner {
                    bytes.extend_from_slice(&c.to_le_bytes());
                }
            }
            bytes.extend_from_slice(&[0u8; 2]);
        }
        bytes
    }

    const TETRA: [[[f32; 3]; 3]; 4] = [
        [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -0.0]],
    ];

    #[test]
    fn binary_starting_with_solid_is_read_as_binary_and_welded() {
        let bytes = binary(&TETRA, b"solid but actually binary");
        let loaded = read_stl(&bytes).unwrap();
        assert_eq!(loaded.mesh.vertex_count(), 4);
        assert_eq!(loaded.mesh.triangle_count(), 4);
        assert_eq!(loaded.report.vertex_records, 12);
        assert_eq!(loaded.report.welded_vertices, 8);
        assert_eq!(loaded.mesh.triangles()[3], [2, 1, 0]);
    }

    #[test]
    fn truncated_binary_is_a_size_error() {
        let bytes = binary(&TETRA, b"binary");
        let err = read_stl(&bytes[..bytes.len() - 7]).unwrap_err();
        assert!(matches!(
            err,
            IoError::Parse {
                location: Location::Byte(277),
                reason: ParseReason::SizeMismatch {
                    expected: 284,
                    found: 277
                },
                ..
            }
        ));
    }

    #[test]
    fn binary_nan_is_located_at_its_bytes() {
        let mut tri = TETRA;
        tri[1][2][1] = f32::NAN;
        let err = read_stl(&binary(&tri, b"")).unwrap_err();
        assert!(matches!(
            err,
            IoError::Parse {
                location: Location::Byte(170),
                reason: ParseReason::NonFiniteFacetCoordinate {
                    facet: 1,
                    corner: 2,
                    axis: 'y',
                    ..
                },
                ..
            }
        ));
    }

    fn parse_error(bytes: &[u8]) -> (Location, ParseReason) {
        super::super::tests::parse_error(bytes, Format::Stl)
    }

    const ONE: [[[f32; 3]; 3]; 1] = [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]];

    #[test]
    fn solid_header_binary_with_a_trailing_byte_loads_its_facet() {
        for tail in [1, 49] {
            let mut bytes = binary(&ONE, b"solid part exported by a CAD tool");
            bytes.extend(std::iter::repeat_n(b'\n', tail));
            let loaded = read_stl(&bytes).unwrap();
            assert_eq!(loaded.mesh.triangle_count(), 1, "tail {tail}");
            assert_eq!(loaded.mesh.vertex_count(), 3);
        }
    }

    #[test]
    fn binary_tail_that_could_hold_a_facet_is_an_error() {
        let mut bytes = binary(&ONE, b"solid part");
        bytes.extend_from_slice(&[0; 50]);
        assert_eq!(
            parse_error(&bytes),
            (
                Location::Byte(134),
                ParseReason::SizeMismatch {
                    expected: 134,
                    found: 184
                }
            )
        );
    }

    #[test]
    fn truncated_solid_header_binary_is_a_size_error_not_an_empty_mesh() {
        let bytes = binary(&TETRA, b"solid part exported by a CAD tool");
        // Cut inside the text of the header, the data are a bare `solid` line: an ASCII
        // error (no `endsolid`), still not a mesh.
        assert!(read_stl(&bytes[..20]).is_err());
        for len in [40, 80, 83, 84, 100, 283] {
            assert_eq!(
                parse_error(&bytes[..len]),
                (
                    Location::Byte(len as u64),
                    ParseReason::SizeMismatch {
                        expected: if len < 84 { 84 } else { 284 },
                        found: len as u64
                    }
                ),
                "cut at {len}"
            );
        }
        // A header and body of printable bytes only (no NUL in the first 512 bytes) but no
        // `facet`/`endsolid` keyword is binary too.
        let mut printable = b"solid ".to_vec();
        printable.resize(80, b' ');
        printable.extend_from_slice(b"AAAA"); // 0x41414141 facets
        printable.resize(700, b'A');
        assert!(matches!(
            parse_error(&printable),
            (
                Location::Byte(700),
                ParseReason::SizeMismatch { found: 700, .. }
            )
        ));
    }

    #[test]
    fn ascii_missing_endsolid_is_an_error_with_a_line() {
        let text = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
        assert_eq!(
            parse_error(text),
            (
                Location::Line(8),
                ParseReason::UnexpectedEnd {
                    expected: "a solid (no `endsolid`)"
                }
            )
        );
        assert!(matches!(
            parse_error(b"solid x\n"),
            (Location::Line(1), ParseReason::UnexpectedEnd { .. })
        ));
        // An empty but well-formed solid is a valid (empty) mesh.
        let empty = read_stl(b"solid x\nendsolid x\n").unwrap();
        assert_eq!(empty.mesh.triangle_count(), 0);
    }

    #[test]
    fn ascii_with_binary_bytes_is_an_error_not_an_empty_mesh() {
        // Reached directly (detection sends such data to the binary reader).
        let err = read_ascii(b"solid blob\x01\x7f\nendsolid\n").unwrap_err();
        assert!(matches!(
            err,
            IoError::Parse {
                location: Location::Line(1),
                reason: ParseReason::BinaryByte { byte: 1 },
                ..
            }
        ));
        let err = read_ascii(b"solid x\nfacet\n\0\nendsolid\n").unwrap_err();
        assert!(matches!(
            err,
            IoError::Parse {
                location: Location::Line(3),
                reason: ParseReason::BinaryByte { byte: 0 },
                ..
            }
        ));
    }

    #[test]
    fn ascii_is_read_and_welded() {
        let text = b"solid tetra\n facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n   vertex 1 0 0\n  endloop\n endfacet\n\
            facet normal 0 0 0\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 0 0 1\n endloop\n endfacet\nendsolid tetra\n";
        let loaded = read_stl(text).unwrap();
        assert_eq!(loaded.mesh.vertex_count(), 4);
        assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 2, 3]]);
        assert_eq!(loaded.report.welded_vertices, 2);
    }

    #[test]
    fn ascii_keywords_are_case_insensitive() {
        let text = b"SOLID part\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID part\n";
        let loaded = read_stl(text).unwrap();
        assert_eq!(loaded.mesh.triangle_count(), 1);
    }

    #[test]
    fn ascii_errors_have_lines() {
        let two = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n";
        assert!(matches!(
            read_stl(two).unwrap_err(),
            IoError::Parse {
                location: Location::Line(3),
                reason: ParseReason::TooFewFaceVertices { count: 2 },
                ..
            }
        ));
        let bad = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n";
        assert!(matches!(
            read_stl(bad).unwrap_err(),
            IoError::Parse {
                location: Location::Line(4),
                reason: ParseReason::InvalidNumber { .. },
                ..
            }
        ));
        let open = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
        assert!(matches!(
            read_stl(open).unwrap_err(),
            IoError::Parse {
                location: Location::Line(3),
                reason: ParseReason::UnexpectedEnd { .. },
                ..
            }
        ));
    }

    proptest::proptest! {
        /// Welding against brute force: every facet reads back with its own corner
        /// positions, and the vertex count is the number of distinct positions.
        #[test]
        fn welding_matches_brute_force(
            facets in proptest::collection::vec(
                proptest::array::uniform3(proptest::array::uniform3(-2i8..3)),
                0..40,
            )
        ) {
            let triangles: Vec<[[f32; 3]; 3]> = facets
                .iter()
                .map(|f| f.map(|c| c.map(|v| f32::from(v) * 0.5)))
                .collect();
            let loaded = read_stl(&binary(&triangles, b"")).unwrap();
            let mesh = &loaded.mesh;
            proptest::prop_assert_eq!(mesh.triangle_count(), triangles.len());
            for (t, facet) in mesh.triangles().iter().zip(&triangles) {
                for (&v, corner) in t.iter().zip(facet) {
                    let expected = DVec3::from_array(corner.map(f64::from));
                    proptest::prop_assert!(mesh.positions()[v as usize] == expected);
                }
            }
            let mut distinct: Vec<[i64; 3]> = triangles
                .iter()
                .flatten()
                .map(|c| c.map(|v| (v * 2.0) as i64))
                .collect();
            distinct.sort_unstable();
            distinct.dedup();
            proptest::prop_assert_eq!(mesh.vertex_count(), distinct.len());
            proptest::prop_assert_eq!(
                loaded.report.welded_vertices,
                3 * triangles.len() - distinct.len()
            );
        }
    }
}
