//! Whole processes side by side (issue 21): `pocketeer offset` and `pocketeer pocket` against
//! the cavalier_contours baseline (`--bin baseline`) with the same command line on the same DXF
//! files, run in turn; and the rate at which pocketeer reads each drawing.
//!
//! `cargo build --release` (the workspace, for the `pocketeer` binary), then
//! `cargo run --release --manifest-path bench/Cargo.toml --bin whole [-- --runs N] [--quick]
//! [--ours PATH] [--only TEXT] [--command offset|pocket]`. The drawings are written to `bench/target/whole/`. Prints
//! Markdown tables: medians of N runs each (default 5), our time over the baseline's, and the
//! loops each program wrote.

use pocketeer_bench::cases::{self, Case};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let runs: usize = value("--runs").and_then(|s| s.parse().ok()).unwrap_or(5);
    let quick = args.iter().any(|a| a == "--quick");
    let only = value("--only");
    let command_only = value("--command");
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ours = value("--ours").map_or_else(|| manifest.join("../target/release/pocketeer"), PathBuf::from);
    let baseline = std::env::current_exe()
        .ok()
        .and_then(|p| p.parent().map(|d| d.join("baseline")))
        .unwrap_or_else(|| PathBuf::from("baseline"));
    for (what, path) in [("pocketeer", &ours), ("baseline", &baseline)] {
        if !path.exists() {
            eprintln!(
                "{what} not found at {}: build it first (cargo build --release, in the workspace and in bench/)",
                path.display()
            );
            std::process::exit(2);
        }
    }
    let dir = manifest.join("target/whole");
    if let Err(e) = std::fs::create_dir_all(dir.join("bin")) {
        eprintln!("{}: {e}", dir.display());
        std::process::exit(2);
    }
    // Both programs are run from copies side by side: where an executable lies changes what
    // a start costs (on one machine here, 0.3-0.4 ms more from the workspace's filesystem
    // than from /tmp, a tenth of a small job), which would weigh on one side only.
    let [ours, baseline] = [("pocketeer", &ours), ("baseline", &baseline)].map(|(name, from)| {
        let to = dir.join("bin").join(name);
        if let Err(e) = std::fs::copy(from, &to) {
            eprintln!("copying {} to {}: {e}", from.display(), to.display());
            std::process::exit(2);
        }
        to
    });

    let mut drawings: Vec<(Case, &str)> = Vec::new();
    let sizes: &[usize] = if quick {
        &[1_000, 10_000]
    } else {
        &[1_000, 10_000, 100_000]
    };
    for arcs in [false, true] {
        for &n in sizes {
            drawings.push((cases::smooth_with_islands(n, arcs), "smooth"));
        }
    }
    drawings.push((cases::plate(15, 5), "plate"));
    drawings.push((cases::plate(20, 15), "plate"));
    if !quick {
        drawings.push((cases::plate(40, 30), "plate"));
    }
    if let Some(only) = &only {
        drawings.retain(|(c, _)| c.name.contains(only.as_str()));
    }

    println!("Import: pocketeer::read_drawing on the file's bytes, in process, median of {runs}; the same drawing as a binary DXF beside it.\n");
    println!("| drawing | MB | read ms | MB/s | binary MB | binary ms | binary MB/s |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut files = Vec::new();
    for (case, kind) in &drawings {
        let text = pocketeer_bench::dxf(case);
        let file = dir.join(format!("{}.dxf", slug(&case.name)));
        if let Err(e) = std::fs::write(&file, &text) {
            eprintln!("{}: {e}", file.display());
            std::process::exit(2);
        }
        let binary = pocketeer_bench::binary_dxf(&text);
        let read = |bytes: &[u8]| {
            let times: Vec<Duration> = (0..runs)
                .map(|_| {
                    let t = Instant::now();
                    let read = pocketeer::read_drawing(bytes, &Default::default());
                    let elapsed = t.elapsed();
                    assert!(read.is_ok(), "{}: not read", case.name);
                    elapsed
                })
                .collect();
            let ms = median(times).as_secs_f64() * 1e3;
            let mb = bytes.len() as f64 / 1e6;
            (mb, ms, mb / ms * 1e3)
        };
        let (mb, ms, rate) = read(text.as_bytes());
        let (bmb, bms, brate) = read(&binary);
        println!(
            "| {} | {mb:.2} | {ms:.1} | {rate:.0} | {bmb:.2} | {bms:.1} | {brate:.0} |",
            case.name
        );
        files.push((case.name.clone(), *kind, file));
    }

    let out = dir.join("out");
    let jobs: [(&str, &[&str]); 2] = [
        ("offset", &["--distance", "3"]),
        (
            "pocket",
            &["--tool-diameter", "6", "--stepover", "2.4", "--depth", "2"],
        ),
    ];
    for (command, flags) in jobs {
        if command_only.as_deref().is_some_and(|c| c != command) {
            continue;
        }
        println!(
            "\n`{command} FILE {} -o OUT`, whole processes in turn, median of {runs} wall times:\n",
            flags.join(" ")
        );
        let counted = if command == "offset" { "loops" } else { "entries" };
        println!("| drawing | pocketeer s | baseline s | pocketeer / baseline | {counted} pocketeer | {counted} baseline |");
        println!("|---|---:|---:|---:|---:|---:|");
        for (name, _, file) in &files {
            let line = |program: &Path| {
                let mut c = Command::new(program);
                c.arg(command).arg(file).args(flags).arg("-o").arg(&out);
                if program == ours {
                    c.arg("--quiet");
                }
                c
            };
            let (mut a, mut b) = (Vec::new(), Vec::new());
            let (mut count_a, mut count_b) = (0, 0);
            // In turn, each program first every other run: a run pays for what the run before
            // left (the file it replaces was written just before, the caches it shares).
            for k in 0..runs {
                for ours_now in [k % 2 == 0, k % 2 == 1] {
                    if ours_now {
                        let (t, loops) = timed(&mut line(&ours), &out, command);
                        a.push(t);
                        count_a = loops;
                    } else {
                        let (t, loops) = timed(&mut line(&baseline), &out, command);
                        b.push(t);
                        count_b = loops;
                    }
                }
            }
            let (a, b) = (median(a).as_secs_f64(), median(b).as_secs_f64());
            println!(
                "| {name} | {a:.3} | {b:.3} | {:.2} | {count_a} | {count_b} |",
                a / b
            );
        }
    }
}

