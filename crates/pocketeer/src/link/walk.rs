//! Turning loops and clean-up paths into walks: where to start, which way round, and the
//! moves along them.

use crate::clear::Path;
use crate::geom::{closest_param, distance_from_segment, Point, Segment};
use crate::toolpath::{Feed, Point3, Toolpath};

/// The segments of `path` as the tool follows them: closed paths start at their point nearest
/// to `from` and are reversed when `reverse` (conventional milling: the plan's loops run with
/// the material on their right, as climb milling with an M3 spindle goes); open paths start
/// at their end nearer to `from`.
pub fn walk_from(path: &Path, from: Point, reverse: bool, eps: f64) -> Vec<Segment> {
    let oriented: Vec<Segment> = if reverse {
        path.segments.iter().rev().map(Segment::reversed).collect()
    } else {
        path.segments.clone()
    };
    if !path.closed {
        let (first, last) = (oriented[0].start(), oriented[oriented.len() - 1].end());
        return if from.distance(last) < from.distance(first) {
            oriented.iter().rev().map(Segment::reversed).collect()
        } else {
            oriented
        };
    }
    let (mut best, mut best_d) = (0, f64::INFINITY);
    for (i, s) in oriented.iter().enumerate() {
        let d = distance_from_segment(s, from);
        if d < best_d {
            (best, best_d) = (i, d);
        }
    }
    let t = closest_param(&oriented[best], from);
    let n = oriented.len();
    let mut out = Vec::with_capacity(n + 1);
    let (head, tail) = oriented[best].split_at(t);
    if tail.length() > eps {
        out.push(tail);
    }
    out.extend((1..n).map(|k| oriented[(best + k) % n]));
    if head.length() > eps {
        out.push(head);
    }
    if out.is_empty() {
        out.push(oriented[best]);
    }
    out
}

/// How far `p` is from where the walk of `path` from `p` starts (see [`walk_from`]): its
/// nearest point when it is closed, its nearer end when it is open. The next path is chosen
/// by this: an open clean-up path that passes near the tool but ends far from it is not
/// near (on the 90 % rectangle one along a wall, 80 mm from either end where it passed the
/// tool, was taken for the nearest and reached by a retract and a new entry).
pub fn distance_to_start(path: &Path, p: Point) -> f64 {
    if !path.closed {
        let (first, last) = (
            path.segments[0].start(),
            path.segments[path.segments.len() - 1].end(),
        );
        return p.distance(first).min(p.distance(last));
    }
    path.segments
        .iter()
        .map(|s| distance_from_segment(s, p))
        .fold(f64::INFINITY, f64::min)
}

/// Total length of `segments`.
pub fn length(segments: &[Segment]) -> f64 {
    segments.iter().map(Segment::length).sum()
}

/// Follows `segments` at height `z` with the cutting feed.
pub fn follow(path: &mut Toolpath, segments: &[Segment], z: f64) {
    for s in segments {
        emit(path, s, z, Feed::Cut);
    }
}

/// One segment as a move ending at height `z`.
pub fn emit(path: &mut Toolpath, s: &Segment, z: f64, feed: Feed) {
    match s {
        Segment::Line(l) => path.line(Point3::at(l.end, z), feed),
        Segment::Arc(a) => path.arc_to(Point3::at(a.end(), z), a.center(), a.sweep(), feed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Contour;

    fn square() -> Path {
        let p = Point::new;
        Path {
            segments: Contour::polygon(&[p(0.0, 0.0), p(10.0, 0.0), p(10.0, 10.0), p(0.0, 10.0)]).segments,
            closed: true,
        }
    }

    #[test]
    fn closed_walks_start_nearest_and_close() {
        let w = walk_from(&square(), Point::new(4.0, -3.0), false, 1e-12);
        assert_eq!(w[0].start(), Point::new(4.0, 0.0));
        assert_eq!(w[w.len() - 1].end(), Point::new(4.0, 0.0));
        assert_eq!(w.len(), 5);
        assert!((length(&w) - 40.0).abs() < 1e-12);
        let r = walk_from(&square(), Point::new(4.0, -3.0), true, 1e-12);
        assert_eq!(r[0].start(), Point::new(4.0, 0.0));
        assert_eq!(r[0].end(), Point::new(0.0, 0.0));
    }

    #[test]
    fn open_walks_start_at_the_nearer_end() {
        let mut open = square();
        open.segments.pop();
        open.closed = false;
        let w = walk_from(&open, Point::new(-1.0, 9.0), false, 1e-12);
        assert_eq!(w[0].start(), Point::new(0.0, 10.0));
        assert_eq!(w[w.len() - 1].end(), Point::new(0.0, 0.0));
    }
}
