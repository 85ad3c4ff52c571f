//! Real drawings from other CAD programs (copied from the shared corpus, see
//! fixtures/corpus/LICENSES.md), with areas measured independently.

mod common;

use common::fixture;
use pocketeer::import::ImportError;
use pocketeer::{analyze, read_drawing, Analysis, ImportOptions};

fn analyze_file(rel: &str) -> Result<Analysis, ImportError> {
    let bytes = std::fs::read(fixture(rel)).expect("fixture exists");
    analyze(&bytes, &ImportOptions::default())
}

#[test]
fn empty_handles_is_one_pocket_with_one_island() {
    let a = analyze_file("corpus/mit/empty_handles.dxf").unwrap();
    assert_eq!(a.nesting.pockets.len(), 1);
    let p = &a.nesting.pockets[0];
    assert!((p.boundary.signed_area() - 56100.0).abs() < 1e-6);
    assert_eq!(p.islands.len(), 1);
    assert!((p.islands[0].signed_area() + 1292.0).abs() < 1e-6);
}

#[test]
fn rotated_inserts_make_one_contour_of_2000() {
    let a = analyze_file("corpus/cc0/example013.dxf").unwrap();
    assert_eq!(a.chains.contours.len(), 1);
    assert!((a.nesting.pockets[0].area() - 2000.0).abs() < 1e-6);
}

#[test]
fn the_body_touching_the_plate_edges_is_an_island_of_the_plate() {
    // OpenSCAD's example 9: a 40 mm plate and a body of eight arcs whose radius-20 arcs touch
    // the plate's edges at their midpoints, so the body's extent equals the plate's up to
    // rounding. The body is an island of the plate (it was dropped as "in no pocket", and
    // the plate cut through it). Its area, 1436.39822 mm², is Green's theorem summed over
    // the eight arcs as the file gives them.
    let a = analyze_file("corpus/cc0/example009.dxf").unwrap();
    let plate = &a.nesting.pockets[0];
    assert!((plate.boundary.signed_area() - 1600.0).abs() < 1e-9);
    assert_eq!(plate.islands.len(), 1);
    assert!((plate.islands[0].signed_area() + 1436.39822).abs() < 1e-5);
    assert!((plate.area() - 163.60178).abs() < 1e-5);
    let dropped = a
        .nesting
        .warnings
        .iter()
        .filter(|w| matches!(w, pocketeer::import::ImportWarning::IslandInNoPocket { .. }));
    assert_eq!(dropped.count(), 0);
}

#[test]
fn binary_dxf_r12_and_r2000_are_read() {
    for f in ["corpus/mit/bin_dxf_r12.dxf", "corpus/mit/bin_dxf_r2000.dxf"] {
        let bytes = std::fs::read(fixture(f)).unwrap();
        let list = pocketeer::import::dxf::GroupList::read(&bytes).unwrap();
        assert!(list.binary() && list.saw_eof(), "{f}");
        assert!(
            list.all()
                .iter()
                .any(|g| g.is(0, "ENTITIES") || g.is(2, "ENTITIES")),
            "{f}"
        );
    }
    // The R12 file draws an open polyline: read, then refused for having no closed contour.
    let r12 = analyze_file("corpus/mit/bin_dxf_r12.dxf").unwrap_err();
    assert!(matches!(r12, ImportError::NoClosedContour { .. }), "{r12}");
    // The R2000 file holds a single TEXT.
    let r2000 = analyze_file("corpus/mit/bin_dxf_r2000.dxf").unwrap_err();
    assert!(r2000.to_string().contains("1 TEXT"), "{r2000}");
}

#[test]
fn bytes_after_eof_are_ignored() {
    let a = analyze_file("corpus/mit/R12_with_trash_beyond_EOF.dxf").unwrap();
    assert_eq!(a.nesting.pockets.len(), 1);
}

#[test]
fn a_damaged_file_is_read_as_far_as_it_makes_sense() {
    // Several ENTITIES sections, a header variable after ENDSEC, no EOF.
    let bytes = std::fs::read(fixture("corpus/mit/recover01.dxf")).unwrap();
    let d = read_drawing(&bytes, &ImportOptions::default()).unwrap();
    assert!(d
        .warnings
        .contains(&pocketeer::import::ImportWarning::NoEofMarker));
    assert_eq!(d.entity_counts.get("LINE"), Some(&1441));
}

#[test]
fn every_fixture_imports_or_is_refused_with_a_message() {
    for path in common::corpus::dxf_files(&fixture("corpus")) {
        let bytes = std::fs::read(&path).unwrap();
        match analyze(&bytes, &ImportOptions::default()) {
            Ok(a) => assert!(!a.nesting.pockets.is_empty(), "{}", path.display()),
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
}

#[test]
fn the_ac1003_part_loses_its_leader_and_corner_marks_and_keeps_its_hole() {
    // A part of lines and arcs with a hole of radius 0.3, a leader drawn from the hole to the
    // corner (3.5, 1.5) and two corner marks there: the strokes bound nothing and are left
    // out. The outline's area, 3.1427, was summed independently over its arcs sampled finely.
    let a = analyze_file("corpus/mit/AC1003_LINE_Example.dxf").unwrap();
    assert_eq!(a.nesting.pockets.len(), 1);
    let p = &a.nesting.pockets[0];
    assert!(
        (p.boundary.signed_area() - 3.142699).abs() < 1e-5,
        "{}",
        p.boundary.signed_area()
    );
    assert_eq!(p.islands.len(), 1);
    assert!((p.islands[0].signed_area() + 0.09 * std::f64::consts::PI).abs() < 1e-9);
    let strokes: Vec<_> = a
        .chains
        .warnings
        .iter()
        .filter_map(|w| match w {
            pocketeer::import::ImportWarning::StrokeRemoved { from, to, .. } => Some((*from, *to)),
            _ => None,
        })
        .collect();
    assert_eq!(strokes.len(), 3, "{:?}", a.chains.warnings);
    let corner = pocketeer::geom::Point::new(3.5, 1.5);
    assert!(strokes.iter().any(|s| s.1.distance(corner) < 1e-9), "{strokes:?}");
}

#[test]
fn the_keyboard_case_is_read_with_its_gaps_bridged_and_its_crossing_filled() {
    // Refused before the importer repaired: an outline open by 0.0155 mm whose ends overlap,
    // so that once bridged it touches itself.
    let a = analyze_file("corpus/mit/crkbd.dxf").unwrap();
    assert_eq!(a.nesting.pockets.len(), 13);
    let kinds: Vec<&str> = a
        .chains
        .warnings
        .iter()
        .chain(&a.nesting.warnings)
        .map(|w| w.kind())
        .collect();
    assert_eq!(
        kinds.iter().filter(|k| **k == "gap-bridged").count(),
        2,
        "{kinds:?}"
    );
    assert_eq!(
        kinds.iter().filter(|k| **k == "self-crossing-filled").count(),
        1,
        "{kinds:?}"
    );
    let strict = ImportOptions {
        strict: true,
        ..Default::default()
    };
    let bytes = std::fs::read(fixture("corpus/mit/crkbd.dxf")).unwrap();
    let err = analyze(&bytes, &strict).unwrap_err();
    assert!(err.to_string().contains("(26.8681, 40.8427)"), "{err}");
}
