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
}
