//! Numbers printed with a fixed count of decimals, as G-code and DXF carry them.
//!
//! `format!("{:.10}", x)` finds the exact decimal expansion of the binary number (Grisu, and
//! Dragon4 where Grisu gives up) and was a third of the time of a whole `offset` of a drawing of
//! 100 000 lines. Here the number is scaled to units of its last decimal, rounded half away
//! from zero and printed as an integer: the same text except where the scaling itself rounds,
//! which moves the last decimal by one at most.

/// Text being written, held as bytes: digits are appended as a slice, where a `String` takes
/// them one `char` at a time or checks each run of them again for UTF-8 (both were most of
/// the time of writing a large drawing). Only whole `str`s and `char`s go in, so the bytes are
/// always UTF-8; they are checked once, in [`Text::into_string`].
#[derive(Debug, Default)]
pub(crate) struct Text(Vec<u8>);

impl Text {
    /// Appends `s`.
    pub(crate) fn push_str(&mut self, s: &str) {
        self.0.extend_from_slice(s.as_bytes());
    }

    /// Appends `c`.
    pub(crate) fn push(&mut self, c: char) {
        let mut utf8 = [0; 4];
        self.push_str(c.encode_utf8(&mut utf8));
    }

    /// Appends `other`.
    pub(crate) fn append(&mut self, other: &Text) {
        self.0.extend_from_slice(&other.0);
    }

    /// The length in bytes.
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    /// Cuts the text back to its first `len` bytes (a length this text had before).
    pub(crate) fn truncate(&mut self, len: usize) {
        self.0.truncate(len);
    }

    /// Makes room for `additional` more bytes.
    pub(crate) fn reserve(&mut self, additional: usize) {
        self.0.reserve(additional);
    }

    /// The text as a `String`.
    pub(crate) fn into_string(self) -> String {
        // Cannot fail (see the type's comment); lossy rather than a panic if it ever did.
        String::from_utf8(self.0).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
    }
}

/// 10^k for every k whose power a `u64` holds (and an `f64` holds exactly up to 10^22).
const POWERS: [u64; 20] = {
    let mut p = [1u64; 20];
    let mut k = 1;
    while k < 20 {
        p[k] = p[k - 1] * 10;
        k += 1;
    }
    p
};

/// The largest scaled value printed as an integer: above 2^53 an `f64` no longer holds every
/// integer, and the digits would be noise.
const LARGEST: f64 = 9.0e15;

/// `v` in units of its `decimals`-th decimal, rounded half away from zero, when it fits:
/// 1.23456 to 4 decimals is 12346; 1e300 does not fit, nor does anything to 20 decimals or more.
pub(crate) fn quantize(v: f64, decimals: usize) -> Option<i64> {
    let scaled = (v * *POWERS.get(decimals)? as f64).round();
    (scaled.abs() < LARGEST).then_some(scaled as i64)
}

/// Appends `n`, in units of the `decimals`-th decimal, with exactly `decimals` decimals (a
/// zero is never signed: `-0.0000` would be a negative zero to a reader). `n` is a value
/// [`quantize`] gave, so `decimals` is below 20.
pub(crate) fn push_fixed(out: &mut Text, n: i64, decimals: usize) {
    if n < 0 {
        out.push('-');
    }
    let a = n.unsigned_abs();
    let unit = POWERS.get(decimals).copied().unwrap_or(u64::MAX);
    push_digits(out, a / unit, 1);
    if decimals > 0 {
        out.push('.');
        push_digits(out, a % unit, decimals);
    }
}

/// Appends `v` with exactly `decimals` decimals, rounded half away from zero; numbers too large
/// to scale are printed exactly.
pub(crate) fn push_number(out: &mut Text, v: f64, decimals: usize) {
    match quantize(v, decimals) {
        Some(n) => push_fixed(out, n, decimals),
        None => out.push_str(&format!("{v:.decimals$}")),
    }
}

/// `v` with exactly `decimals` decimals (see [`push_number`]).
pub(crate) fn fixed(v: f64, decimals: usize) -> String {
    let mut out = Text::default();
    push_number(&mut out, v, decimals);
    out.into_string()
}

/// The two digits of every number below 100, side by side.
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Appends the decimal digits of `n`, padded with zeros to at least `width` digits (20 at
/// most, the digits of `u64::MAX`; zero is one digit whatever the width). Two digits a
/// division: a drawing's text is mostly digits.
pub(crate) fn push_digits(out: &mut Text, mut n: u64, width: usize) {
    // u64::MAX has 20 digits.
    let mut buf = [b'0'; 20];
    let mut at = buf.len();
    while n >= 100 {
        let pair = (n % 100) as usize * 2;
        n /= 100;
        at -= 2;
        buf[at..at + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    }
    if n >= 10 {
        at -= 2;
        buf[at..at + 2].copy_from_slice(&PAIRS[n as usize * 2..n as usize * 2 + 2]);
    } else if n > 0 {
        at -= 1;
        buf[at] = b'0' + n as u8;
    }
    let start = at.min(buf.len() - width.clamp(1, buf.len()));
    // ASCII digits: whole characters.
    out.0.extend_from_slice(&buf[start..]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn decimals_round_half_away_from_zero_and_zero_has_no_sign() {
        assert_eq!(fixed(1.23456, 4), "1.2346");
        assert_eq!(fixed(-0.00004, 4), "0.0000");
        assert_eq!(fixed(-12.5, 4), "-12.5000");
        assert_eq!(fixed(0.000051, 4), "0.0001");
        assert_eq!(fixed(99999.99999, 4), "100000.0000");
        assert_eq!(fixed(-0.25, 0), "0");
        assert_eq!(fixed(-0.5, 0), "-1");
        assert_eq!(fixed(7.0, 0), "7");
        assert_eq!(fixed(0.5, 10), "0.5000000000");
        assert_eq!(fixed(-123456.0000000001, 10), "-123456.0000000001");
        assert_eq!(fixed(1e300, 4).len(), 306);
        assert_eq!(fixed(0.5, 19), "0.5000000000000000000");
        assert_eq!(fixed(0.5, 25), format!("{:.25}", 0.5));
    }

    proptest! {
        /// Digits as the standard library prints them, zero-padded to the width.
        #[test]
        fn digits_as_printed(n in prop_oneof![0u64..1000, any::<u64>()], width in 0usize..=20) {
            let mut out = Text::default();
            push_digits(&mut out, n, width);
            prop_assert_eq!(out.into_string(), format!("{n:0width$}"));
        }

        /// The text reads back within half a last decimal (and the scaling's rounding) of the
        /// number, and differs from the standard library's exact formatting by one in the last
        /// decimal at most.
        #[test]
        fn the_text_is_the_number_to_its_last_decimal(v in -1.0e5f64..1.0e5, decimals in 0usize..=12) {
            let text = fixed(v, decimals);
            let unit = 10f64.powi(-(decimals as i32));
            // A few units in the last place of v: the scaling's and the parsing's rounding.
            let ulps = 8.0 * f64::EPSILON * v.abs();
            let back: f64 = text.parse().unwrap();
            prop_assert!((back - v).abs() <= 0.5 * unit + ulps, "{v} {text}");
            let exact: f64 = format!("{v:.decimals$}").parse().unwrap();
            prop_assert!((back - exact).abs() <= unit + ulps, "{v} {text}");
            prop_assert_eq!(text.split('.').nth(1).map_or(0, str::len), decimals);
        }
    }
}
