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
    let half = 0.5 * (hi - lo) * p.segment.length();
    let mid = 0.5 * (lo + hi);
    if *work > WORK {
        out.push((lo, hi));
        return;
    }
    *work += 1;
    if r - half > 0.0 && walls.any_within(p.segment.point_at(mid), r - half) {
        return;
    }
    if depth == 0 {
        out.push((lo, hi));
        return;
    }
    keep_spans(p, walls, r, (lo, mid), depth - 1, (&mut *out, &mut *work));
    keep_spans(p, walls, r, (mid, hi), depth - 1, (out, work));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Contour, Line, Point, Segment, Source};

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
