//! How figures read in messages and program headers: lengths and feeds in the job's unit,
//! counts with the right plural, times as `4m07s`.

use pocketeer::import::Units;

/// The unit a job speaks: millimetres, or inches for a drawing in an imperial unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobUnits {
    /// Millimetres (G21).
    Millimetres,
    /// Inches (G20).
    Inches,
}

impl JobUnits {
    /// Inches for a drawing in inches, feet, mils, microinches or yards; else millimetres.
    pub fn of(units: Units) -> JobUnits {
        match units {
            Units::Inches | Units::Feet | Units::Mils | Units::Microinches | Units::Yards => JobUnits::Inches,
            _ => JobUnits::Millimetres,
        }
    }

    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        match self {
            JobUnits::Millimetres => 1.0,
            JobUnits::Inches => 25.4,
        }
    }

    /// `mm` or `in`.
    pub fn symbol(self) -> &'static str {
        match self {
            JobUnits::Millimetres => "mm",
            JobUnits::Inches => "in",
        }
    }

    /// A length given in millimetres, in this unit: `6 mm`, `0.25 in`.
    pub fn length(self, mm: f64) -> String {
        let decimals = match self {
            JobUnits::Millimetres => 4,
            JobUnits::Inches => 5,
        };
        format!("{} {}", num(mm / self.mm(), decimals), self.symbol())
    }

    /// A long length (a path's), one decimal in millimetres, three in inches.
    pub fn distance(self, mm: f64) -> String {
        match self {
            JobUnits::Millimetres => format!("{} mm", fixed(mm, 1)),
            JobUnits::Inches => format!("{} in", fixed(mm / 25.4, 3)),
        }
    }

    /// A feed given in millimetres per minute, in this unit: `1000 mm/min`, `40 in/min`.
    pub fn rate(self, mm_per_min: f64) -> String {
        format!("{} {}/min", num(mm_per_min / self.mm(), 3), self.symbol())
    }
}

/// `v` with at most `decimals` decimals, trailing zeros dropped, never `-0`.
///
/// Kept out of a doc test: the binary crate has no library to test it from.
pub fn num(v: f64, decimals: usize) -> String {
    let t = format!("{v:.decimals$}");
    let t = if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    };
    if t == "-0" {
        "0".to_string()
    } else {
        t
    }
}

/// `v` with exactly `decimals` decimals, never `-0.0`.
pub fn fixed(v: f64, decimals: usize) -> String {
    let t = format!("{v:.decimals$}");
    if t.starts_with('-') && t[1..].chars().all(|c| c == '0' || c == '.') {
        t[1..].to_string()
    } else {
        t
    }
}

/// `1 pass`, `2 passes`: the library's plural, for the CLI's messages too.
pub use pocketeer::import::error::fmt_count as count;

/// A duration as `4m07s`, or `2h05m00s` from an hour on.
pub fn time(seconds: f64) -> String {
    let s = if seconds.is_finite() {
        seconds.max(0.0).round() as u64
    } else {
        u64::MAX
    };
    if s >= 3600 {
        format!("{}h{:02}m{:02}s", s / 3600, s / 60 % 60, s % 60)
    } else {
        format!("{}m{:02}s", s / 60, s % 60)
    }
}

/// `text` in lines of at most `width` characters, broken between words; the lines after the
/// first indented by two spaces. A word too long for a line (a long path) is cut into pieces
/// on lines of their own, each but the last ending in `\`.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    let piece = width.saturating_sub(3).max(8);
    for word in text.split(' ') {
        let chars: Vec<char> = word.chars().collect();
        if chars.len() > piece {
            let pieces: Vec<String> = chars.chunks(piece).map(|c| c.iter().collect()).collect();
            let n = pieces.len();
            for (k, p) in pieces.into_iter().enumerate() {
                lines.push(format!("  {p}{}", if k + 1 < n { "\\" } else { "" }));
            }
            continue;
        }
        let w = word;
        let Some(last) = lines.last_mut() else { break };
        if !last.trim().is_empty() && last.len() + 1 + w.len() > width {
            lines.push(format!("  {w}"));
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(w);
        }
    }
    lines.retain(|l| !l.is_empty());
    lines
}

/// The command line as comment lines of at most 72 characters.
pub fn command_line_comment() -> Vec<String> {
    let words: Vec<String> = std::env::args()
        .enumerate()
        .map(|(k, a)| {
            let a = if k == 0 { "pocketeer".to_string() } else { a };
            if a.is_empty() || a.contains(|c: char| c.is_whitespace() || c == '\'') {
                format!("'{}'", a.replace('\'', "'\\''"))
            } else {
                a
            }
        })
        .collect();
    wrap(&format!("command: {}", words.join(" ")), 72)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_read_as_a_machinist_writes_them() {
        assert_eq!(num(-0.00001, 4), "0");
        assert_eq!(num(2.5, 4), "2.5");
        assert_eq!(num(1000.0, 3), "1000");
        assert_eq!(fixed(-0.00004, 3), "0.000");
        assert_eq!(fixed(-1.25, 1), "-1.2");
        assert_eq!(count(1, "pass", "passes"), "1 pass");
        assert_eq!(count(3, "pass", "passes"), "3 passes");
        assert_eq!(time(247.0), "4m07s");
        assert_eq!(time(7500.0), "2h05m00s");
        let inch = JobUnits::Inches;
        assert_eq!(inch.length(6.35), "0.25 in");
        assert_eq!(inch.rate(1016.0), "40 in/min");
        assert_eq!(JobUnits::Millimetres.rate(1000.0), "1000 mm/min");
        assert_eq!(inch.distance(254.0), "10.000 in");
    }

    #[test]
    fn header_lines_wrap_between_words_and_cut_long_words() {
        assert_eq!(wrap("a short line", 72), vec!["a short line"]);
        let long =
            "units mm: the drawing was read in millimetres as asked (--units), though it declares metres";
        let lines = wrap(long, 72);
        assert!(
            lines.len() == 2 && lines.iter().all(|l| l.len() <= 72),
            "{lines:?}"
        );
        assert_eq!(
            lines.join(" ").split_whitespace().collect::<Vec<_>>(),
            long.split(' ').collect::<Vec<_>>()
        );
        let path = format!("command: pocketeer pocket /{}/plate.dxf -o x.nc", "d".repeat(100));
        let lines = wrap(&path, 72);
        assert!(lines.iter().all(|l| l.len() <= 72), "{lines:?}");
        assert!(
            lines[1].ends_with('\\') && lines.last().is_some_and(|l| l.ends_with("-o x.nc")),
            "{lines:?}"
        );
    }
}
