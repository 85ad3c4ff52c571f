//! A static packed R-tree: boxes sorted along a Hilbert curve and grouped sixteen to a node,
//! height by height, in flat arrays. Built once in O(n log n), it answers box and distance
//! queries without allocating per node, and a small set of boxes is a single node that a query
//! scans straight through.

use super::{Aabb, Point};
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Children per node: a node's boxes fit in a few cache lines and are scanned in a row.
const NODE_SIZE: usize = 16;

/// Boxes indexed for overlap and nearest queries; items are the boxes' positions in the slice
/// the tree was built from.
///
/// ```
/// use pocketeer::geom::{Aabb, PackedTree, Point};
/// let b = |x0, y0, x1, y1| Aabb::from_points(Point::new(x0, y0), Point::new(x1, y1));
/// let boxes: Vec<Aabb> = (0..100).map(|k| b(k as f64, 0.0, k as f64 + 0.5, 1.0)).collect();
/// let tree = PackedTree::new(&boxes);
/// let mut hits: Vec<usize> = tree.search(|x| x.intersects(&b(10.2, 0.0, 12.2, 0.5))).collect();
/// hits.sort();
/// assert_eq!(hits, vec![10, 11, 12]);
/// let p = Point::new(40.7, 3.0);
/// let (nearest, _) = tree.nearest(|x| x.distance_sq(p).sqrt(), |i| boxes[i].distance_sq(p).sqrt()).unwrap();
/// assert_eq!(nearest, 40);
/// ```
pub struct PackedTree {
    /// Height 0: the items' boxes in tree order; then the nodes of each height up to the root.
    boxes: Vec<Aabb>,
    /// Height 0: the item at that position; above: the position of the node's first child.
    ids: Vec<usize>,
    /// Where each height ends in `boxes`.
    height_ends: Vec<usize>,
}

/// Position of the cell (x, y) along a Hilbert curve over a 65536 × 65536 grid.
/// `items` ordered by `key`, equal keys in their order: a stable radix sort of the keys a byte at
/// a time (four passes over the items, a pass skipped where every key has the same byte), which
/// orders the hundred thousand boxes of a large drawing several times faster than comparing.
fn sorted_by_key(items: Vec<usize>, key: impl Fn(usize) -> u32) -> Vec<usize> {
    let mut pairs: Vec<(u32, usize)> = items.into_iter().map(|i| (key(i), i)).collect();
    let n = pairs.len();
    if n < 256 {
        pairs.sort_by_key(|p| p.0);
    } else {
        let mut other = vec![(0u32, 0usize); n];
        for shift in [0, 8, 16, 24] {
            let byte = |k: u32| ((k >> shift) & 0xFF) as usize;
            let mut counts = [0usize; 256];
            for &(k, _) in &pairs {
                counts[byte(k)] += 1;
            }
            if counts.contains(&n) {
                continue;
            }
            let mut next = [0usize; 256];
            let mut total = 0;
            for (b, &c) in counts.iter().enumerate() {
                next[b] = total;
                total += c;
            }
            for &p in &pairs {
                let b = byte(p.0);
                other[next[b]] = p;
                next[b] += 1;
            }
            std::mem::swap(&mut pairs, &mut other);
        }
    }
    pairs.into_iter().map(|(_, i)| i).collect()
}

