//! Ways at depth round what is in the way: a short chain of straight moves from one point to
//! another through a region the caller describes only by which straight moves it allows (in
//! the linker: the moves that keep the tool centre a part's distance from every wall).
//!
//! The search runs on a square lattice through the start (A* with the straight-line distance
//! to the goal as its estimate, eight neighbours, each step tested as a move), then pulls the
//! lattice path tight: from each corner, straight to the farthest later corner the region
//! allows. Every move of the answer is one the caller allowed, whatever the lattice's
//! resolution; the resolution only decides which narrow passages are found.

use crate::geom::Point;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};
use std::hash::{BuildHasherDefault, Hasher};

/// Most lattice points expanded in one search: beyond it there is no way short enough, or it
/// winds through a maze the lattice does not resolve, and the caller goes over the top.
const MAX_EXPANDED: usize = 4_000;

/// A chain of straight moves from `a` to `b` at most `max_length` long, each allowed by
/// `free(from, to)`, searched on a lattice of spacing `step`: the corners after `a`, the last
/// being `b`. `None` when the lattice finds no such way within its budget.
///
/// ```
/// use pocketeer::geom::Point;
/// use pocketeer::link::detour;
/// // A wall on the line x = 5 from y = -10 to y = 4: the way from (0, 0) to (10, 0) goes
/// // over its top end.
/// let free = |p: Point, q: Point| {
///     let t = (5.0 - p.x) / (q.x - p.x);
///     !((0.0..=1.0).contains(&t) && p.y + t * (q.y - p.y) < 4.5)
/// };
/// let way = detour(Point::new(0.0, 0.0), Point::new(10.0, 0.0), 0.5, 30.0, free).unwrap();
/// assert_eq!(way.last(), Some(&Point::new(10.0, 0.0)));
/// assert!(way.len() >= 2 && way.iter().any(|p| p.y >= 4.5));
/// ```
pub fn detour(
    a: Point,
    b: Point,
    step: f64,
    max_length: f64,
    free: impl Fn(Point, Point) -> bool,
) -> Option<Vec<Point>> {
    if !(step > 0.0 && max_length.is_finite()) || a.distance(b) > max_length {
        return None;
    }
    if free(a, b) {
        return Some(vec![b]);
    }
    let at = |(i, j): (i64, i64)| Point::new(a.x + i as f64 * step, a.y + j as f64 * step);
    let reach = 1.5 * step;
    // Best known length to each lattice point, and the point it was reached from.
    let mut best: Lattice<(f64, (i64, i64))> = Lattice::default();
    let mut open = BinaryHeap::new();
    best.insert((0, 0), (0.0, (0, 0)));
    open.push(Open {
        estimate: a.distance(b),
        length: 0.0,
        node: (0, 0),
    });
    let mut expanded = 0;
    let mut goal = None;
    while let Some(Open { length, node, .. }) = open.pop() {
        if best.get(&node).is_some_and(|&(g, _)| g < length) {
            continue; // a shorter way to it was found after this entry was queued
        }
        expanded += 1;
        if expanded > MAX_EXPANDED {
            return None;
        }
        let p = at(node);
        if p.distance(b) <= reach && free(p, b) {
            goal = Some(node);
            break;
        }
        for (di, dj) in NEIGHBOURS {
            let next = (node.0 + di, node.1 + dj);
            let q = at(next);
            let g = length + p.distance(q);
            let estimate = g + q.distance(b);
            if estimate > max_length || best.get(&next).is_some_and(|&(h, _)| h <= g) || !free(p, q) {
                continue;
            }
            best.insert(next, (g, node));
            open.push(Open {
                estimate,
                length: g,
                node: next,
            });
        }
    }
    let mut corners = vec![b];
    let mut node = goal?;
    while node != (0, 0) {
        corners.push(at(node));
        node = best[&node].1;
    }
    corners.push(a);
    corners.reverse();
    let way = pulled_tight(&corners, &free);
    let length: f64 = std::iter::once(a)
        .chain(way.iter().copied())
        .collect::<Vec<_>>()
        .windows(2)
        .map(|w| w[0].distance(w[1]))
        .sum();
    (length <= max_length).then_some(way)
}

