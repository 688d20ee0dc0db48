//! The outer layer of a glTF file: the binary GLB container (header, JSON chunk, binary
//! chunk) or plain JSON, and the JSON parsed into the glTF schema.
//!
//! The GLB container is parsed here rather than by the `gltf` crate so that every size in
//! its header is checked against the data, with the byte offset of the problem.

use ::gltf::json;

use super::super::parse_error::token_text;
use super::super::text::is_blank;
use super::super::{Location, ParseReason};
use super::error;
use crate::IoError;

/// The JSON text of a glTF file and, for a `.glb`, its binary chunk.
pub(super) struct Container<'a> {
    pub(super) json: &'a [u8],
    pub(super) bin: Option<&'a [u8]>,
}

/// The little-endian `u32` at `offset`, if the data hold it.
fn u32_at(bytes: &[u8], offset: usize) -> Option<u32> {
    let word = bytes.get(offset..offset + 4)?;
    Some(u32::from_le_bytes(word.try_into().ok()?))
}

/// Splits glTF data into JSON and binary chunk: a GLB if they start with the `glTF` magic,
/// JSON otherwise.
pub(super) fn split(bytes: &[u8]) -> Result<Container<'_>, IoError> {
    let byte = |offset: usize, reason| error(Location::Byte(offset as u64), reason);
    if !bytes.starts_with(b"glTF") {
        if is_blank(bytes) {
            return Err(byte(0, ParseReason::EmptyFile));
        }
        let json = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        return Ok(Container { json, bin: None });
    }
    let header_end = |offset| {
        byte(
            offset,
            ParseReason::UnexpectedEnd {
                expected: "the GLB header",
            },
        )
    };
    let version = u32_at(bytes, 4).ok_or_else(|| header_end(bytes.len()))?;
    if version != 2 {
        return Err(byte(
            4,
            ParseReason::UnsupportedVersion {
                version: version.to_string(),
            },
        ));
    }
    let length = u32_at(bytes, 8).ok_or_else(|| header_end(bytes.len()))?;
    if u64::from(length) != bytes.len() as u64 {
        return Err(byte(
            bytes.len().min(length as usize),
            ParseReason::SizeMismatch {
                expected: u64::from(length),
                found: bytes.len() as u64,
            },
        ));
    }
    let mut json = None;
    let mut bin = None;
    let mut offset = 12;
    while offset < bytes.len() {
        let chunk_end = |expected| byte(bytes.len(), ParseReason::UnexpectedEnd { expected });
        let chunk_length = u32_at(bytes, offset).ok_or_else(|| chunk_end("a GLB chunk header"))?;
        let kind = bytes
            .get(offset + 4..offset + 8)
            .ok_or_else(|| chunk_end("a GLB chunk header"))?;
        let start = offset + 8;
        let end = start
            .checked_add(chunk_length as usize)
            .ok_or_else(|| chunk_end("a GLB chunk"))?;
        let data = bytes
            .get(start..end)
            .ok_or_else(|| chunk_end("a GLB chunk"))?;
        match kind {
            b"JSON" if json.is_none() => json = Some(data),
            b"BIN\0" if json.is_some() && bin.is_none() => bin = Some(data),
            _ if json.is_none() => {
                return Err(byte(
                    offset + 4,
                    ParseReason::UnexpectedToken {
                        expected: "a JSON chunk first",
                        found: token_text(kind),
                    },
                ));
            }
            // Other chunks are ignored, as the specification asks.
            _ => {}
        }
        offset = end;
    }
    let json = json.ok_or_else(|| {
        byte(
            bytes.len(),
            ParseReason::UnexpectedEnd {
                expected: "the JSON chunk",
            },
        )
    })?;
    Ok(Container { json, bin })
}

/// The JSON parsed into the glTF schema (without the `gltf` crate's validation, whose
/// checks this reader makes itself, with locations).
pub(super) fn parse_json(text: &[u8]) -> Result<json::Root, IoError> {
    json::deserialize::from_slice::<json::Root>(text).map_err(|e| {
        let (line, column) = (e.line(), e.column());
        let full = e.to_string();
        let message = full
            .strip_suffix(&format!(" at line {line} column {column}"))
            .unwrap_or(&full)
            .to_owned();
        error(
            Location::Json {
                line: line.max(1),
                column: column.max(1),
            },
            ParseReason::InvalidJson { message },
        )
    })
}
