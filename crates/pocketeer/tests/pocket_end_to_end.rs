//! The whole `pocket` job on drawings, read back from the G-code text: the tool never leaves
//! the region below the stock top (no gouge), and everything the tool can reach is cut at the
//! final depth (no leftover), at stepovers up to 90 % of the diameter.

mod common;

use common::replay::{measure, read, Target};
use common::shapes::{circle_cw, pocket_strategy, rect, star};
use pocketeer::clear::ClearParams;
use pocketeer::geom::Pocket;
use pocketeer::geom::PreparedPocket;
use pocketeer::geom::{Segment, Tolerance};
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::offset::offset_pocket;
use pocketeer::post::Dialect;

struct Outcome {
    gouge: f64,
    leftover: usize,
    tested: usize,
    deepest: f64,
    rapids_below_top: usize,
    warnings: Vec<pocketeer::link::LinkWarning>,
}

fn run(
    pockets: &[Pocket],
    diameter: f64,
    stepover: f64,
    depth: f64,
    entry: Entry,
    dialect: Dialect,
) -> Outcome {
    let tol = Tolerance::default();
    let r = 0.5 * diameter;
    let (program, warnings) =
        common::program::our_program(pockets, diameter, stepover, depth, entry, dialect);
    let moves = read(&program).expect("the program reads back");
    let prepared: Vec<(PreparedPocket, Vec<Segment>, Vec<Segment>)> = pockets
        .iter()
        .map(|p| {
            let walls = p.contours().flat_map(|c| c.segments.iter().copied()).collect();
            let centres = offset_pocket(p, r, &tol)
                .unwrap()
                .iter()
                .flat_map(|c| c.segments.iter().copied())
                .collect();
            (PreparedPocket::new(p), walls, centres)
        })
        .collect();
    let targets: Vec<Target> = prepared
        .iter()
        .map(|(region, walls, centres)| Target {
            region,
            walls,
            centres,
        })
        .collect();
    // A 0.2 mm grid, coarser on large drawings (at most about four million points).
    let area: f64 = pockets
        .iter()
        .map(|p| p.boundary.bbox().width() * p.boundary.bbox().height())
        .sum();
    let h = (area / 4e6).sqrt().max(0.2);
    let m = measure(&moves, &targets, r, -depth, h, 0.01);
    if !m.leftover_points.is_empty() {
        eprintln!(
            "leftover at {:?}",
            &m.leftover_points[..m.leftover_points.len().min(5)]
        );
    }
    Outcome {
        gouge: m.gouge,
        leftover: m.leftover_points.len(),
        tested: m.tested,
        deepest: m.deepest,
        rapids_below_top: m.rapids_below_top,
        warnings,
    }
}

fn assert_clean(o: &Outcome, depth: f64) {
    assert!(o.gouge <= 0.01, "gouge {:.4} mm", o.gouge);
    assert_eq!(
        o.leftover, 0,
        "{} of {} reachable points left uncut",
        o.leftover, o.tested
    );
    assert!(o.tested > 100, "only {} points tested", o.tested);
    assert!((o.deepest + depth).abs() < 1e-3, "deepest {}", o.deepest);
    assert_eq!(o.rapids_below_top, 0);
}

#[test]
fn rectangle_with_two_round_islands_at_every_stepover_up_to_90_percent() {
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 100.0, 60.0),
        islands: vec![circle_cw(30.0, 30.0, 10.0), circle_cw(70.0, 30.0, 8.0)],
    };
    for o in clean_at(&pocket, &[30.0, 50.0, 70.0, 83.0, 90.0]) {
        assert!(o.warnings.is_empty(), "{:?}", o.warnings);
    }
}

/// `pocket` cleared 2 mm deep with a 6 mm tool at each of the stepovers `percents` (of the
/// diameter), each program checked clean; their outcomes.
fn clean_at(pocket: &Pocket, percents: &[f64]) -> Vec<Outcome> {
    (percents.iter())
        .map(|&percent| {
            let o = run(
                std::slice::from_ref(pocket),
                6.0,
                6.0 * percent / 100.0,
                2.0,
                Entry::Helix,
                Dialect::Grbl,
            );
            eprintln!("{percent}%: tested {}", o.tested);
            assert_clean(&o, 2.0);
            o
        })
        .collect()
}

#[test]
fn the_spaces_between_holes_cleared_from_one_spot_each_leave_nothing() {
    // Holes of 8 mm at a 20 mm pitch, a 6 mm tool at 40 %: what the loops round the holes
    // leave between four of them is cut from one spot in its middle, not by a loop (and at
    // 30 % and 50 %, where the loops leave more or less there).
    let holes = (0..16)
        .map(|k| circle_cw(10.0 + 20.0 * (k % 4) as f64, 10.0 + 20.0 * (k / 4) as f64, 4.0))
        .collect();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 80.0, 80.0),
        islands: holes,
    };
    clean_at(&pocket, &[30.0, 40.0, 50.0]);
}

