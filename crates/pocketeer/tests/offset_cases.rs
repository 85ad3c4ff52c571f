//! Offsets of pockets with known answers, and the invariants every offset loop must keep.

use pocketeer::geom::{Arc, Contour, Line, Pocket, Point, Segment, Tolerance};
use pocketeer::offset::{offset_contour, offset_pocket, verify_offset};
use std::f64::consts::{PI, TAU};

fn polygon(pts: &[(f64, f64)]) -> Contour {
    Contour::polygon(&pts.iter().map(|&(x, y)| Point::new(x, y)).collect::<Vec<_>>())
}

fn circle_cw(x: f64, y: f64, r: f64) -> Contour {
    Contour::new(vec![Segment::Arc(Arc::new(Point::new(x, y), r, 0.0, -TAU))])
}

/// Every loop closed, at distance d from the walls and inside the pocket.
fn check_loops(pocket: &Pocket, loops: &[Contour], d: f64) {
    if let Err(fault) = verify_offset(pocket, loops, d) {
        panic!("{fault}");
    }
}

fn area(loops: &[Contour]) -> f64 {
    loops.iter().map(Contour::signed_area).sum()
}

#[test]
fn rectangle_with_a_square_island_rounds_the_island_corners() {
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (0.0, 100.0)]),
        islands: vec![polygon(&[(40.0, 40.0), (40.0, 60.0), (60.0, 60.0), (60.0, 40.0)])],
    };
    let loops = offset_pocket(&pocket, 5.0, &Tolerance::default()).unwrap();
    assert_eq!(loops.len(), 2);
    let island = 900.0 - (4.0 - PI) * 25.0;
    assert!(
        (area(&loops) - (8100.0 - island)).abs() < 1e-9,
        "{}",
        area(&loops)
    );
    assert_eq!(loops.iter().filter(|l| l.is_ccw()).count(), 1);
    check_loops(&pocket, &loops, 5.0);
}

#[test]
fn a_distance_larger_than_the_pocket_gives_nothing() {
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]),
        islands: vec![],
    };
    assert!(offset_pocket(&pocket, 6.0, &Tolerance::default())
        .unwrap()
        .is_empty());
}

#[test]
fn a_neck_narrower_than_twice_the_distance_splits_the_pocket() {
    // Two 40 x 40 rooms joined by a corridor 4 wide.
    let pocket = Pocket {
        boundary: polygon(&[
            (0.0, 0.0),
            (40.0, 0.0),
            (40.0, 18.0),
            (60.0, 18.0),
            (60.0, 0.0),
            (100.0, 0.0),
            (100.0, 40.0),
            (60.0, 40.0),
            (60.0, 22.0),
            (40.0, 22.0),
            (40.0, 40.0),
            (0.0, 40.0),
        ]),
        islands: vec![],
    };
    let wide = offset_pocket(&pocket, 1.5, &Tolerance::default()).unwrap();
    assert_eq!(wide.len(), 1);
    check_loops(&pocket, &wide, 1.5);
    let narrow = offset_pocket(&pocket, 3.0, &Tolerance::default()).unwrap();
    assert_eq!(narrow.len(), 2);
    // Each room keeps 34 x 34, plus the sliver at the corridor's mouth between the arcs of
    // radius 3 around its two corners (4 apart): 2 ∫₀² (3 - √(9 - u²)) du.
    let integral = 2.0 * 5f64.sqrt() / 2.0 + 4.5 * (2.0f64 / 3.0).asin();
    let mouth = 2.0 * (6.0 - integral);
    assert!(
        (area(&narrow) - 2.0 * (34.0 * 34.0 + mouth)).abs() < 1e-9,
        "{}",
        area(&narrow)
    );
    check_loops(&pocket, &narrow, 3.0);
}

#[test]
fn arcs_smaller_than_the_distance_on_the_inside_disappear() {
    // A 40 x 20 slot with half-circle ends of radius 10, offset by 4: a 40 x 12 slot of radius 6.
    let p = Point::new;
    let slot = Contour::new(vec![
        Segment::Line(Line::new(p(0.0, 0.0), p(40.0, 0.0))),
        Segment::Arc(Arc::new(p(40.0, 10.0), 10.0, -PI / 2.0, PI)),
        Segment::Line(Line::new(p(40.0, 20.0), p(0.0, 20.0))),
        Segment::Arc(Arc::new(p(0.0, 10.0), 10.0, PI / 2.0, PI)),
    ]);
    let loops = offset_contour(&slot, 4.0, &Tolerance::default()).unwrap();
    assert_eq!(loops.len(), 1);
    assert!((area(&loops) - (40.0 * 12.0 + PI * 36.0)).abs() < 1e-9);
    // Outward by 5: radius 15 ends, lines moved out.
    let out = offset_contour(&slot, -5.0, &Tolerance::default()).unwrap();
    assert_eq!(out.len(), 1);
    assert!(
        (area(&out) - (40.0 * 30.0 + PI * 225.0)).abs() < 1e-9,
        "{}",
        area(&out)
    );
    // Inward by 10 or more: nothing left.
    assert!(offset_contour(&slot, 10.5, &Tolerance::default())
        .unwrap()
        .is_empty());
}

