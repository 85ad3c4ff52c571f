//! Proving that the tool, following a chain of segments, sweeps only points that earlier moves
//! at that height swept.

use super::cover::{Cover, Held};
use crate::geom::{distance_from_segment, Aabb, Arc, Line, Point, Segment, SegmentIndex};
use std::f64::consts::TAU;

/// Where across the sweep the probes of a station lie, in tool radii from the centre line: a
/// sliver of stock between earlier sweeps is often narrower than the sweep's half width.
pub const ACROSS: [f64; 9] = [0.999_999, -0.999_999, 0.0, 0.5, -0.5, 0.25, -0.25, 0.75, -0.75];

/// Spacing of the quick probes along a chain, in tool radii: one probe outside every earlier
/// sweep settles that the chain cuts.
pub const PROBE_STEP_RADII: f64 = 0.25;

/// Spacing of the first samples along the edges of the earlier sweeps, in tool radii, each
/// interval halved where its sample decides nothing, down to [`FINEST_EDGE_RADII`]: far from
/// the chain one sample settles a long interval.
const EDGE_STEP_RADII: f64 = 4.0;

/// The finest interval of an edge, in tool radii: one left undecided there takes the chain to
/// cut (at a 3 mm radius, 0.003 mm).
const FINEST_EDGE_RADII: f64 = 0.001;

/// How far into the run's sweep a point of an earlier sweep's edge may lie and be taken to
/// touch it, in tool radii (rounding).
const TOUCH_RADII: f64 = 1e-7;

/// Samples one proof may take besides one per edge before it gives up (undecided).
const MOST_SAMPLES: usize = 20_000;

/// What a proof found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Proof {
    /// The chain sweeps nothing the earlier moves had not swept.
    Nothing,
    /// The chain's sweep holds this point, which no earlier sweep was proven to hold.
    CutsAt(Point),
    /// No earlier sweep comes near the chain: it cuts wherever it goes.
    Cuts,
    /// The proof ran out of samples.
    Undecided,
}

/// What a chain's sweep is proven against: the runs of `cover` before run `before`, and
/// `extra` (the part of the chain's first sweep already cut when the chain starts inside it).
#[derive(Clone, Copy)]
pub struct Earlier<'c> {
    pub cover: &'c Cover,
    pub before: usize,
    pub extra: Option<Segment>,
}

impl Earlier<'_> {
    /// True when an earlier sweep's path comes nearer to `p` than `reach` (`held`: see
    /// [`Cover::reaches_held`]).
    fn reaches(&self, p: Point, reach: f64, held: &mut Held) -> bool {
        self.cover.reaches_held(p, reach, self.before, held)
            || self.extra.is_some_and(|e| distance_from_segment(&e, p) < reach)
    }
}

/// Room reused from one proof to the next.
#[derive(Default)]
pub struct Scratch {
    /// The cover's cells near a run.
    cells: Vec<usize>,
    /// For each sweep of the cover, the stamp of the last proof that took it as near.
    seen: Vec<u32>,
    stamp: u32,
}

impl Scratch {
    /// A new stamp for a cover of `n` sweeps.
    fn next_stamp(&mut self, n: usize) {
        if self.seen.len() != n || self.stamp == u32::MAX {
            self.seen = vec![0; n];
            self.stamp = 0;
        }
        self.stamp += 1;
    }
}

/// An earlier sweep near a chain: its centre path and whether the circles round its start and
/// end may hold points of the edge of all the sweeps (not where it runs on smoothly into a
/// neighbour that is among them).
#[derive(Clone, Copy)]
struct Near {
    segment: Segment,
    bbox: Aabb,
    /// The radius of its sweep (less than the tool's for a run of short moves).
    radius: f64,
    circles: [bool; 2],
}

