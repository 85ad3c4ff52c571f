//! Lengths on the command line: a number with an optional `mm` or `in` suffix; a bare number is
//! millimetres, whatever the drawing's units.

/// Parses `3`, `3mm`, `0.125in`, `0.125 in` into millimetres.
pub fn parse_length(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let (num, factor) = if let Some(n) = t.strip_suffix("mm") {
        (n, 1.0)
    } else if let Some(n) = t.strip_suffix("in") {
        (n, 25.4)
    } else if let Some(n) = t.strip_suffix('"') {
        (n, 25.4)
    } else {
        (t, 1.0)
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a length (examples: 3, 3mm, 0.125in)"))?;
    if !v.is_finite() {
        return Err(format!("'{s}' is not a finite length"));
    }
    Ok(v * factor)
}

/// Parses a non-negative length.
pub fn parse_nonneg_length(s: &str) -> Result<f64, String> {
    let v = parse_length(s)?;
    if v < 0.0 {
        return Err(format!("'{s}' must not be negative"));
    }
    Ok(v)
}

/// Parses a feed per minute into millimetres per minute: `1000`, `1000mm/min`, `40in/min`,
/// `40 in/min` (a bare number is mm/min).
pub fn parse_rate(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let lower = t.to_ascii_lowercase();
    let bare = lower.strip_suffix("/min").map_or(t, |_| &t[..t.len() - 4]);
    parse_length(bare).map_err(|_| format!("'{s}' is not a feed (examples: 1000, 1000mm/min, 40in/min)"))
}

/// Parses `X,Y` (two lengths) into millimetres.
pub fn parse_point(s: &str) -> Result<(f64, f64), String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("'{s}' is not a point: give X,Y (example: 0,150)"))?;
    Ok((parse_length(x)?, parse_length(y)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffixes() {
        assert_eq!(parse_length("3").unwrap(), 3.0);
        assert_eq!(parse_length("3mm").unwrap(), 3.0);
        assert_eq!(parse_length("0.125in").unwrap(), 3.175);
        assert_eq!(parse_length(" 1 in").unwrap(), 25.4);
        assert!(parse_length("3cm").is_err());
        assert!(parse_length("nan").is_err());
        assert!(parse_nonneg_length("-1").is_err());
    }

    #[test]
    fn rates_and_points() {
        assert_eq!(parse_rate("1000").unwrap(), 1000.0);
        assert_eq!(parse_rate("1000mm/min").unwrap(), 1000.0);
        assert_eq!(parse_rate("40in/min").unwrap(), 1016.0);
        assert_eq!(parse_rate(" 40 in/MIN ").unwrap(), 1016.0);
        assert!(parse_rate("fast").unwrap_err().contains("not a feed"));
        assert_eq!(parse_point("-10,150").unwrap(), (-10.0, 150.0));
        assert_eq!(parse_point("1in, 2in").unwrap(), (25.4, 50.8));
        assert!(parse_point("10").is_err());
    }
}
