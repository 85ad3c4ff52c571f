//! Runs only pocketeer's offsets of one smooth-profile case, for profiling:
//! `cargo run --release --bin ours -- N lines|arcs`.

use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::cases;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let case = cases::smooth(n, args.get(2).is_some_and(|s| s == "arcs"));
    let pocket = pocketeer_bench::pocket(&case);
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let total: f64 = case
        .distances
        .iter()
        .map(|&d| {
            pocketeer::offset::offset_pocket(&pocket, d, &tol)
                .unwrap()
                .iter()
                .map(Contour::signed_area)
                .sum::<f64>()
        })
        .sum();
    println!("{total}");
}
