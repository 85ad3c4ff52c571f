//! Drawings built in code, read end to end: DXF text → elements → contours → pockets.

mod common;

use common::*;
use pocketeer::import::{ImportError, ImportWarning, Units};
use pocketeer::{analyze, Analysis, ImportOptions};
use std::f64::consts::PI;

fn read(d: &Drawing) -> Analysis {
    analyze(d.text().as_bytes(), &ImportOptions::default()).expect("drawing should import")
}

fn read_err(d: &Drawing) -> ImportError {
    match analyze(d.text().as_bytes(), &ImportOptions::default()) {
        Ok(_) => panic!("drawing should be refused"),
        Err(e) => e,
    }
}

/// (net area, boundary area, island areas) of every pocket.
fn pockets(a: &Analysis) -> Vec<(f64, f64, Vec<f64>)> {
    a.nesting
        .pockets
        .iter()
        .map(|p| {
            let mut isl: Vec<f64> = p.islands.iter().map(|c| -c.signed_area()).collect();
            isl.sort_by(f64::total_cmp);
            (p.area(), p.boundary.signed_area(), isl)
        })
        .collect()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn rectangle_with_a_circle_island_in_any_order_and_direction() {
    let mut rng = Rng(7);
    for _ in 0..20 {
        let mut ents = rect_lines("0", 0.0, 0.0, 100.0, 60.0);
        ents.push(circle("0", 40.0, 30.0, 5.0));
        // Reverse some lines and shuffle everything.
        for e in ents.iter_mut().filter(|e| e.kind == "LINE") {
            if rng.below(2) == 1 {
                let (a, b) = (e.groups[1].1.clone(), e.groups[2].1.clone());
                e.groups[1].1 = e.groups[3].1.clone();
                e.groups[2].1 = e.groups[4].1.clone();
                e.groups[3].1 = a;
                e.groups[4].1 = b;
            }
        }
        rng.shuffle(&mut ents);
        let a = read(&Drawing::new(ents));
        let p = pockets(&a);
        assert_eq!(p.len(), 1);
        assert!(close(p[0].0, 6000.0 - 25.0 * PI, 1e-9), "{p:?}");
        assert!(a.nesting.pockets[0].boundary.is_ccw());
        assert!(!a.nesting.pockets[0].islands[0].is_ccw());
    }
}

#[test]
fn lwpolyline_bulges_are_exact_arcs() {
    // A 40 x 12 slot: two half circles of radius 6 joined by lines.
    let slot = lwpoly(
        "0",
        &[
            (0.0, 0.0, 0.0),
            (40.0, 0.0, 1.0),
            (40.0, 12.0, 0.0),
            (0.0, 12.0, 1.0),
        ],
        true,
    );
    let a = read(&Drawing::new(vec![slot]));
    assert_eq!(a.drawing.elements.len(), 4);
    assert!(close(pockets(&a)[0].0, 480.0 + 36.0 * PI, 1e-9));
}

#[test]
fn polyline_whose_last_point_repeats_the_first_closes() {
    let open_but_closed = lwpoly(
        "0",
        &[
            (0.0, 0.0, 0.0),
            (10.0, 0.0, 0.0),
            (10.0, 10.0, 0.0),
            (0.0, 0.0, 0.0),
        ],
        false,
    );
    let a = read(&Drawing::new(vec![open_but_closed]));
    assert!(close(pockets(&a)[0].0, 50.0, 1e-9));
    assert!(a.chains.open.is_empty());
}

#[test]
fn gaps_below_the_tolerance_close_and_a_duplicated_edge_is_dropped() {
    let g = 0.0004;
    let mut ents = vec![
        line("0", 0.0, 0.0, 50.0, g),
        line("0", 50.0, 0.0, 50.0 - g, 30.0),
        line("0", 50.0, 30.0, 0.0, 30.0 + g),
        line("0", 0.0, 30.0, g, 0.0),
    ];
    ents.push(line("0", 50.0, 30.0, 0.0, 30.0));
    let a = read(&Drawing::new(ents));
    assert_eq!(a.chains.contours.len(), 1);
    assert_eq!(a.chains.duplicates_dropped, 1);
    assert!(a.chains.gaps_closed >= 3);
    assert!(a.chains.largest_gap <= 0.001);
    assert!(close(pockets(&a)[0].0, 1500.0, 0.1));
    // Joined ends are moved onto one node: the contour closes exactly.
    let segs = &a.nesting.pockets[0].boundary.segments;
    for k in 0..segs.len() {
        assert_eq!(segs[k].end(), segs[(k + 1) % segs.len()].start());
    }
}

#[test]
fn a_gap_above_the_tolerance_leaves_an_open_chain_that_names_its_ends() {
    let ents = vec![
        line("0", 0.0, 0.0, 10.0, 0.0),
        line("0", 10.0, 0.0, 10.0, 10.0),
        line("0", 10.0, 10.0, 0.0, 0.005),
    ];
    let err = read_err(&Drawing::new(ents));
    let msg = err.to_string();
    assert!(matches!(err, ImportError::NoClosedContour { .. }), "{msg}");
    assert!(
        msg.contains("(0.0000, 0.0050)") && msg.contains("(0.0000, 0.0000)"),
        "{msg}"
    );
    // A larger join tolerance closes it.
    let opts = ImportOptions {
        join_tolerance: 0.01,
        ..Default::default()
    };
    let ents = vec![
        line("0", 0.0, 0.0, 10.0, 0.0),
        line("0", 10.0, 0.0, 10.0, 10.0),
        line("0", 10.0, 10.0, 0.0, 0.005),
    ];
    assert!(analyze(Drawing::new(ents).text().as_bytes(), &opts).is_ok());
}

#[test]
fn a_pocket_inside_an_island_is_a_pocket_of_its_own() {
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 100.0, 100.0),
        rect_poly("0", 20.0, 20.0, 80.0, 80.0),
        rect_poly("0", 40.0, 40.0, 60.0, 60.0),
    ];
    let a = read(&Drawing::new(ents));
    assert_eq!(a.nesting.depths, vec![0, 1, 2]);
    let p = pockets(&a);
    assert_eq!(p.len(), 2);
    assert!(close(p[0].0, 10000.0 - 3600.0, 1e-9) && p[0].2.len() == 1);
    assert!(close(p[1].0, 400.0, 1e-9) && p[1].2.is_empty());
}