fn hilbert(mut x: u32, mut y: u32) -> u64 {
    let n: u32 = 1 << 16;
    let mut d: u64 = 0;
    let mut s = n / 2;
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        // Rotate the quadrant so that the curve inside it runs the right way.
        if ry == 0 {
            if rx == 1 {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}

impl PackedTree {
    /// Indexes `boxes`; empty boxes are left out.
    pub fn new(boxes: &[Aabb]) -> PackedTree {
        let items: Vec<usize> = (0..boxes.len()).filter(|&i| !boxes[i].is_empty()).collect();
        let extent = items.iter().fold(Aabb::EMPTY, |a, &i| a.union(&boxes[i]));
        let (w, h) = (extent.width(), extent.height());
        // Grid cell of a box's centre; `as` saturates, and a NaN box goes to cell 0.
        let cell = |v: f64, lo: f64, span: f64| -> u32 {
            if span > 0.0 {
                ((v - lo) / span * 65535.0).min(65535.0) as u32
            } else {
                0
            }
        };
        let key = |b: &Aabb| {
            let c = Point::new(0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y));
            hilbert(cell(c.x, extent.min.x, w), cell(c.y, extent.min.y, h))
        };
        // The curve's index of a cell is below 2^32 (cells are 16 bits a side).
        let items = sorted_by_key(items, |i| key(&boxes[i]) as u32);
        let mut tree_boxes: Vec<Aabb> = items.iter().map(|&i| boxes[i]).collect();
        let mut ids = items;
        let mut height_ends = vec![tree_boxes.len()];
        let mut start = 0;
        while tree_boxes.len() - start > 1 {
            let end = tree_boxes.len();
            for first in (start..end).step_by(NODE_SIZE) {
                let last = (first + NODE_SIZE).min(end);
                let b = tree_boxes[first..last]
                    .iter()
                    .fold(Aabb::EMPTY, |a, c| a.union(c));
                tree_boxes.push(b);
                ids.push(first);
            }
            start = end;
            height_ends.push(tree_boxes.len());
        }
        PackedTree {
            boxes: tree_boxes,
            ids,
            height_ends,
        }
    }

    /// Number of items indexed.
    pub fn len(&self) -> usize {
        self.height_ends[0]
    }

    /// True when nothing is indexed.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every item with its box, in tree order.
    pub fn items(&self) -> impl Iterator<Item = (usize, &Aabb)> + '_ {
        self.ids[..self.len()]
            .iter()
            .copied()
            .zip(&self.boxes[..self.len()])
    }

    /// The children of the node at `pos` on height `height` (> 0), as positions.
    fn children(&self, pos: usize, height: usize) -> std::ops::Range<usize> {
        let first = self.ids[pos];
        first..(first + NODE_SIZE).min(self.height_ends[height - 1])
    }

    /// The root's position and height, when there is anything indexed.
    fn root(&self) -> Option<(usize, usize)> {
        let pos = self.boxes.len().checked_sub(1)?;
        Some((pos, self.height_ends.len() - 1))
    }

    /// The items whose boxes pass `keep`, where `keep` must pass every box that contains a
    /// box it passes (as "intersects a query box" or "comes within r of a point" do): whole
    /// nodes failing it are skipped.
    pub fn search<K: Fn(&Aabb) -> bool>(&self, keep: K) -> Search<'_, K> {
        let mut stack = SmallVec::new();
        if let Some(root) = self.root() {
            if keep(&self.boxes[root.0]) {
                stack.push(root);
            }
        }
        Search {
            tree: self,
            keep,
            stack,
            items: 0..0,
        }
    }

    /// The item for which `exact` is least, with that value, searched best first: `bound(b)`
    /// must never exceed `exact` of an item whose box lies inside `b` (a box's distance to a
    /// point, for the distance of a segment in that box). `None` when the tree is empty.
    pub fn nearest(
        &self,
        bound: impl Fn(&Aabb) -> f64,
        exact: impl Fn(usize) -> f64,
    ) -> Option<(usize, f64)> {
        self.nearest_below(bound, exact, f64::INFINITY)
    }

    /// [`PackedTree::nearest`] among the items whose `exact` is below `limit`: nothing whose
    /// bound reaches the limit is looked into, so that a search for what lies near costs the
    /// few boxes near, not every box that holds something farther. `None` when no item is
    /// below the limit.
    pub fn nearest_below(
        &self,
        bound: impl Fn(&Aabb) -> f64,
        exact: impl Fn(usize) -> f64,
        limit: f64,
    ) -> Option<(usize, f64)> {
        let (pos, height) = self.root()?;
        // The queue's room is kept from one search to the next on the thread: searches come by
        // the hundred thousand (the clean-up's coverage tests), and a queue allocated and grown
        // anew each time cost a third of their time. A search made from within `bound` or
        // `exact` finds the room taken and makes its own.
        let mut queue = BinaryHeap::from(QUEUE.with(|q| std::mem::take(&mut *q.borrow_mut())));
        let found = self.search_nearest(&mut queue, pos, height, bound, exact, limit);
        let mut room = queue.into_vec();
        room.clear();
        QUEUE.with(|q| *q.borrow_mut() = room);
        found
    }

    /// [`PackedTree::nearest_below`] from the node at `pos` of `height`, with `queue` (empty)
    /// to keep the nodes and items waiting in.
    fn search_nearest(
        &self,
        queue: &mut BinaryHeap<Queued>,
        pos: usize,
        height: usize,
        bound: impl Fn(&Aabb) -> f64,
        exact: impl Fn(usize) -> f64,
        limit: f64,
    ) -> Option<(usize, f64)> {
        let key = bound(&self.boxes[pos]);
        if key < limit {
            queue.push(Queued { key, pos, height });
        }
        while let Some(q) = queue.pop() {
            match q.height {
                EXACT => return Some((self.ids[q.pos], q.key)),
                0 => {
                    let key = exact(self.ids[q.pos]);
                    if key < limit {
                        queue.push(Queued {
                            key,
                            height: EXACT,
                            ..q
                        });
                    }
                }
                height => {
                    for c in self.children(q.pos, height) {
                        let key = bound(&self.boxes[c]);
                        if key < limit {
                            queue.push(Queued {
                                key,
                                pos: c,
                                height: height - 1,
                            });
                        }
                    }
                }
            }
        }
        None
    }
}

