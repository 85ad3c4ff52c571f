//! Spatial indexes over bounding boxes and segments (on a [`PackedTree`]), for finding the
//! pairs of elements that may touch, and distances, without testing every pair.

use super::{
    distance_from_segment, segment_distance, segments_nearer_than, Aabb, PackedTree, Point, Segment,
};
use std::cell::Cell;

/// Boxes indexed by their position in the slice they were built from.
///
/// ```
/// use pocketeer::geom::{Aabb, BoxIndex, Point};
/// let boxes = [
///     Aabb::from_points(Point::new(0.0, 0.0), Point::new(2.0, 2.0)),
///     Aabb::from_points(Point::new(1.0, 1.0), Point::new(3.0, 3.0)),
///     Aabb::from_points(Point::new(5.0, 5.0), Point::new(6.0, 6.0)),
/// ];
/// let index = BoxIndex::new(&boxes);
/// assert_eq!(index.pairs(), vec![(0, 1)]);
/// assert_eq!(index.at_point(Point::new(5.5, 5.5)).collect::<Vec<_>>(), vec![2]);
/// ```
pub struct BoxIndex {
    tree: PackedTree,
}

impl BoxIndex {
    /// Indexes `boxes` (empty boxes are left out).
    pub fn new(boxes: &[Aabb]) -> BoxIndex {
        BoxIndex {
            tree: PackedTree::new(boxes),
        }
    }

    /// Indices of the boxes that intersect `b`.
    pub fn intersecting(&self, b: &Aabb) -> impl Iterator<Item = usize> + '_ {
        let b = *b;
        self.tree.search(move |x| x.intersects(&b))
    }

    /// The item whose `exact` distance is least and below `limit`, searched best first by
    /// `bound`, a lower bound of `exact` for the items in a box (see
    /// [`PackedTree::nearest_below`]): the item's index and its distance.
    pub fn nearest_below(
        &self,
        bound: impl Fn(&Aabb) -> f64,
        exact: impl Fn(usize) -> f64,
        limit: f64,
    ) -> Option<(usize, f64)> {
        self.tree.nearest_below(bound, exact, limit)
    }

    /// Indices of the boxes that contain `p`.
    pub fn at_point(&self, p: Point) -> impl Iterator<Item = usize> + '_ {
        self.tree.search(move |x| x.contains(p))
    }

    /// Every pair `(i, j)`, `i < j`, of intersecting boxes, sorted.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let mut out: Vec<(usize, usize)> = self
            .tree
            .items()
            .flat_map(|(i, b)| self.intersecting(b).filter(move |&j| i < j).map(move |j| (i, j)))
            .collect();
        out.sort_unstable();
        out
    }
}

/// The pairs `(i, j)`, `i < j`, of `boxes` that overlap (touching counts), sorted: see
/// [`for_each_overlapping_pair`].
///
/// ```
/// use pocketeer::geom::{overlapping_pairs, Aabb, Point};
/// let b = |x0, y0, x1, y1| Aabb::from_points(Point::new(x0, y0), Point::new(x1, y1));
/// let boxes = [b(0.0, 0.0, 2.0, 2.0), b(1.0, 1.0, 3.0, 3.0), b(5.0, 0.0, 6.0, 1.0), b(2.0, 5.0, 3.0, 6.0)];
/// assert_eq!(overlapping_pairs(&boxes), vec![(0, 1)]);
/// ```
pub fn overlapping_pairs(boxes: &[Aabb]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    // Without a budget the sweep runs to the end.
    let _ = for_each_overlapping_pair(boxes, u64::MAX, |i, j| {
        out.push((i, j));
        true
    });
    out.sort_unstable();
    out
}

/// The pairs `(i, j)`, `i < j`, of `boxes` that overlap (touching counts), sorted, by the
/// cheaper way: the sweep of [`for_each_overlapping_pair`] while few boxes are open at once
/// (a contour's pieces, in order along it), else a [`BoxIndex`] (a spiral, where a sweep line
/// crosses every turn). The same pairs as [`BoxIndex::pairs`] either way.
///
/// ```
/// use pocketeer::geom::{box_pairs, Aabb, BoxIndex, Point};
/// let b = |x0, y0, x1, y1| Aabb::from_points(Point::new(x0, y0), Point::new(x1, y1));
/// let boxes = [b(0.0, 0.0, 2.0, 2.0), b(1.0, 1.0, 3.0, 3.0), b(5.0, 0.0, 6.0, 1.0), b(2.0, 3.0, 3.0, 6.0)];
/// assert_eq!(box_pairs(&boxes), vec![(0, 1), (1, 3)]);
/// assert_eq!(box_pairs(&boxes), BoxIndex::new(&boxes).pairs());
/// ```
pub fn box_pairs(boxes: &[Aabb]) -> Vec<(usize, usize)> {
    let mut out = box_pairs_unsorted(boxes);
    out.sort_unstable();
    out
}

