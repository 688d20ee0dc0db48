//! Stanford PLY reader (`ascii`, `binary_little_endian`, `binary_big_endian`).
//!
//! The header is parsed in full. The `vertex` element must have scalar `x`, `y`, `z`
//! properties of any numeric type; the `face` element must have a list property named
//! `vertex_indices` (or `vertex_index`) of any count and index types. Every other property
//! (normals, colours, confidence, lists) and every other element (edges, materials,
//! tristrips...) is read past and ignored. Elements may come in any order.

use super::builder::MeshBuilder;
use super::parse_error::token_text;
use super::text::{Lines, is_blank, parse_f64, parse_i64, tokens};
use super::{Format, LoadedMesh, Location, ParseReason};
use crate::IoError;

fn error(location: Location, reason: ParseReason) -> IoError {
    IoError::Parse {
        path: None,
        format: Format::Ply,
        location,
        reason,
    }
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Self> {
        Some(match name {
            b"char" | b"int8" => Self::I8,
            b"uchar" | b"uint8" => Self::U8,
            b"short" | b"int16" => Self::I16,
            b"ushort" | b"uint16" => Self::U16,
            b"int" | b"int32" => Self::I32,
            b"uint" | b"uint32" => Self::U32,
            b"float" | b"float32" => Self::F32,
            b"double" | b"float64" => Self::F64,
            _ => return None,
        })
    }

    fn is_float(self) -> bool {
        matches!(self, Self::F32 | Self::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: Vec<u8>,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: Vec<u8>,
    count: usize,
    properties: Vec<Property>,
    /// Header line that declared it.
    line: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the first byte after `end_header`'s line.
    body_start: usize,
    /// Line number of the first body line (ASCII).
    body_line: usize,
}

fn parse_header(bytes: &[u8]) -> Result<Header, IoError> {
    if is_blank(bytes) {
        return Err(error(Location::Line(1), ParseReason::EmptyFile));
    }
    let mut lines = Lines::new(bytes, 1);
    let magic_ok = lines
        .next()
        .is_some_and(|(_, first)| first.trim_ascii_end() == b"ply");
    if !magic_ok {
        return Err(error(
            Location::Line(1),
            ParseReason::BadMagic { expected: "ply" },
        ));
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        let Some((line, content)) = lines.next() else {
            return Err(error(
                Location::Line(lines.next_line_number()),
                ParseReason::UnexpectedEnd {
                    expected: "the header (no `end_header` line)",
                },
            ));
        };
        let at = Location::Line(line);
        let mut toks = tokens(content);
        let Some(keyword) = toks.next() else { continue };
        let unexpected = |expected: &'static str, found: Option<&[u8]>| {
            error(
                at,
                ParseReason::UnexpectedToken {
                    expected,
                    found: found.map(token_text).unwrap_or_default(),
                },
            )
        };
        match keyword {
            b"comment" | b"obj_info" => {}
            b"format" => {
                encoding = Some(match toks.next() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::LittleEndian,
                    Some(b"binary_big_endian") => Encoding::BigEndian,
                    other => {
                        return Err(unexpected(
                            "ascii, binary_little_endian or binary_big_endian",
                            other,
                        ));
                    }
                });
                match toks.next() {
                    Some(b"1.0" | b"1") => {}
                    other => return Err(unexpected("format version 1.0", other)),
                }
            }
            b"element" => {
                let Some(name) = toks.next() else {
                    return Err(unexpected("an element name", None));
                };
                let count_tok = toks.next();
                let count = count_tok
                    .and_then(parse_i64)
                    .ok_or_else(|| unexpected("an element count", count_tok))?;
                let count = usize::try_from(count).map_err(|_| {
                    error(
                        at,
                        ParseReason::InvalidCount {
                            what: "element count",
                            value: count as f64,
                        },
                    )
                })?;
                if name == b"vertex" && count > u32::MAX as usize {
                    return Err(error(
                        at,
                        ParseReason::TooManyVertices {
                            count: count as u64,
                        },
                    ));
                }
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    properties: Vec::new(),
                    line,
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(unexpected(
                        "an `element` line before `property`",
                        Some(keyword),
                    ));
                };
                let type_tok = toks.next();
                let kind = if type_tok == Some(b"list") {
                    let count_tok = toks.next();
                    let count = count_tok
                        .and_then(Scalar::from_name)
                        .ok_or_else(|| unexpected("a PLY scalar type", count_tok))?;
                    let item_tok = toks.next();
                    let item = item_tok
                        .and_then(Scalar::from_name)
                        .ok_or_else(|| unexpected("a PLY scalar type", item_tok))?;
                    Kind::List { count, item }
                } else {
                    Kind::Scalar(
                        type_tok
                            .and_then(Scalar::from_name)
                            .ok_or_else(|| unexpected("a PLY scalar type or `list`", type_tok))?,
                    )
                };
                let Some(name) = toks.next() else {
                    return Err(unexpected("a property name", None));
                };
                element.properties.push(Property {
                    name: name.to_vec(),
                    kind,
                });
            }
            b"end_header" => break,
            other => return Err(unexpected("a PLY header keyword", Some(other))),
        }
    }
    let Some(encoding) = encoding else {
        return Err(error(
            Location::Line(1),
            ParseReason::UnexpectedToken {
                expected: "a `format` line in the header",
                found: "end_header".to_owned(),
            },
        ));
    };
    Ok(Header {
        encoding,
        elements,
        body_start: lines.position(),
        body_line: lines.next_line_number(),
    })
}

