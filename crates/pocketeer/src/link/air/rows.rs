//! Where a row of a grid meets the points near a segment: what lists a move in the cells its
//! sweep reaches, one row at a time instead of one distance for each cell.

use crate::geom::{Aabb, Point, Segment};

/// The spans of the horizontal line at height `y` that hold every point of it within `d` of
/// `s` (whose box is `bbox`): at most two intervals of x, lowest first. For a line they hold
/// only such points (the points near a line make a convex set, met in one interval); for an arc
/// they are those of the ring of its circle within `d`, within `d` of the arc's box, and may
/// hold points farther from the arc than `d` (beyond its ends). A line along x from 0 to 10 is
/// met 3 above it within 5 from -4 to 14.
pub fn row_spans(s: &Segment, bbox: &Aabb, y: f64, d: f64) -> [Option<(f64, f64)>; 2] {
    match s {
        Segment::Line(l) => [line_span(l.start, l.end, y, d), None],
        Segment::Arc(a) => {
            let (c, radius) = (a.center(), a.radius());
            let dy = y - c.y;
            let Some(outer) = half_chord(radius + d, dy) else {
                return [None, None];
            };
            let clip = |(lo, hi): (f64, f64)| {
                let (lo, hi) = (lo.max(bbox.min.x - d), hi.min(bbox.max.x + d));
                (lo <= hi).then_some((lo, hi))
            };
            match half_chord(radius - d, dy).filter(|&w| w > 0.0) {
                Some(inner) => [clip((c.x - outer, c.x - inner)), clip((c.x + inner, c.x + outer))],
                None => [clip((c.x - outer, c.x + outer)), None],
            }
        }
    }
}

/// Half the chord that the line at `dy` from a circle's centre cuts from a circle of radius
/// `radius`, or None where it misses it (or the radius is negative).
fn half_chord(radius: f64, dy: f64) -> Option<f64> {
    (radius >= 0.0 && dy.abs() <= radius).then(|| (radius * radius - dy * dy).max(0.0).sqrt())
}

/// The span of the horizontal line at height `y` within `d` of the segment from `a` to `b`:
/// the union of what the discs round its ends and the band along it between them cut from the
/// line (one interval, the set being convex).
fn line_span(a: Point, b: Point, y: f64, d: f64) -> Option<(f64, f64)> {
    let disc = |p: Point| half_chord(d, y - p.y).map(|w| (p.x - w, p.x + w));
    let mut span = union(disc(a), disc(b));
    let v = b - a;
    let length = v.length();
    if length > 0.0 {
        let (u, n) = (v * (1.0 / length), v.perp() * (1.0 / length));
        // Along: (x - a.x) u.x + (y - a.y) u.y in [0, length]; across: the same with n in
        // [-d, d]. Each is an interval of x, or all of it or none where x does not count.
        let band = linear_range(u.x, (y - a.y) * u.y - a.x * u.x, 0.0, length)
            .zip(linear_range(n.x, (y - a.y) * n.y - a.x * n.x, -d, d))
            .and_then(|((l0, h0), (l1, h1))| {
                let (lo, hi) = (l0.max(l1), h0.min(h1));
                (lo <= hi).then_some((lo, hi))
            });
        span = union(span, band);
    }
    span
}

/// The x for which `k x + c` lies in `[lo, hi]`: an interval, all of them (infinite bounds) or
/// none.
fn linear_range(k: f64, c: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    if k == 0.0 {
        return (lo <= c && c <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (x0, x1) = ((lo - c) / k, (hi - c) / k);
    Some((x0.min(x1), x0.max(x1)))
}

/// The least interval holding both (each may be missing).
fn union(a: Option<(f64, f64)>, b: Option<(f64, f64)>) -> Option<(f64, f64)> {
    match (a, b) {
        (Some((l0, h0)), Some((l1, h1))) => Some((l0.min(l1), h0.max(h1))),
        (a, None) => a,
        (None, b) => b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{distance_from_segment, Arc, Line};

    fn inside(spans: &[Option<(f64, f64)>; 2], x: f64) -> bool {
        spans.iter().flatten().any(|&(lo, hi)| lo <= x && x <= hi)
    }

    /// The one span of a line's row, which must be within rounding of `expected`.
    fn one_span(s: &Segment, y: f64, d: f64) -> Option<(f64, f64)> {
        let [span, None] = row_spans(s, &s.bbox(), y, d) else {
            panic!("a line's row is met in one span")
        };
        span
    }

    fn close(span: Option<(f64, f64)>, (lo, hi): (f64, f64)) -> bool {
        span.is_some_and(|(a, b)| (a - lo).abs() < 1e-12 && (b - hi).abs() < 1e-12)
    }

    #[test]
    fn a_line_is_met_in_its_capsule() {
        let s = Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(10.0, 0.0)));
        assert!(close(one_span(&s, 3.0, 5.0), (-4.0, 14.0)));
        assert_eq!(one_span(&s, 5.5, 5.0), None);
        // Upright: the row meets the band across it, and the ends' discs beyond.
        let s = Segment::Line(Line::new(Point::new(2.0, 0.0), Point::new(2.0, 10.0)));
        assert!(close(one_span(&s, 5.0, 1.0), (1.0, 3.0)));
        assert!(close(one_span(&s, 10.6, 1.0), (1.2, 2.8)));
    }

    #[test]
    fn a_ring_is_met_in_two_spans() {
        let s = Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 10.0));
        let [Some((a0, a1)), Some((b0, b1))] = row_spans(&s, &s.bbox(), 0.0, 1.0) else {
            panic!("two spans")
        };
        assert!((a0 + 11.0).abs() < 1e-12 && (a1 + 9.0).abs() < 1e-12);
        assert!((b0 - 9.0).abs() < 1e-12 && (b1 - 11.0).abs() < 1e-12);
        assert_eq!(row_spans(&s, &s.bbox(), 11.5, 1.0), [None, None]);
    }

    proptest::proptest! {
        /// Every point of a row within the distance of a segment lies in its spans, and for a
        /// line every point of the spans does.
        #[test]
        fn the_spans_hold_every_point_near_the_segment(
            p in proptest::array::uniform4(-20.0..20.0f64),
            arc in proptest::bool::ANY, sweep in -7.0..7.0f64,
            d in 0.1..6.0f64, y in -30.0..30.0f64,
        ) {
            let s = if arc {
                Segment::Arc(Arc::new(Point::new(p[0], p[1]), p[2].abs() + 0.01, p[3], sweep))
            } else {
                Segment::Line(Line::new(Point::new(p[0], p[1]), Point::new(p[2], p[3])))
            };
            let spans = row_spans(&s, &s.bbox(), y, d);
            for k in 0..=400 {
                let x = -40.0 + 80.0 * k as f64 / 400.0;
                let near = distance_from_segment(&s, Point::new(x, y));
                if near <= d * (1.0 - 1e-9) {
                    proptest::prop_assert!(inside(&spans, x), "{x} at {near}: {spans:?}");
                }
                if !arc && near > d * (1.0 + 1e-9) {
                    proptest::prop_assert!(!inside(&spans, x), "{x} at {near}: {spans:?}");
                }
            }
        }
    }
}
