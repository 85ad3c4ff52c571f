//! What the CLI tests share: running the binary from the repository's root, and a small DXF
//! writer.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The repository's root, where the tests run the binary.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `pocketeer` with `args` from the repository's root.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pocketeer"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("binary runs")
}

/// A DXF with closed or open LWPOLYLINEs on layer `parts`, and `$INSUNITS` = `units`.
pub fn dxf(polylines: &[(&[(f64, f64)], bool)], circles: &[(f64, f64, f64)], units: i32) -> String {
    let mut s =
        format!("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n{units}\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    for (pts, closed) in polylines {
        s += &format!(
            "0\nLWPOLYLINE\n8\nparts\n90\n{}\n70\n{}\n",
            pts.len(),
            u8::from(*closed)
        );
        for (x, y) in pts.iter() {
            s += &format!("10\n{x}\n20\n{y}\n");
        }
    }
    for (x, y, r) in circles {
        s += &format!("0\nCIRCLE\n8\nparts\n10\n{x}\n20\n{y}\n40\n{r}\n");
    }
    s + "0\nENDSEC\n0\nEOF\n"
}
