//! The bytes of a glTF document's buffers: the binary chunk of a `.glb`, `data:` URIs
//! (base64 or percent-encoded) and separate files resolved relative to the glTF file.
//!
//! Buffers are loaded on first use, so a file whose unused buffers (animations, images
//! stored in buffers) are missing still loads its meshes.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use ::gltf::json;

use super::super::parse_error::token_text;
use super::super::{GltfObject, Location, ParseReason, percent_decode};
use super::error;
use crate::{FilePolicy, IoError};

/// The buffers of one document, loaded on demand.
pub(super) struct Buffers<'a> {
    /// The binary chunk of a `.glb`, the data of a first buffer without `uri`.
    bin: Option<&'a [u8]>,
    /// The folder of the glTF file, against which buffer files are resolved and to which
    /// they are confined, and the policy they are read by; `None` when reading from bytes.
    base: Option<(&'a Path, &'a FilePolicy)>,
    /// The data of each buffer, once loaded.
    loaded: Vec<Option<Cow<'a, [u8]>>>,
}

impl<'a> Buffers<'a> {
    /// No buffer loaded yet.
    pub(super) fn new(
        root: &json::Root,
        bin: Option<&'a [u8]>,
        base: Option<(&'a Path, &'a FilePolicy)>,
    ) -> Self {
        Self {
            bin,
            base,
            loaded: vec![None; root.buffers.len()],
        }
    }

    /// The data of buffer `index`, if [`Self::load`] has loaded it.
    pub(super) fn get(&self, index: usize) -> Option<&[u8]> {
        self.loaded.get(index)?.as_deref()
    }

    /// Loads every buffer that accessor `accessor` reads (through its buffer view and its
    /// sparse index and value views). References to missing views or buffers are left for
    /// the accessor reader to report.
    pub(super) fn load_for_accessor(
        &mut self,
        root: &json::Root,
        accessor: usize,
    ) -> Result<(), IoError> {
        let Some(accessor) = root.accessors.get(accessor) else {
            return Ok(());
        };
        let mut views = vec![accessor.buffer_view.map(|v| v.value())];
        if let Some(sparse) = &accessor.sparse {
            views.push(Some(sparse.indices.buffer_view.value()));
            views.push(Some(sparse.values.buffer_view.value()));
        }
        for view in views.into_iter().flatten() {
            if let Some(view) = root.buffer_views.get(view) {
                self.load(root, view.buffer.value())?;
            }
        }
        Ok(())
    }

    /// Loads buffer `index` (nothing if it is loaded or does not exist).
    fn load(&mut self, root: &json::Root, index: usize) -> Result<(), IoError> {
        let (Some(buffer), Some(slot)) = (root.buffers.get(index), self.loaded.get(index)) else {
            return Ok(());
        };
        if slot.is_some() {
            return Ok(());
        }
        let at = |reason| error(Location::Gltf(GltfObject::Buffer(index)), reason);
        let data: Cow<'a, [u8]> = match (&buffer.uri, self.bin) {
            (Some(uri), _) => self.resolve(uri, buffer.byte_length.0).map_err(at)?,
            (None, Some(bin)) if index == 0 => Cow::Borrowed(bin),
            (None, _) => return Err(at(ParseReason::BufferWithoutData)),
        };
        let expected = buffer.byte_length.0;
        if (data.len() as u64) < expected {
            return Err(at(ParseReason::BufferTooShort {
                expected,
                found: data.len() as u64,
            }));
        }
        if let Some(slot) = self.loaded.get_mut(index) {
            *slot = Some(data);
        }
        Ok(())
    }

    /// The bytes a buffer URI names: a `data:` URI decoded, or the first `byte_length`
    /// bytes of a file read by the policy (a regular file inside the glTF file's folder:
    /// an absolute path, a path climbing out with `..` or a link leading out, a device
    /// such as `/dev/zero` or a folder is refused, and a file longer than its buffer is not
    /// read past it).
    fn resolve(&self, uri: &str, byte_length: u64) -> Result<Cow<'a, [u8]>, ParseReason> {
        let invalid = |problem| ParseReason::InvalidUri {
            uri: token_text(uri.as_bytes()),
            problem,
        };
        if let Some(rest) = uri.strip_prefix("data:") {
            let (header, payload) = rest
                .split_once(',')
                .ok_or_else(|| invalid("a data URI needs a comma before its data"))?;
            let data = if header.ends_with(";base64") {
                decode_base64(payload.as_bytes()).ok_or_else(|| invalid("bad base64 data"))?
            } else {
                percent_decode(payload).ok_or_else(|| invalid("bad percent-encoding"))?
            };
            return Ok(Cow::Owned(data));
        }
        if has_scheme(uri) {
            return Err(invalid(
                "only `data:` URIs and paths relative to the glTF file are supported",
            ));
        }
        let Some((base, policy)) = self.base else {
            return Err(ParseReason::ExternalBuffer {
                uri: token_text(uri.as_bytes()),
            });
        };
        let decoded = percent_decode(uri).ok_or_else(|| invalid("bad percent-encoding"))?;
        let relative =
            String::from_utf8(decoded).map_err(|_| invalid("the path is not UTF-8 text"))?;
        if is_absolute(&relative) {
            return Err(invalid(
                "an absolute path: glTF buffer files are named relative to the glTF file",
            ));
        }
        let path: PathBuf = base.join(relative);
        let data =
            policy
                .read_within(&path, Some(base), byte_length)
                .map_err(|error| match error {
                    IoError::Refused { refusal, .. } => ParseReason::BufferRefused {
                        uri: token_text(uri.as_bytes()),
                        path: path.clone(),
                        refusal: Box::new(refusal),
                    },
                    IoError::Io { source, .. } => ParseReason::BufferFile {
                        uri: token_text(uri.as_bytes()),
                        path: path.clone(),
                        kind: source.kind(),
                    },
                    _ => ParseReason::BufferFile {
                        uri: token_text(uri.as_bytes()),
                        path: path.clone(),
                        kind: std::io::ErrorKind::Other,
                    },
                })?;
        Ok(Cow::Owned(data))
    }
}

