//! The `pocketeer` binary as a user runs it: output, JSON, messages and exit codes.

mod common;

use common::{dxf, run};

#[test]
fn inspect_prints_the_bracket() {
    let out = run(&["inspect", "examples/bracket.dxf"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("pockets   1"), "{text}");
    assert!(text.contains("3 islands"), "{text}");
    assert!(text.contains("9569.097"), "{text}");
}

#[test]
fn inspect_json_has_the_same_figures() {
    let out = run(&["inspect", "--json", "examples/bracket.dxf"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["units"], "mm");
    assert_eq!(v["pockets"].as_array().unwrap().len(), 1);
    assert_eq!(v["pockets"][0]["islands"].as_array().unwrap().len(), 3);
    assert_eq!(v["contours"].as_array().unwrap().len(), 4);
    assert_eq!(v["entities"]["LWPOLYLINE"], 2);
}

#[test]
fn inspect_json_lists_the_repairs_and_the_preview_marks_them() {
    // The bracket is clean.
    let out = run(&["inspect", "--json", "examples/bracket.dxf"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["repairs"].as_array().unwrap().len(), 0, "{}", v["repairs"]);
    // A wall missing its start by 0.02 mm round a hole: the gap is bridged, and said where.
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("gap.dxf");
    let wall: &[(f64, f64)] = &[(0.0, 0.02), (0.0, 40.0), (60.0, 40.0), (60.0, 0.0), (0.0, 0.0)];
    std::fs::write(&drawing, dxf(&[(wall, false)], &[(30.0, 20.0, 6.0)], 4)).unwrap();
    let out = run(&["inspect", "--json", drawing.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let repairs = v["repairs"].as_array().unwrap();
    assert_eq!(repairs.len(), 1, "{repairs:?}");
    assert_eq!(repairs[0]["kind"], "gap-bridged");
    let at = repairs[0]["at"].as_array().unwrap();
    assert_eq!(at.len(), 2);
    assert!(at.iter().any(|p| p["y"].as_f64() == Some(0.02)), "{at:?}");
    let svg = dir.path().join("gap.svg");
    let res = run(&[
        "offset",
        drawing.to_str().unwrap(),
        "--distance",
        "1",
        "-o",
        dir.path().join("gap-loops.dxf").to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(res.status.success());
    let text = std::fs::read_to_string(&svg).unwrap();
    let marks = text.split(r#"<g id="repairs""#).nth(1).expect("a repairs layer");
    let marks = &marks[..marks.find("</g>").unwrap()];
    assert_eq!(marks.matches(" Z").count(), 2, "two rings: {marks}");
}

#[test]
fn layer_filter_and_units_flags() {
    let out = run(&[
        "inspect",
        "--json",
        "--layers",
        "pocket",
        "--units",
        "in",
        "examples/bracket.dxf",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["pockets"][0]["islands"].as_array().unwrap().len(), 0);
    assert_eq!(v["units"], "in");
    let area = v["pockets"][0]["area_mm2"].as_f64().unwrap();
    assert!((area - 9569.097 * 645.16).abs() < 1.0, "{area}");
}

#[test]
fn failures_name_the_file_and_exit_2() {
    let out = run(&["inspect", "no/such/file.dxf"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("no/such/file.dxf") && err.contains("cannot read"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");

    let out = run(&["inspect", "README.md"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("README.md") && err.contains("not a DXF"), "{err}");

    let out = run(&["inspect", "--join-tolerance", "fast", "examples/bracket.dxf"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn offset_writes_a_dxf_that_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("loops.dxf");
    let svg = dir.path().join("loops.svg");
    let res = run(&[
        "offset",
        "examples/bracket.dxf",
        "--distance",
        "3",
        "-o",
        out.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(res.status.success(), "{}", String::from_utf8_lossy(&res.stderr));
    let said = String::from_utf8_lossy(&res.stderr);
    assert!(said.contains("1 pocket offset by 3 mm: 4 loops"), "{said}");
    let back = run(&["inspect", "--json", out.to_str().unwrap()]);
    let v: serde_json::Value = serde_json::from_slice(&back.stdout).unwrap();
    // 114 x 74 with corner radius 3, minus bosses of radius 12 and a 40 x 18 slot.
    let pi = std::f64::consts::PI;
    let expected = 114.0 * 74.0 - (4.0 - pi) * 9.0 - 2.0 * pi * 144.0 - (40.0 * 18.0 + pi * 81.0);
    let area = v["pockets"][0]["area_mm2"].as_f64().unwrap();
    assert!((area - expected).abs() < 2e-3, "{area} vs {expected}");
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    // Only the two outputs: no temporary files left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn offset_lengths_take_units_and_a_failure_keeps_the_old_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("loops.dxf");
    let res = run(&[
        "offset",
        "examples/bracket.dxf",
        "--distance",
        "-0.1in",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(res.status.success(), "{}", String::from_utf8_lossy(&res.stderr));
    // Without a preview the pockets are offset without a copy: still counted.
    let said = String::from_utf8_lossy(&res.stderr);
    assert!(said.contains("1 pocket offset by -2.54 mm: "), "{said}");
    let before = std::fs::read(&out).unwrap();
    let res = run(&[
        "offset",
        "README.md",
        "--distance",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(res.status.code(), Some(2));
    assert_eq!(std::fs::read(&out).unwrap(), before);
}

#[test]
fn pocket_writes_a_program_and_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("bracket.nc");
    let svg = dir.path().join("bracket.svg");
    let res = run(&[
        "pocket",
        "examples/bracket.dxf",
        "--tool-diameter",
        "6",
        "--stepover",
        "40%",
        "--depth",
        "8",
        "--post",
        "linuxcnc",
        "-o",
        nc.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert!(res.status.success(), "{stderr}");
    for word in [
        "1 pocket,",
        "loops",
        "2 passes",
        "cutting",
        "rapid",
        "retracts",
        "about",
    ] {
        assert!(stderr.contains(word), "{word} missing from: {stderr}");
    }
    let g = std::fs::read_to_string(&nc).unwrap();
    assert!(g.starts_with("(pocketeer "));
    for word in [
        "G21\n",
        "G91.1",
        "M3 S12000\n",
        "\nG2 ",
        "\nG3 ",
        "Z-4.0000",
        "Z-8.0000",
        "M5\nM2\n",
    ] {
        assert!(g.contains(word), "{word:?} missing");
    }
    assert!(!g.contains(" R"));
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn pocket_refusals_name_the_problem_and_keep_the_old_program() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("old.nc");
    std::fs::write(&nc, "(a good old program)\n").unwrap();
    let cases: [(&[&str], &str); 4] = [
        (&["--tool-diameter", "60"], "fits nowhere in the pocket"),
        (
            &["--tool-diameter", "6", "--stepover", "7"],
            "less than the tool diameter",
        ),
        (
            &["--tool-diameter", "0.25in", "--stepover", "0", "--depth", "2"],
            "stepover must be positive",
        ),
        (
            &["--tool-diameter", "6", "--depth", "-1"],
            "depth must be positive",
        ),
    ];
    for (flags, message) in cases {
        let mut args = vec![
            "pocket",
            "examples/bracket.dxf",
            "--stepover",
            "2",
            "--depth",
            "2",
        ];
        args.extend_from_slice(flags);
        args.extend_from_slice(&["-o", nc.to_str().unwrap()]);
        let res = run(&args);
        let stderr = String::from_utf8_lossy(&res.stderr);
        assert_eq!(res.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert_eq!(std::fs::read_to_string(&nc).unwrap(), "(a good old program)\n");
    }
}

#[test]
fn open_outlines_and_strict_figure_eights_are_refused_and_the_old_program_kept() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("keep.nc");
    std::fs::write(&nc, "(keep me)\n").unwrap();
    let open: &[(f64, f64)] = &[(0.0, 0.0), (50.0, 0.0), (50.0, 40.0), (0.0, 40.0), (0.0, 1.0)];
    let eight: &[(f64, f64)] = &[(0.0, 0.0), (40.0, 30.0), (40.0, 0.0), (0.0, 30.0)];
    let cases = [
        (
            dxf(&[(open, false)], &[(25.0, 20.0, 5.0)], 4),
            "does not close",
            None,
        ),
        (
            dxf(&[(eight, true)], &[], 4),
            "crosses or touches itself at (20",
            Some("--strict"),
        ),
    ];
    for (i, (text, message, flag)) in cases.iter().enumerate() {
        let drawing = dir.path().join(format!("bad{i}.dxf"));
        std::fs::write(&drawing, text).unwrap();
        let mut args = vec![
            "pocket",
            drawing.to_str().unwrap(),
            "--tool-diameter",
            "6",
            "--stepover",
            "2",
            "--depth",
            "1",
            "-o",
            nc.to_str().unwrap(),
        ];
        args.extend(flag);
        let res = run(&args);
        let stderr = String::from_utf8_lossy(&res.stderr);
        assert_eq!(res.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(message), "{stderr}");
        assert!(stderr.contains(&format!("bad{i}.dxf")), "{stderr}");
        assert!(stderr.contains("layer 'parts'"), "{stderr}");
        assert_eq!(std::fs::read_to_string(&nc).unwrap(), "(keep me)\n");
    }
}

#[test]
fn a_figure_eight_is_pocketed_as_two_triangles_with_the_repair_named() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("eight.nc");
    let eight: &[(f64, f64)] = &[(0.0, 0.0), (40.0, 30.0), (40.0, 0.0), (0.0, 30.0)];
    let drawing = dir.path().join("eight.dxf");
    std::fs::write(&drawing, dxf(&[(eight, true)], &[], 4)).unwrap();
    let res = run(&[
        "pocket",
        drawing.to_str().unwrap(),
        "--tool-diameter",
        "3",
        "--stepover",
        "1",
        "--depth",
        "1",
        "-o",
        nc.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert!(res.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "crosses or touches itself at (20.0000, 15.0000): filled by the even-odd rule into 2 loops"
        ),
        "{stderr}"
    );
    assert!(stderr.contains("2 pockets,"), "{stderr}");
    // The two loops meet where the outline crossed itself: that is the repair, not a merge.
    assert!(!stderr.contains("merged"), "{stderr}");
}

#[test]
fn check_passes_our_program_and_fails_a_lazy_one() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("bracket.nc");
    let res = run(&[
        "pocket",
        "examples/bracket.dxf",
        "--tool-diameter",
        "6",
        "--stepover",
        "83%",
        "--depth",
        "2",
        "--check",
        "-o",
        nc.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert!(res.status.success(), "{stderr}");
    assert!(stderr.contains("PASSED"), "{stderr}");
    let res = run(&[
        "check",
        "examples/bracket.dxf",
        nc.to_str().unwrap(),
        "--tool-diameter",
        "6",
        "--json",
    ]);
    assert_eq!(
        res.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&res.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&res.stdout).unwrap();
    assert_eq!(v["passed"], true);
    assert!(v["pockets"][0]["gouge"].as_f64().unwrap() <= 0.01);
    // Without its arcs the program cuts across the islands and leaves material.
    let g = std::fs::read_to_string(&nc).unwrap();
    let lazy: String = g
        .lines()
        .filter(|l| !l.starts_with("G2 ") && !l.starts_with("G3 "))
        .map(|l| format!("{l}\n"))
        .collect();
    let lazy_nc = dir.path().join("lazy.nc");
    std::fs::write(&lazy_nc, lazy).unwrap();
    let res = run(&[
        "check",
        "examples/bracket.dxf",
        lazy_nc.to_str().unwrap(),
        "--tool-diameter",
        "6",
    ]);
    let out = String::from_utf8_lossy(&res.stdout);
    assert_eq!(res.status.code(), Some(1), "{out}");
    assert!(out.contains("FAILED"), "{out}");
    // A program that does not read is an error naming the line.
    let bad = dir.path().join("bad.nc");
    std::fs::write(&bad, "G0 X0 Y0 Z0\nG2 X10 Y0 I4 J0 F100\n").unwrap();
    let res = run(&[
        "check",
        "examples/bracket.dxf",
        bad.to_str().unwrap(),
        "--tool-diameter",
        "6",
    ]);
    assert_eq!(res.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&res.stderr).contains("bad.nc: line 2:"));
}

#[test]
fn check_json_carries_the_engagement_distribution() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("bracket.nc");
    let res = run(&[
        "pocket",
        "examples/bracket.dxf",
        "--tool-diameter",
        "6",
        "--stepover",
        "40%",
        "--depth",
        "3",
        "--tool-number",
        "1",
        "-o",
        nc.to_str().unwrap(),
    ]);
    assert!(res.status.success());
    let out = run(&[
        "check",
        "--json",
        "examples/bracket.dxf",
        nc.to_str().unwrap(),
        "--tool-diameter",
        "6",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let e = &v["engagement"];
    let bands: Vec<f64> = e["histogram"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_f64().unwrap())
        .collect();
    assert_eq!(bands.len(), 36);
    // The bands share out the cutting length measured.
    let length = e["length"].as_f64().unwrap();
    assert!((bands.iter().sum::<f64>() - length).abs() < 1e-6 * length, "{e}");
    let (max, p95) = (e["max_deg"].as_f64().unwrap(), e["p95_deg"].as_f64().unwrap());
    assert!(0.0 < p95 && p95 <= max && max <= 360.0, "{e}");
    assert!(e["max_at"]["line"].as_u64().unwrap() > 0);
    let text = String::from_utf8(
        run(&[
            "check",
            "examples/bracket.dxf",
            nc.to_str().unwrap(),
            "--tool-diameter",
            "6",
        ])
        .stdout,
    )
    .unwrap();
    assert!(text.contains("tool engagement           max "), "{text}");
}

/// Runs `pocketeer args` on a terminal (util-linux's `script`), progress shown at once; its
/// transcript, or `None` where `script` is missing.
fn on_a_terminal(args: &str) -> Option<String> {
    let bin = env!("CARGO_BIN_EXE_pocketeer");
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("typescript");
    let out = std::process::Command::new("script")
        .arg("-qec")
        .arg(format!("{bin} {args}"))
        .arg(&log)
        .env("POCKETEER_PROGRESS_DELAY_MS", "0")
        .current_dir(common::repo())
        .output()
        .ok()?;
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    Some(String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned())
}

#[test]
fn progress_shows_on_a_terminal_and_nowhere_else() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("b.nc");
    let args = format!(
        "pocket examples/bracket.dxf --tool-diameter 6 --stepover 2.4 --depth 2 --check -o {}",
        nc.display()
    );
    let Some(shown) = on_a_terminal(&args) else {
        panic!("util-linux's script is needed for this test");
    };
    assert!(
        [
            "reading the drawing",
            "planning pockets",
            "linking",
            "writing the program",
            "checking the program"
        ]
        .iter()
        .any(|s| shown.contains(s)),
        "{shown}"
    );
    let quiet = on_a_terminal(&format!("--quiet {args}")).unwrap();
    assert!(
        !quiet.contains("planning pockets") && !quiet.contains("checking the program"),
        "{quiet}"
    );
    // Not a terminal: the same run prints no progress at all.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pocketeer"))
        .args(args.split(' '))
        .env("POCKETEER_PROGRESS_DELAY_MS", "0")
        .current_dir(common::repo())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success());
    assert!(!err.contains("planning pockets") && !err.contains('\r'), "{err}");
}