#[test]
fn several_separate_pockets() {
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 10.0, 10.0),
        rect_poly("0", 20.0, 0.0, 30.0, 10.0),
        circle("0", 50.0, 5.0, 5.0),
    ];
    assert_eq!(pockets(&read(&Drawing::new(ents))).len(), 3);
}

#[test]
fn overlapping_islands_merge_into_one() {
    let (r, d) = (10.0f64, 10.0f64);
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 100.0, 60.0),
        circle("0", 40.0, 30.0, r),
        circle("0", 40.0 + d, 30.0, r),
    ];
    let a = read(&Drawing::new(ents));
    let lens = 2.0 * r * r * (d / (2.0 * r)).acos() - d / 2.0 * (4.0 * r * r - d * d).sqrt();
    let union = 2.0 * PI * r * r - lens;
    let p = pockets(&a);
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].2.len(), 1, "the two islands become one");
    assert!(
        close(p[0].0, 6000.0 - union, 1e-6),
        "{} vs {}",
        p[0].0,
        6000.0 - union
    );
    assert!(a
        .nesting
        .warnings
        .iter()
        .any(|w| matches!(w, ImportWarning::ContoursMeet { merged: true, .. })));
}

#[test]
fn islands_sharing_an_edge_merge() {
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 100.0, 60.0),
        rect_poly("0", 10.0, 10.0, 30.0, 30.0),
        rect_poly("0", 30.0, 10.0, 50.0, 30.0),
    ];
    let p = pockets(&read(&Drawing::new(ents)));
    assert_eq!(p[0].2.len(), 1);
    assert!(close(p[0].0, 6000.0 - 800.0, 1e-6), "{p:?}");
}

#[test]
fn an_island_crossing_the_wall_cuts_the_pocket_back() {
    // Circle of radius 10 whose centre is 3 mm inside the right wall: most of it is in the pocket.
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 100.0, 60.0),
        circle("0", 97.0, 30.0, 10.0),
    ];
    let a = read(&Drawing::new(ents));
    let p = pockets(&a);
    assert_eq!(p.len(), 1);
    assert!(p[0].2.is_empty(), "the island became part of the wall");
    let (r, h) = (10.0f64, 3.0f64);
    let outside = r * r * (h / r).acos() - h * (r * r - h * h).sqrt();
    assert!(close(p[0].0, 6000.0 - (PI * r * r - outside), 1e-6), "{p:?}");
    assert!(a
        .nesting
        .warnings
        .iter()
        .any(|w| matches!(w, ImportWarning::ContoursMeet { merged: false, .. })));
}

#[test]
fn an_island_touching_the_wall_stays_an_island() {
    let ents = vec![
        rect_poly("0", 0.0, 0.0, 100.0, 60.0),
        circle("0", 50.0, 10.0, 10.0),
    ];
    let p = pockets(&read(&Drawing::new(ents)));
    assert_eq!(p.len(), 1);
    assert!(close(p[0].0, 6000.0 - 100.0 * PI, 1e-6), "{p:?}");
}

