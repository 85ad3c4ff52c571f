//! Checking that a contour does not cross itself, and removing the slivers sloppy drawings make.
//!
//! A closed polyline whose last point misses its first by a few micrometres, joined by its
//! closing segment, crosses itself in a loop a few micrometres across. No tool can cut such a
//! loop, so a self-crossing whose smaller side fits in [`SLIVER_FACTOR`] join tolerances is
//! removed (and reported); any other self-crossing is refused with its coordinates.

use crate::geom::{
    bbox_of, box_pairs_unsorted, distance_from_segment, intersect, Aabb, Contour, Intersection, Line, Point,
    Segment, Tolerance,
};
use std::f64::consts::PI;

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
            let b = bbox_of(segs);
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
    let mut first = None;
    visit_crossings(c, tol, |i, j, h| {
        first = Some((i, j, h));
        false
    });
    first
}

/// Every place where the contour meets itself other than at a shared joint: the segments
/// `(i, j)`, i < j, and how they meet.
pub(super) fn crossings(c: &Contour, tol: &Tolerance) -> Vec<(usize, usize, Intersection)> {
    let mut all = Vec::new();
    visit_crossings(c, tol, |i, j, h| {
        all.push((i, j, h));
        true
    });
    all
}

/// Calls `f` on each place where the contour meets itself other than at a shared joint,
/// while it returns true.
fn visit_crossings(c: &Contour, tol: &Tolerance, mut f: impl FnMut(usize, usize, Intersection) -> bool) {
    let segs = &c.segments;
    let n = segs.len();
    if n < 2 {
        return;
    }
    let boxes: Vec<Aabb> = segs.iter().map(|s| s.bbox().inflated(tol.eps)).collect();
    // Neighbours turning back tangentially at their joint meet again to within rounding up to
    // about sqrt(2 r eps) from it: hits that near, on curves that do not part, are the joint.
    let joint_radius = tol.join.max(tol.crossing());
    // The meetings are found among the pairs in the sweep's order, then put in the order of
    // the pairs (i, j): the first is the same whatever order the pairs came in, and sorting
    // the few meetings is cheaper than sorting the many pairs.
    let mut found: Vec<(usize, usize, Intersection)> = Vec::new();
    for (i, j) in box_pairs_unsorted(&boxes) {
        let meet_only_at_joint = (i + 1 == j && only_at_joint(&segs[i], &segs[j], 0.25 * tol.crossing()))
            || (i == 0 && j + 1 == n && only_at_joint(&segs[j], &segs[i], 0.25 * tol.crossing()));
        if meet_only_at_joint {
            continue;
        }
        for h in intersect(&segs[i], &segs[j], tol.eps).iter() {
            let at_joint = match h {
                // The contour runs back over itself.
                Intersection::Overlap { .. } => false,
                Intersection::Point { point, ta, tb } => {
                    // Where i ends at j's start, the stretches of each between the hit and that
                    // joint; where j ends at i's start (the contour's closing joint), the same
                    // the other way. (A contour of two elements has both.)
                    let ends_at_j = (i + 1 == j).then(|| (segs[j].start(), (ta, 1.0), (0.0, tb)));
                    let j_ends_at = ((j + 1) % n == i).then(|| (segs[i].start(), (0.0, ta), (tb, 1.0)));
                    ends_at_j.into_iter().chain(j_ends_at).any(|(joint, a, b)| {
                        joint.distance(point) <= joint_radius && !lobe_between(&segs[i], a, &segs[j], b, tol)
                    })
                }
            };
            if !at_joint {
                found.push((i, j, h));
            }
        }
    }
    // Stable: a pair's meetings stay in the order `intersect` gives them.
    found.sort_by_key(|&(i, j, _)| (i, j));
    for (i, j, h) in found {
        if !f(i, j, h) {
            return;
        }
    }
}

