//! How ends that do not meet are joined: snapped within the join tolerance, bridged by a
//! straight segment up to the gap-closing length when unambiguous, never otherwise; and that
//! raising the join tolerance never opens a contour closed at a lower one.

mod common;

use common::analysis::*;
use common::*;
use pocketeer::geom::{Line, Point, Segment, Tolerance};
use pocketeer::import::{chain, Element, ImportError, ImportWarning};
use pocketeer::{analyze, ImportOptions};
use proptest::prelude::*;

fn with(d: &Drawing, opts: &ImportOptions) -> Result<pocketeer::Analysis, ImportError> {
    analyze(d.text().as_bytes(), opts)
}

/// A 10 × 10 square of lines whose last corner misses by `gap` along y.
fn square_missing(gap: f64) -> Drawing {
    Drawing::new(vec![
        line("0", 0.0, 0.0, 10.0, 0.0),
        line("0", 10.0, 0.0, 10.0, 10.0),
        line("0", 10.0, 10.0, 0.0, 10.0),
        line("0", 0.0, 10.0, 0.0, gap),
    ])
}

#[test]
fn gaps_below_the_join_tolerance_close_exactly_and_a_reversed_copy_is_dropped() {
    let g = 0.0004;
    let mut ents = vec![
        line("0", 0.0, 0.0, 50.0, g),
        line("0", 50.0, 0.0, 50.0 - g, 30.0),
        line("0", 50.0, 30.0, 0.0, 30.0 + g),
        line("0", 0.0, 30.0, g, 0.0),
    ];
    ents.push(line("0", 0.0, 30.0 + g, 50.0, 30.0));
    let a = read(&Drawing::new(ents));
    assert_eq!(a.chains.contours.len(), 1);
    assert_eq!(a.chains.duplicates_dropped, 1);
    assert_eq!(a.chains.gaps_closed, 4);
    assert!(close(a.chains.largest_gap, g, 1e-9), "{}", a.chains.largest_gap);
    assert!(close(pockets(&a)[0].0, 1500.0, 0.1));
    // Joined ends are moved onto one node: the contour closes exactly.
    let segs = &a.nesting.pockets[0].boundary.segments;
    for k in 0..segs.len() {
        assert_eq!(segs[k].end(), segs[(k + 1) % segs.len()].start());
    }
}

#[test]
fn a_shared_edge_drawn_twice_a_little_apart_closes_both_outlines() {
    // Two parts laid side by side, each drawn whole: their common edge is drawn twice, the
    // second copy 0.0003 mm over. Dropping one copy as a duplicate would leave three ends at
    // each end of the edge and one part open.
    let o = 0.0003;
    let mut ents = rect_lines("0", 0.0, 0.0, 50.0, 30.0);
    ents.extend(rect_lines("0", 50.0 - o, 0.0, 100.0, 30.0));
    let a = read(&Drawing::new(ents));
    assert!(a.chains.open.is_empty(), "{:?}", a.chains.open);
    assert_eq!(a.chains.contours.len(), 2);
    let p = pockets(&a);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(close(p[0].0, 3000.0, 0.01), "{p:?}");
}

#[test]
fn a_small_unambiguous_gap_is_bridged_and_reported_with_its_place() {
    // The wing rib's case: an outline missing closing by 0.0148 mm.
    let a = read(&square_missing(0.0148));
    assert_eq!(a.chains.contours.len(), 1);
    assert!(close(pockets(&a)[0].0, 100.0, 1e-3));
    let bridged: Vec<_> = a
        .chains
        .warnings
        .iter()
        .filter_map(|w| match w {
            ImportWarning::GapBridged { length, from, to } => Some((*length, *from, *to)),
            _ => None,
        })
        .collect();
    assert_eq!(bridged.len(), 1, "{:?}", a.chains.warnings);
    let (length, from, to) = bridged[0];
    assert!(close(length, 0.0148, 1e-12));
    let ends = [from, to];
    assert!(ends.contains(&Point::new(0.0, 0.0)) && ends.contains(&Point::new(0.0, 0.0148)));
    // The bridge is a segment of the contour, not a move of the drawn ends.
    assert_eq!(a.nesting.pockets[0].boundary.segments.len(), 5);
    // Turned off, the gap is refused with both ends named.
    let off = ImportOptions {
        close_gaps: 0.0,
        ..Default::default()
    };
    let err = with(&square_missing(0.0148), &off).unwrap_err();
    assert!(matches!(err, ImportError::NoClosedContour { .. }), "{err}");
}

