//! Small leaves cleared from one spot, or not at all: where a leaf of the tree leaves so little
//! that the tool standing at one point inside it, or passing once along a straight line,
//! removes all of it, its loop gives way to a short path through that point or along that
//! line, a spot of its parent part ([`super::Part::spots`]); where nothing is left for it, it
//! is dropped.
//!
//! Why this leaves nothing: take a leaf part at distance d_k (one outer loop L, no loops round
//! islands, no parts inside), its parent at d_(k−1), and e = d_(k−1) + r. A point p inside L
//! whose distance t to the walls is at most e lies t − d_(k−1) ≤ r from the parent's level
//! along the straight line to its nearest wall (the distance falls as fast as one goes), so
//! the parent's loops sweep it. What they may miss is inside L and farther than e from the
//! walls: the inside of L eroded by δ = e − d_k (at least 0 when the stepover is at most the
//! tool radius, the only case taken here). If that is empty, L sweeps nothing new; if it lies
//! within r of a point c inside L (with a margin), the tool at c sweeps it; if within r of a
//! straight segment inside L, a pass along the segment does (a long narrow leaf). Points
//! outside L are no business of L's: within the distance d_k < e, the parent sweeps them.
//!
//! Only leaves with siblings are taken: the linker cuts those after their parent's loops (see
//! `link::schedule`), so their loops eased nothing for the parent. An only child is cut
//! before its parent, the first loop of its branch and a slot; its parent's loop, a stepover
//! out, then cuts a stepover wide. Without the child the parent's loop would be the slot.
//!
//! On the 300-hole plate at 40 % stepover the 266 loops between four holes, 21 mm each, become
//! steps of about 5 mm out from the last loop round a hole beside them and back (linking
//! bench: 2586.6 -> 2326.0 s of machining).

use super::{ClearParams, ClearPlan, Part, Path, Spot};
use crate::geom::{
    closest_point, distance_from_segment, enclosing_circle, farthest_from_segment, intersect, nearest_on,
    outline_points, Contour, Line, Point, Segment, Tolerance, Vector,
};

/// How much nearer than the tool radius the spot must be to everything it answers for, in tool
/// radii: room for rounding (the same as the clean-up paths keep).
const MARGIN_RADII: f64 = super::residue::REACH_MARGIN_RADII;

/// The turn of the pieces an arc is taken in as chords for the moments of an outline (see
/// [`outline_moments`]), radians.
const MOMENT_PIECE: f64 = 0.1;

/// The length of a spot's path, in tool radii at most: a path has a direction, and linking
/// takes it as any other clean-up path; how long does not matter to what it clears.
const SPOT_LENGTH_RADII: f64 = 0.1;

/// Replaces each leaf of `plan` that one spot clears by a path through that spot, a spot of
/// its parent, and drops the leaves that the parent's loops clear alone; a part whose
/// parts inside all went that way is taken the same way in turn.
pub fn clear_leaves_from_spots(plan: &mut ClearPlan, params: &ClearParams, tol: &Tolerance) {
    let r = params.tool_radius;
    let n = plan.parts.len();
    let (mut gone, mut tried) = (vec![false; n], vec![false; n]);
    // Spots added here, by part: a part with only these is still a leaf that a spot may
    // clear (its own spot covers theirs).
    let mut spots: Vec<Vec<Spot>> = vec![Vec::new(); n];
    // In rounds: the leaves first, on all cores (a plate has hundreds), then the parts all of
    // whose children went, and so on.
    loop {
        let plan_now = &*plan;
        let leaves: Vec<usize> = (0..n)
            .filter(|&i| !tried[i] && takes_part(plan_now, i, &gone))
            .collect();
        if leaves.is_empty() {
            break;
        }
        let found = crate::parallel::map(&leaves, |&i| {
            let part = &plan_now.parts[i];
            let parent = &plan_now.parts[part.parent.unwrap_or(i)];
            spot(part, parent.distance + r - part.distance, r, tol)
        });
        for (&i, found) in leaves.iter().zip(found) {
            tried[i] = true;
            let parent = plan.parts[i].parent.unwrap_or(i);
            match found {
                Some(Found::Nothing) => gone[i] = true,
                Some(Found::At(spot)) => {
                    gone[i] = true;
                    spots[parent].push(spot);
                }
                None => {}
            }
        }
    }
    for (part, mut own) in plan.parts.iter_mut().zip(spots) {
        part.spots.append(&mut own);
    }
    remove_parts(plan, &gone);
}