/// The pairs of [`box_pairs`] in no set order: for a caller that orders what it finds among
/// the pairs (a contour's few crossings) rather than the many pairs themselves.
///
/// ```
/// use pocketeer::geom::{box_pairs, box_pairs_unsorted, Aabb, Point};
/// let b = |x0, y0, x1, y1| Aabb::from_points(Point::new(x0, y0), Point::new(x1, y1));
/// let boxes = [b(0.0, 0.0, 2.0, 2.0), b(1.0, 1.0, 3.0, 3.0), b(5.0, 0.0, 6.0, 1.0), b(2.0, 3.0, 3.0, 6.0)];
/// let mut pairs = box_pairs_unsorted(&boxes);
/// pairs.sort();
/// assert_eq!(pairs, box_pairs(&boxes));
/// ```
pub fn box_pairs_unsorted(boxes: &[Aabb]) -> Vec<(usize, usize)> {
    // About what building and walking the tree costs, in box comparisons.
    let budget = 16 * boxes.len() as u64 + 1024;
    let mut out = Vec::new();
    let swept = for_each_overlapping_pair(boxes, budget, |i, j| {
        out.push((i, j));
        true
    });
    if swept.is_err() {
        return BoxIndex::new(boxes).pairs();
    }
    out
}

/// Calls `f(i, j)` once for every pair of `boxes` that overlap (touching counts), in the
/// order of a sweep along the axis where the boxes are thinnest relative to the whole extent.
/// For the rings of small pieces an offset makes, few boxes are open at once, and this is
/// several times cheaper than building an R-tree to walk it against itself.
///
/// The sweep compares each box with those still open; when that would take more than
/// `budget` comparisons, or when `f` returns `false`, it stops and returns where ([`Stopped`]:
/// the comparisons made and the box it stopped at). The comparisons bound both the
/// sweep's time and the number of pairs.
///
/// ```
/// use pocketeer::geom::{for_each_overlapping_pair, Aabb, Point};
/// let b = |x0, y0, x1, y1| Aabb::from_points(Point::new(x0, y0), Point::new(x1, y1));
/// // Twenty boxes all overlapping: 190 pairs.
/// let boxes: Vec<Aabb> = (0..20).map(|k| b(k as f64, 0.0, 100.0, 1.0)).collect();
/// let mut pairs = 0;
/// let count = |_, _| {
///     pairs += 1;
///     true
/// };
/// assert!(for_each_overlapping_pair(&boxes, 1000, count).is_ok());
/// assert_eq!(pairs, 190);
/// assert!(for_each_overlapping_pair(&boxes, 100, |_, _| true).is_err());
/// assert!(for_each_overlapping_pair(&boxes, 1000, |_, _| false).is_err());
/// ```
pub fn for_each_overlapping_pair(
    boxes: &[Aabb],
    budget: u64,
    mut f: impl FnMut(usize, usize) -> bool,
) -> Result<(), Stopped> {
    let total = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
    let (sum_w, sum_h) = boxes
        .iter()
        .fold((0.0, 0.0), |(w, h), b| (w + b.width(), h + b.height()));
    // Sweep across x when boxes are narrow in x compared with the extent, else across y.
    let along_x = sum_w * total.height() <= sum_h * total.width();
    // (start, end) along the sweep, then (start, end) across it.
    let axes = |b: &Aabb| -> [f64; 4] {
        if along_x {
            [b.min.x, b.max.x, b.min.y, b.max.y]
        } else {
            [b.min.y, b.max.y, b.min.x, b.max.x]
        }
    };
    // The boxes in sweep order, each with its index: the sweep then reads memory in order.
    let mut sorted: Vec<([f64; 4], usize)> = boxes.iter().map(axes).zip(0..).collect();
    sorted.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
    // Positions in `sorted` of the boxes the sweep line is in.
    let mut open: Vec<usize> = Vec::new();
    let mut tests: u64 = 0;
    for (k, &(b, i)) in sorted.iter().enumerate() {
        tests += open.len() as u64;
        if tests > budget {
            return Err(Stopped { tests, at: i });
        }
        open.retain(|&o| sorted[o].0[1] >= b[0]);
        for &o in &open {
            let (o, j) = sorted[o];
            if o[2] <= b[3] && b[2] <= o[3] && !f(i.min(j), i.max(j)) {
                return Err(Stopped { tests, at: i });
            }
        }
        open.push(k);
    }
    Ok(())
}

