//! Property tests of the geometry kernel's invariants.

use pocketeer::geom::{
    distance_from_segment, intersect, segment_distance, signed_area, Arc, Intersection, Line, Point, Segment,
    SegmentIndex, Tolerance, Vector,
};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

fn eps() -> f64 {
    Tolerance::for_scale(300.0, 0.001).eps
}

fn coord() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

fn point() -> impl Strategy<Value = Point> {
    (coord(), coord()).prop_map(|(x, y)| Point::new(x, y))
}

fn line() -> impl Strategy<Value = Segment> {
    (point(), point())
        .prop_filter("non-degenerate", |(a, b)| a.distance(*b) > 1e-3)
        .prop_map(|(a, b)| Segment::Line(Line::new(a, b)))
}

fn sweep() -> impl Strategy<Value = f64> {
    prop_oneof![0.01..TAU, -TAU..-0.01, Just(TAU), Just(-TAU)]
}

fn arc() -> impl Strategy<Value = Segment> {
    (point(), 0.05..100.0f64, -PI..PI, sweep()).prop_map(|(c, r, a, s)| Segment::Arc(Arc::new(c, r, a, s)))
}

fn segment() -> impl Strategy<Value = Segment> {
    prop_oneof![line(), arc()]
}

/// Pairs that meet often in the special ways: collinear lines, co-circular arcs, tangent circles,
/// and a second segment through a point of the first.
fn pair() -> impl Strategy<Value = (Segment, Segment)> {
    prop_oneof![
        (segment(), segment()),
        (point(), point(), -0.5..1.5f64, -0.5..1.5f64)
            .prop_filter("long", |(a, b, _, _)| a.distance(*b) > 1e-2)
            .prop_map(|(a, b, s, t)| {
                let l = Line::new(a, b);
                (
                    Segment::Line(l),
                    Segment::Line(Line::new(l.point_at(s), l.point_at(t))),
                )
            }),
        (point(), 0.05..100.0f64, -PI..PI, sweep(), -PI..PI, sweep()).prop_map(|(c, r, a0, s0, a1, s1)| {
            (
                Segment::Arc(Arc::new(c, r, a0, s0)),
                Segment::Arc(Arc::new(c, r, a1, s1)),
            )
        }),
        (point(), 0.05..50.0f64, 0.05..50.0f64, -PI..PI, any::<bool>()).prop_map(
            |(c, r1, r2, dir, outside)| {
                let d = if outside { r1 + r2 } else { (r1 - r2).abs() };
                let c2 = c + Vector::from_angle(dir) * d;
                (
                    Segment::Arc(Arc::circle(c, r1)),
                    Segment::Arc(Arc::new(c2, r2, dir + 1.0, -TAU)),
                )
            }
        ),
        (segment(), 0.0..1.0f64, -PI..PI, 0.1..50.0f64, 0.0..1.0f64).prop_map(|(s, t, dir, len, k)| {
            let p = s.point_at(t);
            let d = Vector::from_angle(dir) * len;
            (s, Segment::Line(Line::new(p - d * k, p + d * (1.0 - k))))
        }),
    ]
}

