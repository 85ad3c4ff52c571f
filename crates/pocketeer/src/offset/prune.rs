//! Throwing away invalid pieces (paper §6): a piece is kept only when it is nowhere closer than
//! d to the original profile (which also rules out crossing it) and lies inside the region.

use crate::geom::pieces_by_node;
use crate::geom::{Contour, Piece, Point, Segment, SegmentIndex, Tolerance};
use crate::union_find::UnionFind;

/// How far inside the offset distance a joining chord may come and still close a loop, mm:
/// far below any machining tolerance, far above rounding.
const JOIN_SLACK: f64 = 1e-5;

/// The most element distances [`prune`] may measure: a few seconds. Each run is judged by
/// one point; only where the offset is cut into millions of runs, each point having most of
/// the profile at nearly the same distance (the distance a hair below the largest circle a
/// pocket of many elements holds), would it take longer.
pub const MAX_MEASURES: u64 = 40_000_000;

/// How far inside `d` a piece may come and still count as at distance `d`: exact offset
/// pieces are at distance d up to rounding, far below ten epsilons.
pub fn slack(d: f64, tol: &Tolerance) -> f64 {
    (10.0 * tol.eps).min(1e-3 * d)
}

/// The original profile, indexed for distance queries.
pub struct Profile {
    index: SegmentIndex,
}

impl Profile {
    /// Indexes the segments of `contours`.
    pub fn new(contours: &[Contour]) -> Profile {
        let segments: Vec<Segment> = contours.iter().flat_map(|c| c.segments.iter().copied()).collect();
        Profile {
            index: SegmentIndex::new(&segments),
        }
    }

    /// True when the profile comes nearer to `p` than `r`.
    pub fn nearer_than(&self, p: Point, r: f64) -> bool {
        self.index.any_within(p, r)
    }

    /// [`Profile::nearer_than`], adding to `work` the number of elements measured and trying
    /// first the element that answered `last` (see [`SegmentIndex::any_within_after`]).
    pub fn nearer_than_after(&self, p: Point, r: f64, work: &mut u64, last: &mut Option<usize>) -> bool {
        self.index.any_within_after(p, r, work, last)
    }

    /// Distance from `p` to the profile.
    pub fn distance(&self, p: Point) -> f64 {
        self.index.distance(p)
    }

    /// True when the profile comes nearer to the segment `s` than `r`.
    pub fn segment_nearer_than(&self, s: &Segment, r: f64, eps: f64) -> bool {
        self.index.segment_within(s, r, eps)
    }
}

/// The pieces that belong to the offset at distance `d`: not nearer than d to the profile (less
/// a tolerance that absorbs rounding) and inside the region. Node ids must be canonical.
///
/// Along a raw offset curve, the distance to the profile can fall below d only where the curve
/// meets another raw offset curve, and the split stage cut every piece there. So pieces joined
/// end to start at a node no other piece touches (a run) are valid or invalid together, and one
/// point of each run decides: the middle of its longest piece.
///
/// Joining lines (`join_at` gives the element at whose end their joint lies: the chords the
/// raw offset puts where moved elements overlap or collapse) are no offset curve: their points are nearer than d to the joint, so the
/// argument above does not hold along them. A join coming more than `JOIN_SLACK` inside d is
/// a run of its own, and invalid; a shorter one stays in its run.
///
/// `Err` with the point being judged when that would measure more than [`MAX_MEASURES`]
/// element distances.
pub fn prune(
    pieces: Vec<Piece>,
    profile: &Profile,
    inside: &dyn Fn(Point) -> bool,
    join_at: &dyn Fn(&Piece) -> Option<usize>,
    d: f64,
    tol: &Tolerance,
) -> Result<Vec<Piece>, Point> {
    let slack = slack(d, tol);
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .filter(|p| p.segment.length() > tol.eps)
        .collect();
    let degree = Degrees::of(&pieces);
    // A join whose middle is within JOIN_SLACK of the distance (a chord a few micrometres
    // long where two moved elements almost meet) closes its loop as the elements would;
    // any other join is judged alone, and is invalid. A join between two nodes where runs
    // end is judged alone anyway, by its middle against a radius nearer d: it needs no test
    // of its own (near the centre of a curvature of radius about d, where most pieces are
    // such joins, that test would measure most of the profile). The joint's own element is
    // the first to try: it is usually the one that comes nearer.
    let mut work = 0; // element distances measured, for joins and runs together
    let joins: Vec<bool> = pieces
        .iter()
        .map(|p| {
            let alone = !degree.simple(p.start) && !degree.simple(p.end);
            !alone
                && join_at(p).is_some_and(|element| {
                    let mid = p.segment.point_at(0.5);
                    let r = d - JOIN_SLACK.min(0.5 * d);
                    profile.nearer_than_after(mid, r, &mut work, &mut Some(element))
                })
        })
        .collect();
    let run = runs(&pieces, &joins, &degree);
    // The longest piece of each run (runs are numbered by one of their pieces).
    let mut longest: Vec<usize> = vec![usize::MAX; pieces.len()];
    for (i, p) in pieces.iter().enumerate() {
        let best = &mut longest[run[i]];
        if *best == usize::MAX || p.segment.length() > pieces[*best].segment.length() {
            *best = i;
        }
    }
    let mut last = None;
    let mut valid = vec![false; longest.len()];
    for (v, &i) in valid.iter_mut().zip(&longest) {
        if i == usize::MAX {
            continue;
        }
        let m = pieces[i].segment.point_at(0.5);
        *v = !profile.nearer_than_after(m, d - slack, &mut work, &mut last) && inside(m);
        if work > MAX_MEASURES {
            return Err(m);
        }
    }
    Ok(pieces
        .into_iter()
        .enumerate()
        .filter(|(i, _)| valid[run[*i]])
        .map(|(_, p)| p)
        .collect())
}

