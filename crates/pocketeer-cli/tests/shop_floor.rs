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
