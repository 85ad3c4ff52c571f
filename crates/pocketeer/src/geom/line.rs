//! Straight line segments.

use super::{Aabb, Point, Vector};
use serde::Serialize;

/// A straight segment from `start` to `end`, parameterised by t ∈ [0, 1].
///
/// ```
/// use pocketeer::geom::{Line, Point};
/// let l = Line::new(Point::new(0.0, 0.0), Point::new(0.0, 10.0));
/// assert_eq!(l.length(), 10.0);
/// assert_eq!(l.point_at(0.25), Point::new(0.0, 2.5));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Line {
    /// First point.
    pub start: Point,
    /// Last point.
    pub end: Point,
}

impl Line {
    /// The segment from `start` to `end`.
    pub const fn new(start: Point, end: Point) -> Line {
        Line { start, end }
    }

    /// `end - start`.
    pub fn delta(&self) -> Vector {
        self.end - self.start
    }

    /// Length.
    pub fn length(&self) -> f64 {
        self.delta().length()
    }

    /// The point at parameter `t` (0 = start, 1 = end).
    pub fn point_at(&self, t: f64) -> Point {
        if t == 1.0 {
            return self.end;
        }
        self.start.lerp(self.end, t)
    }

    /// Unit direction, or `None` for a zero-length line.
    pub fn direction(&self) -> Option<Vector> {
        self.delta().normalized()
    }

    /// Parameter of the orthogonal projection of `p` on the infinite line (not clamped).
    pub fn param_of(&self, p: Point) -> f64 {
        let d = self.delta();
        let l2 = d.length_sq();
        if l2 == 0.0 {
            0.0
        } else {
            (p - self.start).dot(d) / l2
        }
    }

    /// Signed distance of `p` from the infinite line, positive on the left.
    pub fn signed_distance(&self, p: Point) -> f64 {
        let d = self.delta();
        let l = d.length();
        if l == 0.0 {
            return self.start.distance(p);
        }
        d.cross(p - self.start) / l
    }

    /// Bounding box.
    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(self.start, self.end)
    }

    /// The same line run the other way.
    pub fn reversed(&self) -> Line {
        Line::new(self.end, self.start)
    }

    /// The two pieces on either side of parameter `t`.
    pub fn split_at(&self, t: f64) -> (Line, Line) {
        let p = self.point_at(t);
        (Line::new(self.start, p), Line::new(p, self.end))
    }

    /// The piece between parameters `t0` and `t1`.
    pub fn subsegment(&self, t0: f64, t1: f64) -> Line {
        Line::new(self.point_at(t0), self.point_at(t1))
    }
}
