//! Nesting closed contours into pockets with islands.
//!
//! In: the closed contours the chaining stage made. Out: [`Nesting`], the pockets (each a
//! counter-clockwise boundary with clockwise islands), the nesting depth of every contour and
//! remarks on the contours merged or cut back.
//!
//! Each contour gets a nesting depth: 0 when nothing encloses it, else one more than the
//! deepest contour enclosing it. Material is removed where the deepest enclosing contour has an
//! even depth: depth 0 bounds a pocket, depth 1 an island, depth 2 a pocket inside an island,
//! and so on. Contours that cross or touch each other (overlapping islands, an island crossing the
//! wall) are cut at their intersections, and only the pieces with removed material on exactly
//! one side are kept and stitched into loops: overlapping islands merge, and an island crossing
//! the wall cuts the wall back. A contour that crosses itself is first filled into simple loops
//! by a [`FillRule`] (`fill.rs`), or refused.

use super::chain::ChainedContour;
use super::error::ImportError;
use super::fill::FillRule;
use super::self_crossing::make_simple;
use crate::geom::Source;
use crate::geom::{
    cluster_points, distance_from_segment, intersect, overlapping_pairs, Aabb, BoxIndex, Contour,
    Intersection, Piece, Pocket, Point, Segment, Tolerance, WindingIndex,
};
use crate::import::ImportWarning;
use crate::union_find::UnionFind;
use std::cell::OnceCell;
use std::collections::{HashMap, HashSet};

/// Point-in-contour tests over a set of contours; large contours get a strip index on first use.
struct Locator<'a> {
    contours: Vec<&'a Contour>,
    index: Vec<OnceCell<Option<WindingIndex>>>,
}

impl<'a> Locator<'a> {
    fn new(contours: Vec<&'a Contour>) -> Self {
        let index = contours.iter().map(|_| OnceCell::new()).collect();
        Locator { contours, index }
    }

    /// True when `p` (not on the contour) lies inside contour `k`.
    fn contains(&self, k: usize, p: Point) -> bool {
        let c = self.contours[k];
        let index =
            self.index[k].get_or_init(|| (c.segments.len() > 32).then(|| WindingIndex::new(&c.segments)));
        match index {
            Some(i) => i.winding(&c.segments, p) != 0,
            None => c.contains(p),
        }
    }
}

/// Pockets found in a drawing.
#[derive(Debug, Clone, Default)]
pub struct Nesting {
    /// The pockets, largest first.
    pub pockets: Vec<Pocket>,
    /// Nesting depth of each input contour (0 = outermost).
    pub depths: Vec<usize>,
    /// Remarks (crossing contours merged or cut back).
    pub warnings: Vec<ImportWarning>,
}

/// Where one segment of one contour is.
#[derive(Clone, Copy)]
struct SegRef {
    contour: usize,
    index: usize,
}