/// A source of element records: ASCII lines or binary bytes.
trait Source {
    /// Starts record `index` of `element`.
    fn begin(&mut self, element: &Element, index: usize) -> Result<(), IoError>;
    /// The next value, of type `ty`, in the current record.
    fn value(&mut self, ty: Scalar) -> Result<f64, IoError>;
    /// Ends the current record.
    fn end(&mut self) -> Result<(), IoError>;
    /// Where the current record starts.
    fn location(&self) -> Location;

    /// A list length: a non-negative integer.
    fn list_len(&mut self, ty: Scalar) -> Result<usize, IoError> {
        let value = self.value(ty)?;
        list_length(value, self.location())
    }
}

/// `value` as a list length (a non-negative integer), or an error at `at`.
fn list_length(value: f64, at: Location) -> Result<usize, IoError> {
    if (0.0..1e15).contains(&value) && value.fract() <= 0.0 {
        // Integral and well inside usize; the cast is exact.
        Ok(value as usize)
    } else {
        Err(error(
            at,
            ParseReason::InvalidCount {
                what: "list length",
                value,
            },
        ))
    }
}

struct AsciiSource<'a> {
    lines: Lines<'a>,
    line: usize,
    rest: &'a [u8],
    /// Values the current record needs so far (grows with list lengths).
    needed: usize,
    found: usize,
}

impl AsciiSource<'_> {
    fn next_token(&mut self) -> Option<&[u8]> {
        let rest = self.rest;
        let start = rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let after = &rest[start..];
        let len = after
            .iter()
            .position(u8::is_ascii_whitespace)
            .unwrap_or(after.len());
        self.rest = &after[len..];
        Some(&after[..len])
    }
}

impl Source for AsciiSource<'_> {
    fn begin(&mut self, element: &Element, index: usize) -> Result<(), IoError> {
        loop {
            let Some((line, content)) = self.lines.next() else {
                return Err(error(
                    Location::Line(self.lines.next_line_number()),
                    ParseReason::MissingRecords {
                        element: String::from_utf8_lossy(&element.name).into_owned(),
                        expected: element.count,
                        found: index,
                    },
                ));
            };
            if !is_blank(content) {
                self.line = line;
                self.rest = content;
                self.needed = element.properties.len();
                self.found = 0;
                return Ok(());
            }
        }
    }

    fn value(&mut self, ty: Scalar) -> Result<f64, IoError> {
        let line = self.line;
        let (needed, found) = (self.needed, self.found);
        let Some(token) = self.next_token() else {
            return Err(error(
                Location::Line(line),
                ParseReason::MissingValues {
                    expected: needed,
                    found,
                },
            ));
        };
        let parsed = if ty.is_float() {
            parse_f64(token)
        } else {
            // PLY integer types are at most 32 bits: the conversion is exact.
            parse_i64(token).map(|v| v as f64)
        };
        let Some(value) = parsed else {
            let expected = if ty.is_float() {
                "a floating-point number"
            } else {
                "an integer"
            };
            return Err(error(
                Location::Line(line),
                ParseReason::InvalidNumber {
                    expected,
                    found: token_text(token),
                },
            ));
        };
        self.found += 1;
        Ok(value)
    }

    fn list_len(&mut self, ty: Scalar) -> Result<usize, IoError> {
        let value = self.value(ty)?;
        let len = list_length(value, self.location())?;
        self.needed += len;
        Ok(len)
    }

    fn end(&mut self) -> Result<(), IoError> {
        let extra = tokens(self.rest).count();
        if extra > 0 {
            return Err(error(
                Location::Line(self.line),
                ParseReason::TooManyValues {
                    expected: self.needed,
                    found: self.found + extra,
                },
            ));
        }
        Ok(())
    }

    fn location(&self) -> Location {
        Location::Line(self.line)
    }
}

