//! The `pocketeer` binary as a user runs it: output, JSON, messages and exit codes.

use std::path::PathBuf;
use std::process::{Command, Output};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pocketeer"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("binary runs")
}

#[test]
fn inspect_prints_the_bracket() {
    let out = run(&["inspect", "examples/bracket.dxf"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("pockets   1"), "{text}");
    assert!(text.contains("3 island(s)"), "{text}");
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