#[test]
fn a_figure_eight_is_refused_with_its_crossing_point() {
    let eight = lwpoly(
        "0",
        &[
            (0.0, 0.0, 0.0),
            (10.0, 10.0, 0.0),
            (10.0, 0.0, 0.0),
            (0.0, 10.0, 0.0),
        ],
        true,
    );
    let err = read_err(&Drawing::new(vec![eight]));
    assert!(matches!(err, ImportError::SelfCrossing { .. }));
    assert!(err.to_string().contains("(5.0000, 5.0000)"), "{err}");
}

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
            .map(|e| pocketeer::geom::point_distance(&e.segment, p))
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
fn paper_space_is_ignored_and_layers_filter() {
    let ents = vec![
        rect_poly("cut", 0.0, 0.0, 10.0, 10.0),
        rect_poly("engrave", 20.0, 0.0, 30.0, 10.0),
        rect_poly("cut", 100.0, 0.0, 200.0, 100.0).g(67, 1),
    ];
    let text = Drawing::new(ents).text();
    let all = analyze(text.as_bytes(), &ImportOptions::default()).unwrap();
    assert_eq!(all.nesting.pockets.len(), 2);
    let only = analyze(
        text.as_bytes(),
        &ImportOptions {
            layers: Some(vec!["CUT".into()]),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(only.nesting.pockets.len(), 1);
    assert!(close(only.nesting.pockets[0].area(), 100.0, 1e-9));
}

#[test]
fn refusals_name_what_is_wrong() {
    let empty = Drawing::new(vec![]);
    assert!(matches!(read_err(&empty), ImportError::EmptyModelSpace));
    let text_only = Drawing::new(vec![Entity::new("TEXT", "0").g(10, 0).g(20, 0).g(1, "hello")]);
    assert!(read_err(&text_only).to_string().contains("1 TEXT"));
    let nan = Drawing::new(vec![line("walls", 0.0, 0.0, f64::NAN, 1.0).g(5, "2A")]);
    let msg = read_err(&nan).to_string();
    assert!(
        msg.contains("LINE (handle 2A) on layer 'walls'") && msg.contains("not a number"),
        "{msg}"
    );
    let huge = Drawing::new(vec![line("0", 0.0, 0.0, 1e300, 1.0)]);
    assert!(
        read_err(&huge).to_string().contains("1e300"),
        "{}",
        read_err(&huge)
    );
    let selfish = Drawing::new(vec![insert("0", "A", 0.0, 0.0, 1.0, 1.0, 0.0)])
        .block("A", (0.0, 0.0), vec![insert("0", "B", 1.0, 0.0, 1.0, 1.0, 0.0)])
        .block("B", (0.0, 0.0), vec![insert("0", "A", 1.0, 0.0, 1.0, 1.0, 0.0)]);
    let msg = read_err(&selfish).to_string();
    assert!(
        msg.contains("inserts itself") && msg.contains("A → B → A"),
        "{msg}"
    );
    let text = Drawing::new(vec![rect_poly("0", 0.0, 0.0, 10.0, 10.0)]).text();
    let cut = &text[..text.find("ENDSEC\n  0\nEOF").unwrap() - 4];
    let err = analyze(cut.as_bytes(), &ImportOptions::default()).unwrap_err();
    assert!(matches!(err, ImportError::Truncated { .. }), "{err}");
    assert!(matches!(
        analyze(b"%PDF-1.4 not a drawing", &ImportOptions::default()),
        Err(ImportError::NotDxf(_))
    ));
    assert!(matches!(
        analyze(b"", &ImportOptions::default()),
        Err(ImportError::NotDxf(_))
    ));
}

#[test]
fn an_outline_with_a_gap_around_islands_is_refused() {
    // The wall misses its start by 0.5 mm: pocketing the island alone would be wrong.
    let wall = lwpoly(
        "0",
        &[
            (0.5, 0.0, 0.0),
            (100.0, 0.0, 0.0),
            (100.0, 60.0, 0.0),
            (0.0, 60.0, 0.0),
            (0.0, 0.0, 0.0),
        ],
        false,
    );
    let d = Drawing::new(vec![wall, circle("0", 50.0, 30.0, 10.0)]);
    let err = read_err(&d);
    let msg = err.to_string();
    assert!(
        matches!(err, ImportError::OpenOutline { surrounded: 1, .. }),
        "{msg}"
    );
    // The error names the free end and carries the gap; the CLI words the advice.
    assert!(msg.contains("(0.5000, 0.0000)"), "{msg}");
    assert!(
        matches!(err, ImportError::OpenOutline { gap: Some(g), .. } if (g - 0.5).abs() < 1e-9),
        "{err:?}"
    );
    let ignore = ImportOptions {
        ignore_open: true,
        ..Default::default()
    };
    let a = analyze(d.text().as_bytes(), &ignore).unwrap();
    assert_eq!(a.nesting.pockets.len(), 1);
}

#[test]
fn a_closed_polyline_without_area_is_not_a_contour() {
    let there_and_back = lwpoly("0", &[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)], true);
    let a = read(&Drawing::new(vec![
        there_and_back,
        rect_poly("0", 20.0, 0.0, 30.0, 10.0),
    ]));
    assert_eq!(a.chains.contours.len(), 1);
    assert!(a
        .chains
        .warnings
        .iter()
        .any(|w| matches!(w, ImportWarning::NoArea { elements: 2, .. })));
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
            .map(|s| pocketeer::geom::point_distance(s, p))
            .fold(f64::INFINITY, f64::min);
        assert!(d <= 0.001, "fit point {p:?} is {d} from the curve");
    }
    // An interpolating cubic through 24 points of a circle stays very near the circle.
    assert!(close(pockets(&a)[0].0, 400.0 * PI, 1.0), "{:?}", pockets(&a));
}
