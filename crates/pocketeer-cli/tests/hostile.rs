//! Hostile drawings through `inspect`, `offset` and `pocket`: adversarial files (zero-length
//! and 1e-12 arcs, 1e300 and NaN coordinates, a block inserting itself, exponential block
//! nesting, 20 000 coincident lines, a saw of teeth finer than the tool, random bytes) and
//! mutated and truncated versions of the shipped drawings (`ten_thousand_variants`, ignored,
//! runs ten thousand of them and any folder of drawings). Every run must end within its time limit with
//! a result or a refusal naming the file, never a panic, and a failed run must leave the
//! existing output file as it was.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A minimal DXF with `entities` in model space and `blocks` in the BLOCKS section.
fn dxf(entities: &str, blocks: &str) -> String {
    let mut s = String::from("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n");
    if !blocks.is_empty() {
        s += &format!("0\nSECTION\n2\nBLOCKS\n{blocks}0\nENDSEC\n");
    }
    s + &format!("0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n")
}

fn line(a: (&str, &str), b: (&str, &str)) -> String {
    format!(
        "0\nLINE\n8\n0\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n",
        a.0, a.1, b.0, b.1
    )
}

fn square() -> String {
    [("0", "0"), ("100", "0"), ("100", "100"), ("0", "100")]
        .iter()
        .enumerate()
        .map(|(k, &a)| line(a, [("100", "0"), ("100", "100"), ("0", "100"), ("0", "0")][k]))
        .collect()
}

/// A square `size` across with its corner at (`at`, `at`).
fn scaled_square(size: f64, at: f64) -> String {
    let p = |x: f64, y: f64| ((at + x * size).to_string(), (at + y * size).to_string());
    let c = [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
    (0..4)
        .map(|k| {
            let (a, b) = (&c[k], &c[(k + 1) % 4]);
            line((&a.0, &a.1), (&b.0, &b.1))
        })
        .collect()
}

fn block(name: &str, body: &str) -> String {
    format!("0\nBLOCK\n8\n0\n2\n{name}\n70\n0\n10\n0\n20\n0\n{body}0\nENDBLK\n")
}

fn insert(name: &str, extra: &str) -> String {
    format!("0\nINSERT\n8\n0\n2\n{name}\n10\n0\n20\n0\n{extra}")
}

/// The adversarial drawings, by name.
fn adversarial() -> Vec<(String, Vec<u8>)> {
    let arc =
        |r: &str, a0: &str, a1: &str| format!("0\nARC\n8\n0\n10\n50\n20\n50\n40\n{r}\n50\n{a0}\n51\n{a1}\n");
    let mut fanout = String::new();
    for k in 0..10 {
        let body = if k < 9 {
            (0..10)
                .map(|i| format!("0\nINSERT\n2\nL{}\n10\n{i}\n20\n0\n", k + 1))
                .collect()
        } else {
            square()
        };
        fanout += &block(&format!("L{k}"), &body);
    }
    let coincident = square() + &line(("0", "0"), ("100", "0")).repeat(20_000);
    let saw: String = {
        let n = 1500;
        let pts: Vec<(f64, f64)> = (0..2 * n)
            .map(|k| {
                let t = std::f64::consts::PI * k as f64 / n as f64;
                let r = if k % 2 == 1 { 100.05 } else { 100.0 };
                (r * t.cos(), r * t.sin())
            })
            .collect();
        (0..pts.len())
            .map(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                line(
                    (&a.0.to_string(), &a.1.to_string()),
                    (&b.0.to_string(), &b.1.to_string()),
                )
            })
            .collect()
    };
    let cases: Vec<(&str, String)> = vec![
        ("zero_length_arc", dxf(&(square() + &arc("5", "30", "30")), "")),
        (
            "arc_radius_1e-12",
            dxf(&(square() + &arc("1e-12", "0", "90")), ""),
        ),
        (
            "coordinates_1e300",
            dxf(&line(("1e300", "0"), ("0", "1e300")).repeat(3), ""),
        ),
        (
            "nan_coordinate",
            dxf(&(square() + &line(("nan", "0"), ("5", "5"))), ""),
        ),
        (
            "nan_group_code",
            dxf(&square(), "").replacen("\n10\n", "\nNaN\n", 1),
        ),
        ("inf_radius", dxf(&(square() + &arc("inf", "0", "90")), "")),
        (
            "self_insert",
            dxf(&insert("A", ""), &block("A", &(square() + &insert("A", "")))),
        ),
        (
            "mutual_insert",
            dxf(
                &insert("A", ""),
                &(block("A", &insert("B", "")) + &block("B", &(square() + &insert("A", "")))),
            ),
        ),
        ("exponential_nesting", dxf(&insert("L0", ""), &fanout)),
        (
            "insert_array_1e9",
            dxf(
                &insert("A", "70\n30000\n71\n30000\n44\n200\n45\n200\n"),
                &block("A", &square()),
            ),
        ),
        (
            "insert_scale_0",
            dxf(&insert("A", "41\n0\n42\n0\n"), &block("A", &square())),
        ),
        ("coincident_lines", dxf(&coincident, "")),
        ("fine_saw", dxf(&saw, "")),
        // Found by the long run: crossing contours in a drawing 1e6 mm across made a clamp's
        // lower bound exceed its upper one.
        (
            "huge_crossing_squares",
            dxf(&(scaled_square(1e6, 0.0) + &scaled_square(1e6, 5e5)), ""),
        ),
        ("empty", String::new()),
        ("only_eof", "0\nEOF\n".to_string()),
        ("binary_header_only", "AutoCAD Binary DXF\r\n\x1a\0".to_string()),
    ];
    let mut out: Vec<(String, Vec<u8>)> = cases
        .into_iter()
        .map(|(n, t)| (n.to_string(), t.into_bytes()))
        .collect();
    // Random bytes, and random bytes after a valid start.
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    for k in 0..4 {
        let len = 1 + rng.below(4096);
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        if k % 2 == 1 {
            bytes.splice(0..0, b"0\nSECTION\n2\nENTITIES\n".iter().copied());
        }
        out.push((format!("random_bytes_{k}"), bytes));
    }
    out
}

