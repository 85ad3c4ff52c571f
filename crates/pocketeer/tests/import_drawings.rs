//! Drawings built in code, read end to end: DXF text → elements → contours → pockets. How
//! elements chain, how contours nest, and what is refused; the entities themselves are in
//! `import_entities.rs`.

mod common;

use common::analysis::*;
use common::*;
use pocketeer::import::{FillRule, ImportError, ImportWarning};
use pocketeer::{analyze, Analysis, ImportOptions};
use std::f64::consts::PI;

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

fn outline(pts: &[(f64, f64)]) -> Drawing {
    let pts: Vec<(f64, f64, f64)> = pts.iter().map(|&(x, y)| (x, y, 0.0)).collect();
    Drawing::new(vec![lwpoly("0", &pts, true)])
}

fn filled_with(d: &Drawing, fill: FillRule) -> Analysis {
    let opts = ImportOptions {
        fill,
        ..Default::default()
    };
    analyze(d.text().as_bytes(), &opts).unwrap()
}

#[test]
fn a_bow_tie_becomes_two_triangles_touching_at_its_crossing() {
    let eight = outline(&[(0.0, 0.0), (10.0, 10.0), (10.0, 0.0), (0.0, 10.0)]);
    let a = read(&eight);
    let p = pockets(&a);
    assert_eq!(p.len(), 2, "{p:?}");
    for (area, _, islands) in &p {
        assert!(close(*area, 25.0, 1e-9) && islands.is_empty(), "{p:?}");
    }
    let filled: Vec<_> = a
        .nesting
        .warnings
        .iter()
        .filter_map(|w| match w {
            ImportWarning::SelfCrossingFilled { at, loops, .. } => Some((at.clone(), *loops)),
            _ => None,
        })
        .collect();
    assert_eq!(filled.len(), 1, "{:?}", a.nesting.warnings);
    assert_eq!(filled[0].1, 2);
    assert_eq!(filled[0].0.len(), 1);
    assert!(filled[0].0[0].distance(pocketeer::geom::Point::new(5.0, 5.0)) < 1e-9);
    // --strict refuses it, naming the crossing.
    let strict = ImportOptions {
        strict: true,
        ..Default::default()
    };
    let err = analyze(eight.text().as_bytes(), &strict).unwrap_err();
    assert!(matches!(err, ImportError::SelfCrossing { .. }));
    assert!(err.to_string().contains("(5.0000, 5.0000)"), "{err}");
}

#[test]
fn an_outline_touching_itself_becomes_the_loops_it_bounds() {
    // Two squares sharing a corner drawn as one outline.
    let two = outline(&[
        (0.0, 0.0),
        (10.0, 0.0),
        (10.0, 10.0),
        (20.0, 10.0),
        (20.0, 20.0),
        (10.0, 20.0),
        (10.0, 10.0),
        (0.0, 10.0),
    ]);
    let p = pockets(&read(&two));
    assert_eq!(p.len(), 2, "{p:?}");
    assert!(p.iter().all(|q| close(q.0, 100.0, 1e-9)), "{p:?}");
    // A notch whose tip touches the opposite edge: two quadrilaterals meeting at its tip.
    let notch = outline(&[
        (0.0, 0.0),
        (20.0, 0.0),
        (20.0, 10.0),
        (12.0, 10.0),
        (10.0, 0.0),
        (8.0, 10.0),
        (0.0, 10.0),
    ]);
    let p = pockets(&read(&notch));
    assert_eq!(p.len(), 2, "{p:?}");
    assert!(close(p[0].0 + p[1].0, 200.0 - 20.0, 1e-9), "{p:?}");
}

#[test]
fn a_star_drawn_in_one_stroke_is_filled_by_the_rule_asked_for() {
    // A pentagram: its centre pentagon is wound round twice.
    let star: Vec<(f64, f64)> = (0..5)
        .map(|k| {
            let a = PI / 2.0 + k as f64 * 4.0 * PI / 5.0;
            (50.0 * a.cos(), 50.0 * a.sin())
        })
        .collect();
    let d = outline(&star);
    let even = pockets(&filled_with(&d, FillRule::EvenOdd));
    let nonzero = pockets(&filled_with(&d, FillRule::NonZero));
    // Even-odd: five points round a hole (the centre pentagon an island, or five separate
    // triangles touching at their corners); non-zero: the whole star, no hole.
    let even_area: f64 = even.iter().map(|p| p.0).sum();
    let nonzero_area: f64 = nonzero.iter().map(|p| p.0).sum();
    // The inner pentagon's circumradius is R (cos 72° / cos 36°).
    let r = 50.0 * (2.0 * PI / 5.0).cos() / (PI / 5.0).cos();
    let pentagon = 2.5 * r * r * (2.0 * PI / 5.0).sin();
    assert_eq!(nonzero.len(), 1, "{nonzero:?}");
    assert!(nonzero[0].2.is_empty());
    assert!(
        close(nonzero_area - even_area, pentagon, 1e-6),
        "{even_area} {nonzero_area} {pentagon}"
    );
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
        matches!(err, ImportError::OpenOutline { gap: Some(g), .. } if (g.length - 0.5).abs() < 1e-9 && g.unambiguous),
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
fn a_centre_mark_over_a_hole_is_a_stroke_not_an_outline() {
    // Two lines crossing over a hole "surround" it by their extent, but close round nothing.
    let mut ents = rect_lines("0", 0.0, 0.0, 100.0, 60.0);
    ents.push(circle("0", 50.0, 30.0, 5.0));
    ents.push(line("0", 42.0, 30.0, 58.0, 30.0));
    ents.push(line("0", 50.0, 22.0, 50.0, 38.0));
    // A U-shaped construction stroke round the hole, open by more than a tenth of its length.
    ents.push(lwpoly(
        "0",
        &[
            (40.0, 45.0, 0.0),
            (40.0, 15.0, 0.0),
            (60.0, 15.0, 0.0),
            (60.0, 45.0, 0.0),
        ],
        false,
    ));
    let a = read(&Drawing::new(ents));
    assert_eq!(a.chains.open.len(), 3);
    let p = pockets(&a);
    assert_eq!(p.len(), 1);
    assert!(close(p[0].0, 6000.0 - 25.0 * PI, 1e-9), "{p:?}");
}

#[test]
fn a_broken_island_inside_a_pocket_is_refused() {
    // An island outline missing closing by 0.4 mm inside a closed wall: ignoring it would cut
    // through the island.
    let island = lwpoly(
        "0",
        &[
            (30.4, 20.0, 0.0),
            (70.0, 20.0, 0.0),
            (70.0, 40.0, 0.0),
            (30.0, 40.0, 0.0),
            (30.0, 20.0, 0.0),
        ],
        false,
    );
    let d = Drawing::new(vec![rect_poly("0", 0.0, 0.0, 100.0, 60.0), island]);
    let err = read_err(&d);
    assert!(
        matches!(err, ImportError::OpenOutline { surrounded: 0, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("lies inside a closed contour"), "{err}");
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
