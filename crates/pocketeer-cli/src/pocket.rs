//! `pocketeer pocket`: the drawing in, a G-code program out. The flags become settings (with
//! defaults in the job's unit), the settings a plan, the plan a program with a header that says
//! how to make it again; the program is checked when asked and written last.

use crate::display::{count, num, JobUnits};
use crate::length::{parse_length, parse_nonneg_length, parse_point, parse_rate};
use crate::{output, read_analysis, DrawingArgs, Failure};
use clap::{Args, ValueEnum};
use pocketeer::clear::ClearParams;
use pocketeer::geom::Point;
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{estimate, write_gcode, Coolant, Dialect, Estimate, ProgramSettings, ProgramUnits};
use std::path::PathBuf;

#[derive(Args)]
pub struct PocketArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// Tool diameter (6, 6mm, 0.25in).
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true, required_unless_present = "layer_params")]
    tool_diameter: Option<f64>,
    /// Distance between neighbouring passes: a length (2.4, 2.4mm) or a share of the tool
    /// diameter (40%); less than the diameter.
    #[arg(long, value_parser = parse_stepover, allow_hyphen_values = true)]
    stepover: Stepover,
    /// Depth of the pocket below the stock top (Z=0), a positive length.
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true, required_unless_present = "layer_params")]
    depth: Option<f64>,
    /// Read milling parameters from layer names: `dxf2gcode` takes layers named
    /// `MILL: 1 Md: -3 Sd: -1.5 FeedXY: 400 Td: 6 …` (depth, step-down, feeds, tool number and
    /// diameter, spindle, heights) and pockets each such layer as one operation, the flags
    /// above as defaults; other layers are not cut.
    #[arg(long, value_enum, ignore_case = true)]
    layer_params: Option<LayerParamsArg>,
    /// Largest depth of one pass [default: the whole depth when it is at most the tool
    /// diameter, else equal passes of at most one diameter].
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    step_down: Option<f64>,
    /// Cutting feed per minute (1000, 1000mm/min, 40in/min) [default: 1000 mm/min; 40 in/min
    /// for an inch drawing].
    #[arg(long, value_parser = parse_rate, allow_hyphen_values = true)]
    feed: Option<f64>,
    /// Feed per minute straight down into the stock; helices and ramps go at the cutting feed,
    /// slowed where they would descend faster than this [default: 300 mm/min; 12 in/min for
    /// an inch drawing].
    #[arg(long, value_parser = parse_rate, allow_hyphen_values = true)]
    plunge_feed: Option<f64>,
    /// Spindle speed, rpm.
    #[arg(long, default_value_t = 12000.0, allow_hyphen_values = true)]
    spindle: f64,
    /// Seconds to wait after starting the spindle for it to reach its speed (G4); 0: none.
    #[arg(long, default_value_t = 2.0, allow_hyphen_values = true)]
    spindle_wait: f64,
    /// Height above the stock top (Z=0) for rapid moves [default: 5 mm; 0.2 in for an inch
    /// drawing].
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    safe_z: Option<f64>,
    /// How far above the stock, or above the floor already cut at that spot, rapid descents
    /// stop and the plunge feed takes over [default: 1 mm; 0.04 in for an inch drawing].
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    feed_height: Option<f64>,
    /// Milling direction, for a spindle turning clockwise (M3). climb: the material on the
    /// tool's right (the G41 side), pocket walls followed counter-clockwise and islands
    /// clockwise; conventional: the material on the left, walls clockwise, islands
    /// counter-clockwise.
    #[arg(long, value_enum, ignore_case = true, default_value_t = DirectionArg::Climb)]
    direction: DirectionArg,
    /// Material left on walls and islands by the roughing passes, then removed by one
    /// finishing pass at the wall.
    #[arg(long, default_value = "0", value_parser = parse_nonneg_length, allow_hyphen_values = true)]
    allowance: f64,
    /// How the tool enters the stock.
    #[arg(long, value_enum, ignore_case = true, default_value_t = EntryArg::Helix)]
    entry: EntryArg,
    /// Largest angle of helix and ramp entries from the horizontal, degrees.
    #[arg(long, default_value_t = 3.0, allow_hyphen_values = true)]
    ramp_angle: f64,
    /// The controller the program is for.
    #[arg(long, value_enum, ignore_case = true, default_value_t = PostArg::Grbl)]
    post: PostArg,
    /// Load this tool before starting (T n M6; GRBL, which has no tool changer, gets the T word
    /// and a comment) [default: no tool change].
    #[arg(long)]
    tool_number: Option<u32>,
    /// Coolant: flood (M8), mist (M7) or off.
    #[arg(long, value_enum, ignore_case = true, default_value_t = CoolantArg::Off)]
    coolant: CoolantArg,
    /// Where to move at the safe height at the end, X,Y (lengths: -10,150 or 0,6in)
    /// [default: stay above the last cut].
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true)]
    park: Option<(f64, f64)>,
    /// Rapid speed of the machine for the time estimate, per minute [default: 5000 mm/min;
    /// 200 in/min for an inch drawing].
    #[arg(long, value_parser = parse_rate, allow_hyphen_values = true)]
    rapid_rate: Option<f64>,
    /// Seconds each retract costs beyond its length at the rapid rate (accelerating, settling,
    /// coming down again), for the time estimate and the linking's choices.
    #[arg(long, default_value_t = pocketeer::machining_time::DEFAULT_RETRACT_SECONDS, allow_hyphen_values = true)]
    retract_time: f64,
    /// The G-code file to write (written only when everything succeeded); `-` writes to
    /// standard output.
    #[arg(short, long)]
    output: PathBuf,
    /// Write the program even to a file named like a drawing (`.dxf`).
    #[arg(long)]
    force: bool,
    /// Also draw the drawing, the loops and the tool path in this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Also write an interactive preview: one self-contained HTML page with the drawing, the
    /// program (play slider, moves by kind, the tool at its true size) and the summary.
    #[arg(long)]
    preview: Option<PathBuf>,
    /// Replay the program against the drawing before writing it (as `pocketeer check` does)
    /// and refuse to write it when it gouges or leaves material.
    #[arg(long)]
    check: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum LayerParamsArg {
    Dxf2gcode,
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

impl From<DirectionArg> for Direction {
    fn from(d: DirectionArg) -> Direction {
        match d {
            DirectionArg::Climb => Direction::Climb,
            DirectionArg::Conventional => Direction::Conventional,
        }
    }
}

impl From<EntryArg> for Entry {
    fn from(e: EntryArg) -> Entry {
        match e {
            EntryArg::Helix => Entry::Helix,
            EntryArg::Ramp => Entry::Ramp,
            EntryArg::Plunge => Entry::Plunge,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum PostArg {
    Grbl,
    Linuxcnc,
    Mach3,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum CoolantArg {
    Off,
    Flood,
    Mist,
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

/// Defaults that depend on the job's unit: round figures in that unit, not conversions.
struct Defaults {
    feed: f64,
    plunge_feed: f64,
    safe_z: f64,
    feed_height: f64,
    rapid_rate: f64,
}

impl Defaults {
    fn of(units: JobUnits) -> Defaults {
        match units {
            JobUnits::Millimetres => Defaults {
                feed: 1000.0,
                plunge_feed: 300.0,
                safe_z: 5.0,
                feed_height: 1.0,
                rapid_rate: pocketeer::simulate::check::RAPID_RATE,
            },
            JobUnits::Inches => Defaults {
                feed: 40.0 * 25.4,
                plunge_feed: 12.0 * 25.4,
                safe_z: 0.2 * 25.4,
                feed_height: 0.04 * 25.4,
                rapid_rate: 200.0 * 25.4,
            },
        }
    }
}

/// Everything the job is made with, in millimetres, defaults filled in.
struct Settings {
    units: JobUnits,
    diameter: f64,
    stepover: f64,
    depth: f64,
    step_down: f64,
    feed: f64,
    plunge_feed: f64,
    safe_z: f64,
    feed_height: f64,
    rapid_rate: f64,
    park: Option<Point>,
    dialect: Dialect,
}

fn positive(flag: &str, v: f64, why: &str) -> Result<f64, Failure> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Failure(format!("--{flag} {}: {why}", num(v, 6))))
    }
}

impl Settings {
    fn new(args: &PocketArgs, units: JobUnits) -> Result<Settings, Failure> {
        let d = Defaults::of(units);
        let diameter = positive(
            "tool-diameter",
            args.tool_diameter.unwrap_or(f64::NAN),
            "the tool diameter must be positive",
        )?;
        let stepover = match args.stepover {
            Stepover::Length(v) => v,
            Stepover::Percent(p) => diameter * p / 100.0,
        };
        let depth = positive(
            "depth",
            args.depth.unwrap_or(f64::NAN),
            "the depth must be positive: it is measured down from the stock top (Z=0), e.g. --depth 3",
        )?;
        let step_down = match args.step_down {
            Some(v) => positive("step-down", v, "the step-down must be positive")?,
            None if depth <= diameter => depth,
            None => diameter,
        };
        let feed = positive("feed", args.feed.unwrap_or(d.feed), "the feed must be positive")?;
        let plunge_feed = positive(
            "plunge-feed",
            args.plunge_feed.unwrap_or(d.plunge_feed),
            "the plunge feed must be positive",
        )?;
        positive(
            "spindle",
            args.spindle,
            "the spindle speed must be positive (rpm)",
        )?;
        if !(args.retract_time.is_finite() && args.retract_time >= 0.0) {
            return Err(Failure(format!(
                "--retract-time {}: a retract costs zero seconds or more",
                num(args.retract_time, 3)
            )));
        }
        if !(args.spindle_wait.is_finite() && args.spindle_wait >= 0.0) {
            return Err(Failure(format!(
                "--spindle-wait {}: a wait is zero seconds or more",
                num(args.spindle_wait, 3)
            )));
        }
        let safe_z = positive(
            "safe-z",
            args.safe_z.unwrap_or(d.safe_z),
            "the safe height must be above the stock top (Z=0): rapid moves travel there, over the stock and the clamps",
        )?;
        let feed_height = args.feed_height.unwrap_or(d.feed_height.min(safe_z));
        if !(feed_height.is_finite() && (0.0..=safe_z).contains(&feed_height)) {
            return Err(Failure(format!(
                "--feed-height {}: the feed height is between 0 (the stock top, or the floor already cut) and the safe height ({})",
                num(feed_height, 4),
                units.length(safe_z)
            )));
        }
        let rapid_rate = positive(
            "rapid-rate",
            args.rapid_rate.unwrap_or(d.rapid_rate),
            "the rapid rate must be positive",
        )?;
        let dialect = match args.post {
            PostArg::Grbl => Dialect::Grbl,
            PostArg::Linuxcnc => Dialect::LinuxCnc,
            PostArg::Mach3 => Dialect::Mach3,
        };
        if let Some(n) = args
            .tool_number
            .filter(|&n| args.post == PostArg::Grbl && n > 255)
        {
            return Err(Failure(format!(
                "--tool-number {n}: GRBL takes tool numbers up to 255"
            )));
        }
        if args.post == PostArg::Grbl && args.coolant == CoolantArg::Mist {
            return Err(Failure(
                "--coolant mist: GRBL 1.1 takes M7 only when built with ENABLE_M7, which its stock firmware is not; use --coolant flood (M8)".into(),
            ));
        }
        Ok(Settings {
            units,
            diameter,
            stepover,
            depth,
            step_down,
            feed,
            plunge_feed,
            safe_z,
            feed_height,
            rapid_rate,
            park: args.park.map(|(x, y)| Point::new(x, y)),
            dialect,
        })
    }

    fn clear(&self, args: &PocketArgs) -> ClearParams {
        ClearParams {
            tool_radius: 0.5 * self.diameter,
            stepover: self.stepover,
            allowance: args.allowance,
        }
    }

    fn link(&self, args: &PocketArgs) -> LinkParams {
        link_params(
            args,
            [self.depth, self.step_down, self.safe_z, self.feed_height],
            [self.feed, self.plunge_feed, self.rapid_rate],
        )
    }

    fn program(&self, args: &PocketArgs, header: Vec<String>) -> ProgramSettings {
        ProgramSettings {
            units: match self.units {
                JobUnits::Millimetres => ProgramUnits::Millimetres,
                JobUnits::Inches => ProgramUnits::Inches,
            },
            feed: self.feed,
            plunge_feed: self.plunge_feed,
            spindle: args.spindle,
            safe_z: self.safe_z,
            header,
            spindle_wait: args.spindle_wait,
            tool: args.tool_number,
            coolant: match args.coolant {
                CoolantArg::Off => Coolant::Off,
                CoolantArg::Flood => Coolant::Flood,
                CoolantArg::Mist => Coolant::Mist,
            },
            park: self.park,
        }
    }
}

pub fn run(args: &PocketArgs) -> Result<(), Failure> {
    guard_outputs(args)?;
    if args.layer_params.is_some() {
        return run_layer_params(args);
    }
    let spinner = crate::progress::Spinner::start("reading the drawing");
    let analysis = read_analysis(&args.drawing)?;
    let name = args.drawing.file.display();
    let s = Settings::new(args, JobUnits::of(analysis.drawing.units))?;
    let mut warnings = crate::inspect::import_warnings(&analysis);
    warnings.extend(crate::sanity::size_warnings(&analysis));
    spinner.bar_suspend(|| crate::print_warnings(&warnings));
    let tol = &analysis.tolerance;
    let job = pocketeer::job::pocket_job_with(
        &analysis.nesting.pockets,
        &s.clear(args),
        &s.link(args),
        tol,
        &spinner,
    )
    .map_err(|e| match e {
        pocketeer::job::JobError::ToolFitsNowhere { .. } => Failure(format!(
            "{name}: {e}; {}",
            crate::sanity::unit_advice(&analysis, false)
        )),
        e => Failure(format!("{name}: {e}")),
    })?;
    // The figures do not depend on the header: estimate them first, then write the header.
    let figures = estimate(
        &job.linked.toolpath,
        &s.program(args, Vec::new()),
        s.rapid_rate,
        args.retract_time,
    );
    let loops: usize = job.plans.iter().map(|p| p.loop_count()).sum();
    let passes = pocketeer::link::pass_depths(s.depth, s.step_down).len();
    let header = header(args, &s, &analysis, loops, passes, &figures);
    spinner.stage("writing the program");
    let program = write_gcode(&job.linked.toolpath, &s.program(args, header), s.dialect);
    let report = if args.check {
        spinner.stage("checking the program");
        Some(self_check(args, &s, &analysis, &program, &spinner)?)
    } else {
        None
    };
    if let Some(path) = &args.svg {
        let doc = preview(&analysis, &job, s.diameter);
        output::write_atomic(path, doc.as_bytes()).map_err(Failure)?;
    }
    let mut after: Vec<String> = (job.linked.warnings.iter().map(ToString::to_string))
        .chain(job.warnings.iter().map(ToString::to_string))
        .collect();
    after.extend(crate::sanity::time_warning(&analysis, figures.seconds));
    if let Some(path) = &args.preview {
        let text = warnings
            .iter()
            .chain(&after)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n");
        let doc = html_preview(args, &s, &analysis, &job, &program, report.as_ref(), text)?;
        output::write_atomic(path, doc.as_bytes()).map_err(Failure)?;
    }
    output::write_output(&args.output, program.as_bytes()).map_err(Failure)?;
    drop(spinner);
    crate::print_warnings(&after);
    let u = s.units;
    let extent = &analysis.drawing.extent;
    match u {
        JobUnits::Millimetres => eprintln!("drawing {}", crate::sanity::describe_extent(extent, u)),
        JobUnits::Inches => eprintln!(
            "drawing {} ({})",
            crate::sanity::describe_extent(extent, u),
            crate::sanity::describe_extent(extent, JobUnits::Millimetres)
        ),
    }
    eprintln!(
        "{}, {} in {}: cutting {}, rapid {}, {}, about {} (rapids at {}); written to {}",
        count(analysis.nesting.pockets.len(), "pocket", "pockets"),
        count(loops, "loop", "loops"),
        count(passes, "pass", "passes"),
        u.distance(figures.feed_length),
        u.distance(figures.rapid_length),
        count(figures.retracts, "retract", "retracts"),
        crate::display::time(figures.seconds),
        u.rate(s.rapid_rate),
        output::describe(&args.output)
    );
    Ok(())
}

/// The linking parameters from the flags, with `depth`, step-down, safe height and feed
/// height (mm) and the feed, plunge feed and rapid rate (mm/min) settled elsewhere.
fn link_params(
    args: &PocketArgs,
    [depth, step_down, safe_z, feed_height]: [f64; 4],
    [feed, plunge_feed, rapid]: [f64; 3],
) -> LinkParams {
    LinkParams {
        depth,
        step_down,
        safe_z,
        feed_height,
        direction: args.direction.into(),
        entry: args.entry.into(),
        ramp_angle: args.ramp_angle.to_radians(),
        time: pocketeer::machining_time::TimeModel {
            feed,
            plunge_feed,
            rapid,
            per_retract: args.retract_time,
        },
    }
}

/// `--layer-params dxf2gcode`: every `MILL:` layer of the drawing one operation, the
/// parameters in its name over the flags, all in one program with the tool changes between
/// them (as `pocketeer job` writes it).
fn run_layer_params(args: &PocketArgs) -> Result<(), Failure> {
    use pocketeer::job::{Job, Operation, Tool};
    let name = args.drawing.file.display().to_string();
    let bytes =
        std::fs::read(&args.drawing.file).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let options = crate::import_options(&args.drawing);
    let drawing = pocketeer::read_drawing(&bytes, &options).map_err(|e| Failure(format!("{name}: {e}")))?;
    let units = JobUnits::of(drawing.units);
    let d = Defaults::of(units);
    let mm = drawing.units.mm();
    let mut tools: Vec<Tool> = Vec::new();
    let mut operations = Vec::new();
    for layer in &drawing.layers {
        let Some(p) = crate::layer_params::parse(layer, mm).map_err(|e| Failure(format!("{name}: {e}")))?
        else {
            continue;
        };
        if !p.unused.is_empty() {
            crate::print_warnings(&[format!(
                "layer '{layer}': {} not used (pocketeer cuts from the stock top, Z=0)",
                p.unused.join(", ")
            )]);
        }
        let diameter = positive(
            "tool-diameter",
            p.diameter.or(args.tool_diameter).ok_or_else(|| {
                Failure(format!(
                    "{name}: layer '{layer}' gives no tool diameter (Td: D): give one there or with --tool-diameter"
                ))
            })?,
            &format!("layer '{layer}': the tool diameter must be positive"),
        )?;
        let depth = positive(
            "depth",
            p.depth.or(args.depth).ok_or_else(|| {
                Failure(format!(
                    "{name}: layer '{layer}' gives no depth (Md: -D): give one there or with --depth"
                ))
            })?,
            &format!("layer '{layer}': the depth must be positive"),
        )?;
        let step_down = match p.step_down.or(args.step_down) {
            Some(v) => positive(
                "step-down",
                v,
                &format!("layer '{layer}': the step-down must be positive"),
            )?,
            None if depth <= diameter => depth,
            None => diameter,
        };
        let feed = positive(
            "feed",
            p.feed.or(args.feed).unwrap_or(d.feed),
            &format!("layer '{layer}': the feed must be positive"),
        )?;
        let plunge_feed = positive(
            "plunge-feed",
            p.plunge_feed.or(args.plunge_feed).unwrap_or(d.plunge_feed),
            &format!("layer '{layer}': the plunge feed must be positive"),
        )?;
        let spindle = positive(
            "spindle",
            p.spindle.unwrap_or(args.spindle),
            &format!("layer '{layer}': the spindle speed must be positive"),
        )?;
        let tool = Tool {
            number: 0,
            diameter,
            feed,
            plunge_feed,
            spindle,
        };
        let same = |t: &Tool| {
            t.diameter == tool.diameter
                && t.feed == feed
                && t.plunge_feed == plunge_feed
                && t.spindle == spindle
        };
        let number = match p.tool.or(args.tool_number) {
            Some(n) => n,
            None => tools.iter().find(|t| same(t)).map_or_else(
                || tools.iter().map(|t| t.number).max().unwrap_or(0) + 1,
                |t| t.number,
            ),
        };
        match tools.iter().find(|t| t.number == number) {
            Some(t) if !same(t) => {
                return Err(Failure(format!(
                "{name}: layer '{layer}': tool {number} is {} mm across on an earlier layer and {} mm here",
                crate::display::num(t.diameter, 4),
                crate::display::num(diameter, 4)
            )))
            }
            Some(_) => {}
            None => tools.push(Tool { number, ..tool }),
        }
        let safe_z = positive(
            "safe-z",
            p.safe_z.or(args.safe_z).unwrap_or(d.safe_z),
            &format!("layer '{layer}': the safe height must be above the stock top"),
        )?;
        let feed_height = p
            .feed_height
            .or(args.feed_height)
            .unwrap_or(d.feed_height)
            .clamp(0.0, safe_z);
        let stepover = match args.stepover {
            Stepover::Length(v) => v,
            Stepover::Percent(pc) => diameter * pc / 100.0,
        };
        operations.push(Operation {
            layers: vec![layer.clone()],
            tool: number,
            stepover,
            allowance: args.allowance,
            link: link_params(
                args,
                [depth, step_down, safe_z, feed_height],
                [feed, plunge_feed, args.rapid_rate.unwrap_or(d.rapid_rate)],
            ),
            rest: false,
        });
    }
    if operations.is_empty() {
        return Err(Failure(format!(
            "{name}: --layer-params dxf2gcode: no layer is named 'MILL: …' (its layers: {})",
            drawing.layers.join(", ")
        )));
    }
    let loaded = crate::job::Loaded::new(
        Job { tools, operations },
        args.drawing.file.clone(),
        args.output.clone(),
        match args.post {
            PostArg::Grbl => Dialect::Grbl,
            PostArg::Linuxcnc => Dialect::LinuxCnc,
            PostArg::Mach3 => Dialect::Mach3,
        },
        match args.coolant {
            CoolantArg::Off => Coolant::Off,
            CoolantArg::Flood => Coolant::Flood,
            CoolantArg::Mist => Coolant::Mist,
        },
        args.spindle_wait,
        args.rapid_rate.unwrap_or(d.rapid_rate),
        args.retract_time,
        options,
    )
    .with_park(args.park.map(|(x, y)| pocketeer::geom::Point::new(x, y)));
    let analyses = crate::job::analyses(None, &loaded, &bytes)?;
    let check = args.check.then_some(name.as_str());
    crate::job::execute(
        &loaded,
        &analyses,
        &args.drawing.file,
        args.preview.as_deref(),
        check,
        &|e| format!("{name}: {e}"),
    )
}

/// The program's header: every setting needed to make it again, in the job's unit, and the
/// command line. Short lines: some senders and controllers limit a line to 80 characters.
fn header(
    args: &PocketArgs,
    s: &Settings,
    analysis: &pocketeer::Analysis,
    loops: usize,
    passes: usize,
    figures: &Estimate,
) -> Vec<String> {
    let u = s.units;
    let h = vec![
        format!("pocketeer {}", env!("CARGO_PKG_VERSION")),
        format!("drawing {}", output::file_name(&args.drawing.file)),
        format!("units {}: {}", u.symbol(), crate::sanity::unit_origin(analysis)),
        format!(
            "tool diameter {}, stepover {}",
            u.length(s.diameter),
            u.length(s.stepover)
        ),
        format!(
            "depth {} in {} of {}, step-down at most {}, allowance {}",
            u.length(s.depth),
            count(passes, "pass", "passes"),
            u.length(s.depth / passes.max(1) as f64),
            u.length(s.step_down),
            u.length(args.allowance)
        ),
        format!(
            "feed {}, plunge {}, spindle {} rpm, wait {} s",
            u.rate(s.feed),
            u.rate(s.plunge_feed),
            num(args.spindle, 3),
            num(args.spindle_wait, 3)
        ),
        format!(
            "safe height {}, feed height {}",
            u.length(s.safe_z),
            u.length(s.feed_height)
        ),
        match args.direction {
            DirectionArg::Climb => "climb milling, spindle clockwise M3: walls CCW, islands CW",
            DirectionArg::Conventional => "conventional milling, spindle clockwise M3: walls CW, islands CCW",
        }
        .to_string(),
        format!(
            "entry {}, at most {} degrees",
            args.entry
                .to_possible_value()
                .map_or(String::new(), |v| v.get_name().to_owned()),
            num(args.ramp_angle, 3)
        ),
        format!(
            "{}, {}, retracts {}",
            count(analysis.nesting.pockets.len(), "pocket", "pockets"),
            count(loops, "loop", "loops"),
            figures.retracts
        ),
        format!(
            "cutting {}, rapid {}, time about {}",
            u.distance(figures.feed_length),
            u.distance(figures.rapid_length),
            crate::display::time(figures.seconds)
        ),
        format!("time at rapids of {}", u.rate(s.rapid_rate)),
    ];
    let mut lines: Vec<String> = h.iter().flat_map(|l| crate::display::wrap(l, 72)).collect();
    lines.extend(crate::display::command_line_comment());
    lines
}

/// The interactive page of the job: the program read back from its text.
fn html_preview(
    args: &PocketArgs,
    s: &Settings,
    analysis: &pocketeer::Analysis,
    job: &pocketeer::job::PocketJob,
    program: &str,
    report: Option<&pocketeer::simulate::CheckReport>,
    text: String,
) -> Result<String, Failure> {
    let read = pocketeer::simulate::read_program(program)
        .map_err(|e| Failure(format!("the program written does not read back: {e}")))?;
    let u = s.units;
    let passes = pocketeer::link::pass_depths(s.depth, s.step_down).len();
    let loops: usize = job.plans.iter().map(|p| p.loop_count()).sum();
    let settings = vec![
        ("stepover".to_string(), u.length(s.stepover)),
        (
            "depth".to_string(),
            format!("{} in {}", u.length(s.depth), count(passes, "pass", "passes")),
        ),
        (
            "feed".to_string(),
            format!("{}, plunge {}", u.rate(s.feed), u.rate(s.plunge_feed)),
        ),
        (
            "pockets".to_string(),
            format!(
                "{}, {}",
                analysis.nesting.pockets.len(),
                count(loops, "loop", "loops")
            ),
        ),
    ];
    let too_narrow = job
        .warnings
        .iter()
        .map(|w| match w {
            pocketeer::job::JobWarning::TooNarrow { pocket, .. } => *pocket,
        })
        .collect();
    let context = crate::page::Context {
        title: format!(
            "{} → {}",
            output::file_name(&args.drawing.file),
            output::file_name(&args.output)
        ),
        tool_diameter: s.diameter,
        tool_changes: Vec::new(),
        inches: u == JobUnits::Inches,
        rapid_rate: s.rapid_rate,
        per_retract: args.retract_time,
        settings,
        too_narrow,
        check: report,
        report: text,
    };
    Ok(crate::page::html(analysis, &read, &context))
}

/// Replays the program against the drawing; refuses to write it when the check fails.
fn self_check(
    args: &PocketArgs,
    s: &Settings,
    analysis: &pocketeer::Analysis,
    program: &str,
    spinner: &crate::progress::Spinner,
) -> Result<pocketeer::simulate::CheckReport, Failure> {
    let name = args.drawing.file.display();
    let params = pocketeer::simulate::CheckParams {
        tool_radius: 0.5 * s.diameter,
        depth: Some(s.depth),
        gouge_tolerance: pocketeer::simulate::check::GOUGE_TOLERANCE,
        leftover_tolerance: pocketeer::simulate::check::LEFTOVER_TOLERANCE,
        rapid_rate: s.rapid_rate,
        per_retract: args.retract_time,
    };
    let read = pocketeer::simulate::read_program(program)
        .map_err(|e| Failure(format!("the program written does not read back: {e}")))?;
    let report = pocketeer::simulate::check_program_tools_with(
        &analysis.nesting.pockets,
        &read,
        &[],
        &params,
        &analysis.tolerance,
        spinner,
    )
    .map_err(|e| Failure(format!("{name}: cannot check the program: {e}")))?;
    spinner.bar_suspend(|| eprint!("{}", crate::check::to_text(&report, &params)));
    if report.passed {
        return Ok(report);
    }
    Err(Failure(format!(
        "{name}: the check failed (gouge {:.4} mm, thickest leftover {:.4} mm); {} not written",
        report.gouge,
        report.thickest,
        output::describe(&args.output)
    )))
}

/// Refuses outputs that would overwrite the drawing or each other, and a program written to a
/// `.dxf` file (most likely a drawing given as `-o` by mistake) unless `--force`.
fn guard_outputs(args: &PocketArgs) -> Result<(), Failure> {
    let mut outputs = vec![("-o", args.output.as_path())];
    if let Some(svg) = &args.svg {
        outputs.push(("--svg", svg.as_path()));
    }
    if let Some(page) = &args.preview {
        outputs.push(("--preview", page.as_path()));
    }
    output::guard(&[&args.drawing.file], &outputs).map_err(Failure)?;
    let dxf = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dxf"));
    if dxf && !args.force {
        return Err(Failure(format!(
            "-o {}: a G-code program would be written to a .dxf file; choose a .nc file, or pass --force if that is really meant",
            args.output.display()
        )));
    }
    Ok(())
}

fn preview(analysis: &pocketeer::Analysis, job: &pocketeer::job::PocketJob, diameter: f64) -> String {
    use pocketeer::export::svg;
    let (feeds, rapids) = svg::toolpath_segments(&job.linked.toolpath);
    crate::preview::document(
        analysis,
        &[
            svg::Layer {
                name: "cuts",
                stroke: "#2060c0",
                fill: "none",
                contours: &[],
                paths: &feeds,
                label: "feed moves (cuts, links, entries)",
                width: 0.08 * diameter,
                dash: false,
                frames: false,
            },
            svg::Layer {
                name: "rapids",
                stroke: "#d03030",
                fill: "none",
                contours: &[],
                paths: &rapids,
                label: "rapids",
                width: 0.05 * diameter,
                dash: true,
                frames: false,
            },
        ],
    )
}
