//! `check` on programs with known defects: it finds exactly the defects planted, and passes
//! clean programs.

mod common;

use pocketeer::geom::Pocket;
use pocketeer::geom::{Arc, Contour, Point, Segment, Tolerance};
use pocketeer::link::{Entry, LinkWarning};
use pocketeer::post::{write_gcode, Dialect};
use pocketeer::simulate::{check_program, read_program, CheckParams, CheckReport};

fn pocket() -> Pocket {
    let p = Point::new;
    Pocket {
        boundary: Contour::polygon(&[p(0.0, 0.0), p(100.0, 0.0), p(100.0, 60.0), p(0.0, 60.0)]),
        islands: vec![
            Contour::new(vec![Segment::Arc(Arc::new(
                p(30.0, 30.0),
                10.0,
                0.0,
                -std::f64::consts::TAU,
            ))]),
            Contour::new(vec![Segment::Arc(Arc::new(
                p(70.0, 30.0),
                8.0,
                0.0,
                -std::f64::consts::TAU,
            ))]),
        ],
    }
}

fn our_program(pocket: &Pocket, stepover: f64) -> String {
    our_program_and_warnings(pocket, stepover).0
}

/// Our program and the warnings the job gave (plunges where no helix or ramp fits).
fn our_program_and_warnings(pocket: &Pocket, stepover: f64) -> (String, Vec<LinkWarning>) {
    common::program::our_program(
        std::slice::from_ref(pocket),
        6.0,
        stepover,
        2.0,
        Entry::Helix,
        Dialect::Grbl,
    )
}

/// The check's settings for these programs: a 6 mm tool, 2 mm deep.
fn check_params() -> CheckParams {
    CheckParams {
        tool_radius: 3.0,
        depth: Some(2.0),
        gouge_tolerance: 0.01,
        leftover_tolerance: 0.05,
        rapid_rate: pocketeer::simulate::check::RAPID_RATE,
        per_retract: pocketeer::machining_time::DEFAULT_RETRACT_SECONDS,
    }
}

fn check(pocket: &Pocket, program: &str) -> CheckReport {
    let p = read_program(program).expect("reads");
    let params = check_params();
    check_program(std::slice::from_ref(pocket), &p, &params, &Tolerance::default()).unwrap()
}

#[test]
fn our_programs_pass_at_40_and_83_percent() {
    for stepover in [2.4, 4.98] {
        let r = check(&pocket(), &our_program(&pocket(), stepover));
        assert!(r.passed, "{r:#?}");
        assert!(
            r.gouge <= 0.01 && r.thickest <= 0.05,
            "gouge {} thickest {}",
            r.gouge,
            r.thickest
        );
        assert!(
            r.rapids_into_stock.is_empty() && r.plunges.is_empty() && r.feedless.is_empty(),
            "{r:#?}"
        );
        assert!(
            r.pockets[0].leftover_percent < 0.01,
            "{}",
            r.pockets[0].leftover_percent
        );
        eprintln!(
            "stepover {stepover}: leftover {:.6} mm² thickest {:.5}",
            r.pockets[0].leftover_area, r.thickest
        );
    }
}

/// Our program with `extra` lines inserted after the last feed move at the final depth (a
/// line or an arc: what follows is the retract, which starts wherever the tool is).
fn with_inserted(program: &str, extra: &[&str]) -> (String, usize) {
    with_inserted_after(program, |_| true, extra)
}

/// [`with_inserted`] after the last feed move at the final depth whose line `after` accepts.
fn with_inserted_after(program: &str, after: impl Fn(&str) -> bool, extra: &[&str]) -> (String, usize) {
    let lines: Vec<&str> = program.lines().collect();
    let at = lines
        .iter()
        .rposition(|l| {
            ["G1 ", "G2 ", "G3 "].iter().any(|g| l.starts_with(g))
                && (l.contains('X') || l.contains('Y'))
                && after(l)
        })
        .expect("a feed move");
    let mut out: Vec<&str> = lines[..=at].to_vec();
    out.extend_from_slice(extra);
    out.extend_from_slice(&lines[at + 1..]);
    (out.join("\n") + "\n", at + 2)
}

