//! Closest points and distances between points, lines and arcs.

use super::{intersect, Aabb, Arc, Line, Point, Segment, Vector};
use std::f64::consts::{PI, TAU};

/// Where `p` is nearest to `segments`: the index of the segment (the first of those equally
/// near), the parameter on it and the distance; `(0, 0.0, ∞)` for no segments.
///
/// ```
/// use pocketeer::geom::{nearest_on, Line, Point, Segment};
/// let l = |a: (f64, f64), b: (f64, f64)| Segment::Line(Line::new(Point::new(a.0, a.1), Point::new(b.0, b.1)));
/// let path = [l((0.0, 0.0), (10.0, 0.0)), l((10.0, 0.0), (10.0, 10.0))];
/// assert_eq!(nearest_on(&path, Point::new(12.0, 4.0)), (1, 0.4, 2.0));
/// ```
pub fn nearest_on(segments: &[Segment], p: Point) -> (usize, f64, f64) {
    let mut best = (0, 0.0, f64::INFINITY);
    for (k, s) in segments.iter().enumerate() {
        let d = distance_from_segment(s, p);
        if d < best.2 {
            best = (k, closest_param(s, p), d);
        }
    }
    best
}

/// Parameter of the point of `seg` nearest to `p`.
pub fn closest_param(seg: &Segment, p: Point) -> f64 {
    match seg {
        Segment::Line(l) => l.param_of(p).clamp(0.0, 1.0),
        Segment::Arc(a) => arc_closest_param(a, p),
    }
}

fn arc_closest_param(a: &Arc, p: Point) -> f64 {
    let v = p - a.center();
    if v.length_sq() == 0.0 {
        return 0.0; // every point of the arc is equally near the centre
    }
    let t = a.param_of_angle(v.angle());
    if (0.0..=1.0).contains(&t) {
        return t;
    }
    if a.start().distance_sq(p) <= a.end().distance_sq(p) {
        0.0
    } else {
        1.0
    }
}

/// The point of `seg` nearest to `p`.
///
/// ```
/// use pocketeer::geom::{closest_point, Line, Point, Segment};
/// let s = Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(10.0, 0.0)));
/// assert_eq!(closest_point(&s, Point::new(3.0, 5.0)), Point::new(3.0, 0.0));
/// assert_eq!(closest_point(&s, Point::new(-3.0, 5.0)), Point::new(0.0, 0.0));
/// ```
pub fn closest_point(seg: &Segment, p: Point) -> Point {
    match seg {
        Segment::Line(l) => l.point_at(l.param_of(p).clamp(0.0, 1.0)),
        Segment::Arc(a) => arc_closest_point(a, p),
    }
}

/// The point of `a` nearest to `p`: sign tests against its stored ends and a scaling, where
/// going through the parameter takes an angle and its sine and cosine.
fn arc_closest_point(a: &Arc, p: Point) -> Point {
    let v = p - a.center();
    let length = v.length();
    if length == 0.0 {
        return a.start(); // every point of the arc is equally near the centre
    }
    let (start, end) = (a.start(), a.end());
    if in_sweep(a.sweep(), start - a.center(), end - a.center(), v) {
        a.center() + v * (a.radius() / length)
    } else if start.distance_sq(p) <= end.distance_sq(p) {
        start
    } else {
        end
    }
}

/// Distance from the segment `seg` to the point `p`.
pub fn distance_from_segment(seg: &Segment, p: Point) -> f64 {
    match seg {
        Segment::Line(l) => line_point_distance(l, p),
        Segment::Arc(a) => arc_point_distance(a, p),
    }
}

/// Distance from `p` to the line segment `l`.
pub(crate) fn line_point_distance(l: &Line, p: Point) -> f64 {
    l.point_at(l.param_of(p).clamp(0.0, 1.0)).distance(p)
}

/// Distance from `p` to the arc `a`: sign tests against its stored ends instead of an angle.
fn arc_point_distance(a: &Arc, p: Point) -> f64 {
    let v = p - a.center();
    let (start, end) = (a.start(), a.end());
    if in_sweep(a.sweep(), start - a.center(), end - a.center(), v) {
        (v.length() - a.radius()).abs()
    } else {
        start.distance(p).min(end.distance(p))
    }
}

/// True when the direction `v` from an arc's centre lies within its sweep, the arc running
/// from direction `s` to direction `e` (counter-clockwise when `sweep` > 0): sign tests instead
/// of an angle. The centre itself (`v` zero) counts as within.
pub(crate) fn in_sweep(sweep: f64, s: Vector, e: Vector, v: Vector) -> bool {
    if sweep.abs() >= TAU {
        return true;
    }
    // Counter-clockwise from `from` to `to`.
    let (from, to) = if sweep > 0.0 { (s, e) } else { (e, s) };
    in_turn(from, to, v, sweep.abs() > PI)
}