thread_local! {
    /// The room of the last nearest search's queue on this thread (see
    /// [`PackedTree::nearest_below`]).
    static QUEUE: std::cell::RefCell<Vec<Queued>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The height of a queued item whose key is its exact value rather than a bound.
const EXACT: usize = usize::MAX;

/// A node, an item's box or an item, queued by its key, least first.
struct Queued {
    key: f64,
    pos: usize,
    height: usize,
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Queued {}

impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: the heap pops the least key; at equal keys an exact value comes first.
        o.key
            .total_cmp(&self.key)
            .then_with(|| (self.height == EXACT).cmp(&(o.height == EXACT)))
    }
}

/// The items of a [`PackedTree::search`].
pub struct Search<'a, K> {
    tree: &'a PackedTree,
    keep: K,
    /// Nodes above the leaves still to open, with their heights: at most fifteen per
    /// height below the root, so a tree of a billion items needs fewer than the 128 inline.
    stack: SmallVec<[(usize, usize); 128]>,
    /// Item positions of the lowest-height node being scanned.
    items: std::ops::Range<usize>,
}

impl<K: Fn(&Aabb) -> bool> Iterator for Search<'_, K> {
    type Item = usize;

    fn next(&mut self) -> Option<usize> {
        loop {
            // Items are tested in place, without going through the stack.
            for pos in self.items.by_ref() {
                if (self.keep)(&self.tree.boxes[pos]) {
                    return Some(self.tree.ids[pos]);
                }
            }
            let (pos, height) = self.stack.pop()?;
            match height {
                0 => return Some(self.tree.ids[pos]),
                1 => self.items = self.tree.children(pos, 1),
                _ => {
                    for c in self.tree.children(pos, height) {
                        if (self.keep)(&self.tree.boxes[c]) {
                            self.stack.push((c, height - 1));
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxes(n: usize, seed: u64) -> Vec<Aabb> {
        let mut random = crate::test_random::Lcg::new(seed);
        let mut next = || random.unit();
        (0..n)
            .map(|_| {
                let (x, y) = (100.0 * next(), 50.0 * next());
                let (w, h) = (3.0 * next(), 3.0 * next());
                Aabb::from_points(Point::new(x, y), Point::new(x + w, y + h))
            })
            .collect()
    }

    #[test]
    fn search_finds_exactly_the_overlapping_boxes() {
        for n in [0, 1, 2, 15, 16, 17, 255, 256, 257, 3000] {
            let all = boxes(n, n as u64 + 7);
            let tree = PackedTree::new(&all);
            assert_eq!(tree.len(), n);
            for q in boxes(20, 99) {
                let mut got: Vec<usize> = tree.search(|b| b.intersects(&q)).collect();
                got.sort_unstable();
                let want: Vec<usize> = (0..n).filter(|&i| all[i].intersects(&q)).collect();
                assert_eq!(got, want, "n = {n}");
            }
        }
    }

    #[test]
    fn nearest_is_the_brute_force_minimum() {
        for n in [1, 16, 17, 500] {
            let all = boxes(n, 3 * n as u64);
            let tree = PackedTree::new(&all);
            for q in boxes(30, 5) {
                let p = q.min;
                let (_, got) = tree
                    .nearest(|b| b.distance_sq(p), |i| all[i].distance_sq(p))
                    .unwrap();
                let want = all.iter().map(|b| b.distance_sq(p)).fold(f64::INFINITY, f64::min);
                assert_eq!(got, want);
            }
        }
        assert!(PackedTree::new(&[]).nearest(|_| 0.0, |_| 0.0).is_none());
    }

    #[test]
    fn empty_boxes_are_left_out() {
        let b = Aabb::from_points(Point::new(0.0, 0.0), Point::new(1.0, 1.0));
        let tree = PackedTree::new(&[Aabb::EMPTY, b, Aabb::EMPTY]);
        assert_eq!(tree.len(), 1);
        assert_eq!(tree.search(|_| true).collect::<Vec<_>>(), vec![1]);
    }

    #[test]
    fn radix_order_is_the_stable_order_by_key() {
        let mut random = crate::test_random::Lcg::new(12345);
        for n in [0, 1, 5, 255, 256, 1000, 5000] {
            let keys: Vec<u32> = (0..n)
                // Few distinct bits, so that ties and skipped passes both happen.
                .map(|_| ((random.next_u64() >> 33) as u32) & 0xFF00_0003)
                .collect();
            let items: Vec<usize> = (0..n).rev().filter(|i| i % 7 != 3).collect();
            let mut expected = items.clone();
            expected.sort_by_key(|&i| keys[i]);
            assert_eq!(sorted_by_key(items, |i| keys[i]), expected, "{n}");
        }
    }

    #[test]
    fn hilbert_visits_neighbouring_cells_in_turn() {
        // On the 2x2 top height the curve runs (0,0), (0,1), (1,1), (1,0).
        let h = 1 << 15;
        let order = [hilbert(0, 0), hilbert(0, h), hilbert(h, h), hilbert(h, 0)];
        assert!(order.windows(2).all(|w| w[0] < w[1]));
    }
}
