//! pocketeer: contour-parallel pocket milling from DXF drawings.
//!
//! The library follows the data flow of the design: [`import`] reads a drawing into segments,
//! chains them into closed contours and nests those into pockets with islands; the geometry
//! kernel in [`geom`] holds the exact lines and arcs every stage works on.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod export;
pub mod geom;
pub mod import;

pub use import::{read_drawing, Drawing, ImportError, ImportOptions};

/// A drawing read, chained and nested: everything `inspect` reports and pocketing starts from.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// The drawing as read.
    pub drawing: Drawing,
    /// Its elements joined into contours.
    pub chains: import::Chains,
    /// The contours nested into pockets.
    pub regions: import::Regions,
    /// The tolerances used.
    pub tolerance: geom::Tolerance,
}

/// Reads DXF bytes and finds the pockets in them.
///
/// Fails when the file cannot be read, when no closed contour exists, or when a contour
/// crosses itself.
pub fn analyze(bytes: &[u8], options: &ImportOptions) -> Result<Analysis, ImportError> {
    let drawing = read_drawing(bytes, options)?;
    let tolerance = drawing.tolerance(options.join_tolerance);
    let chains = import::chain(&drawing.elements, &tolerance);
    if chains.contours.is_empty() {
        let ends: Vec<String> = chains
            .open
            .iter()
            .take(5)
            .map(|o| {
                format!(
                    "{} to {}",
                    import::error::fmt_point(o.start),
                    import::error::fmt_point(o.end)
                )
            })
            .collect();
        let more = if chains.open.len() > 5 {
            format!(" and {} more", chains.open.len() - 5)
        } else {
            String::new()
        };
        return Err(ImportError::NoClosedContour(format!(
            "{} open chain(s), free ends {}{more}; close the outline or raise --join-tolerance",
            chains.open.len(),
            ends.join(", ")
        )));
    }
    let regions = import::find_pockets(&chains.contours, &drawing.layers, &tolerance)?;
    Ok(Analysis {
        drawing,
        chains,
        regions,
        tolerance,
    })
}
