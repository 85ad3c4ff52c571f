//! Climb and conventional milling measured on the program text: along every move at the final
//! depth that follows a wall or an island, the material must be on the tool's right for climb
//! (M3 spindle, the G41 side) and on its left for conventional.

mod common;

use common::replay;
use common::shapes::{circle_cw, polygon, rect, star};
use pocketeer::clear::ClearParams;
use pocketeer::geom::{Contour, Segment, Tolerance};
use pocketeer::import::Pocket;
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
        tool_radius: 3.0,
        depth: c.depth,
        step_down: c.step_down,
        safe_z: 5.0,
        feed_height: 1.0,
        direction,
        entry: Entry::Helix,
        ramp_angle: 3f64.to_radians(),
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