/// Nests `contours` into pockets. `layer_names` names layers in messages. A contour that
/// crosses or touches itself (other than in a sliver loop, removed) is filled by `fill`
/// (see [`FillRule`]), or refused when `fill` is `None`.
pub fn find_pockets(
    contours: &[ChainedContour],
    layer_names: &[String],
    tol: &Tolerance,
    fill: Option<FillRule>,
) -> Result<Nesting, ImportError> {
    let mut warnings = Vec::new();
    let (simple, origin) = simplified(contours, layer_names, tol, fill, &mut warnings)?;
    let drawn = contours.len();
    let contours = &simple[..];
    let contour_boxes: Vec<Aabb> = contours.iter().map(|c| c.contour.bbox()).collect();
    // Each contour's area once: the depths order by it, and a lone contour keeps it (turned).
    let areas: Vec<f64> = contours.iter().map(|c| c.contour.signed_area()).collect();
    let meetings = Meetings::find(contours, &contour_boxes, tol);
    let crossing: HashSet<(usize, usize)> = meetings
        .crossings
        .iter()
        .map(|&(a, b, _)| (a.min(b), a.max(b)))
        .collect();
    let locator = Locator::new(contours.iter().map(|c| &c.contour).collect());
    let contour_index = BoxIndex::new(&contour_boxes);
    let depths = nesting_depths(
        contours,
        &areas,
        (&contour_boxes, &contour_index),
        &crossing,
        &locator,
        tol,
    );
    meetings.report(contours, &origin, &depths, layer_names, &mut warnings);

    // Greatest depth of the contours enclosing p (None outside all), read as "material removed
    // here" when even.
    let removed = |p: Point| {
        contour_index
            .at_point(p)
            .filter(|&c| locator.contains(c, p))
            .map(|c| depths[c])
            .max()
            .is_some_and(|l| l % 2 == 0)
    };
    let loops = meetings.loops(contours, &depths, &removed, tol, &mut warnings);
    // The lone contours are moved out of `simple`, not copied: half a million arcs of traced
    // art are 45 MB a copy.
    let mut simple = simple;
    let loops = loops
        .into_iter()
        .map(|l| match l {
            Loop::Alone { contour, ccw } => {
                let mut c = std::mem::take(&mut simple[contour].contour);
                let area = areas[contour];
                if (area > 0.0) != ccw {
                    c.reverse();
                }
                (c, if (area > 0.0) == ccw { area } else { -area })
            }
            Loop::Stitched(c) => {
                let area = c.signed_area();
                (c, area)
            }
        })
        .collect();
    let pockets = assemble_with_areas(loops, tol, &mut warnings);
    // A contour filled into several loops is as deep as its outermost loop.
    let mut drawn_depths = vec![usize::MAX; drawn];
    for (k, &o) in origin.iter().enumerate() {
        drawn_depths[o] = drawn_depths[o].min(depths[k]);
    }
    for d in &mut drawn_depths {
        if *d == usize::MAX {
            *d = 0;
        }
    }
    Ok(Nesting {
        pockets,
        depths: drawn_depths,
        warnings,
    })
}

/// The contours made simple, and the drawn contour each came from: a sliver loop where one
/// crosses itself is removed with a warning; a contour crossing or touching itself otherwise
/// is filled into simple loops by `fill`, with a warning naming where, or refused without one.
fn simplified(
    contours: &[ChainedContour],
    layer_names: &[String],
    tol: &Tolerance,
    fill: Option<FillRule>,
    warnings: &mut Vec<ImportWarning>,
) -> Result<(Vec<ChainedContour>, Vec<usize>), ImportError> {
    let layer_name = |c: &ChainedContour| layer_names.get(c.layer).cloned().unwrap_or_default();
    let mut simple = Vec::with_capacity(contours.len());
    let mut origin = Vec::with_capacity(contours.len());
    // Each contour is checked for crossing itself alone.
    let checked = crate::parallel::map_sized(
        contours,
        |c| c.contour.segments.len(),
        |c| make_simple(&c.contour, tol),
    );
    for (k, (c, made_simple)) in contours.iter().zip(checked).enumerate() {
        match (made_simple, fill) {
            (Ok((contour, removed)), _) => {
                for p in removed {
                    warnings.push(ImportWarning::SliverLoopRemoved {
                        layer: layer_name(c),
                        at: p,
                    });
                }
                simple.push(c.with_contour(contour));
                origin.push(k);
            }
            (Err(x), None) => {
                return Err(ImportError::SelfCrossing {
                    layer: layer_name(c),
                    point: x.point,
                })
            }
            (Err(_), Some(rule)) => {
                let (loops, at) = super::fill::fill(&c.contour, rule, tol);
                warnings.push(ImportWarning::SelfCrossingFilled {
                    layer: layer_name(c),
                    rule,
                    loops: loops.len(),
                    at,
                });
                for contour in loops {
                    simple.push(c.with_contour(contour));
                    origin.push(k);
                }
            }
        }
    }
    Ok((simple, origin))
}

/// Most contours round one whose segments are each tested against those contours' boxes
/// one by one (a hole in a plate has one); beyond, each segment asks the index of boxes.
const FEW_NEIGHBOURS: usize = 8;

