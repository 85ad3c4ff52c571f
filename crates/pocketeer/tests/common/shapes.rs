//! Pockets for tests: rectangles, circles, stars, and random rectangles with round islands.

use pocketeer::geom::Pocket;
use pocketeer::geom::{Arc, Contour, Line, Point, Segment};
use proptest::prelude::*;

/// The polygon through `pts`.
pub fn polygon(pts: &[(f64, f64)]) -> Contour {
    Contour::polygon(&pts.iter().map(|&(x, y)| Point::new(x, y)).collect::<Vec<_>>())
}

/// The mirror image of `s` in the y axis (x → -x): its sense flips.
pub fn mirror_segment(s: &Segment) -> Segment {
    match s {
        Segment::Line(l) => Segment::Line(Line::new(
            Point::new(-l.start.x, l.start.y),
            Point::new(-l.end.x, l.end.y),
        )),
        Segment::Arc(a) => Segment::Arc(Arc::new(
            Point::new(-a.center().x, a.center().y),
            a.radius(),
            std::f64::consts::PI - a.start_angle(),
            -a.sweep(),
        )),
    }
}

/// `c` mirrored in the y axis, then reversed to keep its sense.
pub fn mirrored(c: &Contour) -> Contour {
    Contour::new(c.segments.iter().map(mirror_segment).collect()).reversed()
}

pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Contour {
    let p = Point::new;
    Contour::polygon(&[p(x0, y0), p(x1, y0), p(x1, y1), p(x0, y1)])
}

pub fn circle_cw(cx: f64, cy: f64, r: f64) -> Contour {
    Contour::new(vec![Segment::Arc(pocketeer::geom::Arc::new(
        Point::new(cx, cy),
        r,
        0.0,
        -std::f64::consts::TAU,
    ))])
}

pub fn star(points: usize, outer: f64, inner: f64) -> Contour {
    let pts: Vec<Point> = (0..2 * points)
        .map(|k| {
            let a = std::f64::consts::PI * k as f64 / points as f64 + 0.1;
            let r = if k % 2 == 0 { outer } else { inner };
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect();
    Contour::polygon(&pts)
}

/// A rectangle with up to four round islands that do not overlap each other or the wall.
pub fn pocket_strategy() -> impl Strategy<Value = Pocket> {
    (
        30.0..90.0f64,
        25.0..60.0f64,
        prop::collection::vec((0.05..0.95f64, 0.05..0.95f64, 1.0..8.0f64), 0..4),
    )
        .prop_map(|(w, h, islands)| {
            let mut placed: Vec<(f64, f64, f64)> = Vec::new();
            for (fx, fy, r) in islands {
                let (x, y) = (fx * w, fy * h);
                let clear_of_wall = x - r > 0.5 && y - r > 0.5 && w - x - r > 0.5 && h - y - r > 0.5;
                let clear_of_others = placed.iter().all(|&(a, b, s)| (x - a).hypot(y - b) > r + s + 0.5);
                if clear_of_wall && clear_of_others {
                    placed.push((x, y, r));
                }
            }
            Pocket {
                boundary: rect(0.0, 0.0, w, h),
                islands: placed.iter().map(|&(x, y, r)| circle_cw(x, y, r)).collect(),
            }
        })
}
