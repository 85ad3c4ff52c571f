//! What a machinist meets on a first real job, tried as a user would run the binary: the
//! milling direction, unit mistakes, warnings, outputs that must not destroy inputs, inch jobs.

mod common;

use common::{dxf, run};
use std::path::Path;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A 60 x 40 mm plate with two round islands, in millimetres.
fn plate(dir: &Path) -> std::path::PathBuf {
    let drawing = dir.join("plate.dxf");
    let outline: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
    std::fs::write(
        &drawing,
        dxf(&[(outline, true)], &[(18.0, 20.0, 6.0), (42.0, 20.0, 5.0)], 4),
    )
    .unwrap();
    drawing
}

#[test]
fn the_default_is_climb_and_check_measures_it_along_the_walls() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = plate(dir.path());
    let d = drawing.to_str().unwrap();
    for (flags, share) in [
        (&[][..], "100.0 % climb"),
        (&["--direction", "conventional"][..], "0.0 % climb"),
    ] {
        let nc = dir.path().join("plate.nc");
        let mut args = vec![
            "pocket",
            d,
            "--tool-diameter",
            "6",
            "--stepover",
            "40%",
            "--depth",
            "3",
            "-o",
        ];
        args.push(nc.to_str().unwrap());
        args.extend_from_slice(flags);
        let res = run(&args);
        assert!(res.status.success(), "{}", text(&res.stderr));
        let g = std::fs::read_to_string(&nc).unwrap();
        let named = if flags.is_empty() {
            "(climb milling"
        } else {
            "(conventional milling"
        };
        assert!(g.contains(named), "the header names the direction: {g}");
        let res = run(&["check", d, nc.to_str().unwrap(), "--tool-diameter", "6"]);
        let out = text(&res.stdout);
        assert!(res.status.success(), "{out}");
        assert!(out.contains(share), "{flags:?}: {out}");
    }
}

/// Runs `pocket` on `drawing` with a 6 mm tool, 40 % stepover, 3 mm deep and `extra` flags.
fn pocket(drawing: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "pocket",
        drawing.to_str().unwrap(),
        "--tool-diameter",
        "6",
        "--stepover",
        "40%",
        "--depth",
        "3",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

#[test]
fn a_millimetre_plate_under_a_metres_header_is_called_out_and_pockets_with_units_mm() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("metres.dxf");
    let outline: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
    // $INSUNITS 6: metres, ezdxf's default.
    std::fs::write(
        &drawing,
        dxf(&[(outline, true)], &[(18.0, 20.0, 6.0), (42.0, 20.0, 5.0)], 6),
    )
    .unwrap();
    let res = run(&["inspect", drawing.to_str().unwrap()]);
    let out = text(&res.stdout);
    assert!(out.contains("extents   60000.000 x 40000.000 mm"), "{out}");
    assert!(
        out.contains("declares metres") && out.contains("--units mm"),
        "{out}"
    );
    let nc = dir.path().join("metres.nc");
    let res = pocket(&drawing, &nc, &[]);
    let err = text(&res.stderr);
    // A pocket 60 m across: planned (thousands of nested loops, no stack overflow) but warned.
    assert!(res.status.success(), "{err}");
    assert!(
        err.contains("declares metres") && err.contains("pass --units mm"),
        "{err}"
    );
    assert!(err.contains("longer than 24 h"), "{err}");
    let res = pocket(&drawing, &nc, &["--units", "mm"]);
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert!(!err.contains("larger than") && !err.contains("24 h"), "{err}");
    assert!(
        err.contains("declares metres; read in millimetres as asked"),
        "{err}"
    );
    assert!(err.contains("drawing 60.000 x 40.000 mm"), "{err}");
}

#[test]
fn an_inch_plate_under_a_millimetre_header_is_smaller_than_the_tool_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("inch.dxf");
    let outline: &[(f64, f64)] = &[(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0)];
    std::fs::write(&drawing, dxf(&[(outline, true)], &[], 4)).unwrap();
    let res = pocket(&drawing, &dir.path().join("inch.nc"), &[]);
    let err = text(&res.stderr);
    assert_eq!(res.status.code(), Some(2), "{err}");
    assert!(
        err.contains("fits nowhere in the pocket") && err.contains("the widest place is 3.000 mm"),
        "{err}"
    );
    assert!(
        err.contains("declares millimetres") && err.contains("--units in"),
        "{err}"
    );
}

