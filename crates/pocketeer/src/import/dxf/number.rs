//! Numbers of an ASCII DXF read from the bytes of their line, with the standard library's
//! results: the usual form (a sign, then at most 19 digits with a decimal point among them) is
//! read directly, anything else by `str::parse`.

/// Powers of ten that are exact in an `f64`.
const EXACT_POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18,
    1e19, 1e20, 1e21, 1e22,
];

/// The number written in `text` (blanks around it allowed), as `str::parse::<f64>` reads the
/// trimmed text; `None` when it is not one.
///
/// Digits `d` with `k` of them after the point are `m / 10^k` for the integer `m` they spell.
/// When `m < 2^53` and `k ≤ 22` both are exact doubles and one division rounds the quotient
/// correctly: the same double as any correct parser gives.
pub fn real(text: &[u8]) -> Option<f64> {
    let (negative, digits) = signed(text);
    if let Some((mantissa, decimals)) = decimal(digits) {
        // Below 2^53 the mantissa is exact in a double.
        if mantissa < (1 << 53) {
            if let Some(&scale) = EXACT_POWERS.get(decimals) {
                let x = mantissa as f64 / scale;
                return Some(if negative { -x } else { x });
            }
        }
    }
    std::str::from_utf8(text).ok()?.trim().parse().ok()
}

/// `text` without the blanks around it, as its sign (true for `-`) and what follows the sign.
fn signed(text: &[u8]) -> (bool, &[u8]) {
    let t = text.trim_ascii();
    match t.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, t),
    }
}

/// Digits with at most one point among them (and at least one digit), 19 characters at most:
/// the integer the digits spell without the point, and how many come after the point.
fn decimal(text: &[u8]) -> Option<(u64, usize)> {
    // Nineteen digits at most: below 10^19, no overflow of a u64.
    if text.is_empty() || text.len() > 19 {
        return None;
    }
    let mut mantissa = 0u64;
    let mut point = None;
    for (i, &b) in text.iter().enumerate() {
        let digit = b.wrapping_sub(b'0');
        if digit < 10 {
            mantissa = mantissa * 10 + u64::from(digit);
        } else if b == b'.' && point.is_none() {
            point = Some(i);
        } else {
            return None;
        }
    }
    match point {
        None => Some((mantissa, 0)),
        // A point alone is not a number.
        Some(_) if text.len() == 1 => None,
        Some(p) => Some((mantissa, text.len() - 1 - p)),
    }
}

/// The integer written in `text` (blanks around it allowed), as `str::parse::<i64>` reads the
/// trimmed text.
pub fn int(text: &[u8]) -> Option<i64> {
    let (negative, digits) = signed(text);
    if !digits.is_empty() && digits.len() <= 18 && digits.iter().all(u8::is_ascii_digit) {
        let n = digits.iter().fold(0i64, |n, &d| n * 10 + i64::from(d - b'0'));
        return Some(if negative { -n } else { n });
    }
    std::str::from_utf8(text).ok()?.trim().parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn std_real(s: &str) -> Option<f64> {
        s.trim().parse().ok()
    }

    #[test]
    fn usual_and_unusual_forms() {
        for s in [
            "0",
            "-0",
            "-0.0",
            "+1.5",
            " 12.250 ",
            "1.",
            ".5",
            "-.5",
            "100.006032",
            "1e3",
            "1E-3",
            "-1.5e+2",
            "inf",
            "NaN",
            "",
            " ",
            ".",
            "-",
            "+",
            "1..2",
            "1-2",
            "0x10",
            "１",
            "12345678901234567890",
            "9007199254740993",
            "9007199254740992.5",
            "0.1234567890123456789",
            "1.00000000000000000000001",
            "123456789012345678.9",
            "\t7\r",
            "1 2",
        ] {
            let (ours, theirs) = (real(s.as_bytes()), std_real(s));
            assert_eq!(
                ours.map(f64::to_bits),
                theirs.map(f64::to_bits),
                "'{s}': {ours:?} against {theirs:?}"
            );
        }
        for s in [
            "0",
            "-0",
            "+7",
            " 12 ",
            "-9223372036854775808",
            "9223372036854775807",
            "1.0",
            "",
            "x",
            "99999999999999999999",
        ] {
            assert_eq!(int(s.as_bytes()), s.trim().parse().ok(), "'{s}'");
        }
    }

    proptest! {
        /// Decimal text of any length, sign and point position reads as the standard library
        /// reads it, to the bit.
        #[test]
        fn reads_as_the_standard_library(
            negative in any::<bool>(),
            digits in "[0-9]{1,24}",
            point in proptest::option::of(0usize..25),
        ) {
            let mut s = String::from(if negative { "-" } else { "" });
            let point = point.map(|p| p.min(digits.len()));
            for (i, c) in digits.chars().enumerate() {
                if point == Some(i) {
                    s.push('.');
                }
                s.push(c);
            }
            if point == Some(digits.len()) {
                s.push('.');
            }
            prop_assert_eq!(real(s.as_bytes()).map(f64::to_bits), std_real(&s).map(f64::to_bits), "{}", s);
            prop_assert_eq!(int(s.as_bytes()), s.parse::<i64>().ok(), "{}", s);
        }

        /// Every double printed in full reads back as itself.
        #[test]
        fn printed_doubles_read_back(x in any::<f64>().prop_filter("finite", |x| x.is_finite())) {
            for s in [x.to_string(), format!("{x:.6}"), format!("{x:e}")] {
                prop_assert_eq!(real(s.as_bytes()).map(f64::to_bits), std_real(&s).map(f64::to_bits), "{}", s);
            }
        }
    }
}