/// Whether a decoded URI path is absolute: `/…`, `\\…`, or a Windows drive (`C:/…`).
fn is_absolute(path: &str) -> bool {
    let bytes = path.as_bytes();
    path.starts_with(['/', '\\'])
        || (bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':')
}

/// Whether a URI starts with a scheme (`http:`, `file:`...) of two or more letters; a
/// single letter is taken as a Windows drive (`C:/models/a.bin`).
fn has_scheme(uri: &str) -> bool {
    let Some((scheme, _)) = uri.split_once(':') else {
        return false;
    };
    scheme.len() > 1
        && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
        && scheme
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
}

/// Decodes base64 (the standard alphabet, or the URL-safe one), with or without `=`
/// padding; `None` for any other byte or an impossible length.
pub(super) fn decode_base64(text: &[u8]) -> Option<Vec<u8>> {
    let unpadded = text
        .strip_suffix(b"==")
        .or_else(|| text.strip_suffix(b"="))
        .unwrap_or(text);
    if unpadded.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::with_capacity(unpadded.len() / 4 * 3 + 2);
    let mut acc: u32 = 0;
    let mut bits = 0u32;
    for &c in unpadded {
        let value = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        };
        acc = (acc << 6) | u32::from(value);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_the_rfc_4648_vectors() {
        for (encoded, plain) in [
            ("", ""),
            ("Zg==", "f"),
            ("Zm8=", "fo"),
            ("Zm9v", "foo"),
            ("Zm9vYg==", "foob"),
            ("Zm9vYmE=", "fooba"),
            ("Zm9vYmFy", "foobar"),
            ("Zm9vYmE", "fooba"),
        ] {
            assert_eq!(
                decode_base64(encoded.as_bytes()).as_deref(),
                Some(plain.as_bytes()),
                "{encoded}"
            );
        }
        assert_eq!(decode_base64(b"+/-_").unwrap(), vec![0xfb, 0xff, 0xbf]);
        assert_eq!(decode_base64(b"Zm9vY"), None);
        assert_eq!(decode_base64(b"Zm9v!"), None);
        assert_eq!(decode_base64(b"Zm=v"), None);
    }

    #[test]
    fn percent_decoding_and_schemes() {
        assert_eq!(percent_decode("a%20b%2Fc.bin").unwrap(), b"a b/c.bin");
        assert!(has_scheme("http://example.invalid/a.bin"));
        assert!(has_scheme("file:///a.bin"));
        assert!(!has_scheme("C:/models/a.bin"));
        assert!(!has_scheme("meshes/a.bin"));
    }
}