/// Where contours meet one another: the cuts on each segment, the groups of contours that
/// meet (directly or through others), and one point of every meeting.
struct Meetings {
    /// Parameters and points where other contours meet segment (contour, index).
    cuts: HashMap<(usize, usize), Vec<(f64, Point)>>,
    /// The group of each contour (the id of one of its members).
    cluster: Vec<usize>,
    /// Each meeting: the two contours and a point.
    crossings: Vec<(usize, usize, Point)>,
}

impl Meetings {
    fn find(contours: &[ChainedContour], boxes: &[Aabb], tol: &Tolerance) -> Meetings {
        // Only contours whose boxes overlap another's can meet it: the segments of the others
        // (most contours, in traced art and on island plates) stay out of the segment index.
        let contour_boxes: Vec<Aabb> = boxes.iter().map(|b| b.inflated(tol.eps)).collect();
        // The contours whose boxes overlap each one's.
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); contours.len()];
        for (a, b) in overlapping_pairs(&contour_boxes) {
            neighbours[a].push(b);
            neighbours[b].push(a);
        }
        // Nor does a segment of a contour `c` unless it touches the box of another contour `o`
        // that has a segment touching `c`'s box: a meeting point lies in a segment's box on
        // either side, so each side's segment touches the other contour's box. A profile of
        // 100 000 lines round six islands puts only the islands in the index (its own
        // neighbours' pairs were most of the work, and are never wanted), and a plate whose
        // holes lie clear of its edges puts nothing.
        // Built only for a contour with many round it (the plate round its holes).
        let near_others = std::cell::OnceCell::new();
        // Each segment that touches another contour's box, with that contour.
        let mut touching: Vec<(SegRef, Aabb, usize)> = Vec::new();
        for (c, cc) in contours.iter().enumerate() {
            let others = &neighbours[c];
            if others.is_empty() {
                continue;
            }
            // A hole's segments are tested against the few boxes round it, not the index.
            let few = others.len() <= FEW_NEIGHBOURS;
            for (index, s) in cc.contour.segments.iter().enumerate() {
                let b = s.bbox().inflated(tol.eps);
                let r = SegRef { contour: c, index };
                if few {
                    let touched = others.iter().filter(|&&o| contour_boxes[o].intersects(&b));
                    touching.extend(touched.map(|&o| (r, b, o)));
                } else {
                    let tree = near_others.get_or_init(|| BoxIndex::new(&contour_boxes));
                    let touched = tree.intersecting(&b).filter(|&o| o != c);
                    touching.extend(touched.map(|o| (r, b, o)));
                }
            }
        }
        let reaches: HashSet<(usize, usize)> = touching.iter().map(|(r, _, o)| (r.contour, *o)).collect();
        let mut refs: Vec<SegRef> = Vec::new();
        let mut boxes: Vec<Aabb> = Vec::new();
        for &(r, b, o) in &touching {
            let same = refs
                .last()
                .is_some_and(|l| l.contour == r.contour && l.index == r.index);
            if !same && reaches.contains(&(o, r.contour)) {
                refs.push(r);
                boxes.push(b);
            }
        }
        let seg = |r: &SegRef| &contours[r.contour].contour.segments[r.index];
        let index = BoxIndex::new(&boxes);
        let mut cuts: HashMap<(usize, usize), Vec<(f64, Point)>> = HashMap::new();
        let mut clusters = UnionFind::new(contours.len());
        let mut crossings: Vec<(usize, usize, Point)> = Vec::new();
        for (i, j) in index.pairs() {
            let (a, b) = (refs[i], refs[j]);
            if a.contour == b.contour {
                continue; // made simple before
            }
            let hits = intersect(seg(&a), seg(&b), tol.eps);
            if hits.is_empty() {
                continue;
            }
            for h in hits.iter() {
                let (pa, pb) = match h {
                    Intersection::Point { point, ta, tb } => (vec![(ta, point)], vec![(tb, point)]),
                    Intersection::Overlap {
                        a: (a0, a1),
                        b: (b0, b1),
                    } => {
                        let (p0, p1) = (seg(&a).point_at(a0), seg(&a).point_at(a1));
                        (vec![(a0, p0), (a1, p1)], vec![(b0, p0), (b1, p1)])
                    }
                };
                crossings.push((a.contour, b.contour, pa[0].1));
                cuts.entry((a.contour, a.index)).or_default().extend(pa);
                cuts.entry((b.contour, b.index)).or_default().extend(pb);
            }
            clusters.union(a.contour, b.contour);
        }
        let cluster: Vec<usize> = (0..contours.len()).map(|c| clusters.find(c)).collect();
        Meetings {
            cuts,
            cluster,
            crossings,
        }
    }

    /// One warning per pair of contours that meet: merged where they overlap at one depth, cut
    /// back where one crosses the other.
    /// Loops of one drawn contour (`origin`) meet where it crossed itself, reported already.
    fn report(
        &self,
        contours: &[ChainedContour],
        origin: &[usize],
        depths: &[usize],
        layer_names: &[String],
        warnings: &mut Vec<ImportWarning>,
    ) {
        let mut reported = HashSet::new();
        for &(a, b, p) in &self.crossings {
            if origin[a] != origin[b] && reported.insert((self.cluster[a], a.min(b), a.max(b))) {
                let layer = |c: usize| {
                    layer_names
                        .get(contours[c].layer)
                        .cloned()
                        .unwrap_or_else(|| "?".into())
                };
                warnings.push(ImportWarning::ContoursMeet {
                    layers: [layer(a), layer(b)],
                    at: p,
                    merged: depths[a] == depths[b],
                });
            }
        }
    }

    /// The loops bounding removed material: a contour alone as it is (turned to have the
    /// material on its left), the contours of a group that meet cut at their meetings and the
    /// pieces with removed material on exactly one side stitched.
    fn loops(
        &self,
        contours: &[ChainedContour],
        depths: &[usize],
        removed: &dyn Fn(Point) -> bool,
        tol: &Tolerance,
        warnings: &mut Vec<ImportWarning>,
    ) -> Vec<Loop> {
        let mut members: HashMap<usize, Vec<usize>> = HashMap::new();
        for (c, &root) in self.cluster.iter().enumerate() {
            members.entry(root).or_default().push(c);
        }
        let mut loops: Vec<Loop> = Vec::new();
        let mut roots: Vec<usize> = members.keys().copied().collect();
        roots.sort_unstable();
        for root in roots {
            let group = &members[&root];
            if group.len() == 1 {
                // Alone, a contour bounds removed material on its inside exactly when its depth
                // is even.
                loops.push(Loop::Alone {
                    contour: group[0],
                    ccw: depths[group[0]] % 2 == 0,
                });
                continue;
            }
            let members: Vec<&Contour> = group.iter().map(|&c| &contours[c].contour).collect();
            let cuts = |g: usize, k: usize| self.cuts.get(&(group[g], k)).map_or(&[][..], Vec::as_slice);
            let pieces = boundary_pieces(&members, &cuts, removed, tol);
            let (stitched, lost) = stitch(pieces, tol);
            if lost > 0 {
                warnings.push(ImportWarning::PiecesLost { pieces: lost });
            }
            loops.extend(stitched.into_iter().map(Loop::Stitched));
        }
        loops
    }
}

