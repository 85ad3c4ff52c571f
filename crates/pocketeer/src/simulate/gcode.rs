//! Reading G-code programs back: the moves a controller would make, in millimetres, absolute.
//!
//! Our own reader rather than the `gcode` crate: the check needs every error to name its line,
//! LinuxCNC's and GRBL's rule on arc end points, and modal state (units, distance modes, arc
//! centre modes) applied exactly as controllers do, which is most of the work either way.

use crate::geom::Point;
use crate::toolpath::Point3;
use thiserror::Error;

/// Largest distance between an arc's end point and its circle that is accepted (LinuxCNC
/// refuses beyond 0.002 mm; GRBL beyond 0.005 mm).
pub const ARC_END_TOLERANCE: f64 = 0.002;

/// Why a program cannot be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GcodeError {
    /// A word that is not a letter followed by a number.
    #[error("line {line}: cannot read '{word}'")]
    BadWord {
        /// Line number (from 1).
        line: usize,
        /// The text.
        word: String,
    },
    /// A plane other than XY.
    #[error("line {line}: only the XY plane (G17) is supported, not G{code}")]
    Plane {
        /// Line number.
        line: usize,
        /// 18 or 19.
        code: u32,
    },
    /// An arc whose end point is off its circle.
    #[error(
        "line {line}: the arc's end point is {off:.4} mm off its circle (radius {radius:.4} at the start)"
    )]
    ArcEnd {
        /// Line number.
        line: usize,
        /// Difference of the radii at the two ends, mm.
        off: f64,
        /// Radius at the start, mm.
        radius: f64,
    },
    /// An arc that cannot be built (no centre, R too small for the chord).
    #[error("line {line}: {what}")]
    BadArc {
        /// Line number.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// A move before any position is known on an axis it does not name.
    #[error("line {line}: a move before the program has set Z (the start position is unknown)")]
    UnknownStart {
        /// Line number.
        line: usize,
    },
}

/// What kind of move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// G0.
    Rapid,
    /// G1.
    Line,
    /// G2 or G3 around `center` (XY); a helix when Z changes.
    Arc {
        /// Centre in XY.
        center: Point,
        /// Signed sweep, radians (positive counter-clockwise).
        sweep: f64,
    },
}

/// One move of a program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgramMove {
    /// Line (from 1).
    pub line: usize,
    /// Kind.
    pub motion: Motion,
    /// Start, mm.
    pub from: Point3,
    /// End, mm.
    pub to: Point3,
    /// Feed rate in force, mm/min (`None` when no F word came yet).
    pub feed: Option<f64>,
}

impl ProgramMove {
    /// Length in space, helical arcs included.
    pub fn length(&self) -> f64 {
        match self.motion {
            Motion::Arc { center, sweep } => {
                (center.distance(self.from.xy()) * sweep.abs()).hypot(self.to.z - self.from.z)
            }
            _ => self.from.distance(self.to),
        }
    }

    /// Seconds the move takes in the time model of [`crate::machining_time`]: a feed move its
    /// length at its feed (none without a feed), a rapid its length at `rapid_rate` (mm/min),
    /// and a rapid upwards (a retract) `per_retract` on top.
    ///
    /// ```
    /// use pocketeer::simulate::read_program;
    /// let p = read_program("G0 X0 Y0 Z0\nG1 X10 F600\nG0 Z5\n").unwrap();
    /// assert_eq!(p.moves[0].seconds(5000.0, 0.5), 1.0);
    /// assert_eq!(p.moves[1].seconds(6000.0, 0.5), 0.05 + 0.5);
    /// ```
    pub fn seconds(&self, rapid_rate: f64, per_retract: f64) -> f64 {
        let len = self.length();
        match (self.motion, self.feed) {
            (Motion::Rapid, _) if self.to.z > self.from.z => 60.0 * len / rapid_rate + per_retract,
            (Motion::Rapid, _) => 60.0 * len / rapid_rate,
            (_, Some(f)) if f > 0.0 => 60.0 * len / f,
            _ => 0.0,
        }
    }

