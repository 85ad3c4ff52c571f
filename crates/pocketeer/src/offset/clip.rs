//! Cutting away, before the split, the parts of raw pieces that are provably nearer than d to
//! the profile: the fallback when a raw offset has too many crossings to split whole.
//!
//! Where a profile has sharp detail much finer than d, or near the deepest point of a pocket
//! drawn with many elements, most raw pieces cross most others and the split is Θ(n²). Nearly
//! all of those crossings lie in parts that are invalid anyway. A part every point of which
//! is nearer than d to the profile can go before the split without changing the result: a
//! valid piece ends only where it meets another raw piece at distance exactly d from the
//! profile, never on such a part, so every crossing that bounds a valid piece survives.

use super::split::Nodes;
use crate::geom::{Piece, SegmentIndex};

/// How many times a piece is halved at most while looking for invalid parts.
const DEPTH: u32 = 10;

/// The most tests in all (a few seconds): the fallback must stay bounded too.
const WORK: u64 = 4_000_000;

/// The pieces with their provably invalid parts removed. A piece cut into parts gets fresh
/// nodes at the cuts; consecutive kept parts stay one piece.
///
/// Distance to the profile changes by at most the arc length moved, so a part of half length
/// h whose middle is nearer than `d - slack - h` to the profile is nearer than `d - slack`
/// everywhere. A piece is halved at most [`DEPTH`] times; `None` when that would take more
/// than [`WORK`] tests in all.
pub fn clip_invalid(
    pieces: &[Piece],
    walls: &SegmentIndex,
    d: f64,
    slack: f64,
    nodes: &mut Nodes,
) -> Option<Vec<Piece>> {
    let mut out = Vec::with_capacity(pieces.len());
    let mut spans = Vec::new();
    let mut work = 0;
    for p in pieces {
        spans.clear();
        keep_spans(p, walls, d - slack, (0.0, 1.0), DEPTH, (&mut spans, &mut work));
        if work > WORK {
            return None;
        }
        // Merge neighbouring spans.
        let mut merged: Vec<(f64, f64)> = Vec::with_capacity(spans.len());
        for &(a, b) in &spans {
            match merged.last_mut() {
                Some(last) if last.1 == a => last.1 = b,
                _ => merged.push((a, b)),
            }
        }
        for (a, b) in merged {
            let start = if a == 0.0 { p.start } else { nodes.add() };
            let end = if b == 1.0 { p.end } else { nodes.add() };
            let segment = if a == 0.0 && b == 1.0 {
                p.segment
            } else {
                p.segment.subsegment(a, b)
            };
            out.push(Piece {
                segment,
                start,
                end,
                source: p.source,
            });
        }
    }
    Some(out)
}

/// True when every point of every one of `pieces` is proven nearer than `r` to the profile
/// by halving each piece (see [`clip_invalid`]) at most [`EMPTY_DEPTH`] times, within `work`
/// distances measured in all; stops at the first span not proven so. Then no piece of the
/// offset at a distance d with d − slack ≥ `r` is valid: a run is judged by the middle of one
/// of its pieces, a point of a raw piece, and goes when that is nearer than d − slack.
///
/// The proof of an empty level: beyond the deepest point of a region, where every raw piece
/// crosses many others, splitting and judging them costs more than any level with loops.
///
/// The pieces are taken a stride apart, then the ones after those, and so on: a level with
/// loops, asked in vain, stops sooner where its few valid pieces run together.
pub fn all_invalid(pieces: &[Piece], walls: &SegmentIndex, r: f64, mut work: u64) -> bool {
    let stride = (pieces.len() as f64).sqrt() as usize + 1;
    (0..stride)
        .flat_map(|first| pieces.iter().skip(first).step_by(stride))
        .all(|p| {
            let mut hint = None;
            invalid_span(p, walls, r, (0.0, 1.0), EMPTY_DEPTH, (&mut work, &mut hint))
        })
}

/// How many times [`all_invalid`] halves a piece at most: a span of a four-thousandth of the
/// piece's length is proven when its middle is that much nearer than `r`.
const EMPTY_DEPTH: u32 = 12;

/// True when the span `(lo, hi)` of `p` is proven nearer than `r` to the profile everywhere,
/// halving it at most `depth` times while `work` lasts; `hint`: the wall that answered last.
fn invalid_span(
    p: &Piece,
    walls: &SegmentIndex,
    r: f64,
    (lo, hi): (f64, f64),
    depth: u32,
    (work, hint): (&mut u64, &mut Option<usize>),
) -> bool {
    // Room for the rounding of the distance measured: a millionth of a micrometre for 1 m.
    let margin = 1e-12 * r.abs().max(1.0);
    let mut measured = 0;
    let proven = span_near(p, walls, r, (lo, hi), margin, (&mut measured, &mut *hint));
    *work = work.saturating_sub(measured);
    if proven {
        return true;
    }
    if depth == 0 || *work == 0 {
        return false;
    }
    let mid = 0.5 * (lo + hi);
    invalid_span(p, walls, r, (lo, mid), depth - 1, (&mut *work, &mut *hint))
        && invalid_span(p, walls, r, (mid, hi), depth - 1, (work, hint))
}

