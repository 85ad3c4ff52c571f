//! From DXF bytes to pockets: reading ([`dxf`]), block expansion, curves to exact lines and arcs,
//! chaining into closed contours ([`mod@chain`]), and nesting into pockets with islands ([`nesting`]);
//! [`analyze`] does it all. What it repaired or left out on the way is an [`ImportWarning`].

mod analysis;
pub mod biarc;
pub mod biarc_piece;
pub mod chain;
pub mod curve;
mod dangles;
pub mod dxf;
mod entities;
pub mod error;
mod expand;
mod faces;
mod fill;
mod free_ends;
pub mod nesting;
mod nodes;
mod placement;
// Public for the property tests, which check its repair on random contours; not an API.
#[doc(hidden)]
pub mod self_crossing;
pub mod span_polynomial;
pub mod units;
mod warning;

pub use analysis::{analyze, Analysis};
pub use chain::{chain, ChainedContour, Chains, NearestGap, OpenChain};
pub use error::{EntityRef, ImportError, Pos};
pub use fill::FillRule;
pub use nesting::{find_pockets, Nesting};
pub use units::Units;
pub use warning::ImportWarning;

use crate::geom::{Aabb, Segment, Tolerance, DEFAULT_JOIN_TOLERANCE};
use curve::Affine;
use std::collections::BTreeMap;

/// Coordinates beyond this many millimetres from the origin are refused: no machine is that big,
/// and f64 resolution there would be coarser than our tolerances.
pub const MAX_COORDINATE: f64 = 1e8;

/// Largest deviation of the arcs that replace an ellipse or spline, in millimetres.
pub const CURVE_TOLERANCE: f64 = 0.001;

/// Default for [`ImportOptions::close_gaps`], mm: far below what any cutter could tell, far
/// above the rounding and curve-fitting errors that open real outlines.
pub const DEFAULT_CLOSE_GAPS: f64 = 0.05;

/// How to read a drawing.
#[derive(Debug, Clone)]
pub struct ImportOptions {
    /// Only these layers (case-insensitive); all when `None`.
    pub layers: Option<Vec<String>>,
    /// The drawing's unit, overriding `$INSUNITS`; when both are absent, millimetres.
    pub units: Option<Units>,
    /// Join tolerance in millimetres: free ends this near are moved to meet.
    pub join_tolerance: f64,
    /// Gaps between free ends up to this many millimetres, where each end is the other's
    /// nearest by far, are closed with a straight segment; 0 closes none.
    pub close_gaps: f64,
    /// How a contour that crosses or touches itself is filled.
    pub fill: FillRule,
    /// Refuse a contour that crosses or touches itself instead of filling it.
    pub strict: bool,
    /// Ignore open chains even where they surround closed contours (by default such a drawing
    /// is refused: the open chain is most likely a pocket outline that does not close).
    pub ignore_open: bool,
}

impl Default for ImportOptions {
    fn default() -> Self {
        ImportOptions {
            layers: None,
            units: None,
            join_tolerance: DEFAULT_JOIN_TOLERANCE,
            close_gaps: DEFAULT_CLOSE_GAPS,
            fill: FillRule::EvenOdd,
            strict: false,
            ignore_open: false,
        }
    }
}

/// One drawn line or arc of the drawing, in millimetres.
#[derive(Debug, Clone)]
pub struct Element {
    /// The geometry.
    pub segment: Segment,
    /// Index into [`Drawing::layers`].
    pub layer: usize,
    /// Index into [`Drawing::sources`]: the entity it was drawn by.
    pub source: usize,
    /// Set for the elements of one closed polyline: they form a contour by themselves, in order,
    /// and are not chained with others.
    pub closed_group: Option<usize>,
}

