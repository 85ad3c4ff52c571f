//! Invariance harness: every offset and pocket test drawing (the hard cases of
//! `offset_cases.rs`, the pockets of `pocket_end_to_end.rs`, the corpus fixtures and the
//! shipped example) is also drawn reversed, with its start points rotated, mirrored, and moved
//! by 1e5 mm, written as DXF and read back through the importer. Mapped back, the offsets
//! must be the same loops (every sampled point within 1e-6 mm of the other result, as many
//! loops, the same area) and the clearing plans the same levels.

mod common;

use common::shapes::{circle_cw, mirror_segment, mirrored, polygon, rect, star};
use pocketeer::clear::{plan_pocket, ClearParams};
use pocketeer::export::dxf::{write_dxf, LayeredContour};
use pocketeer::geom::Pocket;
use pocketeer::geom::{distance_from_segment, Arc, Contour, Line, Point, Segment, Vector};
use pocketeer::import::Units;
use pocketeer::ImportOptions;

/// A drawing: its contours (any orientation) and the distances it is offset by.
struct Case {
    name: String,
    contours: Vec<Contour>,
    distances: Vec<f64>,
}

fn case(name: &str, contours: Vec<Contour>, distances: &[f64]) -> Case {
    Case {
        name: name.to_string(),
        contours,
        distances: distances.to_vec(),
    }
}

/// A circle of `n` line segments.
fn polygon_circle(cx: f64, cy: f64, r: f64, n: usize) -> Contour {
    let pts: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            (cx + r * a.cos(), cy + r * a.sin())
        })
        .collect();
    polygon(&pts)
}

/// The drawings the offset and pocket tests use, built the same way.
fn drawn_cases() -> Vec<Case> {
    vec![
        case(
            "rectangle with a square island",
            vec![rect(0.0, 0.0, 100.0, 60.0), rect(40.0, 20.0, 60.0, 40.0)],
            &[5.0, 12.0],
        ),
        case(
            "a neck narrower than twice the distance",
            vec![polygon(&[
                (0.0, 0.0),
                (40.0, 0.0),
                (40.0, 17.0),
                (60.0, 17.0),
                (60.0, 0.0),
                (100.0, 0.0),
                (100.0, 40.0),
                (60.0, 40.0),
                (60.0, 23.0),
                (40.0, 23.0),
                (40.0, 40.0),
                (0.0, 40.0),
            ])],
            &[2.0, 3.0, 4.0],
        ),
        case(
            "islands exactly 2d apart",
            vec![
                rect(0.0, 0.0, 100.0, 60.0),
                circle_cw(35.0, 30.0, 5.0),
                circle_cw(65.0, 30.0, 5.0),
            ],
            &[10.0, 4.0],
        ),
        case(
            "an island 2d from the wall",
            vec![rect(0.0, 0.0, 100.0, 60.0), circle_cw(50.0, 18.0, 10.0)],
            &[4.0, 3.0],
        ),
        case(
            "arcs smaller than the distance on the inside",
            vec![Contour::new(vec![
                Segment::Line(Line::new(Point::new(2.0, 0.0), Point::new(48.0, 0.0))),
                Segment::Arc(Arc::new(
                    Point::new(48.0, 2.0),
                    2.0,
                    -std::f64::consts::FRAC_PI_2,
                    std::f64::consts::FRAC_PI_2,
                )),
                Segment::Line(Line::new(Point::new(50.0, 2.0), Point::new(50.0, 28.0))),
                Segment::Arc(Arc::new(
                    Point::new(48.0, 28.0),
                    2.0,
                    0.0,
                    std::f64::consts::FRAC_PI_2,
                )),
                Segment::Line(Line::new(Point::new(48.0, 30.0), Point::new(2.0, 30.0))),
                Segment::Arc(Arc::new(
                    Point::new(2.0, 28.0),
                    2.0,
                    std::f64::consts::FRAC_PI_2,
                    std::f64::consts::FRAC_PI_2,
                )),
                Segment::Line(Line::new(Point::new(0.0, 28.0), Point::new(0.0, 2.0))),
                Segment::Arc(Arc::new(
                    Point::new(2.0, 2.0),
                    2.0,
                    std::f64::consts::PI,
                    std::f64::consts::FRAC_PI_2,
                )),
            ])],
            &[2.0, 5.0],
        ),
        case(
            "a circle of 2000 segments",
            vec![polygon_circle(0.0, 0.0, 50.0, 2000)],
            &[3.0, 25.0],
        ),
        case(
            "a 7-point star with a round island",
            vec![star(7, 50.0, 22.0), circle_cw(0.0, 0.0, 6.0)],
            &[3.0, 7.8, 12.6],
        ),
        case(
            "a rectangle with two round islands",
            vec![
                rect(0.0, 0.0, 120.0, 80.0),
                circle_cw(35.0, 40.0, 12.0),
                circle_cw(85.0, 40.0, 15.0),
            ],
            &[3.0, 5.4, 10.2],
        ),
        case(
            "a bar island leaving gaps narrower than the tool",
            vec![
                rect(0.0, 0.0, 100.0, 50.0),
                rect(10.0, 22.0, 90.0, 28.0).reversed(),
            ],
            &[3.0, 8.0],
        ),
        case(
            "a tiny distance",
            vec![rect(0.0, 0.0, 30.0, 20.0), circle_cw(15.0, 10.0, 4.0)],
            &[1e-4],
        ),
    ]
}

