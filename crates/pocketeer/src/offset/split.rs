//! Breaking the raw offset (paper §5): every piece is cut where it meets another, found through
//! a spatial index, so that afterwards no two pieces cross.

use crate::geom::{
    for_each_overlapping_pair, intersect, Aabb, Intersection, Intersections, Line, Piece, Point, Segment,
    Tolerance,
};
use crate::union_find::UnionFind;

/// Node ids, united where pieces meet.
pub type Nodes = UnionFind;

/// A cut on a piece.
#[derive(Debug, Clone, Copy)]
struct Cut {
    /// Where on the piece, as its parameter.
    t: f64,
    /// The node the pieces on both sides of the cut share.
    node: usize,
    /// The point.
    point: Point,
}

/// A piece's end nodes as united so far and its element (a joint's pieces count as their
/// element's).
#[derive(Debug, Clone, Copy)]
struct Ends {
    start: usize,
    end: usize,
    element: usize,
}

use crate::geom::TOUCH;

/// How far [`split`] got before giving up.
#[derive(Debug, Clone, Copy)]
pub struct Overrun {
    /// Box comparisons made.
    pub tests: u64,
    /// Crossings found.
    pub crossings: usize,
    /// The piece reached.
    pub at: usize,
}

/// Cuts every piece where it meets another. Pieces meeting at a cut share its node; a cut at a
/// piece's end is that end's node. Pieces not joined end to start also meet where they come
/// within [`TOUCH`], if they are of elements that are not neighbours (by their
/// [`crate::geom::Source`]s) or run opposite ways there.
///
/// Gives up when finding the pairs to intersect would take more than `budget.0` box
/// comparisons or the pieces cross more than `budget.1` times (pieces overlapping by the
/// thousand: a profile with sharp detail much finer than the distance), returning the
/// [`Overrun`].
pub fn split(
    pieces: &[Piece],
    nodes: &mut Nodes,
    tol: &Tolerance,
    budget: (u64, usize),
) -> Result<Vec<Piece>, Overrun> {
    let near_end = tol.rounding();
    let touch = tol.eps.max(TOUCH);
    let pieces = without_points(pieces, nodes, near_end);
    let pieces = &pieces[..];
    let boxes: Vec<Aabb> = pieces.iter().map(|p| p.segment.bbox().inflated(touch)).collect();
    // All cuts in one list, (piece, cut), sorted afterwards: far fewer allocations than a
    // list per piece.
    let mut cuts: Vec<(usize, Cut)> = Vec::new();
    // The node for parameter t on piece i: its end node when t is at an end, else None.
    let end_node = |i: usize, t: f64| -> Option<usize> {
        let len = pieces[i].segment.length();
        if t * len <= near_end {
            Some(pieces[i].start)
        } else if (1.0 - t) * len <= near_end {
            Some(pieces[i].end)
        } else {
            None
        }
    };
    // Dropped points have joined their neighbours' nodes.
    let ends: Vec<Ends> = pieces
        .iter()
        .map(|p| Ends {
            start: nodes.find(p.start),
            end: nodes.find(p.end),
            element: p.source.element() as usize,
        })
        .collect();
    let sweep = for_each_overlapping_pair(&boxes, budget.0, |i, j| {
        // Joined end to start, or of one element or neighbouring ones: see `meetings`.
        let (a, b) = (ends[i], ends[j]);
        let joined = a.end == b.start || b.end == a.start;
        let neighbours = a.element.abs_diff(b.element) <= 1;
        let hits = meetings(
            &pieces[i].segment,
            &pieces[j].segment,
            joined,
            neighbours,
            tol.eps,
            touch,
        );
        for h in hits.iter() {
            let (first, second) = match h {
                Intersection::Point { point, ta, tb } => ((ta, tb, point), None),
                Intersection::Overlap { a, b } => {
                    let s = &pieces[i].segment;
                    ((a.0, b.0, s.point_at(a.0)), Some((a.1, b.1, s.point_at(a.1))))
                }
            };
            for (ta, tb, p) in std::iter::once(first).chain(second) {
                let node = match (end_node(i, ta), end_node(j, tb)) {
                    (Some(x), Some(y)) => {
                        nodes.union(x, y);
                        x
                    }
                    (Some(x), None) | (None, Some(x)) => x,
                    (None, None) => nodes.add(),
                };
                if end_node(i, ta).is_none() {
                    cuts.push((
                        i,
                        Cut {
                            t: ta,
                            node,
                            point: p,
                        },
                    ));
                }
                if end_node(j, tb).is_none() {
                    cuts.push((
                        j,
                        Cut {
                            t: tb,
                            node,
                            point: p,
                        },
                    ));
                }
            }
        }
        cuts.len() <= budget.1.saturating_mul(2)
    });
    if let Err(crate::geom::Stopped { tests, at }) = sweep {
        return Err(Overrun {
            tests,
            crossings: cuts.len() / 2,
            at,
        });
    }
    Ok(cut_at(pieces, cuts, nodes, near_end))
}

