//! Raw offset (paper §4): every line moved sideways by d, every arc's radius changed by d, and
//! an arc of radius d around every joint where the moved elements part.

use crate::geom::Source;
use crate::geom::NEAR_REVERSAL;
use crate::geom::{intersect, Arc, Contour, Intersection, Line, Piece, Point, Segment, Tolerance};
use smallvec::SmallVec;
use std::collections::HashMap;
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
/// open where a loop may still run through it. The trimming of a moved element depends on
/// its neighbours' (see [`Trimmed`]); the pieces returned are those of the whole ring (only
/// the node ids of the ends differ), though where few sources are wanted only the joints
/// they depend on are worked out.
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
    next_node: usize,
    base: usize,
    wanted: &dyn Fn(Source) -> bool,
) -> (Vec<Piece>, usize) {
    let segs = &contour.segments;
    // A deeper level of a finely drawn profile wants a few of its elements: only those and
    // the joints their trims depend on are worked out, not the whole ring.
    let asked =
        |k: usize| wanted(Source::Element((base + k) as u32)) || wanted(Source::Joint((base + k) as u32));
    let asked_for = (0..segs.len()).filter(|&k| asked(k)).count();
    let sparse = asked_for * SPARSE_SHARE < segs.len();
    // The elements that do not collapse: moved element i is element keep[i] moved.
    let (keep, moved): (Vec<usize>, Vec<Segment>) = if sparse {
        (
            (0..segs.len()).filter(|&k| moves(&segs[k], tol)).collect(),
            Vec::new(),
        )
    } else {
        (segs.iter().enumerate())
            .filter_map(|(k, s)| offset_segment(s, d, tol).map(|m| (k, m)))
            .unzip()
    };
    let n = keep.len();
    if n == 0 {
        return (Vec::new(), next_node);
    }
    // Which of each moved element's pieces are wanted: its own, and those of the joint at
    // its end (see the function's documentation).
    let element_wanted = |i: usize| wanted(Source::Element((base + keep[i]) as u32));
    let wants = |i: usize| {
        let own = element_wanted(i);
        (
            own,
            own || element_wanted(after(i, n)) || wanted(Source::Joint((base + keep[i]) as u32)),
        )
    };
    let needed = (0..n).map(|i| (i, wants(i))).filter(|(_, (_, joint))| *joint);
    let ring = Ring {
        segs,
        keep: &keep,
        d,
        tol,
    };
    if sparse {
        let mut sparse = Sparse {
            ring,
            moved: HashMap::new(),
            settled: HashMap::new(),
        };
        // An element asked for brings its joints and the joint before it.
        pieces_of(ring, &mut sparse, needed, (next_node, 3 * asked_for), base)
    } else {
        let mut whole = Whole::new(ring, moved);
        pieces_of(ring, &mut whole, needed, (next_node, 2 * n), base)
    }
}

/// A ring is worked out only round the elements wanted when fewer than one in this many are.
const SPARSE_SHARE: usize = 8;

/// The raw pieces of the `needed` moved elements of `ring` (with whether the element's own
/// pieces and its joint's are wanted), trimmed as `trimmed` says, their nodes numbered from
/// `next_node`; and the next free node. `expected`: about how many pieces there will be.
fn pieces_of(
    ring: Ring<'_>,
    trimmed: &mut impl Trimmed,
    needed: impl Iterator<Item = (usize, (bool, bool))>,
    (mut next_node, expected): (usize, usize),
    base: usize,
) -> (Vec<Piece>, usize) {
    let (segs, keep, d) = (ring.segs, ring.keep, ring.d);
    let n = keep.len();
    let first = next_node;
    next_node += n;
    // Node at the start of moved element i is first + i; its end is the next one's start, with
    // a joining piece between them where they do not meet.
    let mut pieces = Vec::with_capacity(expected);
    for (i, (want_element, want_joint)) in needed {
        let next = after(i, n);
        let (k, j) = (keep[i], keep[next]);
        let (a, b) = (trimmed.moved(i), trimmed.moved(next));
        let (joint, from, to) = (trimmed.joint(i), trimmed.from(i), trimmed.to(i));
        let a = if from > 0.0 || to < 1.0 {
            a.subsegment(from, to)
        } else {
            a
        };
        let start = first + i;
        let next_start = first + next;
        let meets = joint == Joint::Meet;
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
        let next_from = trimmed.from(next);
        let b_start = if next_from > 0.0 {
            b.point_at(next_from)
        } else {
            b.start()
        };
        let source = Source::Joint((base + k) as u32);
        let ends = (a.end(), b_start, end, next_start);
        next_node = joining(
            &segs[k],
            &segs[j],
            d,
            adjacent(segs, k, j),
            joint,
            ends,
            source,
            next_node,
            &mut pieces,
        );
    }
    (pieces, next_node)
}