/// True when part `i` of `plan` is a leaf (every part inside it `gone`) that a spot may take.
fn takes_part(plan: &ClearPlan, i: usize, gone: &[bool]) -> bool {
    let part = &plan.parts[i];
    let Some(parent) = part.parent.map(|p| &plan.parts[p]) else {
        return false;
    };
    let leaf = part.holes.is_empty() && part.cleanups.is_empty() && part.children.iter().all(|&c| gone[c]);
    // The only child of its parent is cut before it, the first of its branch, a slot in full
    // stock; without it the parent's loop would be that slot, longer and its cut heavier all
    // round (on the bench's small fillets the p95 engagement rose from 136° to 161°).
    let siblings = parent.children.len() > 1;
    // A finishing loop (the level at the tool radius when there is an allowance) is cut with
    // leads, nothing on its way round.
    let finishing = plan.allowance > 0.0 && parent.level == 0;
    leaf && siblings && !finishing
}

/// What clears a leaf besides its parent's loops.
enum Found {
    /// Nothing is left for it.
    Nothing,
    /// The tool at the end of this spot's path, or along it, clears what is.
    At(Spot),
}

/// What the leaf `part` leaves beyond its parent's reach, `reach` inside its loop: None when
/// neither one spot nor one straight path clears it (or the leaf cannot be eroded).
fn spot(part: &Part, reach: f64, r: f64, tol: &Tolerance) -> Option<Found> {
    if reach < 0.0 {
        return None;
    }
    let left = if reach > 0.0 {
        crate::offset::offset_contour(&part.outer, reach, tol).ok()?
    } else {
        vec![part.outer.clone()]
    };
    if left.is_empty() {
        return Some(Found::Nothing);
    }
    let limit = r * (1.0 - MARGIN_RADII);
    let points: Vec<Point> = left.iter().flat_map(|c| outline_points(&c.segments)).collect();
    let path = |line| Path {
        segments: vec![Segment::Line(line)],
        closed: false,
    };
    if let Some(line) = one_point(part, &left, &points, limit, r) {
        return Some(Found::At(Spot {
            path: path(line),
            left: Some((left, limit)),
        }));
    }
    let line = spine(part, &left, &points, limit, r, tol)?;
    Some(Found::At(Spot {
        path: path(line),
        left: None,
    }))
}

/// A short path ending at the one point within `limit` of all of `left` (the centre of the
/// smallest circle round its `points`, checked exactly), running from it towards the leaf's
/// loop; None when there is no such point inside the loop.
fn one_point(part: &Part, left: &[Contour], points: &[Point], limit: f64, r: f64) -> Option<Line> {
    let b = left.iter().map(Contour::bbox).reduce(|a, b| a.union(&b))?;
    if b.width() > 2.0 * limit || b.height() > 2.0 * limit {
        return None;
    }
    let (c, _) = enclosing_circle(points)?;
    let mut segments = left.iter().flat_map(|c| c.segments.iter());
    if segments.any(|s| farthest_from_segment(s, c) > limit) || !part.outer.contains(c) {
        return None;
    }
    // The nearest point of the loop: the path runs from c towards it, inside the loop.
    let (k, _, room) = nearest_on(&part.outer.segments, c);
    let q = closest_point(part.outer.segments.get(k)?, c);
    let length = room.min(SPOT_LENGTH_RADII * r);
    let toward = (q - c).normalized()?;
    if length < 1e-3 * r {
        return None;
    }
    Some(Line::new(c + toward * length, c))
}

/// A straight path along the middle of `left` (the principal axis of its outline, half way
/// across its `points`) within `limit` of every point of it, inside the leaf's loop; None when
/// `left` is too wide or bent for one. A long narrow leaf (between two islands and a wall) is
/// cleared by a pass along it instead of a loop round it.
fn spine(
    part: &Part,
    left: &[Contour],
    points: &[Point],
    limit: f64,
    r: f64,
    tol: &Tolerance,
) -> Option<Line> {
    let (mean, sxx, sxy, syy) = outline_moments(left.iter().flat_map(|c| &c.segments))?;
    let u = Vector::from_angle(0.5 * (2.0 * sxy).atan2(sxx - syy));
    let v = u.perp();
    // Built a little inside the limit: the points are samples of the arcs.
    let build = limit - 0.02 * r;
    let across = |p: &Point| (*p - mean).dot(v);
    let (lo, hi) = points
        .iter()
        .map(across)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| {
            (a.min(h), b.max(h))
        });
    let middle = 0.5 * (lo + hi);
    if 0.5 * (hi - lo) > build {
        return None;
    }
    // Each point is within `build` of the stretch [from, to] of the axis when its distance
    // along lies within w = √(build² − h²) of it.
    let (mut from, mut to) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        let (t, h) = ((*p - mean).dot(u), across(p) - middle);
        let w = (build * build - h * h).max(0.0).sqrt();
        (from, to) = (from.min(t + w), to.max(t - w));
    }
    if from >= to {
        return None;
    }
    let at = |t: f64| mean + u * t + v * middle;
    let line = Line::new(at(from), at(to));
    let path = Segment::Line(line);
    let mut segments = left.iter().flat_map(|c| c.segments.iter());
    if segments.any(|s| farthest_bound(s, &path, 0.005 * r) > limit) {
        return None;
    }
    let clear_of_loop = (part.outer.segments.iter()).all(|o| intersect(&path, o, tol.eps).is_empty());
    (clear_of_loop && part.outer.contains(line.start) && part.outer.contains(line.end)).then_some(line)
}

