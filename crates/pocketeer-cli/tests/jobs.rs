//! `pocketeer job`: job files with a tool library and operations on layers, run as a user
//! would, on the example plate (`examples/plate.dxf`: SHALLOW and DEEP layers).

mod common;

use pocketeer::simulate::gcode::Motion;
use std::path::{Path, PathBuf};

/// A folder holding the example plate and `job` as `job.toml`.
fn job_dir(job: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        common::repo().join("examples/plate.dxf"),
        dir.path().join("plate.dxf"),
    )
    .unwrap();
    let path = dir.path().join("job.toml");
    std::fs::write(&path, job).unwrap();
    (dir, path)
}

fn run_job(path: &Path) -> std::process::Output {
    common::run(&["job", path.to_str().unwrap()])
}

const TOOLS: &str = r#"drawing = "plate.dxf"
output = "plate.nc"
post = "linuxcnc"

[[tools]]
number = 1
diameter = "6mm"
feed = "1200mm/min"
plunge-feed = "300mm/min"
spindle = 12000

[[tools]]
number = 2
diameter = "2mm"
feed = "600mm/min"
plunge-feed = "150mm/min"
spindle = 18000
"#;

#[test]
fn two_layers_two_tools_one_program_with_a_tool_change() {
    let job = format!(
        "{TOOLS}\n[[operations]]\nlayers = [\"SHALLOW\"]\ntool = 1\ndepth = \"3mm\"\nstepover = \"40%\"\n\n[[operations]]\nlayers = [\"DEEP\"]\ntool = 1\ndepth = \"6mm\"\nstep-down = \"2mm\"\nstepover = \"40%\"\n\n[[operations]]\nlayers = [\"SHALLOW\"]\ntool = 2\ndepth = \"3mm\"\nstepover = \"40%\"\n"
    );
    let (dir, path) = job_dir(&job);
    let out = run_job(&path);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(dir.path().join("plate.nc")).unwrap();
    // One change, to tool 2 at its speed, after the spindle stopped at the safe height.
    assert_eq!(text.matches("T1 M6").count(), 1);
    assert_eq!(text.matches("T2 M6").count(), 1);
    let change = text.find("T2 M6").unwrap();
    assert!(
        text[..change].ends_with("G0 Z5.0000\nM5\n(operation 3: layers SHALLOW, depth 3 mm, tool 2, 2 mm)\n"),
        "{}",
        &text[change.saturating_sub(200)..change]
    );
    assert!(text[change..].starts_with("T2 M6\nG43 H2\nM3 S18000\nG4 P2\n"));
    // SHALLOW never below 3 mm, DEEP down to 6 mm: the moves of each section.
    let p = pocketeer::simulate::read_program(&text).unwrap();
    // The section comments after the header's list of the operations.
    let body = text.find("T1 M6").unwrap();
    let deep_start = text[..body + text[body..].find("(operation 2: layers DEEP").unwrap()]
        .lines()
        .count();
    let deep_end = text[..change].lines().count();
    let lowest = |from: usize, to: usize| {
        p.moves
            .iter()
            .filter(|m| m.line > from && m.line <= to)
            .map(|m| m.to.z)
            .fold(f64::INFINITY, f64::min)
    };
    assert!((lowest(0, deep_start) + 3.0).abs() < 1e-9);
    assert!((lowest(deep_start, deep_end) + 6.0).abs() < 1e-9);
    assert!((lowest(deep_end, usize::MAX) + 3.0).abs() < 1e-9);
    // The 2 mm tool's feeds.
    assert!(p
        .moves
        .iter()
        .any(|m| m.line > deep_end && m.motion != Motion::Rapid && m.feed == Some(600.0)));
}

#[test]
fn a_misspelled_key_is_refused_with_its_line() {
    let job = format!(
        "{TOOLS}\n[[operations]]\nlayers = [\"DEEP\"]\ntool = 1\ndepth = \"6mm\"\nstepovr = \"40%\"\n"
    );
    let (_dir, path) = job_dir(&job);
    let out = run_job(&path);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let line = job.lines().position(|l| l.starts_with("stepovr")).unwrap() + 1;
    assert!(err.contains(&format!("job.toml:{line}:")), "{err}");
    assert!(err.contains("stepovr"), "{err}");
}

#[test]
fn a_layer_the_drawing_lacks_is_refused_with_its_line() {
    let job = format!(
        "{TOOLS}\n[[operations]]\nlayers = [\"DEEPER\"]\ntool = 1\ndepth = \"6mm\"\nstepover = \"40%\"\n"
    );
    let (_dir, path) = job_dir(&job);
    let out = run_job(&path);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let line = job.lines().position(|l| l.contains("DEEPER")).unwrap() + 1;
    assert!(
        err.contains(&format!(
            "job.toml:{line}: operations[1].layers: layer 'DEEPER' is not in plate.dxf"
        )),
        "{err}"
    );
    assert!(
        err.contains("SHALLOW") && err.contains("DEEP"),
        "the drawing's layers are listed: {err}"
    );
}

