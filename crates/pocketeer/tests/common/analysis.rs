//! Reading test drawings through the whole importer.

use super::Drawing;
use pocketeer::import::ImportError;
use pocketeer::{analyze, Analysis, ImportOptions};

/// The drawing imported with the default options.
pub fn read(d: &Drawing) -> Analysis {
    analyze(d.text().as_bytes(), &ImportOptions::default()).expect("drawing should import")
}

/// The importer's refusal of the drawing.
pub fn read_err(d: &Drawing) -> ImportError {
    match analyze(d.text().as_bytes(), &ImportOptions::default()) {
        Ok(_) => panic!("drawing should be refused"),
        Err(e) => e,
    }
}

/// (net area, boundary area, island areas) of every pocket.
pub fn pockets(a: &Analysis) -> Vec<(f64, f64, Vec<f64>)> {
    a.nesting
        .pockets
        .iter()
        .map(|p| {
            let mut isl: Vec<f64> = p.islands.iter().map(|c| -c.signed_area()).collect();
            isl.sort_by(f64::total_cmp);
            (p.area(), p.boundary.signed_area(), isl)
        })
        .collect()
}

/// True when `a` and `b` differ by at most `tol`.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}
