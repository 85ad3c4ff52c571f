//! DXF entities read as exact geometry, end to end: units, coordinates far from the origin,
//! blocks, extrusion, ellipses, splines and old-style polylines.

mod common;

use common::analysis::*;
use common::*;
use pocketeer::import::Units;
use pocketeer::{analyze, ImportOptions};
use std::f64::consts::PI;

#[test]
fn inch_drawings_are_converted_to_millimetres() {
    let a = read(&Drawing::new(vec![rect_poly("0", 0.0, 0.0, 2.0, 1.0)]).units(1));
    assert_eq!(a.drawing.units, Units::Inches);
    assert!(close(pockets(&a)[0].0, 2.0 * 25.4 * 25.4, 1e-9));
    // Without $INSUNITS, millimetres unless told otherwise.
    let plain = Drawing::new(vec![rect_poly("0", 0.0, 0.0, 2.0, 1.0)]).text();
    let mm = analyze(plain.as_bytes(), &ImportOptions::default()).unwrap();
    assert!(close(pockets(&mm)[0].0, 2.0, 1e-12));
    let inch = analyze(
        plain.as_bytes(),
        &ImportOptions {
            units: Some(Units::Inches),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(close(pockets(&inch)[0].0, 2.0 * 645.16, 1e-9));
}

#[test]
fn far_from_the_origin_behaves_as_at_the_origin() {
    let build = |o: f64| {
        let mut ents = rect_lines("0", o, o, o + 100.0, o + 60.0);
        ents.push(circle("0", o + 40.0, o + 30.0, 5.0));
        ents.push(arc("0", o + 70.0, o + 30.0, 8.0, 0.0, 180.0));
        ents.push(line("0", o + 62.0, o + 30.0, o + 78.0, o + 30.0));
        read(&Drawing::new(ents))
    };
    let (near, far) = (pockets(&build(0.0)), pockets(&build(1e5)));
    assert_eq!(near.len(), far.len());
    for (a, b) in near.iter().zip(&far) {
        assert!(close(a.0, b.0, 1e-6 * a.0.abs()), "{a:?} vs {b:?}");
        assert_eq!(a.2.len(), b.2.len());
    }
}

#[test]
fn a_2000_vertex_polyline() {
    let n = 2000;
    let r = 50.0;
    let pts: Vec<(f64, f64, f64)> = (0..n)
        .map(|k| (k as f64 / n as f64 * 2.0 * PI).sin_cos())
        .map(|(s, c)| (r * c, r * s, 0.0))
        .collect();
    let a = read(&Drawing::new(vec![lwpoly("0", &pts, true)]));
    let exact = 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
    assert!(close(pockets(&a)[0].0, exact, 1e-6));
    assert_eq!(a.nesting.pockets[0].boundary.segments.len(), n);
}

#[test]
fn blocks_are_inserted_with_rotation_scale_mirror_and_nesting() {
    // A 10 x 10 square block with base point (5, 5), and a block that inserts it.
    let d = Drawing::new(vec![
        insert("0", "SQ", 0.0, 0.0, 1.0, 1.0, 30.0),
        insert("0", "SQ", 100.0, 0.0, 2.0, 0.5, 0.0),
        insert("0", "SQ", 200.0, 0.0, -1.0, 1.0, 45.0),
        insert("0", "OUTER", 300.0, 0.0, 3.0, 3.0, 90.0),
    ])
    .block("SQ", (5.0, 5.0), vec![rect_poly("0", 0.0, 0.0, 10.0, 10.0)])
    .block(
        "OUTER",
        (0.0, 0.0),
        vec![insert("0", "SQ", 5.0, 0.0, 1.0, 1.0, 0.0)],
    )
    .block(
        "UNUSED",
        (0.0, 0.0),
        vec![rect_poly("0", 0.0, 0.0, 1000.0, 1000.0)],
    );
    let a = read(&d);
    let mut areas: Vec<f64> = pockets(&a).iter().map(|p| p.0).collect();
    areas.sort_by(f64::total_cmp);
    assert_eq!(areas.len(), 4, "{areas:?}");
    for (got, want) in areas.iter().zip([100.0, 100.0, 100.0, 900.0]) {
        assert!(close(*got, want, 1e-9), "{areas:?}");
    }
    // The nested one: centre at (300, 0) + rotate90(scale 3 × (5, 0)) = (300, 15).
    let big = a
        .nesting
        .pockets
        .iter()
        .find(|p| p.area() > 800.0)
        .unwrap()
        .boundary
        .bbox();
    assert!(close(big.min.x, 285.0, 1e-9) && close(big.max.x, 315.0, 1e-9));
    assert!(close(big.min.y, 0.0, 1e-9) && close(big.max.y, 30.0, 1e-9));
}

#[test]
fn a_circle_in_a_non_uniformly_scaled_block_becomes_an_ellipse_of_arcs() {
    let d = Drawing::new(vec![insert("0", "C", 0.0, 0.0, 3.0, 1.0, 0.0)]).block(
        "C",
        (0.0, 0.0),
        vec![circle("0", 0.0, 0.0, 10.0)],
    );
    let a = read(&d);
    assert!(a
        .drawing
        .elements
        .iter()
        .all(|e| matches!(e.segment, pocketeer::geom::Segment::Arc(_))));
    // A polygon within 0.001 mm needs about ∫ sqrt(κ / 8e-3) ds chords; arcs (error falling with
    // the cube of their length, not the square) need fewer than half as many.
    let chords: f64 = (0..10_000)
        .map(|k| {
            let t = k as f64 / 10_000.0 * 2.0 * PI;
            let (a, b) = (30.0f64, 10.0f64);
            let speed = (a * a * t.sin().powi(2) + b * b * t.cos().powi(2)).sqrt();
            let curvature = a * b / speed.powi(3);
            (curvature / 8e-3).sqrt() * speed * 2.0 * PI / 10_000.0
        })
        .sum();
    let arcs = a.drawing.elements.len();
    assert!(
        arcs * 2 < chords as usize,
        "{arcs} arcs where a polygon needs {chords:.0} chords"
    );
    // Within 0.001 mm everywhere: the area is within perimeter × 0.001.
    assert!(close(pockets(&a)[0].0, PI * 30.0 * 10.0, 0.14 * 1.0));
    for k in 0..720 {
        let t = k as f64 / 720.0 * 2.0 * PI;
        let p = pocketeer::geom::Point::new(30.0 * t.cos(), 10.0 * t.sin());
        let d = a
            .drawing
            .elements
            .iter()
            .map(|e| pocketeer::geom::distance_from_segment(&e.segment, p))
            .fold(f64::INFINITY, f64::min);
        assert!(d <= 0.001, "deviation {d} at {p:?}");
    }
}

#[test]
fn extrusion_minus_z_mirrors_arcs_and_circles() {
    // In an OCS with normal (0, 0, -1), x is mirrored.
    let flipped = circle("0", 30.0, 5.0, 2.0).g(210, 0.0).g(220, 0.0).g(230, -1.0);
    let half = arc("0", 10.0, 0.0, 5.0, 0.0, 180.0)
        .g(210, 0.0)
        .g(220, 0.0)
        .g(230, -1.0);
    let chord = line("0", -15.0, 0.0, -5.0, 0.0);
    let a = read(&Drawing::new(vec![flipped, half, chord]));
    let boxes: Vec<_> = a.nesting.pockets.iter().map(|p| p.boundary.bbox()).collect();
    assert!(boxes
        .iter()
        .any(|b| close(b.min.x, -32.0, 1e-9) && close(b.max.x, -28.0, 1e-9)));
    assert!(boxes
        .iter()
        .any(|b| close(b.min.x, -15.0, 1e-9) && close(b.max.y, 5.0, 1e-9)));
}

#[test]
fn a_clockwise_slot_in_a_tilted_plane_is_a_few_elliptical_arcs() {
    // The 40 x 12 slot drawn clockwise (bulges -1) in a plane with normal (0.3, 0, 0.954):
    // seen from +z its half circles are elliptical arcs run clockwise, whose fitting took
    // 2^24 lines each (a 28 KB drawing found by fuzzing ran out of memory).
    let nz = (1.0f64 - 0.09).sqrt();
    let slot = lwpoly(
        "0",
        &[
            (0.0, 0.0, -1.0),
            (0.0, 12.0, 0.0),
            (40.0, 12.0, -1.0),
            (40.0, 0.0, 0.0),
        ],
        true,
    )
    .g(210, 0.3)
    .g(220, 0.0)
    .g(230, nz);
    let a = read(&Drawing::new(vec![slot]));
    let n = a.drawing.elements.len();
    assert!((4..100).contains(&n), "{n} elements");
    // The projected area, within perimeter × 0.001.
    let area = (480.0 + 36.0 * PI) * nz;
    assert!(
        close(pockets(&a)[0].0, area, 0.12),
        "{:?} against {area}",
        pockets(&a)
    );
}

#[test]
fn ellipse_entities_become_arcs_within_a_micrometre() {
    let e = Entity::new("ELLIPSE", "0")
        .g(10, 5.0)
        .g(20, 5.0)
        .g(11, 20.0)
        .g(21, 0.0)
        .g(40, 0.4)
        .g(41, 0.0)
        .g(42, 2.0 * PI);
    let a = read(&Drawing::new(vec![e]));
    assert!(a
        .drawing
        .elements
        .iter()
        .all(|e| matches!(e.segment, pocketeer::geom::Segment::Arc(_))));
    assert!(close(pockets(&a)[0].0, PI * 20.0 * 8.0, 0.1));
}

#[test]
fn a_rational_spline_circle_is_read_as_arcs() {
    // The exact NURBS circle of radius 10: degree 2, nine control points.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let cps = [
        (10.0, 0.0, 1.0),
        (10.0, 10.0, w),
        (0.0, 10.0, 1.0),
        (-10.0, 10.0, w),
        (-10.0, 0.0, 1.0),
        (-10.0, -10.0, w),
        (0.0, -10.0, 1.0),
        (10.0, -10.0, w),
        (10.0, 0.0, 1.0),
    ];
    let mut e = Entity::new("SPLINE", "0")
        .g(70, 1 | 4)
        .g(71, 2)
        .g(72, 12)
        .g(73, 9);
    for k in [0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0] {
        e = e.g(40, k);
    }
    for (x, y, wt) in cps {
        e = e.g(10, x).g(20, y).g(30, 0.0).g(41, wt);
    }
    let a = read(&Drawing::new(vec![e]));
    assert!(close(pockets(&a)[0].0, 100.0 * PI, 1e-3), "{:?}", pockets(&a));
    for el in &a.drawing.elements {
        for k in 0..=8 {
            let p = el.segment.point_at(k as f64 / 8.0);
            assert!((p.distance(pocketeer::geom::Point::ORIGIN) - 10.0).abs() <= 0.001);
        }
    }
}

#[test]
fn old_style_polylines_with_vertex_bulges() {
    // POLYLINE / VERTEX / SEQEND: a 20 x 10 slot with half-circle ends (bulge 1).
    let mut ents = vec![Entity::new("POLYLINE", "0")
        .g(66, 1)
        .g(70, 1)
        .g(10, 0)
        .g(20, 0)
        .g(30, 0)];
    for (x, y, b) in [
        (0.0, 0.0, 0.0),
        (20.0, 0.0, 1.0),
        (20.0, 10.0, 0.0),
        (0.0, 10.0, 1.0),
    ] {
        ents.push(Entity::new("VERTEX", "0").g(10, x).g(20, y).g(42, b));
    }
    ents.push(Entity::new("SEQEND", "0"));
    let a = read(&Drawing::new(ents));
    assert!(close(pockets(&a)[0].0, 200.0 + 25.0 * PI, 1e-9));
}

#[test]
fn a_spline_given_by_fit_points_passes_through_them() {
    // Fit points on a circle of radius 20, first and last equal: a closed curve.
    let n = 24;
    let mut e = Entity::new("SPLINE", "0").g(70, 8).g(71, 3).g(74, n + 1);
    let pts: Vec<(f64, f64)> = (0..=n)
        .map(|k| (k as f64 / n as f64 * 2.0 * PI).sin_cos())
        .map(|(s, c)| (20.0 * c, 20.0 * s))
        .collect();
    for &(x, y) in &pts {
        e = e.g(11, x).g(21, y).g(31, 0.0);
    }
    let a = read(&Drawing::new(vec![e]));
    let segs: Vec<_> = a.drawing.elements.iter().map(|e| e.segment).collect();
    for &(x, y) in &pts {
        let p = pocketeer::geom::Point::new(x, y);
        let d = segs
            .iter()
            .map(|s| pocketeer::geom::distance_from_segment(s, p))
            .fold(f64::INFINITY, f64::min);
        assert!(d <= 0.001, "fit point {p:?} is {d} from the curve");
    }
    // An interpolating cubic through 24 points of a circle stays very near the circle.
    assert!(close(pockets(&a)[0].0, 400.0 * PI, 1.0), "{:?}", pockets(&a));
}

/// A closed spline of degree 1 through `corners` (the first repeated at the end).
fn closed_polygon_spline(layer: &str, corners: &[(f64, f64)]) -> Entity {
    let n = corners.len() + 1;
    let mut e = Entity::new("SPLINE", layer)
        .g(70, 1)
        .g(71, 1)
        .g(72, n + 2)
        .g(73, n);
    let knots: Vec<f64> = std::iter::once(0.0)
        .chain((0..n).map(|k| k as f64))
        .chain(std::iter::once((n - 1) as f64))
        .collect();
    for k in knots {
        e = e.g(40, k);
    }
    for &(x, y) in corners.iter().chain(&corners[..1]) {
        e = e.g(10, x).g(20, y).g(30, 0.0);
    }
    e
}

/// Closed splines are whole contours: two that share a stretch (overlapping shapes in traced
/// art) stay two closed contours, which nesting merges, instead of losing the shared stretch
/// to duplicate removal and leaving an open chain.
#[test]
fn closed_splines_sharing_a_stretch_stay_closed_and_merge() {
    let a = closed_polygon_spline("0", &[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
    let b = closed_polygon_spline("0", &[(10.0, 0.0), (20.0, 0.0), (20.0, 10.0), (10.0, 10.0)]);
    let r = read(&Drawing::new(vec![a, b]));
    assert!(r.chains.open.is_empty(), "{:?}", r.chains.open);
    assert_eq!(r.chains.contours.len(), 2);
    assert_eq!(r.chains.duplicates_dropped, 0);
    let p = pockets(&r);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(close(p[0].0, 200.0, 1e-6), "{p:?}");
}

/// A full ELLIPSE written to six digits (0 to 6.28318, short of 2π by 5e-6) is a whole
/// contour, like a closed spline: no gap to close, and no duplicate removal cuts into it.
#[test]
fn a_full_ellipse_written_to_six_digits_is_a_closed_contour() {
    let e = Entity::new("ELLIPSE", "0")
        .g(10, 0.0)
        .g(20, 0.0)
        .g(11, 8.77715)
        .g(21, 7.66376)
        .g(40, 0.286616)
        .g(41, 0.0)
        // 2π to six digits, as the writer put it (not the constant: that is the point).
        .g(42, (2.0 * PI * 1e5).floor() / 1e5);
    let a = read(&Drawing::new(vec![e]));
    assert!(a.drawing.elements.iter().all(|e| e.closed_group.is_some()));
    assert_eq!(a.chains.contours.len(), 1);
    assert!(a.chains.warnings.is_empty(), "{:?}", a.chains.warnings);
    let major = 8.77715f64.hypot(7.66376);
    let area = PI * major * major * 0.286616;
    // Within the arcs' 1 µm of the ellipse along its 53 mm.
    assert!(close(pockets(&a)[0].0, area, 0.06), "{:?} vs {area}", pockets(&a));
}
