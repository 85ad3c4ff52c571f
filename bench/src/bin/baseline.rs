//! The whole-process baseline of issue 21: what a developer builds from cavalier_contours 0.9
//! in an afternoon, taking pocketeer's command line.
//!
//! - `baseline offset FILE --distance D -o OUT`: every closed LWPOLYLINE of the drawing (the
//!   largest the boundary, the others islands) offset once by cavalier_contours' `Shape`, the
//!   loops written as a DXF of LWPOLYLINEs with bulges.
//! - `baseline pocket FILE --tool-diameter T --stepover S --depth Z -o OUT`: the levels at the
//!   tool radius and every stepover beyond until nothing is left, each offset from the
//!   drawing; each loop cut alone (up, across, down, round) as G-code with G2/G3. No clean-up
//!   of what the levels leave, no linking, no check.
//!
//! It reads only what the bench's drawings hold (closed LWPOLYLINEs, ASCII), with a reader as
//! lean as such a program would have: every line is split once, numbers parsed as they come.
//! Other flags are accepted and ignored, so both programs run on one command line.

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, PlineVertex, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use std::fmt::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("baseline: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let flag = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .map(String::as_str)
    };
    let number = |name: &str| -> Result<f64, String> {
        let v = flag(name).ok_or(format!("{name} is needed"))?;
        v.trim_end_matches("mm")
            .parse()
            .map_err(|_| format!("{name} {v}: not a number"))
    };
    let command = args.first().map(String::as_str).unwrap_or("");
    // The drawing: the first argument after the command that is not a flag or a flag's value.
    let mut file = None;
    let mut k = 1;
    while k < args.len() {
        if args[k].starts_with('-') {
            k += if args[k] == "--quiet" { 1 } else { 2 };
        } else {
            file = Some(&args[k]);
            break;
        }
    }
    let file = file.ok_or("no drawing given")?;
    let out = flag("-o").or(flag("--output")).ok_or("-o is needed")?;
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    let shape = Shape::from_plines(read_plines(&text)?);
    let options = ShapeOffsetOptions::default();
    let written = match command {
        "offset" => {
            let loops = shape.parallel_offset(number("--distance")?, &options);
            let mut plines: Vec<&Polyline<f64>> = Vec::new();
            plines.extend(loops.ccw_plines.iter().map(|p| &p.polyline));
            plines.extend(loops.cw_plines.iter().map(|p| &p.polyline));
            write_dxf(&plines)
        }
        "pocket" => {
            let radius = 0.5 * number("--tool-diameter")?;
            let step = number("--stepover")?;
            let depth = number("--depth")?;
            let mut levels = Vec::new();
            let mut d = radius;
            loop {
                let level = shape.parallel_offset(d, &options);
                if level.ccw_plines.is_empty() {
                    break;
                }
                levels.push(level);
                d += step;
            }
            write_gcode(&levels, depth)
        }
        _ => return Err(format!("unknown command '{command}': offset or pocket")),
    };
    std::fs::write(out, written).map_err(|e| format!("{out}: {e}"))
}

/// The closed LWPOLYLINEs of an ASCII DXF.
fn read_plines(text: &str) -> Result<Vec<Polyline<f64>>, String> {
    let mut lines = text.lines();
    let mut plines = Vec::new();
    let mut current: Option<Polyline<f64>> = None;
    let mut x = 0.0;
    let num = |v: &str| v.trim().parse::<f64>().map_err(|_| format!("not a number: {v}"));
    while let (Some(code), Some(value)) = (lines.next(), lines.next()) {
        match code.trim() {
            "0" => {
                plines.extend(current.take());
                if value.trim() == "LWPOLYLINE" {
                    current = Some(Polyline::new_closed());
                }
            }
            "10" => x = num(value)?,
            "20" => {
                let y = num(value)?;
                if let Some(p) = current.as_mut() {
                    p.add(x, y, 0.0);
                }
            }
            "42" => {
                if let Some(p) = current.as_mut() {
                    let last = p.vertex_count() - 1;
                    let v = p.at(last);
                    p.set_vertex(last, PlineVertex::new(v.x, v.y, num(value)?));
                }
            }
            _ => {}
        }
    }
    plines.extend(current);
    Ok(plines)
}

/// The loops as closed LWPOLYLINEs.
fn write_dxf(plines: &[&Polyline<f64>]) -> String {
    let mut s = String::from("0\nSECTION\n2\nENTITIES\n");
    for p in plines {
        let _ = write!(s, "0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", p.vertex_count());
        for v in p.iter_vertexes() {
            let _ = write!(s, "10\n{:.10}\n20\n{:.10}\n42\n{:.12}\n", v.x, v.y, v.bulge);
        }
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

/// Every loop of every level cut alone: up to a safe height, across, down to depth, round.
fn write_gcode(levels: &[Shape<f64>], depth: f64) -> String {
    let mut s = String::from("G21 G90 G17\nM3 S10000\n");
    for level in levels {
        let loops = level.ccw_plines.iter().chain(&level.cw_plines);
        for p in loops.map(|p| &p.polyline) {
            let first = p.at(0);
            let _ = writeln!(s, "G0 Z5.0000\nG0 X{:.4} Y{:.4}", first.x, first.y);
            let _ = writeln!(s, "G1 Z{:.4} F300", -depth);
            let n = p.vertex_count();
            for i in 0..n {
                let (a, b) = (p.at(i), p.at((i + 1) % n));
                if a.bulge == 0.0 {
                    let _ = writeln!(s, "G1 X{:.4} Y{:.4} F1000", b.x, b.y);
                } else {
                    // The centre from the bulge: the chord's midpoint moved along its normal.
                    let (dx, dy) = (b.x - a.x, b.y - a.y);
                    let k = (1.0 - a.bulge * a.bulge) / (4.0 * a.bulge);
                    let (cx, cy) = (a.x + 0.5 * dx - k * dy, a.y + 0.5 * dy + k * dx);
                    let word = if a.bulge > 0.0 { "G3" } else { "G2" };
                    let _ = writeln!(
                        s,
                        "{word} X{:.4} Y{:.4} I{:.4} J{:.4} F1000",
                        b.x,
                        b.y,
                        cx - a.x,
                        cy - a.y
                    );
                }
            }
        }
    }
    s.push_str("G0 Z5.0000\nM5\nM30\n");
    s
}