/// True when `a` and `b`, `b` starting where `a` ends, can meet nowhere but at that joint,
/// which [`visit_crossings`] passes over: two lines turning by less than a right angle, or two
/// arcs going on the same way (no fold back), each less than a half turn (so passing the
/// joint only at its end), whose circles' other meeting point, the joint mirrored in the line
/// of the centres, lies within `reach` of it (two circles meet twice at most). The joints of
/// a fitted curve or a long polyline are such pairs, one for every element: skipping them
/// spares an intersection each.
fn only_at_joint(a: &Segment, b: &Segment, reach: f64) -> bool {
    if let (Segment::Line(a), Segment::Line(b)) = (a, b) {
        // Two lines meet once, or lie on one line: turning by less than a right angle at
        // their joint (far from folding back), they share only it.
        return a.end == b.start && (a.end - a.start).dot(b.end - b.start) > 0.0;
    }
    let (Segment::Arc(a), Segment::Arc(b)) = (a, b) else {
        return false;
    };
    let joint = a.end();
    if joint != b.start() || a.sweep().abs() >= PI || b.sweep().abs() >= PI {
        return false;
    }
    let (ra, rb) = (joint - a.center(), joint - b.center());
    // The directions of travel at the joint are the radii turned by the sweeps' senses.
    let same_way = a.sweep().signum() * b.sweep().signum() * ra.dot(rb) > 0.0;
    let centres = b.center() - a.center();
    let apart = centres.length();
    same_way && apart > 0.0 && 2.0 * centres.cross(ra).abs() <= reach * apart
}

