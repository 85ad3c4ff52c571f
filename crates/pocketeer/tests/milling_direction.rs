//! Climb and conventional milling measured on the program text: along every move at the final
//! depth that follows a wall or an island, the material must be on the tool's right for climb
//! (M3 spindle, the G41 side) and on its left for conventional.

mod common;

use common::replay;
use common::shapes::{circle_cw, polygon, rect, star};
use pocketeer::clear::ClearParams;
use pocketeer::geom::Pocket;
use pocketeer::geom::{Contour, Segment, Tolerance};
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Dialect};

struct Case {
    name: &'static str,
    pocket: Pocket,
    stepover: f64,
    allowance: f64,
    depth: f64,
    step_down: f64,
}

fn cases() -> Vec<Case> {
    let case = |name, pocket, stepover, allowance, depth, step_down| Case {
        name,
        pocket,
        stepover,
        allowance,
        depth,
        step_down,
    };
    vec![
        case(
            "rectangle with two round islands",
            Pocket {
                boundary: rect(0.0, 0.0, 80.0, 50.0),
                islands: vec![circle_cw(25.0, 25.0, 8.0), circle_cw(55.0, 25.0, 6.0)],
            },
            2.4,
            0.0,
            2.0,
            2.0,
        ),
        case(
            "seven-point star",
            Pocket {
                boundary: star(7, 40.0, 18.0),
                islands: vec![],
            },
            4.5,
            0.0,
            3.0,
            1.5,
        ),
        case(
            "L-shape with a square island and a finishing allowance",
            Pocket {
                boundary: polygon(&[
                    (0.0, 0.0),
                    (70.0, 0.0),
                    (70.0, 30.0),
                    (30.0, 30.0),
                    (30.0, 60.0),
                    (0.0, 60.0),
                ]),
                islands: vec![rect(8.0, 8.0, 20.0, 20.0).reversed()],
            },
            3.0,
            0.5,
            4.0,
            2.0,
        ),
        case(
            "ring between two circles",
            Pocket {
                boundary: Contour::new(vec![Segment::Arc(pocketeer::geom::Arc::circle(
                    pocketeer::geom::Point::new(0.0, 0.0),
                    30.0,
                ))]),
                islands: vec![circle_cw(0.0, 0.0, 12.0)],
            },
            5.0,
            0.0,
            2.0,
            2.0,
        ),
    ]
}

fn program(c: &Case, direction: Direction) -> String {
    let clear = ClearParams {
        tool_radius: 3.0,
        stepover: c.stepover,
        allowance: c.allowance,
    };
    let link = LinkParams {
        depth: c.depth,
        step_down: c.step_down,
        safe_z: 5.0,
        feed_height: 1.0,
        direction,
        entry: Entry::Helix,
        ramp_angle: 3f64.to_radians(),
        time: pocketeer::machining_time::TimeModel::default(),
    };
    let job = pocketeer::job::pocket_job(
        std::slice::from_ref(&c.pocket),
        &clear,
        &link,
        &Tolerance::default(),
    )
    .expect("job");
    write_gcode(
        &job.linked.toolpath,
        &common::program::settings(),
        Dialect::LinuxCnc,
    )
}

#[test]
fn climb_keeps_the_material_on_the_right_and_conventional_on_the_left() {
    for c in cases() {
        let walls: Vec<Segment> = c.pocket.contours().flat_map(|k| k.segments.clone()).collect();
        let perimeter: f64 = walls.iter().map(Segment::length).sum();
        for direction in [Direction::Climb, Direction::Conventional] {
            let moves = replay::read(&program(&c, direction)).expect("program reads back");
            let (right, left) = replay::wall_sides(&moves, &walls, 3.0, -c.depth);
            // The walls are followed (their loops are shorter than the walls round convex
            // corners of the pocket, longer round convex corners of islands).
            assert!(
                right + left > 0.5 * perimeter,
                "{}: {right} + {left} of {perimeter}",
                c.name
            );
            let (on, off) = match direction {
                Direction::Climb => (right, left),
                Direction::Conventional => (left, right),
            };
            assert!(
                on >= 0.99 * (on + off),
                "{} {direction:?}: {on:.3} mm on the expected side, {off:.3} mm on the other",
                c.name
            );
        }
    }
}

