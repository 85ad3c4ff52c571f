//! Writes a benchmark case as an ASCII DXF of LWPOLYLINEs (bulges for arcs), the drawing the
//! whole-process and import comparisons read: `cargo run --release --bin drawing -- CASE >
//! case.dxf`, CASE one of `lines N` and `arcs N` (the smooth profile r = 100 + 8 sin 12t of N
//! vertices), `islands` (the 10 × 6 grid of round islands) or `gear`.

use pocketeer_bench::cases::{self, Case};
use std::fmt::Write;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count = || args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let case: Case = match args.first().map(String::as_str) {
        Some("lines") => cases::smooth(count(), false),
        Some("arcs") => cases::smooth(count(), true),
        Some("islands") => cases::grid_of_islands(),
        Some("gear") => cases::gear(),
        _ => {
            eprintln!("usage: drawing lines N | arcs N | islands | gear");
            std::process::exit(2);
        }
    };
    print!("{}", dxf(&case));
}

/// The case's rings as closed LWPOLYLINEs on layer 0, in millimetres.
fn dxf(case: &Case) -> String {
    let mut s =
        String::from("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    for ring in &case.rings {
        let _ = write!(s, "0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", ring.len());
        for &(x, y, bulge) in ring {
            let _ = write!(s, "10\n{x:.6}\n20\n{y:.6}\n");
            if bulge != 0.0 {
                let _ = write!(s, "42\n{bulge:.9}\n");
            }
        }
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}
