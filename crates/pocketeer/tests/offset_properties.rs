//! Offsets of random pockets with random islands keep their invariants, and their areas agree
//! with an independent implementation (cavalier_contours, a dev-dependency oracle only).

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use pocketeer::geom::{distance_from_segment, Arc, Contour, Line, Point, Segment, Tolerance, Vector};
use pocketeer::geom::{Pocket, PreparedPocket};
use pocketeer::import::self_crossing::make_simple;
use pocketeer::offset::{loops_meet, offset_pocket, verify_offset};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// A star-shaped pocket (radii at evenly spread angles, some edges bulged a little) with
/// circular islands kept clear of the wall and of each other.
fn pocket() -> impl Strategy<Value = Pocket> {
    (
        prop::collection::vec((30.0..60.0f64, -0.15..0.15f64, any::<bool>()), 5..14),
        prop::collection::vec((-25.0..25.0f64, -25.0..25.0f64, 1.0..6.0f64), 0..5),
    )
        .prop_map(|(spokes, holes)| {
            let n = spokes.len();
            let pts: Vec<Point> = spokes
                .iter()
                .enumerate()
                .map(|(k, &(r, _, _))| {
                    Point::new(0.0, 0.0) + Vector::from_angle(k as f64 / n as f64 * TAU) * r
                })
                .collect();
            let segs = (0..n)
                .map(|k| {
                    let (a, b) = (pts[k], pts[(k + 1) % n]);
                    let (_, bulge, curved) = spokes[k];
                    match Arc::from_bulge(a, b, bulge) {
                        Some(arc) if curved => Segment::Arc(arc),
                        _ => Segment::Line(Line::new(a, b)),
                    }
                })
                .collect();
            let boundary = Contour::new(segs);
            let mut islands: Vec<(Point, f64)> = Vec::new();
            for (x, y, r) in holes {
                let c = Point::new(x, y);
                let clear_of_wall = boundary
                    .segments
                    .iter()
                    .all(|s| distance_from_segment(s, c) > r + 1.0);
                let clear_of_others = islands.iter().all(|&(o, ro)| o.distance(c) > r + ro + 1.0);
                if clear_of_wall && clear_of_others && boundary.contains(c) {
                    islands.push((c, r));
                }
            }
            let islands = islands
                .into_iter()
                .map(|(c, r)| Contour::new(vec![Segment::Arc(Arc::new(c, r, 0.3, -TAU))]))
                .collect();
            Pocket { boundary, islands }
        })
}

/// The contour as the oracle's polyline. An arc flatter than a bulge of 1e-6 (its sagitta a
/// millionth of its chord, under 0.1 µm here) goes as a line: the oracle offsets such an arc,
/// radius 7e7 mm, 0.18 mm² off on a pocket of 2 000 mm² (ours agrees with the same pocket drawn
/// with a line there to 5e-5 mm², the difference of the two outlines).
fn to_pline(c: &Contour) -> Polyline<f64> {
    let mut p = Polyline::new_closed();
    for s in &c.segments {
        let start = s.start();
        let bulge = match s {
            Segment::Arc(a) if a.bulge().abs() >= 1e-6 => a.bulge(),
            _ => 0.0,
        };
        p.add(start.x, start.y, bulge);
    }
    p
}

/// The oracle's area of the pocket eroded by `d`.
fn cavalier_area(pocket: &Pocket, d: f64) -> f64 {
    let mut plines = vec![to_pline(&pocket.boundary)];
    for i in &pocket.islands {
        // A full circle as two half arcs.
        let Segment::Arc(a) = i.segments[0] else {
            unreachable!()
        };
        let halves = Contour::new(vec![
            Segment::Arc(a.subsegment(0.0, 0.5)),
            Segment::Arc(a.subsegment(0.5, 1.0)),
        ]);
        plines.push(to_pline(&halves));
    }
    let shape = Shape::from_plines(plines);
    let out = shape.parallel_offset(d, &ShapeOffsetOptions::default());
    out.ccw_plines.iter().map(|p| p.polyline.area()).sum::<f64>()
        + out.cw_plines.iter().map(|p| p.polyline.area()).sum::<f64>()
}

