//! Offsetting pockets and contours: the paper's raw offset → split → prune → stitch
//! (`../shared/paper/summary.md` §3–§6), one stage per file.

mod prune;
mod raw;
mod split;

use crate::geom::{stitch, Contour, Piece, Point, Tolerance, WindingIndex};
use crate::import::Pocket;
use prune::{cancel_opposites, prune, remove_dangling, Profile};
use split::{split, Nodes};

/// The loops of `pocket` eroded by `d` > 0: outer loops counter-clockwise, loops around
/// islands clockwise, made of exact lines and arcs. Empty when nothing of the pocket is
/// farther than `d` from its walls and islands.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Line, Point, Segment, Tolerance};
/// use pocketeer::import::Pocket;
/// use pocketeer::offset::offset_pocket;
/// let p = Point::new;
/// let c = [p(0.0, 0.0), p(100.0, 0.0), p(100.0, 60.0), p(0.0, 60.0)];
/// let boundary = Contour::new((0..4).map(|k| Segment::Line(Line::new(c[k], c[(k + 1) % 4]))).collect());
/// let island = Contour::new(vec![Segment::Arc(Arc::new(p(50.0, 30.0), 10.0, 0.0, -std::f64::consts::TAU))]);
/// let loops = offset_pocket(&Pocket { boundary, islands: vec![island] }, 5.0, &Tolerance::default());
/// let area: f64 = loops.iter().map(|l| l.signed_area()).sum();
/// assert_eq!(loops.len(), 2);
/// assert!((area - (90.0 * 50.0 - std::f64::consts::PI * 15.0 * 15.0)).abs() < 1e-9);
/// ```
///
/// A negative `d` offsets outward: the pocket grows by |d| and its islands shrink.
pub fn offset_pocket(pocket: &Pocket, d: f64, tol: &Tolerance) -> Vec<Contour> {
    let mut contours = vec![pocket.boundary.clone()];
    contours.extend(pocket.islands.iter().cloned());
    let within = region_test(&contours);
    let inside = |p: Point| within(p);
    if d >= 0.0 {
        erode(&contours, &inside, d, tol)
    } else {
        // Growing the pocket is eroding everything else.
        let reversed: Vec<Contour> = contours.iter().map(Contour::reversed).collect();
        let outside = |p: Point| !inside(p);
        erode(&reversed, &outside, -d, tol)
            .iter()
            .map(Contour::reversed)
            .collect()
    }
}

/// The offset of one closed contour by `d`: inward for `d` > 0 (the contour's inside eroded),
/// outward for `d` < 0 (its inside dilated). Loops are counter-clockwise around material,
/// clockwise around holes.
pub fn offset_contour(contour: &Contour, d: f64, tol: &Tolerance) -> Vec<Contour> {
    let ccw = if contour.is_ccw() {
        contour.clone()
    } else {
        contour.reversed()
    };
    let within = region_test(std::slice::from_ref(&ccw));
    if d >= 0.0 {
        let inside = |p: Point| within(p);
        erode(std::slice::from_ref(&ccw), &inside, d, tol)
    } else {
        // Dilating the inside is eroding the outside: offset the reversed contour, then turn the
        // loops so that they run counter-clockwise around the dilated shape.
        let outside = |p: Point| !within(p);
        erode(&[ccw.reversed()], &outside, -d, tol)
            .iter()
            .map(Contour::reversed)
            .collect()
    }
}

/// Point-in-region test for a region whose contours have it on their left (an outer boundary
/// counter-clockwise, islands clockwise): the winding numbers add up to 1 inside. Each contour
/// gets a strip index, so a test costs a few segments, not all of them.
fn region_test(contours: &[Contour]) -> impl Fn(Point) -> bool + '_ {
    let indexes: Vec<WindingIndex> = contours.iter().map(|c| WindingIndex::new(&c.segments)).collect();
    move |p: Point| {
        contours
            .iter()
            .zip(&indexes)
            .map(|(c, i)| i.winding(&c.segments, p))
            .sum::<i32>()
            > 0
    }
}

/// The boundary of the region on the left of `contours` (where `inside` holds) eroded by `d`.
fn erode(contours: &[Contour], inside: &dyn Fn(Point) -> bool, d: f64, tol: &Tolerance) -> Vec<Contour> {
    if !(d > 0.0 && d.is_finite()) {
        return contours.to_vec();
    }
    let mut raw: Vec<Piece> = Vec::new();
    let mut next_node = 0;
    for c in contours {
        let (pieces, next) = raw::raw_offset(c, d, tol, next_node);
        raw.extend(pieces);
        next_node = next;
    }
    let mut nodes = Nodes::new(next_node);
    let pieces = split(&raw, &mut nodes, tol);
    let profile = Profile::new(contours);
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .map(|p| Piece {
            start: nodes.find(p.start),
            end: nodes.find(p.end),
            ..p
        })
        .collect();
    let kept = prune(pieces, &profile, inside, d, tol);
    let kept = remove_dangling(cancel_opposites(kept, tol));
    let (loops, _lost) = stitch(&kept);
    loops
        .into_iter()
        .filter(|l| l.signed_area().abs() > tol.eps * l.length())
        .collect()
}