/// Whether the tool following `chain` (consecutive segments) at the cover's height sweeps only
/// points that the `earlier` moves swept.
///
/// Let U be the union of the earlier sweeps and P the sweep of a connected run of the chain.
/// P lies in U when a point of P lies in U and no point of U's boundary lies in P's interior
/// (were part of P outside U, a path inside P from there to the point in U would cross U's
/// boundary). U's boundary lies on the edges of the sweeps it is made of (for each earlier
/// segment its two offset curves and the circles round its ends), so those edges are sampled:
/// a sample is settled when it lies farther than the radius from the run, or nearer than the
/// radius to some earlier segment, by more than half the spacing (distances change no faster
/// than the point moves); else its interval is halved. Pieces that lie along earlier segments
/// (a way back along a path just cut) are inside those sweeps at once, and left out of the
/// runs.
pub fn sweeps_nothing(earlier: &Earlier, chain: &[Segment], scratch: &mut Scratch) -> Proof {
    let mut run: Vec<Segment> = Vec::new();
    for (i, piece) in chain.iter().enumerate() {
        let along = retraced(earlier, piece);
        if !along {
            run.push(*piece);
        }
        if (along || i + 1 == chain.len()) && !run.is_empty() {
            let found = run_sweeps_nothing(earlier, &run, scratch);
            if found != Proof::Nothing {
                return found;
            }
            run.clear();
        }
    }
    Proof::Nothing
}

/// [`sweeps_nothing`] for a connected run with no piece along an earlier segment.
fn run_sweeps_nothing(earlier: &Earlier, run: &[Segment], scratch: &mut Scratch) -> Proof {
    let r = earlier.cover.r;
    let run_index = SegmentIndex::new(run);
    let run_box = (run.iter()).fold(Aabb::EMPTY, |b, s| b.union(&s.bbox()));
    // The quick probes first: most runs that cut fail there, and need no more than whether an
    // earlier sweep comes near at all.
    if let Some(q) = probe_in_stock(earlier, run) {
        return match near_runs(earlier, run, &run_index, &run_box, scratch, 1).is_empty() {
            true => Proof::Cuts,
            false => Proof::CutsAt(q),
        };
    }
    let near = near_runs(earlier, run, &run_index, &run_box, scratch, usize::MAX);
    if near.is_empty() {
        return Proof::Cuts;
    }
    let finest = FINEST_EDGE_RADII * r;
    let reach_box = run_box.inflated(r);
    let edges: Vec<Segment> = (near.iter())
        .filter(|n| n.bbox.inflated(r).intersects(&reach_box))
        .flat_map(|n| edges(&n.segment, n.radius, n.circles))
        .collect();
    let mut budget = MOST_SAMPLES + 4 * edges.len();
    let (mut work, mut nearest) = (0, None);
    let mut along_edges = Held::default();
    let mut stack: Vec<(f64, f64)> = Vec::new();
    for edge in &edges {
        let length = edge.length();
        let m = ((length / (EDGE_STEP_RADII * r)).ceil() as usize).max(1);
        stack.extend((0..m).map(|k| (k as f64 / m as f64, (k + 1) as f64 / m as f64)));
        while let Some((t0, t1)) = stack.pop() {
            if budget == 0 {
                return Proof::Undecided;
            }
            budget -= 1;
            let q = edge.point_at(0.5 * (t0 + t1));
            // Every point of the interval is within half its length of q.
            let h = 0.5 * (t1 - t0) * length;
            // Far from the run's box, or from the run (asked first of the piece that answered
            // last), or within an earlier sweep: settled.
            let far = run_box.distance_sq(q) > (r + h) * (r + h)
                || !run_index.any_within_hinted(q, r + h, &mut work, &mut nearest);
            if far || earlier.reaches(q, r - h, &mut along_edges) {
                continue;
            }
            if h <= finest {
                // Left: a point of the edge where it touches the run's sweep (the run passes
                // an earlier sweep's edge at the radius, as along a wall), or stock the run
                // cuts. Only a touch within rounding is let pass: a run that cut into a
                // sliver beyond the edge of the earlier sweeps would, where that edge is the
                // wall, cut the wall.
                if !run_index.any_within(q, r * (1.0 - TOUCH_RADII)) {
                    continue;
                }
                return Proof::CutsAt(q);
            }
            let mid = 0.5 * (t0 + t1);
            stack.push((mid, t1));
            stack.push((t0, mid));
        }
    }
    Proof::Nothing
}

