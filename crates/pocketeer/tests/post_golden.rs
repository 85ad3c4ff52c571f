//! The G-code text is the contract with the machine: a small job written for each controller
//! must match its golden file byte for byte. After an intended change, regenerate with
//! `UPDATE_GOLDEN=1 cargo test -p pocketeer --test post_golden` and review the diff.

use pocketeer::clear::ClearParams;
use pocketeer::geom::Pocket;
use pocketeer::geom::{Arc, Contour, Point, Segment, Tolerance};
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Coolant, Dialect, ProgramSettings, ProgramUnits};

fn program(dialect: Dialect, units: ProgramUnits) -> String {
    let p = Point::new;
    let pocket = Pocket {
        boundary: Contour::polygon(&[p(0.0, 0.0), p(30.0, 0.0), p(30.0, 20.0), p(0.0, 20.0)]),
        islands: vec![Contour::new(vec![Segment::Arc(Arc::new(
            p(15.0, 10.0),
            3.0,
            0.0,
            -std::f64::consts::TAU,
        ))])],
    };
    let clear = ClearParams {
        tool_radius: 3.0,
        stepover: 2.4,
        allowance: 0.0,
    };
    let link = LinkParams {
        depth: 3.0,
        step_down: 1.5,
        safe_z: 5.0,
        feed_height: 1.0,
        direction: Direction::Climb,
        entry: Entry::Helix,
        ramp_angle: 3f64.to_radians(),
        time: pocketeer::machining_time::TimeModel::default(),
    };
    let job = pocketeer::job::pocket_job(&[pocket], &clear, &link, &Tolerance::default()).unwrap();
    let settings = ProgramSettings {
        units,
        feed: 800.0,
        plunge_feed: 250.0,
        spindle: 16000.0,
        safe_z: 5.0,
        header: vec!["golden: 30 x 20 pocket, 6 mm island, 6 mm tool".into()],
        // The controllers with a tool changer load tool 3 and switch the flood coolant on, and
        // park away from the part; GRBL's programs keep the defaults.
        tool: (dialect != Dialect::Grbl).then_some(3),
        coolant: if dialect == Dialect::Grbl {
            Coolant::Off
        } else {
            Coolant::Flood
        },
        park: (dialect != Dialect::Grbl).then_some(Point::new(-10.0, 40.0)),
        ..ProgramSettings::default()
    };
    write_gcode(&job.linked.toolpath, &settings, dialect)
}

fn check(name: &str, text: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, text).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != text {
        let first = expected
            .lines()
            .zip(text.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(expected.lines().count().min(text.lines().count()));
        panic!(
            "{name} differs from its golden file at line {}: expected {:?}, got {:?}",
            first + 1,
            expected.lines().nth(first),
            text.lines().nth(first)
        );
    }
}

#[test]
fn grbl() {
    check("grbl.nc", &program(Dialect::Grbl, ProgramUnits::Millimetres));
}

#[test]
fn linuxcnc() {
    check(
        "linuxcnc.nc",
        &program(Dialect::LinuxCnc, ProgramUnits::Millimetres),
    );
}

#[test]
fn mach3() {
    check("mach3.nc", &program(Dialect::Mach3, ProgramUnits::Millimetres));
}

#[test]
fn grbl_inches() {
    check("grbl-inch.nc", &program(Dialect::Grbl, ProgramUnits::Inches));
}
