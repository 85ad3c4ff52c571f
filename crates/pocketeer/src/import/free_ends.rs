//! Joining free ends: element ends that meet no other end once the drawing's own nodes are
//! built. Two free ends are joined only with each other, nearest pairs first, so that raising
//! a tolerance never undoes a join made at a lower one:
//!
//! * within the join tolerance, both ends move to their midpoint (each by half the gap);
//! * farther, up to the gap-closing length, a straight segment bridges them, but only when the
//!   pair is unambiguous: no other free end lies within five times the gap of either end.
//!
//! An element's own two ends join only when it is much longer than the gap (an arc of almost a
//! full turn): a short line never collapses into a point.

use super::chain::End;
use super::nodes::Nodes;
use super::Element;
use crate::geom::{Aabb, BoxIndex, Point};

/// How much nearer the joined free end must be than any other, for a gap to be bridged.
pub(super) const UNAMBIGUOUS: f64 = 5.0;

/// A gap between two free ends closed with a straight segment.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bridge {
    /// The end the segment starts at.
    pub(super) from: End,
    /// The end it runs to.
    pub(super) to: End,
}

/// Joins the free ends of the live `elements`: snaps the pairs within `join` in `nodes`, and
/// returns the pairs to bridge (up to `close_gaps`, unambiguous ones only).
pub(super) fn join_free_ends(
    elements: &[Element],
    alive: &[bool],
    nodes: &mut Nodes,
    join: f64,
    close_gaps: f64,
) -> Vec<Bridge> {
    let reach = join.max(close_gaps);
    if reach <= 0.0 {
        return Vec::new();
    }
    let degree = nodes.degrees(alive);
    let free: Vec<End> = (0..elements.len())
        .filter(|&i| alive[i])
        .flat_map(|i| [(i, 0), (i, 1)])
        .filter(|&e| degree[nodes.node(e)] == 1)
        .collect();
    let pts: Vec<Point> = free.iter().map(|&e| nodes.point(e)).collect();
    let layer = |k: usize| elements[free[k].0].layer;
    let boxes: Vec<Aabb> = pts.iter().map(|&p| Aabb::from_points(p, p)).collect();
    let index = BoxIndex::new(&boxes);

    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for a in 0..free.len() {
        for b in index.intersecting(&boxes[a].inflated(reach)) {
            if b <= a || layer(a) != layer(b) {
                continue;
            }
            let d = pts[a].distance(pts[b]);
            let own = free[a].0 == free[b].0;
            if d <= reach && (!own || elements[free[a].0].segment.length() > 4.0 * d) {
                pairs.push((d, a, b));
            }
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));

    let mut taken = vec![false; free.len()];
    for &(d, a, b) in pairs.iter().take_while(|p| p.0 <= join) {
        if !taken[a] && !taken[b] {
            taken[a] = true;
            taken[b] = true;
            let at = pts[a].midpoint(pts[b]);
            nodes.merge(free[a], free[b], at);
            nodes.record_gap(d, at);
        }
    }
    // Whether a bridge is ambiguous is judged against every free end not snapped, bridged or
    // not, so that a larger join tolerance (fewer such ends) never forbids a bridge.
    let snapped = taken.clone();
    let crowded = |me: usize, a: usize, b: usize, d: f64| {
        let r = UNAMBIGUOUS * d;
        index
            .intersecting(&boxes[me].inflated(r))
            .any(|c| c != a && c != b && !snapped[c] && layer(c) == layer(me) && pts[c].distance(pts[me]) < r)
    };
    let mut bridges = Vec::new();
    for &(d, a, b) in pairs.iter().filter(|p| p.0 > join && p.0 <= close_gaps) {
        if !taken[a] && !taken[b] && !crowded(a, a, b, d) && !crowded(b, a, b, d) {
            taken[a] = true;
            taken[b] = true;
            bridges.push(Bridge {
                from: free[a],
                to: free[b],
            });
        }
    }
    bridges
}