/// The centroid of the outline `segments` and its second moments about it (xx, xy, yy),
/// by length: exact along lines, arcs taken as chords of pieces of [`MOMENT_PIECE`]; None for
/// an outline of no length.
pub(super) fn outline_moments<'a>(
    segments: impl Iterator<Item = &'a Segment>,
) -> Option<(Point, f64, f64, f64)> {
    let mut chords: Vec<(Point, Point)> = Vec::new();
    for s in segments {
        let pieces = match s {
            Segment::Line(_) => 1,
            Segment::Arc(a) => ((a.sweep().abs() / MOMENT_PIECE).ceil() as usize).clamp(1, 4096),
        };
        let at = |k: usize| s.point_at(k as f64 / pieces as f64);
        chords.extend((0..pieces).map(|k| (at(k), at(k + 1))));
    }
    let length: f64 = chords.iter().map(|(p, q)| p.distance(*q)).sum();
    if length <= 0.0 {
        return None;
    }
    let (mut mx, mut my) = (0.0, 0.0);
    for (p, q) in &chords {
        let l = p.distance(*q);
        (mx, my) = (mx + 0.5 * l * (p.x + q.x), my + 0.5 * l * (p.y + q.y));
    }
    let mean = Point::new(mx / length, my / length);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (p, q) in &chords {
        let (l, a, b) = (p.distance(*q), *p - mean, *q - mean);
        sxx += l * (a.x * a.x + a.x * b.x + b.x * b.x) / 3.0;
        syy += l * (a.y * a.y + a.y * b.y + b.y * b.y) / 3.0;
        sxy += l * (2.0 * a.x * a.y + a.x * b.y + b.x * a.y + 2.0 * b.x * b.y) / 6.0;
    }
    Some((mean, sxx, sxy, syy))
}

/// At least the largest distance from a point of `seg` to the straight `path`: exact for a
/// line (the distance to a segment is convex, largest at an end); for an arc, the largest at
/// the corners of the boxes round pieces of it that bulge at most `sagitta` off their chords.
fn farthest_bound(seg: &Segment, path: &Segment, sagitta: f64) -> f64 {
    let d = |p: Point| distance_from_segment(path, p);
    match seg {
        Segment::Line(l) => d(l.start).max(d(l.end)),
        Segment::Arc(a) => {
            // A piece of sweep θ bulges R (1 − cos θ/2) off its chord.
            let step = 2.0 * (1.0 - (sagitta / a.radius()).min(1.0)).acos();
            let pieces = ((a.sweep().abs() / step.max(1e-3)).ceil() as usize).clamp(2, 4096);
            (0..pieces)
                .map(|k| {
                    let (t0, t1) = (k as f64 / pieces as f64, (k + 1) as f64 / pieces as f64);
                    let (p, q, m) = (a.point_at(t0), a.point_at(t1), a.point_at(0.5 * (t0 + t1)));
                    // The piece lies between its chord and the chord moved out to its middle.
                    let out = m - p.midpoint(q);
                    [p, q, p + out, q + out].map(d).into_iter().fold(0.0, f64::max)
                })
                .fold(0.0, f64::max)
        }
    }
}

