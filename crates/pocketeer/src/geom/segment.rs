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
            Segment::Arc(a) => chord + a.radius() * a.radius() * sweep_less_sine(a.sweep()),
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
        let (s, c) = super::sin_cos(angle);
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

/// 1 / (2k + 3)! with the sign (−1)^k, for k = 0..=6: the series of θ − sin θ over θ³.
const SERIES: [f64; 7] = [
    1.0 / 6.0,
    -1.0 / 120.0,
    1.0 / 5040.0,
    -1.0 / 362_880.0,
    1.0 / 39_916_800.0,
    -1.0 / 6_227_020_800.0,
    1.0 / 1_307_674_368_000.0,
];

/// θ − sin θ, twice the area of the circular segment of a unit circle cut off by a sweep θ.
/// Below half a radian by its series (θ³/3! − θ⁵/5! + … to θ¹⁵; the first term left out is
/// below 1e-18 of the sum there): the difference of two nearly equal numbers loses the small
/// segments of short arcs to rounding, and the sine was a tenth of the time of summing the
/// area of a contour of arcs.
fn sweep_less_sine(theta: f64) -> f64 {
    if theta.abs() >= 0.5 {
        return theta - theta.sin();
    }
    let t2 = theta * theta;
    SERIES.iter().rev().fold(0.0, |sum, c| sum * t2 + c) * t2 * theta
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_series_meets_the_difference_where_it_takes_over() {
        for theta in [0.5f64 - 1e-15, -0.5 + 1e-15] {
            let direct = theta - theta.sin();
            assert!((sweep_less_sine(theta) - direct).abs() <= 1e-15 * direct.abs());
        }
        assert_eq!(sweep_less_sine(0.0), 0.0);
        // Far below rounding of the difference, the series keeps θ³/6.
        let tiny = 1e-6;
        assert!((sweep_less_sine(tiny) / (tiny * tiny * tiny / 6.0) - 1.0).abs() < 1e-12);
        assert_eq!(sweep_less_sine(-0.3), -sweep_less_sine(0.3));
    }

    #[test]
    fn a_circle_of_short_arcs_has_the_circles_area() {
        let n = 10_000;
        let step = std::f64::consts::TAU / n as f64;
        let arcs: Vec<Segment> = (0..n)
            .map(|k| Segment::Arc(Arc::new(Point::new(3.0, -2.0), 5.0, k as f64 * step, step)))
            .collect();
        let area = super::super::contour::signed_area(&arcs);
        let exact = std::f64::consts::PI * 25.0;
        assert!((area - exact).abs() < 1e-11 * exact, "{area} vs {exact}");
    }
}
