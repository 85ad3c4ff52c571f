//! Repeats the small offset cases, for profiling: `cargo run --release --bin small -- a|d N`.

use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::cases;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case = match args.get(1).map(String::as_str) {
        Some("d") => cases::grid_of_islands(),
        Some("b") => cases::gear(),
        _ => cases::rounded_with_islands(),
    };
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let pocket = pocketeer_bench::pocket(&case);
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let region = pocketeer::geom::PreparedPocket::new(&pocket);
    let mut total = 0.0;
    for _ in 0..n {
        total += region
            .offset_levels(&case.distances, &tol)
            .unwrap()
            .iter()
            .flatten()
            .map(Contour::signed_area)
            .sum::<f64>();
    }
    println!("{total}");
}
