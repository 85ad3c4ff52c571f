//! Throwing away invalid pieces (paper §6): a piece is kept only when it is nowhere closer than
//! d to the original profile (which also rules out crossing it) and lies inside the region.

use crate::geom::{Contour, Piece, Point, Segment, SegmentIndex, Tolerance};
use crate::union_find::UnionFind;

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
pub fn prune(
    pieces: Vec<Piece>,
    profile: &Profile,
    inside: &dyn Fn(Point) -> bool,
    d: f64,
    tol: &Tolerance,
) -> Vec<Piece> {
    // Exact offset pieces are at distance d up to rounding, far below ten epsilons.
    let slack = (10.0 * tol.eps).min(1e-3 * d);
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .filter(|p| p.segment.length() > tol.eps)
        .collect();
    let run = runs(&pieces);
    // The longest piece of each run (runs are numbered by one of their pieces).
    let mut longest: Vec<usize> = vec![usize::MAX; pieces.len()];
    for (i, p) in pieces.iter().enumerate() {
        let best = &mut longest[run[i]];
        if *best == usize::MAX || p.segment.length() > pieces[*best].segment.length() {
            *best = i;
        }
    }
    let valid: Vec<bool> = longest
        .iter()
        .map(|&i| {
            i != usize::MAX && {
                let m = pieces[i].segment.point_at(0.5);
                !profile.nearer_than(m, d - slack) && inside(m)
            }
        })
        .collect();
    pieces
        .into_iter()
        .enumerate()
        .filter(|(i, _)| valid[run[*i]])
        .map(|(_, p)| p)
        .collect()
}

/// One more than the largest node id.
fn node_count(pieces: &[Piece]) -> usize {
    pieces.iter().map(|p| p.start.max(p.end) + 1).max().unwrap_or(0)
}

/// The run each piece belongs to: pieces are joined through nodes where exactly one piece
/// ends and exactly one starts.
fn runs(pieces: &[Piece]) -> Vec<usize> {
    let nodes = node_count(pieces);
    let (mut ins, mut outs) = (vec![0u32; nodes], vec![0u32; nodes]);
    let (mut into, mut from) = (vec![usize::MAX; nodes], vec![usize::MAX; nodes]);
    for (i, p) in pieces.iter().enumerate() {
        outs[p.start] += 1;
        from[p.start] = i;
        ins[p.end] += 1;
        into[p.end] = i;
    }
    let mut sets = UnionFind::new(pieces.len());
    for node in 0..nodes {
        if ins[node] == 1 && outs[node] == 1 {
            sets.union(into[node], from[node]);
        }
    }
    (0..pieces.len()).map(|i| sets.find(i)).collect()
}

/// Removes pairs of pieces that run along each other in opposite directions between the same
/// two nodes: they bound no area (offsets of two walls exactly 2d apart coincide like this), and
/// keeping them would make loops that run back over themselves.
pub fn cancel_opposites(pieces: Vec<Piece>, tol: &Tolerance) -> Vec<Piece> {
    let mut by_ends: std::collections::HashMap<(usize, usize), Vec<usize>> = std::collections::HashMap::new();
    for (i, p) in pieces.iter().enumerate() {
        by_ends.entry((p.start, p.end)).or_default().push(i);
    }
    let mut gone = vec![false; pieces.len()];
    for (i, p) in pieces.iter().enumerate() {
        if gone[i] {
            continue;
        }
        let mid = p.segment.point_at(0.5);
        let twin = by_ends.get(&(p.end, p.start)).and_then(|v| {
            v.iter().copied().find(|&j| {
                !gone[j] && j != i && pieces[j].segment.point_at(0.5).distance(mid) <= 1e3 * tol.eps
            })
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
    use std::collections::HashMap;
    let mut ins: HashMap<usize, usize> = HashMap::new();
    let mut outs: HashMap<usize, usize> = HashMap::new();
    for p in &pieces {
        *outs.entry(p.start).or_default() += 1;
        *ins.entry(p.end).or_default() += 1;
    }
    let mut alive = vec![true; pieces.len()];
    let mut by_start: HashMap<usize, Vec<usize>> = HashMap::new();
    let mut by_end: HashMap<usize, Vec<usize>> = HashMap::new();
    for (i, p) in pieces.iter().enumerate() {
        by_start.entry(p.start).or_default().push(i);
        by_end.entry(p.end).or_default().push(i);
    }
    let dangling = |p: &Piece, ins: &HashMap<usize, usize>, outs: &HashMap<usize, usize>| {
        ins.get(&p.start).copied().unwrap_or(0) == 0 || outs.get(&p.end).copied().unwrap_or(0) == 0
    };
    let mut queue: Vec<usize> = (0..pieces.len())
        .filter(|&i| dangling(&pieces[i], &ins, &outs))
        .collect();
    while let Some(i) = queue.pop() {
        if !alive[i] {
            continue;
        }
        alive[i] = false;
        let p = &pieces[i];
        if let Some(n) = outs.get_mut(&p.start) {
            *n -= 1;
        }
        if let Some(n) = ins.get_mut(&p.end) {
            *n -= 1;
        }
        // Removing it may strand the pieces that led into its start or left from its end.
        for &j in by_end
            .get(&p.start)
            .into_iter()
            .flatten()
            .chain(by_start.get(&p.end).into_iter().flatten())
        {
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