#[test]
fn a_gap_above_both_lengths_leaves_an_open_chain_that_names_its_ends() {
    let err = read_err(&square_missing(0.2));
    let msg = err.to_string();
    assert!(matches!(err, ImportError::NoClosedContour { .. }), "{msg}");
    assert!(
        msg.contains("(0.0000, 0.2000)") && msg.contains("(0.0000, 0.0000)"),
        "{msg}"
    );
    // A larger join tolerance moves the ends to meet; a larger gap length bridges them.
    let join = ImportOptions {
        join_tolerance: 0.3,
        ..Default::default()
    };
    let a = with(&square_missing(0.2), &join).unwrap();
    assert_eq!(a.nesting.pockets[0].boundary.segments.len(), 4);
    let bridge = ImportOptions {
        close_gaps: 0.3,
        ..Default::default()
    };
    let a = with(&square_missing(0.2), &bridge).unwrap();
    assert_eq!(a.nesting.pockets[0].boundary.segments.len(), 5);
}

#[test]
fn a_gap_with_another_free_end_nearby_is_not_bridged() {
    // A stroke ends 0.06 mm from the gap of 0.02: which end closes the outline is a guess.
    let mut d = square_missing(0.02);
    d.entities.push(line("0", -0.06, 0.0, -5.0, 0.0));
    let err = read_err(&d);
    assert!(matches!(err, ImportError::NoClosedContour { .. }), "{err}");
    // Five times the gap away, it is no competitor.
    let mut d = square_missing(0.02);
    d.entities.push(line("0", -0.11, 0.0, -5.0, 0.0));
    let a = read(&d);
    assert_eq!(a.chains.contours.len(), 1);
}

#[test]
fn a_short_stroke_is_never_closed_on_itself() {
    // A line shorter than the gap length, alone: bridging its own ends would make a contour
    // of no area.
    let mut d = square_missing(0.0);
    d.entities.push(line("0", 20.0, 20.0, 20.03, 20.0));
    let a = read(&d);
    assert_eq!(a.chains.contours.len(), 1);
    assert_eq!(a.chains.open.len(), 1);
}

/// A random drawing of separate polygons, each side cut into pieces (some a few micrometres
/// long), every joint either exact or open by up to `max_gap`, pieces reversed and shuffled.
fn broken_polygons(max_gap: f64) -> impl Strategy<Value = Vec<Element>> {
    let polygon = (
        prop::collection::vec(5.0..20.0f64, 3..8),
        prop::collection::vec((1usize..4, any::<bool>(), 0.0..1.0f64, 0.0..1.0f64), 8),
    );
    (prop::collection::vec(polygon, 1..4), any::<u64>()).prop_map(move |(polys, seed)| {
        let mut rng = Rng(seed | 1);
        let mut segs: Vec<Segment> = Vec::new();
        for (k, (radii, cuts)) in polys.iter().enumerate() {
            let centre = Point::new(60.0 * k as f64, 0.0);
            let n = radii.len();
            let corner = |i: usize| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                Point::new(
                    centre.x + radii[i % n] * a.cos(),
                    centre.y + radii[i % n] * a.sin(),
                )
            };
            // Every point where one piece ends and the next starts.
            let mut joints: Vec<Point> = Vec::new();
            for i in 0..n {
                let (a, b) = (corner(i), corner(i + 1));
                let (pieces, micro, _, _) = cuts[i % cuts.len()];
                joints.push(a);
                for p in 1..pieces {
                    let mut t = p as f64 / pieces as f64;
                    if micro && p == pieces - 1 {
                        t = 1.0 - 0.003 / a.distance(b);
                    }
                    joints.push(a + (b - a) * t);
                }
            }
            for (j, &start) in joints.iter().enumerate() {
                let end = joints[(j + 1) % joints.len()];
                let (_, _, chance, size) = cuts[j % cuts.len()];
                let open = chance < 0.5;
                let shift = if open {
                    let angle = rng.below(360) as f64;
                    let r = size * max_gap;
                    Point::new(r * angle.to_radians().cos(), r * angle.to_radians().sin())
                } else {
                    Point::new(0.0, 0.0)
                };
                // The piece ends where the next starts, or a little beside it.
                let end = Point::new(end.x + shift.x, end.y + shift.y);
                segs.push(Segment::Line(Line::new(start, end)));
            }
        }
        let mut elements: Vec<Element> = segs
            .into_iter()
            .enumerate()
            .map(|(k, s)| Element {
                segment: if rng.below(2) == 1 { s.reversed() } else { s },
                layer: 0,
                source: k,
                closed_group: None,
            })
            .collect();
        rng.shuffle(&mut elements);
        elements
    })
}

