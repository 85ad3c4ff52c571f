//! End points merged into nodes: ends within the coincidence distance of each other (on one
//! layer) are one node, at the mean of their positions. This is the drawing's own topology,
//! the same whatever the join tolerance; joining ends that are farther apart is
//! [`super::free_ends`]'s work.

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
    /// Nodes whose ends were moved by more than rounding to meet.
    pub(super) gaps_closed: usize,
    /// The largest gap closed (twice the farthest an end moved to its node), mm.
    pub(super) largest_gap: f64,
    /// Where that was.
    pub(super) largest_gap_at: Point,
}

impl Nodes {
    /// Nodes of the live elements' ends.
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
        let cluster = cluster_points_by(&ends, node_distance(tol), |i| elements[live[i] / 2].layer);
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
                nodes.record_gap(2.0 * m, nodes.pos[id]);
            }
        }
        nodes
    }

    /// Counts a gap of `size` closed at `at`.
    pub(super) fn record_gap(&mut self, size: f64, at: Point) {
        self.gaps_closed += 1;
        if size > self.largest_gap {
            self.largest_gap = size;
            self.largest_gap_at = at;
        }
    }

    /// The node of an element end.
    pub(super) fn node(&self, (e, end): End) -> usize {
        self.node_of[2 * e + end as usize]
    }

    /// Where an element end lies after joining.
    pub(super) fn point(&self, end: End) -> Point {
        self.pos[self.node(end)]
    }

    /// How many live element ends meet at each node.
    pub(super) fn degrees(&self, alive: &[bool]) -> Vec<usize> {
        let mut degree = vec![0; self.pos.len()];
        for (k, &id) in self.node_of.iter().enumerate() {
            if alive.get(k / 2) == Some(&true) {
                degree[id] += 1;
            }
        }
        degree
    }

    /// Joins the node of end `b` into the node of end `a`, both now at `at`. Only for nodes
    /// holding one end each (free ends), so no other end moves.
    pub(super) fn merge(&mut self, a: End, b: End, at: Point) {
        let (na, nb) = (self.node(a), self.node(b));
        self.pos[na] = at;
        self.pos[nb] = at;
        self.node_of[2 * b.0 + b.1 as usize] = na;
    }

    /// Gives a new element (a segment bridging a gap) the nodes of its two ends.
    pub(super) fn attach(&mut self, start_node: usize, end_node: usize) {
        self.node_of.push(start_node);
        self.node_of.push(end_node);
    }
}

/// Ends this near are one node whatever the join tolerance: far below any tolerance a user
/// sets, far above rounding, so the nodes are the drawing's topology. A join tolerance set
/// below it (asking for exact ends) lowers it.
pub(super) fn node_distance(tol: &Tolerance) -> f64 {
    tol.coincident().min(tol.join.max(tol.rounding()))
}