/// The loops `b` (moved back by `shift`) are the loops `a`: as many, and every point of each
/// within `within` of the other set, both ways.
fn same_loops(a: &[Contour], b: &[Contour], shift: Vector, within: f64) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.len(), b.len());
    let back: Vec<Segment> = b
        .iter()
        .flat_map(|l| l.segments.iter().map(|s| s.translated(-shift)))
        .collect();
    let fwd: Vec<Segment> = a.iter().flat_map(|l| l.segments.iter().copied()).collect();
    for (from, to) in [(&fwd, &back), (&back, &fwd)] {
        for s in from.iter() {
            for k in 0..=4 {
                let q = s.point_at(k as f64 / 4.0);
                let dist = to
                    .iter()
                    .map(|o| distance_from_segment(o, q))
                    .fold(f64::INFINITY, f64::min);
                prop_assert!(dist <= within, "{:?} is {} from the other result", q, dist);
            }
        }
    }
    Ok(())
}

fn area(loops: &[Contour]) -> f64 {
    loops.iter().map(Contour::signed_area).sum()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn offsets_are_closed_simple_at_distance_d_and_inside(p in pocket(), d in 0.3..12.0f64) {
        let tol = Tolerance::default();
        let loops = offset_pocket(&p, d, &tol).unwrap();
        verify_offset(&p, &loops, d).map_err(|f| TestCaseError::fail(f.to_string()))?;
        prop_assert!(loops_meet(&loops).is_none(), "{:?}", loops_meet(&loops));
        for l in &loops {
            let (_, slivers) = make_simple(l, &Tolerance { join: 1e-9, ..tol }).map_err(|x| TestCaseError::fail(format!("loop crosses itself at {:?}", x.point)))?;
            prop_assert!(slivers.is_empty());
        }
    }

    #[test]
    fn areas_agree_with_an_independent_implementation(p in pocket(), d in 0.3..12.0f64) {
        // The oracle is wrong on nearly straight arcs: see
        // a_nearly_straight_arc_offsets_outside_its_chords_offset.
        prop_assume!(p.boundary.segments.iter().all(|s| !matches!(s, Segment::Arc(a) if a.radius() > 1e5)));
        let ours = area(&offset_pocket(&p, d, &Tolerance::default()).unwrap());
        let theirs = cavalier_area(&p, d);
        prop_assert!((ours - theirs).abs() <= 1e-6 * (1.0 + theirs.abs()), "ours {} theirs {}", ours, theirs);
    }

    #[test]
    fn start_point_and_translation_do_not_matter(p in pocket(), d in 0.3..12.0f64, shift in 1usize..20) {
        let tol = Tolerance::for_scale(2e5, 0.001);
        let base = offset_pocket(&p, d, &tol).unwrap();
        let n = p.boundary.segments.len();
        let mut rotated = p.boundary.segments.clone();
        rotated.rotate_left(shift % n);
        let turned = Pocket { boundary: Contour::new(rotated), islands: p.islands.clone() };
        // The engine joins ends closer than ten epsilons (2e-5 mm at this scale): results may
        // differ by that much, and by no more.
        let within = 20.0 * tol.eps;
        same_loops(&base, &offset_pocket(&turned, d, &tol).unwrap(), Vector::new(0.0, 0.0), within)?;
        let far = Vector::new(1e5, -1e5);
        let moved = Pocket {
            boundary: Contour::new(p.boundary.segments.iter().map(|s| s.translated(far)).collect()),
            islands: p.islands.iter().map(|i| Contour::new(i.segments.iter().map(|s| s.translated(far)).collect())).collect(),
        };
        same_loops(&base, &offset_pocket(&moved, d, &tol).unwrap(), far, within)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Just short of and just beyond the deepest point of the pocket, where a deeper level is
    /// proven empty before it is split (see `offset/clip.rs`), the offset from the sources of
    /// a smaller one is the offset alone: as many loops, the same area; none beyond.
    #[test]
    fn the_levels_round_the_deepest_point_are_the_offsets_alone(
        p in pocket(),
        at in 0.2..0.9f64,
        side in prop::bool::ANY,
        off in prop_oneof![Just(1e-4), Just(1e-2)],
    ) {
        let tol = Tolerance::default();
        let region = PreparedPocket::new(&p);
        let deepest = region.largest_inscribed_radius(&tol).unwrap();
        let d = deepest * if side { 1.0 + off } else { 1.0 - off };
        let (_, sources) = region.offset_with_sources(at * deepest, &tol, None).unwrap();
        let (fast, _) = region.offset_with_sources(d, &tol, Some(&sources)).unwrap();
        let alone = region.offset(d, &tol).unwrap();
        prop_assert_eq!(fast.len(), alone.len());
        prop_assert_eq!(fast.is_empty(), side);
        prop_assert!((area(&fast) - area(&alone)).abs() <= 1e-9 * (1.0 + area(&alone).abs()));
    }
}

/// The input on which the oracle disagreed (found in CI): a pentagon whose first edge is an arc
/// of radius 7e7 mm (bulge 1.2e-7). Eroded by 0.3, it has the area of the same pentagon with a
/// line there, to the 5e-5 mm² by which the two outlines differ.
#[test]
fn a_flat_arc_of_radius_7e7_offsets_as_the_line_it_nearly_is() {
    let arc = Arc::new(
        Point::new(-58388027.53140587, -42421385.12791423),
        72171595.37145887,
        0.6283182863897366,
        4.886564437994333e-7,
    );
    let rest = [
        Segment::Arc(Arc::new(
            Point::new(-32.737472209801155, 100.75557926883741),
            83.55213907151393,
            -1.0439895162856028,
            -0.4252950903006291,
        )),
        Segment::Line(Line::new(
            Point::new(-24.27050983124842, 17.633557568774197),
            Point::new(-24.270509831248425, -17.63355756877419),
        )),
        Segment::Line(Line::new(
            Point::new(-24.270509831248425, -17.63355756877419),
            Point::new(9.270509831248416, -28.53169548885461),
        )),
        Segment::Line(Line::new(
            Point::new(9.270509831248416, -28.53169548885461),
            Point::new(30.0, 0.0),
        )),
    ];
    let eroded = |first: Segment| {
        let mut segs = vec![first];
        segs.extend(rest);
        let p = Pocket {
            boundary: Contour::new(segs),
            islands: vec![],
        };
        let loops = offset_pocket(&p, 0.3, &Tolerance::default()).unwrap();
        verify_offset(&p, &loops, 0.3).unwrap();
        (area(&loops), p.boundary.signed_area())
    };
    let (with_arc, outline_arc) = eroded(Segment::Arc(arc));
    let (with_line, outline_line) = eroded(Segment::Line(Line::new(arc.start(), arc.end())));
    assert!((outline_arc - outline_line).abs() < 1e-4);
    assert!(
        (with_arc - with_line).abs() <= 2.0 * (outline_arc - outline_line).abs() + 1e-9,
        "{with_arc} {with_line}"
    );
}

/// A pocket whose side is an arc of radius 5.4 km (sagitta 53 nm), with an island, found by
/// the oracle test: eroded by 9.33 mm, cavalier_contours gives 651.34145 mm², less than the
/// 651.34208 mm² both give with that side a straight line, though the arc bulges out of the
/// pocket and the eroded region can only grow. Ours gives more than with the line, and lies at
/// the exact distance; the oracle test leaves arcs above 100 m radius out.
#[test]
fn a_nearly_straight_arc_offsets_outside_its_chords_offset() {
    let p = Point::new;
    let (a, b) = (p(9.270509831248416, -28.53169548885461), p(47.7700653477934, 0.0));
    let arc = Arc::from_center(p(-3222699.0217079427, 4348608.407705695), a, b, true);
    let corners = [
        b,
        p(9.270509831248424, 28.531695488854606),
        p(-24.27050983124842, 17.633557568774197),
        p(-24.270509831248425, -17.63355756877419),
        a,
    ];
    let pocket = |last: Segment| {
        let mut segments: Vec<Segment> = corners
            .windows(2)
            .map(|w| Segment::Line(Line::new(w[0], w[1])))
            .collect();
        segments.push(last);
        let island = Arc::new(
            p(17.82087088007886, 6.46316436156112),
            5.82833840188394,
            0.3,
            -TAU,
        );
        Pocket {
            boundary: Contour::new(segments),
            islands: vec![Contour::new(vec![Segment::Arc(island)])],
        }
    };
    let (curved, straight) = (pocket(Segment::Arc(arc)), pocket(Segment::Line(Line::new(a, b))));
    assert!(curved.area() > straight.area());
    let d = 9.332269473255527;
    let tol = Tolerance::default();
    let eroded = |p: &Pocket| {
        let loops = offset_pocket(p, d, &tol).unwrap();
        verify_offset(p, &loops, d).unwrap();
        area(&loops)
    };
    let (with_arc, with_line) = (eroded(&curved), eroded(&straight));
    assert!(with_arc > with_line, "{with_arc} {with_line}");
    // With the line, the oracle agrees to the last digit.
    assert!((with_line - cavalier_area(&straight, d)).abs() < 1e-9);
}
