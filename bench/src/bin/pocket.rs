//! The whole `pocket` job (DXF text in, G-code text out) on the smooth profile of case (c)
//! with six circular islands, at 10k and 100k elements: median wall time of each phase.
//! `cargo run --release --bin pocket [-- --runs N] [-- --quick]`

use pocketeer::clear::ClearParams;
use pocketeer::export::dxf::{write_dxf, LayeredContour};
use pocketeer::import::Units;
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Dialect, ProgramSettings, ProgramUnits};
use pocketeer::ImportOptions;
use pocketeer_bench::cases;
use std::time::Instant;

fn drawing(n: usize) -> String {
    let mut case = cases::smooth(n - 6, false);
    for k in 0..6 {
        let a = k as f64 * std::f64::consts::TAU / 6.0;
        let (cx, cy) = (55.0 * a.cos(), 55.0 * a.sin());
        case.rings.push(vec![(cx + 8.0, cy, -1.0), (cx - 8.0, cy, -1.0)]);
    }
    let pocket = pocketeer_bench::pocket(&case);
    let contours: Vec<_> = std::iter::once(&pocket.boundary).chain(&pocket.islands).collect();
    let layered: Vec<LayeredContour> = contours
        .iter()
        .map(|c| LayeredContour {
            layer: "0",
            contour: c,
        })
        .collect();
    write_dxf(&layered, Units::Millimeters)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs: usize = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    if let Some(i) = args.iter().position(|a| a == "--write") {
        // Writes the drawing of the given size, for profiling the command line on it.
        let n: usize = args.get(i + 1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
        print!("{}", drawing(n));
        return;
    }
    let sizes: &[usize] = if args.iter().any(|a| a == "--quick") {
        &[10_000]
    } else {
        &[10_000, 100_000]
    };
    println!("| elements | import ms | plan ms | link ms | G-code ms | total ms | loops | G-code lines |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in sizes {
        let text = drawing(n);
        let mut phases: Vec<[f64; 5]> = Vec::new();
        let (mut loops, mut lines) = (0, 0);
        for _ in 0..runs {
            let t0 = Instant::now();
            let analysis = pocketeer::analyze(text.as_bytes(), &ImportOptions::default()).expect("reads");
            let t1 = Instant::now();
            let clear = ClearParams {
                tool_radius: 3.0,
                stepover: 2.4,
                allowance: 0.0,
            };
            let link = LinkParams {
                depth: 2.0,
                step_down: 2.0,
                safe_z: 5.0,
                feed_height: 1.0,
                direction: Direction::Climb,
                entry: Entry::Helix,
                ramp_angle: 3f64.to_radians(),
                time: pocketeer::machining_time::TimeModel::default(),
            };
            let tol = &analysis.tolerance;
            let pockets = &analysis.nesting.pockets;
            let regions: Vec<pocketeer::geom::PreparedPocket> =
                pockets.iter().map(pocketeer::geom::PreparedPocket::new).collect();
            let plans: Vec<_> = regions
                .iter()
                .map(|r| pocketeer::clear::plan_prepared(r, &clear, tol).expect("plans"))
                .collect();
            let t2 = Instant::now();
            let jobs: Vec<_> = regions.iter().zip(&plans).collect();
            let linked = pocketeer::link::link(&jobs, &link, tol).expect("bench parameters are in range");
            let t3 = Instant::now();
            let settings = ProgramSettings {
                units: ProgramUnits::Millimetres,
                feed: 1000.0,
                plunge_feed: 300.0,
                spindle: 12000.0,
                safe_z: 5.0,
                header: vec![],
                ..ProgramSettings::default()
            };
            let g = write_gcode(&linked.toolpath, &settings, Dialect::Grbl);
            let t4 = Instant::now();
            loops = plans.iter().map(|p| p.loop_count()).sum();
            lines = g.lines().count();
            let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
            phases.push([ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t4), ms(t0, t4)]);
        }
        let col = |k: usize| median(phases.iter().map(|p| p[k]).collect());
        println!(
            "| {n} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {loops} | {lines} |",
            col(0),
            col(1),
            col(2),
            col(3),
            col(4)
        );
    }
}