/// The moved element after element i of a ring of `n`.
fn after(i: usize, n: usize) -> usize {
    if i + 1 == n {
        0
    } else {
        i + 1
    }
}

/// Consecutive moved elements k and j follow each other in the contour, across the points
/// dropped between them if any; a joint needs two of them (a lone element among points
/// closes on itself, j = k, unless it is the whole contour, a circle).
fn adjacent(segs: &[Segment], k: usize, j: usize) -> bool {
    k != j || segs.len() == 1
}

/// One contour's elements and distance.
#[derive(Clone, Copy)]
struct Ring<'a> {
    segs: &'a [Segment],
    /// The elements that do not collapse, in order: moved element i is element keep[i] moved.
    keep: &'a [usize],
    d: f64,
    tol: &'a Tolerance,
}

impl Ring<'_> {
    /// What moved elements i (`a`) and i + 1 (`b`) show at their joint before the trims
    /// beside it are known.
    fn step(&self, i: usize, a: &Segment, b: &Segment) -> Step {
        let n = self.keep.len();
        let (k, j) = (self.keep[i], self.keep[after(i, n)]);
        if a.end().distance(b.start()) <= self.tol.rounding() {
            return Step::Fixed(Joint::Meet);
        }
        if !adjacent(self.segs, k, j) {
            return Step::Fixed(Joint::Apart);
        }
        if right_turn(&self.segs[k], &self.segs[j], self.d) {
            return Step::Fixed(Joint::RightTurn);
        }
        if n < 2 {
            return Step::Fixed(Joint::Apart);
        }
        let found = intersect(a, b, self.tol.eps)
            .iter()
            .filter_map(|h| match h {
                Intersection::Point { point, ta, tb } => Some((point, ta, tb)),
                Intersection::Overlap { .. } => None,
            })
            .collect();
        Step::Cross(self.segs[k].end(), found)
    }
}

/// What two consecutive moved elements show at their joint before the trims beside it are
/// known: how they meet, or where they cross (points and parameters on each) round the
/// original joint.
enum Step {
    Fixed(Joint),
    Cross(Point, SmallVec<[(Point, f64, f64); 2]>),
}

impl Step {
    /// True when the joint depends on where the first element was trimmed at its start.
    fn crosses(&self) -> bool {
        matches!(self, Step::Cross(_, found) if !found.is_empty())
    }

    /// How the elements come together, given where the first starts (`from`, a parameter of
    /// it) and where the second ends (`next_to`): where the moved elements overlap at a turn to
    /// the left, both are trimmed to their crossing nearest the joint (so they meet in one
    /// node), as long as each keeps some length.
    fn settle(self, from: f64, next_to: f64) -> Settled {
        match self {
            Step::Fixed(joint) => (joint, None),
            Step::Cross(corner, found) => found
                .into_iter()
                .filter(|&(_, ta, tb)| ta > from && tb < next_to)
                .min_by(|x, y| x.0.distance(corner).total_cmp(&y.0.distance(corner)))
                .map_or((Joint::Apart, None), |(_, ta, tb)| (Joint::Meet, Some((ta, tb)))),
        }
    }
}

