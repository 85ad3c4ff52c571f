//! Raw offset (paper §4): every line moved sideways by d, every arc's radius changed by d, and
//! an arc of radius d around every joint where the moved elements part.

use crate::geom::{Arc, Contour, Line, Piece, Segment, Tolerance};
use std::f64::consts::PI;

/// The raw offset of a closed contour by `d` to its left (the side the material to remove is
/// on), as pieces whose node ids start at `next_node`; returns the pieces and the next free id.
///
/// Consecutive pieces share a node where they meet: where the moved elements part (a turn to
/// the right), a node arc joins them; where they overlap (a turn to the left), their ends stay
/// apart and the split stage finds where they cross.
pub fn raw_offset(contour: &Contour, d: f64, tol: &Tolerance, mut next_node: usize) -> (Vec<Piece>, usize) {
    let segs = &contour.segments;
    let n = segs.len();
    let moved: Vec<Option<Segment>> = segs.iter().map(|s| offset_segment(s, d, tol)).collect();
    let mut pieces = Vec::with_capacity(2 * n);
    // Node at the start of each moved element: shared with the previous element's end when the
    // two meet, fresh otherwise.
    let first_node = next_node;
    let mut start_node = vec![usize::MAX; n];
    let mut end_node = vec![usize::MAX; n];
    for k in 0..n {
        start_node[k] = next_node;
        next_node += 1;
        end_node[k] = next_node; // provisional; fixed below where the next element meets it
        next_node += 1;
    }
    let mut joints: Vec<Option<Piece>> = vec![None; n];
    for k in 0..n {
        let j = (k + 1) % n;
        let (Some(a), Some(b)) = (moved[k], moved[j]) else {
            continue;
        };
        let gap = a.end().distance(b.start());
        if gap <= 10.0 * tol.eps {
            end_node[k] = start_node[j];
            continue;
        }
        let t_in = segs[k].tangent_at(1.0);
        let t_out = segs[j].tangent_at(0.0);
        if t_in.cross(t_out) < 0.0 || (t_in.cross(t_out) == 0.0 && t_in.dot(t_out) < 0.0) {
            // A turn to the right: the moved elements part; an arc of radius d around the
            // joint closes the gap, turning the same way.
            let corner = segs[k].end();
            let a0 = (a.end() - corner).angle();
            let a1 = (b.start() - corner).angle();
            let mut sweep = (a1 - a0).rem_euclid(2.0 * PI);
            if sweep > 0.0 {
                sweep -= 2.0 * PI;
            }
            let arc = Arc::new(corner, d, a0, sweep);
            joints[k] = Some(Piece {
                segment: Segment::Arc(arc),
                start: end_node[k],
                end: start_node[j],
            });
        }
    }
    for k in 0..n {
        if let Some(s) = moved[k] {
            pieces.push(Piece {
                segment: s,
                start: start_node[k],
                end: end_node[k],
            });
        }
        if let Some(p) = joints[k] {
            pieces.push(p);
        }
    }
    debug_assert!(next_node >= first_node);
    (pieces, next_node)
}

/// One element moved by `d` to its left; `None` when it collapses to a point.
fn offset_segment(s: &Segment, d: f64, tol: &Tolerance) -> Option<Segment> {
    match s {
        Segment::Line(l) => {
            let n = l.direction()?.perp() * d;
            Some(Segment::Line(Line::new(l.start + n, l.end + n)))
        }
        Segment::Arc(a) => {
            // Left of a counter-clockwise arc is towards its centre.
            let r = if a.sweep > 0.0 { a.radius - d } else { a.radius + d };
            if r.abs() <= 10.0 * tol.eps {
                return None;
            }
            if r > 0.0 {
                Some(Segment::Arc(Arc::new(a.center, r, a.start_angle, a.sweep)))
            } else {
                // Offset past its centre: the paper's arc of radius |r - d| turned by 180°.
                Some(Segment::Arc(Arc::new(a.center, -r, a.start_angle + PI, a.sweep)))
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
        let contour = Contour::new(
            (0..4)
                .map(|k| Segment::Line(Line::new(c[k], c[(k + 1) % 4])))
                .collect(),
        );
        let (pieces, next) = raw_offset(&contour, 2.0, &Tolerance::default(), 0);
        assert_eq!(pieces.len(), 8);
        assert_eq!(next, 8);
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
}
