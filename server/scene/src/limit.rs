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

/// A TOML parser's error for a message: at most 512 characters, and the numbers it quotes in full
/// (serde writes a float of the wrong type as all its digits, 1e300 as 301) written as
/// [`needlesim_core::num::num`] writes them.
pub fn toml_message(e: &impl std::fmt::Display) -> String {
    clip(&compact_numbers(e.to_string().trim_end()), 512)
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
#[error("{what} is {amount} {unit}, over the limit of {limit} {unit}{hint}")]
pub struct SizeLimit {
    /// What is too large, e.g. "the scene's estimated memory".
    pub what: String,
    pub amount: u64,
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