/// `pieces` without those shorter than `near_end`: each is a point where the pieces before
/// and after it meet, and its ends become one node.
fn without_points<'a>(
    pieces: &'a [Piece],
    nodes: &mut Nodes,
    near_end: f64,
) -> std::borrow::Cow<'a, [Piece]> {
    if !pieces.iter().any(|p| p.segment.length() <= near_end) {
        return std::borrow::Cow::Borrowed(pieces);
    }
    for p in pieces.iter().filter(|p| p.segment.length() <= near_end) {
        nodes.union(p.start, p.end);
    }
    std::borrow::Cow::Owned(
        pieces
            .iter()
            .filter(|p| p.segment.length() > near_end)
            .copied()
            .collect(),
    )
}

/// Where two pieces meet, with the tolerance that fits how they lie. Pieces `joined` end to
/// start are one offset curve going on (tangent where an element runs smoothly into the
/// next): near their node they stay within TOUCH of each other for a while without meeting,
/// and only rounding (`eps`) decides their crossings. Likewise pieces of one element or of
/// `neighbours` where the profile runs on smoothly: their offsets stay near each other for a
/// while, running the same way. Where neighbours turn back at their joint (a hairpin: two
/// walls 2d apart that meet), their offsets come near each other running opposite ways, as
/// those of any walls 2d apart do, and meet within `touch`, as all other pieces do.
fn meetings(
    si: &Segment,
    sj: &Segment,
    joined: bool,
    neighbours: bool,
    eps: f64,
    touch: f64,
) -> Intersections {
    if joined {
        return intersect(si, sj, eps);
    }
    if !neighbours {
        return intersect(si, sj, touch);
    }
    let near = intersect(si, sj, touch);
    let opposed = |h: Intersection| {
        let (ta, tb) = match h {
            Intersection::Point { ta, tb, .. } => (ta, tb),
            Intersection::Overlap { a, b } => (a.0, b.0),
        };
        si.tangent_at(ta).dot(sj.tangent_at(tb)) < 0.0
    };
    // Nothing within TOUCH is nothing within eps either: no second try then.
    if near.iter().all(opposed) {
        near
    } else {
        intersect(si, sj, eps)
    }
}

/// The pieces cut at `cuts` ((piece, cut), in any order): two cuts at one place are one node.
fn cut_at(pieces: &[Piece], mut cuts: Vec<(usize, Cut)>, nodes: &mut Nodes, near_end: f64) -> Vec<Piece> {
    cuts.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.t.total_cmp(&b.1.t)));
    let mut out = Vec::with_capacity(pieces.len() + cuts.len());
    let mut next = 0;
    for (i, piece) in pieces.iter().enumerate() {
        let first = next;
        while next < cuts.len() && cuts[next].0 == i {
            next += 1;
        }
        if first == next {
            out.push(*piece);
            continue;
        }
        let s = &piece.segment;
        let mut prev = Cut {
            t: 0.0,
            node: piece.start,
            point: s.start(),
        };
        let last = Cut {
            t: 1.0,
            node: piece.end,
            point: s.end(),
        };
        let at = cuts[first..next].iter().map(|c| c.1);
        for cut in at.chain(std::iter::once(last)) {
            if (cut.t - prev.t) * s.length() <= near_end {
                // Two cuts at one place: one node.
                nodes.union(prev.node, cut.node);
                continue;
            }
            out.push(Piece {
                segment: between(s, prev, cut),
                start: prev.node,
                end: cut.node,
                source: piece.source,
            });
            prev = cut;
        }
    }
    out
}

/// The part of `s` between two cuts, a line ending exactly on the cut points.
fn between(s: &Segment, a: Cut, b: Cut) -> Segment {
    match s {
        Segment::Line(_) => Segment::Line(Line::new(a.point, b.point)),
        Segment::Arc(_) => s.subsegment(a.t, b.t),
    }
}
