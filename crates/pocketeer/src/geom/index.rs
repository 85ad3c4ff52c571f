//! A spatial index over bounding boxes (an R*-tree from the `rstar` crate), for finding the
//! pairs of elements that may touch without testing every pair.

use super::{point_distance, segment_distance, Aabb, Point, Segment};
use rstar::{primitives::GeomWithData, primitives::Rectangle, PointDistance, RTree, RTreeObject, AABB};

type Entry = GeomWithData<Rectangle<[f64; 2]>, usize>;

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
    tree: RTree<Entry>,
}

fn envelope(b: &Aabb) -> AABB<[f64; 2]> {
    AABB::from_corners([b.min.x, b.min.y], [b.max.x, b.max.y])
}

impl BoxIndex {
    /// Indexes `boxes` (empty boxes are left out).
    pub fn new(boxes: &[Aabb]) -> BoxIndex {
        let entries = boxes
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.is_empty())
            .map(|(i, b)| {
                GeomWithData::new(Rectangle::from_corners([b.min.x, b.min.y], [b.max.x, b.max.y]), i)
            })
            .collect();
        BoxIndex {
            tree: RTree::bulk_load(entries),
        }
    }

    /// Indices of the boxes that intersect `b`.
    pub fn intersecting<'a>(&'a self, b: &Aabb) -> impl Iterator<Item = usize> + 'a {
        self.tree
            .locate_in_envelope_intersecting(&envelope(b))
            .map(|e| e.data)
    }

    /// Indices of the boxes that contain `p`.
    pub fn at_point(&self, p: Point) -> impl Iterator<Item = usize> + '_ {
        self.tree.locate_all_at_point(&[p.x, p.y]).map(|e| e.data)
    }

    /// Every pair `(i, j)`, `i < j`, of intersecting boxes, sorted.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        // One simultaneous walk of the tree against itself: cheaper than a query per box.
        let mut out: Vec<(usize, usize)> = self
            .tree
            .intersection_candidates_with_other_tree(&self.tree)
            .filter(|(a, b)| a.data < b.data)
            .map(|(a, b)| (a.data, b.data))
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

/// Calls `f(i, j)` once for every pair of `boxes` that overlap (touching counts), in the
/// order of a sweep along the axis where the boxes are thinnest relative to the whole extent.
/// For the rings of small pieces an offset makes, few boxes are open at once, and this is
/// several times cheaper than building an R-tree to walk it against itself.
///
/// The sweep compares each box with those still open; when that would take more than
/// `budget` comparisons, or when `f` returns `false`, it stops and returns `Err` with the
/// number of comparisons made and the box it stopped at. The comparisons bound both the
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
) -> Result<(), (u64, usize)> {
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
    let spans: Vec<[f64; 4]> = boxes.iter().map(axes).collect();
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_unstable_by(|&a, &b| spans[a][0].total_cmp(&spans[b][0]));
    let mut open: Vec<usize> = Vec::new();
    let mut tests: u64 = 0;
    for &i in &order {
        let b = spans[i];
        tests += open.len() as u64;
        if tests > budget {
            return Err((tests, i));
        }
        open.retain(|&j| spans[j][1] >= b[0]);
        for &j in &open {
            let o = spans[j];
            if o[2] <= b[3] && b[2] <= o[3] && !f(i.min(j), i.max(j)) {
                return Err((tests, i));
            }
        }
        open.push(i);
    }
    Ok(())
}

/// A segment filed in an R-tree by its bounding box (computed once: the tree asks often).
struct Filed(Segment, AABB<[f64; 2]>);

impl RTreeObject for Filed {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.1
    }
}

impl PointDistance for Filed {
    fn distance_2(&self, point: &[f64; 2]) -> f64 {
        point_distance(&self.0, Point::new(point[0], point[1])).powi(2)
    }
}

/// Segments indexed for nearest-distance queries: a best-first search through the R-tree
/// visits only the few segments near the query point, however many there are.
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
    tree: RTree<Filed>,
}

impl SegmentIndex {
    /// Indexes `segments`.
    pub fn new(segments: &[Segment]) -> SegmentIndex {
        SegmentIndex {
            tree: RTree::bulk_load(segments.iter().map(|s| Filed(*s, envelope(&s.bbox()))).collect()),
        }
    }

    /// True when some segment comes nearer to `p` than `r`: stops at the first one found, so it
    /// is cheaper than [`SegmentIndex::distance`] when the answer is yes.
    pub fn any_within(&self, p: Point, r: f64) -> bool {
        self.any_within_counted(p, r, &mut 0)
    }

    /// [`SegmentIndex::any_within`], adding to `work` one for the search and one for every
    /// segment it measured (those whose boxes come within `r`): near the middle of a round
    /// profile, with `r` close to its radius, that is most of them.
    pub fn any_within_counted(&self, p: Point, r: f64, work: &mut u64) -> bool {
        *work += 1;
        r > 0.0
            && self.tree.locate_within_distance([p.x, p.y], r * r).any(|f| {
                *work += 1;
                point_distance(&f.0, p) < r
            })
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
        let b = s.bbox();
        let query = AABB::from_corners([b.min.x - r, b.min.y - r], [b.max.x + r, b.max.y + r]);
        self.tree
            .locate_in_envelope_intersecting(&query)
            .any(|f| segment_distance(&f.0, s, eps).0 < r)
    }

    /// The nearest segment to the segment `s` if one is nearer than `limit`: the distance and
    /// the nearest point on `s`.
    pub fn nearest_to_segment(&self, s: &Segment, limit: f64, eps: f64) -> Option<(f64, Point)> {
        let b = s.bbox();
        let query = AABB::from_corners(
            [b.min.x - limit, b.min.y - limit],
            [b.max.x + limit, b.max.y + limit],
        );
        self.tree
            .locate_in_envelope_intersecting(&query)
            .map(|f| {
                let (d, on_s, _) = segment_distance(s, &f.0, eps);
                (d, on_s)
            })
            .filter(|(d, _)| *d < limit)
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Distance from `p` to the nearest segment (infinite when there is none).
    pub fn distance(&self, p: Point) -> f64 {
        // Not `nearest_neighbor`: its pruning by the boxes' min-max distance can miss the
        // nearest segment (rstar issue #13, seen here on a pocket program); the iterator
        // orders candidates by exact lower bounds.
        self.tree
            .nearest_neighbor_iter(&[p.x, p.y])
            .next()
            .map_or(f64::INFINITY, |f| point_distance(&f.0, p))
    }
}
