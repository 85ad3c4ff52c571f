//! Runs only pocketeer's offsets of one smooth-profile case, for profiling:
//! `cargo run --release --bin ours -- N lines|arcs`.

use pocketeer::geom::{Arc, Contour, Line, Point, Segment, Tolerance};
use pocketeer::import::Pocket;
use pocketeer_bench::cases;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let case = cases::smooth(n, args.get(2).is_some_and(|s| s == "arcs"));
    let ring = &case.rings[0];
    let m = ring.len();
    let segs = (0..m)
        .map(|k| {
            let (x0, y0, b) = ring[k];
            let (x1, y1, _) = ring[(k + 1) % m];
            let (a, e) = (Point::new(x0, y0), Point::new(x1, y1));
            Arc::from_bulge(a, e, b)
                .map(Segment::Arc)
                .unwrap_or(Segment::Line(Line::new(a, e)))
        })
        .collect();
    let pocket = Pocket {
        boundary: Contour::new(segs),
        islands: vec![],
    };
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let total: f64 = case
        .distances
        .iter()
        .map(|&d| {
            pocketeer::offset::offset_pocket(&pocket, d, &tol)
                .iter()
                .map(Contour::signed_area)
                .sum::<f64>()
        })
        .sum();
    println!("{total}");
}
