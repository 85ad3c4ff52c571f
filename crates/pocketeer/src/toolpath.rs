//! Tool paths: the moves of the tool centre (tip) in three dimensions, lines and arcs exact,
//! the only thing the G-code posts translate.

use crate::geom::{normalize_angle, Arc, Line, Point, Segment};
use std::f64::consts::TAU;

/// A point in machine space, mm; Z = 0 is the top of the stock, cutting happens below.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point3 {
    /// X.
    pub x: f64,
    /// Y.
    pub y: f64,
    /// Z.
    pub z: f64,
}

impl Point3 {
    /// The point (x, y, z).
    pub const fn new(x: f64, y: f64, z: f64) -> Point3 {
        Point3 { x, y, z }
    }

    /// `p` at height `z`.
    pub const fn at(p: Point, z: f64) -> Point3 {
        Point3 { x: p.x, y: p.y, z }
    }

    /// The point in the XY plane.
    pub const fn xy(self) -> Point {
        Point::new(self.x, self.y)
    }

    /// Distance to `o`.
    pub fn distance(self, o: Point3) -> f64 {
        ((self.x - o.x).powi(2) + (self.y - o.y).powi(2) + (self.z - o.z).powi(2)).sqrt()
    }
}

/// Which feed rate a cutting move uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feed {
    /// The cutting feed.
    Cut,
    /// The plunge feed: straight down into the stock.
    Plunge,
    /// Down into the stock along a path (a helix, a ramp): the cutting feed, as FreeCAD and
    /// most CAM programs give every feed move that moves in X or Y, but never descending faster
    /// than the plunge feed (see [`Feed::rate`]).
    Ramp,
}

impl Feed {
    /// The feed rate of a move of `length` (mm, in 3D) that descends `drop` mm, at this kind of
    /// feed, for a cutting feed `feed` and a plunge feed `plunge_feed` (mm/min).
    ///
    /// ```
    /// use pocketeer::toolpath::Feed;
    /// // A 3° ramp descends at sin 3° of its feed: 52 mm/min at 1000, under a 300 plunge feed.
    /// let len = 3.0 / 3f64.to_radians().sin();
    /// assert_eq!(Feed::Ramp.rate(1000.0, 300.0, len, 3.0), 1000.0);
    /// // A steep 45° ramp would descend at 707: slowed to 424 so that it descends at 300.
    /// assert!((Feed::Ramp.rate(1000.0, 300.0, 2f64.sqrt(), 1.0) - 300.0 * 2f64.sqrt()).abs() < 1e-9);
    /// assert_eq!(Feed::Plunge.rate(1000.0, 300.0, 5.0, 5.0), 300.0);
    /// ```
    pub fn rate(self, feed: f64, plunge_feed: f64, length: f64, drop: f64) -> f64 {
        match self {
            Feed::Cut => feed,
            Feed::Plunge => plunge_feed,
            Feed::Ramp if drop > 0.0 => feed.min(plunge_feed * length / drop),
            Feed::Ramp => feed,
        }
    }
}

/// One move from the previous position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Move {
    /// Straight at rapid speed (G0).
    Rapid {
        /// Where to.
        to: Point3,
    },
    /// Straight at a feed rate (G1).
    Line {
        /// Where to.
        to: Point3,
        /// Which feed.
        feed: Feed,
    },
    /// A circular arc in XY, helical when Z changes (G2/G3).
    Arc {
        /// Where to.
        to: Point3,
        /// Centre in XY.
        center: Point,
        /// Signed angle swept, radians: positive counter-clockwise (G3), up to any number of
        /// turns.
        sweep: f64,
        /// Which feed.
        feed: Feed,
    },
}

impl Move {
    /// The end of the move.
    pub fn to(&self) -> Point3 {
        match *self {
            Move::Rapid { to } | Move::Line { to, .. } | Move::Arc { to, .. } => to,
        }
    }

