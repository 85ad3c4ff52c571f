//! Inputs the `offset` fuzz target (fuzz/src/bin/offset.rs) found, built the same way: a
//! bulged polygon in hundredths of a millimetre (bulge in 128ths), round islands, a distance
//! in micrometres above 0.01 mm. Each runs from every start vertex and in both directions (the
//! polygon drawn the other way round), and every offset must pass
//! [`pocketeer::offset::verify_offset`]: closed loops, every point at distance d from the
//! walls and inside the pocket. The table holds the inputs with a one-line note on what each
//! exercises; the tests after it check more than the invariants.

mod offset_fuzz_inputs;

use offset_fuzz_inputs::{Take, CASES};
use pocketeer::geom::Pocket;
use pocketeer::geom::{distance_from_segment, Arc, Contour, Line, Point, Segment, Tolerance};
use pocketeer::import::FillRule;

/// A fuzz input's vertex: x, y in hundredths of a millimetre, the bulge of the edge to the
/// next in 128ths (wider than the input's i8 so that a reversed -128 stays exact).
type Vertex = (i16, i16, i16);

#[test]
fn every_input_from_every_start_in_both_directions() {
    for case in CASES {
        for (label, v) in variants(case.vertices) {
            let boundary = match case.take {
                Take::Outline => outline(&v),
                Take::Imported => match imported(&v[..v.len().min(64)]) {
                    Some(boundary) => boundary,
                    None => panic!("{} ({label}): the importer refuses the outline", case.note),
                },
            };
            let islands = round_islands(&boundary, &case.islands[..case.islands.len().min(4)]);
            let pocket = Pocket { boundary, islands };
            let d = distance(case.distance);
            if let Err(fault) = verified_loops(&pocket, d) {
                panic!("{} ({label}, {:?}, d = {d}): {fault}", case.note, case.take);
            }
        }
    }
}

/// `vertices` from every start vertex, as given and reversed, with a label for messages.
fn variants(vertices: &[(i16, i16, i8)]) -> Vec<(String, Vec<Vertex>)> {
    let given: Vec<Vertex> = vertices.iter().map(|&(x, y, b)| (x, y, b as i16)).collect();
    let n = given.len();
    // Reversed, vertex k+1 starts the edge that was k: it carries that edge's bulge, negated.
    let reversed: Vec<Vertex> = (0..n)
        .rev()
        .map(|k| {
            let (x, y, _) = given[(k + 1) % n];
            (x, y, -given[k].2)
        })
        .collect();
    let mut out = Vec::new();
    for (way, v) in [("as given", given), ("reversed", reversed)] {
        for start in 0..n {
            let mut turned = v.clone();
            turned.rotate_left(start);
            out.push((format!("{way}, from vertex {start}"), turned));
        }
    }
    out
}

fn distance(input: u16) -> f64 {
    0.01 + input as f64 / 1000.0
}

/// The offset of `pocket` by `d`, when it passes [`pocketeer::offset::verify_offset`].
fn verified_loops(pocket: &Pocket, d: f64) -> Result<Vec<Contour>, pocketeer::offset::OffsetFault> {
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let loops = pocketeer::offset::offset_pocket(pocket, d, &tol).expect("no input here is too complex");
    pocketeer::offset::verify_offset(pocket, &loops, d)?;
    Ok(loops)
}

/// [`verified_loops`] at the fuzz input's distance, failing the test on a fault.
fn check(pocket: &Pocket, distance_input: u16) -> Vec<Contour> {
    let d = distance(distance_input);
    verified_loops(pocket, d).unwrap_or_else(|f| panic!("d = {d}: {f}"))
}

