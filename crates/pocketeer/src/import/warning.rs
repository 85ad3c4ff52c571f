//! What the importer met, repaired or left out: typed remarks with their numbers and places,
//! which a front end formats (their `Display` is a one-line message).

use super::error::{fmt_count, fmt_number, EntityRef};
use super::{FillRule, Units};
use crate::geom::Point;
use thiserror::Error;

/// One remark of the importer. The drawing was read; this says what was changed or ignored
/// on the way, and where.
///
/// ```
/// use pocketeer::geom::Point;
/// use pocketeer::import::ImportWarning;
/// let w = ImportWarning::GapsClosed { count: 3, largest: 0.0004, at: Point::new(10.0, 5.0) };
/// assert_eq!(w.to_string(), "3 gaps between end points closed, the largest 0.000400 mm at (10.0000, 5.0000)");
/// ```
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ImportWarning {
    /// A section other than ENTITIES or BLOCKS runs to the end of the file.
    #[error("the {section} section has no end; the file may be truncated")]
    SectionNotEnded {
        /// The section's name.
        section: String,
    },
    /// The file ends without an EOF marker.
    #[error("the file has no EOF marker")]
    NoEofMarker,
    /// The drawing declares one unit and was read in another, as asked.
    #[error("the drawing declares {}; read in {} as asked", .declared.name(), .read_as.name())]
    UnitsOverridden {
        /// The unit the header declares.
        declared: Units,
        /// The unit the drawing was read in.
        read_as: Units,
    },
    /// A layer asked for is not in the drawing.
    #[error("layer '{layer}' is not in the drawing (layers: {})", .layers.join(", "))]
    LayerNotInDrawing {
        /// The layer asked for.
        layer: String,
        /// Every layer the drawing has.
        layers: Vec<String>,
    },
    /// An INSERT names a block the file does not define.
    #[error("{insert}: block '{name}' is not defined; ignored")]
    UndefinedBlock {
        /// The INSERT.
        insert: EntityRef,
        /// The block's name.
        name: String,
    },
    /// An INSERT scales its block to nothing (or to an infinite size).
    #[error("{insert}: block '{name}' inserted with scale {} × {}: nothing to draw; ignored",
        fmt_number(.scale.0), fmt_number(.scale.1))]
    BlockScaledToNothing {
        /// The INSERT.
        insert: EntityRef,
        /// The block's name.
        name: String,
        /// Its x and y scale.
        scale: (f64, f64),
    },
    /// Elements drawn twice (or lying on another) were dropped.
    #[error("{} dropped: drawn twice, cut once", fmt_count(*.count, "duplicate element", "duplicate elements"))]
    DuplicatesDropped {
        /// How many.
        count: usize,
    },
    /// Elements with no length were dropped.
    #[error("{} dropped", fmt_count(*.count, "zero-length element", "zero-length elements"))]
    ZeroLengthDropped {
        /// How many.
        count: usize,
    },
    /// End points that did not coincide exactly were moved to meet.
    #[error("{} between end points closed, the largest {largest:.6} mm at {at}",
        fmt_count(*.count, "gap", "gaps"))]
    GapsClosed {
        /// Nodes where ends were moved to meet.
        count: usize,
        /// The largest gap closed, mm (each end moved by half of it).
        largest: f64,
        /// Where that was.
        at: Point,
    },
    /// A gap between two free ends, each the other's nearest, closed with a straight segment.
    #[error("gap of {length:.4} mm between free ends at {from} and {to} closed with a straight segment")]
    GapBridged {
        /// The gap's width, mm.
        length: f64,
        /// One end.
        from: Point,
        /// The other end.
        to: Point,
    },
    /// A stroke that bounds nothing, from a free end or an outline to where it meets an
    /// outline (a construction line, a leader), was left out, so that the outline does not
    /// branch there.
    #[error("a stroke of {} from {from} to {to}, where it meets an outline, ignored: it bounds nothing",
        fmt_count(*.elements, "element", "elements"))]
    StrokeRemoved {
        /// Its elements.
        elements: usize,
        /// Its other end: free, or on another outline.
        from: Point,
        /// Where it meets an outline.
        to: Point,
    },
    /// Strokes branch (three, five, … ends meet at a point): the faces they enclose were taken
    /// as contours.
    #[error("the outline branches at {at}{}: the {} it encloses taken as contours",
        if *.branches > 1 { format!(" and {} more places", .branches - 1) } else { String::new() },
        fmt_count(*.faces, "face", "faces"))]
    BranchingOutline {
        /// The first place where it branches.
        at: Point,
        /// How many places it branches at.
        branches: usize,
        /// How many faces it encloses.
        faces: usize,
    },
    /// A closed polyline drawn there and back again: a line, no outline.
    #[error("a closed polyline of {} at {at} encloses no area; ignored",
        fmt_count(*.elements, "element", "elements"))]
    NoArea {
        /// Its elements.
        elements: usize,
        /// Its first point.
        at: Point,
    },
    /// An odd number (three or more) of elements end at one point: one is left open.
    #[error("{ends} elements end at {at}: one of them is left open")]
    OddJunction {
        /// How many end there.
        ends: usize,
        /// The point.
        at: Point,
    },
    /// A contour crossed itself in a loop too thin to matter, and the loop was cut off.
    #[error("a sliver loop where the contour on layer '{layer}' crosses itself at {at} removed")]
    SliverLoopRemoved {
        /// The contour's layer.
        layer: String,
        /// Where it crosses itself.
        at: Point,
    },
    /// A contour crossing or touching itself was filled by a rule into simple loops.
    #[error("the contour on layer '{layer}' crosses or touches itself {}: filled by the {} rule into {}",
        fmt_places(.at), match .rule { FillRule::EvenOdd => "even-odd", FillRule::NonZero => "non-zero" },
        fmt_count(*.loops, "loop", "loops"))]
    SelfCrossingFilled {
        /// The contour's layer.
        layer: String,
        /// The rule used.
        rule: FillRule,
        /// How many simple loops it became.
        loops: usize,
        /// Every place where it meets itself.
        at: Vec<Point>,
    },
    /// Two contours meet: overlapping ones at the same nesting depth are merged, a contour
    /// crossing the wall of the pocket around it cuts the wall back.
    #[error("contours on layers '{}' and '{}' meet at {at}; they {}", .layers[0], .layers[1],
        if *.merged { "overlap: merged" } else { "cross: cut back" })]
    ContoursMeet {
        /// The two contours' layers.
        layers: [String; 2],
        /// A point where they meet.
        at: Point,
        /// True when merged, false when the outer one was cut back.
        merged: bool,
    },
    /// Pieces of crossing contours that could not be joined into loops.
    #[error("{} of crossing contours could not be joined into loops and were left out",
        fmt_count(*.pieces, "piece", "pieces"))]
    PiecesLost {
        /// How many.
        pieces: usize,
    },
    /// A clockwise loop that no pocket encloses.
    #[error("an island at {at} lies in no pocket; ignored")]
    IslandInNoPocket {
        /// Its first point.
        at: Point,
    },
}

