//! Our pocket job as program text, the way the end-to-end tests run it.

use pocketeer::clear::ClearParams;
use pocketeer::geom::Pocket;
use pocketeer::geom::Tolerance;
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Dialect, ProgramSettings, ProgramUnits};

/// Millimetres, 1000/300 mm/min, 10000 rpm, safe height 5 mm, no header.
pub fn settings() -> ProgramSettings {
    ProgramSettings {
        units: ProgramUnits::Millimetres,
        feed: 1000.0,
        plunge_feed: 300.0,
        spindle: 10000.0,
        safe_z: 5.0,
        header: vec![],
        ..ProgramSettings::default()
    }
}

/// The program `pocket` writes for `pockets` with a tool of `diameter` (climb, depth passes of
/// at most one diameter, 3° entries), and the job's warnings.
pub fn our_program(
    pockets: &[Pocket],
    diameter: f64,
    stepover: f64,
    depth: f64,
    entry: Entry,
    dialect: Dialect,
) -> (String, Vec<pocketeer::link::LinkWarning>) {
    let r = 0.5 * diameter;
    let clear = ClearParams {
        tool_radius: r,
        stepover,
        allowance: 0.0,
    };
    let link = LinkParams {
        depth,
        step_down: diameter,
        safe_z: 5.0,
        feed_height: 1.0,
        direction: Direction::Climb,
        entry,
        ramp_angle: 3f64.to_radians(),
        time: pocketeer::machining_time::TimeModel::default(),
    };
    let job = pocketeer::job::pocket_job(pockets, &clear, &link, &Tolerance::default()).expect("job");
    (
        write_gcode(&job.linked.toolpath, &settings(), dialect),
        job.linked.warnings,
    )
}