/// True when the direction `v` lies within the turn counter-clockwise from direction `from`
/// to direction `to`, boundaries included; `more_than_half` says whether that turn exceeds
/// half a turn (the directions alone cannot tell a quarter turn from three quarters).
pub(crate) fn in_turn(from: Vector, to: Vector, v: Vector, more_than_half: bool) -> bool {
    if more_than_half {
        // The gap from `to` round to `from` is less than half a turn.
        !(to.cross(v) > 0.0 && v.cross(from) > 0.0)
    } else {
        from.cross(v) >= 0.0 && v.cross(to) >= 0.0
    }
}

/// A box holding the segment: a line's own, an arc's whole circle's (grown by a margin for ends
/// given off the circle by rounding), which holds the arc's box.
fn hull_box(s: &Segment) -> Aabb {
    match s {
        Segment::Line(l) => l.bbox(),
        Segment::Arc(a) => {
            let c = a.center();
            let r = a.radius() + 1e-9 * (a.radius() + c.x.abs() + c.y.abs() + 1.0);
            Aabb::from_points(Point::new(c.x - r, c.y - r), Point::new(c.x + r, c.y + r))
        }
    }
}

/// Distance between two segments, with the nearest point of each.
///
/// ```
/// use pocketeer::geom::{segment_distance, Arc, Line, Point, Segment};
/// let circle = Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 1.0));
/// let line = Segment::Line(Line::new(Point::new(-5.0, 3.0), Point::new(5.0, 3.0)));
/// let (d, on_circle, on_line) = segment_distance(&circle, &line, 1e-9);
/// assert!((d - 2.0).abs() < 1e-12);
/// assert!(on_circle.distance(Point::new(0.0, 1.0)) < 1e-12);
/// assert!(on_line.distance(Point::new(0.0, 3.0)) < 1e-12);
/// ```
pub fn segment_distance(a: &Segment, b: &Segment, eps: f64) -> (f64, Point, Point) {
    // Segments whose boxes stay apart by more than the tolerance cannot meet: the intersection
    // test, most of the cost between two arcs or a line and an arc, is left out (the loops of
    // a part and the ones inside it, measured against each other, are a stepover apart).
    // The circles' boxes first: an arc's own box costs a rounding and a loop, and most pairs
    // measured are apart by more than either circle.
    let may_meet = || {
        hull_box(a).inflated(4.0 * eps).intersects(&hull_box(b))
            && a.bbox().inflated(4.0 * eps).intersects(&b.bbox())
    };
    if let Some(i) = may_meet()
        .then(|| intersect(a, b, eps))
        .and_then(|x| x.iter().next())
    {
        let p = match i {
            intersect::Intersection::Point { point, .. } => point,
            intersect::Intersection::Overlap { a: span, .. } => a.point_at(span.0),
        };
        return (0.0, p, p);
    }
    let mut best = (f64::INFINITY, Point::ORIGIN, Point::ORIGIN);
    let mut consider = |pa: Point, pb: Point| {
        let d = pa.distance(pb);
        if d < best.0 {
            best = (d, pa, pb);
        }
    };
    // End points against the other segment.
    for p in [a.start(), a.end()] {
        consider(p, closest_point(b, p));
    }
    for p in [b.start(), b.end()] {
        consider(closest_point(a, p), p);
    }
    // Interior-to-interior minima lie on a normal through an arc's centre.
    for (x, y, flip) in [(a, b, false), (b, a, true)] {
        if let Segment::Arc(arc) = x {
            for q in interior_candidates(arc, y).into_iter().flatten() {
                let on_y = closest_point(y, q);
                if flip {
                    consider(on_y, q);
                } else {
                    consider(q, on_y);
                }
            }
        }
    }
    best
}