/// A loop bounding removed material, as [`Meetings::loops`] finds it.
enum Loop {
    /// A contour that meets no other, to be turned counter-clockwise when `ccw`.
    Alone { contour: usize, ccw: bool },
    /// A loop stitched from the pieces of contours that meet, turned already.
    Stitched(Contour),
}

/// Nesting depth of each contour: 0 when none encloses it, else one more than the deepest contour
/// that encloses it.
///
/// Two contours that cross enclose neither, strictly. Where a contour crosses a larger one that
/// bounds a pocket (even depth) and lies mostly inside it, it is taken as an island of that pocket
/// crossing its wall, so the wall is cut back. Contours crossing at an odd depth (islands) keep
/// the same depth and are merged.
fn nesting_depths(
    contours: &[ChainedContour],
    signed_areas: &[f64],
    (boxes, index): (&[Aabb], &BoxIndex),
    crossing: &HashSet<(usize, usize)>,
    locator: &Locator,
    tol: &Tolerance,
) -> Vec<usize> {
    let n = contours.len();
    let areas: Vec<f64> = signed_areas.iter().map(|a| a.abs()).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| areas[b].total_cmp(&areas[a]));
    let mut depths = vec![0usize; n];
    let mut done = vec![false; n];
    for &b in &order {
        let inner = &contours[b].contour;
        let probe = inner.points_along(1);
        let mut depth = 0;
        for a in index.intersecting(&boxes[b]) {
            if a == b || !done[a] {
                continue;
            }
            let enclosed = if crossing.contains(&(a.min(b), a.max(b))) {
                depths[a] % 2 == 0 && mostly_inside(inner, a, locator, tol)
            } else {
                boxes[a].contains_box(&boxes[b]) && probe.first().is_some_and(|&p| locator.contains(a, p))
            };
            if enclosed {
                depth = depth.max(depths[a] + 1);
            }
        }
        depths[b] = depth;
        done[b] = true;
    }
    depths
}

