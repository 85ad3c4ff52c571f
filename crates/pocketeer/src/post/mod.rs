//! G-code: one writer for the moves, one small file per controller for what differs between
//! them (start and end of the program, comments, arc centre mode).
//!
//! In: a [`Toolpath`] and [`ProgramSettings`] (feeds, spindle, heights, coolant). Out: the
//! program text ([`write_gcode`]) for a [`Dialect`], and the time it takes ([`estimate`]).
//!
//! Arcs stay arcs: G2/G3 with I/J relative to the printed start point (never R), split into
//! pieces of at most half a turn, so the centre the controller computes is within 0.0001 mm of
//! ours and every end point lies on its circle to well under GRBL's 0.005 mm.

mod grbl;
mod linuxcnc;
mod mach3;

use crate::fixed::{fixed, push_fixed, quantize, Text};
use crate::geom::{Point, Vector};
use crate::machining_time::TimeModel;
use crate::toolpath::{half_turns, Feed, Move, Point3, Toolpath};

/// Coolant switched on after the spindle starts and off at the end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Coolant {
    /// None (no M7/M8 written; M9 neither).
    #[default]
    Off,
    /// Flood coolant (M8).
    Flood,
    /// Mist coolant (M7). GRBL accepts M7 only when built with `ENABLE_M7`; its post writes a
    /// comment instead.
    Mist,
}

/// The controllers we write for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    /// GRBL 1.1 (hobby machines, Arduino based).
    Grbl,
    /// LinuxCNC 2.8 and later.
    LinuxCnc,
    /// Mach3.
    Mach3,
}

/// Units of the program (coordinates and feeds).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramUnits {
    /// Millimetres (G21).
    Millimetres,
    /// Inches (G20).
    Inches,
}

/// What the program needs besides the moves.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramSettings {
    /// Units of the program.
    pub units: ProgramUnits,
    /// Cutting feed, mm/min.
    pub feed: f64,
    /// Plunge feed, mm/min.
    pub plunge_feed: f64,
    /// Spindle speed, rpm.
    pub spindle: f64,
    /// Safe height, mm.
    pub safe_z: f64,
    /// Lines for the header comment (tool, stepover, statistics...).
    pub header: Vec<String>,
    /// Seconds to dwell after starting the spindle, so that it reaches its speed before the
    /// first cut (G4 P in seconds, as LinuxCNC and GRBL 1.1 read it; Mach3 reads P in seconds
    /// or milliseconds by a setting of its own, which its programs' dwell line names); 0 writes
    /// none.
    pub spindle_wait: f64,
    /// The tool to load before the spindle starts (`T n M6`; GRBL, which has no tool changer,
    /// gets the `T` word and a comment), or none.
    pub tool: Option<u32>,
    /// Coolant during the program.
    pub coolant: Coolant,
    /// Where to move at the safe height after the spindle stops (XY, mm), or nowhere.
    pub park: Option<Point>,
}

impl Default for ProgramSettings {
    /// Millimetres, 1000 and 300 mm/min, 12000 rpm, 5 mm safe height, a 2 s spindle wait, no
    /// tool change, no coolant, no park, no header.
    fn default() -> ProgramSettings {
        ProgramSettings {
            units: ProgramUnits::Millimetres,
            feed: 1000.0,
            plunge_feed: 300.0,
            spindle: 12000.0,
            safe_z: 5.0,
            header: Vec::new(),
            spindle_wait: 2.0,
            tool: None,
            coolant: Coolant::Off,
            park: None,
        }
    }
}

/// The figures of a program as written: lengths, retracts, dwells and time.
///
/// The first move only brings the tool from wherever it is to the start: its length is not
/// known and is not counted (a reader of the program, such as `check`, cannot count it either).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Estimate {
    /// Length of feed moves (cutting, plunging, ramping, leaving the stock), mm.
    pub feed_length: f64,
    /// Length of rapid moves, mm.
    pub rapid_length: f64,
    /// Rapid moves upwards.
    pub retracts: usize,
    /// Seconds of dwell.
    pub dwell: f64,
    /// Estimated machining time, seconds.
    pub seconds: f64,
}

