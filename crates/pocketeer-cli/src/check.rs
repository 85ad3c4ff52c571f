//! `pocketeer check`: a program replayed against its drawing.

use crate::length::{parse_length, parse_nonneg_length, parse_rate};
use crate::{emit, output, read_analysis, DrawingArgs, Failure};
use clap::Args;
use pocketeer::simulate::{read_program, CheckParams, CheckReport};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct CheckArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// The G-code program to check.
    program: PathBuf,
    /// Tool diameter (6, 6mm, 0.25in), for a program of one tool.
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    tool_diameter: Option<f64>,
    /// For a program of several tools: the diameter of tool T (its T word), as T=D (2=2mm);
    /// once per tool. Each move's gouge is measured with its tool, the leftover against the
    /// smallest. Given a job file (.toml) in place of the drawing, its tools and layers are
    /// used: each layer checked at its own depth with the operations on it.
    #[arg(long = "tool", value_parser = parse_tool, allow_hyphen_values = true)]
    tools: Vec<(u32, f64)>,
    /// Depth of the pocket below Z=0: the area swept at this depth or deeper is judged
    /// [default: the deepest Z of the program].
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    depth: Option<f64>,
    /// Rapid speed of the machine for the time estimate, per minute.
    #[arg(long, default_value_t = pocketeer::simulate::check::RAPID_RATE, value_parser = parse_rate, allow_hyphen_values = true)]
    rapid_rate: f64,
    /// Seconds each retract costs beyond its length at the rapid rate, for the time estimate.
    #[arg(long, default_value_t = pocketeer::machining_time::DEFAULT_RETRACT_SECONDS, allow_hyphen_values = true)]
    retract_time: f64,
    /// Largest gouge accepted.
    #[arg(long, default_value_t = pocketeer::simulate::check::GOUGE_TOLERANCE, value_parser = parse_nonneg_length, allow_hyphen_values = true)]
    gouge_tolerance: f64,
    /// Thickest leftover accepted.
    #[arg(long, default_value_t = pocketeer::simulate::check::LEFTOVER_TOLERANCE, value_parser = parse_nonneg_length, allow_hyphen_values = true)]
    leftover_tolerance: f64,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Also draw the pockets, the swept area and the leftover in this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Also write an interactive preview: one self-contained HTML page with the drawing, the
    /// program, the gouges and leftovers marked and numbered, and the report.
    #[arg(long)]
    preview: Option<PathBuf>,
}

/// The outcome: the report passed (exit 0) or found defects (exit 1).
pub enum Verdict {
    Passed,
    Failed,
}

/// Refuses a rapid rate that is not positive and a retract cost below zero.
pub fn rates_valid(rapid_rate: f64, retract_time: f64) -> Result<(), Failure> {
    if !(rapid_rate.is_finite() && rapid_rate > 0.0) {
        return Err(Failure(format!(
            "--rapid-rate {rapid_rate}: the rapid rate must be positive"
        )));
    }
    if !(retract_time.is_finite() && retract_time >= 0.0) {
        return Err(Failure(format!(
            "--retract-time {retract_time}: a retract costs zero seconds or more"
        )));
    }
    Ok(())
}

/// `T=D`: a tool number and its diameter.
fn parse_tool(s: &str) -> Result<(u32, f64), String> {
    let (t, d) = s
        .split_once('=')
        .ok_or_else(|| format!("'{s}': a tool as T=D (example: 2=2mm)"))?;
    let t: u32 = t
        .trim()
        .parse()
        .map_err(|_| format!("'{t}' is not a tool number"))?;
    let d = parse_length(d)?;
    if !(d.is_finite() && d > 0.0) {
        return Err(format!("'{s}': the diameter must be positive"));
    }
    Ok((t, d))
}