/// Wall time of one run, and what it wrote: the loops of a DXF, the entries of a program. A failed run stops the benchmark: a fast failure is no result.
fn timed(c: &mut Command, out: &Path, command: &str) -> (Duration, usize) {
    let t = Instant::now();
    let result = c.output();
    let elapsed = t.elapsed();
    match result {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            eprintln!("{c:?} failed: {}", String::from_utf8_lossy(&o.stderr));
            std::process::exit(1);
        }
        Err(e) => {
            eprintln!("{c:?}: {e}");
            std::process::exit(1);
        }
    }
    let text = std::fs::read_to_string(out).unwrap_or_default();
    let loops = if command == "offset" {
        text.lines().filter(|l| l.trim() == "LWPOLYLINE").count()
    } else {
        entries(&text)
    };
    (elapsed, loops)
}

/// The entries of a program: rapids across followed by a feed move (a plunge or a helix's
/// first arc). The baseline enters every loop; pocketeer links loops at depth.
fn entries(gcode: &str) -> usize {
    let mut count = 0;
    let mut after_rapid = false;
    for l in gcode.lines() {
        let l = l.trim();
        if l.starts_with("G0 ") || l.starts_with("G00 ") {
            after_rapid = l.contains('X') || l.contains('Y') || after_rapid;
        } else if after_rapid && (l.starts_with("G1") || l.starts_with("G2") || l.starts_with("G3")) {
            count += 1;
            after_rapid = false;
        }
    }
    count
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// A file name from a case's name.
fn slug(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}
