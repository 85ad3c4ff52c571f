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
    let slack = (1e3 * tol.eps).min(1e-3 * d);
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