/// How moved element i and the next come together once trimmed: the joint, and where they
/// cross (the parameters on each) when trimmed to their crossing.
type Settled = (Joint, Option<(f64, f64)>);

/// The moved elements of a ring and how each is trimmed.
///
/// Each joint depends on where the element before it was trimmed at its start (the crossing
/// must lie beyond it), so on the joint before; the last on the first, whose element is
/// untrimmed at its start when its joint is worked out. The joints are as when worked out in
/// ring order from the first.
trait Trimmed {
    /// Moved element i.
    fn moved(&mut self, i: usize) -> Segment;
    /// How moved element i and the next come together.
    fn joint(&mut self, i: usize) -> Joint;
    /// Where moved element i starts, as a parameter of it (0: not trimmed).
    fn from(&mut self, i: usize) -> f64;
    /// Where moved element i ends (1: not trimmed).
    fn to(&mut self, i: usize) -> f64;
}

/// A whole ring, worked out at once in ring order.
struct Whole {
    moved: Vec<Segment>,
    joint: Vec<Joint>,
    from: Vec<f64>,
    to: Vec<f64>,
}

impl Whole {
    /// The trims of `ring`, its elements `moved`.
    fn new(ring: Ring<'_>, moved: Vec<Segment>) -> Whole {
        let n = moved.len();
        let mut from = vec![0.0; n];
        let mut to = vec![1.0; n];
        let mut joint = vec![Joint::Apart; n];
        for i in 0..n {
            let next = after(i, n);
            // The first element's end as the last joint finds it: trimmed by the first joint
            // already (unless the ring is that one element); any other's not yet.
            let settled = ring.step(i, &moved[i], &moved[next]).settle(from[i], to[next]);
            joint[i] = settled.0;
            if let Some((ta, tb)) = settled.1 {
                to[i] = ta;
                from[next] = tb;
            }
        }
        Whole {
            moved,
            joint,
            from,
            to,
        }
    }
}

impl Trimmed for Whole {
    fn moved(&mut self, i: usize) -> Segment {
        self.moved[i]
    }

    fn joint(&mut self, i: usize) -> Joint {
        self.joint[i]
    }

    fn from(&mut self, i: usize) -> f64 {
        self.from[i]
    }

    fn to(&mut self, i: usize) -> f64 {
        self.to[i]
    }
}

/// A ring worked out only where asked: the moved elements asked for, and the joints their
/// trims depend on, back to one that depends on none.
struct Sparse<'a> {
    ring: Ring<'a>,
    moved: HashMap<usize, Segment>,
    settled: HashMap<usize, Settled>,
}

impl Sparse<'_> {
    fn settled(&mut self, i: usize) -> Settled {
        if let Some(&s) = self.settled.get(&i) {
            return s;
        }
        let n = self.ring.keep.len();
        // The joints back from i that depend on the one before them, latest first.
        let mut chain: Vec<(usize, Step)> = Vec::new();
        let mut at = i;
        loop {
            let (a, b) = (self.moved(at), self.moved(after(at, n)));
            let step = self.ring.step(at, &a, &b);
            let depends = step.crosses() && at > 0 && !self.settled.contains_key(&(at - 1));
            chain.push((at, step));
            if !depends {
                break;
            }
            at -= 1;
        }
        for (at, step) in chain.into_iter().rev() {
            let from = match at.checked_sub(1).and_then(|p| self.settled.get(&p)) {
                Some(&(_, Some((_, tb)))) => tb,
                _ => 0.0,
            };
            let next_to = if at + 1 == n && n > 1 {
                self.settled(0).1.map_or(1.0, |(ta, _)| ta)
            } else {
                1.0
            };
            let settled = step.settle(from, next_to);
            self.settled.insert(at, settled);
        }
        self.settled.get(&i).copied().unwrap_or((Joint::Apart, None))
    }
}

