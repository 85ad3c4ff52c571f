//! A pocket prepared for the questions every stage asks of it: how far a point is from the
//! walls, whether a point is inside, whether a tool moving along a segment comes too near.

use super::{Aabb, BoxIndex, Contour, Pocket, Point, Segment, SegmentIndex, Tolerance, WindingIndex};
use std::sync::OnceLock;

/// A region indexed once for distance and containment queries: the walls (boundary and islands)
/// in a [`SegmentIndex`], each contour in a [`WindingIndex`]. The clearing planner, the linker,
/// the check and the job all ask the same prepared pocket; the offset stage erodes it (see
/// [`PreparedPocket::offset`]).
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Pocket, PreparedPocket, Segment};
/// let p = Point::new;
/// let boundary = Contour::polygon(&[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 30.0), p(0.0, 30.0)]);
/// let island = Contour::new(vec![Segment::Arc(Arc::new(p(20.0, 15.0), 5.0, 0.0, -std::f64::consts::TAU))]);
/// let pocket = PreparedPocket::new(&Pocket { boundary, islands: vec![island] });
/// assert!(pocket.contains(p(5.0, 5.0)));
/// assert!(!pocket.contains(p(20.0, 15.0)));
/// assert!((pocket.distance(p(20.0, 25.0)) - 5.0).abs() < 1e-12);
/// ```
pub struct PreparedPocket {
    /// Contours with the region on their left: boundary counter-clockwise, islands clockwise.
    contours: Vec<Contour>,
    /// Built on first use (see [`PreparedPocket::offset_with_sources`], which builds them
    /// beside its first steps on a large region).
    indexes: OnceLock<Indexes>,
}

/// The indexes of a [`PreparedPocket`].
struct Indexes {
    /// Every segment of the contours, in order, indexed for distances.
    walls: SegmentIndex,
    /// One per contour.
    winding: Vec<WindingIndex>,
    /// The contours' extents (see [`WindingIndex::extent`]): a point's winding numbers are
    /// summed over the few contours its ray meets, not over every island of a plate.
    extents: BoxIndex,
    /// Contours whose extent is not a finite box, asked every time.
    unindexed: Vec<usize>,
}

impl Indexes {
    /// The indexes of `loops`; the two main ones at once on a large region when `share`.
    fn new(loops: &[Contour], share: bool) -> Indexes {
        // Sized at once: collected from the contours' iterators it would grow by doubling, to
        // twice a large pocket's segments.
        let mut segments: Vec<Segment> = Vec::with_capacity(loops.iter().map(|c| c.segments.len()).sum());
        for c in loops {
            segments.extend_from_slice(&c.segments);
        }
        let windings = || {
            loops
                .iter()
                .map(|c| WindingIndex::new(&c.segments))
                .collect::<Vec<_>>()
        };
        // The two indexes are independent: built at once on a large pocket.
        let (walls, winding) = if share {
            crate::parallel::join(segments.len(), || SegmentIndex::from_vec(segments), windings)
        } else {
            (SegmentIndex::from_vec(segments), windings())
        };
        let finite = |b: &Aabb| b.min.is_finite() && b.max.is_finite();
        let extents: Vec<Aabb> = winding
            .iter()
            .map(|w| Some(w.extent()).filter(finite).unwrap_or(Aabb::EMPTY))
            .collect();
        let unindexed = (0..winding.len())
            .filter(|&k| !finite(&winding[k].extent()))
            .collect();
        Indexes {
            walls,
            winding,
            extents: BoxIndex::new(&extents),
            unindexed,
        }
    }
}

/// Segments from which [`PreparedPocket::offset_with_sources`] builds the indexes on another
/// core while it offsets (a thread costs tens of microseconds to start).
const BACKGROUND_SEGMENTS: usize = 20_000;

impl PreparedPocket {
    /// Prepares `pocket` (boundary counter-clockwise, islands clockwise).
    pub fn new(pocket: &Pocket) -> PreparedPocket {
        PreparedPocket::from_pocket(pocket.clone())
    }

    /// Prepares `pocket`, keeping its contours without a copy (see [`PreparedPocket::new`]).
    pub fn from_pocket(pocket: Pocket) -> PreparedPocket {
        let mut loops = Vec::with_capacity(1 + pocket.islands.len());
        loops.push(pocket.boundary);
        loops.extend(pocket.islands);
        PreparedPocket::from_loops(loops)
    }

    /// Prepares the region on the left of `loops` (counter-clockwise around material,
    /// clockwise around holes), such as the loops of an offset.
    pub fn from_loops(loops: Vec<Contour>) -> PreparedPocket {
        PreparedPocket {
            contours: loops,
            indexes: OnceLock::new(),
        }
    }

