//! Small leaves cleared from one spot, or not at all: where a leaf of the tree leaves so little
//! that the tool standing at one point inside it removes all of it, its loop gives way to a
//! short path through that point, a spot of its parent part ([`super::Part::spots`]); where
//! nothing is left for it, it is dropped.
//!
//! Why this leaves nothing: take a leaf part at distance d_k (one outer loop L, no loops round
//! islands, no parts inside), its parent at d_(k−1), and e = d_(k−1) + r. A point p inside L
//! whose distance t to the walls is at most e lies t − d_(k−1) ≤ r from the parent's level
//! along the straight line to its nearest wall (the distance falls as fast as one goes), so
//! the parent's loops sweep it. What they may miss is inside L and farther than e from the
//! walls: the inside of L eroded by δ = e − d_k (at least 0 when the stepover is at most the
//! tool radius, the only case taken here). If that is empty, L sweeps nothing new; if it lies
//! within r of a point c inside L (with a margin), the tool at c sweeps it. Points outside L
//! are no business of L's: within the distance d_k < e, the parent sweeps them.
//!
//! Only leaves with siblings are taken: the linker cuts those after their parent's loops (see
//! `link::schedule`), so their loops eased nothing for the parent. An only child is cut
//! before its parent, the first loop of its branch and a slot; its parent's loop, a stepover
//! out, then cuts a stepover wide. Without the child the parent's loop would be the slot.
//!
//! On the 300-hole plate at 40 % stepover the 266 loops between four holes, 21 mm each, become
//! steps of about 5 mm out from the loop round a hole and back (linking bench: 2586.6 ->
//! 2321.2 s of machining).

use super::{ClearParams, ClearPlan, Part, Path};
use crate::geom::{
    distance_from_segment, enclosing_circle, farthest_from_segment, outline_points, Contour, Line, Point,
    Segment, Tolerance,
};

/// How much nearer than the tool radius the spot must be to everything it answers for, in tool
/// radii: room for rounding (the same as the clean-up paths keep).
const MARGIN_RADII: f64 = super::residue::REACH_MARGIN_RADII;

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
    let mut spots: Vec<Vec<Path>> = vec![Vec::new(); n];
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
                Some(Spot::Nothing) => gone[i] = true,
                Some(Spot::At(path)) => {
                    gone[i] = true;
                    spots[parent].push(path);
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
enum Spot {
    /// Nothing is left for it.
    Nothing,
    /// The tool at the end of this path clears what is.
    At(Path),
}

/// What the leaf `part` leaves beyond its parent's reach, `reach` inside its loop: None when
/// one spot does not clear it (or the leaf cannot be eroded).
fn spot(part: &Part, reach: f64, r: f64, tol: &Tolerance) -> Option<Spot> {
    if reach < 0.0 {
        return None;
    }
    let left = if reach > 0.0 {
        crate::offset::offset_contour(&part.outer, reach, tol).ok()?
    } else {
        vec![part.outer.clone()]
    };
    if left.is_empty() {
        return Some(Spot::Nothing);
    }
    let limit = r * (1.0 - MARGIN_RADII);
    let segments = || left.iter().flat_map(|c| c.segments.iter());
    let b = left.iter().map(Contour::bbox).reduce(|a, b| a.union(&b))?;
    if b.width() > 2.0 * limit || b.height() > 2.0 * limit {
        return None;
    }
    let points: Vec<Point> = left.iter().flat_map(|c| outline_points(&c.segments)).collect();
    let (c, _) = enclosing_circle(&points)?;
    if segments().any(|s| farthest_from_segment(s, c) > limit) || !part.outer.contains(c) {
        return None;
    }
    // The nearest point of the loop: the path runs from c towards it, inside the loop.
    let (room, q) = (part.outer.segments.iter())
        .map(|s| (distance_from_segment(s, c), crate::geom::closest_point(s, c)))
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    let length = room.min(SPOT_LENGTH_RADII * r);
    let toward = (q - c).normalized()?;
    if length < 1e-3 * r {
        return None;
    }
    let start = Point::new(c.x + toward.x * length, c.y + toward.y * length);
    Some(Spot::At(Path {
        segments: vec![Segment::Line(Line::new(start, c))],
        closed: false,
    }))
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
            .map(|c| c.segments[0].end())
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
        // A leaf's loop, a square of half side 2.5 round (10, 10), its parent's reach 0.6 mm
        // inside it: left is a square of half side 1.9, whose corners are 2.69 mm from its
        // middle, within 0.95 of a 3 mm radius. Of half side 2.2 the corners are 3.11 mm away.
        let p = Point::new;
        let square = |h: f64| {
            Contour::polygon(&[
                p(10.0 - h, 10.0 - h),
                p(10.0 + h, 10.0 - h),
                p(10.0 + h, 10.0 + h),
                p(10.0 - h, 10.0 + h),
            ])
        };
        let leaf = |h: f64| Part {
            level: 2,
            distance: 7.8,
            outer: square(h),
            holes: vec![],
            children: vec![],
            parent: Some(0),
            cleanups: vec![],
            spots: vec![],
        };
        let tol = Tolerance::default();
        match spot(&leaf(2.5), 0.6, 3.0, &tol) {
            Some(Spot::At(path)) => {
                let end = path.segments[0].end();
                assert!(end.distance(p(10.0, 10.0)) < 1e-9, "the spot at {end:?}");
                assert!(path.segments[0].start().distance(end) > 0.0);
            }
            _ => panic!("one spot clears it"),
        }
        assert!(spot(&leaf(2.8), 0.6, 3.0, &tol).is_none());
        assert!(matches!(spot(&leaf(0.5), 0.6, 3.0, &tol), Some(Spot::Nothing)));
        assert!(
            spot(&leaf(2.5), -0.1, 3.0, &tol).is_none(),
            "a stepover above the radius"
        );
    }
}