/// One more than the largest node id.
fn node_count(pieces: &[Piece]) -> usize {
    pieces.iter().map(|p| p.start.max(p.end) + 1).max().unwrap_or(0)
}

/// How many pieces start and end at each node.
struct Degrees {
    ins: Vec<u32>,
    outs: Vec<u32>,
    /// For each node, a piece ending there and one starting there.
    into: Vec<usize>,
    from: Vec<usize>,
}

impl Degrees {
    fn of(pieces: &[Piece]) -> Degrees {
        let nodes = node_count(pieces);
        let (mut ins, mut outs) = (vec![0u32; nodes], vec![0u32; nodes]);
        let (mut into, mut from) = (vec![usize::MAX; nodes], vec![usize::MAX; nodes]);
        for (i, p) in pieces.iter().enumerate() {
            outs[p.start] += 1;
            from[p.start] = i;
            ins[p.end] += 1;
            into[p.end] = i;
        }
        Degrees {
            ins,
            outs,
            into,
            from,
        }
    }

    /// True at a node where exactly one piece ends and exactly one starts: a run goes on
    /// through it.
    fn simple(&self, node: usize) -> bool {
        self.ins[node] == 1 && self.outs[node] == 1
    }
}

/// The run each piece belongs to: pieces are joined through simple nodes (see
/// [`Degrees::simple`]) unless one of them is a join judged alone.
fn runs(pieces: &[Piece], joins: &[bool], degree: &Degrees) -> Vec<usize> {
    let mut sets = UnionFind::new(pieces.len());
    for node in 0..degree.ins.len() {
        let (a, b) = (degree.into[node], degree.from[node]);
        if degree.simple(node) && !joins[a] && !joins[b] {
            sets.union(a, b);
        }
    }
    (0..pieces.len()).map(|i| sets.find(i)).collect()
}

/// Removes pairs of pieces that run along each other in opposite directions between the same
/// two nodes: they bound no area (offsets of two walls exactly 2d apart coincide like this), and
/// keeping them would make loops that run back over themselves.
pub fn cancel_opposites(pieces: Vec<Piece>, tol: &Tolerance) -> Vec<Piece> {
    // The twins of a piece start where it ends.
    let (first, by_start) = pieces_by_node(&pieces, node_count(&pieces), |p| p.start);
    let mut gone = vec![false; pieces.len()];
    for (i, p) in pieces.iter().enumerate() {
        if gone[i] || p.start == p.end {
            continue;
        }
        let mid = p.segment.point_at(0.5);
        let twin = by_start[first[p.end]..first[p.end + 1]]
            .iter()
            .copied()
            .find(|&j| {
                pieces[j].end == p.start
                    && !gone[j]
                    && pieces[j].segment.point_at(0.5).distance(mid) <= 1e3 * tol.eps
            });
        if let Some(j) = twin {
            gone[i] = true;
            gone[j] = true;
        }
    }
    pieces
        .into_iter()
        .zip(gone)
        .filter_map(|(p, g)| (!g).then_some(p))
        .collect()
}

/// Removes pieces that cannot be part of a closed loop: those starting at a node no kept piece
/// ends at, or ending where no kept piece starts. Such stubs are left where an invalid piece
/// came within rounding of being valid; a true offset is made of closed loops only.
pub fn remove_dangling(pieces: Vec<Piece>) -> Vec<Piece> {
    let nodes = node_count(&pieces);
    let (mut ins, mut outs) = (vec![0u32; nodes], vec![0u32; nodes]);
    for p in &pieces {
        outs[p.start] += 1;
        ins[p.end] += 1;
    }
    let (start_first, by_start) = pieces_by_node(&pieces, nodes, |p| p.start);
    let (end_first, by_end) = pieces_by_node(&pieces, nodes, |p| p.end);
    let mut alive = vec![true; pieces.len()];
    let dangling = |p: &Piece, ins: &[u32], outs: &[u32]| ins[p.start] == 0 || outs[p.end] == 0;
    let mut queue: Vec<usize> = (0..pieces.len())
        .filter(|&i| dangling(&pieces[i], &ins, &outs))
        .collect();
    while let Some(i) = queue.pop() {
        if !alive[i] {
            continue;
        }
        alive[i] = false;
        let p = &pieces[i];
        outs[p.start] -= 1;
        ins[p.end] -= 1;
        // Removing it may strand the pieces that led into its start or left from its end.
        let into_start = &by_end[end_first[p.start]..end_first[p.start + 1]];
        let from_end = &by_start[start_first[p.end]..start_first[p.end + 1]];
        for &j in into_start.iter().chain(from_end) {
            if alive[j] && dangling(&pieces[j], &ins, &outs) {
                queue.push(j);
            }
        }
    }
    pieces
        .into_iter()
        .zip(alive)
        .filter_map(|(p, a)| a.then_some(p))
        .collect()
}