    /// The indexes, built now if they are not yet.
    fn indexes(&self) -> &Indexes {
        self.indexes.get_or_init(|| Indexes::new(&self.contours, true))
    }

    /// Runs `work`, building the indexes meanwhile on another core if they are not built yet
    /// and the region is large: `work`'s first steps need only the contours.
    pub(crate) fn with_indexes_built_beside<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        let segments: usize = self.contours.iter().map(|c| c.segments.len()).sum();
        if self.indexes.get().is_some() || segments < BACKGROUND_SEGMENTS || crate::parallel::cores() < 2 {
            return work();
        }
        std::thread::scope(|scope| {
            // Built on one core: the other does `work`. Whoever asks first waits for it.
            scope.spawn(|| self.indexes.get_or_init(|| Indexes::new(&self.contours, false)));
            work()
        })
    }

    /// The contours, the region on their left.
    pub fn contours(&self) -> &[Contour] {
        &self.contours
    }

    /// The box around every contour (for a pocket, its boundary's box).
    pub fn bbox(&self) -> Aabb {
        self.contours.iter().fold(Aabb::EMPTY, |b, c| b.union(&c.bbox()))
    }

    /// The walls' segments, indexed; segment k of contour c is numbered after all segments
    /// of the contours before c.
    pub fn walls(&self) -> &SegmentIndex {
        &self.indexes().walls
    }

    /// True when `p` (not on a contour) lies in the region: the winding numbers of the
    /// counter-clockwise boundary and clockwise islands add up to 1 there.
    pub fn contains(&self, p: Point) -> bool {
        // A closed contour winds 0 times round a point outside its extent (its gaps closed
        // included): only the few extents holding p count, not every one a ray from p meets
        // (on a plate, the holes to the right in p's row).
        let ix = self.indexes();
        let winding = |k: usize| ix.winding[k].winding(&self.contours[k].segments, p);
        let indexed: i32 = ix.extents.at_point(p).map(winding).sum();
        indexed + ix.unindexed.iter().map(|&k| winding(k)).sum::<i32>() > 0
    }

    /// Distance from `p` to the nearest wall or island.
    pub fn distance(&self, p: Point) -> f64 {
        self.walls().distance(p)
    }

    /// [`PreparedPocket::distance`] for points asked about one after another along a path,
    /// starting from the wall `hint` holds and leaving the nearest there (see
    /// [`SegmentIndex::distance_hinted`]).
    pub fn distance_hinted(&self, p: Point, hint: &std::cell::Cell<usize>) -> f64 {
        (self.walls().distance_hinted(p, f64::INFINITY, hint)).unwrap_or(f64::INFINITY)
    }

    /// The walls' and islands' segments whose boxes meet `b`: a search confined to `b` tests
    /// its moves against these alone.
    pub fn walls_meeting(&self, b: &Aabb) -> impl Iterator<Item = &Segment> + '_ {
        self.walls().segments_meeting(b)
    }

    /// True when the segment `s` comes nearer than `r` to a wall or an island: a tool centre
    /// moving along `s` stays at least `r` from them exactly when this is false.
    pub fn segment_nearer_than(&self, s: &Segment, r: f64, tol: &Tolerance) -> bool {
        self.walls().segment_within(s, r, tol.eps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_large_region_offsets_the_same_with_its_indexes_built_beside_the_offset() {
        // 30 000 segments, over BACKGROUND_SEGMENTS: the indexes are built on another core
        // while the raw offset is made and split; built first, they give the same loops.
        let n = 30_000;
        let points: Vec<Point> = (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64;
                let r = 100.0 + 8.0 * (12.0 * t).sin();
                Point::new(r * t.cos(), r * t.sin())
            })
            .collect();
        let island = Contour::polygon(&[
            Point::new(-10.0, -10.0),
            Point::new(-10.0, 10.0),
            Point::new(10.0, 10.0),
            Point::new(10.0, -10.0),
        ]);
        let pocket = Pocket {
            boundary: Contour::polygon(&points),
            islands: vec![island],
        };
        assert!(n >= BACKGROUND_SEGMENTS);
        let tol = Tolerance::default();
        let beside = PreparedPocket::new(&pocket);
        assert!(beside.indexes.get().is_none(), "not built before the offset asks");
        let first = PreparedPocket::new(&pocket);
        first.walls();
        let loops = beside.offset(3.0, &tol).unwrap();
        assert_eq!(loops.len(), 2);
        assert_eq!(loops, first.offset(3.0, &tol).unwrap());
        assert!(beside.indexes.get().is_some());
        // Asked again, the region answers from the same indexes.
        assert!(beside.contains(Point::new(50.0, 0.0)) && !beside.contains(Point::new(0.0, 0.0)));
    }
}
