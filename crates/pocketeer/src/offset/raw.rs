//! Raw offset (paper §4): every line moved sideways by d, every arc's radius changed by d, and
//! an arc of radius d around every joint where the moved elements part.

use crate::geom::Source;
use crate::geom::NEAR_REVERSAL;
use crate::geom::{intersect, Arc, Contour, Intersection, Line, Piece, Segment, Tolerance};
use std::f64::consts::PI;

/// The raw offset of a closed contour by `d` to its left (the side the material to remove is
/// on), as a closed ring of pieces whose node ids start at `next_node`; returns the pieces and
/// the next free id.
///
/// Each piece's `source` says what made it: `Element(base + k)` for the moved element k of
/// the contour, `Joint(base + k)` for the joint at the end of element k (`base`: the index of
/// the contour's first element among all elements offset together).
///
/// Only the pieces `wanted` allows are returned: a moved element when its source is wanted, a
/// joint's pieces when the joint or a moved element beside it is, so that the ring does not
/// open where a loop may still run through it. The trimming of moved elements is worked out
/// along the whole ring (it depends on the neighbours), so the pieces returned are those of
/// the whole ring (only the node ids of the ends differ).
///
/// Consecutive moved elements share a node where they meet. Where they part (a turn to the
/// right), an arc of radius d around the joint closes the gap; where they overlap (a turn to the
/// left) or an element collapsed, a short line joins their ends, and the split stage cuts the
/// overlap away. Every ring is closed, so a crossing missed by rounding at a nearly tangent
/// joint cannot break a loop open.
pub fn raw_offset(
    contour: &Contour,
    d: f64,
    tol: &Tolerance,
    mut next_node: usize,
    base: usize,
    wanted: &dyn Fn(Source) -> bool,
) -> (Vec<Piece>, usize) {
    let segs = &contour.segments;
    // The moved elements that did not collapse, with the index of their original.
    let moved: Vec<(usize, Segment)> = segs
        .iter()
        .enumerate()
        .filter_map(|(k, s)| offset_segment(s, d, tol).map(|m| (k, m)))
        .collect();
    let n = moved.len();
    if n == 0 {
        return (Vec::new(), next_node);
    }
    // Consecutive moved elements k and j follow each other in the contour, across the points
    // dropped between them if any; a joint needs two of them (a lone element among points
    // closes on itself, j = k, unless it is the whole contour, a circle).
    let adjacent = |k: usize, j: usize| k != j || segs.len() == 1;
    let Trims { from, to, joint } = trims(segs, &moved, d, tol, &adjacent);
    let first = next_node;
    next_node += n;
    // Node at the start of moved element i is first + i; its end is the next one's start, with
    // a joining piece between them where they do not meet.
    let mut pieces = Vec::with_capacity(2 * n);
    let element_wanted = |i: usize| wanted(Source::Element((base + moved[i].0) as u32));
    for i in 0..n {
        let (k, a) = moved[i];
        let (j, b) = moved[(i + 1) % n];
        let (want_element, want_joint) = {
            let own = element_wanted(i);
            let joint = own || element_wanted((i + 1) % n) || wanted(Source::Joint((base + k) as u32));
            (own, joint)
        };
        if !want_element && !want_joint {
            continue;
        }
        let a = if from[i] > 0.0 || to[i] < 1.0 {
            a.subsegment(from[i], to[i])
        } else {
            a
        };
        let start = first + i;
        let next_start = first + (i + 1) % n;
        let meets = joint[i] == Joint::Meet;
        let end = if meets {
            next_start
        } else {
            next_node += 1;
            next_node - 1
        };
        if want_element {
            pieces.push(Piece {
                segment: a,
                start,
                end,
                source: Source::Element((base + k) as u32),
            });
        }
        if meets || !want_joint {
            continue;
        }
        let b_start = if from[(i + 1) % n] > 0.0 {
            b.point_at(from[(i + 1) % n])
        } else {
            b.start()
        };
        let source = Source::Joint((base + k) as u32);
        let ends = (a.end(), b_start, end, next_start);
        let adjacent = adjacent(k, j);
        next_node = joining(
            &segs[k],
            &segs[j],
            d,
            adjacent,
            joint[i],
            ends,
            source,
            next_node,
            &mut pieces,
        );
    }
    (pieces, next_node)
}

/// How each moved element and the next come together, and how far each is trimmed.
struct Trims {
    /// Where moved element i starts, as a parameter of it (0: not trimmed).
    from: Vec<f64>,
    /// Where it ends (1: not trimmed).
    to: Vec<f64>,
    /// How moved element i and the next one come together.
    joint: Vec<Joint>,
}