impl ImportWarning {
    /// A short name of the kind of remark, for scripts: `gap-bridged`, `self-crossing-filled`, …
    ///
    /// ```
    /// use pocketeer::geom::Point;
    /// use pocketeer::import::ImportWarning;
    /// let w = ImportWarning::GapBridged { length: 0.02, from: Point::new(0.0, 0.0), to: Point::new(0.0, 0.02) };
    /// assert_eq!(w.kind(), "gap-bridged");
    /// assert!(w.is_repair());
    /// assert_eq!(w.places().len(), 2);
    /// ```
    pub fn kind(&self) -> &'static str {
        match self {
            ImportWarning::SectionNotEnded { .. } => "section-not-ended",
            ImportWarning::NoEofMarker => "no-eof-marker",
            ImportWarning::UnitsOverridden { .. } => "units-overridden",
            ImportWarning::LayerNotInDrawing { .. } => "layer-not-in-drawing",
            ImportWarning::UndefinedBlock { .. } => "undefined-block",
            ImportWarning::BlockScaledToNothing { .. } => "block-scaled-to-nothing",
            ImportWarning::DuplicatesDropped { .. } => "duplicates-dropped",
            ImportWarning::ZeroLengthDropped { .. } => "zero-length-dropped",
            ImportWarning::GapsClosed { .. } => "gaps-closed",
            ImportWarning::GapBridged { .. } => "gap-bridged",
            ImportWarning::StrokeRemoved { .. } => "stroke-removed",
            ImportWarning::BranchingOutline { .. } => "branching-outline",
            ImportWarning::NoArea { .. } => "no-area",
            ImportWarning::OddJunction { .. } => "odd-junction",
            ImportWarning::SliverLoopRemoved { .. } => "sliver-loop-removed",
            ImportWarning::SelfCrossingFilled { .. } => "self-crossing-filled",
            ImportWarning::ContoursMeet { .. } => "contours-meet",
            ImportWarning::PiecesLost { .. } => "pieces-lost",
            ImportWarning::IslandInNoPocket { .. } => "island-in-no-pocket",
        }
    }

    /// True when the remark is a repair: the outlines pocketed differ from the elements as
    /// drawn (ends moved or joined, elements dropped or added, crossings filled, contours
    /// merged). A drawing imported without a repair is pocketed exactly as drawn.
    pub fn is_repair(&self) -> bool {
        !matches!(
            self,
            ImportWarning::SectionNotEnded { .. }
                | ImportWarning::NoEofMarker
                | ImportWarning::UnitsOverridden { .. }
                | ImportWarning::LayerNotInDrawing { .. }
                | ImportWarning::UndefinedBlock { .. }
                | ImportWarning::BlockScaledToNothing { .. }
        )
    }

    /// The places the remark is about, in mm (none for a remark about the whole file).
    pub fn places(&self) -> Vec<Point> {
        match self {
            ImportWarning::GapsClosed { at, .. }
            | ImportWarning::BranchingOutline { at, .. }
            | ImportWarning::NoArea { at, .. }
            | ImportWarning::OddJunction { at, .. }
            | ImportWarning::SliverLoopRemoved { at, .. }
            | ImportWarning::ContoursMeet { at, .. }
            | ImportWarning::IslandInNoPocket { at } => vec![*at],
            ImportWarning::GapBridged { from, to, .. } | ImportWarning::StrokeRemoved { from, to, .. } => {
                vec![*from, *to]
            }
            ImportWarning::SelfCrossingFilled { at, .. } => at.clone(),
            _ => Vec::new(),
        }
    }
}

/// "at (x, y)", or "at N places: (x, y), (x, y), … and N more".
fn fmt_places(at: &[Point]) -> String {
    match at {
        [] => "somewhere".to_owned(),
        [p] => format!("at {p}"),
        _ => {
            let shown: Vec<String> = at.iter().take(3).map(ToString::to_string).collect();
            let more = if at.len() > 3 {
                format!(" and {} more", at.len() - 3)
            } else {
                String::new()
            };
            format!("at {} places: {}{more}", at.len(), shown.join(", "))
        }
    }
}