/// The figures of the program [`write_gcode`] writes for `path` with `s`, timed with its feeds,
/// rapids at `rapid_rate` mm/min and `per_retract` seconds for each retract
/// (see [`crate::machining_time`]).
///
/// ```
/// use pocketeer::post::{estimate, ProgramSettings};
/// use pocketeer::toolpath::{Feed, Point3, Toolpath};
/// let mut path = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
/// path.rapid(Point3::new(10.0, 0.0, 5.0)); // from an unknown place: not counted
/// path.rapid(Point3::new(10.0, 0.0, 1.0));
/// path.line(Point3::new(10.0, 0.0, -2.0), Feed::Plunge);
/// path.line(Point3::new(40.0, 0.0, -2.0), Feed::Cut);
/// let e = estimate(&path, &ProgramSettings::default(), 5000.0, 0.5);
/// // 3 mm down at 300 mm/min, 30 mm at 1000; rapids 4 mm down and 7 mm up at the end.
/// assert_eq!((e.feed_length, e.rapid_length, e.retracts), (33.0, 11.0, 1));
/// // The spindle's 2 s dwell counts too, and half a second for the retract.
/// assert!((e.seconds - (0.6 + 1.8 + 11.0 * 60.0 / 5000.0 + 2.0 + 0.5)).abs() < 1e-9);
/// ```
pub fn estimate(path: &Toolpath, s: &ProgramSettings, rapid_rate: f64, per_retract: f64) -> Estimate {
    let model = TimeModel {
        feed: s.feed,
        plunge_feed: s.plunge_feed,
        rapid: rapid_rate,
        per_retract,
    };
    let stats = path.stats();
    let mut e = Estimate {
        feed_length: stats.cut_length + stats.plunge_length,
        rapid_length: stats.rapid_length,
        retracts: stats.retracts,
        dwell: s.spindle_wait.max(0.0),
        seconds: 0.0,
    };
    let mut end = path.position();
    if end.z < s.safe_z {
        e.rapid_length += s.safe_z - end.z;
        e.retracts += 1;
        end.z = s.safe_z;
    }
    if let Some(p) = s.park {
        e.rapid_length += end.xy().distance(p);
    }
    let time = model.toolpath(path);
    // The path's own rapids and retracts, then the ones the program adds at its end.
    e.seconds = time.total()
        + model.rapid_seconds(e.rapid_length - stats.rapid_length)
        + per_retract * (e.retracts - stats.retracts) as f64
        + e.dwell;
    e
}

/// What one controller needs at the start and end of a program.
trait Post {
    /// A comment line holding `text`: in parentheses, which every controller we write for reads.
    fn comment(&self, text: &str) -> String {
        format!("({text})")
    }
    /// The lines that load tool `n` (before the spindle starts): by default a changer's
    /// `T n M6` and the tool's length offset.
    fn tool_change(&self, n: u32) -> Vec<String> {
        change_tool_with_length_offset(n)
    }
    /// The lines that change to tool `n` in the middle of a program, the spindle stopped.
    fn tool_change_during(&self, n: u32) -> Vec<String> {
        self.tool_change(n)
    }
    /// True when the controller takes M7 (mist coolant).
    fn has_mist(&self) -> bool {
        true
    }
    /// A remark for the dwell line, where the controller's reading of G4 P is a setting.
    fn dwell_remark(&self) -> Option<&'static str> {
        None
    }
    /// Modal setup after the units word.
    fn setup(&self) -> &'static [&'static str];
    /// The program end.
    fn end(&self) -> &'static str;
}

/// `T n M6` and the tool's length offset from the machine's tool table (`G43 H n`), as
/// controllers with a tool changer take them.
fn change_tool_with_length_offset(n: u32) -> Vec<String> {
    vec![format!("T{n} M6"), format!("G43 H{n}")]
}

fn post(d: Dialect) -> &'static dyn Post {
    match d {
        Dialect::Grbl => &grbl::Grbl,
        Dialect::LinuxCnc => &linuxcnc::LinuxCnc,
        Dialect::Mach3 => &mach3::Mach3,
    }
}

/// Parentheses close a comment in every dialect: keep them (and control characters) out of
/// the text.
fn clean(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '(' | ')' => '/',
            c if c.is_control() => ' ',
            c => c,
        })
        .collect()
}

/// Writes `path` as a G-code program for `dialect`.
///
/// ```
/// use pocketeer::post::{write_gcode, Dialect, ProgramSettings, ProgramUnits};
/// use pocketeer::toolpath::{Feed, Point3, Toolpath};
/// let mut path = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
/// path.rapid(Point3::new(10.0, 0.0, 5.0));
/// path.line(Point3::new(10.0, 0.0, -1.0), Feed::Plunge);
/// let settings = ProgramSettings {
///     units: ProgramUnits::Millimetres, feed: 1000.0, plunge_feed: 300.0, spindle: 12000.0,
///     safe_z: 5.0, ..ProgramSettings::default()
/// };
/// let g = write_gcode(&path, &settings, Dialect::Grbl);
/// assert!(g.contains("M3 S12000\nG4 P2\n"));
/// assert!(g.contains("G0 X10.0000 Y0.0000\n"));
/// assert!(g.contains("G1 Z-1.0000 F300\n"));
/// ```
pub fn write_gcode(path: &Toolpath, s: &ProgramSettings, dialect: Dialect) -> String {
    let one = ToolSection {
        toolpath: path,
        tool: s.tool,
        feed: s.feed,
        plunge_feed: s.plunge_feed,
        spindle: s.spindle,
        remark: String::new(),
    };
    write_gcode_tools(&[one], s, dialect)
}

