//! The `pocketeer` command: a thin layer of argument parsing and messages over the library.

mod allocator;
mod check;
mod deferred;
mod display;
mod inspect;
mod job;
mod jobfile;
mod layer_params;
mod length;
mod output;
mod page;
mod pocket;
mod preview;
mod progress;
mod sanity;
mod view;

use clap::{Args, Parser, Subcommand};
use deferred::Deferred;
use pocketeer::import::{FillRule, Units};
use pocketeer::ImportOptions;
use std::path::PathBuf;
use std::process::ExitCode;

/// Contour-parallel pocket milling from DXF drawings.
#[derive(Parser)]
#[command(name = "pocketeer", version, about, args_override_self = true)]
struct Cli {
    /// No progress on the terminal (warnings and the summary still print).
    #[arg(long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Show what a drawing holds: units, extents, layers, entities, contours, pockets and
    /// islands.
    Inspect(Deferred<InspectArgs>),
    /// Offset every pocket of a drawing by a distance and write the loops as a DXF.
    #[command(allow_negative_numbers = true)]
    Offset(Deferred<OffsetArgs>),
    /// Clear every pocket of a drawing and write the G-code program.
    #[command(allow_negative_numbers = true)]
    Pocket(Deferred<pocket::PocketArgs>),
    /// Replay a G-code program against its drawing: gouge, leftover, milling side, rapids,
    /// plunges, time.
    #[command(allow_negative_numbers = true)]
    Check(Deferred<check::CheckArgs>),
    /// Run a job file: operations on layers, each with a tool of the job's library, in one
    /// program with the tool changes between them.
    Job(Deferred<job::JobArgs>),
    /// Write an interactive preview of any G-code program over its drawing: one
    /// self-contained HTML page (zoom, pan, a play slider, moves by kind, the summary).
    #[command(allow_negative_numbers = true)]
    View(Deferred<view::ViewArgs>),
}

/// How to read a drawing (shared by every command that reads one).
#[derive(Args)]
struct DrawingArgs {
    /// The DXF drawing (ASCII or binary).
    file: PathBuf,
    /// Only these layers (comma-separated, case-insensitive).
    #[arg(long, value_delimiter = ',')]
    layers: Option<Vec<String>>,
    /// The drawing's unit when it declares none, or to override what it declares (mm, in, ...).
    #[arg(long)]
    units: Option<Units>,
    /// Free end points closer than this are moved to meet (a length: 0.001, 0.01mm, 0.0001in).
    #[arg(long, default_value = "0.001", value_parser = length::parse_nonneg_length, allow_hyphen_values = true)]
    join_tolerance: f64,
    /// Gaps up to this length between two free ends, each the other's nearest by far, are
    /// closed with a straight segment and reported; 0 closes none.
    #[arg(long, default_value = "0.05mm", value_parser = length::parse_nonneg_length, allow_hyphen_values = true)]
    close_gaps: f64,
    /// How an outline that crosses or touches itself is filled: `evenodd` (crossing the outline
    /// always changes inside to outside) or `nonzero` (a loop wound round twice stays filled).
    #[arg(long, value_enum, default_value = "evenodd")]
    fill: Fill,
    /// Refuse an outline that crosses or touches itself, naming where, instead of filling it.
    #[arg(long)]
    strict: bool,
    /// Ignore open chains even where they surround closed contours (refused by default: such a
    /// chain is most likely a pocket outline with a gap).
    #[arg(long)]
    ignore_open: bool,
}

/// The fill rules, as the command line spells them.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Fill {
    Evenodd,
    Nonzero,
}

#[derive(Args)]
struct InspectArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct OffsetArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// Offset distance (3, 3mm, 0.125in): positive shrinks the pockets, negative grows them.
    #[arg(long, value_parser = length::parse_length, allow_hyphen_values = true)]
    distance: f64,
    /// The DXF file to write: closed LWPOLYLINEs with bulges, in the drawing's units; `-`
    /// writes to standard output.
    #[arg(short, long)]
    output: PathBuf,
    /// Also draw the drawing and the loops in this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
}

/// A failure reported to the user: one message, exit code 2.
struct Failure(String);

