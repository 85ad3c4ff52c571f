//! The HTML preview (`--preview` on `pocket` and `check`, and `pocketeer view`): the drawing,
//! the program read back from its G-code text, and what the command found, put into the
//! library's page.
//!
//! The page is always made from the program's text, whichever command writes it, so what it
//! draws and sums up is what the controller will run.

use crate::display::{count, time};
use pocketeer::export::preview::{page, Mark, MarkKind, Preview};
use pocketeer::geom::{Pocket, Point};
use pocketeer::simulate::gcode::{Motion, ProgramMove};

use pocketeer::simulate::{CheckReport, Program};
use pocketeer::Analysis;

/// What a command knows beyond the drawing and the program.
pub struct Context<'a> {
    /// Title: drawing and program names.
    pub title: String,
    /// Tool diameter, mm (the first tool's).
    pub tool_diameter: f64,
    /// For programs of several tools: from which move each cuts, and its diameter.
    pub tool_changes: Vec<(usize, f64)>,
    /// Lengths in inches.
    pub inches: bool,
    /// Rapid rate, mm/min, and the cost of a retract, s.
    pub rapid_rate: f64,
    pub per_retract: f64,
    /// Rows of the summary the program cannot tell (stepover, depth, …), first.
    pub settings: Vec<(String, String)>,
    /// Pockets known to be too narrow for the tool (indices).
    pub too_narrow: Vec<usize>,
    /// The check's report, when there was one.
    pub check: Option<&'a CheckReport>,
    /// Warnings and the report as text.
    pub report: String,
}

/// The page for `program` (read from the G-code text) cut in the drawing of `a`.
pub fn html(a: &Analysis, program: &Program, c: &Context) -> String {
    let moves = &program.moves;
    let pockets = &a.nesting.pockets;
    let not_cut = not_cut(pockets, moves);
    let mut marks: Vec<Mark> = Vec::new();
    for &i in &not_cut {
        let p = &pockets[i];
        let at = p
            .boundary
            .segments
            .first()
            .map_or(Point::new(0.0, 0.0), |s| s.start());
        let why = if c.too_narrow.contains(&i) {
            format!("too narrow for the {} mm tool", num(c.tool_diameter))
        } else {
            "the program does not reach it".to_string()
        };
        marks.push(Mark {
            kind: MarkKind::NotCut,
            x: at.x,
            y: at.y,
            text: format!("pocket {} (area {:.1} mm²) not cut: {why}", i + 1, p.area()),
        });
    }
    for w in crate::inspect::repairs(a) {
        for at in w.places().into_iter().take(50) {
            marks.push(Mark {
                kind: MarkKind::Repair,
                x: at.x,
                y: at.y,
                text: format!("repaired: {w}"),
            });
        }
    }
    let mut leftovers = Vec::new();
    if let Some(r) = c.check {
        check_marks(r, &mut marks);
        leftovers = r
            .pockets
            .iter()
            .flat_map(|p| p.leftover.iter().cloned())
            .collect();
    }
    // The tool first, then what the command knows, then what the program says.
    let mut summary = program_summary(program, c);
    let rest = summary.split_off(1);
    summary.extend(c.settings.iter().cloned());
    summary.extend(rest);
    let preview = Preview {
        title: c.title.clone(),
        inches: c.inches,
        tool_diameter: c.tool_diameter,
        tool_changes: c.tool_changes.clone(),
        pockets,
        not_cut,
        open_chains: crate::preview::ignored_open_chains(a),
        leftovers,
        marks,
        moves,
        dwell: program.dwell,
        rapid_rate: c.rapid_rate,
        per_retract: c.per_retract,
        summary,
        report: c.report.clone(),
    };
    page(&preview)
}

fn num(v: f64) -> String {
    crate::display::num(v, 4)
}

/// The summary rows the program itself gives: moves, lengths, entries, retracts, time, in the
/// time model the check uses.
fn program_summary(program: &Program, c: &Context) -> Vec<(String, String)> {
    let moves = &program.moves;
    let u = if c.inches {
        crate::display::JobUnits::Inches
    } else {
        crate::display::JobUnits::Millimetres
    };
    let mut cutting = 0.0;
    let mut rapid = 0.0;
    let mut retracts = 0;
    let mut entries = 0;
    let mut seconds = program.dwell;
    let mut last_down = false;
    for m in moves {
        seconds += m.seconds(c.rapid_rate, c.per_retract);
        if m.motion == Motion::Rapid {
            rapid += m.length();
            if m.to.z > m.from.z {
                retracts += 1;
            }
            last_down = false;
            continue;
        }
        cutting += m.length();
        let down = m.to.z < m.from.z - 1e-9 && m.to.z < 0.0;
        if down && !last_down {
            entries += 1;
        }
        last_down = down;
    }
    vec![
        (
            "tool".to_string(),
            format!("{} diameter", u.length(c.tool_diameter)),
        ),
        ("moves".to_string(), count(moves.len(), "move", "moves")),
        ("cutting".to_string(), u.distance(cutting)),
        ("rapid".to_string(), u.distance(rapid)),
        ("entries".to_string(), entries.to_string()),
        ("retracts".to_string(), retracts.to_string()),
        (
            "time".to_string(),
            format!(
                "about {} (rapids at {}, {} s a retract, {} s of dwell)",
                time(seconds),
                u.rate(c.rapid_rate),
                crate::display::num(c.per_retract, 3),
                crate::display::num(program.dwell, 3)
            ),
        ),
    ]
}

/// Gouges and leftovers thinner than this (mm) are not marked: the check's own rounding.
const SHOWN: f64 = 5e-3;

/// Marks for what a check found: gouges and thickest leftovers over the tolerances, rapids
/// into the stock and plunges (the first few of each).
fn check_marks(r: &CheckReport, marks: &mut Vec<Mark>) {
    for (i, p) in r.pockets.iter().enumerate() {
        if let Some(at) = p.gouge_at.filter(|_| p.gouge >= SHOWN) {
            marks.push(Mark {
                kind: MarkKind::Gouge,
                x: at.x,
                y: at.y,
                text: format!("pocket {}: gouge {:.4} mm, line {}", i + 1, p.gouge, at.line),
            });
        }
        if let Some(at) = p.thickest_at.filter(|_| p.thickest >= SHOWN) {
            marks.push(Mark {
                kind: MarkKind::Leftover,
                x: at.x,
                y: at.y,
                text: format!(
                    "pocket {}: material left {:.4} mm thick ({:.3} mm² in all)",
                    i + 1,
                    p.thickest,
                    p.leftover_area
                ),
            });
        }
    }
    for (what, places) in [
        ("rapid into the stock", &r.rapids_into_stock),
        ("plunge into uncut stock", &r.plunges),
    ] {
        for at in places.iter().take(20) {
            marks.push(Mark {
                kind: MarkKind::Warning,
                x: at.x,
                y: at.y,
                text: format!("{what}, line {}", at.line),
            });
        }
    }
}

/// The pockets no feed move below the stock top ends in.
fn not_cut(pockets: &[Pocket], moves: &[ProgramMove]) -> Vec<usize> {
    let ends: Vec<Point> = moves
        .iter()
        .filter(|m| m.motion != Motion::Rapid && m.to.z < 0.0)
        .map(|m| m.to.xy())
        .collect();
    (0..pockets.len())
        .filter(|&i| {
            let p = &pockets[i];
            let b = p.boundary.bbox();
            !ends
                .iter()
                .any(|&q| b.contains(q) && p.boundary.contains(q) && !p.islands.iter().any(|h| h.contains(q)))
        })
        .collect()
}
