//! `pocketeer pocket`: the drawing in, a G-code program out.

use crate::length::{parse_length, parse_nonneg_length};
use crate::{output, read_analysis, DrawingArgs, Failure};
use clap::{Args, ValueEnum};
use pocketeer::clear::ClearParams;
use pocketeer::import::Units;
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Dialect, ProgramSettings, ProgramUnits};
use std::path::PathBuf;

/// Rapid speed assumed for the time estimate, mm/min.
const RAPID_RATE: f64 = 5000.0;

#[derive(Args)]
pub struct PocketArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// Tool diameter (6, 6mm, 0.25in).
    #[arg(long, value_parser = parse_length)]
    tool_diameter: f64,
    /// Distance between neighbouring passes: a length (2.4, 2.4mm) or a share of the tool
    /// diameter (40%); less than the diameter.
    #[arg(long, value_parser = parse_stepover)]
    stepover: Stepover,
    /// Depth of the pocket below the stock top (Z=0), a positive length.
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    depth: f64,
    /// Largest depth of one pass [default: the whole depth when it is at most the tool
    /// diameter, else equal passes of at most one diameter].
    #[arg(long, value_parser = parse_length)]
    step_down: Option<f64>,
    /// Cutting feed per minute (1000 = 1000 mm/min; 40in = 40 in/min).
    #[arg(long, default_value = "1000", value_parser = parse_length)]
    feed: f64,
    /// Feed per minute for moves that go down into the stock (helix, ramp, plunge).
    #[arg(long, default_value = "300", value_parser = parse_length)]
    plunge_feed: f64,
    /// Spindle speed, rpm.
    #[arg(long, default_value_t = 12000.0)]
    spindle: f64,
    /// Height above the stock for rapid moves.
    #[arg(long, default_value = "5", value_parser = parse_length)]
    safe_z: f64,
    /// Milling direction, for a spindle turning clockwise (M3). climb: the material on the
    /// tool's right (the G41 side), pocket walls followed counter-clockwise and islands
    /// clockwise; conventional: the material on the left, walls clockwise, islands
    /// counter-clockwise.
    #[arg(long, value_enum, default_value_t = DirectionArg::Climb)]
    direction: DirectionArg,
    /// Material left on walls and islands by the roughing passes, then removed by one
    /// finishing pass at the wall.
    #[arg(long, default_value = "0", value_parser = parse_nonneg_length)]
    allowance: f64,
    /// How the tool enters the stock.
    #[arg(long, value_enum, default_value_t = EntryArg::Helix)]
    entry: EntryArg,
    /// Largest angle of helix and ramp entries from the horizontal, degrees.
    #[arg(long, default_value_t = 3.0)]
    ramp_angle: f64,
    /// The controller the program is for.
    #[arg(long, value_enum, default_value_t = PostArg::Grbl)]
    post: PostArg,
    /// The G-code file to write (written only when everything succeeded).
    #[arg(short, long)]
    output: PathBuf,
    /// Also draw the drawing, the loops and the tool path in this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Replay the program against the drawing before writing it (as `pocketeer check` does)
    /// and refuse to write it when it gouges or leaves material.
    #[arg(long)]
    check: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum DirectionArg {
    Climb,
    Conventional,
}

#[derive(Clone, Copy, ValueEnum)]
enum EntryArg {
    Helix,
    Ramp,
    Plunge,
}

#[derive(Clone, Copy, ValueEnum)]
enum PostArg {
    Grbl,
    Linuxcnc,
    Mach3,
}

/// A stepover as given: millimetres or a share of the diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepover {
    /// Millimetres.
    Length(f64),
    /// Percent of the tool diameter.
    Percent(f64),
}

fn parse_stepover(s: &str) -> Result<Stepover, String> {
    if let Some(p) = s.trim().strip_suffix('%') {
        let v: f64 = p
            .trim()
            .parse()
            .map_err(|_| format!("'{s}' is not a percentage (example: 40%)"))?;
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("'{s}' must be a positive percentage"));
        }
        return Ok(Stepover::Percent(v));
    }
    parse_length(s).map(Stepover::Length)
}

fn positive(name: &str, v: f64) -> Result<f64, Failure> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Failure(format!("{name} must be positive (got --{name} {v})")))
    }
}

