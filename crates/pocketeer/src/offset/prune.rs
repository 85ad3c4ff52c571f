//! Throwing away invalid pieces (paper §6): a piece is kept only when it is nowhere closer than
//! d to the original profile (which also rules out crossing it) and lies inside the region.

use crate::geom::{segment_distance, Aabb, BoxIndex, Contour, Piece, Point, Segment, Tolerance};

/// The original profile, indexed for distance queries.
pub struct Profile<'a> {
    segments: Vec<&'a Segment>,
    index: BoxIndex,
}

impl<'a> Profile<'a> {
    /// Indexes the segments of `contours`.
    pub fn new(contours: &'a [Contour]) -> Profile<'a> {
        let segments: Vec<&Segment> = contours.iter().flat_map(|c| c.segments.iter()).collect();
        let boxes: Vec<Aabb> = segments.iter().map(|s| s.bbox()).collect();
        Profile {
            index: BoxIndex::new(&boxes),
            segments,
        }
    }

    /// True when `s` comes nearer than `limit` to any segment of the profile.
    pub fn nearer_than(&self, s: &Segment, limit: f64, eps: f64) -> bool {
        let reach = s.bbox().inflated(limit);
        self.index
            .intersecting(&reach)
            .any(|k| segment_distance(s, self.segments[k], eps).0 < limit)
    }
}

/// The pieces that belong to the offset at distance `d`: not nearer than d to the profile
/// (less a tolerance that absorbs rounding) and with their middle inside the region.
pub fn prune(
    pieces: Vec<Piece>,
    profile: &Profile,
    inside: &dyn Fn(Point) -> bool,
    d: f64,
    tol: &Tolerance,
) -> Vec<Piece> {
    // Exact offset pieces are at distance d up to rounding, far below ten epsilons.
    let slack = (10.0 * tol.eps).min(1e-3 * d);
    pieces
        .into_iter()
        .filter(|p| p.segment.length() > tol.eps)
        .filter(|p| inside(p.segment.point_at(0.5)))
        .filter(|p| !profile.nearer_than(&p.segment, d - slack, tol.eps))
        .collect()
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
