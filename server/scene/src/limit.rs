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
