//! Tokens: SHA-256 digests compared in constant time, and short fingerprints for the logs (a
//! token itself is never logged nor stored on disk; only its digest is).

use subtle::ConstantTimeEq;

/// The SHA-256 digest of a token.
pub type TokenDigest = [u8; 32];

/// The SHA-256 digest of `token`.
pub fn token_digest(token: &str) -> TokenDigest {
    let d = ring::digest::digest(&ring::digest::SHA256, token.as_bytes());
    let mut out = [0u8; 32];
    out.copy_from_slice(d.as_ref());
    out
}

/// Whether `presented` is `expected`: their digests are compared in constant time, so that the
/// time taken says nothing about how much of a guess was right.
pub fn token_matches(presented: &str, expected: &str) -> bool {
    digest_matches(presented, &token_digest(expected))
}

/// Whether the digest of `presented` is `expected_sha256`, compared in constant time.
pub fn digest_matches(presented: &str, expected_sha256: &TokenDigest) -> bool {
    bool::from(token_digest(presented).ct_eq(expected_sha256))
}

/// The first 8 hex digits of the token's SHA-256: what the logs show instead of a token.
pub fn fingerprint(token: &str) -> String {
    to_hex(&token_digest(token)[..4])
}

/// Lower-case hex of `bytes`.
pub fn to_hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The bytes of a lower-case or upper-case hex string of exactly 64 digits, or `None`.
pub fn digest_from_hex(hex: &str) -> Option<TokenDigest> {
    let hex = hex.as_bytes();
    if hex.len() != 64 {
        return None;
    }
    let mut out = [0u8; 32];
    for (k, pair) in hex.chunks_exact(2).enumerate() {
        let s = std::str::from_utf8(pair).ok()?;
        out[k] = u8::from_str_radix(s, 16).ok()?;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digests_fingerprints_and_hex() {
        // SHA-256("abc"), FIPS 180-2 appendix B.1.
        assert_eq!(to_hex(&token_digest("abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
        assert_eq!(fingerprint("abc"), "ba7816bf");
        assert!(token_matches("abc", "abc"));
        assert!(!token_matches("abd", "abc"));
        assert!(!token_matches("", "abc"));
        let d = token_digest("some token");
        assert_eq!(digest_from_hex(&to_hex(&d)), Some(d));
        assert_eq!(digest_from_hex("ab"), None);
        assert_eq!(digest_from_hex(&"zz".repeat(32)), None);
    }
}
