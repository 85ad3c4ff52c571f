//! One piece of a biarc while the fit tries it: its ends, and for an arc its centre, radius
//! and sense, without the angles a [`Segment`] computes (two arc tangents per try, most tries
//! kept). The questions the fit asks of it — where does a curve point project on it, how far
//! is it, does the projection move forward along it — are answered with products and roots.

use crate::geom::distance::in_turn;
use crate::geom::{Arc, Line, Point, Segment, Vector};

/// A line or an arc of a biarc being tried.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// The line from `start` to `end`.
    Line {
        /// First end.
        start: Point,
        /// Second end.
        end: Point,
    },
    /// The arc around `center` from `start` to `end`, counter-clockwise when `ccw`.
    Arc {
        /// Centre.
        center: Point,
        /// Radius: the distance from the centre to `start` (`end` lies on the circle too, to
        /// within rounding).
        radius: f64,
        /// First end.
        start: Point,
        /// Second end.
        end: Point,
        /// Turning sense.
        ccw: bool,
    },
}

impl Piece {
    /// The piece as a segment of the drawing. Its ends are kept as they are, or where rounding
    /// left one off the circle by more than [`Arc::from_center`] allows, the end the radius was
    /// measured from is kept and the other moved onto the circle.
    ///
    /// ```
    /// use pocketeer::geom::{Point, Segment};
    /// use pocketeer::import::biarc_piece::Piece;
    /// let (start, end) = (Point::new(1.0, 0.0), Point::new(0.0, 1.0));
    /// let quarter = Piece::Arc { center: Point::ORIGIN, radius: 1.0, start, end, ccw: true };
    /// let Segment::Arc(a) = quarter.segment() else { panic!() };
    /// assert!((a.sweep() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    /// ```
    pub fn segment(&self) -> Segment {
        match *self {
            Piece::Line { start, end } => Segment::Line(Line::new(start, end)),
            Piece::Arc {
                center,
                radius,
                start,
                end,
                ccw,
            } => Segment::Arc(
                if (center.distance(end) - radius).abs() < (center.distance(start) - radius).abs() {
                    Arc::from_center(center, end, start, !ccw).reversed()
                } else {
                    Arc::from_center(center, start, end, ccw)
                },
            ),
        }
    }

    /// The first end.
    pub fn start(&self) -> Point {
        match *self {
            Piece::Line { start, .. } | Piece::Arc { start, .. } => start,
        }
    }

    /// The second end.
    pub fn end(&self) -> Point {
        match *self {
            Piece::Line { end, .. } | Piece::Arc { end, .. } => end,
        }
    }

    /// The piece run the other way (an arc keeps the radius measured from its old start, now
    /// its end: see [`Piece::segment`]).
    pub fn reversed(&self) -> Piece {
        match *self {
            Piece::Line { start, end } => Piece::Line {
                start: end,
                end: start,
            },
            Piece::Arc {
                center,
                radius,
                start,
                end,
                ccw,
            } => Piece::Arc {
                center,
                radius,
                start: end,
                end: start,
                ccw: !ccw,
            },
        }
    }

    /// The direction the piece runs in at its end (not of unit length).
    ///
    /// ```
    /// use pocketeer::geom::{Point, Vector};
    /// use pocketeer::import::biarc_piece::Piece;
    /// let (start, end) = (Point::new(1.0, 0.0), Point::new(0.0, 1.0));
    /// let quarter = Piece::Arc { center: Point::ORIGIN, radius: 1.0, start, end, ccw: true };
    /// assert_eq!(quarter.end_tangent(), Vector::new(-1.0, 0.0));
    /// ```
    pub fn end_tangent(&self) -> Vector {
        match *self {
            Piece::Line { start, end } => end - start,
            Piece::Arc { center, end, ccw, .. } => {
                let left = (end - center).perp();
                if ccw {
                    left
                } else {
                    -left
                }
            }
        }
    }

    /// True when the piece has no length: its ends are one point (a biarc leaves such a piece
    /// out; an arc with equal ends would be a full circle).
    pub fn is_empty(&self) -> bool {
        self.start() == self.end()
    }

    /// The distance from `p` to the piece when `p` projects onto it (onto the line between its
    /// ends, or radially onto the arc between them), `None` when it projects beyond an end.
    ///
    /// ```
    /// use pocketeer::geom::Point;
    /// use pocketeer::import::biarc_piece::Piece;
    /// let (start, end) = (Point::new(1.0, 0.0), Point::new(0.0, 1.0));
    /// let quarter = Piece::Arc { center: Point::ORIGIN, radius: 1.0, start, end, ccw: true };
    /// assert!((quarter.projected_distance(Point::new(2.0, 2.0)).unwrap() - (8f64.sqrt() - 1.0)).abs() < 1e-12);
    /// assert_eq!(quarter.projected_distance(Point::new(1.0, -0.5)), None);
    /// ```
    pub fn projected_distance(&self, p: Point) -> Option<f64> {
        match *self {
            Piece::Line { start, end } => {
                let d = end - start;
                let w = p - start;
                let along = w.dot(d);
                (along >= 0.0 && along <= d.length_sq()).then(|| w.cross(d).abs() / d.length())
            }
            Piece::Arc {
                center,
                radius,
                start,
                end,
                ccw,
            } => {
                let v = p - center;
                in_sector(start - center, end - center, v, ccw).then(|| (v.length() - radius).abs())
            }
        }
    }

