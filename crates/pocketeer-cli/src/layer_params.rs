//! Milling parameters in layer names, as dxf2gcode reads them (`--layer-params dxf2gcode`): a
//! layer named `MILL: 1 Md: -3 Sd: -1.5 FeedXY: 400 FeedZ: 150 Td: 6` is pocketed 3 mm deep in
//! passes of 1.5 mm at 400 mm/min with a 6 mm tool. The names are dxf2gcode's defaults (its
//! `[Layer_Options]`: English, German and short forms, compared here without regard to case),
//! each followed by `:` and a number, a decimal comma read as a point; values are in the
//! drawing's unit. dxf2gcode writes depths as Z values (`Md: -3`, 3 mm below the stock top);
//! its own examples also write them positive, so a depth is read by its size either way.
//! Layers named `IGNORE: …` and layers without the `MILL:` prefix are not cut.

/// What a layer name sets (`None`: not said, the command line's value holds).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LayerParams {
    /// Depth, mm (positive).
    pub depth: Option<f64>,
    /// Largest depth of one pass, mm (positive).
    pub step_down: Option<f64>,
    /// Safe height above the stock, mm.
    pub safe_z: Option<f64>,
    /// Where rapid descents stop above the stock, mm.
    pub feed_height: Option<f64>,
    /// Cutting feed, mm/min.
    pub feed: Option<f64>,
    /// Plunge feed, mm/min.
    pub plunge_feed: Option<f64>,
    /// Tool number.
    pub tool: Option<u32>,
    /// Tool diameter, mm.
    pub diameter: Option<f64>,
    /// Spindle speed, rpm.
    pub spindle: Option<f64>,
    /// Names read and not used (start depth, start radius), for a warning.
    pub unused: Vec<String>,
}

/// The parameters of a layer named `name`, `mm` millimetres to the drawing's unit; `None`
/// for a layer that is not a milling layer. A value that is not a number is an error naming
/// it.
pub fn parse(name: &str, mm: f64) -> Result<Option<LayerParams>, String> {
    let t = name.trim();
    let Some(rest) = strip_prefix_ci(t, "MILL:") else {
        return Ok(None);
    };
    let rest = rest.replace(',', ".");
    let mut p = LayerParams::default();
    // Pairs `Name: value`: split at each ':', the name the last word before it, the value
    // the first word after it.
    let parts: Vec<&str> = rest.split(':').collect();
    for w in parts.windows(2) {
        let Some(key) = w[0].split_whitespace().last() else {
            continue;
        };
        let Some(value) = w[1].split_whitespace().next() else {
            continue;
        };
        if !key.chars().all(|c| c.is_ascii_alphabetic()) {
            continue;
        }
        let v: f64 = value
            .parse()
            .map_err(|_| format!("layer '{name}': {key}: '{value}' is not a number"))?;
        if !v.is_finite() {
            return Err(format!("layer '{name}': {key}: '{value}' is not a finite number"));
        }
        let k = key.to_ascii_lowercase();
        let is = |names: &[&str]| names.iter().any(|n| n.eq_ignore_ascii_case(&k));
        if is(&["MillDepth", "Md", "TiefeGesamt", "Tg"]) {
            p.depth = Some(v.abs() * mm);
        } else if is(&["SliceDepth", "Sd", "TiefeZustellung", "Tz"]) {
            p.step_down = Some(v.abs() * mm);
        } else if is(&["RetractHeight", "Rh", "Freifahrthoehe", "FFh"]) {
            p.safe_z = Some(v * mm);
        } else if is(&["SafeMargin", "Sm", "Sicherheitshoehe", "Sh"]) {
            p.feed_height = Some(v * mm);
        } else if is(&["FeedXY", "Fxy", "VorschubXY", "Vxy", "F"]) {
            p.feed = Some(v * mm);
        } else if is(&["FeedZ", "Fz", "VorschubZ", "Vz"]) {
            p.plunge_feed = Some(v * mm);
        } else if is(&["ToolNr", "Tn", "T", "WerkzeugNummer", "Wn"]) {
            if v < 0.0 || v.fract() != 0.0 {
                return Err(format!("layer '{name}': {key}: '{value}' is not a tool number"));
            }
            p.tool = Some(v as u32);
        } else if is(&["ToolDiameter", "Td", "WerkzeugDurchmesser", "Wd"]) {
            p.diameter = Some(v * mm);
        } else if is(&["SpindleSpeed", "Drehzahl", "RPM", "UPM", "S"]) {
            p.spindle = Some(v);
        } else {
            p.unused.push(key.to_string());
        }
    }
    Ok(Some(p))
}

/// `s` without `prefix` (compared without regard to case).
fn strip_prefix_ci<'a>(s: &'a str, prefix: &str) -> Option<&'a str> {
    (s.len() >= prefix.len() && s[..prefix.len()].eq_ignore_ascii_case(prefix)).then(|| &s[prefix.len()..])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dxf2gcodes_example_layer_reads() {
        let p = parse("MILL: 1 Md: 2 Sd: 2 FeedXY: 400 FeedZ: 200", 1.0)
            .unwrap()
            .unwrap();
        assert_eq!(p.depth, Some(2.0));
        assert_eq!(p.step_down, Some(2.0));
        assert_eq!(p.feed, Some(400.0));
        assert_eq!(p.plunge_feed, Some(200.0));
        assert!(p.unused.is_empty());
    }

    #[test]
    fn depths_as_z_values_german_names_and_decimal_commas() {
        let p = parse(
            "mill: 2 TiefeGesamt: -3,5 Tz: -1,75 Vxy: 600 Wd: 4 T: 3 S: 18000 St: 0",
            1.0,
        )
        .unwrap()
        .unwrap();
        assert_eq!(p.depth, Some(3.5));
        assert_eq!(p.step_down, Some(1.75));
        assert_eq!(p.feed, Some(600.0));
        assert_eq!(p.diameter, Some(4.0));
        assert_eq!(p.tool, Some(3));
        assert_eq!(p.spindle, Some(18000.0));
        assert_eq!(p.unused, vec!["St".to_string()]);
    }

    #[test]
    fn inch_drawings_and_other_layers() {
        let p = parse("MILL: 1 Md: -0.125 Td: 0.25", 25.4).unwrap().unwrap();
        assert!((p.depth.unwrap() - 3.175).abs() < 1e-12);
        assert!((p.diameter.unwrap() - 6.35).abs() < 1e-12);
        assert_eq!(parse("IGNORE: Helper", 1.0).unwrap(), None);
        assert_eq!(parse("0", 1.0).unwrap(), None);
        assert!(parse("MILL: 1 Md: deep", 1.0)
            .unwrap_err()
            .contains("Md: 'deep' is not a number"));
    }
}