/// Works out the [`Trims`] of the `moved` elements of `segs` (each with the index of its
/// original) at distance `d`; `adjacent(k, j)` tells whether originals k and j share a joint.
fn trims(
    segs: &[Segment],
    moved: &[(usize, Segment)],
    d: f64,
    tol: &Tolerance,
    adjacent: &dyn Fn(usize, usize) -> bool,
) -> Trims {
    // Where the moved elements overlap at a turn to the left, trim both to their crossing
    // nearest the joint (so they meet in one node), as long as each keeps some length.
    let n = moved.len();
    let mut from = vec![0.0; n];
    let mut to = vec![1.0; n];
    // How moved element i and the next one come together.
    let mut joint = vec![Joint::Apart; n];
    for i in 0..n {
        let (k, a) = moved[i];
        let (j, b) = moved[(i + 1) % n];
        if a.end().distance(b.start()) <= tol.rounding() {
            joint[i] = Joint::Meet;
            continue;
        }
        if !adjacent(k, j) {
            continue;
        }
        if right_turn(&segs[k], &segs[j], d) {
            joint[i] = Joint::RightTurn;
            continue;
        }
        if n < 2 {
            continue;
        }
        let corner = segs[k].end();
        let crossing = intersect(&a, &b, tol.eps)
            .iter()
            .filter_map(|h| match h {
                Intersection::Point { point, ta, tb } => Some((point, ta, tb)),
                Intersection::Overlap { .. } => None,
            })
            .filter(|&(_, ta, tb)| ta > from[i] && tb < to[(i + 1) % n])
            .min_by(|x, y| x.0.distance(corner).total_cmp(&y.0.distance(corner)));
        if let Some((_, ta, tb)) = crossing {
            to[i] = ta;
            from[(i + 1) % n] = tb;
            joint[i] = Joint::Meet;
        }
    }
    Trims { from, to, joint }
}

/// The pieces joining moved element a (of original `seg_k`) to the next one b (of `seg_j`)
/// where they do not meet, from node `end` at `a_end` to node `next_start` at `b_start`, and
/// the next free node id: a tip arc at a needle (see `tip_arc`), an arc of radius `d` round
/// the joint where they part (a right turn), else a straight line that the split stage cuts
/// away with the overlap.
#[allow(clippy::too_many_arguments)]
fn joining(
    seg_k: &Segment,
    seg_j: &Segment,
    d: f64,
    adjacent: bool,
    joint: Joint,
    (a_end, b_start, end, next_start): (crate::geom::Point, crate::geom::Point, usize, usize),
    source: Source,
    mut next_node: usize,
    pieces: &mut Vec<Piece>,
) -> usize {
    let turns_right = joint == Joint::RightTurn;
    // A needle tip whose moved sides do not cross: see `tip_arc`.
    if adjacent && !turns_right && near_reversal(seg_k, seg_j) {
        let (arc, whole) = tip_arc(seg_k.end(), d, a_end, b_start);
        let arc = Segment::Arc(arc);
        let parts: Vec<(Segment, usize, usize)> = if whole {
            vec![(arc, end, next_start)]
        } else {
            // Chord, arc, chord: the chords are judged alone, the arc with its run.
            let (n1, n2) = (next_node, next_node + 1);
            next_node += 2;
            let chord = |p: crate::geom::Point, q: crate::geom::Point| Segment::Line(Line::new(p, q));
            vec![
                (chord(a_end, arc.start()), end, n1),
                (arc, n1, n2),
                (chord(arc.end(), b_start), n2, next_start),
            ]
        };
        for (segment, start, end) in parts {
            pieces.push(Piece {
                segment,
                start,
                end,
                source,
            });
        }
        return next_node;
    }
    let join = if turns_right {
        // The moved elements part: an arc of radius d around the joint, turning the same way.
        let corner = seg_k.end();
        let (a0, sweep) = clockwise_sweep(corner, a_end, b_start);
        Segment::Arc(Arc::new(corner, d, a0, sweep))
    } else {
        Segment::Line(Line::new(a_end, b_start))
    };
    pieces.push(Piece {
        segment: join,
        start: end,
        end: next_start,
        source,
    });
    next_node
}

/// How two moved elements, consecutive in the ring, come together at the joint between them.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Joint {
    /// They meet (end to start, or trimmed to their crossing).
    Meet,
    /// They part at a right turn of the contour: a node arc closes the gap.
    RightTurn,
    /// Neither: a joining chord (or a tip's arc) closes the gap.
    Apart,
}

/// True when the contour turns back within [`NEAR_REVERSAL`] of a full reversal at the joint
/// from `a` into `b`.
fn near_reversal(a: &Segment, b: &Segment) -> bool {
    let (t_in, t_out) = (a.tangent_at(1.0), b.tangent_at(0.0));
    t_in.dot(t_out) < 0.0 && t_in.cross(t_out).abs() <= NEAR_REVERSAL
}

