//! Times pocketeer's offsets against cavalier_contours 0.9.0 on the same inputs, and against
//! Clipper2 (arcs flattened to 0.001 mm) on cases (a) and (c), every level from the original
//! shape, and prints a Markdown table of medians and ratios. Run: `cargo run --release --manifest-path bench/Cargo.toml [-- --quick] [--only PREFIX]
//! [--no-clipper] [--clipper-all]`.

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use pocketeer::geom::{Contour, Tolerance};
use pocketeer_bench::cases::{self, Case};
use pocketeer_bench::{clipper_eroded_area, flattened, pocket};
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
    (median(times), out.expect("at least one run"))
}

/// The median of `times` (at least one).
fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    times[times.len() / 2]
}

/// Medians of `f` and `g` run in turn, at least `reps` times each and until each has run for
/// a second (at most 2000 times): a millisecond case gets hundreds of runs, and a change in
/// the machine's load during the run falls on both alike. What the last runs returned.
fn time_pair<T, U>(
    reps: usize,
    mut f: impl FnMut() -> T,
    mut g: impl FnMut() -> U,
) -> ((Duration, T), (Duration, U)) {
    let (mut tf, mut tg) = (Vec::new(), Vec::new());
    let (mut of, mut og) = (None, None);
    let total = |v: &[Duration]| v.iter().sum::<Duration>();
    while tf.len() < reps
        || (tf.len() < 2000 && (total(&tf) < Duration::from_secs(1) || total(&tg) < Duration::from_secs(1)))
    {
        let t = Instant::now();
        of = Some(f());
        tf.push(t.elapsed());
        let t = Instant::now();
        og = Some(g());
        tg.push(t.elapsed());
    }
    (
        (median(tf), of.expect("at least one run")),
        (median(tg), og.expect("at least one run")),
    )
}

fn ms(d: Duration) -> String {
    format!("{:.1}", d.as_secs_f64() * 1e3)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
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
    println!(
        "| case | levels | pocketeer ms | cavalier_contours ms | cavalier / pocketeer | Clipper2 ms | Clipper2 / pocketeer | area pocketeer | area cavalier | area Clipper2 |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    // `--only PREFIX`: just the cases whose names start with it, as "(a)".
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1));
    let no_clipper = args.iter().any(|a| a == "--no-clipper");
    // `--clipper-all`: Clipper2 on every (a) and (c) case, once where it is slow (hours at 100k).
    let clipper_all = args.iter().any(|a| a == "--clipper-all");
    for case in list
        .iter()
        .filter(|c| only.is_none_or(|o| c.name.starts_with(o.as_str())))
    {
        let reps = if case.name.contains("100000") { 3 } else { 7 };
        let p = pocket(case);
        let tol = Tolerance::for_extent(&p.boundary.bbox(), 0.001);
        // Both sides index their input once, outside the timing, as cavalier's Shape does.
        let region = pocketeer::geom::PreparedPocket::new(&p);
        let s = shape(case);
        let opts = ShapeOffsetOptions::default();
        // Ours: all levels in one call, on both cores, deeper levels from the sources of
        // shallower. Theirs: level by level. In turn, run for run.
        let ((ours, our_area), (theirs, their_area)) = time_pair(
            reps,
            || {
                region
                    .offset_levels(&case.distances, &tol)
                    .unwrap()
                    .iter()
                    .flatten()
                    .map(Contour::signed_area)
                    .sum::<f64>()
            },
            || {
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
            },
        );
        // Clipper2 takes 96 s for the 10k-line case (one run): it runs once there and is left
        // out of the 10k-arc (204 s once) and 100k cases unless asked.
        let big = case.name.contains("10000 ") || case.name.contains("100000");
        let with_clipper = !no_clipper
            && (case.name.starts_with("(a)") || case.name.starts_with("(c)"))
            && (clipper_all || !(case.name.contains("100000") || case.name.contains("10000 arcs")));
        let (clip_ms, clip_ratio, clip_area) = if with_clipper {
            let paths = flattened(case);
            let (t, area) = time(if big { 1 } else { reps }, || {
                case.distances
                    .iter()
                    .map(|&d| clipper_eroded_area(&paths, d))
                    .sum::<f64>()
            });
            (
                ms(t),
                format!("{:.2}", t.as_secs_f64() / ours.as_secs_f64()),
                format!("{area:.3}"),
            )
        } else {
            ("—".into(), "—".into(), "—".into())
        };
        println!(
            "| {} | {} | {} | {} | {:.2} | {} | {} | {:.3} | {:.3} | {} |",
            case.name,
            case.distances.len(),
            ms(ours),
            ms(theirs),
            theirs.as_secs_f64() / ours.as_secs_f64(),
            clip_ms,
            clip_ratio,
            our_area,
            their_area,
            clip_area
        );
    }
}
