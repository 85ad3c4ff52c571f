//! Where do pocketeer and cavalier_contours differ on the smooth profile with arcs at d = 30?
//! Checks the loops' corners and every vertex against exact distances to the profile, and
//! computes the area of our loop a second way (polygon plus circular segments by series):
//! `cargo run --release --bin tipcheck -- 100000`.

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use pocketeer::geom::*;
use pocketeer_bench::cases;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100000);
    let case = cases::smooth(n, true);
    let pocket = pocketeer_bench::pocket(&case);
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let d = 30.0;
    let loops = pocketeer::offset::offset_pocket(&pocket, d, &tol).unwrap();
    let segs = &loops[0].segments;
    let profile = SegmentIndex::new(&pocket.boundary.segments);
    // Corners: joints where the direction turns by more than 0.2 rad.
    let m = segs.len();
    let mut corners = Vec::new();
    for i in 0..m {
        let (a, b) = (&segs[i], &segs[(i + 1) % m]);
        let (t0, t1) = (a.tangent_at(1.0), b.tangent_at(0.0));
        let turn = t0.cross(t1).atan2(t0.dot(t1));
        if turn.abs() > 0.05 {
            corners.push((i, turn, a.end()));
        }
    }
    println!("{} segments, {} corners", m, corners.len());
    for &(i, turn, p) in corners.iter().take(14) {
        let (a, b) = (&segs[i], &segs[(i + 1) % m]);
        let bis = (a.tangent_at(1.0) - b.tangent_at(0.0))
            .normalized()
            .unwrap_or_default();
        // Outside the region across the corner: away from the left of both tangents.
        let out = -(a.tangent_at(1.0).perp() + b.tangent_at(0.0).perp())
            .normalized()
            .unwrap_or_default();
        let _ = bis;
        let mut line = format!(
            "corner {i} turn {turn:.3} at ({:.4},{:.4}) dist {:.7}",
            p.x,
            p.y,
            profile.distance(p)
        );
        for e in [1e-4, 1e-3, 1e-2] {
            let q = p + out * e;
            line += &format!(" | out {e}: {:.7}", profile.distance(q));
        }
        println!("{line}");
    }

    let mut pl = Polyline::new_closed();
    for &(x, y, b) in &case.rings[0] {
        pl.add(x, y, b);
    }
    let shape = Shape::from_plines([pl]);
    let theirs = shape.parallel_offset(d, &ShapeOffsetOptions::default());
    let mut worst: (f64, f64) = (0.0, 0.0);
    let mut count = 0;
    for p in theirs.ccw_plines.iter().chain(&theirs.cw_plines) {
        let pl = &p.polyline;
        for k in 0..pl.vertex_count() {
            let v = pl.at(k);
            let dist = profile.distance(Point::new(v.x, v.y));
            worst.0 = worst.0.min(dist - d);
            worst.1 = worst.1.max(dist - d);
            if (dist - d).abs() > 1e-6 {
                count += 1;
            }
        }
        println!("cavalier loop: {} vertices", pl.vertex_count());
    }
    println!(
        "cavalier vertices off by more than 1e-6: {count}; range {:?}",
        worst
    );
    let mut worst2: (f64, f64) = (0.0, 0.0);
    let mut count2 = 0;
    for s in segs {
        for t in [0.0, 0.5] {
            let dist = profile.distance(s.point_at(t));
            worst2.0 = worst2.0.min(dist - d);
            worst2.1 = worst2.1.max(dist - d);
            if (dist - d).abs() > 1e-6 {
                count2 += 1;
            }
        }
    }
    println!("ours off by more than 1e-6: {count2}; range {:?}", worst2);

    // Area two ways: ours, and the polygon through every start and end point (a gap between
    // one piece's end and the next one's start, up to some 1e-8 mm, is a side of it) plus
    // each arc's circular segment.
    let mut poly = 0.0;
    let mut segs_area = 0.0;
    let o = segs[0].start();
    let mut from = segs[segs.len() - 1].end() - o;
    for s in segs {
        let (a, b) = (s.start() - o, s.end() - o);
        poly += 0.5 * (from.cross(a) + a.cross(b));
        from = b;
        if let Segment::Arc(arc) = s {
            let th = arc.sweep().abs();
            // theta - sin(theta) by its series for small angles.
            let tms = if th < 1e-2 {
                th.powi(3) / 6.0 - th.powi(5) / 120.0 + th.powi(7) / 5040.0
            } else {
                th - th.sin()
            };
            segs_area += arc.sweep().signum() * 0.5 * arc.radius() * arc.radius() * tms;
        }
    }
    let cav: f64 = theirs
        .ccw_plines
        .iter()
        .chain(&theirs.cw_plines)
        .map(|p| p.polyline.area())
        .sum();
    println!(
        "ours {:.7} independent {:.7} cavalier {:.7}",
        loops[0].signed_area(),
        poly + segs_area,
        cav
    );
}