/// Where [`for_each_overlapping_pair`] stopped, over its budget or told to by its callback.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stopped {
    /// The box comparisons made by then.
    pub tests: u64,
    /// The box being swept.
    pub at: usize,
}

/// Segments indexed for distance queries: a best-first search through a [`PackedTree`]
/// visits only the few segments near the query point, however many there are. Arcs keep their
/// end points, so measuring a distance takes no trigonometry.
///
/// ```
/// use pocketeer::geom::{Line, Point, Segment, SegmentIndex};
/// let segs: Vec<Segment> = (0..100)
///     .map(|k| Segment::Line(Line::new(Point::new(k as f64, 0.0), Point::new(k as f64 + 1.0, 0.0))))
///     .collect();
/// let index = SegmentIndex::new(&segs);
/// assert!((index.distance(Point::new(50.5, 3.0)) - 3.0).abs() < 1e-12);
/// ```
pub struct SegmentIndex {
    tree: PackedTree,
    segments: Vec<Segment>,
}

impl SegmentIndex {
    /// Indexes `segments`.
    pub fn new(segments: &[Segment]) -> SegmentIndex {
        SegmentIndex::from_vec(segments.to_vec())
    }

    /// Indexes `segments`, keeping them without a copy.
    pub fn from_vec(segments: Vec<Segment>) -> SegmentIndex {
        let boxes: Vec<Aabb> = segments.iter().map(Segment::bbox).collect();
        SegmentIndex {
            tree: PackedTree::new(&boxes),
            segments,
        }
    }

    /// True when some segment comes nearer to `p` than `r`: stops at the first one found, so it
    /// is cheaper than [`SegmentIndex::distance`] when the answer is yes.
    pub fn any_within(&self, p: Point, r: f64) -> bool {
        self.any_within_hinted(p, r, &mut 0, &mut None)
    }

    /// [`SegmentIndex::any_within`] that measures first the segment `last` found and keeps
    /// the one it finds there (queries made in order along a curve are mostly answered by the
    /// segment that answered the one before), adding to `work` one for the search and one for
    /// every segment it measured (those whose boxes come within `r`): near the middle of a
    /// round profile, with `r` close to its radius, that is most of them.
    pub fn any_within_hinted(&self, p: Point, r: f64, work: &mut u64, last: &mut Option<usize>) -> bool {
        *work += 1;
        if r.is_nan() || r <= 0.0 {
            return false;
        }
        if let Some(m) = last.and_then(|i| self.segments.get(i)) {
            *work += 1;
            if distance_from_segment(m, p) < r {
                return true;
            }
        }
        let r2 = r * r;
        let found = self.tree.search(|b| b.distance_sq(p) <= r2).find(|&i| {
            *work += 1;
            distance_from_segment(&self.segments[i], p) < r
        });
        if found.is_some() {
            *last = found;
        }
        found.is_some()
    }