/// The part of a program one tool cuts: its moves, the tool and its rates.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolSection<'a> {
    /// The moves, starting above the stock at the safe height.
    pub toolpath: &'a Toolpath,
    /// The tool to load (`T n M6`), or none for the tool already in the spindle.
    pub tool: Option<u32>,
    /// Cutting feed, mm/min.
    pub feed: f64,
    /// Plunge feed, mm/min.
    pub plunge_feed: f64,
    /// Spindle speed, rpm.
    pub spindle: f64,
    /// A comment written where the section starts (what the tool cuts), or nothing.
    pub remark: String,
}

/// Writes the `sections` one after the other as one G-code program for `dialect`, with a
/// tool change between them: up to the safe height, spindle and coolant off, the change
/// (`T n M6` and the length offset `G43 H n`; GRBL, which has no changer, stops with `M0` and a
/// comment naming the tool to load), the spindle on at the new tool's speed and its wait. The
/// units, safe height, header, wait, coolant and park come from `s` (its tool and rates are
/// the sections').
///
/// ```
/// use pocketeer::post::{write_gcode_tools, Dialect, ProgramSettings, ToolSection};
/// use pocketeer::toolpath::{Feed, Point3, Toolpath};
/// let mut a = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
/// a.rapid(Point3::new(10.0, 0.0, 5.0));
/// a.line(Point3::new(10.0, 0.0, -1.0), Feed::Plunge);
/// let b = a.clone();
/// let section = |path, tool, spindle| ToolSection {
///     toolpath: path, tool: Some(tool), feed: 1000.0, plunge_feed: 300.0, spindle,
///     remark: String::new(),
/// };
/// let s = ProgramSettings::default();
/// let g = write_gcode_tools(&[section(&a, 1, 12000.0), section(&b, 2, 18000.0)], &s, Dialect::LinuxCnc);
/// assert!(g.contains("G0 Z5.0000\nM5\nT2 M6\nG43 H2\nM3 S18000\n"));
/// let g = write_gcode_tools(&[section(&a, 1, 12000.0), section(&b, 2, 18000.0)], &s, Dialect::Grbl);
/// assert!(g.contains("M5\n(load tool 2, then press cycle start)\nT2\nM0\nM3 S18000\n"));
/// ```
pub fn write_gcode_tools(sections: &[ToolSection], s: &ProgramSettings, dialect: Dialect) -> String {
    let post = post(dialect);
    let mut w = Writer {
        out: Text::default(),
        scale: match s.units {
            ProgramUnits::Millimetres => 1.0,
            ProgramUnits::Inches => 1.0 / 25.4,
        },
        decimals: match s.units {
            ProgramUnits::Millimetres => 4,
            ProgramUnits::Inches => 5,
        },
        at: [None, None, None],
        feed: None,
    };
    for line in &s.header {
        w.line(&post.comment(&clean(line)));
    }
    w.line(match s.units {
        ProgramUnits::Millimetres => "G21",
        ProgramUnits::Inches => "G20",
    });
    for l in post.setup() {
        w.line(l);
    }
    let safe = w.num(s.safe_z);
    w.line(&format!("G0 Z{safe}"));
    w.at[2] = w.quantized(s.safe_z);
    // The word that switches the coolant on, where the controller has one: M9 ends it.
    let coolant_on = match s.coolant {
        Coolant::Off => None,
        Coolant::Flood => Some("M8"),
        Coolant::Mist => post.has_mist().then_some("M7"),
    };
    let mut spindle: Option<f64> = None;
    for (k, section) in sections.iter().enumerate() {
        // A section with a tool to load starts the spindle again; one with the tool already
        // in the spindle only changes its speed, where it differs.
        let start = k == 0 || section.tool.is_some();
        if k > 0 && start {
            // The last section ended at the safe height: the spindle and coolant off.
            w.line("M5");
            if coolant_on.is_some() {
                w.line("M9");
            }
        }
        if !section.remark.is_empty() {
            w.line(&post.comment(&clean(&section.remark)));
        }
        if let Some(n) = section.tool {
            let lines = if k == 0 {
                post.tool_change(n)
            } else {
                post.tool_change_during(n)
            };
            for l in lines {
                w.line(&l);
            }
        }
        if start || spindle != Some(section.spindle) {
            w.line(&format!("M3 S{}", fmt_rate(section.spindle)));
            spindle = Some(section.spindle);
        }
        if start && s.spindle_wait > 0.0 {
            let remark = post
                .dwell_remark()
                .map(|r| format!(" {}", post.comment(r)))
                .unwrap_or_default();
            w.line(&format!("G4 P{}{remark}", fmt_rate(s.spindle_wait)));
        }
        match coolant_on {
            Some(word) if start => w.line(word),
            None if s.coolant == Coolant::Mist && k == 0 => w.line(
                &post.comment("mist coolant asked for: this controller has no M7, switch it on by hand"),
            ),
            _ => {}
        }
        let rates = ProgramSettings {
            feed: section.feed,
            plunge_feed: section.plunge_feed,
            ..ProgramSettings::default()
        };
        let path = section.toolpath;
        let mut from = path.start;
        for m in &path.moves {
            match *m {
                Move::Rapid { to } => w.motion("G0", to, None, ""),
                Move::Line { to, feed } => {
                    let f = w.feed_word(rate(&rates, feed, m, from));
                    w.motion("G1", to, None, &f)
                }
                Move::Arc {
                    to,
                    center,
                    sweep,
                    feed,
                } => {
                    let f = w.feed_word(rate(&rates, feed, m, from));
                    w.arc(from, to, center, sweep, &f)
                }
            }
            from = m.to();
        }
        let p = path.position();
        if p.z < s.safe_z {
            w.motion("G0", Point3::new(p.x, p.y, s.safe_z), None, "");
        }
    }
    w.line("M5");
    if coolant_on.is_some() {
        w.line("M9");
    }
    if let Some(park) = s.park {
        w.motion("G0", Point3::at(park, s.safe_z), None, "");
    }
    w.line(post.end());
    w.out.into_string()
}

