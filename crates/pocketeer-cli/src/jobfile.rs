//! Job files: TOML naming a drawing, a tool library and operations, lengths with units as on
//! the command line (`6mm`, `1200mm/min`, `40%`; a bare number is millimetres). Every error
//! names the file, the line and the key.

use crate::length::{parse_length, parse_rate};
use pocketeer::link::{Direction, Entry, LinkParams};
use serde::Deserialize;
use std::ops::Range;
use toml::Spanned;

/// A length, a feed or a share, as written: a number or a text with its unit.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum Quantity {
    /// A bare number: millimetres (or mm/min, or rpm).
    Number(f64),
    /// A number with its unit.
    Text(String),
}

/// The keys an operation takes, also as `[defaults]` for all of them.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
pub struct OperationKeys {
    pub layers: Option<Spanned<Vec<String>>>,
    pub tool: Option<Spanned<u32>>,
    pub depth: Option<Spanned<Quantity>>,
    pub step_down: Option<Spanned<Quantity>>,
    pub stepover: Option<Spanned<Quantity>>,
    pub rest: Option<bool>,
    pub direction: Option<Spanned<String>>,
    pub entry: Option<Spanned<String>>,
    pub ramp_angle: Option<Spanned<f64>>,
    pub allowance: Option<Spanned<Quantity>>,
    pub safe_z: Option<Spanned<Quantity>>,
    pub feed_height: Option<Spanned<Quantity>>,
}

/// A tool of the library.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
pub struct ToolKeys {
    pub number: Spanned<u32>,
    pub diameter: Spanned<Quantity>,
    pub feed: Option<Spanned<Quantity>>,
    pub plunge_feed: Option<Spanned<Quantity>>,
    pub spindle: Option<Spanned<f64>>,
}

/// The whole file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
pub struct JobFile {
    pub drawing: Spanned<String>,
    pub output: Option<Spanned<String>>,
    pub post: Option<Spanned<String>>,
    pub units: Option<Spanned<String>>,
    pub join_tolerance: Option<Spanned<Quantity>>,
    pub close_gaps: Option<Spanned<Quantity>>,
    pub fill: Option<Spanned<String>>,
    pub strict: Option<bool>,
    pub ignore_open: Option<bool>,
    pub coolant: Option<Spanned<String>>,
    pub spindle_wait: Option<Spanned<f64>>,
    pub park: Option<Spanned<String>>,
    pub rapid_rate: Option<Spanned<Quantity>>,
    pub retract_time: Option<Spanned<f64>>,
    #[serde(default)]
    pub defaults: OperationKeys,
    #[serde(default)]
    pub tools: Vec<ToolKeys>,
    #[serde(default)]
    pub operations: Vec<OperationKeys>,
}

/// The place of an error: the 1-based line and column of a byte offset of `text`.
pub fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(before.len(), |i| before.len() - i - 1) + 1;
    (line, col)
}

/// Reads the file's text; a TOML error (a misspelled key among them) with its line.
pub fn parse(name: &str, text: &str) -> Result<JobFile, String> {
    toml::from_str(text).map_err(|e| {
        let at = e.span().map_or(String::new(), |s| {
            let (l, c) = line_col(text, s.start);
            format!(":{l}:{c}")
        });
        format!("{name}{at}: {}", e.message().trim())
    })
}

/// A located error: `file:line: key: what`.
pub struct Locator<'a> {
    pub name: &'a str,
    pub text: &'a str,
}

