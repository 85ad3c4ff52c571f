//! Offsetting pockets and contours: the paper's raw offset → split → prune → stitch (Göktaş,
//! Güldaş, Dilipak 2011, §3–§6), one stage per file.
//!
//! In: a [`PreparedPocket`] and a distance d. Out: the loops of the pocket eroded by d
//! (`Vec<Contour>`: outer loops counter-clockwise, loops around islands clockwise) and, for
//! the deeper levels, the [`Sources`] that gave them pieces. Between the stages the data is a
//! `Vec<Piece>`: a segment with its end nodes and the element or joint it came from.
//!
//! - `raw.rs`: every element moved by d along its normal, joints closed by arcs or chords;
//! - `split.rs`: the raw pieces cut where they cross;
//! - `prune.rs`: a piece is thrown away when it comes nearer than d to the walls or lies
//!   outside the region — the stage that decides a piece is too close;
//! - `clip.rs`: a fallback that cuts provably invalid parts before splitting;
//! - `levels.rs`: many distances at once, on every core;
//! - `verify.rs`: an offset checked against its definition ([`verify_offset`]);
//! - stitching the kept pieces into loops is [`crate::geom::stitch`]'s.
//!
//! The contours must be as the importer makes them, each simple (not crossing
//! itself) and none crossing another. A contour that crosses itself, even in a loop a
//! micrometre across, has no well-defined inside there and its offset is not held to the
//! accuracy below.
//!
//! Accuracy: the loops are made of exact lines and arcs, and every point of them lies at
//! distance d from the profile within 1e-6 · max(d, 1 mm) (the property tests and the offset
//! fuzz target check it piece by piece). Raw offset curves that come within
//! [`crate::geom::TOUCH`] of each other are taken as meeting there, and pieces that far inside d as at
//! d: offsets of walls drawn exactly 2d apart coincide only to the precision of the drawing.
//! Where raw offset curves meet tangentially to within rounding, around elements a few
//! micrometres across or an arc of radius d, the split may find no crossing to cut at: a
//! joining chord coming less than [`crate::geom::JOIN_SLACK`] inside d stays in its run so that the
//! loop it closes is not lost, and stitching closes a loop wherever its walk comes back to a
//! node it passed, so that a detour through such a chord beyond the true meeting point is a
//! sliver loop of its own and goes.

mod clip;
mod levels;
mod prune;
mod raw;
mod split;
mod verify;

pub(crate) use levels::offsets_until_empty;
pub use verify::{loops_meet, verify_offset, OffsetFault, OFFSET_ACCURACY};

use crate::geom::Pocket;
use crate::geom::{
    stitch_kept, Contour, Piece, PieceGraph, Point, PreparedPocket, SegmentIndex, Source, Tolerance,
};
use prune::{cancel_opposites, prune, remove_dangling};
use split::{split, Nodes};
use thiserror::Error;

/// The most box comparisons one offset may make to find the pieces of its raw offset that
/// may cross, and the most crossings it may find: a few seconds of work and a few hundred
/// megabytes at most. Fine drawings stay far below (the 100 000-element benchmark profiles
/// make under 4 million comparisons and 150 000 crossings per level); a profile with
/// thousands of sharp features closer together than the distance makes Θ(n²) of both, and
/// is refused rather than hung on.
pub const MAX_BOX_TESTS: u64 = 60_000_000;

/// See [`MAX_BOX_TESTS`].
pub const MAX_CROSSINGS: usize = 2_000_000;

/// Crossings per raw piece beyond which an offset cuts the provably invalid parts of its raw
/// pieces before splitting them (the 100 000-element benchmark profiles make under one).
const QUADRATIC_CROSSINGS: usize = 4;

/// Distances measured for each raw piece, at most, in proving a level empty before
/// splitting it (see `clip::all_invalid`): a level with loops stops at its first valid
/// piece, usually the first.
const EMPTY_PROOF_WORK: u64 = 64;

