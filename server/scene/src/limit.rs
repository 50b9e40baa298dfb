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

/// How a CSV header differs from the one wanted, without quoting it (the trajectory parser's,
/// shared by every CSV reader: marker tracks, logs, frames.csv).
pub use needlesim_trajectory::header_mismatch;

/// A TOML parser's error on `text` for a message: "TOML parse error at line L, column C: " and
/// the parser's words ([`toml::de::Error::message`], its line and column from
/// [`toml::de::Error::span`], counted in characters from 1), never the line itself: a scene read
/// from a local file never has its contents in an error (a line of `/proc/self/environ` or of a
/// secret), and a client has its own text. Each value the words quote is clipped to
/// [`MAX_QUOTE_CHARS`] characters ([`clip_quotes`]), the numbers they quote in full (serde writes
/// a float of the wrong type as all its digits, 1e300 as 301) written as
/// [`needlesim_core::num::num`] writes them; at most 512 characters in all. The one form of a TOML
/// error for every reader of scenes and exercises (server, CLI through the server, lab, Python).
pub fn toml_message(e: &toml::de::Error, text: &str) -> String {
    let words = clip_quotes(&compact_numbers(e.message().trim_end()));
    let Some(span) = e.span() else { return clip(&format!("TOML parse error: {words}"), 512) };
    let mut start = span.start.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_no = text[..line_start].bytes().filter(|&b| b == b'\n').count() + 1;
    let col = text[line_start..start].chars().count() + 1;
    // A value of the wrong kind in valid TOML (the text parses as a table): name its key, a key
    // of the schema; a syntax error names none (its line may be anything, e.g. the environment).
    let key = if toml::from_str::<toml::Table>(text).is_ok() { value_key(&text[line_start..start]) } else { None };
    match key {
        Some(key) => clip(&format!("TOML parse error at line {line_no}, column {col} (the value of `{key}`): {words}"), 512),
        None => clip(&format!("TOML parse error at line {line_no}, column {col}: {words}"), 512),
    }
}

/// The key whose value starts where the error points: the bare key (letters, digits, `_`, `-`,
/// at most [`MAX_QUOTE_CHARS`]) just before `=` at the end of the line's text before the span;
/// `None` when the span is not at a value (a key, not a line, is what is named).
fn value_key(before: &str) -> Option<&str> {
    let head = before.trim_end().strip_suffix('=')?.trim_end();
    let start = head.rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-')).map_or(0, |i| i + 1);
    let key = &head[start..];
    (!key.is_empty() && key.chars().count() <= MAX_QUOTE_CHARS).then_some(key)
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
    fn issue_35_a_toml_error_names_line_and_column_and_never_quotes_the_line() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct S {
            a: f64,
        }
        // A line of the environment (what /proc/self/environ reads as): its text is not quoted.
        let text = "a = 1.0\nSHELL=/bin/bash\u{0}SECRET_TOKEN=sk_live_0123456789abcdef\u{0}HOME=/root";
        let m = toml_message(&toml::from_str::<S>(text).unwrap_err(), text);
        assert!(m.starts_with("TOML parse error at line 2, column "), "{m}");
        for part in ["SHELL", "bash", "SECRET", "sk_live", "HOME", "root", "\n"] {
            assert!(!m.contains(part), "{part} quoted: {m}");
        }
        // The column is counted in characters, the parser's words follow.
        let text = "a = 1.0\né = = broken";
        let m = toml_message(&toml::from_str::<S>(text).unwrap_err(), text);
        assert!(!m.contains("broken"), "{m}");
        let col: usize = m.split("column ").nth(1).and_then(|r| r.split(':').next()).unwrap().parse().unwrap();
        let span = toml::from_str::<S>(text).unwrap_err().span().unwrap();
        assert_eq!(col, text[..span.start].rsplit('\n').next().unwrap().chars().count() + 1, "{m}");
    }

    #[test]
    fn a_value_of_the_wrong_kind_names_its_key() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct S {
            base_m: [f64; 3],
        }
        let text = "# a scene\nbase_m = [0.05, 0.05]";
        let m = toml_message(&toml::from_str::<S>(text).unwrap_err(), text);
        assert!(m.starts_with("TOML parse error at line 2, column 10 (the value of `base_m`): "), "{m}");
        assert!(!m.contains("0.05"), "{m}");
    }

    #[test]
    fn issue_35_a_toml_error_on_a_long_line_quotes_at_most_a_clipped_value() {
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
        // A short line is not quoted either: line and column only.
        let text = "a = 1.0\nb = [1,";
        let m = toml_message(&toml::from_str::<S>(text).unwrap_err(), text);
        assert!(m.starts_with("TOML parse error at line 2, column ") && !m.contains("b = [1,") && !m.contains('\n'), "{m}");
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
