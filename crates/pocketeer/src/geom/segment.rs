//! One type over lines and arcs.

use super::{Aabb, Arc, Line, Point, Vector};
use serde::Serialize;

/// A line or a circular arc: the only two kinds of element from drawing to G-code.
///
/// ```
/// use pocketeer::geom::{Arc, Line, Point, Segment};
/// use std::f64::consts::PI;
/// let l = Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(4.0, 0.0)));
/// let a = Segment::Arc(Arc::new(Point::new(0.0, 0.0), 1.0, 0.0, PI));
/// assert_eq!(l.length(), 4.0);
/// assert!((a.length() - PI).abs() < 1e-12);
/// assert_eq!(l.reversed().start(), Point::new(4.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Segment {
    /// A straight line.
    Line(Line),
    /// A circular arc.
    Arc(Arc),
}

impl From<Line> for Segment {
    fn from(l: Line) -> Self {
        Segment::Line(l)
    }
}
impl From<Arc> for Segment {
    fn from(a: Arc) -> Self {
        Segment::Arc(a)
    }
}

impl Segment {
    /// First point.
    pub fn start(&self) -> Point {
        match self {
            Segment::Line(l) => l.start,
            Segment::Arc(a) => a.start(),
        }
    }

    /// Last point.
    pub fn end(&self) -> Point {
        match self {
            Segment::Line(l) => l.end,
            Segment::Arc(a) => a.end(),
        }
    }

    /// Length.
    pub fn length(&self) -> f64 {
        match self {
            Segment::Line(l) => l.length(),
            Segment::Arc(a) => a.length(),
        }
    }

    /// The point at parameter `t` ∈ [0, 1].
    pub fn point_at(&self, t: f64) -> Point {
        match self {
            Segment::Line(l) => l.point_at(t),
            Segment::Arc(a) => a.point_at(t),
        }
    }

    /// Unit tangent in the direction of travel at `t` (the zero vector for a zero-length line).
    pub fn tangent_at(&self, t: f64) -> Vector {
        match self {
            Segment::Line(l) => l.direction().unwrap_or_default(),
            Segment::Arc(a) => a.tangent_at(t),
        }
    }

    /// Bounding box.
    pub fn bbox(&self) -> Aabb {
        match self {
            Segment::Line(l) => l.bbox(),
            Segment::Arc(a) => a.bbox(),
        }
    }

    /// The same segment run the other way.
    pub fn reversed(&self) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(l.reversed()),
            Segment::Arc(a) => Segment::Arc(a.reversed()),
        }
    }

    /// The piece between parameters `t0` and `t1`.
    pub fn subsegment(&self, t0: f64, t1: f64) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(l.subsegment(t0, t1)),
            Segment::Arc(a) => Segment::Arc(a.subsegment(t0, t1)),
        }
    }

    /// The two pieces on either side of parameter `t`.
    pub fn split_at(&self, t: f64) -> (Segment, Segment) {
        (self.subsegment(0.0, t), self.subsegment(t, 1.0))
    }

    /// The two pieces on either side of the point of the segment nearest to `p`.
    pub fn split_at_point(&self, p: Point) -> (Segment, Segment) {
        let t = super::distance::closest_param(self, p);
        self.split_at(t)
    }

    /// Parameter of `p` along the segment, continued past the ends (see [`Arc::param_of`]).
    pub fn param_of(&self, p: Point) -> f64 {
        match self {
            Segment::Line(l) => l.param_of(p),
            Segment::Arc(a) => a.param_of(p),
        }
    }

    /// Twice the signed area between the segment and the point `o` (the segment's contribution to
    /// a closed contour's area when every segment uses the same `o`).
    pub fn area_term(&self, o: Point) -> f64 {
        let chord = (self.start() - o).cross(self.end() - o);
        match self {
            Segment::Line(_) => chord,
            Segment::Arc(a) => chord + a.radius() * a.radius() * (a.sweep() - a.sweep().sin()),
        }
    }

    /// True when every coordinate and size of the segment is a finite number.
    pub fn is_finite(&self) -> bool {
        match self {
            Segment::Line(l) => l.start.is_finite() && l.end.is_finite(),
            Segment::Arc(a) => {
                a.center().is_finite()
                    && a.radius().is_finite()
                    && a.start_angle().is_finite()
                    && a.sweep().is_finite()
            }
        }
    }

    /// The segment moved by `v`.
    pub fn translated(&self, v: Vector) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(Line::new(l.start + v, l.end + v)),
            Segment::Arc(a) => Segment::Arc(Arc::new(a.center() + v, a.radius(), a.start_angle(), a.sweep())),
        }
    }

    /// The segment turned by `angle` radians about the origin.
    pub fn rotated(&self, angle: f64) -> Segment {
        let (s, c) = angle.sin_cos();
        let rot = |p: Point| Point::new(c * p.x - s * p.y, s * p.x + c * p.y);
        match self {
            Segment::Line(l) => Segment::Line(Line::new(rot(l.start), rot(l.end))),
            Segment::Arc(a) => Segment::Arc(Arc::new(
                rot(a.center()),
                a.radius(),
                a.start_angle() + angle,
                a.sweep(),
            )),
        }
    }
}