/// The earlier runs (and `extra`) whose paths come within twice the radius of `run` (indexed
/// in `run_index`, its box `run_box`), at most `most` of them: all that a point of the run's
/// sweep can lie in.
fn near_runs(
    earlier: &Earlier,
    run: &[Segment],
    run_index: &SegmentIndex,
    run_box: &Aabb,
    scratch: &mut Scratch,
    most: usize,
) -> Vec<Near> {
    let cover = earlier.cover;
    let (r, before) = (cover.r, earlier.before);
    let eps = 1e-9 * r;
    scratch.cells.clear();
    for s in run {
        cover.cells_of(&s.bbox().inflated(2.0 * r), &mut scratch.cells);
    }
    scratch.cells.sort_unstable();
    scratch.cells.dedup();
    scratch.next_stamp(cover.runs.len());
    let mut near: Vec<Near> = Vec::new();
    for i in scratch.cells.iter().flat_map(|&c| cover.listed(c, before)) {
        if near.len() >= most {
            return near;
        }
        if scratch.seen[i] == scratch.stamp {
            continue;
        }
        scratch.seen[i] = scratch.stamp;
        let run = &cover.runs[i];
        if run.bbox.distance_to_box(run_box) <= 2.0 * r
            && run_index.segment_within(&run.segment, 2.0 * r, eps)
        {
            near.push(Near {
                segment: run.segment,
                bbox: run.bbox,
                radius: r - run.shrink,
                circles: [
                    !(i > 0 && cover.runs[i - 1].smooth_next),
                    !(run.smooth_next && i + 1 < before),
                ],
            });
        }
    }
    if let Some(e) = earlier
        .extra
        .filter(|e| near.len() < most && run_index.segment_within(e, 2.0 * r, eps))
    {
        near.push(Near {
            segment: e,
            bbox: e.bbox(),
            radius: r,
            circles: [true, true],
        });
    }
    near
}

/// The first of the quick probes of `run` that no earlier sweep reaches, if one is: just
/// inside the tool's circle behind its start and in front of its end, then across its sweep
/// every so often along it and at its end, each place across with its own run that held it
/// last.
fn probe_in_stock(earlier: &Earlier, run: &[Segment]) -> Option<Point> {
    let r = earlier.cover.r;
    let inside = r * (1.0 - 1e-6);
    let mut held = [Held::default(); ACROSS.len()];
    let mut probe_at = |p: Point, k: usize| !earlier.reaches(p, r * (1.0 + 1e-9), &mut held[k]);
    let (first, last) = (run[0], run[run.len() - 1]);
    let ends = [
        first.start() - first.tangent_at(0.0) * inside,
        last.end() + last.tangent_at(1.0) * inside,
    ];
    // Behind the start and in front of the end lie on the centre line: held as the probe
    // across at 0 (`ACROSS[2]`) is.
    if let Some(&q) = ends.iter().find(|&&q| probe_at(q, 2)) {
        return Some(q);
    }
    let step = PROBE_STEP_RADII * r;
    let mut to_next = 0.0;
    for s in run {
        let len = s.length();
        let mut at = to_next;
        while at <= len {
            let t = if len > 0.0 { at / len } else { 0.0 };
            let (p, normal) = (s.point_at(t), s.tangent_at(t).perp());
            if let Some(q) = (ACROSS.iter().enumerate())
                .map(|(k, &u)| (k, p + normal * (u * r)))
                .find_map(|(k, q)| probe_at(q, k).then_some(q))
            {
                return Some(q);
            }
            at += step;
        }
        to_next = at - len;
    }
    (ACROSS.iter().enumerate())
        .map(|(k, &u)| (k, last.end() + last.tangent_at(1.0).perp() * (u * r)))
        .find_map(|(k, q)| probe_at(q, k).then_some(q))
}