/// The feed rate of move `m` from `from`.
fn rate(s: &ProgramSettings, f: Feed, m: &Move, from: Point3) -> f64 {
    f.rate(s.feed, s.plunge_feed, m.length(from), from.z - m.to().z)
}

/// A rate (feed or speed) without needless decimals.
fn fmt_rate(v: f64) -> String {
    let t = format!("{v:.3}");
    let t = t.trim_end_matches('0').trim_end_matches('.');
    t.to_string()
}

struct Writer {
    out: Text,
    /// Program units per millimetre.
    scale: f64,
    decimals: usize,
    /// The last printed X, Y, Z, in units of the last printed decimal.
    at: [Option<i64>; 3],
    /// The feed last written, mm/min.
    feed: Option<f64>,
}

impl Writer {
    fn line(&mut self, l: &str) {
        self.out.push_str(l);
        self.out.push('\n');
    }

    fn num(&self, mm: f64) -> String {
        fixed(mm * self.scale, self.decimals)
    }

    /// A coordinate as it will be printed (None when too large to quantize).
    fn quantized(&self, mm: f64) -> Option<i64> {
        quantize(mm * self.scale, self.decimals)
    }

    /// A printed value back in millimetres.
    fn mm(&self, n: i64) -> f64 {
        n as f64 / 10f64.powi(self.decimals as i32) / self.scale
    }

    /// " F..." when the feed changes, else "".
    fn feed_word(&mut self, mm_per_min: f64) -> String {
        if self.feed == Some(mm_per_min) {
            return String::new();
        }
        self.feed = Some(mm_per_min);
        format!(" F{}", fmt_rate(mm_per_min * self.scale))
    }

    /// Writes a motion word with the coordinates that change, then I/J and the feed.
    fn motion(&mut self, word: &str, to: Point3, ij: Option<(f64, f64)>, feed: &str) {
        let line_start = self.out.len();
        self.out.push_str(word);
        let mut moved = false;
        for (k, (name, v)) in [('X', to.x), ('Y', to.y), ('Z', to.z)].into_iter().enumerate() {
            let n = self.quantized(v);
            if n.is_none() || self.at[k] != n {
                self.out.push(' ');
                self.out.push(name);
                match n {
                    Some(n) => push_fixed(&mut self.out, n, self.decimals),
                    None => {
                        let t = self.num(v);
                        self.out.push_str(&t);
                    }
                }
                self.at[k] = n;
                moved = true;
            }
        }
        if let Some((i, j)) = ij {
            for (name, v) in [(" I", i), (" J", j)] {
                self.out.push_str(name);
                match self.quantized(v) {
                    Some(n) => push_fixed(&mut self.out, n, self.decimals),
                    None => {
                        let t = self.num(v);
                        self.out.push_str(&t);
                    }
                }
            }
        } else if !moved {
            self.out.truncate(line_start);
            return;
        }
        self.out.push_str(feed);
        self.out.push('\n');
    }

