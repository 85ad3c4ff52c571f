//! Rest machining: the pockets a smaller tool still has to clear after larger tools cleared
//! a pocket, from the geometry of their planned cuts, exactly (lines and arcs, no grid).
//!
//! A leftover-free plan of a tool of radius r₁ in a pocket P sweeps exactly P opened by the
//! disc of r₁: E₁ ⊕ D(r₁), where E₁ = P ⊖ D(r₁) is the region its centre covers (the plan's
//! loops fill it, its outermost loop is E₁'s boundary). A tool of radius r < r₁ whose centre
//! lies in U = E₁ ⊕ D(r₁ − r) meets nothing the larger tool left, since D(r) ⊕ D(r₁ − r) =
//! D(r₁). So its centre has work only in R = (P ⊖ D(r)) \ U, and every material point it can
//! reach that the larger tool did not is within r of R. The small tool clears the pockets
//! R ⊕ D(r): they lie inside P (R ⊂ P ⊖ D(r)), are open for the disc of r (their own
//! erosion by r gives R back), and the same offset engine clears them leftover-free.
//!
//! Every set is made by the offset engine (erosions and dilations of pockets), and the one
//! difference R by cutting the two sets of loops where they cross and keeping the pieces with
//! R on one side ([`crate::import::nesting`]'s mechanism for overlapping contours). U is made
//! [`GROW`] wider, so that along straight walls, where U's and P ⊖ D(r)'s boundaries coincide,
//! the difference has no sliver: that leaves at most that much more material uncut.

use crate::geom::{
    box_pairs, intersect, Aabb, Contour, Intersection, Pocket, Point, Tolerance, WindingIndex,
};
use crate::offset::{offset_pocket, OffsetError};
use std::collections::HashMap;

/// How much wider U is made than its exact width, mm (see the module's documentation).
pub const GROW: f64 = 1e-3;

/// Pieces of R narrower than this on average (twice their area over their perimeter), mm,
/// are dropped: rounding, not material.
const SLIVER: f64 = 2e-3;

/// The pockets a tool of radius `r` must clear in `pocket` after tools of radii `earlier`
/// cleared it leftover-free (see the module's documentation); none when an earlier tool was
/// no larger.
///
/// ```
/// use pocketeer::clear::rest::rest_pockets;
/// use pocketeer::geom::{Contour, Point, Pocket, Tolerance};
/// let p = Point::new;
/// let square = Contour::polygon(&[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 30.0), p(0.0, 30.0)]);
/// let pocket = Pocket { boundary: square, islands: vec![] };
/// // After a 6 mm tool, a 2 mm one has the four corners to clear.
/// let rest = rest_pockets(&pocket, 1.0, &[3.0], &Tolerance::default()).unwrap();
/// assert_eq!(rest.len(), 4);
/// let area: f64 = rest.iter().map(|q| q.area()).sum();
/// assert!(area < 4.0 * 5.0 * 5.0, "{area}");
/// ```
pub fn rest_pockets(
    pocket: &Pocket,
    r: f64,
    earlier: &[f64],
    tol: &Tolerance,
) -> Result<Vec<Pocket>, OffsetError> {
    Ok(rest_pockets_exact(pocket, r, earlier, tol)?.0)
}

/// [`rest_pockets`], and whether they are exact (false: the difference could not be made, and
/// they are the whole pocket the tool reaches).
pub fn rest_pockets_exact(
    pocket: &Pocket,
    r: f64,
    earlier: &[f64],
    tol: &Tolerance,
) -> Result<(Vec<Pocket>, bool), OffsetError> {
    let rest = rest_centres(pocket, r, earlier, tol)?;
    let mut out = Vec::new();
    for piece in assemble(rest.centres, tol) {
        if 2.0 * piece.area() <= SLIVER * piece.contours().map(Contour::length).sum::<f64>() {
            continue;
        }
        out.extend(offset_pocket(&piece, -r, tol)?);
    }
    Ok((assemble(out, tol), rest.exact))
}

/// The loops of R, where the centre of the tool of radius `r` still has work in `pocket`
/// after tools of radii `earlier` (see the module's documentation).
pub fn rest_centres(pocket: &Pocket, r: f64, earlier: &[f64], tol: &Tolerance) -> Result<Rest, OffsetError> {
    if earlier.iter().any(|&r1| r1 <= r) {
        return Ok(Rest {
            centres: Vec::new(),
            exact: true,
        });
    }
    let mut region = offset_pocket(pocket, r, tol)?;
    for &r1 in earlier {
        if region.is_empty() {
            break;
        }
        let mut cleared = Vec::new();
        for e in assemble(offset_pocket(pocket, r1, tol)?, tol) {
            cleared.extend(offset_pocket(&e, -(r1 - r + GROW), tol)?);
        }
        match difference(&region, &cleared, tol) {
            Some(r) => region = r,
            // Safe rather than exact: the tool's whole centre region, so the whole pocket it
            // can reach (more cutting, never material left).
            None => {
                return Ok(Rest {
                    centres: offset_pocket(pocket, r, tol)?,
                    exact: false,
                })
            }
        }
    }
    Ok(Rest {
        centres: region,
        exact: true,
    })
}