/// With an allowance, the finishing pass at the walls is met and left along tangent arcs:
/// every feed move at the final depth that arrives at a wall (ends a tool radius from it,
/// coming from farther away) is an arc whose direction there runs along the wall, and so is
/// every move that leaves one.
#[test]
fn the_finishing_pass_enters_and_leaves_the_walls_on_tangent_arcs() {
    for c in cases()
        .into_iter()
        .filter(|c| c.allowance > 0.0)
        .chain(std::iter::once(Case {
            name: "rectangle with round islands and an allowance",
            pocket: Pocket {
                boundary: rect(0.0, 0.0, 80.0, 50.0),
                islands: vec![circle_cw(25.0, 25.0, 8.0), circle_cw(55.0, 25.0, 6.0)],
            },
            stepover: 2.4,
            allowance: 0.3,
            depth: 2.0,
            step_down: 2.0,
        }))
    {
        let walls: Vec<Segment> = c.pocket.contours().flat_map(|k| k.segments.clone()).collect();
        let index = pocketeer::geom::SegmentIndex::new(&walls);
        for direction in [Direction::Climb, Direction::Conventional] {
            let moves = replay::read(&program(&c, direction)).expect("program reads back");
            let (mut arrivals, mut departures) = (0, 0);
            for mv in moves
                .iter()
                .filter(|m| !m.rapid && m.z0 == -c.depth && m.z1 == -c.depth)
            {
                let (a, b) = (mv.segment.start(), mv.segment.end());
                let (da, db) = (index.distance(a), index.distance(b));
                for (at, t, from, to, count) in
                    [(b, 1.0, da, db, &mut arrivals), (a, 0.0, db, da, &mut departures)]
                {
                    if (to - 3.0).abs() > 1e-3 || from < 3.0 + 1e-2 {
                        continue;
                    }
                    *count += 1;
                    assert!(
                        matches!(mv.segment, Segment::Arc(_)),
                        "{} {direction:?}: straight onto or off the wall at {at:?}, line {}",
                        c.name,
                        mv.line
                    );
                    let (w, _) = index.nearest(at).expect("walls");
                    let along = mv.segment.tangent_at(t).normalized().expect("a direction");
                    let normal = (w - at).normalized().expect("off the wall");
                    // Within the program's rounding (0.0001 mm on a lead of about a millimetre).
                    assert!(
                        along.dot(normal).abs() < 1e-3,
                        "{} {direction:?}: not tangent at {at:?}, line {}: {:?} {}",
                        c.name,
                        mv.line,
                        mv.segment,
                        along.dot(normal)
                    );
                }
            }
            assert!(
                arrivals > 0 && departures > 0,
                "{} {direction:?}: {arrivals} {departures}",
                c.name
            );
        }
    }
}

/// Both directions, the leads onto the finishing pass and the re-entries above the previous
/// pass's floor keep every program clean: no gouge, no leftover, no rapid through the stock,
/// no plunge into uncut stock.
#[test]
fn every_case_passes_the_check_both_ways() {
    use pocketeer::simulate::{check_program, read_program, CheckParams};
    for c in cases() {
        for direction in [Direction::Climb, Direction::Conventional] {
            let program = read_program(&program(&c, direction)).expect("program reads back");
            let params = CheckParams {
                tool_radius: 3.0,
                depth: Some(c.depth),
                gouge_tolerance: 0.01,
                leftover_tolerance: 0.05,
                rapid_rate: 5000.0,
                per_retract: 0.0,
            };
            let r = check_program(
                std::slice::from_ref(&c.pocket),
                &program,
                &params,
                &Tolerance::default(),
            )
            .expect("check");
            assert!(
                r.passed && r.plunges.is_empty() && r.rapids_into_stock.is_empty(),
                "{} {direction:?}: gouge {}, thickest {}, plunges {:?}, rapids {:?}",
                c.name,
                r.gouge,
                r.thickest,
                r.plunges,
                r.rapids_into_stock
            );
        }
    }
}