/// True when the segments `a` and `b` come nearer to each other than `r`: the same answer as
/// [`segment_distance`] `< r`, found mostly from the distances of `b`'s ends to `a`, which are
/// cheap. An end nearer than `r` answers yes; both ends farther than `r` by half of `b`'s
/// length answer no, every point of `b` being within that of one of its ends; only between
/// the two is the exact distance measured (a short move tested against the walls, as ways
/// round islands are searched, is decided by its ends almost always).
///
/// ```
/// use pocketeer::geom::{segments_nearer_than, Arc, Line, Point, Segment};
/// let circle = Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 1.0));
/// let line = Segment::Line(Line::new(Point::new(-5.0, 3.0), Point::new(5.0, 3.0)));
/// assert!(segments_nearer_than(&circle, &line, 2.1, 1e-9));
/// assert!(!segments_nearer_than(&circle, &line, 1.9, 1e-9));
/// ```
pub fn segments_nearer_than(a: &Segment, b: &Segment, r: f64, eps: f64) -> bool {
    let ends = distance_from_segment(a, b.start()).min(distance_from_segment(a, b.end()));
    if ends < r {
        return true;
    }
    if ends >= r + 0.5 * b.length() {
        return false;
    }
    segment_distance(a, b, eps).0 < r
}

/// Points of `arc` where an interior minimum of the distance to `other` can be (at most two).
fn interior_candidates(arc: &Arc, other: &Segment) -> [Option<Point>; 2] {
    let target = match other {
        // The foot of the centre on the line: the arc point towards it is nearest to the line.
        Segment::Line(l) => l.point_at(l.param_of(arc.center()).clamp(0.0, 1.0)),
        Segment::Arc(o) => o.center(),
    };
    let v = target - arc.center();
    let Some(u) = v.normalized() else {
        return [None, None];
    };
    // Sign tests against the arc's stored ends, not an angle (see `in_sweep`).
    let (s, e) = (arc.start() - arc.center(), arc.end() - arc.center());
    [u, -u].map(|d| in_sweep(arc.sweep(), s, e, d).then(|| arc.center() + d * arc.radius()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The circle's box holds the arc's box, for arcs of every sweep both ways, far from the
    /// origin too.
    #[test]
    fn hull_box_holds_the_arcs_box() {
        for k in 0..200 {
            let a0 = k as f64 * 0.37;
            let sweep = (k as f64 * 0.61).sin() * 6.3;
            let c = Point::new(1e3 * (k as f64).cos(), -50.0 + k as f64);
            let arc = Segment::Arc(Arc::new(c, 0.01 + k as f64 * 0.5, a0, sweep));
            let (hull, own) = (hull_box(&arc), arc.bbox());
            assert!(hull.contains(own.min) && hull.contains(own.max), "{arc:?}");
        }
    }

    /// The shortcut through the ends gives the exact distance's answer on lines and arcs of
    /// every kind against each other, at distances either side of each pair's.
    #[test]
    fn nearer_than_by_the_ends_agrees_with_the_exact_distance() {
        let mut segments = Vec::new();
        for k in 0..6 {
            let t = k as f64 * 0.9;
            let p = Point::new(t.cos() * 3.0, t.sin() * 2.0);
            segments.push(Segment::Line(Line::new(
                p,
                p + Vector::from_angle(t * 1.7) * (0.3 + k as f64),
            )));
            segments.push(Segment::Arc(Arc::new(
                p,
                0.5 + 0.4 * k as f64,
                t,
                0.4 + 1.1 * k as f64 - 2.5,
            )));
        }
        for a in &segments {
            for b in &segments {
                let d = segment_distance(a, b, 1e-9).0;
                for r in [0.5 * d, d - 1e-6, d + 1e-6, d + 0.3, 2.0 * d + 1.0] {
                    if r > 0.0 {
                        assert_eq!(segments_nearer_than(a, b, r, 1e-9), d < r, "{a:?} {b:?} r {r}");
                    }
                }
            }
        }
    }

    /// The sign tests agree with the angle test all round arcs of every kind of sweep, both
    /// ways.
    #[test]
    fn arc_distances_by_sign_tests_match_the_angle_test() {
        use std::f64::consts::{PI, TAU};
        let c = Point::new(3.0, -2.0);
        for &sweep in &[0.3, 1.5, PI, 4.0, 6.0, TAU, -0.3, -PI, -4.0, -TAU] {
            for k in 0..12 {
                let a = Arc::new(c, 2.0, k as f64 * 0.55 - 3.0, sweep);
                for j in 0..72 {
                    let t = j as f64 * TAU / 72.0 + 0.01;
                    for r in [0.0, 0.5, 2.0, 3.5] {
                        let p = c + Vector::from_angle(t) * r;
                        let v = p - c;
                        let want = if v.length_sq() > 0.0 && a.contains_angle(v.angle(), 0.0) {
                            (v.length() - a.radius()).abs()
                        } else {
                            a.start().distance(p).min(a.end().distance(p))
                        };
                        let got = distance_from_segment(&Segment::Arc(a), p);
                        assert!((got - want).abs() < 1e-12, "sweep {sweep} k {k} j {j} r {r}");
                    }
                }
            }
        }
    }
}