struct BinarySource<'a> {
    bytes: &'a [u8],
    pos: usize,
    record_start: usize,
    big_endian: bool,
    /// Element name, count and record index, for truncation errors.
    element: String,
    count: usize,
    index: usize,
}

impl BinarySource<'_> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let chunk = self.bytes.get(self.pos..self.pos.checked_add(N)?)?;
        let mut array = [0; N];
        array.copy_from_slice(chunk);
        if self.big_endian {
            array.reverse();
        }
        self.pos += N;
        Some(array)
    }
}

impl Source for BinarySource<'_> {
    fn begin(&mut self, element: &Element, index: usize) -> Result<(), IoError> {
        self.record_start = self.pos;
        if index == 0 {
            self.element = String::from_utf8_lossy(&element.name).into_owned();
            self.count = element.count;
        }
        self.index = index;
        Ok(())
    }

    fn value(&mut self, ty: Scalar) -> Result<f64, IoError> {
        // Bytes were reversed for big-endian data, so they are little-endian here.
        let value = match ty {
            Scalar::I8 => self.take::<1>().map(|b| f64::from(i8::from_le_bytes(b))),
            Scalar::U8 => self.take::<1>().map(|b| f64::from(b[0])),
            Scalar::I16 => self.take::<2>().map(|b| f64::from(i16::from_le_bytes(b))),
            Scalar::U16 => self.take::<2>().map(|b| f64::from(u16::from_le_bytes(b))),
            Scalar::I32 => self.take::<4>().map(|b| f64::from(i32::from_le_bytes(b))),
            Scalar::U32 => self.take::<4>().map(|b| f64::from(u32::from_le_bytes(b))),
            Scalar::F32 => self.take::<4>().map(|b| f64::from(f32::from_le_bytes(b))),
            Scalar::F64 => self.take::<8>().map(f64::from_le_bytes),
        };
        value.ok_or_else(|| {
            error(
                self.location(),
                ParseReason::MissingRecords {
                    element: self.element.clone(),
                    expected: self.count,
                    found: self.index,
                },
            )
        })
    }

    fn end(&mut self) -> Result<(), IoError> {
        Ok(())
    }

    fn location(&self) -> Location {
        Location::Byte(self.record_start as u64)
    }
}

/// Parses PLY data.
pub(crate) fn read_ply(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    let header = parse_header(bytes)?;
    let body = bytes.get(header.body_start..).unwrap_or_default();
    match header.encoding {
        Encoding::Ascii => read_body(
            &header,
            body.len(),
            AsciiSource {
                lines: Lines::new(body, header.body_line),
                line: header.body_line,
                rest: &[],
                needed: 0,
                found: 0,
            },
        ),
        Encoding::LittleEndian | Encoding::BigEndian => read_body(
            &header,
            body.len(),
            BinarySource {
                bytes,
                pos: header.body_start,
                record_start: header.body_start,
                big_endian: header.encoding == Encoding::BigEndian,
                element: String::new(),
                count: 0,
                index: 0,
            },
        ),
    }
}

/// Why `value` is not a valid vertex index (kept out of the face loop).
#[cold]
fn bad_index(value: f64, vertex_count: usize) -> ParseReason {
    if value.is_finite() && value.fract().abs() <= 0.0 {
        // An integer; `as` saturates beyond the i64 range, which is out of range anyway.
        ParseReason::IndexOutOfRange {
            index: value as i64,
            vertex_count,
        }
    } else {
        ParseReason::NonIntegerIndex { value }
    }
}

