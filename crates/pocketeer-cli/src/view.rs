//! `pocketeer view`: the interactive preview of any G-code program over its drawing.

use crate::check::rates_valid;
use crate::length::{parse_length, parse_rate};
use crate::{output, read_analysis, DrawingArgs, Failure};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct ViewArgs {
    #[command(flatten)]
    drawing: DrawingArgs,
    /// The G-code program to show.
    program: PathBuf,
    /// Tool diameter (6, 6mm, 0.25in): the tool is drawn at its size, and moves are told
    /// apart as cuts or links through cut stock with it.
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    tool_diameter: f64,
    /// Rapid speed of the machine for the elapsed time, per minute.
    #[arg(long, default_value_t = pocketeer::simulate::check::RAPID_RATE, value_parser = parse_rate, allow_hyphen_values = true)]
    rapid_rate: f64,
    /// Seconds each retract costs beyond its length at the rapid rate.
    #[arg(long, default_value_t = pocketeer::machining_time::DEFAULT_RETRACT_SECONDS, allow_hyphen_values = true)]
    retract_time: f64,
    /// The HTML file to write.
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(args: &ViewArgs) -> Result<(), Failure> {
    if !(args.tool_diameter.is_finite() && args.tool_diameter > 0.0) {
        return Err(Failure(format!(
            "--tool-diameter {}: the tool diameter must be positive",
            args.tool_diameter
        )));
    }
    rates_valid(args.rapid_rate, args.retract_time)?;
    output::guard(&[&args.drawing.file, &args.program], &[("-o", &args.output)]).map_err(Failure)?;
    let analysis = read_analysis(&args.drawing)?;
    let program = read_program(&args.program)?;
    let warnings = crate::inspect::import_warnings(&analysis);
    crate::print_warnings(&warnings);
    let context = crate::page::Context {
        title: format!(
            "{} → {}",
            output::file_name(&args.drawing.file),
            output::file_name(&args.program)
        ),
        tool_diameter: args.tool_diameter,
        tool_changes: Vec::new(),
        inches: crate::display::JobUnits::of(analysis.drawing.units) == crate::display::JobUnits::Inches,
        rapid_rate: args.rapid_rate,
        per_retract: args.retract_time,
        settings: Vec::new(),
        too_narrow: Vec::new(),
        check: None,
        report: warnings.join("\n"),
    };
    let spinner = crate::progress::Spinner::start("drawing the page");
    let doc = crate::page::html(&analysis, &program, &context);
    drop(spinner);
    output::write_atomic(&args.output, doc.as_bytes()).map_err(Failure)?;
    eprintln!(
        "{} moves shown; written to {}",
        program.moves.len(),
        output::describe(&args.output)
    );
    Ok(())
}

/// The program in `path`, or a message naming the file and the line.
pub fn read_program(path: &Path) -> Result<pocketeer::simulate::Program, Failure> {
    let text = std::fs::read(path).map_err(|e| Failure(format!("{}: cannot read: {e}", path.display())))?;
    let program = pocketeer::simulate::read_program(&String::from_utf8_lossy(&text))
        .map_err(|e| Failure(format!("{}: {e}", path.display())))?;
    Ok(program)
}