    /// The move from `from` seen from above: a line, or the arc it turns round its centre
    /// (the Z it climbs or descends left out).
    ///
    /// ```
    /// use pocketeer::geom::Point;
    /// use pocketeer::toolpath::{Feed, Move, Point3};
    /// let half_turn = Move::Arc {
    ///     to: Point3::new(-1.0, 0.0, -1.0),
    ///     center: Point::new(0.0, 0.0),
    ///     sweep: std::f64::consts::PI,
    ///     feed: Feed::Cut,
    /// };
    /// let s = half_turn.planar(Point3::new(1.0, 0.0, 0.0));
    /// assert!((s.length() - std::f64::consts::PI).abs() < 1e-12);
    /// assert!(s.point_at(0.5).distance(Point::new(0.0, 1.0)) < 1e-12);
    /// ```
    pub fn planar(&self, from: Point3) -> Segment {
        match *self {
            Move::Arc { center, sweep, .. } => {
                let v = from.xy() - center;
                Segment::Arc(Arc::new(center, v.length(), v.angle(), sweep))
            }
            _ => Segment::Line(Line::new(from.xy(), self.to().xy())),
        }
    }

    /// Length of the move from `from`, helical arcs included.
    pub fn length(&self, from: Point3) -> f64 {
        match *self {
            Move::Rapid { to } | Move::Line { to, .. } => from.distance(to),
            Move::Arc {
                to, center, sweep, ..
            } => {
                let planar = center.distance(from.xy()) * sweep.abs();
                planar.hypot(to.z - from.z)
            }
        }
    }
}

/// The moves of one program, starting at `start` (above the stock at the safe height).
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    /// Where the tool is before the first move.
    pub start: Point3,
    /// The moves.
    pub moves: Vec<Move>,
}

/// Figures of a tool path.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stats {
    /// Length of feed moves at the cutting feed, mm.
    pub cut_length: f64,
    /// Length of feed moves at the plunge feed, mm.
    pub plunge_length: f64,
    /// Length of rapid moves, mm.
    pub rapid_length: f64,
    /// Number of rapid moves upwards (retracts to the safe height).
    pub retracts: usize,
}

impl Toolpath {
    /// An empty path starting at `start`.
    pub fn new(start: Point3) -> Toolpath {
        Toolpath {
            start,
            moves: Vec::new(),
        }
    }

    /// Where the tool is after the last move.
    pub fn position(&self) -> Point3 {
        self.moves.last().map_or(self.start, Move::to)
    }

    /// Rapid to `to` (skipped when already there).
    pub fn rapid(&mut self, to: Point3) {
        if to != self.position() {
            self.moves.push(Move::Rapid { to });
        }
    }

    /// Straight feed move to `to` (skipped when already there).
    pub fn line(&mut self, to: Point3, feed: Feed) {
        if to != self.position() {
            self.moves.push(Move::Line { to, feed });
        }
    }

    /// Arc (helical when `z` changes) around `center` sweeping `sweep` radians, ending at
    /// height `z`.
    pub fn arc(&mut self, center: Point, sweep: f64, z: f64, feed: Feed) {
        let from = self.position();
        let v = from.xy() - center;
        let end = center + crate::geom::Vector::from_angle(normalize_angle(v.angle() + sweep)) * v.length();
        self.moves.push(Move::Arc {
            to: Point3::at(end, z),
            center,
            sweep,
            feed,
        });
    }

    /// Arc (helical when `z` changes) around `center` to `to`, sweeping `sweep` radians: for
    /// arcs whose exact end point is known.
    pub fn arc_to(&mut self, to: Point3, center: Point, sweep: f64, feed: Feed) {
        self.moves.push(Move::Arc {
            to,
            center,
            sweep,
            feed,
        });
    }