/// A small deterministic generator (xorshift), so that failures replay.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// `count` mutations of `bytes`: truncations, byte flips, deleted and duplicated lines, and
/// numbers replaced with extreme ones.
fn mutants(bytes: &[u8], count: usize, seed: u64) -> Vec<Vec<u8>> {
    let mut rng = Rng(seed | 1);
    let extremes = [
        "0",
        "-0",
        "1e300",
        "-1e308",
        "nan",
        "inf",
        "1e-300",
        "999999999999",
        "-1",
        "x",
        "",
    ];
    (0..count)
        .map(|_| {
            let mut b = bytes.to_vec();
            match rng.below(5) {
                0 => b.truncate(rng.below(b.len())),
                1 => {
                    for _ in 0..1 + rng.below(8) {
                        let i = rng.below(b.len());
                        b[i] = rng.next() as u8;
                    }
                }
                2 | 3 => {
                    let text = String::from_utf8_lossy(&b).into_owned();
                    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
                    for _ in 0..1 + rng.below(4) {
                        let i = rng.below(lines.len());
                        match rng.below(3) {
                            0 => {
                                lines.remove(i);
                            }
                            1 => {
                                let l = lines[i].clone();
                                lines.insert(i, l);
                            }
                            _ => lines[i] = extremes[rng.below(extremes.len())].to_owned(),
                        }
                    }
                    b = (lines.join("\n") + "\n").into_bytes();
                }
                _ => {
                    let at = rng.below(b.len());
                    let len = rng.below(200).min(b.len() - at);
                    let chunk = b[at..at + len].to_vec();
                    let to = rng.below(b.len());
                    b.splice(to..to, chunk);
                }
            }
            b
        })
        .collect()
}