pub fn run(args: &CheckArgs) -> Result<Verdict, Failure> {
    let is_job = args
        .drawing
        .file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    if is_job {
        return check_job(args);
    }
    let tool_diameter = match (args.tool_diameter, args.tools.first()) {
        (Some(d), _) => d,
        (None, Some(&(_, d))) => d,
        (None, None) => {
            return Err(Failure(
                "--tool-diameter (or --tool T=D for each tool of the program, or a job file in place of the drawing) is needed".into(),
            ))
        }
    };
    if !(tool_diameter.is_finite() && tool_diameter > 0.0) {
        return Err(Failure(format!(
            "--tool-diameter {tool_diameter}: the tool diameter must be positive"
        )));
    }
    if let Some(d) = args.depth.filter(|d| !(d.is_finite() && *d > 0.0)) {
        return Err(Failure(format!(
            "--depth {d}: the depth must be positive: it is measured down from the stock top (Z=0)"
        )));
    }
    rates_valid(args.rapid_rate, args.retract_time)?;
    let mut outputs = Vec::new();
    if let Some(svg) = &args.svg {
        outputs.push(("--svg", svg.as_path()));
    }
    if let Some(page) = &args.preview {
        outputs.push(("--preview", page.as_path()));
    }
    output::guard(&[&args.drawing.file, &args.program], &outputs).map_err(Failure)?;
    let analysis = read_analysis(&args.drawing)?;
    let name = args.program.display();
    let text = std::fs::read(&args.program).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let text = String::from_utf8_lossy(&text);
    let program = read_program(&text).map_err(|e| Failure(format!("{name}: {e}")))?;
    let params = CheckParams {
        tool_radius: 0.5 * tool_diameter,
        depth: args.depth,
        gouge_tolerance: args.gouge_tolerance,
        leftover_tolerance: args.leftover_tolerance,
        rapid_rate: args.rapid_rate,
        per_retract: args.retract_time,
    };
    let spinner = crate::progress::Spinner::start("replaying the program");
    let radii = if args.tools.is_empty() {
        vec![(0, params.tool_radius)]
    } else {
        tool_radii(&program, &args.tools, &name.to_string())?
    };
    let report = pocketeer::simulate::check_program_tools_with(
        &analysis.nesting.pockets,
        &program,
        &radii,
        &params,
        &analysis.tolerance,
        &spinner,
    )
    .map_err(|e| Failure(format!("{}: {e}", args.drawing.file.display())))?;
    drop(spinner);
    if let Some(path) = &args.svg {
        output::write_atomic(
            path,
            preview(&analysis, &program, &report, tool_diameter).as_bytes(),
        )
        .map_err(Failure)?;
    }
    if let Some(path) = &args.preview {
        let context = crate::page::Context {
            title: format!(
                "{} → {}",
                output::file_name(&args.drawing.file),
                output::file_name(&args.program)
            ),
            tool_diameter,
            tool_changes: radii.iter().map(|&(k, r)| (k, 2.0 * r)).collect(),
            inches: crate::display::JobUnits::of(analysis.drawing.units) == crate::display::JobUnits::Inches,
            rapid_rate: args.rapid_rate,
            per_retract: args.retract_time,
            settings: Vec::new(),
            too_narrow: (0..report.pockets.len())
                .filter(|&i| report.pockets[i].reachable_area <= 0.0)
                .collect(),
            check: Some(&report),
            report: to_text(&report, &params),
        };
        let doc = crate::page::html(&analysis, &program, &context);
        output::write_atomic(path, doc.as_bytes()).map_err(Failure)?;
    }
    let text = if args.json {
        let mut t =
            serde_json::to_string_pretty(&report).map_err(|e| Failure(format!("cannot write JSON: {e}")))?;
        t.push('\n');
        t
    } else {
        to_text(&report, &params)
    };
    emit(&text)?;
    Ok(if report.passed {
        Verdict::Passed
    } else {
        Verdict::Failed
    })
}

/// Each tool's radius from the move it is loaded at, by the program's T words and the
/// diameters given; moves before the first T word are the first tool's.
fn tool_radii(
    program: &pocketeer::simulate::Program,
    tools: &[(u32, f64)],
    name: &str,
) -> Result<Vec<(usize, f64)>, Failure> {
    let diameter = |t: u32| tools.iter().find(|x| x.0 == t).map(|x| x.1);
    let mut out = Vec::new();
    for &(k, t) in &program.tools {
        let d = diameter(t).ok_or_else(|| {
            let line = program.moves.get(k).map_or(0, |m| m.line);
            Failure(format!(
                "{name}: tool {t} is loaded (before line {line}): give its diameter with --tool {t}=D"
            ))
        })?;
        out.push((k, 0.5 * d));
    }
    if out.is_empty() {
        out.push((0, 0.5 * tools[0].1));
    }
    out[0].0 = 0;
    Ok(out)
}