/// A closed chain through the points: to each next point a line, or an arc with the given bulge;
/// steps shorter than `min_len` are skipped.
fn closed_chain(pts: &[(Point, f64, bool)], min_len: f64) -> Vec<Segment> {
    let n = pts.len();
    (0..n)
        .filter_map(|i| {
            let (a, bulge, is_arc) = pts[i];
            let b = pts[(i + 1) % n].0;
            if a.distance(b) < min_len {
                return None;
            }
            Some(match (is_arc, Arc::from_bulge(a, b, bulge)) {
                (true, Some(arc)) => Segment::Arc(arc),
                _ => Segment::Line(Line::new(a, b)),
            })
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn intersections_lie_on_both_segments((a, b) in pair()) {
        let e = eps();
        for i in intersect(&a, &b, e).iter() {
            match i {
                Intersection::Point { point, ta, tb } => {
                    prop_assert!(distance_from_segment(&a, point) <= 4.0 * e, "{:?} off a by {}", point, distance_from_segment(&a, point));
                    prop_assert!(distance_from_segment(&b, point) <= 4.0 * e, "{:?} off b by {}", point, distance_from_segment(&b, point));
                    prop_assert!(a.point_at(ta).distance(point) <= 4.0 * e);
                    prop_assert!(b.point_at(tb).distance(point) <= 4.0 * e);
                }
                Intersection::Overlap { a: ra, b: rb } => {
                    prop_assert!(ra.0 < ra.1);
                    for (ta, tb) in [(ra.0, rb.0), (ra.1, rb.1), (0.5 * (ra.0 + ra.1), 0.5 * (rb.0 + rb.1))] {
                        let p = a.point_at(ta);
                        prop_assert!(distance_from_segment(&b, p) <= 4.0 * e);
                        prop_assert!(b.point_at(tb).distance(p) <= 4.0 * e, "{:?} vs {:?}", b.point_at(tb), p);
                    }
                }
            }
        }
    }

    #[test]
    fn intersection_is_symmetric_in_count((a, b) in pair()) {
        let e = eps();
        prop_assert_eq!(intersect(&a, &b, e).len(), intersect(&b, &a, e).len());
    }

    #[test]
    fn distance_is_symmetric_and_zero_at_intersections((a, b) in pair()) {
        let e = eps();
        let (dab, pa, pb) = segment_distance(&a, &b, e);
        let (dba, _, _) = segment_distance(&b, &a, e);
        prop_assert!((dab - dba).abs() <= 1e-9 * (1.0 + dab));
        if !intersect(&a, &b, e).is_empty() {
            prop_assert_eq!(dab, 0.0);
        }
        // The reported points are on their segments and as far apart as reported.
        prop_assert!(distance_from_segment(&a, pa) <= 4.0 * e);
        prop_assert!(distance_from_segment(&b, pb) <= 4.0 * e);
        prop_assert!((pa.distance(pb) - dab).abs() <= 4.0 * e);
        // No pair of sampled points is nearer than the distance.
        for i in 0..=16 {
            let p = a.point_at(i as f64 / 16.0);
            prop_assert!(distance_from_segment(&b, p) >= dab - 1e-9 * (1.0 + dab));
        }
    }

    #[test]
    fn split_pieces_join_back(s in segment(), t in 0.0..1.0f64) {
        let (x, y) = s.split_at(t);
        let tol = 1e-9;
        prop_assert!(x.start().distance(s.start()) <= tol);
        prop_assert!(x.end().distance(y.start()) <= tol);
        prop_assert!(y.end().distance(s.end()) <= tol);
        prop_assert!((x.length() + y.length() - s.length()).abs() <= 1e-9 * (1.0 + s.length()));
        let (u, v) = s.split_at_point(s.point_at(t));
        prop_assert!(u.end().distance(s.point_at(t)) <= tol && v.start().distance(s.point_at(t)) <= tol);
    }

    #[test]
    fn area_flips_on_reversal_and_survives_rotation_and_translation(
        pts in prop::collection::vec((point(), -2.0..2.0f64, any::<bool>()), 3..12),
        angle in -PI..PI,
    ) {
        let segs = closed_chain(&pts, 1e-6);
        prop_assume!(!segs.is_empty());
        let area = signed_area(&segs);
        let scale = 1.0 + segs.iter().map(|s| s.bbox().magnitude()).fold(0.0, f64::max).powi(2);
        let reversed: Vec<Segment> = segs.iter().rev().map(Segment::reversed).collect();
        prop_assert!((signed_area(&reversed) + area).abs() <= 1e-9 * scale);
        let rotated: Vec<Segment> = segs.iter().map(|s| s.rotated(angle)).collect();
        prop_assert!((signed_area(&rotated) - area).abs() <= 1e-9 * scale);
        let far = Vector::new(1e5, -1e5);
        let moved: Vec<Segment> = segs.iter().map(|s| s.translated(far)).collect();
        prop_assert!((signed_area(&moved) - area).abs() <= 1e-9 * scale);
    }
}

/// Winding number of a closed chain of straight lines by the classic crossing count.
fn polygon_winding(pts: &[Point], p: Point) -> i32 {
    let mut w = 0;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        let side = (b - a).cross(p - a);
        if a.y <= p.y && b.y > p.y && side > 0.0 {
            w += 1;
        } else if b.y <= p.y && a.y > p.y && side < 0.0 {
            w -= 1;
        }
    }
    w
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn winding_number_agrees_with_a_fine_polygon(
        pts in prop::collection::vec((point(), -3.0..3.0f64, any::<bool>()), 2..8),
        probes in prop::collection::vec(point(), 20),
    ) {
        let segs = closed_chain(&pts, 1e-3);
        prop_assume!(segs.len() >= 2);
        let mut poly = Vec::new();
        for s in &segs {
            let k = if matches!(s, Segment::Arc(_)) { 4000 } else { 1 };
            for i in 0..k {
                poly.push(s.point_at(i as f64 / k as f64));
            }
        }
        for p in probes {
            // Points on (or within the flattening error of) the curve have no defined winding.
            if segs.iter().any(|s| distance_from_segment(s, p) < 1e-2) {
                continue;
            }
            prop_assert_eq!(pocketeer::geom::winding_number(&segs, p), polygon_winding(&poly, p), "at {:?}", p);
        }
    }
}

/// Short axis-aligned and slanted segments, many of them, like the floor moves of a program.
fn short_segment() -> impl Strategy<Value = Segment> {
    (point(), 0.0..8.0f64, 0..3u8).prop_map(|(a, len, kind)| {
        let b = match kind {
            0 => a + Vector::new(len, 0.0),
            1 => a + Vector::new(0.0, len),
            _ => a + Vector::new(0.6 * len, -0.8 * len),
        };
        Segment::Line(Line::new(a, b))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The index's nearest distance is the brute-force minimum (the best-first search stops
    /// only at an exact distance no box bound undercuts).
    #[test]
    fn index_distance_is_the_brute_force_minimum(
        segs in prop::collection::vec(prop_oneof![4 => short_segment(), 1 => arc()], 1..300),
        queries in prop::collection::vec(point(), 1..40),
    ) {
        let index = SegmentIndex::new(&segs);
        for q in queries {
            let brute = segs.iter().map(|s| distance_from_segment(s, q)).fold(f64::INFINITY, f64::min);
            prop_assert!((index.distance(q) - brute).abs() <= 1e-9, "{} vs {}", index.distance(q), brute);
        }
    }

    /// `any_within` says yes exactly when some segment is nearer than the radius (away from
    /// the boundary case, where rounding may decide either way).
    #[test]
    fn index_any_within_is_the_brute_force_answer(
        segs in prop::collection::vec(prop_oneof![4 => short_segment(), 1 => arc()], 1..300),
        queries in prop::collection::vec((point(), 0.01f64..20.0), 1..40),
    ) {
        let index = SegmentIndex::new(&segs);
        for (q, r) in queries {
            let brute = segs.iter().map(|s| distance_from_segment(s, q)).fold(f64::INFINITY, f64::min);
            if (brute - r).abs() > 1e-9 {
                prop_assert_eq!(index.any_within(q, r), brute < r, "at {:?} r {}: nearest {}", q, r, brute);
            }
        }
    }
}