/// The most segments the levels of one pocket may hold together (about a gigabyte, and a
/// program of tens of millions of moves): a drawing of 100 000 elements cleared with a
/// stepover of a tenth of a millimetre would need billions.
pub const MAX_LEVEL_SEGMENTS: usize = 20_000_000;

/// Why an offset cannot be computed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OffsetError {
    /// The work would grow with the square of the drawing: raw offset pieces overlapping by
    /// the thousand (sharp detail much finer than the distance), or many elements at nearly
    /// the same distance from the points tested (the distance within a hair of the largest
    /// circle the pocket holds).
    #[error(
        "offsetting by {distance} mm is too much work: {what}, near ({x:.4}, {y:.4}) mm; the \
         drawing has detail much finer than the distance there, or the distance is within a \
         hair of the widest place of the pocket; simplify the drawing or change the distance",
        x = near.x,
        y = near.y
    )]
    TooComplex {
        /// The offset distance, mm.
        distance: f64,
        /// What ran over its limit.
        what: String,
        /// A point of the raw offset where the work stopped, mm.
        near: Point,
    },
    /// The levels of a pocket would hold more segments than [`MAX_LEVEL_SEGMENTS`].
    #[error(
        "the levels up to {distance:.4} mm from the walls already hold {segments} segments, more \
         than the {} allowed: the tool path would have tens of millions of moves; raise the \
         stepover or simplify the drawing",
        MAX_LEVEL_SEGMENTS
    )]
    TooLarge {
        /// The level being added, mm from the walls.
        distance: f64,
        /// Segments held with it.
        segments: usize,
    },
}

