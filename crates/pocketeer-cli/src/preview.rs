//! The SVG previews every command writes: the drawing (its pockets, the open chains ignored,
//! and a ring round every place the importer repaired) beneath the command's own layers.

use pocketeer::export::svg;
use pocketeer::geom::{Arc, Contour, Segment};
use pocketeer::Analysis;

/// An SVG document of the drawing of `a` with `layers` drawn over it.
pub fn document(a: &Analysis, layers: &[svg::Layer]) -> String {
    let walls: Vec<Contour> = a
        .nesting
        .pockets
        .iter()
        .flat_map(|p| p.contours().cloned())
        .collect();
    let ignored = ignored_open_chains(a);
    let repaired = repair_marks(a);
    let mut all = vec![
        svg::Layer {
            name: "drawing",
            stroke: "black",
            fill: "#dde6f0",
            contours: &walls,
            paths: &[],
            label: "pocket (islands white)",
            width: 0.0,
            dash: false,
            frames: true,
        },
        svg::Layer {
            name: "ignored-open-chains",
            stroke: "#e07000",
            fill: "none",
            contours: &[],
            paths: &ignored,
            label: "open chain, ignored",
            width: 0.0,
            dash: true,
            frames: true,
        },
        svg::Layer {
            name: "repairs",
            stroke: "#d0008a",
            fill: "none",
            contours: &repaired,
            paths: &[],
            label: "repaired by the importer",
            width: 0.0,
            dash: false,
            frames: false,
        },
    ];
    all.extend_from_slice(layers);
    svg::svg_document(&all, "mm")
}

/// The elements of the open chains ignored under `--ignore-open`, one path each.
pub fn ignored_open_chains(a: &Analysis) -> Vec<Vec<Segment>> {
    a.chains
        .open
        .iter()
        .flat_map(|o| o.elements.iter().filter_map(|&e| a.drawing.elements.get(e)))
        .map(|e| vec![e.segment])
        .collect()
}

/// A ring round every place the importer repaired, a hundredth of the drawing across (a
/// gap of micrometres would not show otherwise).
fn repair_marks(a: &Analysis) -> Vec<Contour> {
    let e = &a.drawing.extent;
    let r = (0.005 * e.width().max(e.height())).max(1e-3);
    crate::inspect::repairs(a)
        .iter()
        .flat_map(|w| w.places())
        .map(|p| Contour::new(vec![Segment::Arc(Arc::new(p, r, 0.0, std::f64::consts::TAU))]))
        .collect()
}