impl Locator<'_> {
    /// The message for a value at `span` of key `key`.
    pub fn at(&self, span: Range<usize>, key: &str, what: &str) -> String {
        let (l, _) = line_col(self.text, span.start);
        format!("{}:{l}: {key}: {what}", self.name)
    }

    /// A length in mm from `q` (`positive`: more than zero; else zero or more).
    pub fn length(&self, q: &Spanned<Quantity>, key: &str, positive: bool) -> Result<f64, String> {
        let v = match q.get_ref() {
            Quantity::Number(v) => *v,
            Quantity::Text(t) => parse_length(t).map_err(|e| self.at(q.span(), key, &e))?,
        };
        let ok = v.is_finite() && if positive { v > 0.0 } else { v >= 0.0 };
        if !ok {
            let need = if positive { "positive" } else { "zero or more" };
            return Err(self.at(q.span(), key, &format!("{v} must be {need}")));
        }
        Ok(v)
    }

    /// A feed in mm/min from `q`.
    pub fn rate(&self, q: &Spanned<Quantity>, key: &str) -> Result<f64, String> {
        let v = match q.get_ref() {
            Quantity::Number(v) => *v,
            Quantity::Text(t) => parse_rate(t).map_err(|e| self.at(q.span(), key, &e))?,
        };
        if !(v.is_finite() && v > 0.0) {
            return Err(self.at(q.span(), key, "a feed must be positive"));
        }
        Ok(v)
    }

    /// A stepover in mm: a length or a share of `diameter` (`40%`).
    pub fn stepover(&self, q: &Spanned<Quantity>, diameter: f64) -> Result<f64, String> {
        if let Quantity::Text(t) = q.get_ref() {
            if let Some(p) = t.trim().strip_suffix('%') {
                let v: f64 = p
                    .trim()
                    .parse()
                    .map_err(|_| self.at(q.span(), "stepover", &format!("'{t}' is not a percentage")))?;
                if !(v.is_finite() && v > 0.0 && v < 100.0) {
                    return Err(self.at(
                        q.span(),
                        "stepover",
                        "a share of the diameter is above 0 % and below 100 %",
                    ));
                }
                return Ok(diameter * v / 100.0);
            }
        }
        self.length(q, "stepover", true)
    }
}

/// `a`, or where it is missing `b`.
fn or<T: Clone>(a: &Option<T>, b: &Option<T>) -> Option<T> {
    a.clone().or_else(|| b.clone())
}

/// One operation's keys with the `[defaults]` filled in.
pub fn with_defaults(op: &OperationKeys, d: &OperationKeys) -> OperationKeys {
    OperationKeys {
        layers: or(&op.layers, &d.layers),
        tool: or(&op.tool, &d.tool),
        depth: or(&op.depth, &d.depth),
        step_down: or(&op.step_down, &d.step_down),
        stepover: or(&op.stepover, &d.stepover),
        rest: op.rest.or(d.rest),
        direction: or(&op.direction, &d.direction),
        entry: or(&op.entry, &d.entry),
        ramp_angle: or(&op.ramp_angle, &d.ramp_angle),
        allowance: or(&op.allowance, &d.allowance),
        safe_z: or(&op.safe_z, &d.safe_z),
        feed_height: or(&op.feed_height, &d.feed_height),
    }
}

/// The link parameters of an operation (its feeds come from its tool later).
pub fn link_params(loc: &Locator, k: usize, op: &OperationKeys, diameter: f64) -> Result<LinkParams, String> {
    let key = |name: &str| format!("operations[{}].{name}", k + 1);
    let depth = match &op.depth {
        Some(q) => loc.length(q, &key("depth"), true)?,
        None => return Err(format!("{}: operation {} has no depth", loc.name, k + 1)),
    };
    let step_down = match &op.step_down {
        Some(q) => loc.length(q, &key("step-down"), true)?,
        None if depth <= diameter => depth,
        None => diameter,
    };
    let safe_z = match &op.safe_z {
        Some(q) => loc.length(q, &key("safe-z"), true)?,
        None => 5.0,
    };
    let feed_height = match &op.feed_height {
        Some(q) => loc.length(q, &key("feed-height"), false)?,
        None => 1f64.min(safe_z),
    };
    let direction = match op.direction.as_ref() {
        None => Direction::Climb,
        Some(d) => match d.get_ref().to_ascii_lowercase().as_str() {
            "climb" => Direction::Climb,
            "conventional" => Direction::Conventional,
            other => {
                return Err(loc.at(
                    d.span(),
                    &key("direction"),
                    &format!("'{other}': climb or conventional"),
                ))
            }
        },
    };
    let entry = match op.entry.as_ref() {
        None => Entry::Helix,
        Some(e) => match e.get_ref().to_ascii_lowercase().as_str() {
            "helix" => Entry::Helix,
            "ramp" => Entry::Ramp,
            "plunge" => Entry::Plunge,
            other => {
                return Err(loc.at(
                    e.span(),
                    &key("entry"),
                    &format!("'{other}': helix, ramp or plunge"),
                ))
            }
        },
    };
    let ramp_angle = op.ramp_angle.as_ref().map_or(3.0, |a| *a.get_ref());
    Ok(LinkParams {
        depth,
        step_down,
        safe_z,
        feed_height,
        direction,
        entry,
        ramp_angle: ramp_angle.to_radians(),
        time: pocketeer::machining_time::TimeModel::default(),
    })
}