pub fn run(args: &PocketArgs) -> Result<(), Failure> {
    let diameter = positive("tool-diameter", args.tool_diameter)?;
    let stepover = match args.stepover {
        Stepover::Length(v) => v,
        Stepover::Percent(p) => diameter * p / 100.0,
    };
    let depth = positive("depth", args.depth)?;
    let step_down = match args.step_down {
        Some(v) => positive("step-down", v)?,
        None if depth <= diameter => depth,
        None => diameter,
    };
    positive("feed", args.feed)?;
    positive("plunge-feed", args.plunge_feed)?;
    positive("spindle", args.spindle)?;
    let clear = ClearParams {
        tool_radius: 0.5 * diameter,
        stepover,
        allowance: args.allowance,
    };
    let link = LinkParams {
        tool_radius: 0.5 * diameter,
        depth,
        step_down,
        safe_z: args.safe_z,
        direction: match args.direction {
            DirectionArg::Climb => Direction::Climb,
            DirectionArg::Conventional => Direction::Conventional,
        },
        entry: match args.entry {
            EntryArg::Helix => Entry::Helix,
            EntryArg::Ramp => Entry::Ramp,
            EntryArg::Plunge => Entry::Plunge,
        },
        ramp_angle: args.ramp_angle.to_radians(),
    };
    let analysis = read_analysis(&args.drawing)?;
    let name = args.drawing.file.display();
    let tol = &analysis.tolerance;
    let job = pocketeer::job::pocket_job(&analysis.regions.pockets, &clear, &link, tol)
        .map_err(|e| Failure(format!("{name}: {e}")))?;
    let stats = job.linked.toolpath.stats();
    let seconds = stats.seconds(args.feed, args.plunge_feed, RAPID_RATE);
    let loops: usize = job.plans.iter().map(|p| p.loop_count()).sum();
    let passes = pocketeer::link::pass_depths(depth, step_down).len();
    let units = if analysis.drawing.units == Units::Inches {
        ProgramUnits::Inches
    } else {
        ProgramUnits::Millimetres
    };
    // Short lines: some senders and controllers limit a line to 80 characters.
    let header = vec![
        format!("pocketeer {}", env!("CARGO_PKG_VERSION")),
        format!("drawing {}", file_name(&args.drawing.file)),
        format!("tool diameter {} mm, stepover {:.4} mm", fmt(diameter), stepover),
        format!(
            "depth {} mm in {passes} passes, allowance {} mm",
            fmt(depth),
            fmt(args.allowance)
        ),
        format!(
            "feed {} mm/min, plunge {} mm/min, spindle {} rpm",
            fmt(args.feed),
            fmt(args.plunge_feed),
            fmt(args.spindle)
        ),
        match args.direction {
            DirectionArg::Climb => "climb milling, spindle clockwise M3: walls CCW, islands CW",
            DirectionArg::Conventional => "conventional milling, spindle clockwise M3: walls CW, islands CCW",
        }
        .to_string(),
        format!(
            "pockets {}, loops {loops}, retracts {}",
            analysis.regions.pockets.len(),
            stats.retracts
        ),
        format!(
            "cutting {:.1} mm, rapid {:.1} mm, time about {}",
            stats.cut_length + stats.plunge_length,
            stats.rapid_length,
            fmt_time(seconds)
        ),
    ];
    let settings = ProgramSettings {
        units,
        feed: args.feed,
        plunge_feed: args.plunge_feed,
        spindle: args.spindle,
        safe_z: args.safe_z,
        header,
    };
    let dialect = match args.post {
        PostArg::Grbl => Dialect::Grbl,
        PostArg::Linuxcnc => Dialect::LinuxCnc,
        PostArg::Mach3 => Dialect::Mach3,
    };
    let program = write_gcode(&job.linked.toolpath, &settings, dialect);
    if args.check {
        let params = pocketeer::simulate::CheckParams {
            tool_radius: 0.5 * diameter,
            depth: Some(depth),
            gouge_tolerance: 0.01,
            leftover_tolerance: 0.05,
        };
        let read = pocketeer::simulate::read_program(&program)
            .map_err(|e| Failure(format!("the program written does not read back: {e}")))?;
        let report = pocketeer::simulate::check_program(&analysis.regions.pockets, &read, &params, tol)
            .map_err(|e| Failure(format!("{name}: cannot check the program: {e}")))?;
        eprint!("{}", crate::check::to_text(&report, &params));
        if !report.passed {
            return Err(Failure(format!(
                "{name}: the check failed (gouge {:.4} mm, thickest leftover {:.4} mm); {} not written",
                report.gouge,
                report.thickest,
                args.output.display()
            )));
        }
    }
    if let Some(path) = &args.svg {
        let doc = preview(&analysis, &job);
        output::write_atomic(path, doc.as_bytes()).map_err(Failure)?;
    }
    output::write_atomic(&args.output, program.as_bytes()).map_err(Failure)?;
    for w in analysis.regions.warnings.iter().chain(&job.linked.warnings) {
        eprintln!("pocketeer: warning: {w}");
    }
    eprintln!(
        "{} pocket(s), {loops} loop(s) in {passes} pass(es): cutting {:.1} mm, rapid {:.1} mm, {} retract(s), about {} (rapids at {RAPID_RATE} mm/min); written to {}",
        analysis.regions.pockets.len(),
        stats.cut_length + stats.plunge_length,
        stats.rapid_length,
        stats.retracts,
        fmt_time(seconds),
        args.output.display()
    );
    Ok(())
}

fn preview(analysis: &pocketeer::Analysis, job: &pocketeer::job::Job) -> String {
    use pocketeer::export::svg;
    let walls: Vec<pocketeer::geom::Contour> = analysis
        .regions
        .pockets
        .iter()
        .flat_map(|p| p.contours().cloned())
        .collect();
    let (feeds, rapids) = svg::toolpath_segments(&job.linked.toolpath);
    svg::svg_document(&[
        svg::Layer {
            name: "drawing",
            stroke: "black",
            fill: "#dde6f0",
            contours: &walls,
            paths: &[],
        },
        svg::Layer {
            name: "cuts",
            stroke: "#2060c0",
            fill: "none",
            contours: &[],
            paths: &feeds,
        },
        svg::Layer {
            name: "rapids",
            stroke: "#d03030",
            fill: "none",
            contours: &[],
            paths: &rapids,
        },
    ])
}

fn file_name(p: &std::path::Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// A number without needless decimals.
fn fmt(v: f64) -> String {
    let t = format!("{v:.4}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn fmt_time(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}h{:02}m{:02}s", s / 3600, s / 60 % 60, s % 60)
    } else {
        format!("{}m{:02}s", s / 60, s % 60)
    }
}