#[test]
fn narrow_leaves_cleared_by_one_pass_each_leave_nothing() {
    // A 30 x 20 pocket round an island of radius 3, a 6 mm tool at 40 %: the level at 5.4 mm
    // leaves a narrow leaf each side of the island, cleared by one straight pass along its
    // middle (see `clear::spots`), replayed here from the G-code.
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 30.0, 20.0),
        islands: vec![circle_cw(15.0, 10.0, 3.0)],
    };
    let params = ClearParams {
        tool_radius: 3.0,
        stepover: 2.4,
        allowance: 0.0,
    };
    let plan = pocketeer::clear::plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
    let passes = (plan.parts.iter().flat_map(|p| &p.spots))
        .filter(|s| s.path.segments.iter().map(Segment::length).sum::<f64>() > 1.0)
        .count();
    assert_eq!(passes, 2, "a pass each side of the island");
    // A pass is cut along its length, not stopped short as a spot at one point may be.
    assert!((plan.parts.iter().flat_map(|p| &p.spots)).all(|s| s.left.is_none()));
    let o = run(&[pocket], 6.0, 2.4, 3.0, Entry::Helix, Dialect::Grbl);
    assert_clean(&o, 3.0);
}

#[test]
fn cusps_between_island_loops_cleared_from_one_spot_each_leave_nothing() {
    // Four islands of radius 8 at a 43 x 50 mm pitch, a 6 mm tool above half its diameter:
    // the clean-up pieces in the cusps between the loops round the islands and the walls'
    // loops, little triangles, become steps in to one spot each (see `clear::residue`).
    // Without those steps 22 points of the replay are left uncut.
    let islands = [(35.0, 35.0), (78.0, 35.0), (35.0, 85.0), (78.0, 85.0)]
        .iter()
        .map(|&(x, y)| circle_cw(x, y, 8.0))
        .collect();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 113.0, 120.0),
        islands,
    };
    for percent in [70.0, 80.0, 90.0] {
        let params = ClearParams {
            tool_radius: 3.0,
            stepover: 6.0 * percent / 100.0,
            allowance: 0.0,
        };
        let plan = pocketeer::clear::plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
        let spots = (plan.parts.iter().flat_map(|p| &p.cleanups))
            .filter(|c| c.segments.len() == 1 && c.segments[0].length() <= 0.3 + 1e-9)
            .count();
        assert!(spots >= 4, "{percent} %: {spots} spots");
    }
    clean_at(&pocket, &[70.0, 80.0, 90.0]);
}

#[test]
fn seven_point_star_at_80_percent() {
    let pocket = Pocket {
        boundary: star(7, 50.0, 22.0),
        islands: vec![],
    };
    let o = run(&[pocket], 6.0, 4.8, 3.0, Entry::Helix, Dialect::LinuxCnc);
    assert_clean(&o, 3.0);
}

#[test]
fn bar_island_splits_the_pocket_and_both_sides_are_cleared() {
    let bar = rect(10.0, 13.0, 50.0, 17.0).reversed();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 60.0, 30.0),
        islands: vec![bar],
    };
    let o = run(&[pocket], 4.0, 3.4, 6.0, Entry::Ramp, Dialect::Mach3);
    assert_clean(&o, 6.0);
}

#[test]
fn a_leaf_wrapping_round_an_island_is_stepped_into_round_the_island_not_across_it() {
    // Found by `random_pockets_are_cleared_cleanly`: the loop of one level wraps round the
    // island and its inner loop lies in the corner beyond it; the step in from where that
    // loop began crossed the island, a gouge of 1.5 mm. Now along the loop first.
    let d = 7.84253889017074;
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 38.31872983768194, 43.02310806421963),
        islands: vec![circle_cw(
            16.360855638595204,
            18.988484523185956,
            6.0116662659293185,
        )],
    };
    // The stepover it was found at, and some about it (the tree changes with it).
    for percent in [41.08729799548897, 36.0, 39.0, 43.0, 46.0] {
        let o = run(
            std::slice::from_ref(&pocket),
            d,
            d * percent / 100.0,
            1.0,
            Entry::Helix,
            Dialect::Grbl,
        );
        assert_clean(&o, 1.0);
    }
}

mod random {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

        /// Random pockets at random stepovers from 10 % to 90 %: no gouge, no leftover.
        #[test]
        fn random_pockets_are_cleared_cleanly(pocket in pocket_strategy(), percent in 10.0..90.0f64, d in 3.0..8.0f64) {
            let o = run(std::slice::from_ref(&pocket), d, d * percent / 100.0, 1.0, Entry::Helix, Dialect::Grbl);
            prop_assert!(o.gouge <= 0.01, "gouge {}", o.gouge);
            prop_assert_eq!(o.leftover, 0, "{} of {} points left", o.leftover, o.tested);
        }
    }
}