#[test]
fn pocket_and_offset_show_the_importers_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("twice.dxf");
    let outline: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
    // Every outline drawn twice, as some exporters do.
    std::fs::write(
        &drawing,
        dxf(
            &[(outline, true), (outline, true)],
            &[(30.0, 20.0, 6.0), (30.0, 20.0, 6.0)],
            4,
        ),
    )
    .unwrap();
    let nc = dir.path().join("twice.nc");
    let res = pocket(&drawing, &nc, &[]);
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert_eq!(err.matches("duplicate").count(), 1, "once: {err}");
    let loops = dir.path().join("loops.dxf");
    let res = run(&[
        "offset",
        drawing.to_str().unwrap(),
        "--distance",
        "3",
        "-o",
        loops.to_str().unwrap(),
    ]);
    let err = text(&res.stderr);
    assert!(res.status.success() && err.contains("duplicate"), "{err}");
}

#[test]
fn an_ignored_open_outline_is_drawn_in_the_preview() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("open.dxf");
    let outline: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
    let broken: &[(f64, f64)] = &[
        (-10.0, -10.0),
        (70.0, -10.0),
        (70.0, 50.0),
        (-10.0, 50.0),
        (-10.0, 0.0),
    ];
    std::fs::write(&drawing, dxf(&[(outline, true), (broken, false)], &[], 4)).unwrap();
    let svg = dir.path().join("open.svg");
    let res = pocket(
        &drawing,
        &dir.path().join("open.nc"),
        &["--ignore-open", "--svg", svg.to_str().unwrap()],
    );
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert!(
        err.contains("open chain of 4 elements on layer 'parts' ignored"),
        "{err}"
    );
    let doc = std::fs::read_to_string(&svg).unwrap();
    let layer = doc
        .split(r#"<g id="ignored-open-chains""#)
        .nth(1)
        .expect("a layer for the open chains");
    let layer = layer.split("</g>").next().unwrap_or_default();
    assert!(layer.contains("M-10 -10 L70 -10"), "{layer}");
}

#[test]
fn outputs_never_destroy_the_drawing() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = plate(dir.path());
    let before = std::fs::read(&drawing).unwrap();
    // The drawing itself, by another spelling, and by a hard link.
    let other = dir.path().join("sub").join("..").join("plate.dxf");
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let link = dir.path().join("linked.nc");
    std::fs::hard_link(&drawing, &link).unwrap();
    for out in [&drawing, &other, &link] {
        let res = pocket(&drawing, out, &["--force"]);
        let err = text(&res.stderr);
        assert_eq!(res.status.code(), Some(2), "{err}");
        assert!(err.contains("refusing to overwrite"), "{err}");
        assert_eq!(std::fs::read(&drawing).unwrap(), before);
    }
    let res = run(&[
        "offset",
        drawing.to_str().unwrap(),
        "--distance",
        "3",
        "-o",
        drawing.to_str().unwrap(),
    ]);
    assert_eq!(res.status.code(), Some(2), "{}", text(&res.stderr));
    assert_eq!(std::fs::read(&drawing).unwrap(), before);
    // A program to a .dxf needs --force.
    let dxf_out = dir.path().join("program.dxf");
    let res = pocket(&drawing, &dxf_out, &[]);
    assert!(text(&res.stderr).contains("--force"), "{}", text(&res.stderr));
    assert!(!dxf_out.exists());
    assert!(pocket(&drawing, &dxf_out, &["--force"]).status.success());
    // --svg and -o naming one file.
    let nc = dir.path().join("plate.nc");
    let res = pocket(&drawing, &nc, &["--svg", nc.to_str().unwrap()]);
    assert!(
        text(&res.stderr).contains("-o and --svg both name"),
        "{}",
        text(&res.stderr)
    );
    assert!(!nc.exists());
    // -o - writes the program to standard output.
    let res = pocket(&drawing, Path::new("-"), &[]);
    let out = text(&res.stdout);
    assert!(
        res.status.success() && out.starts_with("(pocketeer ") && out.ends_with("M2\n"),
        "{out}"
    );
    assert!(text(&res.stderr).contains("written to standard output"));
}

