//! Writes a benchmark case as an ASCII DXF of LWPOLYLINEs (bulges for arcs), the drawing the
//! whole-process and import comparisons read: `cargo run --release --bin drawing -- CASE >
//! case.dxf`, CASE one of `lines N` and `arcs N` (the smooth profile r = 100 + 8 sin 12t of N
//! vertices), `islands` (the 10 × 6 grid of round islands) or `gear`.

use pocketeer_bench::cases::{self, Case};

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
    print!("{}", pocketeer_bench::dxf(&case));
}