/// A drawing read from DXF: every outline element in millimetres, with what was seen on the way.
#[derive(Debug, Clone)]
pub struct Drawing {
    /// `$INSUNITS` as declared, if any.
    pub declared_units: Option<Units>,
    /// The unit the drawing was read in.
    pub units: Units,
    /// Every layer name: the LAYER table, then layers used but not declared.
    pub layers: Vec<String>,
    /// Number of model-space entities of each type (before block expansion).
    pub entity_counts: BTreeMap<String, usize>,
    /// The outline elements (after the layer filter).
    pub elements: Vec<Element>,
    /// The entities elements come from.
    pub sources: Vec<EntityRef>,
    /// Bounding box of the elements.
    pub extent: Aabb,
    /// Remarks about the file.
    pub warnings: Vec<ImportWarning>,
    /// True for a binary DXF.
    pub binary: bool,
}

impl Drawing {
    /// The tolerances for this drawing.
    pub fn tolerance(&self, join: f64) -> Tolerance {
        Tolerance::for_extent(&self.extent, join)
    }
}

/// Reads a DXF file's bytes into a [`Drawing`].
pub fn read_drawing(bytes: &[u8], options: &ImportOptions) -> Result<Drawing, ImportError> {
    let list = dxf::GroupList::read(bytes)?;
    let mut doc = dxf::parse_document(&list)?;
    let binary = doc.binary;
    let mut warnings = std::mem::take(&mut doc.warnings);
    let (declared_units, units) = drawing_units(&doc, options, &mut warnings);

    let mut model = std::mem::take(&mut doc.entities);
    model.retain(|e| !e.in_paper_space());
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for e in &model {
        *counts.entry(e.kind.as_ref()).or_insert(0) += 1;
    }
    let entity_counts: BTreeMap<String, usize> = counts.into_iter().map(|(k, n)| (k.to_owned(), n)).collect();
    if model.is_empty() {
        return Err(ImportError::EmptyModelSpace);
    }

    let mut expander = expand::Expander::new(&doc, options.layers.as_deref());
    expander.walk(&model, &Affine::scale(units.mm()), None)?;
    warnings.append(&mut expander.warnings);
    let layers = expander.layers;
    warn_of_missing_layers(&layers, options, &mut warnings);
    let sources = expander.sources;
    let (elements, extent) = expander.elements.finish();
    if elements.is_empty() {
        return Err(nothing_to_pocket(options, &layers, &entity_counts));
    }
    Ok(Drawing {
        declared_units,
        units,
        layers,
        entity_counts,
        elements,
        sources,
        extent,
        warnings,
        binary,
    })
}

/// The unit `$INSUNITS` declares, if any, and the one the drawing is read in (the options',
/// else the declared one, else millimetres); a warning when the options override the drawing.
fn drawing_units(
    doc: &dxf::Document,
    options: &ImportOptions,
    warnings: &mut Vec<ImportWarning>,
) -> (Option<Units>, Units) {
    let declared_units = doc
        .header_value("$INSUNITS")
        .and_then(|g| g.int())
        .and_then(Units::from_insunits);
    let units = options.units.or(declared_units).unwrap_or(Units::Millimeters);
    if let (Some(d), Some(o)) = (declared_units, options.units) {
        if d != o {
            warnings.push(ImportWarning::UnitsOverridden {
                declared: d,
                read_as: o,
            });
        }
    }
    (declared_units, units)
}

/// A warning for each layer asked for that the drawing does not have.
fn warn_of_missing_layers(layers: &[String], options: &ImportOptions, warnings: &mut Vec<ImportWarning>) {
    for w in options.layers.iter().flatten() {
        if !layers.iter().any(|l| l.eq_ignore_ascii_case(w)) {
            warnings.push(ImportWarning::LayerNotInDrawing {
                layer: w.clone(),
                layers: layers.to_vec(),
            });
        }
    }
}

/// Why a drawing whose model space has entities gives no element to pocket.
fn nothing_to_pocket(
    options: &ImportOptions,
    layers: &[String],
    entity_counts: &BTreeMap<String, usize>,
) -> ImportError {
    if options.layers.is_some() {
        ImportError::NothingOnLayers {
            layers: layers.to_vec(),
        }
    } else {
        ImportError::NoOutline {
            kinds: entity_counts.clone(),
        }
    }
}