fn property_index(element: &Element, names: &[&[u8]]) -> Option<usize> {
    element
        .properties
        .iter()
        .position(|p| names.contains(&p.name.as_slice()))
}

fn read_body<S: Source>(
    header: &Header,
    body_bytes: usize,
    mut src: S,
) -> Result<LoadedMesh, IoError> {
    let vertex_element = header.elements.iter().position(|e| e.name == b"vertex");
    let face_element = header.elements.iter().position(|e| e.name == b"face");
    let vertex_count = vertex_element.map_or(0, |i| header.elements[i].count);
    // Reserve no more than the body could hold (a header may announce 2^60 records):
    // a vertex takes at least 3 bytes (three `uchar`s, or `0 0 0` less separators), a face
    // at least 4 (a `uchar` count and three `uchar` indices).
    let mut builder = MeshBuilder::default();
    builder.positions.reserve(vertex_count.min(body_bytes / 3));
    if let Some(f) = face_element {
        builder.reserve_triangles(header.elements[f].count.min(body_bytes / 4));
    }
    let mut face: Vec<u32> = Vec::with_capacity(8);
    for (e, element) in header.elements.iter().enumerate() {
        if Some(e) == vertex_element {
            let mut axes = [0usize; 3];
            for (slot, name) in axes.iter_mut().zip(["x", "y", "z"]) {
                *slot = property_index(element, &[name.as_bytes()])
                    .filter(|&i| matches!(element.properties[i].kind, Kind::Scalar(_)))
                    .ok_or_else(|| {
                        error(
                            Location::Line(element.line),
                            ParseReason::MissingProperty {
                                element: "vertex",
                                property: name,
                            },
                        )
                    })?;
            }
            for vertex in 0..element.count {
                src.begin(element, vertex)?;
                let mut xyz = [0.0; 3];
                for (k, property) in element.properties.iter().enumerate() {
                    match property.kind {
                        Kind::Scalar(ty) => {
                            let value = src.value(ty)?;
                            if let Some(axis) = axes.iter().position(|&a| a == k) {
                                xyz[axis] = value;
                            }
                        }
                        Kind::List { count, item } => {
                            for _ in 0..src.list_len(count)? {
                                src.value(item)?;
                            }
                        }
                    }
                }
                src.end()?;
                builder
                    .push_vertex(xyz)
                    .map_err(|reason| error(src.location(), reason))?;
            }
        } else if Some(e) == face_element {
            let list = property_index(element, &[b"vertex_indices", b"vertex_index"])
                .filter(|&i| matches!(element.properties[i].kind, Kind::List { .. }))
                .ok_or_else(|| {
                    error(
                        Location::Line(element.line),
                        ParseReason::MissingProperty {
                            element: "face",
                            property: "vertex_indices",
                        },
                    )
                })?;
            for index in 0..element.count {
                src.begin(element, index)?;
                face.clear();
                for (k, property) in element.properties.iter().enumerate() {
                    match property.kind {
                        Kind::Scalar(ty) => {
                            src.value(ty)?;
                        }
                        Kind::List { count, item } => {
                            let len = src.list_len(count)?;
                            for _ in 0..len {
                                let value = src.value(item)?;
                                if k != list {
                                    continue;
                                }
                                if !(value >= 0.0
                                    && value < vertex_count as f64
                                    && value.fract() <= 0.0)
                                {
                                    return Err(error(
                                        src.location(),
                                        bad_index(value, vertex_count),
                                    ));
                                }
                                // An integer in range of a u32 vertex count: the cast is exact.
                                face.push(value as u32);
                            }
                        }
                    }
                }
                src.end()?;
                builder
                    .push_face(&face)
                    .map_err(|reason| error(src.location(), reason))?;
            }
        } else if !element.properties.is_empty() {
            // (An element without properties has empty records: nothing to read past.)
            for index in 0..element.count {
                src.begin(element, index)?;
                for property in &element.properties {
                    match property.kind {
                        Kind::Scalar(ty) => {
                            src.value(ty)?;
                        }
                        Kind::List { count, item } => {
                            for _ in 0..src.list_len(count)? {
                                src.value(item)?;
                            }
                        }
                    }
                }
                src.end()?;
            }
        }
    }
    builder.finish(MeshBuilder::report(Format::Ply, vertex_count))
}