    /// The path of the move seen from above.
    pub fn footprint(&self) -> crate::geom::Segment {
        use crate::geom::{Arc, Line, Segment};
        match self.motion {
            Motion::Arc { center, sweep } => {
                let v = self.from.xy() - center;
                Segment::Arc(Arc::new(center, v.length(), v.angle(), sweep))
            }
            _ => Segment::Line(Line::new(self.from.xy(), self.to.xy())),
        }
    }

    /// The point at parameter `t` in 0..=1 (Z linear along the move).
    pub fn point_at(&self, t: f64) -> Point3 {
        let z = self.from.z + (self.to.z - self.from.z) * t;
        match self.motion {
            Motion::Arc { center, sweep } => {
                let v = self.from.xy() - center;
                let a = v.angle() + sweep * t;
                let p = center + crate::geom::Vector::from_angle(a) * v.length();
                Point3::at(p, z)
            }
            _ => Point3::at(self.from.xy().lerp(self.to.xy(), t), z),
        }
    }
}

/// A program read: its moves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    /// The moves in order.
    pub moves: Vec<ProgramMove>,
    /// Seconds of dwell (G4 P, in seconds as LinuxCNC, GRBL 1.1 and Mach3's default read it).
    pub dwell: f64,
    /// The tools named (T words): the number of moves before each, and the tool's number.
    pub tools: Vec<(usize, u32)>,
}

/// Reads `text`: G0/G1/G2/G3 (modal), G17 (G18/G19 refused), G20/G21, G90/G91, G90.1/G91.1,
/// I/J or R arcs (helical when Z changes), comments in parentheses or after `;`, N numbers, `%`
/// lines; F is read (per minute), G4 P adds its seconds to the dwell, other words (M, S, T,
/// G40, G43, G49, G54, G64, G80, G94) are skipped. The start position is unknown until X, Y and Z have been set.
///
/// ```
/// use pocketeer::simulate::gcode::{read_program, Motion};
/// let p = read_program("G21 G90\nG0 Z5\nG0 X10 Y0\nG1 Z-1 F300\nG2 X-10 Y0 I-10 J0 F1000\n").unwrap();
/// // The first two rapids only set the start: the moves begin once X, Y and Z are known.
/// assert_eq!(p.moves.len(), 2);
/// assert!(matches!(p.moves[1].motion, Motion::Arc { sweep, .. } if (sweep + std::f64::consts::PI).abs() < 1e-12));
/// assert_eq!(p.moves[1].feed, Some(1000.0));
/// ```
pub fn read_program(text: &str) -> Result<Program, GcodeError> {
    let mut st = State::default();
    let mut out = Program::default();
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let words = words(raw, line)?;
        st.apply(&words, line, &mut out)?;
    }
    Ok(out)
}

#[derive(Debug)]
struct State {
    /// Known position per axis, mm.
    pos: [Option<f64>; 3],
    /// Millimetres per program unit.
    unit: f64,
    absolute: bool,
    arc_absolute: bool,
    motion: Option<u32>,
    feed: Option<f64>,
}

impl Default for State {
    fn default() -> Self {
        State {
            pos: [None; 3],
            unit: 1.0,
            absolute: true,
            arc_absolute: false,
            motion: None,
            feed: None,
        }
    }
}

/// The letter-number words of one line, comments removed.
fn words(raw: &str, line: usize) -> Result<Vec<(char, f64)>, GcodeError> {
    let mut text = String::with_capacity(raw.len());
    let mut in_comment = false;
    for c in raw.chars() {
        match c {
            '(' => in_comment = true,
            ')' => in_comment = false,
            ';' if !in_comment => break,
            '%' if !in_comment => {}
            c if !in_comment && !c.is_whitespace() => text.push(c.to_ascii_uppercase()),
            _ => {}
        }
    }
    let bytes: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let letter = bytes[i];
        if !letter.is_ascii_alphabetic() {
            return Err(GcodeError::BadWord {
                line,
                word: bytes[i..].iter().take(12).collect(),
            });
        }
        let start = i + 1;
        let mut j = start;
        while j < bytes.len() && (bytes[j].is_ascii_digit() || matches!(bytes[j], '.' | '-' | '+')) {
            j += 1;
        }
        let num: String = bytes[start..j].iter().collect();
        let value: f64 = num.parse().map_err(|_| GcodeError::BadWord {
            line,
            word: bytes[i..j.max(i + 1)].iter().collect(),
        })?;
        if !value.is_finite() {
            return Err(GcodeError::BadWord {
                line,
                word: format!("{letter}{num}"),
            });
        }
        out.push((letter, value));
        i = j;
    }
    Ok(out)
}

