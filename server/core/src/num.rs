//! Numbers in messages: a client's value echoed in an error, compactly and exactly.
//!
//! `{}` prints an `f64` in full positional notation, so `1e300` becomes 301 digits and `1e-300`
//! 300 zeros; [`num`] prints it as `{}` does between 10⁻⁴ and 10¹⁶ (`0.205`, `1000`, `-3.5`) and in
//! scientific notation outside (`1e300`, `2.5e-7`), the shortest digits that read back as the same
//! number in both cases: at most 24 characters whatever the value (`-2.2250738585072014e-308`).

use std::fmt;

/// An `f64` printed for a message ([`num`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

/// `x` for a message: positional between 10⁻⁴ and 10¹⁶ in magnitude (and 0), scientific
/// outside, NaN and ±inf as `{}` prints them; the shortest digits that round-trip.
pub fn num(x: f64) -> Num {
    Num(x)
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if !x.is_finite() || a == 0.0 || (1e-4..1e16).contains(&a) { write!(f, "{x}") } else { write!(f, "{x:e}") }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_numbers_in_messages_are_short_and_round_trip() {
        for (x, s) in [
            (1e300, "1e300"),
            (-1e300, "-1e300"),
            (1e-300, "1e-300"),
            (0.205, "0.205"),
            (1000.0, "1000"),
            (-3.5, "-3.5"),
            (0.0, "0"),
            (2.5e-7, "2.5e-7"),
            (1e16, "1e16"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(num(x).to_string(), s);
        }
        for x in [f64::MAX, f64::MIN_POSITIVE, -f64::MIN_POSITIVE, 5e-324, 1.0 / 3.0, 9_999_999_999_999_998.0, 1.2345678901234567e-4] {
            let s = num(x).to_string();
            assert!(s.len() <= 24, "{x:e}: {s}");
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
    }
}
