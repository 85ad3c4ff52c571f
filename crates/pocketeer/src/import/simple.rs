//! Checking that a contour does not cross itself, and removing the slivers sloppy drawings make.
//!
//! A closed polyline whose last point misses its first by a few micrometres, joined by its
//! closing segment, crosses itself in a loop a few micrometres across. No tool can cut such a
//! loop, so a self-crossing whose smaller side fits in [`SLIVER_FACTOR`] join tolerances is
//! removed (and reported); any other self-crossing is refused with its coordinates.

use crate::geom::{intersect, Aabb, BoxIndex, Contour, Intersection, Line, Point, Segment, Tolerance};

/// A loop cut off by a self-crossing is a sliver when its extent is at most this many join
/// tolerances.
pub const SLIVER_FACTOR: f64 = 10.0;

/// Most slivers removed from one contour before giving up.
const MAX_REPAIRS: usize = 64;

/// A self-crossing found in a contour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Where the contour crosses itself.
    pub point: Point,
}

/// The contour without sliver loops, and where slivers were removed; or the first crossing
/// that is not a sliver.
pub fn make_simple(contour: &Contour, tol: &Tolerance) -> Result<(Contour, Vec<Point>), Crossing> {
    let mut c = contour.clone();
    let mut removed = Vec::new();
    while let Some((i, j, hit)) = first_crossing(&c, tol) {
        let Intersection::Point { point, ta, tb } = hit else {
            // The contour runs back over itself.
            let Intersection::Overlap { a, .. } = hit else {
                unreachable!()
            };
            return Err(Crossing {
                point: c.segments[i].point_at(0.5 * (a.0 + a.1)),
            });
        };
        let (inner, outer) = split_loops(&c, i, j, ta, tb, point);
        let small = |segs: &[Segment]| {
            let b = segs.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.bbox()));
            b.width().hypot(b.height()) <= SLIVER_FACTOR * tol.join
        };
        let keep = if small(&inner) && !outer.is_empty() {
            outer
        } else if small(&outer) && !inner.is_empty() {
            inner
        } else {
            return Err(Crossing { point });
        };
        if removed.len() >= MAX_REPAIRS {
            return Err(Crossing { point });
        }
        removed.push(point);
        c = Contour::new(keep);
    }
    Ok((c, removed))
}

/// The first pair of segments `(i, j)`, i < j, that meet other than at a shared joint.
fn first_crossing(c: &Contour, tol: &Tolerance) -> Option<(usize, usize, Intersection)> {
    let segs = &c.segments;
    let n = segs.len();
    if n < 2 {
        return None;
    }
    let boxes: Vec<Aabb> = segs.iter().map(|s| s.bbox().inflated(tol.eps)).collect();
    let index = BoxIndex::new(&boxes);
    let joint_radius = tol.join.max(100.0 * tol.eps);
    for (i, j) in index.pairs() {
        let mut joints = Vec::new();
        if i + 1 == j {
            joints.push(segs[j].start());
        }
        if (j + 1) % n == i {
            joints.push(segs[i].start());
        }
        for h in intersect(&segs[i], &segs[j], tol.eps).iter() {
            let at_joint = match h {
                Intersection::Point { point, .. } => joints.iter().any(|q| q.distance(point) <= joint_radius),
                Intersection::Overlap { .. } => false,
            };
            if !at_joint {
                return Some((i, j, h));
            }
        }
    }
    None
}

/// Cuts the contour at the crossing of segments `i` (at `ta`) and `j` (at `tb`): the loop
/// through the segments between them, and the loop through the rest.
fn split_loops(c: &Contour, i: usize, j: usize, ta: f64, tb: f64, p: Point) -> (Vec<Segment>, Vec<Segment>) {
    let segs = &c.segments;
    let piece =
        |s: &Segment, t0: f64, t1: f64, start: Option<Point>, end: Option<Point>| -> Option<Segment> {
            if (t1 - t0) * s.length() <= 0.0 {
                return None;
            }
            let mut out = s.sub(t0, t1);
            if let Segment::Line(l) = &mut out {
                *l = Line::new(start.unwrap_or(l.start), end.unwrap_or(l.end));
            }
            Some(out)
        };
    let mut inner = Vec::new();
    inner.extend(piece(&segs[i], ta, 1.0, Some(p), None));
    inner.extend(segs[i + 1..j].iter().copied());
    inner.extend(piece(&segs[j], 0.0, tb, None, Some(p)));
    let mut outer = Vec::new();
    outer.extend(piece(&segs[j], tb, 1.0, Some(p), None));
    outer.extend(segs[j + 1..].iter().copied());
    outer.extend(segs[..i].iter().copied());
    outer.extend(piece(&segs[i], 0.0, ta, None, Some(p)));
    (inner, outer)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(pts: &[(f64, f64)]) -> Contour {
        Contour::polygon(&pts.iter().map(|&(x, y)| Point::new(x, y)).collect::<Vec<_>>())
    }

    #[test]
    fn a_figure_eight_is_refused_at_its_crossing() {
        let c = polygon(&[(0.0, 0.0), (10.0, 10.0), (10.0, 0.0), (0.0, 10.0)]);
        let err = make_simple(&c, &Tolerance::default()).unwrap_err();
        assert!(err.point.distance(Point::new(5.0, 5.0)) < 1e-9);
    }

    #[test]
    fn a_closing_sliver_is_removed() {
        // The last point misses the first by 3 µm: the closing segment makes a tiny loop.
        let c = polygon(&[
            (100.0, 0.0),
            (80.0, 50.0),
            (20.0, 50.0),
            (0.0, 0.0),
            (100.0, 0.003),
        ]);
        let (simple, removed) = make_simple(&c, &Tolerance::default()).unwrap();
        assert_eq!(removed.len(), 1);
        assert!(first_crossing(&simple, &Tolerance::default()).is_none());
        let expected = 0.5 * (100.0 + 60.0) * 50.0;
        // The bottom edge now rises by 3 µm over 100 mm: 0.15 mm² less than the trapezoid.
        assert!((simple.signed_area().abs() - (expected - 0.15)).abs() < 1e-3);
    }

    #[test]
    fn a_simple_contour_is_unchanged() {
        let c = polygon(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        let (simple, removed) = make_simple(&c, &Tolerance::default()).unwrap();
        assert!(removed.is_empty());
        assert_eq!(simple, c);
    }
}