/// The bulged polygon of the fuzz input, in its own direction (edges under 1 µm dropped).
fn polygon(vertices: &[Vertex]) -> Contour {
    let pts: Vec<(Point, f64)> = vertices
        .iter()
        .map(|&(x, y, b)| (Point::new(x as f64 / 100.0, y as f64 / 100.0), b as f64 / 128.0))
        .collect();
    let n = pts.len();
    let segs: Vec<Segment> = (0..n)
        .filter_map(|k| {
            let ((a, b), (e, _)) = (pts[k], pts[(k + 1) % n]);
            (a.distance(e) >= 1e-3).then(|| {
                Arc::from_bulge(a, e, b)
                    .map(Segment::Arc)
                    .unwrap_or(Segment::Line(Line::new(a, e)))
            })
        })
        .collect();
    Contour::new(segs)
}

/// The bulged polygon of the fuzz input, counter-clockwise.
fn outline(vertices: &[Vertex]) -> Contour {
    polygon(vertices).oriented(true)
}

/// The outline of the one pocket the importer finds in the bulged polygon taken in its own
/// direction, as the fuzz target takes it; `None` when it finds no pocket or several.
fn imported(vertices: &[Vertex]) -> Option<Contour> {
    let nesting = nesting_of(polygon(vertices)).ok()?;
    let [pocket] = &nesting.pockets[..] else {
        return None;
    };
    Some(pocket.boundary.clone().oriented(true))
}

/// The verified loops of the imported outline alone at the fuzz input's distance.
fn imported_loops(vertices: &[Vertex], distance_input: u16) -> Vec<Contour> {
    check(
        &Pocket {
            boundary: imported_as_drawn(vertices),
            islands: vec![],
        },
        distance_input,
    )
}

/// [`imported`], failing the test when the importer refuses.
fn imported_as_drawn(vertices: &[Vertex]) -> Contour {
    imported(vertices).expect("the importer takes the outline")
}

/// The table's input that the strict self-crossing test refuses from some start vertices only:
/// the zigzag of 0.01 mm steps, crossing itself at (2.57, 2.565) from 107 of its 128 starts
/// and directions.
const REFUSED_FROM_SOME_STARTS: &str =
    "two arcs 0.008 and 0.006 mm in radius turning back by 173° at a joint, d = 0.5";

