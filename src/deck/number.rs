//! NASTRAN number formats.
//!
//! Reals may omit the `E` of the exponent (`9.587-5`, `6.24+6`), use `D` for it
//! (`1D-3`), or end in a bare point (`1.`). An integer has no point and no exponent.

/// Parses a NASTRAN integer: optional sign, then digits only.
pub fn parse_int(token: &str) -> Option<i64> {
    let t = token.trim();
    let digits = t.strip_prefix(['+', '-']).unwrap_or(t);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse().ok()
}

/// How a token reads as a real number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RealToken {
    /// A proper real: it has a decimal point or an exponent.
    Real(f64),
    /// An integer where a real was expected (NASTRAN itself rejects this).
    Integer(f64),
}

/// Parses a NASTRAN real: `1.0`, `.25`, `1.`, `1.E3`, `1D-3`, `9.587-5`, `+1.945+5`.
/// Returns `None` for anything that is not a finite number in one of these forms.
pub fn parse_real(token: &str) -> Option<RealToken> {
    let t = token.trim();
    if t.is_empty() {
        return None;
    }
    if let Some(i) = parse_int(t) {
        return Some(RealToken::Integer(i as f64));
    }
    let mut s = String::with_capacity(t.len() + 1);
    let bytes = t.as_bytes();
    let mut has_exp = false;
    for (i, &b) in bytes.iter().enumerate() {
        match b {
            b'0'..=b'9' | b'.' => s.push(b as char),
            b'E' | b'e' | b'D' | b'd' => {
                if has_exp {
                    return None;
                }
                has_exp = true;
                s.push('E');
            }
            b'+' | b'-' => {
                // A sign after a digit or point, with no E before it, starts an exponent.
                if i > 0 && !has_exp && (bytes[i - 1].is_ascii_digit() || bytes[i - 1] == b'.') {
                    has_exp = true;
                    s.push('E');
                }
                s.push(b as char);
            }
            _ => return None,
        }
    }
    let mantissa = s.split('E').next().unwrap_or("");
    if !mantissa.contains('.') && !has_exp {
        return None;
    }
    if !mantissa.bytes().any(|b| b.is_ascii_digit()) {
        return None;
    }
    let v: f64 = s.parse().ok()?;
    v.is_finite().then_some(RealToken::Real(v))
}

/// Formats a real so that `parse_real` reads it back exactly (used by replication
/// and by deck writers).
pub fn format_real(v: f64) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains('E') {
        s.replace('e', "E")
    } else {
        format!("{s}.")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn real(s: &str) -> f64 {
        match parse_real(s) {
            Some(RealToken::Real(v)) => v,
            other => panic!("{s}: {other:?}"),
        }
    }

    #[test]
    fn nastran_reals_in_every_printed_form() {
        assert_eq!(real("9.587-5"), 9.587e-5);
        assert_eq!(real("6.24+6"), 6.24e6);
        assert_eq!(real("1.0-7"), 1.0e-7);
        assert_eq!(real("10.0+6"), 10.0e6);
        assert_eq!(real("1.E3"), 1.0e3);
        assert_eq!(real("1D-3"), 1.0e-3);
        assert_eq!(real("+1.945+5"), 1.945e5);
        assert_eq!(real("-7.779+5"), -7.779e5);
        assert_eq!(real(".25"), 0.25);
        assert_eq!(real("1."), 1.0);
        assert_eq!(real("-3.000000000E+00"), -3.0);
        assert_eq!(real("00.0"), 0.0);
    }

    #[test]
    fn integers_and_garbage() {
        assert_eq!(parse_int("144"), Some(144));
        assert_eq!(parse_int("-3"), Some(-3));
        assert_eq!(parse_int("1.0"), None);
        assert_eq!(parse_int(""), None);
        assert_eq!(parse_real("12"), Some(RealToken::Integer(12.0)));
        for bad in [
            "", "abc", "1.0.0", "1E", "inf", "NaN", "1.0E+5E3", "--1.0", "+", ".", "1,0", "1e999",
        ] {
            assert!(parse_real(bad).is_none(), "{bad} should not parse");
        }
    }

    #[test]
    fn formatted_reals_read_back_exactly() {
        for v in [0.0, 0.25, -3.0, 1.0e-7, 6.24e6, 1.0 / 3.0, 36.0] {
            assert_eq!(real(&format_real(v)), v);
        }
    }
}
