//! How long a program takes: the one time model the pocket summary prints, `check` reports and
//! the linker weighs its choices in.
//!
//! Feed moves take their length at their feed, rapids their length at the rapid rate, dwells
//! their seconds, and each retract to the safe height a fixed cost on top: the acceleration,
//! deceleration and settling of going up, across and down again that lengths over rates leave
//! out, and that makes many short hops dearer than one longer feed move.

use crate::toolpath::{Feed, Move, Point3, Toolpath};

/// The fixed cost of one retract, seconds, unless told: an estimate (set it for the machine
/// with `--retract-time`). A rapid of a few millimetres at 5000 mm/min and an acceleration of
/// 500 mm/s² loses about v/a = 0.17 s to speeding up and braking; a retract is three of them
/// (up, across, down).
pub const DEFAULT_RETRACT_SECONDS: f64 = 0.5;

/// Rates and fixed costs that turn moves into seconds.
///
/// ```
/// use pocketeer::machining_time::TimeModel;
/// let m = TimeModel { feed: 1000.0, plunge_feed: 300.0, rapid: 5000.0, per_retract: 0.5 };
/// assert_eq!(m.feed_seconds(1000.0, 1000.0), 60.0);
/// assert_eq!(m.rapid_seconds(5000.0), 60.0);
/// // A 20 mm link at the feed against a retract of 5 mm up, 20 across and 5 down, and a
/// // 2 mm plunge: the link is the quicker.
/// assert!(m.feed_seconds(20.0, m.feed) < m.hop_seconds(5.0, 20.0, 5.0) + m.feed_seconds(2.0, m.plunge_feed));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeModel {
    /// The cutting feed, mm/min.
    pub feed: f64,
    /// The plunge feed (entries and leaving the stock), mm/min.
    pub plunge_feed: f64,
    /// The rapid rate, mm/min.
    pub rapid: f64,
    /// The fixed cost of each retract, seconds.
    pub per_retract: f64,
}

impl Default for TimeModel {
    /// 1000 and 300 mm/min, rapids at 5000 mm/min, [`DEFAULT_RETRACT_SECONDS`] a retract.
    fn default() -> TimeModel {
        TimeModel {
            feed: 1000.0,
            plunge_feed: 300.0,
            rapid: crate::simulate::check::RAPID_RATE,
            per_retract: DEFAULT_RETRACT_SECONDS,
        }
    }
}

/// A program's time, seconds, by kind of move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MachiningTime {
    /// Feed moves at the cutting feed.
    pub cutting: f64,
    /// Entries: feed moves at the plunge feed, and helices and ramps.
    pub plunging: f64,
    /// Rapid moves.
    pub rapid: f64,
    /// The fixed cost of the retracts.
    pub retracts: f64,
    /// Dwells.
    pub dwell: f64,
}

impl MachiningTime {
    /// The whole time, seconds.
    pub fn total(&self) -> f64 {
        self.cutting + self.plunging + self.rapid + self.retracts + self.dwell
    }
}

impl TimeModel {
    /// Seconds for `length` mm at `feed` mm/min (none for a feed that is not positive: such a
    /// move is reported, not timed).
    pub fn feed_seconds(&self, length: f64, feed: f64) -> f64 {
        if feed > 0.0 {
            60.0 * length / feed
        } else {
            0.0
        }
    }

    /// Seconds for `length` mm of rapid moves.
    pub fn rapid_seconds(&self, length: f64) -> f64 {
        60.0 * length / self.rapid
    }

    /// Seconds for a hop: `up` mm to the safe height, `across` at it and `down` again, as
    /// rapids, with the fixed cost of a retract.
    pub fn hop_seconds(&self, up: f64, across: f64, down: f64) -> f64 {
        self.rapid_seconds(up + across + down) + self.per_retract
    }

    /// The time of `path`, its first rapid left out (it only brings the tool from wherever it
    /// is to the start, see [`Toolpath::stats`]).
    ///
    /// ```
    /// use pocketeer::machining_time::TimeModel;
    /// use pocketeer::toolpath::{Feed, Point3, Toolpath};
    /// let mut path = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
    /// path.rapid(Point3::new(10.0, 0.0, 5.0)); // not counted
    /// path.line(Point3::new(10.0, 0.0, -3.0), Feed::Plunge);
    /// path.line(Point3::new(40.0, 0.0, -3.0), Feed::Cut);
    /// path.rapid(Point3::new(40.0, 0.0, 5.0));
    /// let m = TimeModel { feed: 1000.0, plunge_feed: 300.0, rapid: 5000.0, per_retract: 0.5 };
    /// let t = m.toolpath(&path);
    /// assert!((t.plunging - 1.6).abs() < 1e-9 && (t.cutting - 1.8).abs() < 1e-9);
    /// assert!((t.rapid - 8.0 * 60.0 / 5000.0).abs() < 1e-9 && t.retracts == 0.5);
    /// ```
    pub fn toolpath(&self, path: &Toolpath) -> MachiningTime {
        self.moves(path.counted_moves())
    }

    /// The time of `moves`, each with where it starts, every one counted (see
    /// [`TimeModel::toolpath`] for a whole program, whose first rapid is not).
    ///
    /// ```
    /// use pocketeer::machining_time::TimeModel;
    /// use pocketeer::toolpath::{Move, Point3};
    /// let m = TimeModel { feed: 1000.0, plunge_feed: 300.0, rapid: 5000.0, per_retract: 0.5 };
    /// let up = Move::Rapid { to: Point3::new(0.0, 0.0, 5.0) };
    /// let t = m.moves([(Point3::new(0.0, 0.0, -3.0), &up)]);
    /// assert!((t.rapid - 8.0 * 60.0 / 5000.0).abs() < 1e-9 && t.retracts == 0.5);
    /// ```
    pub fn moves<'a>(&self, moves: impl IntoIterator<Item = (Point3, &'a Move)>) -> MachiningTime {
        let mut t = MachiningTime::default();
        for (at, m) in moves {
            let len = m.length(at);
            match m {
                Move::Rapid { to } => {
                    t.rapid += self.rapid_seconds(len);
                    if to.z > at.z {
                        t.retracts += self.per_retract;
                    }
                }
                Move::Line { feed: Feed::Cut, .. } | Move::Arc { feed: Feed::Cut, .. } => {
                    t.cutting += self.feed_seconds(len, self.feed)
                }
                Move::Line { feed, .. } | Move::Arc { feed, .. } => {
                    let rate = feed.rate(self.feed, self.plunge_feed, len, at.z - m.to().z);
                    t.plunging += self.feed_seconds(len, rate)
                }
            }
        }
        t
    }
}
