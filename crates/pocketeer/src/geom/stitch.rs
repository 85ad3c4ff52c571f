//! Joining pieces of boundary into closed loops.
//!
//! Each piece knows the nodes at its ends (ids shared by the pieces that meet there), so loops
//! are formed by how the pieces were made, not by loose proximity. Where several pieces leave
//! a node, the one turning most to the left is taken: with the material on the left of every
//! piece, two loops that touch at one point stay two loops.

use super::{Contour, Segment, Vector};

/// A piece of boundary, with the material on its left, between two nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// The geometry.
    pub segment: Segment,
    /// Node at the start.
    pub start: usize,
    /// Node at the end.
    pub end: usize,
    /// What made the piece.
    pub source: Source,
}

/// What made a [`Piece`]: an element of the profile (numbered among all elements worked on
/// together; for a caller that does not offset, whatever the caller numbers) or the joint at
/// the end of element k, where it meets the next one.
///
/// ```
/// use pocketeer::geom::Source;
/// // Two elements and their two joints in one table: elements first, then joints.
/// assert_eq!(Source::Element(1).index(2), 1);
/// assert_eq!(Source::Joint(1).index(2), 3);
/// assert_eq!(Source::Joint(1).element(), 1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Source {
    /// The element k, moved by the offset distance.
    Element(u32),
    /// The joint at the end of element k: the arc or chord closing the gap between the moved
    /// element k and the next.
    Joint(u32),
}

impl Source {
    /// The element: the piece's own, or the one at whose end the joint lies.
    pub fn element(self) -> u32 {
        match self {
            Source::Element(k) | Source::Joint(k) => k,
        }
    }

    /// Position in a table of `elements` elements followed by as many joints.
    pub fn index(self, elements: usize) -> usize {
        match self {
            Source::Element(k) => k as usize,
            Source::Joint(k) => elements + k as usize,
        }
    }
}

/// The closed loops the pieces form, and how many pieces could not be closed into one.
///
/// ```
/// use pocketeer::geom::{stitch, Line, Piece, Point, Segment, Source};
/// let p = |x, y| Point::new(x, y);
/// let corners = [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
/// let pieces: Vec<Piece> = (0..4)
///     .map(|k| Piece { segment: Segment::Line(Line::new(corners[k], corners[(k + 1) % 4])), start: k, end: (k + 1) % 4, source: Source::Element(k as u32) })
///     .collect();
/// let (loops, lost) = stitch(&pieces);
/// assert_eq!((loops.len(), lost), (1, 0));
/// assert!((loops[0].signed_area() - 1.0).abs() < 1e-12);
/// ```
pub fn stitch(pieces: &[Piece]) -> (Vec<Contour>, usize) {
    stitch_kept(pieces, &PieceGraph::new(pieces), &vec![true; pieces.len()])
}

