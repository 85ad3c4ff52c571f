//! Benchmark inputs shared by the bench binaries.

pub mod cases;

use cases::{Case, Ring};
use pocketeer::geom::{Arc, Contour, Line, Point, Segment};
use pocketeer::import::Pocket;

/// A bulged polyline as exact lines and arcs.
pub fn contour(ring: &Ring) -> Contour {
    let n = ring.len();
    Contour::new(
        (0..n)
            .map(|k| {
                let (x0, y0, b) = ring[k];
                let (x1, y1, _) = ring[(k + 1) % n];
                let (a, e) = (Point::new(x0, y0), Point::new(x1, y1));
                Arc::from_bulge(a, e, b)
                    .map(Segment::Arc)
                    .unwrap_or(Segment::Line(Line::new(a, e)))
            })
            .collect(),
    )
}

/// The case as a pocket: the first ring its boundary, the others its islands.
pub fn pocket(case: &Case) -> Pocket {
    Pocket {
        boundary: contour(&case.rings[0]),
        islands: case.rings[1..].iter().map(contour).collect(),
    }
}