impl Trimmed for Sparse<'_> {
    fn moved(&mut self, i: usize) -> Segment {
        let ring = self.ring;
        // Kept because it moves (`moves`): never the element itself.
        let s = &ring.segs[ring.keep[i]];
        *(self.moved)
            .entry(i)
            .or_insert_with(|| offset_segment(s, ring.d, ring.tol).unwrap_or(*s))
    }

    fn joint(&mut self, i: usize) -> Joint {
        self.settled(i).0
    }

    fn from(&mut self, i: usize) -> f64 {
        let n = self.ring.keep.len();
        self.settled((i + n - 1) % n).1.map_or(0.0, |(_, tb)| tb)
    }

    fn to(&mut self, i: usize) -> f64 {
        self.settled(i).1.map_or(1.0, |(ta, _)| ta)
    }
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

/// False for an element that collapses when moved (see [`offset_segment`]); asked without
/// moving an arc.
fn moves(s: &Segment, tol: &Tolerance) -> bool {
    match s {
        Segment::Line(_) => offset_segment(s, 1.0, tol).is_some(),
        Segment::Arc(_) => true,
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

    /// A closed ring of `radii.len()` lines round the origin, each spoke's length given,
    /// with an arc every `arc_every` edges: concave and convex joints mixed, so that moved
    /// neighbours overlap (trimmed in chains along concave stretches) and part.
    fn wobbly_ring(radii: &[f64], arc_every: usize) -> Contour {
        let n = radii.len();
        let at = |k: usize| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            Point::new(radii[k % n] * t.cos(), radii[k % n] * t.sin())
        };
        let segments = (0..n)
            .map(|k| match Arc::from_bulge(at(k), at(k + 1), 0.2) {
                Some(a) if k % arc_every == 0 => Segment::Arc(a),
                _ => Segment::Line(Line::new(at(k), at(k + 1))),
            })
            .collect();
        Contour::new(segments)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// A few sources wanted of a long ring (its trims worked out only round them): the
        /// pieces are those of the whole ring's offset with those sources, joined end to start
        /// where they follow each other.
        #[test]
        fn a_few_wanted_sources_get_the_pieces_of_the_whole_ring(
            radii in proptest::collection::vec(20.0..30.0f64, 80..240),
            arc_every in 2usize..9,
            d in 0.2..6.0f64,
            picks in proptest::collection::vec((0usize..1000, proptest::bool::ANY), 1..6),
        ) {
            let contour = wobbly_ring(&radii, arc_every);
            let n = contour.segments.len();
            let wanted_set: Vec<Source> = picks
                .iter()
                .map(|&(k, joint)| if joint { Source::Joint((k % n) as u32) } else { Source::Element((k % n) as u32) })
                .collect();
            let tol = Tolerance::default();
            let (all, _) = raw_offset(&contour, d, &tol, 0, 0, &|_| true);
            let wanted = |s: Source| wanted_set.contains(&s);
            let (some, _) = raw_offset(&contour, d, &tol, 0, 0, &wanted);
            // As a wanted set this small is worked out: see `SPARSE_SHARE`.
            proptest::prop_assert!(wanted_set.len() * SPARSE_SHARE < n);
            for piece in &some {
                let twins: Vec<&Piece> = all.iter().filter(|q| q.source == piece.source && q.segment == piece.segment).collect();
                proptest::prop_assert_eq!(twins.len(), 1, "{:?} not in the whole ring", piece);
            }
            // Each wanted source's pieces are all there.
            for w in &wanted_set {
                let count = |pieces: &[Piece]| pieces.iter().filter(|p| p.source == *w).count();
                if count(&all) > 0 {
                    proptest::prop_assert_eq!(count(&some), count(&all), "{:?}", w);
                }
            }
            // Pieces that follow each other in the whole ring share their node here too.
            for w in some.windows(2) {
                let follows = all.windows(2).any(|v| v[0].segment == w[0].segment && v[1].segment == w[1].segment);
                if follows {
                    proptest::prop_assert_eq!(w[0].end, w[1].start);
                }
            }
        }
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