/// Contours of every pocket of the drawings shipped with the tests and the example.
fn file_cases() -> Vec<Case> {
    let mut out = Vec::new();
    let mut files = vec![std::path::PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/bracket.dxf"
    ))];
    files.extend(common::corpus::dxf_files(&common::fixture("corpus")));
    for f in files {
        let Ok(bytes) = std::fs::read(&f) else { continue };
        let Ok(a) = pocketeer::analyze(&bytes, &ImportOptions::default()) else {
            continue;
        };
        for (k, p) in a.nesting.pockets.iter().enumerate() {
            let b = p.boundary.bbox();
            let size = b.width().min(b.height());
            let name = format!(
                "{} pocket {}",
                f.file_name()
                    .map_or(String::new(), |n| n.to_string_lossy().into_owned()),
                k + 1
            );
            out.push(case(
                &name,
                p.contours().cloned().collect(),
                &[0.05 * size, 0.2 * size],
            ));
        }
    }
    out
}

/// A change of the drawing and the map taking its results back.
#[derive(Clone, Copy, Debug)]
enum Change {
    Reversed,
    StartRotated,
    Mirrored,
    Moved,
}

const FAR: Vector = Vector { x: 1e5, y: -1e5 };

impl Change {
    fn apply(self, c: &Contour) -> Contour {
        match self {
            Change::Reversed => c.reversed(),
            Change::StartRotated => {
                let mut s = c.segments.clone();
                let k = s.len() / 3;
                s.rotate_left(k);
                Contour::new(s)
            }
            Change::Mirrored => Contour::new(c.segments.iter().map(mirror_segment).collect()),
            Change::Moved => Contour::new(c.segments.iter().map(|s| s.translated(FAR)).collect()),
        }
    }

    /// A result loop mapped back (a mirrored loop also reversed, to keep its sense).
    fn back_loop(self, l: &Contour) -> Contour {
        match self {
            Change::Reversed | Change::StartRotated => l.clone(),
            Change::Mirrored => mirrored(l),
            Change::Moved => Contour::new(l.segments.iter().map(|s| s.translated(-FAR)).collect()),
        }
    }
}

/// The pockets of `contours` written as DXF (LWPOLYLINEs with bulges) and read back.
fn pockets_through_dxf(contours: &[Contour]) -> Vec<Pocket> {
    let layered: Vec<LayeredContour> = contours
        .iter()
        .map(|c| LayeredContour {
            layer: "0",
            contour: c,
        })
        .collect();
    let text = write_dxf(&layered, Units::Millimeters);
    pocketeer::analyze(text.as_bytes(), &ImportOptions::default())
        .expect("a drawing written by pocketeer reads back")
        .nesting
        .pockets
}