fn read_analysis(args: &DrawingArgs) -> Result<pocketeer::Analysis, Failure> {
    let name = args.file.display();
    let bytes = std::fs::read(&args.file).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let options = import_options(args);
    pocketeer::analyze(&bytes, &options).map_err(|e| Failure(format!("{name}: {e}{}", advice(&e))))
}

/// How to read the drawing, from the drawing flags.
fn import_options(args: &DrawingArgs) -> ImportOptions {
    ImportOptions {
        layers: args.layers.clone(),
        units: args.units,
        join_tolerance: args.join_tolerance,
        close_gaps: args.close_gaps,
        fill: match args.fill {
            Fill::Evenodd => FillRule::EvenOdd,
            Fill::Nonzero => FillRule::NonZero,
        },
        strict: args.strict,
        ignore_open: args.ignore_open,
    }
}

/// What the user can do about an import error, in the flags of this command line: the
/// library's errors carry the numbers, the CLI words the advice.
fn advice(e: &pocketeer::ImportError) -> String {
    use pocketeer::ImportError;
    match e {
        ImportError::NoClosedContour { gap, .. } => format!(
            "; close the outline{}",
            gap.and_then(inspect::gap_flag)
                .map(|f| format!(" or pass {f}"))
                .unwrap_or_default()
        ),
        ImportError::OpenOutline { gap, .. } => format!(
            "; close it{}, leave its layer out with --layers, or pass --ignore-open",
            gap.and_then(inspect::gap_flag)
                .map(|f| format!(" or pass {f}"))
                .unwrap_or_default()
        ),
        _ => String::new(),
    }
}

fn inspect(args: &InspectArgs) -> Result<(), Failure> {
    let analysis = read_analysis(&args.drawing)?;
    let report = inspect::Report::new(&args.drawing.file.display().to_string(), &analysis);
    let text = if args.json {
        let mut t =
            serde_json::to_string_pretty(&report).map_err(|e| Failure(format!("cannot write JSON: {e}")))?;
        t.push('\n');
        t
    } else {
        report.to_text()
    };
    emit(&text)
}

fn offset(args: &OffsetArgs) -> Result<(), Failure> {
    use pocketeer::export::{dxf, svg};
    let mut outputs = vec![("-o", args.output.as_path())];
    if let Some(svg) = &args.svg {
        outputs.push(("--svg", svg.as_path()));
    }
    output::guard(&[&args.drawing.file], &outputs).map_err(Failure)?;
    let mut analysis = read_analysis(&args.drawing)?;
    print_warnings(&inspect::import_warnings(&analysis));
    let pockets = if args.svg.is_none() {
        // From here on only the pockets are read (the preview would draw the rest): the
        // drawing's elements and their chains, two more copies of every element, go back
        // before the offset, whose working memory is the run's peak, and the pockets are
        // offset without a copy.
        analysis.drawing.elements = Vec::new();
        analysis.chains = Default::default();
        std::mem::take(&mut analysis.nesting.pockets)
    } else {
        analysis.nesting.pockets.clone()
    };
    let pocket_count = pockets.len();
    let tol = &analysis.tolerance;
    let mut loops: Vec<pocketeer::geom::Contour> = Vec::new();
    let name = args.drawing.file.display();
    for (k, p) in pockets.into_iter().enumerate() {
        let at = p
            .boundary
            .segments
            .first()
            .map_or(pocketeer::geom::Point::new(0.0, 0.0), |s| s.start());
        let place = format!("pocket {} (outline through {})", k + 1, at);
        let region = pocketeer::geom::PreparedPocket::from_pocket(p);
        let offset = region
            .offset(args.distance, tol)
            .map_err(|e| Failure(format!("{name}: {place}: {e}")))?;
        if offset.is_empty() {
            let r = region
                .largest_inscribed_radius(tol)
                .map_err(|e| Failure(format!("{name}: {place}: {e}")))?;
            eprintln!(
                "pocketeer: warning: {place} has no loop at {} mm: its largest inscribed circle has a radius of {r:.4} mm",
                display::num(args.distance, 6)
            );
        }
        loops.extend(offset);
    }
    let layered: Vec<dxf::LayeredContour> = loops
        .iter()
        .map(|c| dxf::LayeredContour {
            layer: "offset",
            contour: c,
        })
        .collect();
    let text = dxf::write_dxf(&layered, analysis.drawing.units);
    output::write_output(&args.output, text.as_bytes()).map_err(Failure)?;
    if let Some(path) = &args.svg {
        let doc = preview::document(
            &analysis,
            &[svg::Layer {
                name: "offset",
                stroke: "#d03030",
                fill: "none",
                contours: &loops,
                paths: &[],
                label: "offset loops",
                width: 0.0,
                dash: false,
                frames: false,
            }],
        );
        output::write_atomic(path, doc.as_bytes()).map_err(Failure)?;
    }
    eprintln!(
        "{} offset by {} mm: {} written to {}",
        display::count(pocket_count, "pocket", "pockets"),
        display::num(args.distance, 6),
        display::count(loops.len(), "loop", "loops"),
        output::describe(&args.output)
    );
    Ok(())
}