/// Runs the binary with a time limit; returns the exit code (None: killed by a signal) and
/// stderr, or fails the test on a timeout.
fn run_limited(args: &[&str], limit: Duration) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_pocketeer"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("binary runs");
    let start = Instant::now();
    loop {
        if let Some(_status) = child.try_wait().expect("wait") {
            break;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{args:?} ran past {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let out = child.wait_with_output().expect("output");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs the three commands on `input` and checks what every run must satisfy.
fn check_one(dir: &Path, name: &str, bytes: &[u8]) {
    let input = dir.join(format!("{name}.dxf"));
    std::fs::write(&input, bytes).expect("write input");
    let out_dxf = dir.join("out.dxf");
    let out_nc = dir.join("out.nc");
    let input_s = input.to_string_lossy().into_owned();
    let commands: [Vec<&str>; 3] = [
        vec!["inspect", &input_s],
        vec![
            "offset",
            &input_s,
            "--distance",
            "3",
            "-o",
            out_dxf.to_str().unwrap_or_default(),
        ],
        vec![
            "pocket",
            &input_s,
            "--tool-diameter",
            "6",
            "--stepover",
            "40%",
            "--depth",
            "2",
            "-o",
            out_nc.to_str().unwrap_or_default(),
        ],
    ];
    for args in &commands {
        for f in [&out_dxf, &out_nc] {
            std::fs::write(f, "KEEP").expect("sentinel");
        }
        let (code, stderr) = run_limited(args, Duration::from_secs(60));
        let what = format!("{name}: {} (exit {code:?})\n{stderr}", args[0]);
        assert!(!stderr.contains("panicked"), "{what}");
        assert!(matches!(code, Some(0) | Some(2)), "{what}");
        if code == Some(2) {
            // Warnings about the drawing may come first; the refusal is one line.
            let errors: Vec<&str> = stderr
                .lines()
                .filter(|l| l.starts_with("pocketeer: error: "))
                .collect();
            assert_eq!(errors.len(), 1, "{what}");
            let first = errors[0];
            assert!(
                first.contains(&format!("{name}.dxf")),
                "the refusal names the file: {what}"
            );
            for f in [&out_dxf, &out_nc] {
                assert_eq!(
                    std::fs::read_to_string(f).unwrap_or_default(),
                    "KEEP",
                    "{what}: output replaced"
                );
            }
        }
        // No temporary file is left behind.
        let stray: Vec<_> = std::fs::read_dir(dir)
            .expect("dir")
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| !n.ends_with(".dxf") && !n.ends_with(".nc"))
            .collect();
        assert!(stray.is_empty(), "{what}: left {stray:?}");
    }
    let _ = std::fs::remove_file(&input);
}

#[test]
fn adversarial_drawings_get_a_result_or_a_located_refusal() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, bytes) in adversarial() {
        check_one(dir.path(), &name, &bytes);
    }
}

/// The example, then every DXF under the fixtures and under `extra` (sorted, in folders at any
/// depth).
fn drawings(extra: Option<PathBuf>) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut folders = vec![repo().join("crates/pocketeer/tests/fixtures/corpus")];
    folders.extend(extra);
    while let Some(folder) = folders.pop() {
        for e in std::fs::read_dir(&folder).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                folders.push(p);
            } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")) {
                found.push(p);
            }
        }
    }
    found.sort();
    std::iter::once(repo().join("examples/bracket.dxf"))
        .chain(found)
        .collect()
}

#[test]
fn mutated_and_truncated_drawings_get_a_result_or_a_located_refusal() {
    let dir = tempfile::tempdir().expect("temp dir");
    let sources = drawings(None);
    for (k, src) in sources.iter().enumerate() {
        let bytes = std::fs::read(src).expect("fixture");
        for (i, m) in mutants(&bytes, 12, 0x9E37_79B9_7F4A_7C15 ^ k as u64)
            .iter()
            .enumerate()
        {
            check_one(dir.path(), &format!("mutant_{k}_{i}"), m);
        }
    }
}

/// The long run: `POCKETEER_HOSTILE_COUNT` mutants (default 10 000) spread over the shipped
/// drawings and every DXF under `POCKETEER_HOSTILE_DIR` (for example the shared corpus), plus
/// the adversarial set. Run in release:
/// `POCKETEER_HOSTILE_DIR=… cargo test --release -p pocketeer-cli --test hostile -- --ignored`.
#[test]
#[ignore = "minutes; run by hand, see the doc comment"]
fn ten_thousand_variants() {
    let count: usize = std::env::var("POCKETEER_HOSTILE_COUNT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(10_000);
    let sources = drawings(std::env::var_os("POCKETEER_HOSTILE_DIR").map(PathBuf::from));
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, bytes) in adversarial() {
        check_one(dir.path(), &name, &bytes);
    }
    let per = count.div_ceil(sources.len());
    let started = Instant::now();
    for (k, src) in sources.iter().enumerate() {
        let Ok(bytes) = std::fs::read(src) else { continue };
        if bytes.is_empty() {
            continue;
        }
        for (i, m) in mutants(&bytes, per, 0xD1B5_4A32_D192_ED03 ^ k as u64)
            .iter()
            .enumerate()
        {
            check_one(dir.path(), &format!("mutant_{k}_{i}"), m);
        }
    }
    eprintln!(
        "{} variants of {} drawings in {:.0?}",
        per * sources.len(),
        sources.len(),
        started.elapsed()
    );
}