/// Every sampled point of each result within `within` of the other; as many loops; same area.
fn assert_same(name: &str, a: &[Contour], b: &[Contour], within: f64) {
    assert_eq!(a.len(), b.len(), "{name}: {} loops against {}", a.len(), b.len());
    let area = |l: &[Contour]| l.iter().map(Contour::signed_area).sum::<f64>();
    let (sa, sb) = (area(a), area(b));
    assert!(
        (sa - sb).abs() <= 1e-6 * sa.abs().max(1.0),
        "{name}: area {sa} against {sb}"
    );
    let segs = |l: &[Contour]| {
        l.iter()
            .flat_map(|c| c.segments.iter().copied())
            .collect::<Vec<_>>()
    };
    let (fa, fb) = (segs(a), segs(b));
    for (from, to) in [(&fa, &fb), (&fb, &fa)] {
        for s in from {
            for k in 0..=2 {
                let q = s.point_at(k as f64 / 2.0);
                let dist = to
                    .iter()
                    .map(|o| distance_from_segment(o, q))
                    .fold(f64::INFINITY, f64::min);
                assert!(dist <= within, "{name}: {q:?} is {dist} from the other result");
            }
        }
    }
}

fn offsets(pockets: &[Pocket], d: f64) -> Vec<Contour> {
    pockets
        .iter()
        .flat_map(|p| {
            let tol = pocketeer::geom::Tolerance::for_extent(&p.boundary.bbox(), 0.001);
            pocketeer::offset::offset_pocket(p, d, &tol).expect("offset")
        })
        .collect()
}

fn check(cases: &[Case]) {
    const CHANGES: [Change; 4] = [
        Change::Reversed,
        Change::StartRotated,
        Change::Mirrored,
        Change::Moved,
    ];
    for c in cases {
        let base = pockets_through_dxf(&c.contours);
        for &change in &CHANGES {
            let changed: Vec<Contour> = c.contours.iter().map(|k| change.apply(k)).collect();
            let pockets = pockets_through_dxf(&changed);
            let name = format!("{} ({change:?})", c.name);
            assert_eq!(pockets.len(), base.len(), "{name}: pockets");
            for &d in &c.distances {
                let want = offsets(&base, d);
                let got: Vec<Contour> = offsets(&pockets, d).iter().map(|l| change.back_loop(l)).collect();
                // Coordinates near 1e5 carry 1e-11 relative rounding into every step.
                assert_same(&format!("{name} at d = {d}"), &want, &got, 1e-6);
            }
            // Clearing plans: as many parts and loops, the same swept levels.
            for (p, q) in base.iter().zip(&pockets) {
                let size = p.boundary.bbox().width().min(p.boundary.bbox().height());
                let params = ClearParams {
                    tool_radius: 0.04 * size,
                    stepover: 0.05 * size,
                    allowance: 0.0,
                };
                let tol = |p: &Pocket| pocketeer::geom::Tolerance::for_extent(&p.boundary.bbox(), 0.001);
                let (a, b) = (
                    plan_pocket(p, &params, &tol(p)).expect("plan"),
                    plan_pocket(q, &params, &tol(q)).expect("plan"),
                );
                assert_eq!(a.parts.len(), b.parts.len(), "{name}: parts of the plan");
                assert_eq!(a.loop_count(), b.loop_count(), "{name}: loops of the plan");
                let area = |p: &pocketeer::clear::ClearPlan| -> f64 {
                    p.parts
                        .iter()
                        .flat_map(|n| n.loops())
                        .map(Contour::signed_area)
                        .sum()
                };
                let (sa, sb) = (area(&a), area(&b));
                assert!(
                    (sa - sb).abs() <= 1e-6 * sa.abs().max(1.0),
                    "{name}: plan area {sa} against {sb}"
                );
            }
        }
    }
}

#[test]
fn offset_and_pocket_test_drawings_are_invariant() {
    check(&drawn_cases());
}

#[test]
fn corpus_fixtures_and_the_example_are_invariant() {
    let cases = file_cases();
    assert!(cases.len() >= 5, "{} pockets found in the fixtures", cases.len());
    check(&cases);
}
