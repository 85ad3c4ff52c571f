//! How pocketeer's offset time grows with the number of elements: all 46 levels of the smooth
//! profile (case (c)) with `PreparedPocket::offset_levels`, at 1k, 10k and 100k elements, lines and
//! arcs, the sizes taken in turn in every round so that the machine's drift hits them alike.
//! Prints medians and the growth per tenfold: `cargo run --release --bin growth [-- ROUNDS]`.

use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::cases;
use std::time::Instant;

fn main() {
    let rounds: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let sizes = [1_000, 10_000, 100_000];
    for arcs in [false, true] {
        let prepared: Vec<_> = sizes
            .iter()
            .map(|&n| {
                let case = cases::smooth(n, arcs);
                let pocket = pocketeer_bench::pocket(&case);
                let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
                (case.distances, pocketeer::geom::PreparedPocket::new(&pocket), tol)
            })
            .collect();
        let mut times = vec![Vec::new(); sizes.len()];
        for _ in 0..rounds {
            for (k, (distances, region, tol)) in prepared.iter().enumerate() {
                let t = Instant::now();
                let levels = region.offset_levels(distances, tol).unwrap_or_default();
                let area: f64 = levels.iter().flatten().map(Contour::signed_area).sum();
                times[k].push(t.elapsed().as_secs_f64() * 1e3);
                std::hint::black_box(area);
            }
        }
        let medians: Vec<f64> = times
            .iter_mut()
            .map(|t| {
                t.sort_by(f64::total_cmp);
                t[t.len() / 2]
            })
            .collect();
        let kind = if arcs { "arcs" } else { "lines" };
        for (k, &n) in sizes.iter().enumerate() {
            let growth = if k > 0 {
                format!("×{:.1}", medians[k] / medians[k - 1])
            } else {
                "—".into()
            };
            println!("| {n} {kind} | {:.1} | {growth} |", medians[k]);
        }
    }
}
