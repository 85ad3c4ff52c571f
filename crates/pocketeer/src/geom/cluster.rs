//! Clustering points: the one mechanism by which ends near each other become one node, for the
//! importer's chaining (drawn end points) and its nesting (the ends of pieces cut at crossings).

use super::Point;
use crate::union_find::UnionFind;
use std::collections::HashMap;

/// Node ids for points: points closer than `r` (transitively) share an id, the index of one
/// of them.
///
/// ```
/// use pocketeer::geom::{cluster_points, Point};
/// let p = Point::new;
/// let id = cluster_points(&[p(0.0, 0.0), p(5.0, 0.0), p(0.0, 0.0005), p(0.0, 0.0012)], 0.001);
/// assert_eq!(id[0], id[2]);
/// assert_eq!(id[2], id[3]); // within r of the third, so of the first's node too
/// assert_ne!(id[0], id[1]);
/// ```
pub fn cluster_points(points: &[Point], r: f64) -> Vec<usize> {
    cluster_points_by(points, r, |_| 0)
}

/// [`cluster_points`] where only points of the same `group` (such as a layer) may share a node.
///
/// Points exactly where an earlier point of their group is join its node without being
/// compared again, so that thousands of ends drawn on one spot cost no more than one.
///
/// ```
/// use pocketeer::geom::{cluster_points_by, Point};
/// let p = Point::new(1.0, 1.0);
/// let layer = [0, 1, 0];
/// let id = cluster_points_by(&[p, p, p], 0.001, |k| layer[k]);
/// assert_eq!(id[0], id[2]);
/// assert_ne!(id[0], id[1]);
/// ```
pub fn cluster_points_by(points: &[Point], r: f64, group: impl Fn(usize) -> usize) -> Vec<usize> {
    let cell = |p: Point| ((p.x / r).floor() as i64, (p.y / r).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut exact: HashMap<(u64, u64, usize), usize> = HashMap::new();
    let mut sets = UnionFind::new(points.len());
    for (k, &p) in points.iter().enumerate() {
        let g = group(k);
        match exact.entry((p.x.to_bits(), p.y.to_bits(), g)) {
            std::collections::hash_map::Entry::Occupied(o) => {
                sets.union(*o.get(), k);
                continue;
            }
            std::collections::hash_map::Entry::Vacant(v) => {
                v.insert(k);
            }
        }
        let (cx, cy) = cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &o in grid.get(&(cx + dx, cy + dy)).map(Vec::as_slice).unwrap_or(&[]) {
                    if group(o) == g && points[o].distance(p) <= r {
                        sets.union(o, k);
                    }
                }
            }
        }
        grid.entry((cx, cy)).or_default().push(k);
    }
    (0..points.len()).map(|k| sets.find(k)).collect()
}