/// Prints each warning on its own line of standard error.
fn print_warnings(warnings: &[String]) {
    for w in warnings {
        eprintln!("pocketeer: warning: {w}");
    }
}

/// Writes to standard output; a reader that stops early (`| head`) is not an error.
fn emit(text: &str) -> Result<(), Failure> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure(format!("cannot write the report: {e}")))
        }
        _ => Ok(()),
    }
}

#[global_allocator]
static ALLOCATOR: allocator::Allocator = allocator::Allocator;

fn main() -> ExitCode {
    allocator::tune();
    let cli = Cli::parse();
    progress::QUIET.store(cli.quiet, std::sync::atomic::Ordering::Relaxed);
    let result = match &cli.command {
        Command::Inspect(Deferred(args)) => inspect(args),
        Command::Offset(Deferred(args)) => offset(args),
        Command::Pocket(Deferred(args)) => pocket::run(args),
        Command::View(Deferred(args)) => view::run(args),
        Command::Job(Deferred(args)) => job::run(args),
        Command::Check(Deferred(args)) => match check::run(args) {
            Ok(check::Verdict::Passed) => Ok(()),
            // Defects found: the report says which; exit 1 (2 is for errors).
            Ok(check::Verdict::Failed) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(msg)) => {
            eprintln!("pocketeer: error: {msg}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Cli;
    use clap::{CommandFactory, Parser};

    #[test]
    fn the_command_line_is_consistent_with_every_subcommand_built() {
        // Builds the deferred subcommands too, and checks clap's rules on all of them.
        Cli::command().debug_assert();
    }

    #[test]
    fn each_subcommand_keeps_its_own_summary_with_its_flags_defined_late() {
        // Each with a flag of its own, which only its deferred definition adds.
        for (name, summary, flag) in [
            ("inspect", "Show what a drawing holds", "--layers"),
            ("offset", "Offset every pocket of a drawing", "--distance"),
            ("pocket", "Clear every pocket of a drawing", "--stepover"),
            ("check", "Replay a G-code program against its drawing", "--layers"),
            ("job", "Run a job file", "--print-template"),
            ("view", "Write an interactive preview", "--layers"),
        ] {
            for help in ["-h", "--help"] {
                let Err(e) = Cli::try_parse_from(["pocketeer", name, help]) else {
                    panic!("{name} {help} parsed");
                };
                let text = e.render().to_string();
                assert!(text.starts_with(summary), "{name} {help}: {text}");
                assert!(text.contains(flag), "{name} {help} lacks {flag}: {text}");
            }
        }
    }

    #[test]
    fn a_subcommands_flags_are_parsed_when_defined_late() {
        let cli = Cli::try_parse_from([
            "pocketeer",
            "--quiet",
            "offset",
            "part.dxf",
            "--distance",
            "-2",
            "-o",
            "out.dxf",
        ])
        .unwrap();
        assert!(cli.quiet);
        let super::Command::Offset(super::Deferred(args)) = cli.command else {
            panic!("not offset");
        };
        assert_eq!(args.drawing.file, std::path::Path::new("part.dxf"));
        assert_eq!(args.distance, -2.0);
        assert!(Cli::try_parse_from(["pocketeer", "offset", "part.dxf", "--bogus"]).is_err());
    }
}