/// `check JOB.toml PROGRAM`: every layer set of the job checked at its own depth with the
/// moves of the operations on it (the program's `(operation N: …)` comments say which), each
/// tool's gouge with its radius, the leftover against the smallest tool's reach, and the
/// stock cut deeper than the layer's depth.
fn check_job(args: &CheckArgs) -> Result<Verdict, Failure> {
    let (loaded, analyses, _) = crate::job::read_job(&args.drawing.file, None)?;
    let name = args.program.display().to_string();
    let text = std::fs::read(&args.program).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let text = String::from_utf8_lossy(&text);
    let tolerances = (args.gouge_tolerance, args.leftover_tolerance);
    let spinner = crate::progress::Spinner::start("replaying the program");
    let (report, passed) = job_report(&loaded, &analyses, &name, &text, tolerances)?;
    drop(spinner);
    emit(&report)?;
    Ok(if passed { Verdict::Passed } else { Verdict::Failed })
}

/// The report of a job's program `text` (named `name`), and whether it passed, with the
/// gouge and leftover tolerances given.
pub fn job_report(
    loaded: &crate::job::Loaded,
    analyses: &crate::job::Analyses,
    name: &str,
    text: &str,
    (gouge_tolerance, leftover_tolerance): (f64, f64),
) -> Result<(String, bool), Failure> {
    let program = read_program(text).map_err(|e| Failure(format!("{name}: {e}")))?;
    // Where each operation's moves start: its comment after the header.
    let header_end = text
        .lines()
        .position(|l| !l.trim_start().starts_with('('))
        .unwrap_or(0);
    let mut starts: Vec<(usize, usize)> = Vec::new(); // (line from 1, operation)
    for (i, l) in text.lines().enumerate().skip(header_end) {
        if let Some(rest) = l.trim().strip_prefix("(operation ") {
            if let Some(n) = rest
                .split(':')
                .next()
                .and_then(|n| n.trim().parse::<usize>().ok())
            {
                starts.push((i + 1, n.saturating_sub(1)));
            }
        }
    }
    if starts.is_empty() {
        return Err(Failure(format!(
            "{name}: no (operation N: ...) comments: not a program of this job; check it with --tool T=D against the drawing instead"
        )));
    }
    let op_of_line = |line: usize| starts.iter().take_while(|s| s.0 <= line).last().map(|s| s.1);
    let mut sets: Vec<Vec<String>> = Vec::new();
    for op in &loaded.job.operations {
        let key = crate::job::layer_key(&op.layers);
        if !sets.contains(&key) {
            sets.push(key);
        }
    }
    let mut out = String::new();
    let mut passed = true;
    for key in &sets {
        let Some(a) = analyses.get(key) else { continue };
        let ops: Vec<usize> = (0..loaded.job.operations.len())
            .filter(|&k| crate::job::layer_key(&loaded.job.operations[k].layers) == *key)
            .collect();
        let depth = ops
            .iter()
            .map(|&k| loaded.job.operations[k].link.depth)
            .fold(0.0, f64::max);
        let mut moves = Vec::new();
        let mut radii: Vec<(usize, f64)> = Vec::new();
        let mut last_op = None;
        for m in &program.moves {
            let Some(op) = op_of_line(m.line).filter(|op| ops.contains(op)) else {
                continue;
            };
            if last_op != Some(op) {
                let number = loaded.job.operations[op].tool;
                let d = loaded
                    .job
                    .tools
                    .iter()
                    .find(|t| t.number == number)
                    .map_or(0.0, |t| t.diameter);
                radii.push((moves.len(), 0.5 * d));
                last_op = Some(op);
            }
            moves.push(*m);
        }
        if moves.is_empty() {
            continue;
        }
        let part = pocketeer::simulate::Program {
            moves,
            dwell: 0.0,
            tools: Vec::new(),
        };
        // The reach of the layers' smallest tool, whether or not it has moves.
        let r_min = ops
            .iter()
            .filter_map(|&k| {
                let n = loaded.job.operations[k].tool;
                loaded.job.tools.iter().find(|t| t.number == n)
            })
            .map(|t| 0.5 * t.diameter)
            .fold(f64::INFINITY, f64::min);
        let params = CheckParams {
            tool_radius: r_min,
            depth: Some(depth),
            gouge_tolerance,
            leftover_tolerance,
            rapid_rate: loaded.rapid_rate,
            per_retract: loaded.retract_time,
        };
        let report = pocketeer::simulate::check_program_tools(
            &a.nesting.pockets,
            &part,
            &radii,
            &params,
            &a.tolerance,
        )
        .map_err(|e| Failure(format!("{}: {e}", loaded.drawing.display())))?;
        let deeper = report.deepest < -depth - 1e-3;
        let _ = writeln!(
            out,
            "layers {} at {} mm, operations {}:",
            key.join(", "),
            crate::display::num(depth, 4),
            ops.iter()
                .map(|k| (k + 1).to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        out.push_str(&to_text(&report, &params));
        if deeper {
            let _ = writeln!(
                out,
                "CUT TOO DEEP: Z{:.4}, below the layers' depth of {} mm",
                report.deepest,
                crate::display::num(depth, 4)
            );
        }
        passed &= report.passed && !deeper;
    }
    let _ = writeln!(out, "{}", if passed { "JOB PASSED" } else { "JOB FAILED" });
    Ok((out, passed))
}

fn place(p: &Option<pocketeer::simulate::check::Place>) -> String {
    match p {
        Some(p) if p.line > 0 => format!(" at ({:.3}, {:.3}), line {}", p.x, p.y, p.line),
        Some(p) => format!(" at ({:.3}, {:.3})", p.x, p.y),
        None => String::new(),
    }
}

/// The readable report.
pub fn to_text(r: &CheckReport, params: &CheckParams) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "final depth  Z{:.4} (deepest Z{:.4})",
        r.final_depth, r.deepest
    );
    for (i, p) in r.pockets.iter().enumerate() {
        let _ = writeln!(
            s,
            "pocket {}     area {:.3} mm², reachable {:.3} mm²\n  gouge      {:.4} mm{}\n  leftover   {:.4} mm² ({:.4} %), thickest {:.4} mm{}",
            i + 1,
            p.area,
            p.reachable_area,
            p.gouge,
            place(&p.gouge_at),
            p.leftover_area,
            p.leftover_percent,
            p.thickest,
            place(&p.thickest_at)
        );
    }
    let lines = |v: &[pocketeer::simulate::check::Place]| {
        let l: Vec<String> = v.iter().take(5).map(|p| p.line.to_string()).collect();
        if v.is_empty() {
            "none".to_string()
        } else {
            format!(
                "{} (lines {}{})",
                v.len(),
                l.join(", "),
                if v.len() > 5 { ", ..." } else { "" }
            )
        }
    };
    let _ = writeln!(s, "rapids into the stock     {}", lines(&r.rapids_into_stock));
    let _ = writeln!(s, "plunges into uncut stock  {}", lines(&r.plunges));
    let _ = writeln!(s, "feed moves without F      {}", lines(&r.feedless));
    let sides = &r.wall_sides;
    match sides.climb_share() {
        Some(share) => {
            let _ = writeln!(
                s,
                "along walls               {:.1} mm at the final depth: {:.1} % climb (material on the tool's right, M3), {:.1} % conventional",
                sides.right + sides.left,
                100.0 * share,
                100.0 * (1.0 - share)
            );
        }
        None => {
            let _ = writeln!(
                s,
                "along walls               none: no move at the final depth follows a wall"
            );
        }
    }
    let e = &r.engagement;
    match &e.max_at {
        Some(at) => {
            let _ = writeln!(
                s,
                "tool engagement           max {:.0}° at line {} (X{:.3} Y{:.3}), 95 % of the {:.1} mm cut at one height at or below {:.0}° ({:.0}° of the length touching stock), {:.1} % above 90°, {:.1} % above 150°, {:.1} % touching no stock (entries not counted; sampled every {}° round the tool, {:.3} mm along)",
                e.max_deg,
                at.line,
                at.x,
                at.y,
                e.length,
                e.p95_deg,
                e.p95_in_contact_deg,
                e.above_90_percent,
                e.above_150_percent,
                e.untouched_percent,
                e.angle_step_deg,
                e.spacing
            );
        }
        None => {
            let _ = writeln!(
                s,
                "tool engagement           none: no cutting move below Z0 at one height"
            );
        }
    }
    let _ = writeln!(
        s,
        "cutting {:.1} mm, rapid {:.1} mm, {}, {} s of dwell, about {} (rapids at {} mm/min, {} s a retract)",
        r.cut_length,
        r.rapid_length,
        crate::display::count(r.retracts, "retract", "retracts"),
        crate::display::num(r.dwell, 3),
        crate::display::time(r.seconds),
        crate::display::num(params.rapid_rate, 3),
        crate::display::num(params.per_retract, 3)
    );
    let _ = writeln!(
        s,
        "{}: gouge {:.4} mm (tolerance {}), thickest leftover {:.4} mm (tolerance {})",
        if r.passed { "PASSED" } else { "FAILED" },
        r.gouge,
        params.gouge_tolerance,
        r.thickest,
        params.leftover_tolerance
    );
    s
}

