//! The preview page in a real browser: headless Chromium opens the page written by
//! `pocket --preview` (and `view`) from a file URL with name resolution off, the page's
//! self-test (`#selftest`) moves the play slider to the end and writes what it found into the
//! DOM, and the test reads the DOM back. Any console message fails the test, as does any
//! request the page makes. A screenshot of the example job is written under `target/` for a
//! person to look at.
//!
//! Chromium is the distribution's package (`.ci/run` installs it when missing). Without it
//! these tests fail, unless `POCKETEER_SKIP_BROWSER=1` says to skip them.

mod common;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The browser: `$CHROMIUM`, or the first of the usual names on the PATH.
fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    for dir in std::env::split_paths(&path) {
        for name in [
            "chromium",
            "chromium-browser",
            "google-chrome",
            "google-chrome-stable",
        ] {
            let p = dir.join(name);
            if p.is_file() {
                return Some(p);
            }
        }
    }
    None
}

/// The browser, or `None` when told to skip; a failure otherwise.
fn browser() -> Option<PathBuf> {
    match chromium() {
        Some(p) => Some(p),
        None if std::env::var_os("POCKETEER_SKIP_BROWSER").is_some() => {
            eprintln!("no Chromium found; the browser test is skipped (POCKETEER_SKIP_BROWSER)");
            None
        }
        None => panic!(
            "no Chromium found: install the distribution's chromium package (.ci/run does), set CHROMIUM to its path, or set POCKETEER_SKIP_BROWSER=1 to skip the browser tests"
        ),
    }
}

