//! Filling a contour that crosses or touches itself: cut at every place it meets itself, the
//! pieces with filled area on exactly one side (by the winding number beside them, read by a
//! [`FillRule`]) are stitched into simple loops, counter-clockwise round filled area and
//! clockwise round holes. A bow-tie becomes two triangles touching at a point; a loop that
//! winds round twice leaves a hole under the even-odd rule and none under the non-zero rule.

use super::nesting::{boundary_pieces, stitch};
use super::self_crossing::crossings;
use crate::geom::{Contour, Intersection, Point, Tolerance, WindingIndex};
use std::collections::HashMap;

/// Which points a contour that crosses itself encloses, by its winding number round them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillRule {
    /// Odd winding numbers are inside: crossing the outline always goes from inside to outside
    /// or back. What most drawing and laser programs do.
    #[default]
    EvenOdd,
    /// Every non-zero winding number is inside: a loop wound round twice is still filled.
    NonZero,
}

impl FillRule {
    /// Whether a point with winding number `w` is inside.
    ///
    /// ```
    /// use pocketeer::import::FillRule;
    /// assert!(!FillRule::EvenOdd.fills(2) && FillRule::NonZero.fills(2));
    /// assert!(FillRule::EvenOdd.fills(-1) && !FillRule::NonZero.fills(0));
    /// ```
    pub fn fills(self, w: i32) -> bool {
        match self {
            FillRule::EvenOdd => w % 2 != 0,
            FillRule::NonZero => w != 0,
        }
    }
}

/// The simple loops bounding what `contour` fills under `rule`, and the points where it meets
/// itself. Loops no wider than rounding are left out.
pub(super) fn fill(contour: &Contour, rule: FillRule, tol: &Tolerance) -> (Vec<Contour>, Vec<Point>) {
    let mut cuts: HashMap<usize, Vec<(f64, Point)>> = HashMap::new();
    let mut points = Vec::new();
    let segs = &contour.segments;
    for (i, j, h) in crossings(contour, tol) {
        match h {
            Intersection::Point { point, ta, tb } => {
                cuts.entry(i).or_default().push((ta, point));
                cuts.entry(j).or_default().push((tb, point));
                points.push(point);
            }
            Intersection::Overlap { a, b } => {
                for (t, u) in [(a.0, b.0), (a.1, b.1)] {
                    let p = segs[i].point_at(t);
                    cuts.entry(i).or_default().push((t, p));
                    cuts.entry(j).or_default().push((u, p));
                }
                points.push(segs[i].point_at(0.5 * (a.0 + a.1)));
            }
        }
    }
    let index = WindingIndex::new(segs);
    let filled = |p: Point| rule.fills(index.winding(segs, p));
    let at_segment = |_: usize, k: usize| cuts.get(&k).map_or(&[][..], Vec::as_slice);
    let pieces = boundary_pieces(&[contour], &at_segment, &filled, tol);
    let (loops, _) = stitch(pieces, tol);
    let loops = loops
        .into_iter()
        .filter(|l| {
            let b = l.bbox();
            b.width().min(b.height()) > tol.rounding()
        })
        .collect();
    (loops, dedup_points(points, tol))
}

/// The points, each place once (a crossing at a joint is found by the segments on both sides).
fn dedup_points(points: Vec<Point>, tol: &Tolerance) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::new();
    for p in points {
        if !out.iter().rev().take(8).any(|q| q.distance(p) <= tol.crossing()) {
            out.push(p);
        }
    }
    out
}