    /// Lengths and retracts. A first rapid only brings the tool from wherever it is to the
    /// start of the program (`start` is a stand-in for that unknown place): it is not counted.
    pub fn stats(&self) -> Stats {
        let mut s = Stats::default();
        for (at, m) in self.counted_moves() {
            let len = m.length(at);
            match m {
                Move::Rapid { to } => {
                    s.rapid_length += len;
                    if to.z > at.z {
                        s.retracts += 1;
                    }
                }
                Move::Line { feed: Feed::Cut, .. } | Move::Arc { feed: Feed::Cut, .. } => s.cut_length += len,
                _ => s.plunge_length += len,
            }
        }
        s
    }

    /// The moves the figures count, each with where it starts: all but a first rapid, which
    /// only brings the tool from wherever it is to the start of the program (`start` is a
    /// stand-in for that unknown place).
    pub fn counted_moves(&self) -> impl Iterator<Item = (Point3, &Move)> + '_ {
        self.moves_from(usize::from(matches!(
            self.moves.first(),
            Some(Move::Rapid { .. })
        )))
    }

    /// The moves from the `k`-th on, each with where it starts (where the one before ends, or
    /// `start` for the first).
    ///
    /// ```
    /// use pocketeer::toolpath::{Feed, Point3, Toolpath};
    /// let mut path = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
    /// path.rapid(Point3::new(10.0, 0.0, 5.0));
    /// path.line(Point3::new(10.0, 0.0, -3.0), Feed::Plunge);
    /// let (from, m) = path.moves_from(1).next().unwrap();
    /// assert_eq!((from, m.to()), (Point3::new(10.0, 0.0, 5.0), Point3::new(10.0, 0.0, -3.0)));
    /// ```
    pub fn moves_from(&self, k: usize) -> impl Iterator<Item = (Point3, &Move)> + '_ {
        let first = k.checked_sub(1).map_or(self.start, |j| self.moves[j].to());
        self.moves[k..].iter().scan(first, |at, m| {
            let from = *at;
            *at = m.to();
            Some((from, m))
        })
    }

    /// The lowest Z reached.
    pub fn deepest(&self) -> f64 {
        self.moves.iter().map(|m| m.to().z).fold(self.start.z, f64::min)
    }
}

/// Splits a sweep into pieces of at most half a turn each (G-code arcs beyond 180° are
/// ambiguous or refused by some controllers), returned as the sweep of each piece.
pub fn half_turns(sweep: f64) -> Vec<f64> {
    let n = ((sweep.abs() / (0.5 * TAU)) - 1e-12).ceil().max(1.0) as usize;
    vec![sweep / n as f64; n]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_count_lengths_and_retracts() {
        let mut t = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
        t.rapid(Point3::new(10.0, 0.0, 5.0));
        t.line(Point3::new(10.0, 0.0, -1.0), Feed::Plunge);
        t.arc(Point::new(5.0, 0.0), TAU, -1.0, Feed::Cut);
        t.line(Point3::new(10.0, 0.0, 0.0), Feed::Cut);
        t.rapid(Point3::new(10.0, 0.0, 5.0));
        let s = t.stats();
        // The first rapid comes from an unknown place: not counted.
        assert!((s.rapid_length - 5.0).abs() < 1e-12);
        assert!((s.plunge_length - 6.0).abs() < 1e-12);
        assert!((s.cut_length - 10.0 * std::f64::consts::PI - 1.0).abs() < 1e-9);
        assert_eq!(s.retracts, 1);
        assert!((t.position().x - 10.0).abs() < 1e-12);
        assert_eq!(t.deepest(), -1.0);
    }

    #[test]
    fn sweeps_split_into_half_turns() {
        assert_eq!(half_turns(1.0), vec![1.0]);
        assert_eq!(half_turns(std::f64::consts::PI).len(), 1);
        assert_eq!(half_turns(-TAU).len(), 2);
        assert_eq!(half_turns(3.5 * TAU).len(), 7);
    }
}