/// [`stitch`] over the pieces `kept` marks, with their graph already built.
///
/// A walk that comes back to a node it passed (a loop touching itself at a point) closes the
/// loop from there and goes on with the rest: the loops returned pass each node once. Where
/// offset curves meet tangentially the turns at a node are equal to within rounding, and this
/// keeps a sliver beyond the meeting point a loop of its own (one that the caller can tell
/// by its area) instead of a detour of its neighbour's.
pub(crate) fn stitch_kept(pieces: &[Piece], graph: &PieceGraph, kept: &[bool]) -> (Vec<Contour>, usize) {
    let mut used: Vec<bool> = kept.iter().map(|k| !k).collect();
    let mut loops = Vec::new();
    let mut lost = 0;
    let mut chain: Vec<usize> = Vec::new();
    // Where in `chain` the piece leaving each node the walk passed is (stale entries are
    // told by the check below, never cleared).
    let mut passed: Vec<usize> = vec![usize::MAX; graph.nodes()];
    for start in 0..pieces.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        chain.clear();
        chain.push(start);
        passed[pieces[start].start] = 0;
        loop {
            let node = pieces[chain[chain.len() - 1]].end;
            // An entry counts only while it names a piece of this walk leaving the node: marks
            // left by earlier walks, or by loops closed since, name none (every push marks
            // its node afresh, and a walk passes a node once before closing there).
            let at = passed[node];
            if at < chain.len() && pieces[chain[at]].start == node {
                loops.push(Contour::new(
                    chain[at..].iter().map(|&k| pieces[k].segment).collect(),
                ));
                chain.truncate(at);
                if at == 0 {
                    break;
                }
            }
            let last = &pieces[chain[chain.len() - 1]];
            let options = graph.leaving(last.end);
            let mut open = options.iter().copied().filter(|&i| !used[i]);
            let next = if options.len() == 1 {
                open.next()
            } else {
                let incoming = last.segment.tangent_at(1.0);
                open.max_by(|&a, &b| {
                    turn_key(incoming, &pieces[a].segment)
                        .partial_cmp(&turn_key(incoming, &pieces[b].segment))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
            };
            match next {
                Some(i) => {
                    used[i] = true;
                    passed[pieces[i].start] = chain.len();
                    chain.push(i);
                }
                None => {
                    lost += chain.len();
                    break;
                }
            }
        }
    }
    (loops, lost)
}

/// The pieces leaving and entering each node. Node ids are small integers (indices of some
/// list), so both are kept as offsets into one array each, not as a list per node: node ids
/// may run far beyond the number of pieces.
pub(crate) struct PieceGraph {
    /// `leaving[first_leaving[n]..first_leaving[n + 1]]`: the pieces starting at node n.
    first_leaving: Vec<usize>,
    leaving: Vec<usize>,
    /// Likewise for the pieces ending at node n.
    first_entering: Vec<usize>,
    entering: Vec<usize>,
}

impl PieceGraph {
    /// The graph of `pieces`, in their order at every node.
    pub(crate) fn new(pieces: &[Piece]) -> PieceGraph {
        let nodes = pieces.iter().map(|p| p.start.max(p.end) + 1).max().unwrap_or(0);
        let (first_leaving, leaving) = by_node(pieces, nodes, |p| p.start);
        let (first_entering, entering) = by_node(pieces, nodes, |p| p.end);
        PieceGraph {
            first_leaving,
            leaving,
            first_entering,
            entering,
        }
    }

    /// One more than the largest node id.
    pub(crate) fn nodes(&self) -> usize {
        self.first_leaving.len() - 1
    }

    /// The pieces starting at `node`.
    pub(crate) fn leaving(&self, node: usize) -> &[usize] {
        &self.leaving[self.first_leaving[node]..self.first_leaving[node + 1]]
    }

    /// The pieces ending at `node`.
    pub(crate) fn entering(&self, node: usize) -> &[usize] {
        &self.entering[self.first_entering[node]..self.first_entering[node + 1]]
    }
}

/// The pieces grouped by a node of theirs (`node_of`): `list[first[n]..first[n + 1]]` holds
/// the pieces at node `n`.
fn by_node(pieces: &[Piece], nodes: usize, node_of: impl Fn(&Piece) -> usize) -> (Vec<usize>, Vec<usize>) {
    let mut first = vec![0usize; nodes + 1];
    for p in pieces {
        first[node_of(p) + 1] += 1;
    }
    for n in 0..nodes {
        first[n + 1] += first[n];
    }
    let mut fill = first.clone();
    let mut list = vec![0usize; pieces.len()];
    for (i, p) in pieces.iter().enumerate() {
        let n = node_of(p);
        list[fill[n]] = i;
        fill[n] += 1;
    }
    (first, list)
}

/// How far left `next` turns after travelling along `incoming`: the turn angle (a reversal
/// counts as the sharpest right turn), then the curvature.
fn turn_key(incoming: Vector, next: &Segment) -> (f64, f64) {
    let out = next.tangent_at(0.0);
    let mut angle = incoming.cross(out).atan2(incoming.dot(out));
    if angle >= std::f64::consts::PI - 1e-12 {
        angle = -std::f64::consts::PI;
    }
    let curvature = match next {
        Segment::Line(_) => 0.0,
        Segment::Arc(a) => a.sweep().signum() / a.radius(),
    };
    (angle, curvature)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Line, Point};

    /// Pieces along `path`, a list of (node, point), closed back to its first entry.
    fn pieces_along(path: &[(usize, Point)]) -> Vec<Piece> {
        (0..path.len())
            .map(|k| {
                let ((a, p), (b, q)) = (path[k], path[(k + 1) % path.len()]);
                Piece {
                    segment: Segment::Line(Line::new(p, q)),
                    start: a,
                    end: b,
                    source: Source::Element(k as u32),
                }
            })
            .collect()
    }

    #[test]
    fn a_walk_back_through_a_node_it_passed_closes_a_loop_there() {
        let p = Point::new;
        // A 4 × 4 square whose bottom edge passes node 1 twice: once into a triangle inside it
        // (the sharpest left turn there), once out of it. Two loops, not one of area 17.
        let pieces = pieces_along(&[
            (0, p(0.0, 0.0)),
            (1, p(2.0, 0.0)),
            (2, p(3.0, 1.0)),
            (3, p(1.0, 1.0)),
            (1, p(2.0, 0.0)),
            (4, p(4.0, 0.0)),
            (5, p(4.0, 4.0)),
            (6, p(0.0, 4.0)),
        ]);
        let (loops, lost) = stitch(&pieces);
        assert_eq!(lost, 0);
        let mut areas: Vec<f64> = loops.iter().map(Contour::signed_area).collect();
        areas.sort_by(f64::total_cmp);
        assert_eq!(areas.len(), 2, "{areas:?}");
        assert!(
            (areas[0] - 1.0).abs() < 1e-12 && (areas[1] - 16.0).abs() < 1e-12,
            "{areas:?}"
        );
    }
}
