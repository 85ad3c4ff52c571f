//! Intersections with known answers: crossings, tangencies, overlaps and ends within eps.
use super::*;
use std::f64::consts::PI;

const EPS: f64 = 1e-9;

fn line(x0: f64, y0: f64, x1: f64, y1: f64) -> Segment {
    Segment::Line(Line::new(Point::new(x0, y0), Point::new(x1, y1)))
}

#[test]
fn vertical_and_horizontal_lines_cross() {
    let hits = intersect(&line(5.0, -1.0, 5.0, 1.0), &line(0.0, 0.0, 10.0, 0.0), EPS);
    assert_eq!(hits.len(), 1);
}

/// A point 3e-10 outside the circle of radius 10 about the origin at (10, 0), and the
/// direction 2.4e-4 rad off its tangent, heading in: a curve arriving there along it
/// ends within eps of the circle, and would cross it 1.25e-6 further on.
fn shallow_arrival() -> (Point, Point, Arc) {
    let alpha: f64 = 2.4e-4;
    let end = Point::new(10.0 + 3e-10, 0.0);
    let heading = Point::new(-alpha.sin(), alpha.cos());
    let circle = Arc::new(Point::new(0.0, 0.0), 10.0, -0.5, 1.0);
    (end, heading, circle)
}

/// `hits` (the arriving curve first) are one point: the arriving curve's end, on `circle`.
fn assert_meets_at_end(hits: Intersections, end: Point, circle: &Arc) {
    assert_eq!(hits.len(), 1, "{hits:?}");
    let Some(Intersection::Point { point, ta, tb }) = hits.iter().next() else {
        panic!("{hits:?}")
    };
    assert!(point.distance(end) < 1e-12 && ta == 1.0);
    assert!(circle.point_at(tb).distance(end) < 1e-9);
}

#[test]
fn a_line_ending_on_an_arc_at_a_shallow_angle_meets_it_at_its_end() {
    let (end, heading, circle) = shallow_arrival();
    let start = Point::new(end.x - 5.0 * heading.x, end.y - 5.0 * heading.y);
    let l = Line::new(start, end);
    assert!(start.distance(circle.center()) > 10.0);
    for hits in [
        line_arc(&l, &circle, EPS),
        intersect(&Segment::Arc(circle), &Segment::Line(l), EPS).swapped(),
    ] {
        assert_meets_at_end(hits, end, &circle);
    }
}

#[test]
fn an_arc_ending_on_an_arc_at_a_shallow_angle_meets_it_at_its_end() {
    let (end, heading, circle) = shallow_arrival();
    // Radius 20, turning clockwise (away from the circle) as it arrives.
    let centre = Point::new(end.x + 20.0 * heading.y, end.y - 20.0 * heading.x);
    let at_end = (end - centre).angle();
    let arriving = Arc::new(centre, 20.0, at_end + 0.2, -0.2);
    assert!(arriving.end().distance(end) < 1e-12);
    assert!(arriving.start().distance(circle.center()) > 10.0);
    for hits in [
        arc_arc(&arriving, &circle, EPS),
        arc_arc(&circle, &arriving, EPS).swapped(),
    ] {
        assert_meets_at_end(hits, end, &circle);
    }
}

#[test]
fn an_end_on_the_other_line_at_a_shallow_angle_meets_it_where_it_projects() {
    // The end of the rising line lies 3e-10 below the horizontal one (within eps); their
    // carriers cross 1.2e-6 beyond that end, too far to snap to (offsets of a triangle
    // 0.02 high and 164 long).
    let rising = line(244.17, -0.01, 162.25, 0.01 - 3e-10);
    let flat = line(80.33, 0.01, 244.17, 0.01);
    for (a, b, swapped) in [(&rising, &flat, false), (&flat, &rising, true)] {
        let v: Vec<_> = intersect(a, b, EPS).iter().collect();
        assert_eq!(v.len(), 1, "{v:?}");
        let Intersection::Point { point, ta, tb } = v[0] else {
            panic!("expected a point")
        };
        let (t_rising, t_flat) = if swapped { (tb, ta) } else { (ta, tb) };
        assert_eq!(t_rising, 1.0);
        assert!((t_flat - (162.25 - 80.33) / 163.84).abs() < 1e-12);
        assert!(point.distance(Point::new(162.25, 0.01)) < 1e-9);
    }
}

#[test]
fn collinear_lines_overlap_with_matching_parameters() {
    let hits = intersect(&line(0.0, 0.0, 10.0, 0.0), &line(12.0, 0.0, 4.0, 0.0), EPS);
    let v: Vec<_> = hits.iter().collect();
    assert_eq!(v.len(), 1);
    match v[0] {
        Intersection::Overlap { a, b } => {
            assert!((a.0 - 0.4).abs() < 1e-12 && (a.1 - 1.0).abs() < 1e-12);
            assert!((b.0 - 1.0).abs() < 1e-12 && (b.1 - 0.25).abs() < 1e-12);
        }
        _ => panic!("expected overlap"),
    }
}