/// Where a smaller tool's centre still has work ([`rest_centres`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Rest {
    /// The loops of R.
    pub centres: Vec<Contour>,
    /// False when the difference could not be made exactly and R is the tool's whole centre
    /// region instead.
    pub exact: bool,
}

/// Loops (counter-clockwise round their inside, clockwise round holes) grouped into pockets.
fn assemble(loops: Vec<Contour>, tol: &Tolerance) -> Vec<Pocket> {
    crate::import::nesting::assemble(loops, tol, &mut Vec::new())
}

/// The loops bounding what `a` holds and `b` does not (both sets oriented counter-clockwise
/// round what they hold); `None` when the pieces would not close into loops.
fn difference(a: &[Contour], b: &[Contour], tol: &Tolerance) -> Option<Vec<Contour>> {
    if b.is_empty() {
        return Some(a.to_vec());
    }
    let group: Vec<&Contour> = a.iter().chain(b).collect();
    // Every segment with its contour, and the places where a segment of `a` meets one of `b`.
    let segments: Vec<(usize, usize)> = group
        .iter()
        .enumerate()
        .flat_map(|(c, contour)| (0..contour.segments.len()).map(move |k| (c, k)))
        .collect();
    let boxes: Vec<Aabb> = segments
        .iter()
        .map(|&(c, k)| group[c].segments[k].bbox().inflated(tol.eps))
        .collect();
    let mut cuts: HashMap<(usize, usize), Vec<(f64, Point)>> = HashMap::new();
    for (i, j) in box_pairs(&boxes) {
        let ((ci, ki), (cj, kj)) = (segments[i], segments[j]);
        if (ci < a.len()) == (cj < a.len()) {
            continue; // loops of one set do not cross
        }
        let (si, sj) = (&group[ci].segments[ki], &group[cj].segments[kj]);
        for h in intersect(si, sj, tol.eps).iter() {
            match h {
                Intersection::Point { point, ta, tb } => {
                    cuts.entry((ci, ki)).or_default().push((ta, point));
                    cuts.entry((cj, kj)).or_default().push((tb, point));
                }
                Intersection::Overlap { a: ra, b: rb } => {
                    for (t, u) in [(ra.0, rb.0), (ra.1, rb.1)] {
                        let p = si.point_at(t);
                        cuts.entry((ci, ki)).or_default().push((t, p));
                        cuts.entry((cj, kj)).or_default().push((u, p));
                    }
                }
            }
        }
    }
    let (wa, wb) = (Winding::new(a), Winding::new(b));
    let kept = |p: Point| wa.at(p) > 0 && wb.at(p) <= 0;
    let at_segment = |c: usize, k: usize| cuts.get(&(c, k)).map_or(&[][..], Vec::as_slice);
    let pieces = crate::import::nesting::boundary_pieces(&group, &at_segment, &kept, tol);
    let (loops, left) = crate::import::nesting::stitch(pieces, tol);
    // Pieces that close no loop mean a crossing was missed (near-tangent loops): a region
    // may be lost, so the difference is not to be trusted.
    (left == 0).then_some(loops)
}

/// The winding number of a set of loops round a point: the sum of each loop's (an index of one
/// chain closes the gaps between its segments, so every loop has its own).
struct Winding<'a> {
    loops: Vec<(&'a Contour, Aabb, WindingIndex)>,
}