fn preview(
    analysis: &pocketeer::Analysis,
    program: &pocketeer::simulate::Program,
    report: &CheckReport,
    diameter: f64,
) -> String {
    use pocketeer::export::svg;
    use pocketeer::geom::{Arc, Contour, Point, Segment};
    use pocketeer::simulate::gcode::Motion;
    let polys = |shapes: &[Vec<Vec<[f64; 2]>>]| -> Vec<Contour> {
        shapes
            .iter()
            .flatten()
            .filter(|r| r.len() >= 2)
            .map(|r| Contour::polygon(&r.iter().map(|p| Point::new(p[0], p[1])).collect::<Vec<_>>()))
            .collect()
    };
    let swept = polys(&report.swept);
    let leftover: Vec<Contour> = report.pockets.iter().flat_map(|p| polys(&p.leftover)).collect();
    // The tool path below the stock top, and a ring around every gouge and the thickest leftover.
    let path: Vec<Vec<Segment>> = program
        .moves
        .iter()
        .filter(|m| m.motion != Motion::Rapid && m.to.z.min(m.from.z) < 0.0)
        .map(|m| vec![m.footprint()])
        .filter(|s| s[0].length() > 0.0)
        .collect();
    let size = crate::sanity::pockets_extent(analysis);
    let mark = 0.01 * size.width().max(size.height()).max(1.0);
    let ring = |x: f64, y: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::new(x, y), mark))]);
    let gouges: Vec<Contour> = report
        .pockets
        .iter()
        .filter(|p| p.gouge > 0.001)
        .filter_map(|p| p.gouge_at.map(|a| ring(a.x, a.y)))
        .collect();
    let thick: Vec<Contour> = report
        .pockets
        .iter()
        .filter(|p| p.thickest > 0.001)
        .filter_map(|p| p.thickest_at.map(|a| ring(a.x, a.y)))
        .collect();
    crate::preview::document(
        analysis,
        &[
            svg::Layer {
                name: "swept",
                stroke: "none",
                fill: "#9cc3ea",
                contours: &swept,
                paths: &[],
                label: "swept at the final depth",
                width: 0.0,
                dash: false,
                frames: false,
            },
            svg::Layer {
                name: "path",
                stroke: "#2060c0",
                fill: "none",
                contours: &[],
                paths: &path,
                label: "feed moves below Z0",
                width: 0.08 * diameter,
                dash: false,
                frames: false,
            },
            svg::Layer {
                name: "leftover",
                stroke: "#d03030",
                fill: "#f08080",
                contours: &leftover,
                paths: &[],
                label: "material left",
                width: 0.0,
                dash: false,
                frames: false,
            },
            svg::Layer {
                name: "gouge",
                stroke: "#c000c0",
                fill: "none",
                contours: &gouges,
                paths: &[],
                label: "gouge",
                width: 0.0,
                dash: false,
                frames: false,
            },
            svg::Layer {
                name: "thickest-leftover",
                stroke: "#d07000",
                fill: "none",
                contours: &thick,
                paths: &[],
                label: "thickest leftover",
                width: 0.0,
                dash: false,
                frames: false,
            },
        ],
    )
}