/// True when every point of the span `(lo, hi)` of `p` is shown nearer than `r` to the
/// profile by the span's middle: the distance changes no faster than the point moves along
/// the piece, so a middle nearer than r − h (h: the span's half length) less `margin` shows
/// it. `measured` and `hint` as in [`SegmentIndex::any_within_hinted`].
fn span_near(
    p: &Piece,
    walls: &SegmentIndex,
    r: f64,
    (lo, hi): (f64, f64),
    margin: f64,
    (measured, hint): (&mut u64, &mut Option<usize>),
) -> bool {
    let within = r - 0.5 * (hi - lo) * p.segment.length() - margin;
    within > 0.0 && walls.any_within_hinted(p.segment.point_at(0.5 * (lo + hi)), within, measured, hint)
}

/// Appends to `out`, in order, the spans of `(lo, hi)` on `p` not proven nearer than `r` to
/// the profile.
fn keep_spans(
    p: &Piece,
    walls: &SegmentIndex,
    r: f64,
    (lo, hi): (f64, f64),
    depth: u32,
    (out, work): (&mut Vec<(f64, f64)>, &mut u64),
) {
    if *work > WORK {
        out.push((lo, hi));
        return;
    }
    *work += 1;
    if span_near(p, walls, r, (lo, hi), 0.0, (&mut 0, &mut None)) {
        return;
    }
    if depth == 0 {
        out.push((lo, hi));
        return;
    }
    let mid = 0.5 * (lo + hi);
    keep_spans(p, walls, r, (lo, mid), depth - 1, (&mut *out, &mut *work));
    keep_spans(p, walls, r, (mid, hi), depth - 1, (out, work));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Contour, Line, Point, PreparedPocket, Segment, Source, Tolerance};

    #[test]
    fn a_level_beyond_the_deepest_point_is_proven_empty_and_one_short_of_it_is_not() {
        // Holes of radius 4 at a 20 mm pitch, 3 x 3 in a 60 mm square: the deepest points lie
        // between four holes, 10√2 − 4 = 10.142 mm from them.
        let p = Point::new;
        let mut loops = vec![Contour::polygon(&[
            p(0.0, 0.0),
            p(60.0, 0.0),
            p(60.0, 60.0),
            p(0.0, 60.0),
        ])];
        for k in 0..9 {
            let c = p(20.0 * (k % 3) as f64 + 10.0, 20.0 * (k / 3) as f64 + 10.0);
            loops.push(Contour::new(vec![Segment::Arc(Arc::new(
                c,
                4.0,
                0.0,
                -std::f64::consts::TAU,
            ))]));
        }
        let region = PreparedPocket::from_loops(loops);
        let tol = Tolerance::default();
        let deepest = 200f64.sqrt() - 4.0;
        let raw = |d: f64| {
            let (mut pieces, mut next) = (Vec::new(), 0);
            for (k, c) in region.contours().iter().enumerate() {
                let (more, n) = super::super::raw::raw_offset(c, d, &tol, next, 10 * k, &|_| true);
                pieces.extend(more);
                next = n;
            }
            pieces
        };
        for (d, empty) in [(deepest + 0.01, true), (deepest - 0.01, false), (5.0, false)] {
            let pieces = raw(d);
            let slack = super::super::prune::slack(d, &tol);
            let proven = all_invalid(&pieces, region.walls(), d - slack, 64 * pieces.len() as u64);
            assert_eq!(proven, empty, "at {d}");
            assert_eq!(
                region.offset(d, &tol).unwrap().is_empty(),
                empty,
                "the offset at {d}"
            );
        }
        // Too little work to prove it: not proven.
        let pieces = raw(deepest + 0.01);
        let slack = super::super::prune::slack(deepest + 0.01, &tol);
        assert!(!all_invalid(&pieces, region.walls(), deepest + 0.01 - slack, 100));
    }

    #[test]
    fn the_part_near_the_profile_goes_and_the_rest_keeps_its_ends() {
        let p = Point::new;
        // The profile: a square 10 across; a piece along y = -1 from x = -20 to 20.
        let square = Contour::polygon(&[p(0.0, 0.0), p(10.0, 0.0), p(10.0, 10.0), p(0.0, 10.0)]);
        let walls = SegmentIndex::new(&square.segments);
        let piece = Piece {
            segment: Segment::Line(Line::new(p(-20.0, -1.0), p(20.0, -1.0))),
            start: 0,
            end: 1,
            source: Source::Joint(7),
        };
        let mut nodes = Nodes::new(2);
        let kept = clip_invalid(&[piece], &walls, 2.0, 0.0, &mut nodes).unwrap();
        assert_eq!(kept.len(), 2);
        assert_eq!((kept[0].start, kept[1].end), (0, 1));
        assert!(kept.iter().all(|k| k.source == Source::Joint(7)));
        // Invalid (nearer than 2) exactly for -√3 < x < 10 + √3: what went lies inside that,
        // and most of it went.
        let cut0 = kept[0].segment.end().x;
        let cut1 = kept[1].segment.start().x;
        let root3 = 3f64.sqrt();
        assert!((-root3..-1.0).contains(&cut0), "{cut0}");
        assert!((10.7..=10.0 + root3).contains(&cut1), "{cut1}");
    }
}
