//! Typed errors of the importer, each naming where in the file and what is wrong.

use crate::geom::Point;
use std::fmt;
use thiserror::Error;

/// A place in a DXF file: a line of an ASCII file or a byte offset of a binary one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pos {
    /// 1-based line number in an ASCII DXF.
    Line(usize),
    /// Byte offset in a binary DXF.
    Byte(usize),
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Pos::Line(n) => write!(f, "line {n}"),
            Pos::Byte(n) => write!(f, "byte {n}"),
        }
    }
}

/// Which entity of the drawing something is about.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EntityRef {
    /// Entity type, as in the file (`LINE`, `LWPOLYLINE`, ...).
    pub kind: String,
    /// The entity's handle (group 5), when the file has one.
    pub handle: Option<String>,
    /// Layer name.
    pub layer: String,
    /// Where the entity starts in the file.
    pub pos: Pos,
}

impl fmt::Display for EntityRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.kind)?;
        if let Some(h) = &self.handle {
            write!(f, " (handle {h})")?;
        }
        write!(f, " on layer '{}' at {}", self.layer, self.pos)
    }
}

/// A number as a reader wants it: plain when moderate, in exponent form when huge.
pub fn fmt_number(x: f64) -> String {
    if x.is_finite() && x.abs() < 1e7 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `n` things with the right plural: `1 element`, `3 elements`.
///
/// ```
/// use pocketeer::import::error::fmt_count;
/// assert_eq!(fmt_count(1, "pass", "passes"), "1 pass");
/// assert_eq!(fmt_count(0, "element", "elements"), "0 elements");
/// ```
pub fn fmt_count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `3 TEXT, 1 HATCH`.
fn fmt_kinds(kinds: &std::collections::BTreeMap<String, usize>) -> String {
    let listed: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
    listed.join(", ")
}

/// `a to b, c to d` for the ends listed, and how many chains more there are.
fn free_ends(ends: &[(Point, Point)], open: usize) -> String {
    let listed: Vec<String> = ends.iter().map(|(a, b)| format!("{a} to {b}")).collect();
    let more = open.saturating_sub(ends.len());
    if more > 0 {
        format!("{} and {more} more", listed.join(", "))
    } else {
        listed.join(", ")
    }
}

/// Why a drawing could not be imported.
#[derive(Debug, Error)]
pub enum ImportError {
    /// The bytes are not a DXF file at all.
    #[error("not a DXF file: {0}")]
    NotDxf(String),
    /// The group-code structure is broken.
    #[error("{pos}: {what}")]
    Syntax {
        /// Where.
        pos: Pos,
        /// What is wrong.
        what: String,
    },
    /// The file stops in the middle of the drawing.
    #[error("the file ends at {pos} inside the {section} section: it is truncated")]
    Truncated {
        /// The last position read.
        pos: Pos,
        /// The section that was being read.
        section: String,
    },
    /// One entity cannot be used.
    #[error("{entity}: {what}")]
    BadEntity {
        /// Which entity.
        entity: EntityRef,
        /// What is wrong.
        what: String,
    },
    /// A block that inserts itself, directly or through others.
    #[error("block '{name}' inserts itself ({chain}) at {pos}")]
    RecursiveBlock {
        /// The block.
        name: String,
        /// The chain of insertions.
        chain: String,
        /// Where the INSERT that closes the cycle is.
        pos: Pos,
    },
    /// Expanding blocks would produce more elements than any real drawing has.
    #[error("block insertions expand to more than {limit} elements (at {pos}): refusing to continue")]
    TooLarge {
        /// The limit.
        limit: usize,
        /// The INSERT being expanded.
        pos: Pos,
    },
    /// Model space holds nothing.
    #[error("model space is empty: the drawing has nothing to pocket")]
    EmptyModelSpace,
    /// Nothing on the layers selected draws an outline.
    #[error("no lines, arcs, circles, polylines, splines or ellipses on the selected layers (layers: {})", .layers.join(", "))]
    NothingOnLayers {
        /// Every layer of the drawing.
        layers: Vec<String>,
    },
    /// Model space holds entities, none of which draws an outline.
    #[error("model space holds {} but no lines, arcs, circles, polylines, splines or ellipses", fmt_kinds(.kinds))]
    NoOutline {
        /// How many entities of each kind there are.
        kinds: std::collections::BTreeMap<String, usize>,
    },
    /// No closed contour could be formed: the open chains, and the free ends of the first few.
    #[error("no closed contour: {}, free ends {}", fmt_count(*.open, "open chain", "open chains"), free_ends(.ends, *.open))]
    NoClosedContour {
        /// How many open chains the drawing has.
        open: usize,
        /// The free ends of the first five.
        ends: Vec<(Point, Point)>,
        /// The narrowest gap between free ends.
        gap: Option<crate::import::NearestGap>,
    },
    /// An open chain that would close across a small gap of its own surrounds closed contours
    /// or lies inside one: most likely an outline that does not close.
    #[error(
        "the open chain of {} on layer '{layer}' (free ends at {} and {}) {}: it looks like {} outline that does not close",
        fmt_count(*.elements, "element", "elements"), .start, .end,
        if *.surrounded > 0 { format!("surrounds {}", fmt_count(*.surrounded, "closed contour", "closed contours")) }
        else { "lies inside a closed contour".to_owned() },
        if *.surrounded > 0 { "a pocket" } else { "an island" },
    )]
    OpenOutline {
        /// Layer of the chain.
        layer: String,
        /// Number of elements in the chain.
        elements: usize,
        /// First free end.
        start: Point,
        /// Last free end.
        end: Point,
        /// How many closed contours it would enclose, closed across its gap (0: it lies inside
        /// one).
        surrounded: usize,
        /// The gap to the nearest other free end.
        gap: Option<crate::import::NearestGap>,
    },
    /// A contour crosses or touches itself.
    #[error("the contour on layer '{layer}' crosses or touches itself at {}", .point)]
    SelfCrossing {
        /// Layer of the contour.
        layer: String,
        /// The crossing point.
        point: Point,
    },
}