/// True when at least half of `inner`'s length (sampled, ignoring points on `outer`) lies
/// inside `outer`. An even number of samples, so that a circle centred on a straight wall ties
/// and counts as an island crossing the wall (a relief meant to extend the pocket lies mostly
/// outside it).
fn mostly_inside(inner: &Contour, outer: usize, locator: &Locator, tol: &Tolerance) -> bool {
    let (mut inside, mut outside) = (0, 0);
    for p in inner.points_along(64) {
        if locator.contours[outer]
            .segments
            .iter()
            .any(|s| distance_from_segment(s, p) <= tol.join.max(tol.eps))
        {
            continue;
        }
        if locator.contains(outer, p) {
            inside += 1;
        } else {
            outside += 1;
        }
    }
    inside > 0 && inside >= outside
}

/// Pieces of a group of crossing contours, cut where `cuts(contour in group, segment)` says,
/// that have removed material on exactly one side, oriented with that material on their left.
pub(crate) fn boundary_pieces<'c>(
    group: &[&Contour],
    cuts: &dyn Fn(usize, usize) -> &'c [(f64, Point)],
    removed: &dyn Fn(Point) -> bool,
    tol: &Tolerance,
) -> Vec<Segment> {
    let mut pieces: Vec<Segment> = Vec::new();
    for (c, contour) in group.iter().enumerate() {
        for (k, s) in contour.segments.iter().enumerate() {
            let mut at: Vec<(f64, Point)> = cuts(c, k).to_vec();
            at.push((0.0, s.start()));
            at.push((1.0, s.end()));
            at.sort_by(|a, b| a.0.total_cmp(&b.0));
            for w in at.windows(2) {
                let ((t0, p0), (t1, p1)) = (w[0], w[1]);
                if (t1 - t0) * s.length() <= tol.rounding() {
                    continue;
                }
                let mut piece = s.subsegment(t0, t1);
                // The cut points are where the neighbouring pieces end: use them exactly.
                if let Segment::Line(l) = &mut piece {
                    l.start = p0;
                    l.end = p1;
                }
                pieces.push(piece);
            }
        }
    }
    let pieces = dedup_pieces(pieces, tol);
    let mut out = Vec::new();
    for piece in pieces {
        let mid = piece.point_at(0.5);
        let normal = piece.tangent_at(0.5).perp();
        // Far enough off the piece to be off every other (at least `crossing`, even where that
        // exceeds the usual 1e-4 mm: drawings 1e5 mm across), near enough to stay in the
        // region beside it.
        let delta = (piece.length() * 1e-3).min(1e-4).max(tol.crossing());
        let left = removed(mid + normal * delta);
        let right = removed(mid - normal * delta);
        if left && !right {
            out.push(piece);
        } else if right && !left {
            out.push(piece.reversed());
        }
    }
    out
}