/// True when `piece` lies on the union of the earlier segments that run along its line or
/// circle (the way back along a path just cut, a loop cut again on the way to the next): the
/// tool's sweep along it then lies in theirs. Walked from the piece's start, each step to the
/// farthest point of the piece that one of them holds together with all of the piece between.
fn retraced(earlier: &Earlier, piece: &Segment) -> bool {
    let eps = 1e-9 * (1.0 + piece.bbox().magnitude());
    let mut t = 0.0;
    for _ in 0..64 {
        let p = piece.point_at(t);
        let listed = earlier.cover.sweeps_at(p, earlier.before, eps);
        let reach = (listed.chain(earlier.extra))
            .filter(|s| s.bbox().distance_sq(p) <= eps * eps && distance_from_segment(s, p) <= eps)
            .filter_map(|s| holds_from(piece, &s, t, eps))
            .fold(t, f64::max);
        if reach >= 1.0 {
            return true;
        }
        if reach <= t + 1e-12 {
            return false;
        }
        t = reach;
    }
    false
}

/// How far along `piece`, from `t`, the segment `s` holds all of it (`s` on the same line or
/// circle and through the piece's point at `t`), or None.
fn holds_from(piece: &Segment, s: &Segment, t: f64, eps: f64) -> Option<f64> {
    match (piece, s) {
        (Segment::Line(l), Segment::Line(m)) => {
            if l.signed_distance(m.start).abs() > eps || l.signed_distance(m.end).abs() > eps {
                return None;
            }
            // The line's parameters of `s`'s ends: it holds the piece between them.
            let (a, b) = (l.param_of(m.start), l.param_of(m.end));
            let (lo, hi) = (a.min(b), a.max(b));
            (lo <= t + 1e-12).then_some(hi.min(1.0))
        }
        (Segment::Arc(a), Segment::Arc(b)) => {
            if a.center().distance(b.center()) > eps || (a.radius() - b.radius()).abs() > eps {
                return None;
            }
            // The farther of `s`'s ends along the piece; `s` holds the piece from `t` to it
            // when the angle between the two points is the same along both.
            let end = [b.start(), b.end()]
                .map(|q| a.param_of(q))
                .into_iter()
                .fold(f64::MIN, f64::max)
                .min(1.0);
            if end <= t {
                return None;
            }
            let (u0, u1) = (b.param_of(a.point_at(t)), b.param_of(a.point_at(end)));
            let inside = |u: f64| (-1e-9..=1.0 + 1e-9).contains(&u);
            let along_s = (u1 - u0).abs() * b.sweep().abs();
            let along_piece = (end - t) * a.sweep().abs();
            let mid = a.point_at(0.5 * (t + end));
            (inside(u0)
                && inside(u1)
                && (along_s - along_piece).abs() <= 1e-9 * (1.0 + along_piece)
                && distance_from_segment(s, mid) <= eps)
                .then_some(end)
        }
        _ => None,
    }
}

/// Curves on which the edge of the sweep of `s` (every point within `r` of it) lies: the two
/// curves `r` to either side, and the circles of radius `r` round its ends.
fn edges(s: &Segment, r: f64, circles: [bool; 2]) -> Vec<Segment> {
    let mut out = Vec::with_capacity(4);
    match s {
        Segment::Line(l) => {
            let Some(d) = l.direction() else {
                return vec![Segment::Arc(Arc::circle(l.start, r))];
            };
            let n = d.perp() * r;
            out.push(Segment::Line(Line::new(l.start + n, l.end + n)));
            out.push(Segment::Line(Line::new(l.start - n, l.end - n)));
        }
        Segment::Arc(a) => {
            let (c, rad, a0, sweep) = (a.center(), a.radius(), a.start_angle(), a.sweep());
            out.push(Segment::Arc(Arc::new(c, rad + r, a0, sweep)));
            // Inside: at |rad - r| from the centre, on the far side when the arc is tighter
            // than the tool.
            let inner = rad - r;
            if inner.abs() > 0.0 {
                let shift = if inner > 0.0 { 0.0 } else { 0.5 * TAU };
                out.push(Segment::Arc(Arc::new(c, inner.abs(), a0 + shift, sweep)));
            }
        }
    }
    for (p, keep) in [s.start(), s.end()].into_iter().zip(circles) {
        if keep {
            out.push(Segment::Arc(Arc::circle(p, r)));
        }
    }
    out
}