/// The importer takes a drawn outline whatever vertex it starts at and whichever way round it
/// is drawn: the zigzag above, and the two circles drawn as semicircles touching at a neck
/// (below), which the strict self-crossing test refuses from some starts only, are filled.
#[test]
fn the_importers_verdict_does_not_depend_on_start_or_direction() {
    let zigzag = CASES
        .iter()
        .find(|c| c.note == REFUSED_FROM_SOME_STARTS)
        .expect("in the table");
    let circles: &[(i16, i16, i8)] = &[
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6592, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for v in [zigzag.vertices, circles] {
        let verdicts: Vec<bool> = variants(v).iter().map(|(_, v)| imported(v).is_some()).collect();
        assert!(
            verdicts.iter().all(|&b| b == verdicts[0]),
            "taken from {} of {} starts and directions",
            verdicts.iter().filter(|&&b| b).count(),
            verdicts.len()
        );
    }
}

/// The importer's verdict on one contour, filled by the even-odd rule where it crosses itself.
fn nesting_of(contour: Contour) -> Result<pocketeer::import::Nesting, pocketeer::ImportError> {
    nesting_filled(contour, Some(FillRule::EvenOdd))
}

/// The importer's verdict on one contour, refusing it where it crosses itself when `fill` is
/// `None`.
fn nesting_filled(
    contour: Contour,
    fill: Option<FillRule>,
) -> Result<pocketeer::import::Nesting, pocketeer::ImportError> {
    let tol = Tolerance::for_extent(&contour.bbox(), 0.001);
    let chained = pocketeer::import::ChainedContour {
        contour,
        layer: 0,
        elements: Vec::new(),
    };
    pocketeer::import::find_pockets(&[chained], &["0".to_string()], &tol, fill)
}

/// The fuzz input's round islands that lie inside `boundary` and clear of it.
fn round_islands(boundary: &Contour, islands: &[(i16, i16, u8)]) -> Vec<Contour> {
    islands
        .iter()
        .map(|&(x, y, r)| {
            (
                Point::new(x as f64 / 100.0, y as f64 / 100.0),
                0.1 + r as f64 / 20.0,
            )
        })
        .filter(|&(c, r)| {
            boundary.contains(c)
                && boundary
                    .segments
                    .iter()
                    .all(|s| distance_from_segment(s, c) > r + 0.01)
        })
        .map(|(c, r)| Contour::new(vec![Segment::Arc(Arc::new(c, r, 0.0, -std::f64::consts::TAU))]))
        .collect()
}

/// Outlines with a cusp (an element turning straight back) keep their one loop.
#[test]
fn big_bulge_outlines_keep_their_loop() {
    let a = [
        (3968, 3855, 15),
        (3855, 3855, 15),
        (3855, 100, 15),
        (31503, 31611, 123),
        (-17522, 3855, -15),
    ];
    let b = [
        (512, 0, 85),
        (21845, 21845, 85),
        (21852, 21845, 127),
        (15561, 25669, -97),
    ];
    for (label, v) in variants(&a) {
        let loops = check(
            &Pocket {
                boundary: outline(&v),
                islands: vec![],
            },
            990,
        );
        assert_eq!(loops.len(), 1, "{label}");
        // The outline's area is 158494 mm²; eroded by 1 mm along its 1.5 m of boundary.
        let area: f64 = loops.iter().map(Contour::signed_area).sum();
        assert!((150_000.0..158_494.0).contains(&area), "{label}: {area}");
    }
    for (label, v) in variants(&b) {
        let loops = check(
            &Pocket {
                boundary: outline(&v),
                islands: vec![],
            },
            4990,
        );
        assert_eq!(loops.len(), 1, "{label}");
    }
}

/// A needle 130 mm long whose two sides are flat arcs bulging the same way 0.01 mm apart: the
/// sides cross, and the importer fills the outline naming the place, from every start (and
/// refuses it there when strict).
#[test]
fn a_hair_thin_needle_of_flat_arcs_crosses_itself_and_is_filled_or_refused() {
    let v = [
        (-12851, 128, 0),
        (1535, -31996, -51),
        (-17715, -32564, -51),
        (-17235, -11603, -83),
        (-12849, -128, -1),
        (-12851, -13056, 1),
    ];
    let at_the_crossing = |p: &Point| (p.x + 127.995).abs() < 0.01 && (p.y + 64.64).abs() < 0.01;
    for (label, v) in variants(&v) {
        match nesting_filled(outline(&v), None) {
            Err(pocketeer::ImportError::SelfCrossing { point, .. }) => {
                assert!(at_the_crossing(&point), "{label}: {point:?}")
            }
            other => panic!("{label}: expected a self-crossing refusal, got {other:?}"),
        }
        let nesting = nesting_of(outline(&v)).unwrap();
        let filled = nesting.warnings.iter().any(|w| {
            matches!(w, pocketeer::import::ImportWarning::SelfCrossingFilled { at, .. } if at.iter().any(at_the_crossing))
        });
        assert!(filled, "{label}: {:?}", nesting.warnings);
    }
}

/// Three semicircles 0.02 mm across are a pocket, not a self-crossing.
#[test]
fn the_three_tiny_semicircles_are_a_pocket() {
    let v = [
        (-12850, 1261, -128),
        (-12852, 1261, -128),
        (-12852, 1263, -128),
        (-12862, -12851, 127),
    ];
    for (label, v) in variants(&v) {
        assert!(nesting_of(outline(&v)).is_ok(), "{label}");
    }
}

/// Two circles (radius 115.3 and 48.5) drawn as four semicircles touching at a neck 0.01 mm
/// wide. A line 1e-10 mm long pointing back against the arcs at the big circle's top (as an
/// importer may leave one) is a point to the raw offset: with it or without it, one loop in
/// each circle.
#[test]
fn a_line_shorter_than_rounding_pointing_back_is_a_point() {
    let v = [
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6592, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for (label, v) in variants(&v) {
        let imported = imported_as_drawn(&v);
        let top = imported
            .segments
            .iter()
            .map(Segment::end)
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .expect("segments");
        let k = imported
            .segments
            .iter()
            .position(|s| s.end() == top)
            .expect("the top");
        let mut with_line = imported.segments.clone();
        with_line.insert(
            k + 1,
            Segment::Line(Line::new(top, Point::new(top.x + 1e-10, top.y))),
        );
        for boundary in [imported, Contour::new(with_line)] {
            let loops = check(
                &Pocket {
                    boundary,
                    islands: vec![],
                },
                21845,
            );
            // One loop in each circle: radius 115.31 - 21.855 and 48.53 - 21.855.
            assert_eq!(loops.len(), 2, "{label}");
            let area: f64 = loops.iter().map(Contour::signed_area).sum();
            let expected =
                std::f64::consts::PI * ((115.31f64 - 21.855).powi(2) + (48.53f64 - 21.855).powi(2));
            assert!(
                (area - expected).abs() < 2.0,
                "{label}: {area} against {expected}"
            );
        }
    }
}

/// The two circles joined by a neck 2.6 mm wide, a round island 0.2 mm across in the big one,
/// at d = 0.01: one loop round both circles and one round the island.
#[test]
fn a_line_shorter_than_rounding_beside_an_island() {
    let v = [
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6337, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for (label, v) in variants(&v) {
        let boundary = imported_as_drawn(&v);
        let island = Contour::new(vec![Segment::Arc(Arc::new(
            Point::new(218.45, 41.17),
            0.1,
            0.0,
            -std::f64::consts::TAU,
        ))]);
        assert!(boundary.contains(island.segments[0].start()), "{label}");
        let loops = check(
            &Pocket {
                boundary,
                islands: vec![island],
            },
            0,
        );
        assert_eq!(loops.len(), 2, "{label}");
        assert_eq!(
            loops.iter().filter(|l| l.signed_area() < 0.0).count(),
            1,
            "{label}"
        );
    }
}

/// Triangles whose inscribed circle has radius d to within 1e-9 (164 mm long and 0.02 high;
/// 5.1 mm long upright): nothing is left, and no loop runs round the outside through the walls.
#[test]
fn a_sliver_triangle_whose_inscribed_circle_has_radius_d() {
    for v in [
        [(24417, 0, 0), (8033, 0, 0), (16225, 2, 0)],
        [(257, 257, 0), (257, -255, 0), (255, 1, 0)],
    ] {
        for (label, v) in variants(&v) {
            let loops = imported_loops(&v, 0);
            assert!(loops.is_empty(), "{label}: {loops:?}");
        }
    }
}

/// A lens 151 mm long and a sliver lens 1.3 mm long joined by a neck 0.0185 mm wide, narrower
/// than 2d = 0.02: only the big lens's loop, no loop at the neck.
#[test]
fn a_neck_narrower_than_2d_between_two_lenses() {
    let v = [(2, 131, 1), (-2, 0, 127), (14080, 5632, 0), (0, 0, 0)];
    for (label, v) in variants(&v) {
        let loops = imported_loops(&v, 0);
        assert_eq!(loops.len(), 1, "{label}: {loops:?}");
        assert!(loops[0].is_ccw(), "{label}");
        assert!(loops[0].signed_area() > 8900.0, "{label}");
    }
}

/// A hairpin 327 mm long whose sides (a line and an arc bulging 0.02 mm from it) are 2d apart
/// to within 1e-7 mm at d = 0.01: the sides' offsets meet, and one loop is left, not a
/// clockwise loop through the walls.
#[test]
fn the_offsets_of_a_hairpin_2d_wide_meet() {
    let v = [(0, -32512, -17), (-255, 5888, 17), (-1, -255, -1), (-1, 255, 0)];
    for (label, v) in variants(&v) {
        let loops = imported_loops(&v, 0);
        assert_eq!(loops.len(), 1, "{label}: {loops:?}");
        assert!(loops[0].is_ccw(), "{label}");
    }
}