/// Removes pieces that coincide with an earlier one (in either direction).
fn dedup_pieces(pieces: Vec<Segment>, tol: &Tolerance) -> Vec<Segment> {
    let boxes: Vec<Aabb> = pieces.iter().map(|p| p.bbox()).collect();
    let index = BoxIndex::new(&boxes);
    let r = tol.coincident();
    let mut keep = vec![true; pieces.len()];
    for (i, j) in index.pairs() {
        if !keep[i] || !keep[j] {
            continue;
        }
        let (a, b) = (&pieces[i], &pieces[j]);
        let same_ends = (a.start().distance(b.start()) <= r && a.end().distance(b.end()) <= r)
            || (a.start().distance(b.end()) <= r && a.end().distance(b.start()) <= r);
        if same_ends && distance_from_segment(b, a.point_at(0.5)) <= r {
            keep[j] = false;
        }
    }
    pieces
        .into_iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(p))
        .collect()
}

/// Joins pieces end to start into closed loops (see [`crate::geom::stitch`]); ends closer
/// than [`Tolerance::crossing`] are one node. Returns the loops and how many pieces were left over.
pub(crate) fn stitch(pieces: Vec<Segment>, tol: &Tolerance) -> (Vec<Contour>, usize) {
    let ends: Vec<Point> = pieces.iter().flat_map(|p| [p.start(), p.end()]).collect();
    let node = cluster_points(&ends, tol.crossing());
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .enumerate()
        .map(|(i, segment)| Piece {
            segment,
            start: node[2 * i],
            end: node[2 * i + 1],
            source: Source::Element(i as u32),
        })
        .collect();
    crate::geom::stitch(&pieces)
}

/// Groups loops into pockets: each clockwise loop goes to the smallest counter-clockwise loop
/// around it.
/// Points of a hole tested against the boundaries around it.
const OWNER_PROBES: usize = 8;

pub(crate) fn assemble(
    loops: Vec<Contour>,
    tol: &Tolerance,
    warnings: &mut Vec<ImportWarning>,
) -> Vec<Pocket> {
    let loops = loops
        .into_iter()
        .map(|c| {
            let area = c.signed_area();
            (c, area)
        })
        .collect();
    assemble_with_areas(loops, tol, warnings)
}