/// The part of the circle of radius `d` round a needle tip `corner` that is at distance d
/// from both sides, when the moved sides (ending at `from`, starting at `to`) do not cross;
/// and whether it is all of the sweep.
///
/// Going clockwise from `from` round the tip to `to` sweeps π + α (α: how far the turn falls
/// short of a reversal). The first and last α lie over the sides themselves, nearer than d to
/// them on their outer side, which no raw piece bounds; the π between is at distance d from
/// both, an exact offset of the tip, and is kept as an arc. Were the whole sweep one arc, a run
/// judged by one point could keep its ends; were it a chord, it would pass through the tip and
/// lose the loop where the tip is a slit into material (for a needle of material the arc lies
/// outside the region and goes). When the sweep is not past π the tangents turn right after
/// all (the curvature said otherwise): the moved sides part, and the whole sweep is the arc.
fn tip_arc(
    corner: crate::geom::Point,
    d: f64,
    from: crate::geom::Point,
    to: crate::geom::Point,
) -> (Arc, bool) {
    let (a0, sweep) = clockwise_sweep(corner, from, to);
    let alpha = -sweep - PI;
    if alpha > 0.0 {
        (Arc::new(corner, d, a0 - alpha, -PI), false)
    } else {
        (Arc::new(corner, d, a0, sweep), true)
    }
}

/// The angle of `from` seen from `corner`, and the clockwise sweep (in (-2π, 0]) round
/// `corner` from `from` to `to`: how a node arc turns.
fn clockwise_sweep(
    corner: crate::geom::Point,
    from: crate::geom::Point,
    to: crate::geom::Point,
) -> (f64, f64) {
    let (u, v) = (from - corner, to - corner);
    // The counter-clockwise angle from u to v, in (-π, π], taken clockwise.
    let turn = u.cross(v).atan2(u.dot(v));
    let sweep = if turn > 0.0 { turn - 2.0 * PI } else { turn };
    (u.angle(), sweep)
}

/// True when the contour turns right from `a` into `b`, or turns straight back in a cusp that
/// opens to the right at the scale of the offset, or cannot be told.
///
/// Near a reversal (within [`NEAR_REVERSAL`]) the tangents alone do not tell a needle of material (a left turn: the moved
/// elements overlap) from a slit into it (a right turn: they part around the joint): rounding
/// decides the sign of their cross product `c`, or the elements curve apart a hair beyond the
/// joint. There the side is taken from where `b` lies against `a` at an arc length `s` from
/// the joint (the smaller of `d` and the elements' lengths), to second order
/// `c s - (κa + κb) s² / 2` to the left (κ: signed curvatures). When that cannot be told
/// either (two lines running straight back), the joint is taken as a right turn: its node arc
/// is an exact offset of the joint, where a joining chord would pass through it. Away from
/// reversals the tangents decide: an element that curls round far from the joint says nothing
/// about the joint itself.
fn right_turn(a: &Segment, b: &Segment, d: f64) -> bool {
    let (t_in, t_out) = (a.tangent_at(1.0), b.tangent_at(0.0));
    let c = t_in.cross(t_out);
    if t_in.dot(t_out) >= 0.0 || c.abs() > NEAR_REVERSAL {
        return c < 0.0;
    }
    let s = d.min(a.length()).min(b.length());
    let lateral = c * s - (curvature(a) + curvature(b)) * s * s / 2.0;
    // Rounding of unit tangents is a few 1e-16; below that the side cannot be told.
    lateral.is_nan() || lateral <= 1e-12 * s
}

/// Signed curvature of a segment: 1/radius for a counter-clockwise arc, negative for a
/// clockwise one, 0 for a line.
fn curvature(s: &Segment) -> f64 {
    match s {
        Segment::Line(_) => 0.0,
        Segment::Arc(a) => a.sweep().signum() / a.radius(),
    }
}

