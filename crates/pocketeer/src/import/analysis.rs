//! The whole import in one call: a drawing read, its elements chained into contours, the
//! contours nested into pockets, and the policy for open chains (an open chain round closed
//! contours is a broken outline, refused unless asked to ignore it).

use super::{read_drawing, Drawing, ImportError, ImportOptions};

/// A drawing read, chained and nested: everything `inspect` reports and pocketing starts from.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// The drawing as read.
    pub drawing: Drawing,
    /// Its elements joined into contours.
    pub chains: super::Chains,
    /// The contours nested into pockets.
    pub nesting: super::Nesting,
    /// The tolerances used.
    pub tolerance: crate::geom::Tolerance,
}

/// Reads DXF bytes and finds the pockets in them.
///
/// Fails when the file cannot be read, when no closed contour exists, or when a contour
/// crosses itself.
pub fn analyze(bytes: &[u8], options: &ImportOptions) -> Result<Analysis, ImportError> {
    let drawing = read_drawing(bytes, options)?;
    let tolerance = drawing.tolerance(options.join_tolerance);
    let chains = super::chain(&drawing.elements, &tolerance);
    if chains.contours.is_empty() {
        return Err(ImportError::NoClosedContour {
            open: chains.open.len(),
            ends: chains.open.iter().take(5).map(|o| (o.start, o.end)).collect(),
        });
    }
    if !options.ignore_open {
        refuse_open_outlines(&drawing, &chains)?;
    }
    let nesting = super::find_pockets(&chains.contours, &drawing.layers, &tolerance)?;
    Ok(Analysis {
        drawing,
        chains,
        nesting,
        tolerance,
    })
}

/// Refuses a drawing where an open chain surrounds closed contours: pocketing the contours
/// inside a broken outline would cut its islands as if they were pockets.
fn refuse_open_outlines(drawing: &Drawing, chains: &super::Chains) -> Result<(), ImportError> {
    let boxes: Vec<crate::geom::Aabb> = chains.contours.iter().map(|c| c.contour.bbox()).collect();
    let index = crate::geom::BoxIndex::new(&boxes);
    for o in &chains.open {
        let extent = o.elements.iter().fold(crate::geom::Aabb::EMPTY, |b, &e| {
            b.union(&drawing.elements[e].segment.bbox())
        });
        let surrounded = index
            .intersecting(&extent)
            .filter(|&k| extent.contains_box(&boxes[k]) && boxes[k] != extent)
            .count();
        if surrounded > 0 {
            return Err(ImportError::OpenOutline {
                layer: drawing.layers.get(o.layer).cloned().unwrap_or_default(),
                elements: o.elements.len(),
                start: o.start,
                end: o.end,
                surrounded,
                gap: o.nearest_gap,
            });
        }
    }
    Ok(())
}