impl State {
    fn apply(&mut self, words: &[(char, f64)], line: usize, out: &mut Program) -> Result<(), GcodeError> {
        let (mut target, mut ij, mut r) = ([None::<f64>; 3], [None::<f64>; 2], None::<f64>);
        let mut motion_here = None;
        let (mut dwell, mut p) = (false, None::<f64>);
        for &(l, v) in words {
            match l {
                'G' => {
                    let code = (v * 10.0).round() as i64;
                    match code {
                        0 | 10 | 20 | 30 => motion_here = Some((code / 10) as u32),
                        40 => dwell = true,
                        170 => {}
                        180 | 190 => {
                            return Err(GcodeError::Plane {
                                line,
                                code: (code / 10) as u32,
                            })
                        }
                        200 => self.unit = 25.4,
                        210 => self.unit = 1.0,
                        900 => self.absolute = true,
                        910 => self.absolute = false,
                        901 => self.arc_absolute = true,
                        911 => self.arc_absolute = false,
                        _ => {}
                    }
                }
                'X' => target[0] = Some(v),
                'Y' => target[1] = Some(v),
                'Z' => target[2] = Some(v),
                'I' => ij[0] = Some(v),
                'J' => ij[1] = Some(v),
                'R' => r = Some(v),
                'P' => p = Some(v),
                'F' => self.feed = Some(v * self.unit),
                'T' if v >= 0.0 && v.fract() == 0.0 => out.tools.push((out.moves.len(), v as u32)),
                _ => {}
            }
        }
        if dwell {
            out.dwell += p.unwrap_or(0.0).max(0.0);
            return Ok(());
        }
        if let Some(m) = motion_here {
            self.motion = Some(m);
        }
        if target.iter().all(Option::is_none) {
            return Ok(());
        }
        let mut to = [0.0; 3];
        for k in 0..3 {
            to[k] = match (target[k], self.pos[k]) {
                (Some(v), _) if self.absolute => v * self.unit,
                (Some(v), Some(p)) => p + v * self.unit,
                (Some(v), None) => v * self.unit,
                (None, Some(p)) => p,
                (None, None) => f64::NAN,
            };
        }
        let known = self.pos.iter().all(Option::is_some);
        let from = [self.pos[0], self.pos[1], self.pos[2]];
        for (pos, &v) in self.pos.iter_mut().zip(&to) {
            if !v.is_nan() {
                *pos = Some(v);
            }
        }
        if !known {
            // Rapid positioning before the start is known (a first "G0 Z5", then "G0 X Y"):
            // no move to measure yet. Cutting from an unknown place cannot be checked.
            if self.motion.is_some_and(|m| m != 0) {
                return Err(GcodeError::UnknownStart { line });
            }
            return Ok(());
        }
        let from = Point3::new(
            from[0].unwrap_or(0.0),
            from[1].unwrap_or(0.0),
            from[2].unwrap_or(0.0),
        );
        let to = Point3::new(to[0], to[1], to[2]);
        let motion = match self.motion {
            Some(0) => Motion::Rapid,
            Some(1) => Motion::Line,
            Some(m @ (2 | 3)) => self.arc(m == 3, from, to, ij, r, line)?,
            _ => {
                return Err(GcodeError::BadArc {
                    line,
                    what: "a move without a motion mode (G0, G1, G2 or G3)".into(),
                })
            }
        };
        out.moves.push(ProgramMove {
            line,
            motion,
            from,
            to,
            feed: self.feed,
        });
        Ok(())
    }