/// How far along `chain` (by length) the tool first comes within `r` of `q`: at the first piece
/// that does, found by halving between its start and its point nearest `q` (the distance falls
/// all the way there). The chain's length when it never does.
pub fn first_reach(chain: &[Segment], q: Point, r: f64) -> f64 {
    let mut along = 0.0;
    for s in chain {
        let len = s.length();
        if distance_from_segment(s, q) > r {
            along += len;
            continue;
        }
        let far = |t: f64| s.point_at(t).distance(q) > r;
        if !far(0.0) {
            return along;
        }
        let (mut lo, mut hi) = (0.0, crate::geom::closest_param(s, q));
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if far(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return along + hi * len;
    }
    along
}

#[cfg(test)]
mod tests {
    use super::super::cover::Sweep;
    use super::*;

    fn line(x0: f64, y0: f64, x1: f64, y1: f64) -> Segment {
        Segment::Line(Line::new(Point::new(x0, y0), Point::new(x1, y1)))
    }

    fn cover(segments: &[Segment], r: f64) -> Cover {
        let sweeps = (segments.iter().enumerate())
            .map(|(i, &segment)| Sweep {
                segment,
                order: i,
                smooth_next: false,
            })
            .collect();
        Cover::new(sweeps, r).unwrap()
    }

    /// What the first `before` moves of `c` swept.
    fn all_before(c: &Cover, before: usize) -> Earlier<'_> {
        Earlier {
            cover: c,
            before,
            extra: None,
        }
    }

    #[test]
    fn a_pass_between_two_overlapping_ones_sweeps_nothing() {
        // Two passes 4 mm apart with a 3 mm radius: a third between them, 2 mm from each,
        // sweeps only what they swept; one 3 mm from the lower sweeps a sliver above the
        // upper's edge (y 7 to 7.5).
        let c = cover(&[line(0.0, 0.0, 40.0, 0.0), line(40.0, 4.0, 0.0, 4.0)], 3.0);
        let earlier = all_before(&c, 2);
        assert_eq!(
            sweeps_nothing(&earlier, &[line(10.0, 2.0, 30.0, 2.0)], &mut Scratch::default()),
            Proof::Nothing
        );
        assert!(
            matches!(sweeps_nothing(&earlier, &[line(10.0, 4.5, 30.0, 4.5)], &mut Scratch::default()), Proof::CutsAt(q) if q.y > 7.0)
        );
        // The first pass alone does not cover the middle one's upper side.
        let first_only = Earlier { before: 1, ..earlier };
        assert!(matches!(
            sweeps_nothing(
                &first_only,
                &[line(10.0, 2.0, 30.0, 2.0)],
                &mut Scratch::default()
            ),
            Proof::CutsAt(_)
        ));
        // Far from both: nothing near.
        assert_eq!(
            sweeps_nothing(&earlier, &[line(10.0, 20.0, 30.0, 20.0)], &mut Scratch::default()),
            Proof::Cuts
        );
    }

    #[test]
    fn a_sliver_between_sweeps_is_found() {
        // Two passes 6.2 mm apart with a 3 mm radius leave a strip 0.2 mm wide between them:
        // a move down the middle cuts it, though its probes across every 0.75 mm land on the
        // strip only if they fall in it.
        let c = cover(&[line(0.0, 0.0, 40.0, 0.0), line(40.0, 6.2, 0.0, 6.2)], 3.0);
        let earlier = all_before(&c, 2);
        let found = sweeps_nothing(&earlier, &[line(10.0, 3.1, 30.0, 3.1)], &mut Scratch::default());
        assert!(
            matches!(found, Proof::CutsAt(q) if (3.0..=3.2).contains(&q.y)),
            "{found:?}"
        );
        // The same way back along the first pass is inside its sweep at once.
        assert_eq!(
            sweeps_nothing(&earlier, &[line(30.0, 0.0, 10.0, 0.0)], &mut Scratch::default()),
            Proof::Nothing
        );
    }

    #[test]
    fn a_chain_is_proven_whole() {
        // Along the middle of a slot 10 mm wide cut by three passes, and out across it.
        let c = cover(
            &[
                line(0.0, 0.0, 40.0, 0.0),
                line(40.0, 3.0, 0.0, 3.0),
                line(0.0, 6.0, 40.0, 6.0),
            ],
            3.0,
        );
        let earlier = all_before(&c, 3);
        let chain = [
            line(5.0, 1.5, 20.0, 1.5),
            line(20.0, 1.5, 20.0, 4.5),
            line(20.0, 4.5, 35.0, 4.5),
        ];
        assert_eq!(
            sweeps_nothing(&earlier, &chain, &mut Scratch::default()),
            Proof::Nothing
        );
        let longer = [chain[0], chain[1], line(20.0, 4.5, 45.0, 4.5)];
        assert!(
            matches!(sweeps_nothing(&earlier, &longer, &mut Scratch::default()), Proof::CutsAt(q) if q.x > 40.0)
        );
        assert!((first_reach(&longer, Point::new(44.0, 4.5), 3.0) - (15.0 + 3.0 + 21.0)).abs() < 1e-9);
    }

    proptest::proptest! {
        /// Whatever a chain is proven not to sweep anew lies within the tool radius of the
        /// earlier moves: passes a random spacing apart across a strip and a move at random,
        /// then a chain of two straight moves at random in and about the strip, its sweep
        /// sampled densely wherever the proof says it sweeps nothing new.
        #[test]
        fn what_is_proven_to_sweep_nothing_lies_in_the_earlier_sweeps(
            r in 1.0..4.0f64, spacing in 0.5..1.95f64, passes in 2..6usize,
            extra in proptest::array::uniform4(0.0..30.0f64),
            chain in proptest::array::uniform6(-2.0..32.0f64),
        ) {
            let mut earlier_moves: Vec<Segment> = (0..passes)
                .map(|i| {
                    let y = i as f64 * spacing * r;
                    if i % 2 == 0 { line(0.0, y, 30.0, y) } else { line(30.0, y, 0.0, y) }
                })
                .collect();
            earlier_moves.push(line(extra[0], extra[1] * 0.3, extra[2], extra[3] * 0.3));
            let c = cover(&earlier_moves, r);
            let earlier = all_before(&c, earlier_moves.len());
            let y = |v: f64| v * (passes as f64 * spacing * r) / 30.0 - r;
            let moves = [
                line(chain[0], y(chain[1]), chain[2], y(chain[3])),
                line(chain[2], y(chain[3]), chain[4], y(chain[5])),
            ];
            if sweeps_nothing(&earlier, &moves, &mut Scratch::default()) == Proof::Nothing {
                for m in &moves {
                    for k in 0..=64 {
                        let p = m.point_at(k as f64 / 64.0);
                        for j in 0..24 {
                            let angle = TAU * j as f64 / 24.0;
                            for rho in [0.0, 0.5, 0.9, 0.999] {
                                let q = Point::new(p.x + rho * r * angle.cos(), p.y + rho * r * angle.sin());
                                let nearest = (earlier_moves.iter())
                                    .map(|s| distance_from_segment(s, q))
                                    .fold(f64::INFINITY, f64::min);
                                proptest::prop_assert!(nearest <= r * (1.0 + 1e-6), "{q:?} {nearest}");
                            }
                        }
                    }
                }
            }
        }
    }
}
