//! Decoding the `%XX` escapes of URIs (glTF buffer URIs, URDF mesh URIs).

/// `text` with its `%XX` escapes decoded to bytes; `None` if an escape is incomplete or
/// not two hexadecimal digits (`%+1` and `%-1` are refused, as RFC 3986 says).
///
/// # Examples
///
/// ```
/// use sphaera_io::percent_decode;
///
/// assert_eq!(percent_decode("my%20meshes/b%C3%B8x.obj").as_deref(), Some("my meshes/bøx.obj".as_bytes()));
/// assert_eq!(percent_decode("a%2"), None);
/// assert_eq!(percent_decode("a%zz"), None);
/// assert_eq!(percent_decode("a%+1"), None);
/// ```
#[must_use]
pub fn percent_decode(text: &str) -> Option<Vec<u8>> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        if b == b'%' {
            let &[high, low] = bytes.get(i + 1..i + 3)? else {
                return None;
            };
            out.push((hex_digit(high)? << 4) | hex_digit(low)?);
            i += 3;
        } else {
            out.push(b);
            i += 1;
        }
    }
    Some(out)
}

/// The value of one hexadecimal digit (either case).
fn hex_digit(byte: u8) -> Option<u8> {
    // `to_digit` takes a single character: no sign, no prefix.
    char::from(byte)
        .to_digit(16)
        .and_then(|d| u8::try_from(d).ok())
}

#[cfg(test)]
mod tests {
    use super::percent_decode;
    use proptest::prelude::*;

    proptest! {
        /// Every byte string survives encoding and decoding; an escape with anything but
        /// two hexadecimal digits is refused.
        #[test]
        fn encoding_round_trips(bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
            let encoded: String = bytes.iter().map(|b| format!("%{b:02X}")).collect();
            prop_assert_eq!(percent_decode(&encoded), Some(bytes.clone()));
            prop_assert_eq!(percent_decode(&encoded.to_lowercase()), Some(bytes));
        }

        #[test]
        fn bad_escapes_are_refused(a in any::<char>(), b in any::<char>()) {
            let text = format!("x%{a}{b}");
            let valid = a.is_ascii_hexdigit() && b.is_ascii_hexdigit();
            prop_assert_eq!(percent_decode(&text).is_some(), valid, "{}", text);
        }
    }
}
