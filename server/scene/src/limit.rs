//! Size limits as a typed error, and the clipping of client text quoted in messages: shared by
//! every layer that refuses input for its size (scene loading, image tracking, planning, the API).

/// The most characters of a client's value quoted in a message.
pub const MAX_QUOTE_CHARS: usize = 64;

/// At most [`MAX_QUOTE_CHARS`] characters of `s`, with "…" when cut.
pub fn quote(s: &str) -> String {
    clip(s, MAX_QUOTE_CHARS)
}

/// At most `n` characters of `s`, with "…" appended when cut (the trajectory parser's, shared).
pub use needlesim_trajectory::clip;

/// A TOML parser's error on `text` for a message, laid out as the parser's own (line and
/// column, the line with a caret, the parser's words) but quoting at most [`MAX_QUOTE_CHARS`]
/// characters of the input around the error (a 100 kB line is not echoed), each value the words
/// quote clipped alike ([`clip_quotes`]), the numbers they quote in full (serde writes a float of
/// the wrong type as all its digits, 1e300 as 301) written as [`needlesim_core::num::num`] writes
/// them; at most 512 characters in all.
pub fn toml_message(e: &toml::de::Error, text: &str) -> String {
    let words = clip_quotes(&compact_numbers(e.message().trim_end()));
    let Some(span) = e.span() else { return clip(&words, 512) };
    let mut start = span.start.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = text[line_start..line_end].trim_end_matches('\r');
    let line_no = text[..line_start].bytes().filter(|&b| b == b'\n').count() + 1;
    let col = text[line_start..start].chars().count() + 1;
    // Up to 16 characters before the error, then the rest of MAX_QUOTE_CHARS.
    let skip = (col - 1).saturating_sub(16);
    let mut excerpt: String = if skip > 0 { "…".to_owned() } else { String::new() };
    let mut taken = line.chars().skip(skip);
    excerpt.extend(taken.by_ref().take(MAX_QUOTE_CHARS));
    if taken.next().is_some() {
        excerpt.push('…');
    }
    let caret = " ".repeat(col - 1 - skip + usize::from(skip > 0));
    let gutter = " ".repeat(line_no.to_string().len());
    clip(&format!("TOML parse error at line {line_no}, column {col}\n{gutter} |\n{line_no} | {excerpt}\n{gutter} | {caret}^\n{words}"), 512)
}

/// `s` with every value it quotes between backticks or double quotes clipped to
/// [`MAX_QUOTE_CHARS`] characters ([`quote`]); an unclosed quote clips the rest.
pub fn clip_quotes(s: &str) -> String {
    let mut out = String::with_capacity(s.len().min(1024));
    let mut rest = s;
    while let Some(open) = rest.find(['`', '"']) {
        let q = rest[open..].chars().next().unwrap_or('"');
        out.push_str(&rest[..=open]);
        let inner = &rest[open + 1..];
        match inner.find(q) {
            Some(close) => {
                out.push_str(&quote(&inner[..close]));
                out.push(q);
                rest = &inner[close + 1..];
            }
            None => {
                out.push_str(&quote(inner));
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// `s` with every run of more than 24 digits (and one '.') that reads as a number rewritten
/// compactly ([`needlesim_core::num::num`]: 1e300, not 301 digits).
pub fn compact_numbers(s: &str) -> String {
    let mut out = String::with_capacity(s.len().min(4096));
    let mut rest = s;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let run = &rest[start..];
        let len = run.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(run.len());
        let number = &run[..len];
        match number.parse::<f64>() {
            Ok(x) if len > 24 => out.push_str(&needlesim_core::num::num(x).to_string()),
            _ => out.push_str(number),
        }
        rest = &run[len..];
    }
    out.push_str(rest);
    out
}

/// A request over a size limit: the typed cause of RESOURCE_EXHAUSTED in the service layer, also
/// inside `anyhow` chains (scene loading).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{what} is {} {unit}, over the limit of {limit} {unit}{hint}", needlesim_core::num::num(*amount))]
pub struct SizeLimit {
    /// What is too large, e.g. "the scene's estimated memory".
    pub what: String,
    /// How much was asked for, in `unit`: a float, so that an amount computed from a client's
    /// numbers (a span over a speed of 1e-300) is printed as it is (`1e305`, [`needlesim_core::num`]),
    /// never as a saturated integer.
    pub amount: f64,
    pub limit: u64,
    /// The unit of `amount` and `limit`, e.g. "MiB", "ticks", "pixels".
    pub unit: &'static str,
    /// Appended to the message, e.g. " (flag --max-session-memory-mb)".
    pub hint: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_a_toml_error_quotes_a_short_excerpt_of_a_long_line() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct S {
            a: f64,
        }
        // A 100 kB line with the error at its end, one at its start, and a 100 kB quoted value.
        let long = "x".repeat(100_000);
        for text in [format!("a = 1.0\nb = \"{long}\" ="), format!("a = ?{long}"), format!("a = \"{long}\"")] {
            let e = toml::from_str::<S>(&text).unwrap_err();
            let m = toml_message(&e, &text);
            let longest_x = m.split(|c| c != 'x').map(str::len).max().unwrap_or(0);
            assert!(longest_x <= MAX_QUOTE_CHARS, "{longest_x} x's quoted: {m}");
            assert!(m.chars().count() <= 300, "{} characters: {m}", m.chars().count());
            assert!(m.starts_with("TOML parse error at line "), "{m}");
        }
        // A short line is quoted whole, the caret under the error.
        let text = "a = 1.0\nb = [1,";
        let m = toml_message(&toml::from_str::<S>(text).unwrap_err(), text);
        assert!(m.contains("\n2 | b = [1,\n"), "{m}");
        // A unique multi-byte line is clipped on a character boundary.
        let text = format!("a = \"{}\"", "é".repeat(200));
        let m = toml_message(&toml::from_str::<S>(&text).unwrap_err(), &text);
        assert!(m.contains('…') && !m.contains(&"é".repeat(65)), "{m}");
    }

    #[test]
    fn issue_35_long_numbers_in_parser_messages_are_compacted() {
        let full = format!("invalid type: floating point `1{}.0`, expected usize at line 12", "0".repeat(300));
        assert_eq!(compact_numbers(&full), "invalid type: floating point `1e300`, expected usize at line 12");
        let tiny = format!("`-0.{}1`", "0".repeat(299));
        assert_eq!(compact_numbers(&tiny), "`-1e-300`");
        for short in ["line 6, column 1", "1.5 and 1234567890.25 stay", "a.b.c", "v1.2.3", ""] {
            assert_eq!(compact_numbers(short), short);
        }
    }
}