/// Each closed contour as (its elements sorted, its area).
fn closed(elements: &[Element], tol: &Tolerance, close_gaps: f64) -> Vec<(Vec<usize>, f64, f64)> {
    chain(elements, tol, close_gaps)
        .contours
        .iter()
        .map(|c| {
            let mut e = c.elements.clone();
            e.sort_unstable();
            (e, c.contour.signed_area().abs(), c.contour.length())
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn raising_the_join_tolerance_never_opens_a_contour(
        elements in broken_polygons(0.004),
        t1 in 0.0001..0.004f64,
        factor in 1.0..4.0f64,
    ) {
        let t2 = t1 * factor;
        for close_gaps in [0.0, 0.05] {
            let low = closed(&elements, &Tolerance::for_scale(200.0, t1), close_gaps);
            let high = closed(&elements, &Tolerance::for_scale(200.0, t2), close_gaps);
            for (members, area, length) in &low {
                let same = high.iter().find(|h| &h.0 == members);
                prop_assert!(same.is_some(), "contour of {:?} closed at {} but not at {} (gaps {})", members, t1, t2, close_gaps);
                // Ends move by at most half the larger tolerance, bridges become snaps.
                let moved = same.map_or(0.0, |h| (h.1 - area).abs());
                prop_assert!(moved <= length * t2, "area changed by {} on a contour {} long", moved, length);
            }
        }
    }
}

#[test]
fn strokes_that_bound_nothing_are_left_out_of_the_outline() {
    // A construction line drawn from the wall into the pocket, and a leader from a hole to a
    // corner: each makes three ends meet, and neither bounds anything.
    let mut ents = rect_lines("0", 0.0, 0.0, 100.0, 60.0);
    ents.push(line("0", 100.0, 30.0, 70.0, 30.0));
    ents.push(circle("0", 30.0, 30.0, 5.0));
    ents.push(line("0", 0.0, 60.0, 30.0, 35.0));
    // The wall is drawn in pieces meeting where the strokes start, as CAD programs leave it.
    ents.remove(1);
    ents.push(line("0", 100.0, 0.0, 100.0, 30.0));
    ents.push(line("0", 100.0, 30.0, 100.0, 60.0));
    let a = read(&Drawing::new(ents));
    let p = pockets(&a);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(close(p[0].0, 6000.0 - 25.0 * std::f64::consts::PI, 1e-6), "{p:?}");
    let removed = a
        .chains
        .warnings
        .iter()
        .filter(|w| matches!(w, ImportWarning::StrokeRemoved { .. }))
        .count();
    assert_eq!(removed, 2, "{:?}", a.chains.warnings);
    assert!(!a
        .chains
        .warnings
        .iter()
        .any(|w| matches!(w, ImportWarning::OddJunction { .. })));
}

#[test]
fn a_part_drawn_with_its_internal_edges_is_the_faces_it_encloses() {
    // A plate with a cut-out drawn as a rectangle divided in three: the faces merge into one
    // island, as the even-odd rule reads the strokes.
    let mut ents = rect_lines("0", 0.0, 0.0, 100.0, 60.0);
    ents.extend([
        line("0", 20.0, 20.0, 50.0, 20.0),
        line("0", 50.0, 20.0, 80.0, 20.0),
        line("0", 80.0, 20.0, 80.0, 40.0),
        line("0", 80.0, 40.0, 50.0, 40.0),
        line("0", 50.0, 40.0, 20.0, 40.0),
        line("0", 20.0, 40.0, 20.0, 20.0),
        line("0", 50.0, 20.0, 50.0, 40.0),
    ]);
    let a = read(&Drawing::new(ents));
    let p = pockets(&a);
    assert_eq!(p.len(), 1, "{p:?}");
    assert_eq!(p[0].2.len(), 1, "{p:?}");
    assert!(close(p[0].2[0], 1200.0, 1e-6), "{p:?}");
    let branching: Vec<_> = a
        .chains
        .warnings
        .iter()
        .filter_map(|w| match w {
            ImportWarning::BranchingOutline { at, branches, faces } => Some((*at, *branches, *faces)),
            _ => None,
        })
        .collect();
    assert_eq!(branching.len(), 1, "{:?}", a.chains.warnings);
    assert_eq!((branching[0].1, branching[0].2), (2, 2));
    assert!([Point::new(50.0, 20.0), Point::new(50.0, 40.0)].contains(&branching[0].0));
}
