//! Throwing away invalid pieces (paper §6): a piece is kept only when it is nowhere closer than
//! d to the original profile (which also rules out crossing it) and lies inside the region.

use crate::geom::PieceGraph;
use crate::geom::{Piece, Point, SegmentIndex, Tolerance, JOIN_SLACK};
use crate::union_find::UnionFind;

/// The most element distances [`prune`] may measure: a few seconds. Each run is judged by
/// one point; only where the offset is cut into millions of runs, each point having most of
/// the profile at nearly the same distance (the distance a hair below the largest circle a
/// pocket of many elements holds), would it take longer.
pub const MAX_MEASURES: u64 = 40_000_000;

/// How far inside `d` a piece may come and still count as at distance `d`: see
/// [`crate::geom::offset_slack`].
pub fn slack(d: f64, tol: &Tolerance) -> f64 {
    crate::geom::offset_slack(d, tol)
}

/// Which of `pieces` belong to the offset at distance `d`: not nearer than d to the profile
/// (less a tolerance that absorbs rounding) and inside the region. Node ids must be canonical;
/// `graph` is the graph of `pieces`.
///
/// Along a raw offset curve, the distance to the profile can fall below d only where the curve
/// meets another raw offset curve, and the split stage cut every piece there. So pieces joined
/// end to start at a node no other piece touches (a run) are valid or invalid together, and one
/// point of each run decides: the middle of its longest piece.
///
/// Joining lines (the chords the raw offset puts where moved elements overlap or collapse;
/// `join_at` gives the element at whose end their joint lies) are no offset curve: their points
/// are nearer than d to the joint, so the argument above does not hold along them. A join
/// coming more than `JOIN_SLACK` inside d is a run of its own, and invalid; a shorter one stays
/// in its run.
///
/// `Err` with the point being judged when that would measure more than [`MAX_MEASURES`]
/// element distances.
pub fn prune(
    pieces: &[Piece],
    graph: &PieceGraph,
    walls: &SegmentIndex,
    inside: &dyn Fn(Point) -> bool,
    join_at: &dyn Fn(&Piece) -> Option<usize>,
    d: f64,
    tol: &Tolerance,
) -> Result<Vec<bool>, Point> {
    let slack = slack(d, tol);
    // A run goes on through a node where exactly one piece ends and exactly one starts.
    let simple = |node: usize| graph.leaving(node).len() == 1 && graph.entering(node).len() == 1;
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
            let alone = !simple(p.start) && !simple(p.end);
            !alone
                && join_at(p).is_some_and(|element| {
                    let mid = p.segment.point_at(0.5);
                    let r = d - JOIN_SLACK.min(0.5 * d);
                    walls.any_within_hinted(mid, r, &mut work, &mut Some(element))
                })
        })
        .collect();
    // The run each piece belongs to: pieces are joined through simple nodes unless one of
    // them is a join judged alone.
    let mut sets = UnionFind::new(pieces.len());
    for node in 0..graph.nodes() {
        if simple(node) {
            let (a, b) = (graph.entering(node)[0], graph.leaving(node)[0]);
            if !joins[a] && !joins[b] {
                sets.union(a, b);
            }
        }
    }
    let run: Vec<usize> = (0..pieces.len()).map(|i| sets.find(i)).collect();
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
        *v = !walls.any_within_hinted(m, d - slack, &mut work, &mut last) && inside(m);
        if work > MAX_MEASURES {
            return Err(m);
        }
    }
    Ok(run.iter().map(|&r| valid[r]).collect())
}

/// Drops (from `kept`) pairs of pieces that run along each other in opposite directions
/// between the same two nodes: they bound no area (offsets of two walls exactly 2d apart
/// coincide like this), and keeping them would make loops that run back over themselves.
pub fn cancel_opposites(pieces: &[Piece], graph: &PieceGraph, kept: &mut [bool], tol: &Tolerance) {
    for (i, p) in pieces.iter().enumerate() {
        if !kept[i] || p.start == p.end {
            continue;
        }
        // The twins of a piece start where it ends.
        let twin = graph.leaving(p.end).iter().copied().find(|&j| {
            pieces[j].end == p.start
                && kept[j]
                && pieces[j].segment.point_at(0.5).distance(p.segment.point_at(0.5)) <= tol.coincident()
        });
        if let Some(j) = twin {
            kept[i] = false;
            kept[j] = false;
        }
    }
}

/// Drops (from `kept`) the pieces that cannot be part of a closed loop: those starting at a
/// node no kept piece ends at, or ending where no kept piece starts. Such stubs are left where
/// an invalid piece came within rounding of being valid; a true offset is made of closed
/// loops only.
pub fn remove_dangling(pieces: &[Piece], graph: &PieceGraph, kept: &mut [bool]) {
    let count = |list: &[usize], kept: &[bool]| list.iter().filter(|&&j| kept[j]).count();
    let dangling = |p: &Piece, kept: &[bool]| {
        count(graph.entering(p.start), kept) == 0 || count(graph.leaving(p.end), kept) == 0
    };
    let mut queue: Vec<usize> = (0..pieces.len())
        .filter(|&i| kept[i] && dangling(&pieces[i], kept))
        .collect();
    while let Some(i) = queue.pop() {
        if !kept[i] {
            continue;
        }
        kept[i] = false;
        let p = &pieces[i];
        // Removing it may strand the pieces that led into its start or left from its end.
        for &j in graph.entering(p.start).iter().chain(graph.leaving(p.end)) {
            if kept[j] && dangling(&pieces[j], kept) {
                queue.push(j);
            }
        }
    }
}