#[test]
fn a_tool_the_library_lacks_is_refused_with_its_line() {
    let job = format!(
        "{TOOLS}\n[[operations]]\nlayers = [\"DEEP\"]\ntool = 3\ndepth = \"6mm\"\nstepover = \"40%\"\n"
    );
    let (dir, path) = job_dir(&job);
    let out = run_job(&path);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let line = job.lines().position(|l| l == "tool = 3").unwrap() + 1;
    assert!(
        err.contains(&format!("job.toml:{line}: operations[1].tool: no tool 3")),
        "{err}"
    );
    assert!(!dir.path().join("plate.nc").exists(), "nothing written");
}

#[test]
fn the_template_runs_on_the_example_plate() {
    let out = common::run(&["job", "--print-template"]);
    assert!(out.status.success());
    let template = String::from_utf8(out.stdout).unwrap();
    let (dir, path) = job_dir(&template);
    let out = run_job(&path);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("plate.nc").exists());
}

/// Length of the feed moves from line `from` on.
fn feed_length(p: &pocketeer::simulate::Program, from: usize) -> f64 {
    p.moves
        .iter()
        .filter(|m| m.line > from && m.motion != Motion::Rapid)
        .map(|m| m.length())
        .sum()
}

#[test]
fn the_example_job_sends_the_small_tool_only_where_the_large_one_could_not_reach() {
    let job = std::fs::read_to_string(common::repo().join("examples/plate.toml")).unwrap();
    let (dir, path) = job_dir(&job);
    let out = run_job(&path);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    // The DEEP pocket's corners and islands are all within the 6 mm tool's reach.
    assert!(
        err.contains("operation 4: nothing left to cut for tool 2"),
        "{err}"
    );
    let rest = std::fs::read_to_string(dir.path().join("plate.nc")).unwrap();
    // The same job with the 2 mm tool clearing its layers whole.
    let (full_dir, full_path) = job_dir(&job.replace("rest = true", ""));
    assert!(run_job(&full_path).status.success());
    let full = std::fs::read_to_string(full_dir.path().join("plate.nc")).unwrap();
    let change = |t: &str| t[..t.find("T2 M6").unwrap()].lines().count();
    let (pr, pf) = (
        pocketeer::simulate::read_program(&rest).unwrap(),
        pocketeer::simulate::read_program(&full).unwrap(),
    );
    let (lr, lf) = (feed_length(&pr, change(&rest)), feed_length(&pf, change(&full)));
    assert!(lr > 100.0, "the slot and the corners are cut: {lr}");
    assert!(
        lr < 0.35 * lf,
        "the 2 mm tool cuts {lr:.1} mm against {lf:.1} mm for whole pockets"
    );
    // The 2 mm tool cuts the 4 mm slot the 6 mm one could not enter: moves along it, past its
    // middle.
    let along = |m: &pocketeer::simulate::gcode::ProgramMove| {
        m.line > change(&rest)
            && m.motion != Motion::Rapid
            && (m.from.y - 60.0).abs() <= 1.0 + 1e-6
            && (m.to.y - 60.0).abs() <= 1.0 + 1e-6
            && m.from.x.min(m.to.x) < 35.0
            && m.from.x.max(m.to.x) > 35.0
    };
    assert!(pr.moves.iter().any(along));
    // SHALLOW stays at 3 mm with both tools.
    assert!(pr
        .moves
        .iter()
        .filter(|m| m.line > change(&rest))
        .all(|m| m.to.z >= -3.0 - 1e-9));
}

