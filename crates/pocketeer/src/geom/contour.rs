//! Closed contours of lines and arcs: area, orientation, point containment.

use super::{Aabb, Point, Segment, Vector};
use std::f64::consts::TAU;

/// A closed chain of segments, each starting where the previous one ends and the last ending
/// where the first starts.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Segment};
/// use std::f64::consts::PI;
/// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(3.0, 4.0), 2.0))]);
/// assert!((disc.signed_area() - 4.0 * PI).abs() < 1e-12);
/// assert!(disc.contains(Point::new(3.5, 4.5)));
/// assert!((disc.reversed().signed_area() + 4.0 * PI).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Contour {
    /// The segments, in order of travel.
    pub segments: Vec<Segment>,
}

impl Contour {
    /// A contour from segments already joined end to start.
    pub fn new(segments: Vec<Segment>) -> Contour {
        Contour { segments }
    }

    /// Exact signed area: positive for counter-clockwise contours. Arcs count with their
    /// circular segment, not their chord.
    pub fn signed_area(&self) -> f64 {
        signed_area(&self.segments)
    }

    /// True when the contour runs counter-clockwise.
    pub fn is_ccw(&self) -> bool {
        self.signed_area() > 0.0
    }

    /// The contour run the other way.
    pub fn reversed(&self) -> Contour {
        Contour::new(self.segments.iter().rev().map(Segment::reversed).collect())
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        self.segments.iter().map(Segment::length).sum()
    }

    /// Bounding box.
    pub fn bbox(&self) -> Aabb {
        self.segments.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.bbox()))
    }

    /// Winding number of the contour around `p` (for `p` not on the contour).
    pub fn winding_number(&self, p: Point) -> i32 {
        winding_number(&self.segments, p)
    }

    /// True when `p` lies inside (non-zero winding). Undefined for `p` on the contour.
    pub fn contains(&self, p: Point) -> bool {
        self.winding_number(p) != 0
    }
}

/// Exact signed area enclosed by closed chain `segments` (positive when counter-clockwise).
///
/// Computed about the first start point, so that translating a part far from the origin
/// does not cost precision.
pub fn signed_area(segments: &[Segment]) -> f64 {
    let Some(first) = segments.first() else { return 0.0 };
    let o = first.start();
    0.5 * segments.iter().map(|s| s.area_term(o)).sum::<f64>()
}

/// Angle swept by `seg` as seen from `p`, signed counter-clockwise.
fn swept_angle(seg: &Segment, p: Point) -> f64 {
    let (a, b) = (seg.start() - p, seg.end() - p);
    let chord_angle = a.cross(b).atan2(a.dot(b));
    match seg {
        Segment::Line(_) => chord_angle,
        Segment::Arc(arc) => {
            // The arc and its chord enclose a circular segment; if p lies in it, the arc winds
            // once more around p than the chord does.
            let inside_circle = (p - arc.center).length_sq() < arc.radius * arc.radius;
            if !inside_circle {
                return chord_angle;
            }
            let chord: Vector = seg.end() - seg.start();
            let in_segment = if arc.is_full_circle() || chord.length_sq() == 0.0 {
                true
            } else {
                let side_p = chord.cross(p - seg.start());
                let side_arc = chord.cross(arc.point_at(0.5) - seg.start());
                side_p * side_arc > 0.0
            };
            if in_segment {
                chord_angle + TAU * arc.sweep.signum()
            } else {
                chord_angle
            }
        }
    }
}

/// Winding number of closed chain `segments` around `p`.
pub fn winding_number(segments: &[Segment], p: Point) -> i32 {
    let total: f64 = segments.iter().map(|s| swept_angle(s, p)).sum();
    (total / TAU).round() as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Line};
    use std::f64::consts::PI;

    fn slot() -> Contour {
        // A 10 x 4 rectangle whose right side is a half circle bulging outwards: area 40 + 2π.
        let p = |x, y| Point::new(x, y);
        Contour::new(vec![
            Segment::Line(Line::new(p(0.0, 0.0), p(10.0, 0.0))),
            Segment::Arc(Arc::new(p(10.0, 2.0), 2.0, -PI / 2.0, PI)),
            Segment::Line(Line::new(p(10.0, 4.0), p(0.0, 4.0))),
            Segment::Line(Line::new(p(0.0, 4.0), p(0.0, 0.0))),
        ])
    }

    #[test]
    fn area_counts_arc_segments() {
        assert!((slot().signed_area() - (40.0 + 2.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn winding_sees_points_in_the_arc_bulge() {
        let c = slot();
        assert!(c.contains(Point::new(11.5, 2.0)));
        assert!(!c.contains(Point::new(12.5, 2.0)));
        assert!(c.contains(Point::new(5.0, 2.0)));
        assert_eq!(c.reversed().winding_number(Point::new(11.0, 2.0)), -1);
    }
}