    /// The segments whose boxes meet `b`.
    pub fn segments_meeting(&self, b: &Aabb) -> impl Iterator<Item = &Segment> + '_ {
        let b = *b;
        self.tree
            .search(move |x| x.intersects(&b))
            .map(|i| &self.segments[i])
    }

    /// True when some segment comes nearer to the segment `s` than `r` (`eps`: the geometric
    /// epsilon used to detect touching).
    ///
    /// ```
    /// use pocketeer::geom::{Line, Point, Segment, SegmentIndex};
    /// let p = Point::new;
    /// let index = SegmentIndex::new(&[Segment::Line(Line::new(p(0.0, 0.0), p(10.0, 0.0)))]);
    /// let probe = Segment::Line(Line::new(p(5.0, 2.0), p(5.0, 8.0)));
    /// assert!(index.segment_within(&probe, 2.5, 1e-12));
    /// assert!(!index.segment_within(&probe, 1.5, 1e-12));
    /// ```
    pub fn segment_within(&self, s: &Segment, r: f64, eps: f64) -> bool {
        if r.is_nan() || r <= 0.0 {
            return false;
        }
        let query = s.bbox().inflated(r);
        self.tree
            .search(|b| b.intersects(&query))
            .any(|i| segments_nearer_than(&self.segments[i], s, r, eps))
    }

    /// The nearest segment to the segment `s` if one is nearer than `limit`: the distance and
    /// the nearest point on `s`.
    ///
    /// Searched best first, boxes by their distance from the segment's box: a move along a
    /// wall of thousands of short segments looks at the few nearest, not at every one within
    /// `limit` of it.
    pub fn nearest_to_segment(&self, s: &Segment, limit: f64, eps: f64) -> Option<(f64, Point)> {
        let sb = s.bbox();
        let (i, d) = self.tree.nearest_below(
            |b| b.distance_to_box(&sb),
            |i| segment_distance(s, &self.segments[i], eps).0,
            limit,
        )?;
        Some((d, segment_distance(s, &self.segments[i], eps).1))
    }

    /// The point of the segments nearest to `p` and its distance (`None` when there are no
    /// segments).
    ///
    /// ```
    /// use pocketeer::geom::{Line, Point, Segment, SegmentIndex};
    /// let p = Point::new;
    /// let index = SegmentIndex::new(&[Segment::Line(Line::new(p(0.0, 0.0), p(10.0, 0.0)))]);
    /// assert_eq!(index.nearest(p(4.0, 3.0)), Some((p(4.0, 0.0), 3.0)));
    /// ```
    pub fn nearest(&self, p: Point) -> Option<(Point, f64)> {
        self.tree
            .nearest(
                |b| b.distance_sq(p).sqrt(),
                |i| distance_from_segment(&self.segments[i], p),
            )
            .map(|(i, d)| (super::closest_point(&self.segments[i], p), d))
    }

    /// Distance from `p` to the nearest segment when it is below `limit`, the search starting
    /// from the segment `hint` holds (the nearest to the point last asked about, a guess for a
    /// point near it) and leaving there the one nearest to `p`: it looks only into boxes
    /// nearer than the limit and that segment, a few where points are asked about one after
    /// another along a path.
    ///
    /// ```
    /// use pocketeer::geom::{Line, Point, Segment, SegmentIndex};
    /// use std::cell::Cell;
    /// let p = Point::new;
    /// let line = |x0, y0, x1, y1| Segment::Line(Line::new(p(x0, y0), p(x1, y1)));
    /// let index = SegmentIndex::new(&[line(0.0, 0.0, 10.0, 0.0), line(0.0, 5.0, 10.0, 5.0)]);
    /// let hint = Cell::new(0);
    /// assert_eq!(index.distance_hinted(p(4.0, 4.0), 5.0, &hint), Some(1.0));
    /// assert_eq!(hint.get(), 1);
    /// assert_eq!(index.distance_hinted(p(4.0, 1.0), 5.0, &hint), Some(1.0));
    /// assert_eq!(hint.get(), 0);
    /// assert_eq!(index.distance_hinted(p(4.0, 1.0), 1.0, &hint), None);
    /// ```
    pub fn distance_hinted(&self, p: Point, limit: f64, hint: &Cell<usize>) -> Option<f64> {
        let guess = (self.segments.get(hint.get())).map_or(f64::INFINITY, |s| distance_from_segment(s, p));
        let found = self.tree.nearest_below(
            |b| b.distance_sq(p).sqrt(),
            |i| distance_from_segment(&self.segments[i], p),
            limit.min(guess),
        );
        match found {
            Some((i, d)) => {
                hint.set(i);
                Some(d)
            }
            None => (guess < limit).then_some(guess),
        }
    }

    /// Distance from `p` to the nearest segment (infinite when there is none).
    pub fn distance(&self, p: Point) -> f64 {
        self.tree
            .nearest(
                |b| b.distance_sq(p).sqrt(),
                |i| distance_from_segment(&self.segments[i], p),
            )
            .map_or(f64::INFINITY, |(_, d)| d)
    }
}