/// Removes the parts marked `gone` (leaves only) from `plan`, renumbering the others.
fn remove_parts(plan: &mut ClearPlan, gone: &[bool]) {
    if !gone.contains(&true) {
        return;
    }
    let mut new_index = vec![usize::MAX; gone.len()];
    let mut kept = 0;
    for (i, &g) in gone.iter().enumerate() {
        if !g {
            new_index[i] = kept;
            kept += 1;
        }
    }
    let parts = std::mem::take(&mut plan.parts);
    plan.parts = (parts.into_iter().zip(gone))
        .filter(|(_, &g)| !g)
        .map(|(mut p, _)| {
            p.children = (p.children.iter())
                .filter(|&&c| !gone[c])
                .map(|&c| new_index[c])
                .collect();
            p.parent = p.parent.map(|q| new_index[q]);
            p
        })
        .collect();
    for root in &mut plan.roots {
        *root = new_index[*root];
    }
    // Levels whose parts all went are no longer used.
    let deepest = plan.parts.iter().map(|p| p.level + 1).max().unwrap_or(0);
    plan.distances.truncate(deepest);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clear::plan_pocket;
    use crate::geom::{Arc, Pocket};

    fn plate(holes: usize) -> Pocket {
        // Holes of radius 4 at a 20 mm pitch in a plate with 10 mm round them.
        let p = Point::new;
        let side = 20.0 * holes as f64;
        let islands = (0..holes * holes)
            .map(|k| {
                let c = p(20.0 * (k % holes) as f64 + 10.0, 20.0 * (k / holes) as f64 + 10.0);
                Contour::new(vec![Segment::Arc(Arc::new(c, 4.0, 0.0, -std::f64::consts::TAU))])
            })
            .collect();
        Pocket {
            boundary: Contour::polygon(&[p(0.0, 0.0), p(side, 0.0), p(side, side), p(0.0, side)]),
            islands,
        }
    }

    #[test]
    fn the_space_between_four_holes_is_cleared_from_its_middle() {
        let params = ClearParams {
            tool_radius: 3.0,
            stepover: 2.4,
            allowance: 0.0,
        };
        let plan = plan_pocket(&plate(3), &params, &Tolerance::default()).unwrap();
        // The loops at 7.8 mm between four holes are gone: a path through the middle of each
        // of the four spaces instead.
        assert!(plan.parts.iter().all(|p| p.level < 3), "{:?}", plan.distances);
        let spots: Vec<Point> = (plan.parts.iter())
            .flat_map(|p| &p.spots)
            .map(|c| c.path.segments[0].end())
            .collect();
        assert_eq!(spots.len(), 4);
        for s in spots {
            let near =
                (s.x - 20.0).abs().min((s.x - 40.0).abs()) + (s.y - 20.0).abs().min((s.y - 40.0).abs());
            assert!(near < 1e-6, "a spot at {s:?}");
        }
    }

    #[test]
    fn leaves_the_parent_clears_alone_are_dropped_and_an_only_child_is_kept() {
        // Two 16.4 mm squares joined by a corridor 13 mm wide: for a 6 mm tool at 2.4 mm the
        // level at 7.8 mm splits into one leaf in each square, reaching 8.2 mm from the walls,
        // within the tool radius of the level at 5.4 mm: both go. A single square keeps its
        // leaf, its level's only part (see `clear_leaves_from_spots`).
        let p = Point::new;
        let dumbbell = Contour::polygon(&[
            p(0.0, 0.0),
            p(16.4, 0.0),
            p(16.4, 1.7),
            p(36.4, 1.7),
            p(36.4, 0.0),
            p(52.8, 0.0),
            p(52.8, 16.4),
            p(36.4, 16.4),
            p(36.4, 14.7),
            p(16.4, 14.7),
            p(16.4, 16.4),
            p(0.0, 16.4),
        ]);
        let square = Contour::polygon(&[p(0.0, 0.0), p(16.4, 0.0), p(16.4, 16.4), p(0.0, 16.4)]);
        let params = ClearParams {
            tool_radius: 3.0,
            stepover: 2.4,
            allowance: 0.0,
        };
        let plan = |c: &Contour| {
            let pocket = Pocket {
                boundary: c.clone(),
                islands: vec![],
            };
            plan_pocket(&pocket, &params, &Tolerance::default()).unwrap()
        };
        let two = plan(&dumbbell);
        assert_eq!(two.distances, vec![3.0, 5.4], "the level at 7.8 mm is gone");
        assert!(two.parts.iter().all(|p| p.spots.is_empty() && p.level < 2));
        let one = plan(&square);
        assert_eq!(one.distances, vec![3.0, 5.4, 7.8]);
        assert!(one.parts.iter().all(|p| p.spots.is_empty()));
    }

    #[test]
    fn a_spot_is_taken_only_where_the_tool_reaches_all_that_is_left() {
        // A leaf's loop, a rectangle round (10, 10), its parent's reach 0.6 mm inside it. Of
        // half sides 2.5 and 2.5, left is a square of half side 1.9, whose corners are 2.69 mm
        // from its middle: within 0.95 of a 3 mm radius, one point. Of 2.8 and 2.5, left is
        // 2.2 by 1.9, corners 2.91 mm out: no one point, but a pass of 0.31 mm along the
        // middle (√(2.79² − 1.9²) = 2.04 each side of its ends). Of 3.5, no pass either.
        let p = Point::new;
        let rectangle = |w: f64, h: f64| {
            leaf_of(Contour::polygon(&[
                p(10.0 - w, 10.0 - h),
                p(10.0 + w, 10.0 - h),
                p(10.0 + w, 10.0 + h),
                p(10.0 - w, 10.0 + h),
            ]))
        };
        let tol = Tolerance::default();
        let Some(Found::At(Spot { path: point, left })) = spot(&rectangle(2.5, 2.5), 0.6, 3.0, &tol) else {
            panic!("one spot clears it");
        };
        let end = point.segments[0].end();
        assert!(left.is_some(), "what it answers for, to stop short");
        assert!(end.distance(p(10.0, 10.0)) < 1e-9, "the spot at {end:?}");
        assert!(point.segments[0].length() > 0.0);
        let Some(Found::At(Spot {
            path: pass,
            left: None,
        })) = spot(&rectangle(2.8, 2.5), 0.6, 3.0, &tol)
        else {
            panic!("one pass clears it");
        };
        let (a, b) = (pass.segments[0].start(), pass.segments[0].end());
        assert!((a.distance(b) - 0.314).abs() < 1e-2, "{pass:?}");
        assert!((a.y - 10.0).abs() < 1e-6 && (b.y - 10.0).abs() < 1e-6, "{pass:?}");
        for c in [p(7.8, 8.1), p(12.2, 8.1), p(12.2, 11.9), p(7.8, 11.9)] {
            assert!(distance_from_segment(&pass.segments[0], c) <= 2.85 + 1e-9);
        }
        assert!(spot(&rectangle(3.5, 3.5), 0.6, 3.0, &tol).is_none());
        assert!(matches!(
            spot(&rectangle(0.5, 0.5), 0.6, 3.0, &tol),
            Some(Found::Nothing)
        ));
        assert!(
            spot(&rectangle(2.5, 2.5), -0.1, 3.0, &tol).is_none(),
            "a stepover above the radius"
        );
    }

    fn leaf_of(outer: Contour) -> Part {
        Part {
            level: 2,
            distance: 7.8,
            outer,
            holes: vec![],
            children: vec![],
            parent: Some(0),
            cleanups: vec![],
            spots: vec![],
        }
    }

    #[test]
    fn a_long_narrow_leaf_is_cleared_by_a_pass_along_its_middle() {
        // A 12 x 4 leaf, eroded by 0.6: left is 10.8 x 2.8. Its corners are 1.4 off the middle
        // line, within 2.79 of it (the limit less the room for the arcs' samples) over
        // √(2.79² − 1.4²) = 2.413 along: the pass runs from x = 16 − 2.987 to 16 + 2.987.
        let p = Point::new;
        let leaf = leaf_of(Contour::polygon(&[
            p(10.0, 10.0),
            p(22.0, 10.0),
            p(22.0, 14.0),
            p(10.0, 14.0),
        ]));
        let Some(Found::At(Spot { path, .. })) = spot(&leaf, 0.6, 3.0, &Tolerance::default()) else {
            panic!("one pass clears it");
        };
        let Segment::Line(l) = path.segments[0] else {
            panic!("a straight pass");
        };
        assert!(
            (l.start.y - 12.0).abs() < 1e-3 && (l.end.y - 12.0).abs() < 1e-3,
            "{l:?}"
        );
        let (a, b) = (l.start.x.min(l.end.x), l.start.x.max(l.end.x));
        assert!((a - 13.013).abs() < 1e-2 && (b - 18.987).abs() < 1e-2, "{l:?}");
        // Every corner of what is left within 0.95 of the radius of the pass.
        for c in [p(10.6, 10.6), p(21.4, 10.6), p(21.4, 13.4), p(10.6, 13.4)] {
            assert!(distance_from_segment(&path.segments[0], c) <= 2.85 + 1e-9);
        }
        // Bent, an L of two such arms: no straight pass reaches both ends.
        let ell = leaf_of(Contour::polygon(&[
            p(10.0, 10.0),
            p(22.0, 10.0),
            p(22.0, 14.0),
            p(14.0, 14.0),
            p(14.0, 22.0),
            p(10.0, 22.0),
        ]));
        assert!(spot(&ell, 0.6, 3.0, &Tolerance::default()).is_none());
    }
}