    fn arc(&mut self, from: Point3, to: Point3, center: Point, sweep: f64, feed: &str) {
        let radius = center.distance(from.xy());
        let pieces = half_turns(sweep);
        let mut start = from;
        let mut angle = (from.xy() - center).angle();
        let mut feed = feed.to_string();
        for (k, piece) in pieces.iter().enumerate() {
            angle += piece;
            let end = if k + 1 == pieces.len() {
                to
            } else {
                let xy = center + Vector::from_angle(angle) * radius;
                let z = from.z + (to.z - from.z) * (k + 1) as f64 / pieces.len() as f64;
                Point3::at(xy, z)
            };
            self.arc_piece(start, end, center, *piece, &feed);
            feed.clear();
            start = end;
        }
    }

    /// One arc of at most half a turn; a line when it is too small for a controller to take
    /// as an arc (its printed ends equal, or shorter than a thousandth of a millimetre).
    fn arc_piece(&mut self, from: Point3, to: Point3, center: Point, sweep: f64, feed: &str) {
        let radius = center.distance(from.xy());
        let same_ends =
            self.quantized(from.x) == self.quantized(to.x) && self.quantized(from.y) == self.quantized(to.y);
        if radius * sweep.abs() < 1e-3 || same_ends {
            self.motion("G1", to, None, feed);
            return;
        }
        // I and J from the point the controller starts at: the printed one.
        let sx = self.at[0].map_or(from.x, |n| self.mm(n));
        let sy = self.at[1].map_or(from.y, |n| self.mm(n));
        let word = if sweep > 0.0 { "G3" } else { "G2" };
        // Arc words always carry X and Y, so the controller never reads a full circle.
        self.at[0] = None;
        self.at[1] = None;
        self.motion(word, to, Some((center.x - sx, center.y - sy)), feed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn settings(units: ProgramUnits) -> ProgramSettings {
        ProgramSettings {
            units,
            feed: 1200.0,
            plunge_feed: 300.0,
            spindle: 18000.0,
            safe_z: 5.0,
            header: vec!["tool (6 mm)".into()],
            ..ProgramSettings::default()
        }
    }

    fn circle_path() -> Toolpath {
        let mut p = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
        p.rapid(Point3::new(10.0, 0.0, 5.0));
        p.line(Point3::new(10.0, 0.0, -1.0), Feed::Plunge);
        p.arc_to(
            Point3::new(10.0, 0.0, -1.0),
            Point::new(0.0, 0.0),
            -2.0 * PI,
            Feed::Cut,
        );
        p
    }

    #[test]
    fn full_circles_become_two_half_turns_with_ij() {
        let g = write_gcode(
            &circle_path(),
            &settings(ProgramUnits::Millimetres),
            Dialect::Grbl,
        );
        assert!(
            g.contains("G2 X-10.0000 Y0.0000 I-10.0000 J0.0000 F1200\n"),
            "{g}"
        );
        assert!(g.contains("G2 X10.0000 Y0.0000 I10.0000 J0.0000\n"), "{g}");
        assert!(g.contains("(tool /6 mm/)"));
        assert!(!g.contains(" R"));
    }

    #[test]
    fn inch_programs_scale_coordinates_and_feeds() {
        let g = write_gcode(&circle_path(), &settings(ProgramUnits::Inches), Dialect::LinuxCnc);
        assert!(g.contains("G20\n"));
        assert!(g.contains("G0 X0.39370 Y0.00000\n"), "{g}");
        assert!(g.contains("F47.244"), "{g}");
    }

    #[test]
    fn tiny_arcs_become_lines() {
        let mut p = Toolpath::new(Point3::new(0.0, 0.0, -1.0));
        p.arc_to(
            Point3::new(1e-5, 0.0, -1.0),
            Point::new(0.0, 5.0),
            2e-6,
            Feed::Cut,
        );
        let g = write_gcode(&p, &settings(ProgramUnits::Millimetres), Dialect::Grbl);
        assert!(!g.contains("\nG2 ") && !g.contains("\nG3 "), "{g}");
    }
}