impl<'a> Winding<'a> {
    fn new(loops: &'a [Contour]) -> Winding<'a> {
        Winding {
            loops: loops
                .iter()
                .map(|c| (c, c.bbox(), WindingIndex::new(&c.segments)))
                .collect(),
        }
    }

    fn at(&self, p: Point) -> i32 {
        self.loops
            .iter()
            .filter(|(_, b, _)| b.contains(p))
            .map(|(c, _, w)| w.winding(&c.segments, p))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Segment};

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Contour {
        let p = Point::new;
        Contour::polygon(&[p(x0, y0), p(x1, y0), p(x1, y1), p(x0, y1)])
    }

    #[test]
    fn a_corner_leaves_the_area_between_the_two_tools_arcs() {
        // A square corner after a tool of radius 3 holds (3 − r)² (1 − π/4) for the tool of
        // radius r... seen from the small tool's centre region: R's area is (3 − 1)²(1 − π/4)
        // per corner, less the sliver that GROW takes.
        let pocket = Pocket {
            boundary: rect(0.0, 0.0, 40.0, 30.0),
            islands: vec![],
        };
        let tol = Tolerance::default();
        let region = offset_pocket(&pocket, 1.0, &tol).unwrap();
        let e = assemble(offset_pocket(&pocket, 3.0, &tol).unwrap(), &tol);
        let u: Vec<Contour> = e
            .iter()
            .flat_map(|p| offset_pocket(p, -(2.0 + GROW), &tol).unwrap())
            .collect();
        let r = difference(&region, &u, &tol).unwrap();
        assert_eq!(r.len(), 4);
        let exact = 4.0 * 4.0 * (1.0 - std::f64::consts::FRAC_PI_4);
        let area: f64 = r.iter().map(Contour::signed_area).sum();
        assert!((area - exact).abs() < 0.05, "{area} against {exact}");
    }

    #[test]
    fn a_slot_the_large_tool_cannot_enter_is_all_rest() {
        // 4 mm wide: a 6 mm tool fits nowhere, a 2 mm one everywhere.
        let pocket = Pocket {
            boundary: rect(0.0, 0.0, 40.0, 4.0),
            islands: vec![],
        };
        let tol = Tolerance::default();
        let rest = rest_pockets(&pocket, 1.0, &[3.0], &tol).unwrap();
        assert_eq!(rest.len(), 1);
        // The slot opened by the 2 mm disc: all but its four corners' fillets.
        let exact = 160.0 - 4.0 * (1.0 - std::f64::consts::FRAC_PI_4);
        assert!((rest[0].area() - exact).abs() < 1e-3, "{}", rest[0].area());
    }

    #[test]
    fn a_round_pocket_leaves_nothing_to_a_smaller_tool() {
        let circle = Contour::new(vec![Segment::Arc(Arc::new(
            Point::new(0.0, 0.0),
            20.0,
            0.0,
            std::f64::consts::TAU,
        ))]);
        let pocket = Pocket {
            boundary: circle,
            islands: vec![],
        };
        let rest = rest_pockets(&pocket, 1.0, &[3.0], &Tolerance::default()).unwrap();
        assert!(rest.is_empty(), "{} pieces", rest.len());
    }

    #[test]
    fn the_rest_lies_inside_the_pocket_and_covers_what_the_large_tool_left() {
        // An L with a sharp inner corner and an island: sample points of the pocket that the
        // 2 mm tool reaches and the 6 mm tool does not must lie in the rest pockets.
        let p = Point::new;
        let ell = Contour::polygon(&[
            p(0.0, 0.0),
            p(40.0, 0.0),
            p(40.0, 12.0),
            p(14.0, 12.0),
            p(14.0, 30.0),
            p(0.0, 30.0),
        ]);
        let island = Contour::new(vec![Segment::Arc(Arc::new(
            p(25.0, 6.0),
            2.0,
            0.0,
            -std::f64::consts::TAU,
        ))]);
        let pocket = Pocket {
            boundary: ell,
            islands: vec![island],
        };
        let tol = Tolerance::default();
        let rest = rest_pockets(&pocket, 1.0, &[3.0], &tol).unwrap();
        assert!(!rest.is_empty());
        let inside =
            |q: &Pocket, x: Point| q.boundary.contains(x) && !q.islands.iter().any(|h| h.contains(x));
        // Reached by a disc: within r of a point at least r from every wall.
        let dist = |x: Point| {
            pocket
                .contours()
                .flat_map(|c| c.segments.iter())
                .map(|s| crate::geom::distance_from_segment(s, x))
                .fold(f64::INFINITY, f64::min)
        };
        let reached = |x: Point, r: f64| {
            (0..72).any(|k| {
                let a = k as f64 * std::f64::consts::TAU / 72.0;
                (0..=8).any(|j| {
                    let c = x + crate::geom::Vector::from_angle(a) * (r * j as f64 / 8.0);
                    inside(&pocket, c) && dist(c) >= r - 1e-9
                })
            })
        };
        let mut checked = 0;
        for i in 0..80 {
            for j in 0..60 {
                let x = p(0.25 + 0.5 * i as f64, 0.25 + 0.5 * j as f64);
                // Material the large tool leaves, by more than the leftover tolerance (points
                // at the edge of its reach are judged by a coarse sampling here).
                let near_large = (0..8).any(|k| {
                    let a = k as f64 * std::f64::consts::FRAC_PI_4;
                    reached(x + crate::geom::Vector::from_angle(a) * 0.05, 3.0)
                });
                if !inside(&pocket, x) || !reached(x, 1.0) || reached(x, 3.0) || near_large {
                    continue;
                }
                checked += 1;
                assert!(rest.iter().any(|q| inside(q, x)), "rest at {x} missed");
            }
        }
        assert!(checked > 20, "{checked}");
        // And every rest pocket lies in the pocket.
        for q in &rest {
            for s in q.contours().flat_map(|c| c.segments.iter()) {
                assert!(inside(&pocket, s.point_at(0.5)) || dist(s.point_at(0.5)) < 1e-6);
            }
        }
    }
}
