//! The faces of an outline that branches: where three or more strokes meet at a node (a
//! rectangle divided by a line, a part drawn with its internal edges), no pairing of the ends
//! is the outline. The strokes are taken as the edges of a planar graph and its bounded faces
//! traced, each the loop that keeps turning right at every node; nesting then merges faces
//! that share edges, so the region is what the strokes enclose, by the even-odd rule.

use crate::geom::{Contour, Segment};

/// One edge of the graph: its segments in order from node `ends[0]` to `ends[1]`.
pub(super) struct Edge {
    pub(super) segments: Vec<Segment>,
    pub(super) ends: [usize; 2],
}

/// The bounded faces of the graph of `edges` (counter-clockwise loops; the unbounded face
/// of each connected part, clockwise, is left out), each with the edges it runs along.
pub(super) fn bounded_faces(edges: &[Edge]) -> Vec<(Contour, Vec<usize>)> {
    // Half-edge 2k runs edge k forward, 2k + 1 backward.
    let start = |h: usize| edges[h / 2].ends[h % 2];
    let departure = |h: usize| {
        let segs = &edges[h / 2].segments;
        if h % 2 == 0 {
            segs[0].tangent_at(0.0).angle()
        } else {
            (-segs[segs.len() - 1].tangent_at(1.0)).angle()
        }
    };
    let mut leaving: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
    for h in 0..2 * edges.len() {
        leaving.entry(start(h)).or_default().push(h);
    }
    for hs in leaving.values_mut() {
        hs.sort_by(|&a, &b| departure(a).total_cmp(&departure(b)));
    }
    // After half-edge h, the face on its left goes on along the half-edge leaving h's end
    // next clockwise from h's twin.
    let next = |h: usize| {
        let twin = h ^ 1;
        let around = &leaving[&start(twin)];
        let at = around.iter().position(|&x| x == twin).unwrap_or(0);
        around[(at + around.len() - 1) % around.len()]
    };
    let mut done = vec![false; 2 * edges.len()];
    let mut faces = Vec::new();
    for first in 0..2 * edges.len() {
        if done[first] {
            continue;
        }
        let mut segments = Vec::new();
        let mut along = Vec::new();
        let mut h = first;
        while !done[h] {
            done[h] = true;
            along.push(h / 2);
            let segs = &edges[h / 2].segments;
            if h % 2 == 0 {
                segments.extend(segs.iter().copied());
            } else {
                segments.extend(segs.iter().rev().map(Segment::reversed));
            }
            h = next(h);
        }
        let face = Contour::new(segments);
        if face.signed_area() > 0.0 {
            faces.push((face, along));
        }
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Line, Point};

    fn edge(pts: &[(f64, f64)], ends: [usize; 2]) -> Edge {
        let p: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
        Edge {
            segments: p
                .windows(2)
                .map(|w| Segment::Line(Line::new(w[0], w[1])))
                .collect(),
            ends,
        }
    }

    #[test]
    fn a_divided_rectangle_has_two_faces() {
        // Node 0 at (5, 0), node 1 at (5, 10): the rectangle's two halves and the divider.
        let edges = [
            edge(&[(5.0, 0.0), (10.0, 0.0), (10.0, 10.0), (5.0, 10.0)], [0, 1]),
            edge(&[(5.0, 10.0), (0.0, 10.0), (0.0, 0.0), (5.0, 0.0)], [1, 0]),
            edge(&[(5.0, 0.0), (5.0, 10.0)], [0, 1]),
        ];
        let faces = bounded_faces(&edges);
        assert_eq!(faces.len(), 2);
        for (f, along) in &faces {
            assert!((f.signed_area() - 50.0).abs() < 1e-9);
            assert!(along.contains(&2));
        }
    }
}