/// The corners of `chain` (its first point the start) that a way pulled tight keeps: from each
/// kept corner straight to the farthest later one `free` allows. Neighbouring corners are
/// known to be allowed, so the way always reaches the end.
fn pulled_tight(chain: &[Point], free: &impl Fn(Point, Point) -> bool) -> Vec<Point> {
    let mut kept = Vec::new();
    let mut i = 0;
    while i + 1 < chain.len() {
        let mut j = chain.len() - 1;
        while j > i + 1 && !free(chain[i], chain[j]) {
            j -= 1;
        }
        kept.push(chain[j]);
        i = j;
    }
    kept
}

/// A map keyed by lattice points.
type Lattice<V> = HashMap<(i64, i64), V, BuildHasherDefault<LatticeHasher>>;

/// Hashes lattice points with a multiplication a coordinate, where the standard map's default
/// (SipHash, made to withstand chosen keys, which these are not) took a fifth of a search.
#[derive(Default)]
struct LatticeHasher(u64);

impl Hasher for LatticeHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x517c_c1b7_2722_0a95);
    }

    fn write_i64(&mut self, n: i64) {
        self.write_u64(n as u64);
    }
}

const NEIGHBOURS: [(i64, i64); 8] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
];

/// A lattice point waiting to be expanded, the smallest estimate first.
struct Open {
    estimate: f64,
    length: f64,
    node: (i64, i64),
}

impl PartialEq for Open {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Open {}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed: BinaryHeap pops the greatest.
        other
            .estimate
            .total_cmp(&self.estimate)
            .then(other.node.cmp(&self.node))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Moves that keep at least `d` from the centre of a disc of radius `r` at the origin.
    fn round(r: f64, d: f64) -> impl Fn(Point, Point) -> bool {
        move |p: Point, q: Point| {
            let v = q - p;
            let len2 = v.x * v.x + v.y * v.y;
            let t = if len2 > 0.0 {
                (-(p.x * v.x + p.y * v.y) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let c = Point::new(p.x + t * v.x, p.y + t * v.y);
            c.distance(Point::new(0.0, 0.0)) >= r + d
        }
    }

    fn length(a: Point, way: &[Point]) -> f64 {
        let mut last = a;
        let mut total = 0.0;
        for &p in way {
            total += last.distance(p);
            last = p;
        }
        total
    }

    #[test]
    fn a_free_straight_move_is_the_way() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(3.0, 4.0));
        assert_eq!(detour(a, b, 0.5, 10.0, |_, _| true), Some(vec![b]));
        assert_eq!(detour(a, b, 0.5, 4.0, |_, _| true), None, "longer than allowed");
    }

    #[test]
    fn the_way_round_a_disc_is_nearly_the_shortest_and_every_move_is_allowed() {
        // Round a disc of radius 5 kept 3 away: the shortest way from (-10, 0) to (10, 0)
        // is two tangents and an arc of radius 8, 2 * (sqrt(100 - 64) + 8 * asin(... )).
        let free = round(5.0, 3.0);
        let (a, b) = (Point::new(-10.0, 0.0), Point::new(10.0, 0.0));
        let way = detour(a, b, 0.5, 40.0, &free).unwrap();
        let tangent = (100.0f64 - 64.0).sqrt();
        let arc = 8.0 * (std::f64::consts::PI - 2.0 * (8.0f64 / 10.0).acos());
        let shortest = 2.0 * tangent + arc;
        let got = length(a, &way);
        assert!(
            got >= shortest - 1e-9 && got < 1.05 * shortest,
            "{got} against {shortest}"
        );
        let mut last = a;
        for &p in &way {
            assert!(free(last, p), "{last:?} -> {p:?}");
            last = p;
        }
        assert_eq!(*way.last().unwrap(), b);
    }

    #[test]
    fn no_way_when_the_region_is_cut_in_two_or_the_way_is_too_long() {
        let wall = |p: Point, q: Point| (p.x < 5.0) == (q.x < 5.0);
        assert_eq!(
            detour(Point::new(0.0, 0.0), Point::new(10.0, 0.0), 0.5, 100.0, wall),
            None
        );
        let free = round(5.0, 3.0);
        let (a, b) = (Point::new(-10.0, 0.0), Point::new(10.0, 0.0));
        assert_eq!(detour(a, b, 0.5, 20.5, free), None, "the way round is 21.1 long");
    }
}