#[test]
fn an_inch_job_speaks_inches_with_round_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("inch.dxf");
    let square: &[(f64, f64)] = &[(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0)];
    std::fs::write(&drawing, dxf(&[(square, true)], &[(2.0, 1.5, 0.5)], 1)).unwrap();
    let nc = dir.path().join("inch.nc");
    let res = run(&[
        "pocket",
        drawing.to_str().unwrap(),
        "--tool-diameter",
        "0.25in",
        "--stepover",
        "40%",
        "--depth",
        "0.1in",
        "-o",
        nc.to_str().unwrap(),
    ]);
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert!(
        err.contains(" in, rapid ") && !err.lines().last().unwrap_or_default().contains(" mm"),
        "the summary in inches: {err}"
    );
    assert!(
        err.contains("(101.600 x 76.200 mm, from"),
        "the extents in mm too: {err}"
    );
    assert!(err.contains("drawing 4.000 x 3.000 in"), "{err}");
    let g = std::fs::read_to_string(&nc).unwrap();
    for word in [
        "(tool diameter 0.25 in, stepover 0.1 in)",
        "(feed 40 in/min, plunge 12 in/min, spindle 12000 rpm, wait 2 s)",
        "(safe height 0.2 in, feed height 0.04 in)",
        "\nG20\n",
        "G0 Z0.20000\n",
        " F12\n",
        " F40\n",
    ] {
        assert!(g.contains(word), "{word:?} missing from {g}");
    }
    assert!(
        !g.contains("F11.811") && !g.contains("Z0.19685") && !g.contains(" mm"),
        "{g}"
    );
    assert!(g.contains("Z-0.10000"), "the depth in inches");
    // Every X stays inside the 4 in plate, a tool radius in.
    for x in g
        .lines()
        .filter_map(|l| l.split(' ').find_map(|w| w.strip_prefix('X')))
    {
        let x: f64 = x.parse().unwrap();
        assert!((0.125 - 1e-4..=3.875 + 1e-4).contains(&x), "X{x}");
    }
}

#[test]
fn check_judges_a_program_cut_deeper_than_its_depth_at_that_depth() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = plate(dir.path());
    let nc = dir.path().join("deep.nc");
    assert!(pocket(&drawing, &nc, &[]).status.success());
    // Cut to 3 mm, judged at 2 mm: what was swept at 3 mm was swept at 2 mm too.
    let res = run(&[
        "check",
        drawing.to_str().unwrap(),
        nc.to_str().unwrap(),
        "--tool-diameter",
        "6",
        "--depth",
        "2",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&res.stdout).unwrap();
    assert_eq!(v["passed"], true, "{v}");
    assert!(
        v["pockets"][0]["leftover_percent"].as_f64().unwrap() < 0.01,
        "{v}"
    );
}

#[test]
fn small_words_read_right() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = plate(dir.path());
    let d = drawing.to_str().unwrap();
    let nc = dir.path().join("plate.nc");
    // Negative values reach our own checks, which say why.
    let res = pocket(&drawing, &nc, &["--safe-z", "-3"]);
    let err = text(&res.stderr);
    assert_eq!(res.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--safe-z -3: the safe height must be above the stock top"),
        "{err}"
    );
    assert!(!err.contains("-- -3"), "{err}");
    // Feeds with their unit, names in any case; one pass is a pass.
    let res = pocket(
        &drawing,
        &nc,
        &[
            "--feed",
            "1000mm/min",
            "--plunge-feed",
            "12in/min",
            "--post",
            "LinuxCNC",
            "--direction",
            "Climb",
        ],
    );
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert!(
        err.contains("in 1 pass:") && !err.contains("(s)") && !err.contains("-0.0"),
        "{err}"
    );
    let g = std::fs::read_to_string(&nc).unwrap();
    assert!(g.contains(" F304.8\n") && g.contains("G91.1"), "{g}");
    // pocket and check give the same lengths and time.
    let summary = err.lines().last().unwrap_or_default().to_string();
    let res = run(&["check", d, nc.to_str().unwrap(), "--tool-diameter", "6"]);
    let out = text(&res.stdout);
    let figures = |s: &str, from: &str| {
        s.split(from)
            .nth(1)
            .and_then(|t| t.split(" mm").next())
            .unwrap_or_default()
            .to_string()
    };
    assert_eq!(
        figures(&summary, "rapid "),
        figures(&out, "rapid "),
        "{summary}\n{out}"
    );
    assert_eq!(
        figures(&summary, "cutting "),
        figures(&out, "cutting "),
        "{summary}\n{out}"
    );
    let time = |s: &str| {
        s.split("about ")
            .nth(1)
            .and_then(|t| t.split(' ').next())
            .unwrap_or_default()
            .to_string()
    };
    assert_eq!(time(&summary), time(&out), "{summary}\n{out}");
    assert!(time(&out).ends_with('s') && time(&out).contains('m'), "{out}");
    // An offset with no loop says why.
    let loops = dir.path().join("loops.dxf");
    let res = run(&["offset", d, "--distance", "25", "-o", loops.to_str().unwrap()]);
    let err = text(&res.stderr);
    assert!(res.status.success(), "{err}");
    assert!(
        err.contains("no loop at 25 mm: its largest inscribed circle has a radius of"),
        "{err}"
    );
}