/// Whether neighbours `a` and `b`, meeting again at the far ends of their stretches `sa` and
/// `sb` from their shared joint, enclose a loop there: whether the stretches part by more than
/// two curves touching at the joint do through rounding. Two arcs micrometres across turning
/// back at a joint and crossing again 0.8 µm further on enclose a sliver to remove; a line
/// turning back along a tangent arc does not.
fn lobe_between(a: &Segment, sa: (f64, f64), b: &Segment, sb: (f64, f64), tol: &Tolerance) -> bool {
    let width = tol.crossing();
    let apart = |s: &Segment, (t0, t1): (f64, f64), other: &Segment| {
        (t1 - t0) * s.length() > width && distance_from_segment(other, s.point_at(0.5 * (t0 + t1))) > width
    };
    apart(a, sa, b) || apart(b, sb, a)
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
            let mut out = s.subsegment(t0, t1);
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
    use crate::geom::Arc;

    fn polygon(pts: &[(f64, f64)]) -> Contour {
        Contour::polygon(&pts.iter().map(|&(x, y)| Point::new(x, y)).collect::<Vec<_>>())
    }

    #[test]
    fn only_smooth_joints_of_short_arcs_are_passed_over_without_intersecting() {
        let p = Point::new;
        let reach = 1e-6;
        // A biarc's two arcs: tangent circles, going on the same way.
        let (j, q) = (p(10.0, 0.0), p(20.0, 0.0));
        let first = Segment::Arc(Arc::from_center(p(5.0, 0.0), p(5.0, -5.0), j, true));
        let second = Segment::Arc(Arc::from_center(p(15.0, 0.0), j, p(15.0, 5.0), false));
        assert!(only_at_joint(&first, &second, reach));
        // Folding back along a tangent circle: not passed over.
        let back = Segment::Arc(Arc::from_center(p(7.0, 0.0), j, p(7.0, -3.0), false));
        assert!(!only_at_joint(&first, &back, reach));
        // Circles crossing at the joint meet again elsewhere.
        let crossing = Segment::Arc(Arc::from_center(p(10.0, 5.0), j, q.midpoint(p(10.0, 5.0)), true));
        assert!(!only_at_joint(&first, &crossing, reach));
        // A half turn or more passes the joint's side again.
        let half = Segment::Arc(Arc::from_center(p(15.0, 0.0), j, q, false));
        assert!(!only_at_joint(&first, &half, reach));
        // A line after an arc is left to the intersection test; a line after a line, where
        // it turns by a right angle or more.
        let line = Segment::Line(Line::new(j, q));
        assert!(!only_at_joint(&first, &line, reach));
        let before = Segment::Line(Line::new(p(0.0, 0.0), j));
        assert!(only_at_joint(&before, &line, reach));
        assert!(only_at_joint(
            &before,
            &Segment::Line(Line::new(j, p(15.0, 8.0))),
            reach
        ));
        assert!(!only_at_joint(
            &before,
            &Segment::Line(Line::new(j, p(10.0, 7.0))),
            reach
        ));
        assert!(!only_at_joint(
            &before,
            &Segment::Line(Line::new(j, p(3.0, 0.001))),
            reach
        ));
    }

    #[test]
    fn a_figure_eight_is_refused_at_its_crossing() {
        let c = polygon(&[(0.0, 0.0), (10.0, 10.0), (10.0, 0.0), (0.0, 10.0)]);
        let err = make_simple(&c, &Tolerance::default()).unwrap_err();
        assert!(err.point.distance(Point::new(5.0, 5.0)) < 1e-9);
    }

    #[test]
    fn an_outline_touching_itself_is_refused_where_it_touches() {
        // Two squares sharing a corner drawn as one outline, and a notch whose tip touches
        // the opposite edge: two pockets (or a pocket and an island) meeting at a point, with
        // no inside defined there. Refused with the point, not cut into two loops.
        for (pts, at) in [
            (
                vec![
                    (0.0, 0.0),
                    (10.0, 0.0),
                    (10.0, 10.0),
                    (20.0, 10.0),
                    (20.0, 20.0),
                    (10.0, 20.0),
                    (10.0, 10.0),
                    (0.0, 10.0),
                ],
                Point::new(10.0, 10.0),
            ),
            (
                vec![
                    (0.0, 0.0),
                    (20.0, 0.0),
                    (20.0, 10.0),
                    (12.0, 10.0),
                    (10.0, 0.0),
                    (8.0, 10.0),
                    (0.0, 10.0),
                ],
                Point::new(10.0, 0.0),
            ),
        ] {
            let err = make_simple(&polygon(&pts), &Tolerance::default()).unwrap_err();
            assert!(err.point.distance(at) < 1e-9, "{err:?}");
        }
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
    fn arcs_turning_back_at_a_joint_and_crossing_again_within_the_join_tolerance_lose_the_sliver() {
        // Two arcs 0.008 and 0.006 mm in radius (as biarc fitting leaves them in a fine
        // drawing): they turn back by 173° at their joint and cross again 0.8 µm from it,
        // closer than the join tolerance, enclosing a lobe 2e-5 mm wide that must not be taken
        // for the joint.
        let a = Arc::new(
            Point::new(177.325, 177.33589054188832),
            0.007726479388300923,
            -2.2746039776237192,
            1.4076153016598592,
        );
        let b = Arc::new(
            Point::new(177.33329002490945, 177.325),
            0.005985337409446964,
            2.1527783834467584,
            1.9776285402851015,
        );
        let below = Point::new(177.33, 167.32);
        let c = Contour::new(vec![
            Segment::Arc(a),
            Segment::Arc(b),
            Segment::Line(Line::new(b.end(), below)),
            Segment::Line(Line::new(below, a.start())),
        ]);
        let tol = Tolerance::default();
        assert!(a.end().distance(b.start()) < 1e-12);
        let (simple, removed) = make_simple(&c, &tol).unwrap();
        assert_eq!(removed.len(), 1);
        assert!(
            removed[0].distance(Point::new(177.329347, 177.329503)) < 1e-6,
            "{removed:?}"
        );
        assert!(first_crossing(&simple, &tol).is_none());
        assert_eq!(simple.segments.len(), 4);
    }

    #[test]
    fn a_line_running_back_along_a_tangent_arc_meets_it_only_at_their_joint() {
        // A cusp: the arc leaves the line's end heading back along it, touching it there.
        let a = Arc::new(
            Point::new(10.0, 1.0),
            1.0,
            -std::f64::consts::FRAC_PI_2,
            -std::f64::consts::FRAC_PI_2,
        );
        let c = Contour::new(vec![
            Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(10.0, 0.0))),
            Segment::Arc(a),
            Segment::Line(Line::new(a.end(), Point::new(0.0, 0.0))),
        ]);
        let (simple, removed) = make_simple(&c, &Tolerance::default()).unwrap();
        assert!(removed.is_empty());
        assert_eq!(simple, c);
    }

    #[test]
    fn a_simple_contour_is_unchanged() {
        let c = polygon(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        let (simple, removed) = make_simple(&c, &Tolerance::default()).unwrap();
        assert!(removed.is_empty());
        assert_eq!(simple, c);
    }
}
