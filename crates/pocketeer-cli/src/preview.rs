//! The SVG previews every command writes: the drawing (its pockets, and the open chains
//! ignored under `--ignore-open`) beneath the command's own layers.

use pocketeer::export::svg;
use pocketeer::geom::{Contour, Segment};
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
    let mut all = vec![
        svg::Layer {
            name: "drawing",
            stroke: "black",
            fill: "#dde6f0",
            contours: &walls,
            paths: &[],
        },
        svg::Layer {
            name: "ignored-open-chains",
            stroke: "#e07000",
            fill: "none",
            contours: &[],
            paths: &ignored,
        },
    ];
    all.extend_from_slice(layers);
    svg::svg_document(&all)
}

/// The elements of the open chains ignored under `--ignore-open`, one path each.
fn ignored_open_chains(a: &Analysis) -> Vec<Vec<Segment>> {
    a.chains
        .open
        .iter()
        .flat_map(|o| o.elements.iter().filter_map(|&e| a.drawing.elements.get(e)))
        .map(|e| vec![e.segment])
        .collect()
}
