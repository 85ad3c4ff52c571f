//! Times Clipper2 (arcs flattened to 0.001 mm, round joins) and pocketeer on single levels of
//! the smooth-profile case, where Clipper2 is too slow to run all 46 levels:
//! `cargo run --release --bin clipper_levels -- N lines|arcs LEVEL...` (levels counted from 0).

use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::{cases, clipper_eroded_area, flattened};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let arcs = args.get(2).is_some_and(|s| s == "arcs");
    let levels: Vec<usize> = args[3.min(args.len())..]
        .iter()
        .filter_map(|s| s.parse().ok())
        .collect();
    let case = cases::smooth(n, arcs);
    let pocket = pocketeer_bench::pocket(&case);
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let region = pocketeer::geom::PreparedPocket::new(&pocket);
    let paths = flattened(&case);
    let vertices: usize = paths.iter().map(|p| p.len()).sum();
    println!("{}: {vertices} flattened vertices", case.name);
    for level in levels {
        let Some(&d) = case.distances.get(level) else {
            continue;
        };
        let t = Instant::now();
        let ours: f64 = region
            .offset(d, &tol)
            .unwrap_or_default()
            .iter()
            .map(Contour::signed_area)
            .sum();
        let ours_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let theirs = clipper_eroded_area(&paths, d);
        let clip_ms = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "level {level} d {d:.2}: pocketeer {ours_ms:.1} ms (area {ours:.3}), Clipper2 {clip_ms:.1} ms (area {theirs:.3}), ratio {:.1}",
            clip_ms / ours_ms
        );
    }
}
