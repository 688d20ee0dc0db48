//! Byte-level helpers shared by the text readers: line splitting, tokens, numbers.
//!
//! The readers never build a `String` per line: they walk the file's bytes and parse
//! numbers straight from token slices.

use super::ParseReason;
use super::parse_error::token_text;

/// Iterator over the lines of a buffer: yields `(line_number, line)` with 1-based line
/// numbers and the `\n` (and a trailing `\r`) removed.
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    /// Lines of `bytes`, numbered from `first_line`.
    pub(crate) fn new(bytes: &'a [u8], first_line: usize) -> Self {
        Self {
            bytes,
            pos: 0,
            line: first_line,
        }
    }

    /// Number the next line would get (one past the last line when exhausted).
    pub(crate) fn next_line_number(&self) -> usize {
        self.line
    }

    /// Byte offset of the next line in the buffer.
    pub(crate) fn position(&self) -> usize {
        self.pos
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (usize, &'a [u8]);

    fn next(&mut self) -> Option<Self::Item> {
        let rest = self.bytes.get(self.pos..)?;
        if rest.is_empty() {
            return None;
        }
        let (line, advance) = match rest.iter().position(|&b| b == b'\n') {
            Some(end) => (&rest[..end], end + 1),
            None => (rest, rest.len()),
        };
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        let number = self.line;
        self.pos += advance;
        self.line += 1;
        Some((number, line))
    }
}

/// Whitespace-separated tokens of a line.
pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(u8::is_ascii_whitespace)
        .filter(|t| !t.is_empty())
}

/// The line up to a `#` comment.
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    match line.iter().position(|&b| b == b'#') {
        Some(hash) => &line[..hash],
        None => line,
    }
}

/// Whether a line holds only whitespace.
pub(crate) fn is_blank(line: &[u8]) -> bool {
    line.iter().all(u8::is_ascii_whitespace)
}

/// A decimal floating-point number (also `inf`, `nan`: callers check finiteness so the
/// error names the vertex).
pub(crate) fn parse_f64(token: &[u8]) -> Option<f64> {
    std::str::from_utf8(token).ok()?.parse().ok()
}

/// The next three tokens of `toks` as floating-point coordinates (later tokens are left
/// unread).
///
/// Refuses a missing token ([`ParseReason::MissingValues`]) and one that is not a number
/// ([`ParseReason::InvalidNumber`]); NaN and infinities parse (see [`parse_f64`]).
#[inline]
pub(crate) fn parse_xyz<'a>(
    toks: &mut impl Iterator<Item = &'a [u8]>,
) -> Result<[f64; 3], ParseReason> {
    let mut xyz = [0.0; 3];
    for (k, slot) in xyz.iter_mut().enumerate() {
        let Some(tok) = toks.next() else {
            return Err(ParseReason::MissingValues {
                expected: 3,
                found: k,
            });
        };
        *slot = parse_f64(tok).ok_or_else(|| ParseReason::InvalidNumber {
            expected: "a floating-point coordinate",
            found: token_text(tok),
        })?;
    }
    Ok(xyz)
}

/// A decimal integer with an optional sign; `None` on anything else or on overflow.
pub(crate) fn parse_i64(token: &[u8]) -> Option<i64> {
    let (negative, digits) = match token.split_first()? {
        (b'-', rest) => (true, rest),
        (b'+', rest) => (false, rest),
        _ => (false, token),
    };
    if digits.is_empty() {
        return None;
    }
    let mut value: i64 = 0;
    for &b in digits {
        let digit = b.wrapping_sub(b'0');
        if digit > 9 {
            return None;
        }
        value = value.checked_mul(10)?.checked_add(i64::from(digit))?;
    }
    Some(if negative { -value } else { value })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_strip_crlf_and_number_from_one() {
        let lines: Vec<_> = Lines::new(b"a\r\nb\n\nc", 1).collect();
        assert_eq!(
            lines,
            vec![
                (1, &b"a"[..]),
                (2, &b"b"[..]),
                (3, &b""[..]),
                (4, &b"c"[..])
            ]
        );
    }

    #[test]
    fn integers_parse_with_sign_and_reject_overflow() {
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(parse_i64(b"+7"), Some(7));
        assert_eq!(parse_i64(b"1.5"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"99999999999999999999"), None);
    }

    #[test]
    fn tokens_split_on_any_whitespace() {
        let t: Vec<_> = tokens(b"  f\t1/2/3  4//5 ").collect();
        assert_eq!(t, vec![&b"f"[..], &b"1/2/3"[..], &b"4//5"[..]]);
    }
}
