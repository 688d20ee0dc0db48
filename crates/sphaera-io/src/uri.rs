//! Decoding the `%XX` escapes of URIs (glTF buffer URIs, URDF mesh URIs).

/// `text` with its `%XX` escapes decoded to bytes; `None` if an escape is incomplete or
/// not hexadecimal.
///
/// # Examples
///
/// ```
/// use sphaera_io::percent_decode;
///
/// assert_eq!(percent_decode("my%20meshes/b%C3%B8x.obj").as_deref(), Some("my meshes/bøx.obj".as_bytes()));
/// assert_eq!(percent_decode("a%2"), None);
/// assert_eq!(percent_decode("a%zz"), None);
/// ```
#[must_use]
pub fn percent_decode(text: &str) -> Option<Vec<u8>> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        if b == b'%' {
            let hex = bytes.get(i + 1..i + 3)?;
            let text = std::str::from_utf8(hex).ok()?;
            out.push(u8::from_str_radix(text, 16).ok()?);
            i += 3;
        } else {
            out.push(b);
            i += 1;
        }
    }
    Some(out)
}