    fn arc(
        &self,
        ccw: bool,
        from: Point3,
        to: Point3,
        ij: [Option<f64>; 2],
        r: Option<f64>,
        line: usize,
    ) -> Result<Motion, GcodeError> {
        let (a, b) = (from.xy(), to.xy());
        let center = if let Some(r) = r {
            // R form: the centre on the chord's bisector; a negative R takes the long way.
            let r_mm = r * self.unit;
            let chord = b - a;
            let half = chord.length() / 2.0;
            if half == 0.0 {
                return Err(GcodeError::BadArc {
                    line,
                    what: "an R arc must not end where it starts".into(),
                });
            }
            if half > r_mm.abs() + ARC_END_TOLERANCE {
                return Err(GcodeError::BadArc {
                    line,
                    what: format!("radius {r} is smaller than half the chord ({:.4} mm)", half),
                });
            }
            let h = (r_mm * r_mm - half * half).max(0.0).sqrt();
            let mid = a.midpoint(b);
            let n = chord.perp() * (1.0 / chord.length());
            // Centre to the left of the chord for a short counter-clockwise arc.
            let side = if ccw == (r_mm > 0.0) { 1.0 } else { -1.0 };
            mid + n * (side * h)
        } else {
            let (i, j) = (ij[0].unwrap_or(0.0) * self.unit, ij[1].unwrap_or(0.0) * self.unit);
            if ij.iter().all(Option::is_none) {
                return Err(GcodeError::BadArc {
                    line,
                    what: "an arc without I, J or R".into(),
                });
            }
            if self.arc_absolute {
                Point::new(i, j)
            } else {
                Point::new(a.x + i, a.y + j)
            }
        };
        let (r0, r1) = (center.distance(a), center.distance(b));
        if (r0 - r1).abs() > ARC_END_TOLERANCE {
            return Err(GcodeError::ArcEnd {
                line,
                off: (r0 - r1).abs(),
                radius: r0,
            });
        }
        let mut sweep = (b - center).angle() - (a - center).angle();
        if ccw && sweep <= 1e-12 {
            sweep += std::f64::consts::TAU;
        }
        if !ccw && sweep >= -1e-12 {
            sweep -= std::f64::consts::TAU;
        }
        Ok(Motion::Arc { center, sweep })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_units_and_comments() {
        let p = read_program(
            "%\n(header (nested? no))\nN10 G20 G91 ; inches, relative\nG0 X0 Y0 Z0\nG0 X1 Y1 Z0.5\nG1 Z-0.1 F10\n%\n",
        )
        .unwrap();
        assert_eq!(p.moves.len(), 2);
        let last = p.moves[1];
        assert!((last.to.x - 25.4).abs() < 1e-12 && (last.to.z - 10.16).abs() < 1e-9);
        assert_eq!(last.feed, Some(254.0));
    }

    #[test]
    fn r_arcs_take_the_short_or_long_way() {
        let short = read_program("G0 X0 Y0 Z0\nG2 X10 Y0 R5 F100\n").unwrap();
        let long = read_program("G0 X0 Y0 Z0\nG3 X0 Y10 R-5.000001 F100\n").unwrap();
        match (short.moves[0].motion, long.moves[0].motion) {
            (
                Motion::Arc {
                    center: c0,
                    sweep: s0,
                },
                Motion::Arc { sweep: s1, .. },
            ) => {
                assert!(c0.distance(Point::new(5.0, 0.0)) < 1e-9);
                assert!((s0 + std::f64::consts::PI).abs() < 1e-9);
                assert!(s1 > std::f64::consts::PI);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn errors_name_the_line() {
        let e = read_program("G0 X0 Y0 Z0\nG2 X10 Y0 I4 J0\n").unwrap_err();
        assert!(matches!(e, GcodeError::ArcEnd { line: 2, .. }), "{e}");
        assert!(read_program("G18\n")
            .unwrap_err()
            .to_string()
            .starts_with("line 1:"));
        assert!(read_program("G0 X0 Y0 Z0\nG1 X1 @\n")
            .unwrap_err()
            .to_string()
            .starts_with("line 2:"));
        assert!(
            read_program("G1 X5 Y5 F100\n").is_err(),
            "a cut from an unknown start"
        );
    }
}