#[test]
fn a_move_too_close_to_the_wall_is_found_with_its_depth_and_line() {
    // After the move that ends on the wall loop's left side (X3): the planted moves stay
    // beside it, clear of the islands, wherever the program ends.
    let (program, line) = with_inserted_after(
        &our_program(&pocket(), 2.4),
        |l| l.starts_with("G1 X3.0000"),
        &["G1 X2.8 Y50", "G1 X3 Y50"],
    );
    let r = check(&pocket(), &program);
    assert!(!r.passed);
    assert!((r.gouge - 0.2).abs() < 1e-6, "{}", r.gouge);
    let at = r.pockets[0].gouge_at.unwrap();
    assert_eq!(at.line, line);
    assert!((at.x - 2.8).abs() < 1e-6);
    assert!(r.thickest <= 0.05 && r.rapids_into_stock.is_empty());
}

#[test]
fn a_link_across_an_island_is_a_gouge_as_deep_as_the_island_is_wide() {
    let (program, _) = with_inserted(&our_program(&pocket(), 2.4), &["G1 X30 Y30", "G1 X3 Y57"]);
    let r = check(&pocket(), &program);
    assert!(!r.passed);
    // The tool reaches the island's centre: its radius plus the island's.
    assert!((r.gouge - 13.0).abs() < 1e-6, "{}", r.gouge);
}

#[test]
fn a_rapid_through_the_stock_is_reported() {
    let (program, line) = with_inserted(&our_program(&pocket(), 2.4), &["G0 X50 Y4", "G1 X3 Y3"]);
    let r = check(&pocket(), &program);
    assert!(!r.passed);
    assert_eq!(r.rapids_into_stock.len(), 1);
    assert_eq!(r.rapids_into_stock[0].line, line);
    assert!(r.gouge <= 0.01);
}

#[test]
fn a_missing_loop_leaves_material_and_nothing_else() {
    let program = our_program(&pocket(), 2.4);
    // Drop the cutting moves of the last loop at the wall (the moves after the last link).
    let lines: Vec<&str> = program.lines().collect();
    let end = lines
        .iter()
        .rposition(|l| l.starts_with("G1 X") || l.starts_with("G1 Y"))
        .unwrap();
    let start = (0..end)
        .rev()
        .find(|&k| lines[k].starts_with("G2") || lines[k].starts_with("G3"))
        .unwrap();
    let lazy: Vec<&str> = lines[..=start].iter().chain(&lines[end + 1..]).copied().collect();
    let r = check(&pocket(), &(lazy.join("\n") + "\n"));
    assert!(!r.passed);
    assert!(r.thickest > 0.5, "{}", r.thickest);
    assert!(r.gouge <= 0.01 && r.rapids_into_stock.is_empty() && r.plunges.is_empty());
}

#[test]
fn feed_moves_before_any_feed_rate_and_plunges_are_reported() {
    let program = "G21 G90\nG0 Z5\nG0 X20 Y10\nG1 Z-2\nG1 X80 F1000\nG0 Z5\n";
    let r = check(&pocket(), program);
    assert_eq!(r.feedless.len(), 1);
    assert_eq!(r.feedless[0].line, 4);
    assert_eq!(r.plunges.len(), 1);
    assert_eq!(r.plunges[0].line, 4);
}

/// Plain contour-parallel loops at r + k·stepover, no clean-up: what most CAM does.
fn plain_offsets_program(pocket: &Pocket, r: f64, stepover: f64, depth: f64) -> String {
    use pocketeer::toolpath::{Feed, Point3, Toolpath};
    let tol = Tolerance::default();
    let region = pocketeer::geom::PreparedPocket::new(pocket);
    let distances: Vec<f64> = (0..200).map(|k| r + k as f64 * stepover).collect();
    let mut path = Toolpath::new(Point3::new(0.0, 0.0, 5.0));
    for level in region.offset_levels(&distances, &tol).unwrap().iter().rev() {
        for l in level {
            let s = l.segments[0].start();
            path.rapid(Point3::at(s, 5.0));
            path.line(Point3::at(s, -depth), Feed::Plunge);
            for seg in &l.segments {
                match seg {
                    Segment::Line(line) => path.line(Point3::at(line.end, -depth), Feed::Cut),
                    Segment::Arc(a) => {
                        path.arc_to(Point3::at(a.end(), -depth), a.center(), a.sweep(), Feed::Cut)
                    }
                }
            }
            path.line(Point3::at(s, 0.0), Feed::Cut);
            path.rapid(Point3::at(s, 5.0));
        }
    }
    write_gcode(&path, &common::program::settings(), Dialect::LinuxCnc)
}

