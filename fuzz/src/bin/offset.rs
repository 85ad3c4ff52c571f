//! Random pockets (a polygon with bulges, optional round islands) and distances from an
//! `arbitrary` description: the offset must pass `verify_offset` (closed loops whose points lie
//! at distance d from the walls, 1e-6 relative, and inside the pocket), or be empty; never panic.

use arbitrary::{Arbitrary, Unstructured};
use pocketeer::geom::{distance_from_segment, Arc, Contour, Line, Point, Segment, Tolerance};
use pocketeer::geom::Pocket;

#[derive(Arbitrary, Debug)]
struct Input {
    vertices: Vec<(i16, i16, i8)>,
    islands: Vec<(i16, i16, u8)>,
    distance: u16,
}

fn contour(vertices: &[(i16, i16, i8)]) -> Option<Contour> {
    let pts: Vec<(Point, f64)> = vertices
        .iter()
        .map(|&(x, y, b)| (Point::new(x as f64 / 100.0, y as f64 / 100.0), b as f64 / 128.0))
        .collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let segs: Vec<Segment> = (0..n)
        .filter_map(|k| {
            let ((a, b), (e, _)) = (pts[k], pts[(k + 1) % n]);
            if a.distance(e) < 1e-3 {
                return None;
            }
            Some(
                Arc::from_bulge(a, e, b)
                    .map(Segment::Arc)
                    .unwrap_or(Segment::Line(Line::new(a, e))),
            )
        })
        .collect();
    let c = Contour::new(segs);
    (c.segments.len() >= 2 && c.signed_area().abs() > 1e-3).then_some(c)
}

fn main() {
    // `offset FILE` replays one input and prints it (outside AFL).
    if let Some(path) = std::env::args().nth(1) {
        let data = std::fs::read(path).unwrap_or_default();
        if let Ok(input) = Input::arbitrary(&mut Unstructured::new(&data)) {
            eprintln!("{input:?}");
        }
        run(&data);
        return;
    }
    afl::fuzz!(|data: &[u8]| run(data));
}

fn run(data: &[u8]) {
    {
        let Ok(input) = Input::arbitrary(&mut Unstructured::new(data)) else {
            return;
        };
        let Some(boundary) = contour(&input.vertices[..input.vertices.len().min(64)]) else {
            return;
        };
        // Only what the importer accepts is a pocket: it refuses outlines that cross themselves
        // (a pairwise test of the elements here missed shallow crossings of flat arcs) and cuts
        // away sliver loops; the offset gets its outline.
        let tol = Tolerance::for_extent(&boundary.bbox(), 0.001);
        let chained = pocketeer::import::ChainedContour {
            contour: boundary,
            layer: 0,
            elements: Vec::new(),
        };
        let Ok(regions) = pocketeer::import::find_pockets(&[chained], &["0".to_string()], &tol, Some(pocketeer::import::FillRule::EvenOdd)) else {
            return;
        };
        let [pocket] = &regions.pockets[..] else { return };
        if !pocket.islands.is_empty() {
            return;
        }
        let boundary = pocket.boundary.clone();
        let segs = boundary.segments.clone();
        let boundary = boundary.oriented(true);
        let islands: Vec<Contour> = input
            .islands
            .iter()
            .take(4)
            .map(|&(x, y, r)| {
                (
                    Point::new(x as f64 / 100.0, y as f64 / 100.0),
                    0.1 + r as f64 / 20.0,
                )
            })
            .filter(|&(c, r)| boundary.contains(c) && segs.iter().all(|s| distance_from_segment(s, c) > r + 0.01))
            .map(|(c, r)| Contour::new(vec![Segment::Arc(Arc::new(c, r, 0.0, -std::f64::consts::TAU))]))
            .collect();
        // Islands that overlap each other are merged by the importer: skip such inputs.
        for (i, a) in islands.iter().enumerate() {
            for b in &islands[i + 1..] {
                if !pocketeer::geom::intersect(&a.segments[0], &b.segments[0], 1e-9).is_empty() {
                    return;
                }
            }
        }
        let pocket = Pocket { boundary, islands };
        let d = 0.01 + input.distance as f64 / 1000.0;
        let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
        // A refusal (too complex) is an answer; these inputs are far too small to reach it.
        let Ok(loops) = pocketeer::offset::offset_pocket(&pocket, d, &tol) else {
            return;
        };
        if let Err(fault) = pocketeer::offset::verify_offset(&pocket, &loops, d) {
            panic!("{fault}");
        }
    }
}