#[test]
fn a_refusal_never_suggests_closing_a_gap_over_a_millimetre() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = dir.path().join("gap.dxf");
    // An outline round an island with a 5 mm gap.
    let broken: &[(f64, f64)] = &[
        (0.0, 5.0),
        (0.0, 0.0),
        (60.0, 0.0),
        (60.0, 40.0),
        (0.0, 40.0),
        (0.0, 10.0),
    ];
    std::fs::write(&drawing, dxf(&[(broken, false)], &[(30.0, 20.0, 6.0)], 4)).unwrap();
    let res = pocket(&drawing, &dir.path().join("gap.nc"), &[]);
    let err = text(&res.stderr);
    assert_eq!(res.status.code(), Some(2), "{err}");
    assert!(
        err.contains("does not close") && !err.contains("--join-tolerance") && !err.contains("--close-gaps"),
        "{err}"
    );
    assert!(err.contains("--layers, or pass --ignore-open"), "{err}");
    // A gap of half a millimetre, no other free end near: the gap length that would bridge it
    // is worth naming.
    let near: &[(f64, f64)] = &[(0.5, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0), (0.0, 0.0)];
    std::fs::write(&drawing, dxf(&[(near, false)], &[(30.0, 20.0, 6.0)], 4)).unwrap();
    let res = pocket(&drawing, &dir.path().join("gap.nc"), &[]);
    let err = text(&res.stderr);
    assert!(err.contains("or pass --close-gaps 0.6mm"), "{err}");
}

#[test]
fn the_program_has_what_a_machinist_expects() {
    let dir = tempfile::tempdir().unwrap();
    let drawing = plate(dir.path());
    let nc = dir.path().join("plate.nc");
    let res = pocket(
        &drawing,
        &nc,
        &[
            "--post",
            "linuxcnc",
            "--tool-number",
            "3",
            "--coolant",
            "flood",
            "--park",
            "-10,150",
            "--step-down",
            "1.5",
        ],
    );
    assert!(res.status.success(), "{}", text(&res.stderr));
    let g = std::fs::read_to_string(&nc).unwrap();
    for word in [
        "\nT3 M6\nG43 H3\nM3 S12000\nG4 P2\nM8\n",
        "\nM5\nM9\nG0 X-10.0000 Y150.0000\nM2\n",
        "(command: pocketeer pocket ",
    ] {
        assert!(g.contains(word), "{word:?} missing from {g}");
    }
    // The second pass comes down rapidly to 1 mm above the first pass's floor, not to Z1.
    assert!(g.contains("G0 Z-0.5000\nG1 Z-1.5000 F300\n"), "{g}");
    let res = pocket(&drawing, &nc, &["--spindle-wait", "0", "--tool-number", "3"]);
    assert!(res.status.success(), "{}", text(&res.stderr));
    let g = std::fs::read_to_string(&nc).unwrap();
    // The words, not the comments: the header names the drawing, and a temporary folder's
    // random name may hold "G4" or "M6".
    let code: String = g
        .lines()
        .filter(|l| !l.starts_with('('))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(
        !code.contains("G4") && !code.contains("M6") && code.contains("\nT3\n"),
        "GRBL: no M6 {g}"
    );
    // Every line fits GRBL's 80 characters, even with a long path and a unit override.
    let long = dir
        .path()
        .join("a folder with a rather long name for the drawings of this shop");
    std::fs::create_dir(&long).unwrap();
    let far = long.join("plate.dxf");
    std::fs::copy(&drawing, &far).unwrap();
    let res = pocket(&far, &nc, &["--units", "mm", "--spindle", "18000"]);
    assert!(res.status.success(), "{}", text(&res.stderr));
    let g = std::fs::read_to_string(&nc).unwrap();
    assert!(g.lines().all(|l| l.len() <= 80), "{g}");
    let res = pocket(&drawing, &nc, &["--coolant", "mist"]);
    assert!(text(&res.stderr).contains("ENABLE_M7"), "{}", text(&res.stderr));
}
