//! The whole import in one call: a drawing read, its elements chained into contours, the
//! contours nested into pockets, and the policy for open chains (a broken outline round or
//! inside closed contours is refused unless asked to ignore it; other open strokes are
//! ignored).

use super::{read_drawing, Chains, Drawing, ImportError, ImportOptions, OpenChain};
use crate::geom::{Aabb, BoxIndex, Contour, Line, Segment};

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

/// An open chain whose own gap is at most this share of its length is an outline that does
/// not close; a chain open wider is a stroke (a centre mark, a construction line, a letter).
const BROKEN_OUTLINE_GAP: f64 = 0.1;

/// Reads DXF bytes and finds the pockets in them.
///
/// Fails when the file cannot be read, when no closed contour exists, when a broken outline
/// lies round or inside closed contours, or (with [`ImportOptions::strict`]) when a contour
/// crosses itself.
pub fn analyze(bytes: &[u8], options: &ImportOptions) -> Result<Analysis, ImportError> {
    let drawing = read_drawing(bytes, options)?;
    let tolerance = drawing.tolerance(options.join_tolerance);
    let chains = super::chain(&drawing.elements, &tolerance, options.close_gaps);
    if chains.contours.is_empty() {
        return Err(ImportError::NoClosedContour {
            open: chains.open.len(),
            ends: chains.open.iter().take(5).map(|o| (o.start, o.end)).collect(),
            gap: chains
                .open
                .iter()
                .filter_map(|o| o.nearest_gap)
                .min_by(|a, b| a.length.total_cmp(&b.length)),
        });
    }
    if !options.ignore_open {
        refuse_broken_outlines(&drawing, &chains)?;
    }
    let fill = (!options.strict).then_some(options.fill);
    let nesting = super::find_pockets(&chains.contours, &drawing.layers, &tolerance, fill)?;
    Ok(Analysis {
        drawing,
        chains,
        nesting,
        tolerance,
    })
}

/// The open chain closed across its own gap, when it is a broken outline: the gap at most
/// [`BROKEN_OUTLINE_GAP`] of its length and the loop enclosing more than half the gap times
/// the length (a stroke drawn there and back, a sliver across its gap, encloses at most a
/// quarter of that).
fn closed_across_gap(o: &OpenChain) -> Option<Contour> {
    let length: f64 = o.segments.iter().map(Segment::length).sum();
    let gap = o.start.distance(o.end);
    if gap > BROKEN_OUTLINE_GAP * length {
        return None;
    }
    let mut segments = o.segments.clone();
    if gap > 0.0 {
        segments.push(Segment::Line(Line::new(o.end, o.start)));
    }
    let contour = Contour::new(segments);
    (contour.signed_area().abs() > 0.5 * gap.max(f64::MIN_POSITIVE) * length).then_some(contour)
}

/// Refuses a drawing where a broken outline (see [`closed_across_gap`]) encloses closed
/// contours or lies inside one: pocketing around it would cut its islands as if they were
/// pockets, or cut through the island it was meant to be.
fn refuse_broken_outlines(drawing: &Drawing, chains: &Chains) -> Result<(), ImportError> {
    if chains.open.is_empty() {
        // Nothing to judge: the contours' boxes below are a pass over every segment.
        return Ok(());
    }
    let boxes: Vec<Aabb> = chains.contours.iter().map(|c| c.contour.bbox()).collect();
    let index = BoxIndex::new(&boxes);
    for o in &chains.open {
        let Some(closed) = closed_across_gap(o) else {
            continue;
        };
        let extent = closed.bbox();
        let surrounded = index
            .intersecting(&extent)
            .filter(|&k| {
                let c = &chains.contours[k].contour;
                extent.contains_box(&boxes[k]) && closed.winding_number(c.segments[0].point_at(0.5)) != 0
            })
            .count();
        let inside = index.intersecting(&extent).any(|k| {
            boxes[k].contains_box(&extent) && chains.contours[k].contour.winding_number(o.start) != 0
        });
        if surrounded > 0 || inside {
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
