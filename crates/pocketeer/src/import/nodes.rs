//! End points merged into nodes: ends within the join tolerance of each other (on one layer)
//! are one node, at the mean of their positions; how far that moved them is reported as the
//! gaps closed.

use super::chain::End;
use super::Element;
use crate::geom::{cluster_points_by, Point, Tolerance};
use std::collections::HashMap;

/// End points merged into nodes.
pub(super) struct Nodes {
    /// Node of each element end: `node_of[2 * element + end]`.
    pub(super) node_of: Vec<usize>,
    /// Node positions (mean of their end points).
    pub(super) pos: Vec<Point>,
    pub(super) gaps_closed: usize,
    pub(super) largest_gap: f64,
    pub(super) largest_gap_at: Point,
}

impl Nodes {
    pub(super) fn build(elements: &[Element], alive: &[bool], tol: &Tolerance) -> Nodes {
        let n = elements.len();
        let end_point = |k: usize| {
            let s = &elements[k / 2].segment;
            if k % 2 == 0 {
                s.start()
            } else {
                s.end()
            }
        };
        // Contours are chained within their layer only; dead elements' ends take no part.
        let live: Vec<usize> = (0..2 * n).filter(|&k| alive[k / 2]).collect();
        let ends: Vec<Point> = live.iter().map(|&k| end_point(k)).collect();
        let cluster = cluster_points_by(&ends, tol.join.max(tol.eps), |i| elements[live[i] / 2].layer);
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut node_of = vec![usize::MAX; 2 * n];
        let mut sums: Vec<(f64, f64, usize)> = Vec::new();
        for (i, &k) in live.iter().enumerate() {
            let id = *index.entry(cluster[i]).or_insert_with(|| {
                sums.push((0.0, 0.0, 0));
                sums.len() - 1
            });
            node_of[k] = id;
            sums[id].0 += ends[i].x;
            sums[id].1 += ends[i].y;
            sums[id].2 += 1;
        }
        let pos: Vec<Point> = sums
            .iter()
            .map(|&(x, y, c)| Point::new(x / c as f64, y / c as f64))
            .collect();
        let mut nodes = Nodes {
            node_of,
            pos,
            gaps_closed: 0,
            largest_gap: 0.0,
            largest_gap_at: Point::ORIGIN,
        };
        let mut moved = vec![0.0f64; nodes.pos.len()];
        for (i, &k) in live.iter().enumerate() {
            let id = nodes.node_of[k];
            moved[id] = moved[id].max(ends[i].distance(nodes.pos[id]));
        }
        for (id, &m) in moved.iter().enumerate() {
            // Rounding in the writer's coordinates is not a gap.
            if m > tol.rounding() {
                nodes.gaps_closed += 1;
                if m > nodes.largest_gap {
                    nodes.largest_gap = m;
                    nodes.largest_gap_at = nodes.pos[id];
                }
            }
        }
        nodes
    }

    pub(super) fn node(&self, (e, end): End) -> usize {
        self.node_of[2 * e + end as usize]
    }

    pub(super) fn point(&self, end: End) -> Point {
        self.pos[self.node(end)]
    }
}