#[test]
fn check_replays_a_job_layer_by_layer_with_each_tool() {
    let job = std::fs::read_to_string(common::repo().join("examples/plate.toml")).unwrap();
    let (dir, path) = job_dir(&job);
    assert!(run_job(&path).status.success());
    let nc = dir.path().join("plate.nc");
    let out = common::run(&["check", path.to_str().unwrap(), nc.to_str().unwrap()]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{report}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        report.contains("layers shallow at 3 mm, operations 1, 3:"),
        "{report}"
    );
    assert!(
        report.contains("layers deep at 6 mm, operations 2, 4:"),
        "{report}"
    );
    assert!(report.ends_with("JOB PASSED\n"), "{report}");
    // Without the 2 mm tool's part the slot and the corners are left: the check fails there.
    let text = std::fs::read_to_string(&nc).unwrap();
    let cut = text.find("M5\n(operation 3").unwrap();
    let short = dir.path().join("short.nc");
    std::fs::write(&short, format!("{}M5\nM2\n", &text[..cut])).unwrap();
    let out = common::run(&["check", path.to_str().unwrap(), short.to_str().unwrap()]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{report}");
    assert!(
        report.contains("thickest 4.0000 mm at (35.000, 60.000)"),
        "the slot: {report}"
    );
    // A SHALLOW move below its 3 mm is reported.
    let deep = text.replacen("Z-3.0000", "Z-3.5000", 1);
    let deeper = dir.path().join("deeper.nc");
    std::fs::write(&deeper, deep).unwrap();
    let out = common::run(&["check", path.to_str().unwrap(), deeper.to_str().unwrap()]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{report}");
    assert!(report.contains("CUT TOO DEEP"), "{report}");
}

#[test]
fn dxf2gcode_layer_names_pocket_without_a_job_file() {
    let plate = std::fs::read_to_string(common::repo().join("examples/plate.dxf")).unwrap();
    let named = plate
        .lines()
        .map(|l| match l {
            "SHALLOW" => "MILL: 1 Md: -3 Td: 6 FeedXY: 1200 FeedZ: 300",
            "DEEP" => "MILL: 2 TiefeGesamt: -6 Sd: -2 Wd: 2 Vxy: 600 T: 2 S: 18000",
            other => other,
        })
        .collect::<Vec<_>>()
        .join("\n");
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("named.dxf");
    std::fs::write(&drawing, named).unwrap();
    let nc = dir.path().join("named.nc");
    let out = common::run(&[
        "pocket",
        drawing.to_str().unwrap(),
        "--layer-params",
        "dxf2gcode",
        "--stepover",
        "40%",
        "--post",
        "linuxcnc",
        "-o",
        nc.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&nc).unwrap();
    assert!(
        text.contains("T1 M6") && text.contains("T2 M6\nG43 H2\nM3 S18000"),
        "{text}"
    );
    let p = pocketeer::simulate::read_program(&text).unwrap();
    let change = text[..text.find("T2 M6").unwrap()].lines().count();
    let lowest = |after: bool| {
        p.moves
            .iter()
            .filter(|m| (m.line > change) == after)
            .map(|m| m.to.z)
            .fold(f64::INFINITY, f64::min)
    };
    assert!((lowest(false) + 3.0).abs() < 1e-9, "the first layer 3 mm deep");
    assert!((lowest(true) + 6.0).abs() < 1e-9, "the second 6 mm deep");
    assert!(
        p.moves.iter().any(|m| m.line > change && m.feed == Some(600.0)),
        "Vxy: 600"
    );
    // Without the flag, such a drawing needs a tool and a depth; with it, a drawing with no
    // MILL: layer is refused naming its layers.
    let out = common::run(&[
        "pocket",
        "examples/plate.dxf",
        "--layer-params",
        "dxf2gcode",
        "--stepover",
        "2",
        "-o",
        nc.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no layer is named 'MILL: …'") && err.contains("SHALLOW"),
        "{err}"
    );
}

#[test]
fn job_check_replays_before_writing() {
    let job = std::fs::read_to_string(common::repo().join("examples/plate.toml")).unwrap();
    let (dir, path) = job_dir(&job);
    let out = common::run(&["job", path.to_str().unwrap(), "--check"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("JOB PASSED"), "{err}");
    assert!(dir.path().join("plate.nc").exists());
    // A job whose small tool goes only 1 mm into the SHALLOW layer leaves the slot's floor:
    // refused, nothing written.
    let short = job.replacen("tool = 2\ndepth = \"3mm\"", "tool = 2\ndepth = \"1mm\"", 1);
    assert_ne!(short, job);
    let (dir, path) = job_dir(&short);
    let out = common::run(&["job", path.to_str().unwrap(), "--check"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("the check failed"), "{err}");
    assert!(!dir.path().join("plate.nc").exists());
}

#[test]
fn a_job_whose_tools_fit_nowhere_is_refused_and_one_that_fits_somewhere_runs() {
    // Tool 1 (60 mm) fits in no pocket of the plate: said, and the 2 mm rest still cuts.
    let job = "drawing = \"plate.dxf\"\n[[tools]]\nnumber = 1\ndiameter = 60\n[[tools]]\nnumber = 2\ndiameter = 2\n[defaults]\nlayers = [\"SHALLOW\", \"DEEP\"]\nstepover = \"40%\"\ndepth = 1\n[[operations]]\ntool = 1\n[[operations]]\ntool = 2\nrest = true\n";
    let (dir, path) = job_dir(job);
    let out = run_job(&path);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("operation 1: a 60 mm tool fits in none of the 4 pockets"),
        "{err}"
    );
    assert!(dir.path().join("plate.nc").exists());
    // Both too large: nothing at all to cut is refused, as `pocket` refuses it.
    let (dir, path) = job_dir(&job.replace("diameter = 2\n", "diameter = 50\n"));
    let out = run_job(&path);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("fits in none"), "{err}");
    assert!(!dir.path().join("plate.nc").exists());
}