/// The commented template `pocketeer job --print-template` writes.
pub const TEMPLATE: &str = r#"# A pocketeer job: `pocketeer job THIS.toml`. Lengths take units as on the command line
# (6mm, 0.25in; a bare number is millimetres), feeds per minute (1200mm/min), stepovers a
# length or a share of the tool's diameter (40%). Paths are relative to this file.

drawing = "plate.dxf"          # the DXF drawing
output = "plate.nc"            # the program to write
post = "linuxcnc"              # grbl, linuxcnc or mach3
# coolant = "flood"            # off, flood or mist
# spindle-wait = 2             # seconds after each spindle start
# park = "-10,150"             # X,Y to move to at the safe height at the end
# rapid-rate = "5000mm/min"    # for the time estimate
# retract-time = 0.5           # seconds each retract costs in the estimate
# units = "mm"                 # the drawing's unit, where it declares none
# join-tolerance = "0.001mm"   # drawing repairs, as on the command line
# close-gaps = "0.05mm"
# fill = "evenodd"             # or nonzero
# strict = false
# ignore-open = false

# Keys every operation takes unless it sets its own.
[defaults]
stepover = "40%"
# direction = "climb"          # or conventional (spindle clockwise, M3)
# entry = "helix"              # helix, ramp or plunge
# ramp-angle = 3               # degrees
# allowance = "0mm"            # left by roughing, taken by one finishing loop
# safe-z = "5mm"
# feed-height = "1mm"

# The tool library: numbers as in the machine's tool table.
[[tools]]
number = 1
diameter = "6mm"
feed = "1200mm/min"
plunge-feed = "300mm/min"
spindle = 12000

[[tools]]
number = 2
diameter = "2mm"
feed = "600mm/min"
plunge-feed = "150mm/min"
spindle = 18000

# The operations, in the order they run: the pockets of their layers, with one tool.
[[operations]]
layers = ["SHALLOW"]
tool = 1
depth = "3mm"

[[operations]]
layers = ["DEEP"]
tool = 1
depth = "6mm"
step-down = "2mm"
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_template_reads() {
        let f = parse("template", TEMPLATE).unwrap();
        assert_eq!(f.tools.len(), 2);
        assert_eq!(f.operations.len(), 2);
    }

    #[test]
    fn a_misspelled_key_is_named_with_its_line() {
        let text = "drawing = \"a.dxf\"\n[[tools]]\nnumber = 1\ndiameter = 6\n[[operations]]\nlayers = [\"A\"]\ntool = 1\ndepht = 3\n";
        let e = parse("job.toml", text).unwrap_err();
        assert!(e.starts_with("job.toml:8:"), "{e}");
        assert!(e.contains("depht"), "{e}");
    }

    #[test]
    fn lengths_feeds_and_shares_read_with_their_units() {
        let text = "drawing = \"a.dxf\"\n[[tools]]\nnumber = 1\ndiameter = \"0.25in\"\nfeed = \"40in/min\"\n[[operations]]\ntool = 1\ndepth = 3\nstepover = \"40%\"\n";
        let f = parse("job.toml", text).unwrap();
        let loc = Locator {
            name: "job.toml",
            text,
        };
        let d = loc.length(&f.tools[0].diameter, "diameter", true).unwrap();
        assert!((d - 6.35).abs() < 1e-12);
        assert!((loc.rate(f.tools[0].feed.as_ref().unwrap(), "feed").unwrap() - 1016.0).abs() < 1e-9);
        let s = loc
            .stepover(f.operations[0].stepover.as_ref().unwrap(), d)
            .unwrap();
        assert!((s - 2.54).abs() < 1e-12);
        let bad = "drawing = \"a.dxf\"\n[[operations]]\ntool = 1\ndepth = \"3 furlongs\"\n";
        let f = parse("job.toml", bad).unwrap();
        let loc = Locator {
            name: "job.toml",
            text: bad,
        };
        let e = loc
            .length(
                f.operations[0].depth.as_ref().unwrap(),
                "operations[1].depth",
                true,
            )
            .unwrap_err();
        assert!(e.starts_with("job.toml:4: operations[1].depth:"), "{e}");
    }
}