/// Offsetting a prepared pocket: the offset stage's half of [`PreparedPocket`], whose
/// distance index and containment test it uses to judge pieces.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Pocket, PreparedPocket, Segment, Tolerance};
/// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 10.0))]);
/// let pocket = PreparedPocket::new(&Pocket { boundary: disc, islands: vec![] });
/// let tol = Tolerance::default();
/// let radii: Vec<f64> = (1..5).map(|k| pocket.offset(2.0 * k as f64, &tol).unwrap()[0].signed_area()).collect();
/// assert!((radii[3] - std::f64::consts::PI * 4.0).abs() < 1e-9);
/// ```
impl PreparedPocket {
    /// The radius of the largest circle inside the region, within a millionth of it (see
    /// [`largest_inscribed_radius`]).
    pub fn largest_inscribed_radius(&self, tol: &Tolerance) -> Result<f64, OffsetError> {
        // The boundary's box: the islands lie inside it.
        let b = self.bbox();
        let (mut lo, mut hi) = (0.0, 0.5 * b.width().min(b.height()) * (1.0 + 1e-9) + tol.eps);
        while hi - lo > 1e-6 * hi.max(1e-3) {
            let mid = 0.5 * (lo + hi);
            if self.offset(mid, tol)?.is_empty() {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Ok(lo)
    }

    /// The region eroded by `d` > 0 (grown by |d| for `d` < 0): loops counter-clockwise around
    /// material, clockwise around holes.
    pub fn offset(&self, d: f64, tol: &Tolerance) -> Result<Vec<Contour>, OffsetError> {
        if d >= 0.0 {
            Ok(self.offset_with_sources(d, tol, None)?.0)
        } else {
            // Growing the region is eroding everything else.
            let reversed: Vec<Contour> = self.contours().iter().map(Contour::reversed).collect();
            Ok(
                erode(&reversed, &|| self.walls(), &|p| !self.contains(p), -d, tol, None)?
                    .0
                    .iter()
                    .map(Contour::reversed)
                    .collect(),
            )
        }
    }

    /// The region eroded by `d` ≥ 0, like [`PreparedPocket::offset`], and the [`Sources`] of its loops.
    /// Given the sources of an erosion by a smaller distance, only those are offset: a point
    /// of the offset at d has a disc of radius d touching the walls at one foot, and the
    /// smaller disc tangent at the same foot shows the same element (or joint) gave the smaller
    /// offset a piece too. Many levels of a finely drawn pocket are much cheaper so.
    ///
    /// ```
    /// use pocketeer::geom::{Contour, Point, Tolerance};
    /// use pocketeer::geom::{Pocket, PreparedPocket};
    /// let p = Point::new;
    /// let l = Contour::polygon(&[p(0.0, 0.0), p(60.0, 0.0), p(60.0, 10.0), p(10.0, 10.0), p(10.0, 40.0), p(0.0, 40.0)]);
    /// let region = PreparedPocket::new(&Pocket { boundary: l, islands: vec![] });
    /// let tol = Tolerance::default();
    /// let (_, sources) = region.offset_with_sources(1.0, &tol, None).unwrap();
    /// let (fast, _) = region.offset_with_sources(3.0, &tol, Some(&sources)).unwrap();
    /// let full = region.offset(3.0, &tol).unwrap();
    /// assert!((fast[0].signed_area() - full[0].signed_area()).abs() < 1e-9);
    /// ```
    pub fn offset_with_sources(
        &self,
        d: f64,
        tol: &Tolerance,
        smaller: Option<&Sources>,
    ) -> Result<(Vec<Contour>, Sources), OffsetError> {
        self.with_indexes_built_beside(|| {
            erode(
                self.contours(),
                &|| self.walls(),
                &|p| self.contains(p),
                d.max(0.0),
                tol,
                smaller,
            )
        })
    }

    /// The region eroded by each of `distances` (increasing, positive), computed on every
    /// core, up to the first distance where nothing is left; deeper levels offset only the
    /// sources of a level already done (see [`PreparedPocket::offset_with_sources`]).
    ///
    /// ```
    /// use pocketeer::geom::{Arc, Contour, Point, Segment, Tolerance};
    /// use pocketeer::geom::{Pocket, PreparedPocket};
    /// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 10.0))]);
    /// let region = PreparedPocket::new(&Pocket { boundary: disc, islands: vec![] });
    /// let levels = region.offset_levels(&[2.0, 4.0, 6.0, 8.0, 10.0, 12.0], &Tolerance::default()).unwrap();
    /// assert_eq!(levels.len(), 4);
    /// assert!((levels[3][0].signed_area() - std::f64::consts::PI * 4.0).abs() < 1e-9);
    /// ```
    pub fn offset_levels(
        &self,
        distances: &[f64],
        tol: &Tolerance,
    ) -> Result<Vec<Vec<Contour>>, OffsetError> {
        Ok(offsets_until_empty(self, distances, tol)?
            .into_iter()
            .map(|(l, _)| l)
            .collect())
    }
}

/// Which elements and joints of a region gave pieces to one of its offsets.
#[derive(Debug, Clone, PartialEq)]
pub struct Sources {
    /// Indexed by [`Source::index`] (elements, then joints); `None`: all of them.
    used: Option<Vec<bool>>,
}

impl Sources {
    fn all() -> Sources {
        Sources { used: None }
    }

    /// True when `source` gave pieces (or when all did). The table holds the elements, then
    /// their joints.
    fn has(&self, source: Source) -> bool {
        self.used
            .as_ref()
            .is_none_or(|u| u.get(source.index(u.len() / 2)).copied().unwrap_or(true))
    }

    /// How many were used (of how many), for reports and tests.
    pub fn count(&self) -> Option<(usize, usize)> {
        self.used
            .as_ref()
            .map(|u| (u.iter().filter(|&&b| b).count(), u.len()))
    }
}

/// The loops of `pocket` eroded by `d` > 0: outer loops counter-clockwise, loops around
/// islands clockwise, made of exact lines and arcs. Empty when nothing of the pocket is
/// farther than `d` from its walls and islands.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Line, Point, Segment, Tolerance};
/// use pocketeer::geom::Pocket;
/// use pocketeer::offset::offset_pocket;
/// let p = Point::new;
/// let c = [p(0.0, 0.0), p(100.0, 0.0), p(100.0, 60.0), p(0.0, 60.0)];
/// let boundary = Contour::new((0..4).map(|k| Segment::Line(Line::new(c[k], c[(k + 1) % 4]))).collect());
/// let island = Contour::new(vec![Segment::Arc(Arc::new(p(50.0, 30.0), 10.0, 0.0, -std::f64::consts::TAU))]);
/// let loops = offset_pocket(&Pocket { boundary, islands: vec![island] }, 5.0, &Tolerance::default()).unwrap();
/// let area: f64 = loops.iter().map(|l| l.signed_area()).sum();
/// assert_eq!(loops.len(), 2);
/// assert!((area - (90.0 * 50.0 - std::f64::consts::PI * 15.0 * 15.0)).abs() < 1e-9);
/// ```
///
/// A negative `d` offsets outward: the pocket grows by |d| and its islands shrink. To offset
/// one pocket by many distances, prepare it once as a [`PreparedPocket`].
pub fn offset_pocket(pocket: &Pocket, d: f64, tol: &Tolerance) -> Result<Vec<Contour>, OffsetError> {
    PreparedPocket::new(pocket).offset(d, tol)
}

/// The radius of the largest circle inside `pocket` (clear of its walls and islands), within a
/// millionth of it: the largest distance whose offset is not empty, found by halving the
/// interval between 0 and half the pocket's narrower side. A tool of a larger radius fits
/// nowhere; an offset by a larger distance has no loop.
///
/// ```
/// use pocketeer::geom::{Contour, Point, Tolerance};
/// use pocketeer::geom::Pocket;
/// use pocketeer::offset::largest_inscribed_radius;
/// let p = Point::new;
/// let boundary = Contour::polygon(&[p(0.0, 0.0), p(100.0, 0.0), p(100.0, 30.0), p(0.0, 30.0)]);
/// let r = largest_inscribed_radius(&Pocket { boundary, islands: vec![] }, &Tolerance::default()).unwrap();
/// assert!((r - 15.0).abs() < 1e-4);
/// ```
pub fn largest_inscribed_radius(pocket: &Pocket, tol: &Tolerance) -> Result<f64, OffsetError> {
    PreparedPocket::new(pocket).largest_inscribed_radius(tol)
}

/// The offset of one closed contour by `d`: inward for `d` > 0 (the contour's inside eroded),
/// outward for `d` < 0 (its inside dilated). Loops are counter-clockwise around material,
/// clockwise around holes.
pub fn offset_contour(contour: &Contour, d: f64, tol: &Tolerance) -> Result<Vec<Contour>, OffsetError> {
    PreparedPocket::from_loops(vec![contour.clone().oriented(true)]).offset(d, tol)
}

/// The boundary of the region on the left of `contours` (where `inside` holds, walled by the
/// index `walls` gives, asked for only once the raw offset is split) eroded by `d`, and the
/// sources of its pieces; only the sources in `smaller` are offset when given.
fn erode<'w>(
    contours: &[Contour],
    walls: &(dyn Fn() -> &'w SegmentIndex + Sync),
    inside: &dyn Fn(Point) -> bool,
    d: f64,
    tol: &Tolerance,
    smaller: Option<&Sources>,
) -> Result<(Vec<Contour>, Sources), OffsetError> {
    if !(d > 0.0 && d.is_finite()) {
        return Ok((contours.to_vec(), Sources::all()));
    }
    let elements: usize = contours.iter().map(|c| c.segments.len()).sum();
    let mut raw: Vec<Piece> = Vec::new();
    let (mut next_node, mut base) = (0, 0);
    let wanted = |source: Source| smaller.is_none_or(|s| s.has(source));
    for c in contours {
        let (pieces, next) = raw::raw_offset(c, d, tol, next_node, base, &wanted);
        if raw.is_empty() {
            raw = pieces;
        } else {
            raw.extend(pieces);
        }
        next_node = next;
        base += c.segments.len();
    }
    // A level beyond the deepest point of the region: halving each raw piece shows it too
    // near the walls everywhere. Asked only of a deeper level (the walls are indexed by then;
    // the first level of a large region indexes them beside its raw offset and split).
    let slack = prune::slack(d, tol);
    if smaller.is_some() && clip::all_invalid(&raw, walls(), d - slack, EMPTY_PROOF_WORK * raw.len() as u64) {
        return Ok((
            Vec::new(),
            Sources {
                used: Some(vec![false; 2 * elements]),
            },
        ));
    }
    let mut nodes = Nodes::new(next_node);
    let budget = (MAX_BOX_TESTS, MAX_CROSSINGS);
    // A raw offset crossing itself more than a few times per piece is going quadratic (sharp
    // detail much finer than d, or d near the largest circle of a pocket of many elements):
    // cutting its provably invalid parts first is cheaper than splitting and judging them.
    let first_budget = (
        MAX_BOX_TESTS,
        MAX_CROSSINGS.min(QUADRATIC_CROSSINGS * raw.len() + 100_000),
    );
    let pieces = match split(&raw, &mut nodes, tol, first_budget) {
        Ok(pieces) => pieces,
        Err(first) => {
            // Too many crossings: most lie in parts of pieces that are invalid anyway.
            let too_complex = |pieces: &[Piece], o: split::Overrun| OffsetError::TooComplex {
                distance: d,
                what: format!(
                    "the {} pieces of its raw offset took {} box comparisons and crossed {} times \
                     (limits {MAX_BOX_TESTS} and {MAX_CROSSINGS})",
                    pieces.len(),
                    o.tests,
                    o.crossings
                ),
                near: pieces[o.at].segment.start(),
            };
            let clipped = clip::clip_invalid(&raw, walls(), d, slack, &mut nodes)
                .ok_or_else(|| too_complex(&raw, first))?;
            split(&clipped, &mut nodes, tol, budget).map_err(|o| too_complex(&clipped, o))?
        }
    };
    // The raw offset is cut into `pieces`: its memory goes back before the judging and the
    // stitching, the peak of a large offset.
    drop(raw);
    // Canonical node ids; pieces shorter than rounding go (their ends are one node).
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .filter(|p| p.segment.length() > tol.eps)
        .map(|p| Piece {
            start: nodes.find(p.start),
            end: nodes.find(p.end),
            ..p
        })
        .collect();
    let graph = PieceGraph::new(&pieces);
    // Joining lines: the joint at the end of element k is the source `Joint(k)`. (When
    // growing a region the contours are the profile's reversed, so the element this names is
    // not the profile's element k: a hint that misses, and costs one measure.)
    let join_at = |p: &Piece| match (p.source, p.segment) {
        (Source::Joint(k), crate::geom::Segment::Line(_)) => Some(k as usize),
        _ => None,
    };
    let mut kept = prune(&pieces, &graph, walls(), inside, &join_at, d, tol).map_err(|near| {
        OffsetError::TooComplex {
            distance: d,
            what: format!(
                "judging its pieces would measure more than {} distances to the walls",
                prune::MAX_MEASURES
            ),
            near,
        }
    })?;
    cancel_opposites(&pieces, &graph, &mut kept, tol);
    remove_dangling(&pieces, &graph, &mut kept);
    let mut used = vec![false; 2 * elements];
    for (p, _) in pieces.iter().zip(&kept).filter(|(_, &k)| k) {
        if let Some(u) = used.get_mut(p.source.index(elements)) {
            *u = true;
        }
    }
    let (loops, _lost) = stitch_kept(&pieces, &graph, &kept);
    let loops = loops
        .into_iter()
        // A loop whose mean width (twice its area over its length) is within the distance
        // slack is a sliver of rounding where offset curves touch, no region.
        .filter(|l| l.signed_area().abs() > prune::slack(d, tol) * l.length())
        .collect();
    Ok((loops, Sources { used: Some(used) }))
}