    /// The distance from `p` to the piece (to its nearer end where `p` projects beyond them).
    pub fn distance(&self, p: Point) -> f64 {
        self.projected_distance(p)
            .unwrap_or_else(|| p.distance(self.start()).min(p.distance(self.end())))
    }

    /// True when going from `a` to `b`, two points projecting onto the piece, moves forward
    /// along it, and (on an arc) the arc between their projections strays at most `sag` from
    /// its chord: then the curve between two samples at `a` and `b`, which crosses every
    /// radius between them, passes each arc point there at about the samples' distance.
    pub fn steps_forward(&self, a: Point, b: Point, sag: f64) -> bool {
        match *self {
            Piece::Line { start, end } => (b - a).dot(end - start) >= 0.0,
            Piece::Arc {
                center, radius, ccw, ..
            } => {
                let (va, vb) = (a - center, b - center);
                let (cross, dot) = (va.cross(vb), va.dot(vb));
                let sense = if ccw { 1.0 } else { -1.0 };
                // Forward by less than a quarter turn: the turn θ is then at most tan θ =
                // cross / dot, and the arc strays r (1 − cos θ/2) ≤ r θ² / 8 from its chord.
                sense * cross >= -1e-12 * va.length_sq().max(vb.length_sq())
                    && dot > 0.0
                    && radius * cross * cross <= 8.0 * sag * dot * dot
            }
        }
    }
}

/// True when direction `v` lies in the sector swept from direction `a` to direction `b`
/// (counter-clockwise when `ccw`), boundaries included. The arc's sweep is not stored: whether
/// it exceeds half a turn comes from its end directions (equal ones make a full turn).
fn in_sector(a: Vector, b: Vector, v: Vector, ccw: bool) -> bool {
    let (from, to) = if ccw { (a, b) } else { (b, a) };
    let more_than_half = from.cross(to) < 0.0 || (from.cross(to) == 0.0 && from.dot(to) > 0.0);
    in_turn(from, to, v, more_than_half)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::distance_from_segment;
    use proptest::prelude::*;

    fn arc_piece(center: Point, radius: f64, a0: f64, sweep: f64) -> Piece {
        let at = |a: f64| center + Vector::from_angle(a) * radius;
        Piece::Arc {
            center,
            radius,
            start: at(a0),
            end: at(a0 + sweep),
            ccw: sweep > 0.0,
        }
    }

    proptest! {
        /// The piece's distance is the segment's, for arcs of every sweep and either sense,
        /// and for lines.
        #[test]
        fn distance_is_the_segments(
            cx in -10.0..10.0f64, cy in -10.0..10.0f64, r in 0.1..20.0f64,
            a0 in -4.0..4.0f64, sweep in prop_oneof![-6.2..-0.01f64, 0.01..6.2f64],
            px in -40.0..40.0f64, py in -40.0..40.0f64,
        ) {
            let p = Point::new(px, py);
            let piece = arc_piece(Point::new(cx, cy), r, a0, sweep);
            let d = piece.distance(p);
            let expected = distance_from_segment(&piece.segment(), p);
            prop_assert!((d - expected).abs() <= 1e-9 * (1.0 + expected), "{d} vs {expected}");
            let line = Piece::Line { start: piece.start(), end: Point::new(cx, cy) };
            let expected = distance_from_segment(&line.segment(), p);
            prop_assert!((line.distance(p) - expected).abs() <= 1e-9 * (1.0 + expected));
        }
    }

    #[test]
    fn stepping_backwards_or_far_round_an_arc_is_refused() {
        let quarter = arc_piece(Point::ORIGIN, 10.0, 0.0, std::f64::consts::FRAC_PI_2);
        let at = |a: f64| Point::ORIGIN + Vector::from_angle(a) * 10.0;
        assert!(quarter.steps_forward(at(0.1), at(0.11), 1e-3));
        assert!(!quarter.steps_forward(at(0.11), at(0.1), 1e-3));
        // 0.2 rad on radius 10 strays 10 (1 − cos 0.1) = 0.05 from its chord.
        assert!(!quarter.steps_forward(at(0.1), at(0.3), 1e-3));
        assert!(quarter.steps_forward(at(0.1), at(0.3), 0.06));
        let clockwise = arc_piece(Point::ORIGIN, 10.0, 0.0, -1.0);
        assert!(clockwise.steps_forward(at(-0.1), at(-0.11), 1e-3));
        assert!(!clockwise.steps_forward(at(-0.11), at(-0.1), 1e-3));
    }
}