#[test]
fn islands_whose_offsets_overlap_merge() {
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (100.0, 0.0), (100.0, 60.0), (0.0, 60.0)]),
        islands: vec![circle_cw(40.0, 30.0, 5.0), circle_cw(56.0, 30.0, 5.0)],
    };
    let d = 4.0;
    let loops = offset_pocket(&pocket, d, &Tolerance::default()).unwrap();
    // The two dilated islands (radius 9, 16 apart) overlap: one loop around both.
    assert_eq!(loops.len(), 2);
    let (r, s) = (9.0f64, 16.0f64);
    let lens = 2.0 * r * r * (s / (2.0 * r)).acos() - s / 2.0 * (4.0 * r * r - s * s).sqrt();
    let expected = 92.0 * 52.0 - (2.0 * PI * r * r - lens);
    assert!(
        (area(&loops) - expected).abs() < 1e-9,
        "{} vs {expected}",
        area(&loops)
    );
    check_loops(&pocket, &loops, d);
}

#[test]
fn islands_exactly_two_d_apart_touch_without_merging_into_a_crossing_loop() {
    // Radius 5 islands whose gap is exactly 2d = 8: their offsets touch at one point.
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (100.0, 0.0), (100.0, 60.0), (0.0, 60.0)]),
        islands: vec![circle_cw(40.0, 30.0, 5.0), circle_cw(58.0, 30.0, 5.0)],
    };
    let loops = offset_pocket(&pocket, 4.0, &Tolerance::default()).unwrap();
    let expected = 92.0 * 52.0 - 2.0 * PI * 81.0;
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}: {} loops",
        area(&loops),
        loops.len()
    );
    check_loops(&pocket, &loops, 4.0);
}

#[test]
fn an_island_two_d_from_the_wall() {
    // The island's offset touches the wall's offset at one point.
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (100.0, 0.0), (100.0, 60.0), (0.0, 60.0)]),
        islands: vec![circle_cw(50.0, 13.0, 5.0)],
    };
    let loops = offset_pocket(&pocket, 4.0, &Tolerance::default()).unwrap();
    let expected = 92.0 * 52.0 - PI * 81.0;
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}: {} loops",
        area(&loops),
        loops.len()
    );
    check_loops(&pocket, &loops, 4.0);
}

#[test]
fn far_from_the_origin_and_tiny_distances() {
    for (o, d) in [(1e5, 5.0), (0.0, 1e-4), (1e5, 1e-4)] {
        let pocket = Pocket {
            boundary: polygon(&[(o, o), (o + 100.0, o), (o + 100.0, o + 60.0), (o, o + 60.0)]),
            islands: vec![circle_cw(o + 40.0, o + 30.0, 10.0)],
        };
        let tol = Tolerance::for_scale(o + 100.0, 0.001);
        let loops = offset_pocket(&pocket, d, &tol).unwrap();
        assert_eq!(loops.len(), 2, "at {o} by {d}");
        let expected = (100.0 - 2.0 * d) * (60.0 - 2.0 * d) - PI * (10.0 + d).powi(2);
        assert!(
            (area(&loops) - expected).abs() < 1e-6 * expected,
            "{} vs {expected} at {o} by {d}",
            area(&loops)
        );
    }
}

#[test]
fn an_island_edge_whose_offset_coincides_with_the_wall_offset() {
    // A square island whose bottom edge is exactly 2d above the bottom wall: the two offsets
    // run along the same line for the island's width.
    let d = 4.0;
    let pocket = Pocket {
        boundary: polygon(&[(0.0, 0.0), (100.0, 0.0), (100.0, 60.0), (0.0, 60.0)]),
        islands: vec![polygon(&[(40.0, 8.0), (40.0, 28.0), (60.0, 28.0), (60.0, 8.0)])],
    };
    let loops = offset_pocket(&pocket, d, &Tolerance::default()).unwrap();
    let island = 28.0 * 28.0 - (4.0 - PI) * 16.0;
    // Everything below the island's offset is gone only along the shared line: the area is the
    // plain difference, as the shared line has no width.
    let expected = 92.0 * 52.0 - island;
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}: {} loops",
        area(&loops),
        loops.len()
    );
    check_loops(&pocket, &loops, d);
    for l in &loops {
        assert!(
            l.signed_area().abs() > 1.0,
            "a sliver loop of area {}",
            l.signed_area()
        );
    }
}