/// Runs headless Chromium with `extra` arguments on `url`; its standard output and error.
fn run_browser(bin: &Path, extra: &[&str], url: &str) -> (String, String) {
    let profile = tempfile::tempdir().unwrap();
    let mut child = Command::new(bin)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            // The network off: no name resolves.
            "--host-resolver-rules=MAP * ~NOTFOUND",
            "--enable-logging=stderr",
            "--v=0",
            "--hide-scrollbars",
            "--window-size=1400,900",
            "--virtual-time-budget=30000",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(extra)
        .arg(url)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("Chromium starts");
    let mut out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("Chromium did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    (reader.join().unwrap(), err_reader.join().unwrap())
}

fn file_url(p: &Path) -> String {
    format!("file://{}", p.canonicalize().unwrap().display())
}

/// What the page's self-test found, and the browser's console lines.
fn self_test(bin: &Path, page: &Path) -> serde_json::Value {
    let (dom, log) = run_browser(bin, &["--dump-dom"], &format!("{}#selftest", file_url(page)));
    let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:#?}");
    let start = dom.find("<pre id=\"selftest\">").unwrap_or_else(|| {
        panic!(
            "the self-test wrote nothing; page starts {:?}",
            &dom[..dom.len().min(400)]
        )
    });
    let json = &dom[start + "<pre id=\"selftest\">".len()..];
    let json = &json[..json.find("</pre>").unwrap()];
    let json = json
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    serde_json::from_str(&json).unwrap()
}

/// The moves, retracts and entries of a program as `check` reads it.
fn program_figures(nc: &Path) -> (usize, usize, usize) {
    let text = std::fs::read_to_string(nc).unwrap();
    let p = pocketeer::simulate::read_program(&text).unwrap();
    let retracts = p
        .moves
        .iter()
        .filter(|m| m.motion == pocketeer::simulate::gcode::Motion::Rapid && m.to.z > m.from.z)
        .count();
    let mut entries = 0;
    let mut down = false;
    for m in &p.moves {
        let d = m.motion != pocketeer::simulate::gcode::Motion::Rapid && m.to.z < m.from.z && m.to.z < 0.0;
        entries += usize::from(d && !down);
        down = d;
    }
    (p.moves.len(), retracts, entries)
}

fn row(t: &serde_json::Value, name: &str) -> String {
    t["summary"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|r| r.as_str())
        .find_map(|r| r.strip_prefix(name))
        .unwrap_or_else(|| panic!("no summary row {name}: {t}"))
        .to_string()
}

#[test]
fn the_example_page_plays_to_its_last_move_without_a_console_message() {
    let Some(bin) = browser() else { return };
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("bracket.nc");
    let page = dir.path().join("bracket.html");
    let out = common::run(&[
        "pocket",
        "examples/bracket.dxf",
        "--tool-diameter",
        "6",
        "--stepover",
        "2.4",
        "--depth",
        "4",
        "--step-down",
        "2",
        "--check",
        "-o",
        nc.to_str().unwrap(),
        "--preview",
        page.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let t = self_test(&bin, &page);
    assert_eq!(t["problems"].as_array().unwrap().len(), 0, "{t}");
    assert_eq!(t["resources"], 0, "the page asked for something: {t}");
    let (moves, retracts, entries) = program_figures(&nc);
    assert!(moves > 100);
    assert_eq!(t["moves"], moves);
    assert_eq!(t["drawn"], moves, "every move is drawn at the end: {t}");
    assert_eq!(t["slider"], t["max"]);
    assert_eq!(t["max"], moves);
    // The legend, the scale and the summary are there, and the summary is the program's.
    assert!(t["legend"].as_u64().unwrap() >= 10, "{t}");
    assert!(t["scale"].as_str().unwrap().ends_with(" mm"), "{t}");
    assert_eq!(row(&t, "retracts"), retracts.to_string());
    assert_eq!(row(&t, "entries"), entries.to_string());
    assert_eq!(row(&t, "moves"), format!("{moves} moves"));
    assert!(row(&t, "depth").contains("2 passes"), "{t}");
    // The readout shows the program's last line with a move on it.
    let text = std::fs::read_to_string(&nc).unwrap();
    let last_move_line = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with('G') && (l.contains('X') || l.contains('Y') || l.contains('Z')))
        .map(|(k, _)| k + 1)
        .last()
        .unwrap();
    assert_eq!(t["line"], last_move_line, "{t}");
    assert!(
        t["inked"].as_f64().unwrap() > 0.2,
        "the canvas is nearly blank: {t}"
    );
}

#[test]
fn a_screenshot_of_the_example_job_is_written_under_target() {
    let Some(bin) = browser() else { return };
    let shots = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("preview");
    std::fs::create_dir_all(&shots).unwrap();
    let nc = shots.join("bracket.nc");
    let page = shots.join("bracket.html");
    let out = common::run(&[
        "pocket",
        "examples/bracket.dxf",
        "--tool-diameter",
        "6",
        "--stepover",
        "2.4",
        "--depth",
        "2",
        "-o",
        nc.to_str().unwrap(),
        "--preview",
        page.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for (name, fragment) in [("bracket-end.png", ""), ("bracket-half.png", "#play=0.5")] {
        let png = shots.join(name);
        let _ = std::fs::remove_file(&png);
        let (_, log) = run_browser(
            &bin,
            &[&format!("--screenshot={}", png.display())],
            &format!("{}{fragment}", file_url(&page)),
        );
        let bytes =
            std::fs::read(&png).unwrap_or_else(|e| panic!("no screenshot {}: {e}\n{log}", png.display()));
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(bytes.len() > 30_000, "{} is {} bytes", png.display(), bytes.len());
        eprintln!("screenshot: {}", png.display());
    }
}

#[test]
fn pockets_not_cut_open_chains_and_repairs_are_marked() {
    let Some(bin) = browser() else { return };
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("marks.dxf");
    // A 60 x 40 pocket whose outline misses closing by 0.01 mm (bridged, a repair), a 4 mm
    // square too narrow for a 6 mm tool, and a centre mark (an open line) that is ignored.
    let outline: &[(f64, f64)] = &[(0.01, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0), (0.0, 0.0)];
    let small: &[(f64, f64)] = &[(80.0, 0.0), (84.0, 0.0), (84.0, 4.0), (80.0, 4.0)];
    let mark: &[(f64, f64)] = &[(100.0, 20.0), (110.0, 20.0)];
    std::fs::write(
        &drawing,
        common::dxf(&[(outline, false), (small, true), (mark, false)], &[], 4),
    )
    .unwrap();
    let nc = dir.path().join("marks.nc");
    let page = dir.path().join("marks.html");
    let out = common::run(&[
        "pocket",
        drawing.to_str().unwrap(),
        "--tool-diameter",
        "6",
        "--stepover",
        "3",
        "--depth",
        "1",
        "-o",
        nc.to_str().unwrap(),
        "--preview",
        page.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let t = self_test(&bin, &page);
    assert_eq!(t["problems"].as_array().unwrap().len(), 0, "{t}");
    let marks: Vec<&str> = t["marks"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|m| m.as_str())
        .collect();
    assert!(marks.contains(&"not-cut"), "{t}");
    assert!(marks.contains(&"repair"), "{t}");
    assert_eq!(t["notCut"].as_array().unwrap().len(), 1, "{t}");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("too narrow for the 6 mm tool"),
        "the reason is given"
    );

    // `view` of the same program shows the same moves.
    let viewed = dir.path().join("view.html");
    let out = common::run(&[
        "view",
        drawing.to_str().unwrap(),
        nc.to_str().unwrap(),
        "--tool-diameter",
        "6",
        "-o",
        viewed.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v = self_test(&bin, &viewed);
    assert_eq!(v["problems"].as_array().unwrap().len(), 0, "{v}");
    assert_eq!(v["moves"], t["moves"]);
    assert_eq!(v["drawn"], t["moves"]);
}

#[test]
fn the_example_jobs_page_follows_its_tool_change() {
    let Some(bin) = browser() else { return };
    let dir = tempfile::tempdir().unwrap();
    for f in ["plate.dxf", "plate.toml"] {
        std::fs::copy(common::repo().join("examples").join(f), dir.path().join(f)).unwrap();
    }
    let page = dir.path().join("plate.html");
    let out = common::run(&[
        "job",
        dir.path().join("plate.toml").to_str().unwrap(),
        "--preview",
        page.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let t = self_test(&bin, &page);
    assert_eq!(t["problems"].as_array().unwrap().len(), 0, "{t}");
    let (moves, retracts, _) = program_figures(&dir.path().join("plate.nc"));
    assert_eq!(t["moves"], moves);
    assert_eq!(t["drawn"], moves);
    assert_eq!(row(&t, "retracts"), retracts.to_string());
    // At the last move the 2 mm tool is in the spindle.
    assert!(
        t["readout"].as_str().unwrap().contains("tool 2.000 mm across"),
        "{t}"
    );
    assert!(row(&t, "operation 3").contains("tool 2 (2 mm)"), "{t}");
}
