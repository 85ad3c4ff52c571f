//! Times pocketeer's offsets against cavalier_contours 0.9.0 (and Clipper2 where built) on the
//! same inputs, every level from the original shape, and prints a Markdown table of medians and
//! ratios. Run: `cargo run --release --manifest-path bench/Cargo.toml [-- --quick]`.

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::cases::{self, Case};
use pocketeer_bench::pocket;
use std::time::{Duration, Instant};

fn shape(case: &Case) -> Shape<f64> {
    let plines = case.rings.iter().map(|ring| {
        let mut p = Polyline::new_closed();
        for &(x, y, b) in ring {
            p.add(x, y, b);
        }
        p
    });
    Shape::from_plines(plines)
}

/// Median of `reps` runs of `f`, and what the last run returned.
fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut times = Vec::with_capacity(reps);
    let mut out = None;
    for _ in 0..reps {
        let t = Instant::now();
        out = Some(f());
        times.push(t.elapsed());
    }
    times.sort();
    (times[times.len() / 2], out.expect("at least one run"))
}

fn ms(d: Duration) -> String {
    format!("{:.1}", d.as_secs_f64() * 1e3)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let mut list = vec![
        cases::rounded_with_islands(),
        cases::gear(),
        cases::grid_of_islands(),
    ];
    let sizes: &[usize] = if quick {
        &[1_000, 10_000]
    } else {
        &[1_000, 10_000, 100_000]
    };
    for &n in sizes {
        list.push(cases::smooth(n, false));
        list.push(cases::smooth(n, true));
    }
    println!("| case | levels | pocketeer ms | cavalier_contours ms | cavalier / pocketeer | area pocketeer | area cavalier |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for case in &list {
        let reps = if case.name.contains("100000") { 3 } else { 7 };
        let p = pocket(case);
        let tol = Tolerance::for_extent(&p.boundary.bbox(), 0.001);
        // Both sides index their input once, outside the timing, as cavalier's Shape does.
        let region = pocketeer::offset::Region::new(&p);
        let (ours, our_area) = time(reps, || {
            case.distances
                .iter()
                .map(|&d| {
                    region
                        .offset(d, &tol)
                        .iter()
                        .map(Contour::signed_area)
                        .sum::<f64>()
                })
                .sum::<f64>()
        });
        let s = shape(case);
        let opts = ShapeOffsetOptions::default();
        let (theirs, their_area) = time(reps, || {
            case.distances
                .iter()
                .map(|&d| {
                    let o = s.parallel_offset(d, &opts);
                    o.ccw_plines
                        .iter()
                        .chain(o.cw_plines.iter())
                        .map(|p| p.polyline.area())
                        .sum::<f64>()
                })
                .sum::<f64>()
        });
        println!(
            "| {} | {} | {} | {} | {:.2} | {:.3} | {:.3} |",
            case.name,
            case.distances.len(),
            ms(ours),
            ms(theirs),
            theirs.as_secs_f64() / ours.as_secs_f64(),
            our_area,
            their_area
        );
    }
}