#[test]
fn plain_offsets_above_the_corner_limit_leave_material_ours_do_not() {
    let star = Pocket {
        boundary: common::shapes::star(7, 50.0, 22.0),
        islands: vec![],
    };
    let plain = check(&star, &plain_offsets_program(&star, 3.0, 5.4, 2.0));
    assert!(!plain.passed);
    assert!(plain.thickest > 0.5, "{}", plain.thickest);
    assert!(plain.gouge <= 0.01, "{}", plain.gouge);
    // The program plunges straight down at every loop: into uncut stock at the first.
    assert!(!plain.plunges.is_empty());
    let ours = check(&star, &our_program(&star, 5.4));
    assert!(ours.passed, "gouge {} thickest {}", ours.gouge, ours.thickest);
    assert!(ours.plunges.is_empty());
}

mod random {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

        /// `pocket`'s output passes `check` for random pockets at stepovers from 10 % to 90 %.
        #[test]
        fn our_programs_pass_the_check(pocket in common::shapes::pocket_strategy(), percent in 10.0..90.0f64) {
            let (program, warnings) = our_program_and_warnings(&pocket, 6.0 * percent / 100.0);
            let r = check(&pocket, &program);
            prop_assert!(r.passed, "gouge {} thickest {}", r.gouge, r.thickest);
            // Plunges only where the job said no helix or ramp fits (a part barely wider than
            // the tool, cut off by a neck), once per depth pass.
            let announced = warnings.iter().filter(|w| matches!(w, LinkWarning::Plunged { .. })).count();
            prop_assert!(
                r.rapids_into_stock.is_empty() && r.plunges.len() <= announced && r.feedless.is_empty(),
                "rapids {:?} plunges {:?} feedless {:?}",
                r.rapids_into_stock,
                r.plunges,
                r.feedless
            );
        }
    }
}

/// One loop around a 40 x 30 rectangle at `inset` from its walls, at Z-1, with a 6 mm tool.
fn wall_loop(inset: f64) -> String {
    let (x0, y0, x1, y1) = (inset, inset, 40.0 - inset, 30.0 - inset);
    format!(
        "G21 G90\nG0 Z5\nG0 X{x0} Y{y0}\nG1 Z-1 F200\nG1 X{x1} F1000\nG1 Y{y1}\nG1 X{x0}\nG1 Y{y0}\nG0 Z5\n"
    )
}

#[test]
fn a_wall_pass_0_011_too_close_fails_and_0_005_passes_the_gouge_tolerance() {
    let p = Point::new;
    let rect = Pocket {
        boundary: Contour::polygon(&[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 30.0), p(0.0, 30.0)]),
        islands: vec![],
    };
    let params = CheckParams {
        tool_radius: 3.0,
        depth: Some(1.0),
        gouge_tolerance: 0.01,
        leftover_tolerance: 1e9,
        rapid_rate: pocketeer::simulate::check::RAPID_RATE,
        per_retract: pocketeer::machining_time::DEFAULT_RETRACT_SECONDS,
    };
    let run = |inset: f64| {
        check_program(
            std::slice::from_ref(&rect),
            &read_program(&wall_loop(inset)).unwrap(),
            &params,
            &Tolerance::default(),
        )
        .unwrap()
    };
    let over = run(2.989);
    assert!((over.gouge - 0.011).abs() < 1e-9, "{}", over.gouge);
    assert!(!over.passed);
    let near = run(2.995);
    assert!((near.gouge - 0.005).abs() < 1e-9, "{}", near.gouge);
    assert!(near.passed);
    // The plunge at the loop's start goes into uncut stock.
    assert_eq!(near.plunges.len(), 1);
    assert_eq!(near.plunges[0].line, 4);
}

#[test]
fn the_check_reports_a_step_for_each_move_and_each_cutting_move_measured() {
    let pocket = pocket();
    let program = read_program(&our_program(&pocket, 2.4)).expect("reads");
    let params = check_params();
    let progress = pocketeer::progress::Recorded::default();
    let report = pocketeer::simulate::check_program_tools_with(
        std::slice::from_ref(&pocket),
        &program,
        &[],
        &params,
        &Tolerance::default(),
        &progress,
    )
    .unwrap();
    assert!(report.passed);
    let moves = program.moves.len() as u64;
    let stages = progress.stages();
    assert_eq!(stages.len(), 3, "{stages:?}");
    assert_eq!(stages[0], ("replaying the moves".to_owned(), Some(moves)));
    assert_eq!(stages[1].0, "measuring the tool's engagement");
    let cutting = stages[1].1.unwrap();
    assert!(cutting > 0 && cutting < moves, "{cutting} of {moves}");
    assert_eq!(stages[2], ("sweeping the area cut".to_owned(), None));
    assert_eq!(progress.steps(), moves + cutting);
}