#[test]
fn collinear_lines_touching_end_to_end_meet_in_a_point() {
    let hits = intersect(&line(0.0, 0.0, 1.0, 0.0), &line(1.0, 0.0, 2.0, 0.0), EPS);
    assert!(matches!(hits.iter().next(), Some(Intersection::Point { .. })));
    assert!(intersect(&line(0.0, 0.0, 1.0, 0.0), &line(1.1, 0.0, 2.0, 0.0), EPS).is_empty());
}

#[test]
fn tangent_line_touches_circle_once() {
    let c = Segment::Arc(Arc::circle(Point::ORIGIN, 2.0));
    let hits = intersect(&line(-5.0, 2.0, 5.0, 2.0), &c, EPS);
    assert_eq!(hits.len(), 1);
    let hits = intersect(&c, &line(-5.0, 1.0, 5.0, 1.0), EPS);
    assert_eq!(hits.len(), 2);
}

#[test]
fn arcs_tangent_inside_and_outside() {
    let a = Segment::Arc(Arc::circle(Point::ORIGIN, 2.0));
    let outside = Segment::Arc(Arc::circle(Point::new(3.0, 0.0), 1.0));
    let inside = Segment::Arc(Arc::circle(Point::new(1.0, 0.0), 1.0));
    assert_eq!(intersect(&a, &outside, EPS).len(), 1);
    assert_eq!(intersect(&a, &inside, EPS).len(), 1);
}

#[test]
fn cocircular_arcs_overlap_in_two_spans() {
    let a = Segment::Arc(Arc::new(Point::ORIGIN, 1.0, 0.0, 1.5 * PI));
    let b = Segment::Arc(Arc::new(Point::ORIGIN, 1.0, PI, 1.5 * PI));
    let spans = intersect(&a, &b, EPS)
        .iter()
        .filter(|i| matches!(i, Intersection::Overlap { .. }))
        .count();
    assert_eq!(spans, 2);
    let opposite = Segment::Arc(Arc::new(Point::ORIGIN, 1.0, PI / 2.0, -PI / 4.0));
    match intersect(&a, &opposite, EPS).iter().next() {
        Some(Intersection::Overlap { a, b }) => {
            assert!((a.0 - 1.0 / 6.0).abs() < 1e-12 && (a.1 - 1.0 / 3.0).abs() < 1e-12);
            assert!((b.0 - 1.0).abs() < 1e-12 && b.1.abs() < 1e-12);
        }
        other => panic!("expected overlap, got {other:?}"),
    }
}

#[test]
fn near_tangent_line_crossing_off_the_foot_is_found() {
    // A line passing 5e-10 inside a circle of radius 0.01 (within eps of tangency) crosses
    // it 3.2e-6 either side of the foot; the arc starts past the foot and holds only the
    // crossing on one side.
    let c = Arc::new(Point::new(0.0, 0.0), 0.01, 1e-4, 0.5);
    let x = 0.01 - 5e-10;
    let foot_y = -3.0e-6;
    let l = Line::new(Point::new(x, foot_y), Point::new(x, 1.0));
    let hits = line_arc(&l, &c, EPS);
    assert_eq!(hits.len(), 1);
    let first = hits.iter().next();
    match first {
        Some(Intersection::Point { point, .. }) => {
            assert!((point.distance(c.center()) - 0.01).abs() < 1e-12, "{point:?}");
            assert!((point.y - (1e-4f64 - x * x).sqrt()).abs() < 1e-9, "{point:?}");
        }
        other => panic!("expected a point, got {other:?}"),
    }
}

#[test]
fn circles_of_very_different_radii_meet_on_both() {
    // Radius 9178 against 0.01 at a shallow angle: the point must lie on the small circle
    // too, not 1e-6 off it.
    let big = Arc::new(
        Point::new(9177.91501953125, -56.630292968749984),
        9178.43385118847,
        3.0998,
        0.0312,
    );
    let small = Arc::new(Point::new(0.01, 40.96), 0.01, 3.14151, -0.0262);
    let hits = arc_arc(&big, &small, EPS);
    assert!(!hits.is_empty());
    for h in hits.iter() {
        if let Intersection::Point { point, .. } = h {
            assert!((point.distance(big.center()) - big.radius()).abs() < 1e-9);
            assert!((point.distance(small.center()) - small.radius()).abs() < 1e-12);
        }
    }
}