/// One element moved by `d` to its left: an arc offset onto its centre becomes that point (a
/// line of no length); `None` for a line shorter than rounding, a point whose direction means
/// nothing (the side it would move to is a guess: a line 1e-10 mm long pointing back against
/// its neighbours would put a node arc round each of its ends, outside the pocket), so that
/// its neighbours meet across it.
fn offset_segment(s: &Segment, d: f64, tol: &Tolerance) -> Option<Segment> {
    match s {
        Segment::Line(l) => {
            if l.length() <= tol.rounding() {
                return None;
            }
            let n = l.direction()?.perp() * d;
            Some(Segment::Line(Line::new(l.start + n, l.end + n)))
        }
        Segment::Arc(a) => {
            // Left of a counter-clockwise arc is towards its centre.
            let r = if a.sweep() > 0.0 {
                a.radius() - d
            } else {
                a.radius() + d
            };
            if r.abs() <= tol.rounding() {
                // Offset onto its centre: a point, kept (as a line of no length) so that the
                // joints on either side still get their node arcs through it; split contracts
                // it into one node.
                return Some(Segment::Line(Line::new(a.center(), a.center())));
            }
            if r > 0.0 {
                Some(Segment::Arc(Arc::new(a.center(), r, a.start_angle(), a.sweep())))
            } else {
                // Offset past its centre: the paper's arc of radius |r - d| turned by 180°.
                Some(Segment::Arc(Arc::new(
                    a.center(),
                    -r,
                    a.start_angle() + PI,
                    a.sweep(),
                )))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;

    #[test]
    fn a_square_island_gets_arcs_at_its_corners() {
        // Clockwise square: material (the pocket) on its left, outside.
        let p = Point::new;
        let c = [p(0.0, 0.0), p(0.0, 10.0), p(10.0, 10.0), p(10.0, 0.0)];
        let contour = Contour::polygon(&c);
        let (pieces, next) = raw_offset(&contour, 2.0, &Tolerance::default(), 0, 0, &|_| true);
        assert_eq!(pieces.len(), 8);
        assert_eq!(next, 8);
        assert!(pieces
            .iter()
            .skip(1)
            .step_by(2)
            .all(|p| matches!(p.segment, Segment::Arc(_))));
        let area = crate::geom::signed_area(&pieces.iter().map(|p| p.segment).collect::<Vec<_>>());
        // Clockwise: 14 x 14 square with rounded corners, negative.
        assert!((area + (196.0 - (4.0 - PI) * 4.0)).abs() < 1e-9, "{area}");
        for w in 0..pieces.len() {
            let (a, b) = (pieces[w], pieces[(w + 1) % pieces.len()]);
            assert_eq!(a.end, b.start);
            assert!(a.segment.end().distance(b.segment.start()) < 1e-9);
        }
        // The first moved edge starts 2 to the left of the first corner.
        let s0 = &contour.segments[0];
        let left = s0.start() + s0.tangent_at(0.0).perp() * 2.0;
        assert!(left.distance(pieces[0].segment.start()) < 1e-12);
    }

    #[test]
    fn only_the_wanted_pieces_and_the_joints_beside_them_are_returned() {
        let p = Point::new;
        let c = [p(0.0, 0.0), p(0.0, 10.0), p(10.0, 10.0), p(10.0, 0.0)];
        let contour = Contour::polygon(&c);
        let tol = Tolerance::default();
        let (all, _) = raw_offset(&contour, 2.0, &tol, 0, 0, &|_| true);
        // Element 2: its moved edge and the corner arcs at either end of it (the joints at the
        // ends of elements 1 and 2), as in the whole ring, joined end to start.
        let (some, _) = raw_offset(&contour, 2.0, &tol, 0, 0, &|s| s == Source::Element(2));
        let sources: Vec<Source> = some.iter().map(|p| p.source).collect();
        assert_eq!(
            sources,
            vec![Source::Joint(1), Source::Element(2), Source::Joint(2)]
        );
        for piece in &some {
            let twin = all.iter().find(|q| q.source == piece.source).unwrap();
            assert_eq!(piece.segment, twin.segment);
        }
        assert_eq!((some[0].end, some[1].end), (some[1].start, some[2].start));
        // A joint alone brings only itself.
        let (joint, _) = raw_offset(&contour, 2.0, &tol, 0, 0, &|s| s == Source::Joint(3));
        assert_eq!(joint.len(), 1);
        assert_eq!(joint[0].source, Source::Joint(3));
    }

    #[test]
    fn a_cusp_is_a_needle_or_a_slit_by_where_the_elements_go() {
        let p = Point::new;
        // In along +x to the origin, back along a small arc that curves away below (a slit:
        // material all around the joint) or above (a needle of material).
        let a = Segment::Line(Line::new(p(-10.0, 0.0), p(0.0, 0.0)));
        let below = Segment::Arc(Arc::new(p(0.0, -1.0), 1.0, PI / 2.0, 1.0));
        let above = Segment::Arc(Arc::new(p(0.0, 1.0), 1.0, -PI / 2.0, -1.0));
        assert!(right_turn(&a, &below, 0.5));
        assert!(!right_turn(&a, &above, 0.5));
        // Straight back along a line: cannot be told, taken as a right turn.
        let back = Segment::Line(Line::new(p(0.0, 0.0), p(-5.0, 0.0)));
        assert!(right_turn(&a, &back, 0.5));
        // An ordinary sharp left turn (a 150° star tip).
        let tip = Segment::Line(Line::new(p(0.0, 0.0), p(-5.0, 2.0)));
        assert!(!right_turn(&a, &tip, 0.5));
    }
}
