//! Links at depth through what is already cut: from the end of the path just cut, along it to
//! its point nearest the next path, then straight across, where the straight move from where
//! the tool is would come too near a wall.

use crate::clear::Path;
use crate::geom::{closest_param, segment_distance, Line, Point, Segment, Vector};

/// Most pairs of segments measured when looking for the way across (beyond it the linker
/// retracts instead: two loops of a thousand pieces each).
const MAX_PAIRS: usize = 40_000;

/// Most candidate crossings tried, nearest first, each with a test against the walls.
const MAX_TRIES: usize = 8;

/// A way from the end of `last` (the walk just cut, ending where the tool is) to `next`: the
/// moves back along `last` to a point `a` of it, and the point `b` of `next` to go straight to
/// from there, for which `clear(a, b)` holds; the shortest such way over the pairs of nearest
/// points between the two paths' segments (an open `next` is started at one of its ends, so
/// `b` is one of them). `closed` when `last` is a closed walk (it may then be followed either
/// way round).
pub fn along_last(
    last: &[Segment],
    closed: bool,
    next: &Path,
    eps: f64,
    clear: impl Fn(Point, Point) -> bool,
) -> Option<(Vec<Segment>, Point)> {
    if last.is_empty() || next.segments.is_empty() || last.len() * next.segments.len() > MAX_PAIRS {
        return None;
    }
    let lengths: Vec<f64> = last.iter().map(Segment::length).collect();
    let total: f64 = lengths.iter().sum();
    let mut before = 0.0;
    // (length of the way, segment of `last`, parameter on it, point on it, point of `next`)
    let mut candidates: Vec<(f64, usize, f64, Point, Point)> = Vec::new();
    // An open path is walked from one of its ends: those are the only places to arrive at.
    let ends: Vec<Segment> = if next.closed {
        next.segments.clone()
    } else {
        let (first, last_end) = (
            next.segments[0].start(),
            next.segments[next.segments.len() - 1].end(),
        );
        vec![
            Segment::Line(Line::new(first, first)),
            Segment::Line(Line::new(last_end, last_end)),
        ]
    };
    // The MAX_TRIES least costs so far, ascending: a pair whose cost is surely above the
    // last of them cannot be among the ones tried, and is not measured.
    let mut least: Vec<f64> = Vec::with_capacity(MAX_TRIES + 1);
    let end_lengths: Vec<f64> = ends.iter().map(Segment::length).collect();
    for (i, a) in last.iter().enumerate() {
        // The least way back along `last` from a point of `a`.
        let from = total - before - lengths[i];
        let along_least = if closed {
            // min(s, total - s) over s in [before, before + length] is least at an end.
            before.min(from)
        } else {
            from
        };
        for (b, &b_length) in ends.iter().zip(&end_lengths) {
            if least.len() == MAX_TRIES {
                // Every point of a segment is within its length of its start.
                let apart = a.start().distance(b.start()) - lengths[i] - b_length;
                if along_least + apart.max(0.0) > least[MAX_TRIES - 1] {
                    continue;
                }
            }
            let (d, pa, pb) = segment_distance(a, b, eps);
            let t = closest_param(a, pa);
            let s = before + t * lengths[i];
            // The tool is at the end of `last`, which is also its start when it is closed.
            let back = total - s;
            let along = if closed { s.min(back) } else { back };
            candidates.push((along + d, i, t, pa, pb));
            let at = least.partition_point(|&c| c <= along + d);
            if at < MAX_TRIES {
                least.insert(at, along + d);
                least.truncate(MAX_TRIES);
            }
        }
        before += lengths[i];
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (_, i, t, _, b) = candidates
        .into_iter()
        .take(MAX_TRIES)
        .find(|&(_, _, _, a, b)| clear(a, b))?;
    Some((back_along(last, closed, i, t, eps), b))
}

/// The moves from the end of the walk `last` (where the tool is) along it to its point at
/// parameter `t` of segment `i`: back along it, or, when it is `closed` (its end is its start
/// too), forward from its start where that is shorter.
pub fn back_along(last: &[Segment], closed: bool, i: usize, t: f64, eps: f64) -> Vec<Segment> {
    let lengths = last.iter().map(Segment::length);
    let total: f64 = lengths.clone().sum();
    let s: f64 = lengths.take(i).sum::<f64>() + t * last[i].length();
    let forward = closed && s < total - s;
    let mut moves: Vec<Segment> = Vec::new();
    if forward {
        moves.extend(last[..i].iter().copied());
        moves.push(last[i].subsegment(0.0, t));
    } else {
        moves.extend(last[i + 1..].iter().rev().map(Segment::reversed));
        moves.push(last[i].subsegment(t, 1.0).reversed());
    }
    moves.retain(|m| m.length() > eps);
    moves
}

/// The shortest beginning of `walk` (from its start, where the tool is) from whose end the
/// tool may leave it, `may_leave(p)` telling whether it may from the walk's point `p`: the
/// moves to the earliest such point, found by halving to within `resolution` of it, where the
/// points it may leave from are the walk's last stretch (as the points of a convex loop from
/// which a point outside it is seen straight). None when it may not leave even from the
/// walk's end.
pub fn leave_early(
    walk: &[Segment],
    resolution: f64,
    may_leave: impl Fn(Point) -> bool,
) -> Option<Vec<Segment>> {
    leave_early_hinted(walk, resolution, |_, _| true, may_leave)
}

/// [`leave_early`] where `may_leave` is dear to ask and `hint(p, tangent)` cheaply rules out
/// points of the walk the tool surely may not leave from (those of a convex loop before the
/// point where the way on is tangent to it): halving on the hint first, then `may_leave`
/// asked there and a little past it, and halving on it only between.
pub fn leave_early_hinted(
    walk: &[Segment],
    resolution: f64,
    hint: impl Fn(Point, Vector) -> bool,
    may_leave: impl Fn(Point) -> bool,
) -> Option<Vec<Segment>> {
    let total: f64 = walk.iter().map(Segment::length).sum();
    let end = walk.last().map_or(Point::new(f64::NAN, f64::NAN), Segment::end);
    if walk.is_empty() || !may_leave(end) {
        return None;
    }
    let at = |s: f64| along(walk, s);
    let hinted = |s: f64| {
        let (p, t) = at(s);
        hint(p, t)
    };
    let allowed = |s: f64| may_leave(at(s).0);
    // The earliest length the hint allows, and the earliest `may_leave` does.
    let from = if hinted(0.0) {
        0.0
    } else if hinted(total) {
        earliest(0.0, total, resolution, hinted)
    } else {
        total
    };
    let s = if allowed(from) {
        from
    } else {
        let past = (from + 8.0 * resolution).min(total);
        let hi = if allowed(past) { past } else { total };
        earliest(from, hi, resolution, allowed)
    };
    Some(beginning(walk, s))
}

/// The least length in (`lo`, `hi`] at which `ok` holds, to within `resolution`, by halving:
/// `ok(hi)` holds, `ok(lo)` does not.
pub(super) fn earliest(mut lo: f64, mut hi: f64, resolution: f64, ok: impl Fn(f64) -> bool) -> f64 {
    while hi - lo > resolution {
        let mid = 0.5 * (lo + hi);
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The point `s` along `walk` from its start (its end beyond its length) and the direction
/// of travel there.
fn along(walk: &[Segment], s: f64) -> (Point, Vector) {
    match locate(walk, s) {
        Some((i, t)) => (walk[i].point_at(t), walk[i].tangent_at(t)),
        None => match walk.last() {
            Some(m) => (m.end(), m.tangent_at(1.0)),
            None => (Point::new(f64::NAN, f64::NAN), Vector::new(0.0, 0.0)),
        },
    }
}

/// The moves of `walk` from its start to `s` along it.
fn beginning(walk: &[Segment], s: f64) -> Vec<Segment> {
    match locate(walk, s) {
        Some((i, t)) => {
            let mut moves = walk[..i].to_vec();
            if t > 0.0 {
                moves.push(walk[i].subsegment(0.0, t));
            }
            moves
        }
        None => walk.to_vec(),
    }
}

/// Where `s` along `walk` from its start falls: the segment and the parameter on it; none
/// beyond the walk's length.
fn locate(walk: &[Segment], s: f64) -> Option<(usize, f64)> {
    let mut before = 0.0;
    for (i, seg) in walk.iter().enumerate() {
        let l = seg.length();
        if before + l >= s {
            let t = if l > 0.0 {
                ((s - before) / l).clamp(0.0, 1.0)
            } else {
                0.0
            };
            return Some((i, t));
        }
        before += l;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Contour;

    fn square(x: f64, y: f64, w: f64) -> Vec<Segment> {
        let p = Point::new;
        Contour::polygon(&[p(x, y), p(x + w, y), p(x + w, y + w), p(x, y + w)]).segments
    }

    #[test]
    fn the_way_follows_the_loop_just_cut_to_where_the_next_is_nearest() {
        // The tool is back at (0, 0) after a 10 mm square; the next square is to the right.
        let last = square(0.0, 0.0, 10.0);
        let next = Path {
            segments: square(14.0, 2.0, 6.0),
            closed: true,
        };
        let (moves, b) = along_last(&last, true, &next, 1e-9, |_, _| true).unwrap();
        // Along the bottom edge (the shorter way round) to its corner (10, 0), then 4.47 mm
        // across to the next square's corner (14, 2): 14.47 mm, shorter than going on up the
        // right edge to face the next square 4 mm away.
        assert_eq!(moves[0].start(), Point::new(0.0, 0.0));
        for w in moves.windows(2) {
            assert!(w[0].end().distance(w[1].start()) < 1e-12);
        }
        let end = moves.last().unwrap().end();
        assert!(end.distance(Point::new(10.0, 0.0)) < 1e-9, "{end:?}");
        assert!(b.distance(Point::new(14.0, 2.0)) < 1e-9, "{b:?}");
        // With the corner forbidden, the way goes on up the right edge.
        let (moves, b) = along_last(&last, true, &next, 1e-9, |a, _| a.y > 0.5).unwrap();
        let end = moves.last().unwrap().end();
        assert!(
            end.x == 10.0 && end.y > 0.5 && (b.x - 14.0).abs() < 1e-9,
            "{end:?} {b:?}"
        );
    }

    #[test]
    fn the_tool_leaves_a_walk_at_its_earliest_point_from_which_it_may() {
        let p = Point::new;
        // Along two sides of a 10 mm square from (0, 0), leaving as soon as the tool is on
        // its right side.
        let walk = square(0.0, 0.0, 10.0);
        let moves = leave_early(&walk[..2], 1e-3, |q| q.x >= 10.0 - 1e-12).unwrap();
        let end = moves.last().unwrap().end();
        assert!(end.distance(p(10.0, 0.0)) < 1e-3, "{end:?}");
        assert!(moves.iter().all(|m| m.start().y == 0.0 && m.end().y == 0.0));
        // From the start: no moves; from nowhere: none; from the end of an open walk only
        // (three sides, to (0, 10)): all of it, to within the resolution.
        assert!(leave_early(&walk, 1e-3, |_| true).unwrap().is_empty());
        assert!(leave_early(&walk, 1e-3, |_| false).is_none());
        let moves = leave_early(&walk[..3], 1e-3, |q| q.x < 1e-9 && q.y > 5.0).unwrap();
        assert_eq!(moves.len(), 3);
        assert!(moves[2].end().distance(p(0.0, 10.0)) < 1e-3);
    }

    #[test]
    fn back_along_a_closed_walk_goes_the_shorter_way_round() {
        let p = Point::new;
        // A 10 mm square walked from (0, 0): its point (10, 2) is 12 mm on forward, 28 mm back.
        let walk = square(0.0, 0.0, 10.0);
        let moves = back_along(&walk, true, 1, 0.2, 1e-9);
        assert_eq!(moves.len(), 2);
        assert_eq!(moves[0].start(), p(0.0, 0.0));
        assert!(moves[1].end().distance(p(10.0, 2.0)) < 1e-12);
        // An open walk is only ever followed back: 8 mm down the right edge from (10, 10).
        let moves = back_along(&walk[..2], false, 1, 0.2, 1e-9);
        assert_eq!(moves.len(), 1);
        assert!((moves[0].length() - 8.0).abs() < 1e-12);
    }

    #[test]
    fn a_way_the_walls_forbid_is_not_taken() {
        let last = square(0.0, 0.0, 10.0);
        let next = Path {
            segments: square(14.0, 2.0, 6.0),
            closed: true,
        };
        assert!(along_last(&last, true, &next, 1e-9, |_, _| false).is_none());
        // An open walk is followed back from its end only.
        let (moves, _) = along_last(&last[..2], false, &next, 1e-9, |_, _| true).unwrap();
        assert!(moves.iter().all(|m| m.start().x == 10.0 || m.start().y == 10.0));
    }

    #[test]
    fn an_open_path_is_arrived_at_one_of_its_ends() {
        // A clean-up stroke beside the square: its middle is nearest, but it is walked from an
        // end, and the move across must be to that end (a move to its middle was checked
        // against the walls while the tool went to an end: a gouge on a real drawing).
        let last = square(0.0, 0.0, 10.0);
        let p = Point::new;
        let next = Path {
            segments: vec![
                Segment::Line(Line::new(p(13.0, -6.0), p(13.0, 5.0))),
                Segment::Line(Line::new(p(13.0, 5.0), p(13.0, 16.0))),
            ],
            closed: false,
        };
        let (_, b) = along_last(&last, true, &next, 1e-9, |_, _| true).unwrap();
        assert!(b == p(13.0, -6.0) || b == p(13.0, 16.0), "{b:?}");
    }
}