/// [`assemble`] of loops whose signed areas are known: each `(loop, area)`.
fn assemble_with_areas(
    loops: Vec<(Contour, f64)>,
    tol: &Tolerance,
    warnings: &mut Vec<ImportWarning>,
) -> Vec<Pocket> {
    let (mut outer, holes): (Vec<_>, Vec<_>) = loops.into_iter().partition(|(_, area)| *area > 0.0);
    // Largest first.
    outer.sort_by(|a, b| b.1.total_cmp(&a.1));
    let holes: Vec<Contour> = holes.into_iter().map(|(c, _)| c).collect();
    let (areas, mut pockets): (Vec<f64>, Vec<Pocket>) = outer
        .into_iter()
        .map(|(boundary, area)| {
            let pocket = Pocket {
                boundary,
                islands: Vec::new(),
            };
            (area, pocket)
        })
        .unzip();
    // A hole touching its boundary's extreme reaches it to within rounding, either side.
    let boxes: Vec<Aabb> = pockets
        .iter()
        .map(|p| p.boundary.bbox().inflated(tol.eps))
        .collect();
    let index = BoxIndex::new(&boxes);
    let owners: Vec<Option<usize>> = {
        let locator = Locator::new(pockets.iter().map(|p| &p.boundary).collect());
        holes
            .iter()
            .map(|hole| {
                // A hole may touch its boundary at points (loops that meet there were cut
                // apart), and a single probe may fall on one: the owner is the smallest
                // boundary around most of the probes. An even count keeps the probes off the
                // hole's two ends by length, where a loop cut at two points has its corners.
                let probes = hole.points_along(OWNER_PROBES);
                let extent = hole.bbox();
                index
                    .intersecting(&extent)
                    .filter(|&k| boxes[k].contains_box(&extent))
                    .filter(|&k| {
                        2 * probes.iter().filter(|&&p| locator.contains(k, p)).count() > probes.len()
                    })
                    .min_by(|&a, &b| areas[a].total_cmp(&areas[b]))
            })
            .collect()
    };
    for (hole, owner) in holes.into_iter().zip(owners) {
        match owner {
            Some(k) => pockets[k].islands.push(hole),
            None => {
                let at = hole.segments.first().map(|s| s.start()).unwrap_or_default();
                warnings.push(ImportWarning::IslandInNoPocket { at });
            }
        }
    }
    pockets
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hole_touching_its_boundary_where_it_is_probed_is_still_an_island() {
        // A diamond hole touching the square's top and bottom edges: the middle of the hole by
        // length is a touching point, on the boundary, where inside and outside are a toss-up.
        let square = Contour::polygon(&[
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(10.0, 10.0),
            Point::new(0.0, 10.0),
        ]);
        let diamond = Contour::polygon(&[
            Point::new(5.0, 0.0),
            Point::new(2.0, 5.0),
            Point::new(5.0, 10.0),
            Point::new(8.0, 5.0),
        ]);
        assert!(!diamond.is_ccw());
        let mut warnings = Vec::new();
        let pockets = assemble(vec![square, diamond], &Tolerance::default(), &mut warnings);
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(pockets.len(), 1);
        assert_eq!(pockets[0].islands.len(), 1);
    }

    fn chained(contour: Contour) -> ChainedContour {
        ChainedContour {
            contour,
            layer: 0,
            elements: Vec::new(),
        }
    }

    /// A square of side `2h` round `c`, clockwise.
    fn square_hole(c: Point, h: f64) -> ChainedContour {
        chained(Contour::polygon(&[
            Point::new(c.x - h, c.y - h),
            Point::new(c.x - h, c.y + h),
            Point::new(c.x + h, c.y + h),
            Point::new(c.x + h, c.y - h),
        ]))
    }

    #[test]
    fn meetings_are_found_among_many_contours_where_they_touch_and_nowhere_else() {
        // A triangle with a grid of square holes clear of everything, one hole across its
        // long side, one whose box reaches over that side while the hole stays clear of it,
        // and one lying on the short side: the segments of most holes go into no index, and
        // every meeting is still found.
        let mut contours = vec![chained(Contour::polygon(&[
            Point::new(0.0, 0.0),
            Point::new(100.0, 0.0),
            Point::new(0.0, 100.0),
        ]))];
        for i in 0..6 {
            for j in 0..(6 - i) {
                contours.push(square_hole(
                    Point::new(8.0 + 12.0 * i as f64, 8.0 + 12.0 * j as f64),
                    2.0,
                ));
            }
        }
        let across = contours.len();
        contours.push(square_hole(Point::new(50.0, 50.0), 2.0));
        // A diamond: its box's corner (23, 78) is beyond the side x + y = 100, it is not.
        let c = Point::new(20.0, 75.0);
        contours.push(chained(Contour::polygon(&[
            Point::new(c.x + 3.0, c.y),
            Point::new(c.x, c.y - 3.0),
            Point::new(c.x - 3.0, c.y),
            Point::new(c.x, c.y + 3.0),
        ])));
        let on_edge = contours.len();
        contours.push(square_hole(Point::new(60.0, 2.0), 2.0));
        let boxes: Vec<Aabb> = contours.iter().map(|c| c.contour.bbox()).collect();
        let meetings = Meetings::find(&contours, &boxes, &Tolerance::default());
        let mut pairs: Vec<(usize, usize)> = (meetings.crossings.iter())
            .map(|&(a, b, _)| (a.min(b), a.max(b)))
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs, vec![(0, across), (0, on_edge)]);
        for (c, &group) in meetings.cluster.iter().enumerate() {
            let with_triangle = c == 0 || c == across || c == on_edge;
            assert_eq!(group == meetings.cluster[0], with_triangle, "contour {c}");
        }
    }
}
