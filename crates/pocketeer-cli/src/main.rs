//! The `pocketeer` command: a thin layer of argument parsing and messages over the library.

mod length;
mod report;

use clap::{Args, Parser, Subcommand};
use pocketeer::import::Units;
use pocketeer::ImportOptions;
use std::path::PathBuf;
use std::process::ExitCode;

/// Contour-parallel pocket milling from DXF drawings.
#[derive(Parser)]
#[command(name = "pocketeer", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Show what a drawing holds: units, layers, entities, contours, pockets and islands.
    Inspect(InspectArgs),
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
    /// End points closer than this are joined (a length: 0.001, 0.01mm, 0.0001in).
    #[arg(long, default_value = "0.001", value_parser = length::parse_nonneg_length)]
    join_tolerance: f64,
}

#[derive(Args)]
struct InspectArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

/// A failure reported to the user: one message, exit code 2.
struct Failure(String);

fn read_analysis(args: &DrawingArgs) -> Result<pocketeer::Analysis, Failure> {
    let name = args.file.display();
    let bytes = std::fs::read(&args.file).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let options = ImportOptions {
        layers: args.layers.clone(),
        units: args.units,
        join_tolerance: args.join_tolerance,
    };
    pocketeer::analyze(&bytes, &options).map_err(|e| Failure(format!("{name}: {e}")))
}

fn inspect(args: &InspectArgs) -> Result<(), Failure> {
    let analysis = read_analysis(&args.drawing)?;
    let report = report::Report::new(&args.drawing.file.display().to_string(), &analysis);
    if args.json {
        let text =
            serde_json::to_string_pretty(&report).map_err(|e| Failure(format!("cannot write JSON: {e}")))?;
        println!("{text}");
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Inspect(args) => inspect(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(msg)) => {
            eprintln!("pocketeer: error: {msg}");
            ExitCode::from(2)
        }
    }
}
