//! Prints, level by level, where pocketeer's and cavalier_contours' offset areas differ for the
//! smooth-profile case: `cargo run --release --bin levels -- N arcs|lines`.

use pocketeer_bench::cases;

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use pocketeer::geom::{Contour, Tolerance};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1000);
    let arcs = args.get(2).is_some_and(|s| s == "arcs");
    let case = cases::smooth(n, arcs);
    let pocket = pocketeer_bench::pocket(&case);
    let ring = &case.rings[0];
    let mut p = Polyline::new_closed();
    for &(x, y, b) in ring {
        p.add(x, y, b);
    }
    let shape = Shape::from_plines([p]);
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    for &d in &case.distances {
        let ours = pocketeer::offset::offset_pocket(&pocket, d, &tol).unwrap();
        let theirs = shape.parallel_offset(d, &ShapeOffsetOptions::default());
        let a: f64 = ours.iter().map(Contour::signed_area).sum();
        let b: f64 = theirs
            .ccw_plines
            .iter()
            .chain(&theirs.cw_plines)
            .map(|p| p.polyline.area())
            .sum();
        let flag = if (a - b).abs() > 1e-6 * b.abs().max(1.0) {
            "  <-- differs"
        } else {
            ""
        };
        println!(
            "d {d:6.2}: ours {a:12.4} ({} loops)  cavalier {b:12.4} ({} loops){flag}",
            ours.len(),
            theirs.ccw_plines.len() + theirs.cw_plines.len()
        );
    }
}