/// Every drawing of a corpus folder that imports is pocketed at 40 % and 83 % with a 3 mm tool
/// and measured like the tests above. Ignored: it needs the folder, named by the
/// `POCKETEER_CORPUS` environment variable, and takes a minute:
/// `POCKETEER_CORPUS=path/to/corpus cargo test -p pocketeer --test pocket_end_to_end -- --ignored`
#[test]
#[ignore]
fn corpus_drawings_are_cleared_cleanly() {
    let files = common::corpus::corpus_from_env();
    let mut bad = Vec::new();
    for f in &files {
        let Ok(analysis) = pocketeer::analyze(&std::fs::read(f).unwrap(), &Default::default()) else {
            continue;
        };
        for percent in [40.0, 83.0] {
            let pockets = &analysis.nesting.pockets;
            let fits = pocketeer::job::pocket_job(
                pockets,
                &ClearParams {
                    tool_radius: 1.5,
                    stepover: 3.0 * percent / 100.0,
                    allowance: 0.0,
                },
                &LinkParams {
                    depth: 1.0,
                    step_down: 3.0,
                    safe_z: 5.0,
                    feed_height: 1.0,
                    direction: Direction::Climb,
                    entry: Entry::Helix,
                    ramp_angle: 3f64.to_radians(),
                    time: pocketeer::machining_time::TimeModel::default(),
                },
                &analysis.tolerance,
            )
            .is_ok();
            if !fits {
                continue;
            }
            let o = run(
                pockets,
                3.0,
                3.0 * percent / 100.0,
                1.0,
                Entry::Helix,
                Dialect::Grbl,
            );
            eprintln!(
                "{} at {percent}%: gouge {:.4}, {} of {} points left",
                f.display(),
                o.gouge,
                o.leftover,
                o.tested
            );
            if o.gouge > 0.01 || o.leftover > 0 {
                bad.push(format!("{} at {percent}%", f.display()));
            }
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
}

/// The example the README's first command pockets, read from its DXF file, at a stepover at
/// the radius and one at 85 %, in two depth passes.
#[test]
fn the_bracket_example_is_cleared_cleanly() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/bracket.dxf");
    let analysis = pocketeer::analyze(&std::fs::read(path).unwrap(), &Default::default()).unwrap();
    for stepover in [3.0, 5.1] {
        let o = run(
            &analysis.nesting.pockets,
            6.0,
            stepover,
            8.0,
            Entry::Helix,
            Dialect::Grbl,
        );
        assert_clean(&o, 8.0);
        assert!(o.warnings.is_empty(), "{:?}", o.warnings);
    }
}

/// The same pocket with its start points rotated, mirrored, and moved 1e5 mm away
/// gives the same job: as many loops, the same cutting length, and still clean.
#[test]
fn pocket_jobs_are_invariant_under_start_rotation_mirroring_and_translation() {
    use pocketeer::geom::{Contour, Vector};
    let base = Pocket {
        boundary: star(7, 50.0, 22.0),
        islands: vec![circle_cw(0.0, 0.0, 6.0)],
    };
    let map = |p: &Pocket, f: &dyn Fn(&Contour) -> Contour| Pocket {
        boundary: f(&p.boundary),
        islands: p.islands.iter().map(f).collect(),
    };
    let rotate_start = |c: &Contour| {
        let mut s = c.segments.clone();
        let k = s.len() / 3;
        s.rotate_left(k);
        Contour::new(s)
    };
    let far = |c: &Contour| {
        Contour::new(
            c.segments
                .iter()
                .map(|s| s.translated(Vector::new(1e5, -1e5)))
                .collect(),
        )
    };
    let variants = [
        ("rotated start", map(&base, &rotate_start)),
        ("mirrored", map(&base, &common::shapes::mirrored)),
        ("translated by 1e5", map(&base, &far)),
    ];
    let tol = Tolerance::default();
    let job = |p: &Pocket| {
        let clear = ClearParams {
            tool_radius: 3.0,
            stepover: 4.8,
            allowance: 0.0,
        };
        let link = LinkParams {
            depth: 2.0,
            step_down: 6.0,
            safe_z: 5.0,
            feed_height: 1.0,
            direction: Direction::Climb,
            entry: Entry::Helix,
            ramp_angle: 3f64.to_radians(),
            time: pocketeer::machining_time::TimeModel::default(),
        };
        let j = pocketeer::job::pocket_job(std::slice::from_ref(p), &clear, &link, &tol).unwrap();
        let loops: usize = j.plans.iter().map(|p| p.loop_count()).sum();
        let levels: Vec<f64> = j.plans[0]
            .parts
            .iter()
            .map(|n| n.outer.signed_area() + n.holes.iter().map(Contour::signed_area).sum::<f64>())
            .collect();
        (loops, levels.iter().sum::<f64>())
    };
    let (loops, area) = job(&base);
    for (name, p) in &variants {
        let (l, a) = job(p);
        assert_eq!(l, loops, "{name}: loop count");
        assert!(
            (a - area).abs() <= 1e-6 * area.abs(),
            "{name}: level areas {a} vs {area}"
        );
        let o = run(
            std::slice::from_ref(p),
            6.0,
            4.8,
            2.0,
            Entry::Helix,
            Dialect::Grbl,
        );
        assert_clean(&o, 2.0);
    }
}