#[test]
fn a_neck_exactly_two_d_wide() {
    let pocket = Pocket {
        boundary: polygon(&[
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
        ]),
        islands: vec![],
    };
    let loops = offset_pocket(&pocket, 3.0, &Tolerance::default()).unwrap();
    check_loops(&pocket, &loops, 3.0);
    // The corridor collapses to a line of no area: what is left is the two rooms.
    assert_eq!(loops.len(), 2);
    for l in &loops {
        assert!(l.signed_area() > 1.0, "a sliver loop of area {}", l.signed_area());
    }
}

#[test]
fn a_circle_of_2000_segments() {
    let n = 2000;
    let r = 50.0;
    let pts: Vec<(f64, f64)> = (0..n)
        .map(|k| (k as f64 / n as f64 * TAU).sin_cos())
        .map(|(s, c)| (r * c, r * s))
        .collect();
    let pocket = Pocket {
        boundary: polygon(&pts),
        islands: vec![],
    };
    let loops = offset_pocket(&pocket, 5.0, &Tolerance::default()).unwrap();
    assert_eq!(loops.len(), 1);
    // The inward offset of a regular polygon is the regular polygon of apothem smaller by d.
    let apothem = r * (PI / n as f64).cos() - 5.0;
    let expected = n as f64 * apothem * apothem * (PI / n as f64).tan();
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}",
        area(&loops)
    );
    check_loops(&pocket, &loops, 5.0);
}

/// Area of the intersection of two discs (radii `r1`, `r2`, centres `c` apart).
fn lens(r1: f64, r2: f64, c: f64) -> f64 {
    let a1 = ((c * c + r1 * r1 - r2 * r2) / (2.0 * c * r1)).acos();
    let a2 = ((c * c + r2 * r2 - r1 * r1) / (2.0 * c * r2)).acos();
    let k = ((-c + r1 + r2) * (c + r1 - r2) * (c - r1 + r2) * (c + r1 + r2)).sqrt();
    r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * k
}

#[test]
fn an_island_touching_the_wall_on_tangent_arcs() {
    // A round pocket of four tangent quarter arcs, an island circle touching it inside.
    let quarters: Vec<Segment> = (0..4)
        .map(|k| {
            Segment::Arc(Arc::new(
                Point::new(0.0, 0.0),
                50.0,
                k as f64 * PI / 2.0,
                PI / 2.0,
            ))
        })
        .collect();
    let pocket = Pocket {
        boundary: Contour::new(quarters),
        islands: vec![circle_cw(40.0, 0.0, 10.0)],
    };
    let d = 3.0;
    let loops = offset_pocket(&pocket, d, &Tolerance::default()).unwrap();
    check_loops(&pocket, &loops, d);
    // The disc of radius 47 less the island grown to 13.
    let expected = PI * 47.0 * 47.0 - lens(47.0, 13.0, 40.0);
    assert_eq!(
        loops.len(),
        1,
        "one loop around both: the island offset cuts into the wall offset"
    );
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}",
        area(&loops)
    );
}

#[test]
fn an_island_crossing_the_wall_read_from_a_drawing() {
    // A 100 x 60 rectangle drawn as lines, a circle centred on its right wall: the region is the
    // rectangle less the half disc, and its offset by 3 the rectangle shrunk by 3 less the disc
    // grown to 13 (a circular segment of it, 3 from its centre, lies inside).
    let mut text = String::from("0\nSECTION\n2\nENTITIES\n");
    let corners = [(0.0, 0.0), (100.0, 0.0), (100.0, 60.0), (0.0, 60.0)];
    for k in 0..4 {
        let ((x0, y0), (x1, y1)) = (corners[k], corners[(k + 1) % 4]);
        text += &format!("0\nLINE\n8\n0\n10\n{x0}\n20\n{y0}\n11\n{x1}\n21\n{y1}\n");
    }
    text += "0\nCIRCLE\n8\n0\n10\n100\n20\n30\n40\n10\n0\nENDSEC\n0\nEOF\n";
    let analysis = pocketeer::analyze(text.as_bytes(), &Default::default()).unwrap();
    assert_eq!(analysis.nesting.pockets.len(), 1);
    let pocket = &analysis.nesting.pockets[0];
    assert!(
        (pocket.area() - (6000.0 - PI * 50.0)).abs() < 1e-6,
        "{}",
        pocket.area()
    );
    let loops = offset_pocket(pocket, 3.0, &Tolerance::default()).unwrap();
    check_loops(pocket, &loops, 3.0);
    let (r, h) = (13.0f64, 3.0f64);
    let segment = r * r * (h / r).acos() - h * (r * r - h * h).sqrt();
    let expected = 94.0 * 54.0 - segment;
    assert_eq!(loops.len(), 1);
    assert!(
        (area(&loops) - expected).abs() < 1e-6,
        "{} vs {expected}",
        area(&loops)
    );
}
