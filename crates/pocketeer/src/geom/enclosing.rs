//! The smallest circle enclosing a set of points, and the farthest a segment comes from a point:
//! what a tool standing at one spot reaches.

use super::{Point, Segment};

/// The smallest circle containing every point of `points`, as its centre and radius; None for
/// no points.
///
/// Welzl's incremental construction in a fixed pseudo-random order: expected linear time, and
/// the same circle for the same points (the smallest enclosing circle is unique).
///
/// ```
/// use pocketeer::geom::{enclosing_circle, Point};
/// let p = Point::new;
/// let (c, r) = enclosing_circle(&[p(0.0, 0.0), p(4.0, 0.0), p(2.0, 1.0)]).unwrap();
/// assert!((c.x - 2.0).abs() < 1e-12 && c.y.abs() < 1e-12);
/// assert!((r - 2.0).abs() < 1e-12);
/// ```
pub fn enclosing_circle(points: &[Point]) -> Option<(Point, f64)> {
    let mut p = points.to_vec();
    shuffle(&mut p);
    let first = *p.first()?;
    let (mut c, mut r) = (first, 0.0);
    let outside = |c: Point, r: f64, q: Point| c.distance(q) > r * (1.0 + 1e-12) + 1e-12;
    for i in 1..p.len() {
        if !outside(c, r, p[i]) {
            continue;
        }
        (c, r) = (p[i], 0.0);
        for j in 0..i {
            if !outside(c, r, p[j]) {
                continue;
            }
            (c, r) = (p[i].midpoint(p[j]), 0.5 * p[i].distance(p[j]));
            for k in 0..j {
                if outside(c, r, p[k]) {
                    (c, r) = through_three(p[i], p[j], p[k]);
                }
            }
        }
    }
    Some((c, r))
}

/// The smallest circle through or around `a`, `b` and `c` with all three on or inside it, when
/// `a` and `b` must be on it: the circle through all three, or for (nearly) collinear points
/// the one on the pair farthest apart.
fn through_three(a: Point, b: Point, c: Point) -> (Point, f64) {
    let (u, v) = (b - a, c - a);
    let d = 2.0 * u.cross(v);
    let scale = u.length_sq().max(v.length_sq());
    if d.abs() <= 1e-14 * scale {
        let pairs = [(a, b), (a, c), (b, c)];
        let (p, q) = pairs
            .into_iter()
            .max_by(|x, y| x.0.distance_sq(x.1).total_cmp(&y.0.distance_sq(y.1)))
            .unwrap_or((a, b));
        return (p.midpoint(q), 0.5 * p.distance(q));
    }
    let (lu, lv) = (u.length_sq(), v.length_sq());
    let x = (v.y * lu - u.y * lv) / d;
    let y = (u.x * lv - v.x * lu) / d;
    let centre = Point::new(a.x + x, a.y + y);
    (centre, centre.distance(a))
}

/// Shuffles `p` with a fixed xorshift sequence: Welzl's construction needs an order unrelated
/// to the points' (points along a loop in turn would make it quadratic or worse), but the same
/// one every run.
fn shuffle(p: &mut [Point]) {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    for i in (1..p.len()).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        let j = (s % (i as u64 + 1)) as usize;
        p.swap(i, j);
    }
}

/// The largest distance from `p` to a point of `seg`: at one of its ends, or for an arc at the
/// point of its circle opposite `p` when the arc passes there.
///
/// ```
/// use pocketeer::geom::{farthest_from_segment, Arc, Point, Segment};
/// let half = Segment::Arc(Arc::new(Point::new(0.0, 0.0), 1.0, 0.0, std::f64::consts::PI));
/// // From below the centre, the farthest point is the top of the half circle.
/// assert!((farthest_from_segment(&half, Point::new(0.0, -1.0)) - 2.0).abs() < 1e-12);
/// ```
pub fn farthest_from_segment(seg: &Segment, p: Point) -> f64 {
    let ends = seg.start().distance(p).max(seg.end().distance(p));
    match seg {
        Segment::Line(_) => ends,
        Segment::Arc(a) => {
            let away = a.center() - p;
            if away.length() == 0.0 {
                a.radius()
            } else if a.contains_angle(away.angle(), 0.0) {
                ends.max(away.length() + a.radius())
            } else {
                ends
            }
        }
    }
}

/// Points on `segments` whose smallest enclosing circle is close to the segments' own: every
/// end, and three points inside each arc (an arc of a quarter turn bulges at most 2 % of its
/// radius beyond the chords between them).
pub fn outline_points(segments: &[Segment]) -> Vec<Point> {
    let mut out = Vec::with_capacity(2 * segments.len() + 1);
    for s in segments {
        out.push(s.start());
        if let Segment::Arc(a) = s {
            out.extend([0.25, 0.5, 0.75].map(|t| a.point_at(t)));
        }
    }
    out.extend(segments.last().map(Segment::end));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Line};
    use proptest::prelude::*;

    #[test]
    fn the_circle_of_collinear_points_spans_the_outer_two() {
        let p = Point::new;
        let (c, r) = enclosing_circle(&[p(1.0, 1.0), p(3.0, 3.0), p(2.0, 2.0), p(0.0, 0.0)]).unwrap();
        assert!(c.distance(p(1.5, 1.5)) < 1e-12);
        assert!((r - 1.5 * 2f64.sqrt()).abs() < 1e-12);
        assert!(enclosing_circle(&[]).is_none());
    }

    #[test]
    fn an_arc_is_farthest_opposite_the_point_only_where_it_passes() {
        let p = Point::new;
        let quarter = Segment::Arc(Arc::new(p(0.0, 0.0), 2.0, 0.0, std::f64::consts::FRAC_PI_2));
        // From (-1, -1) the opposite point (45°) is on the arc: 2 + √2.
        assert!((farthest_from_segment(&quarter, p(-1.0, -1.0)) - (2.0 + 2f64.sqrt())).abs() < 1e-12);
        // From (1, 1) the opposite point (225°) is not: the ends are farthest.
        let ends = p(2.0, 0.0).distance(p(1.0, 1.0));
        assert!((farthest_from_segment(&quarter, p(1.0, 1.0)) - ends).abs() < 1e-12);
        let line = Segment::Line(Line::new(p(0.0, 0.0), p(3.0, 4.0)));
        assert_eq!(farthest_from_segment(&line, p(0.0, 0.0)), 5.0);
    }

    proptest! {
        #[test]
        fn the_circle_holds_every_point_and_touches_two(
            pts in prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 1..40)
        ) {
            let pts: Vec<Point> = pts.into_iter().map(|(x, y)| Point::new(x, y)).collect();
            let (c, r) = enclosing_circle(&pts).unwrap();
            let eps = 1e-9 * (1.0 + r);
            for q in &pts {
                prop_assert!(c.distance(*q) <= r + eps);
            }
            // The smallest circle has at least two points on it (one when all coincide).
            let on = pts.iter().filter(|q| (c.distance(**q) - r).abs() <= eps).count();
            prop_assert!(on >= 2 || r <= eps);
        }
    }
}
