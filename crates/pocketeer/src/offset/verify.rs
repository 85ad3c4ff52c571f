//! Checking an offset against its definition, independently of how it was computed: the loops
//! are closed, every point of them lies at the distance from the walls, and inside the pocket.
//! The case tests, the property tests, the fuzz regressions and the fuzz target all judge
//! offsets with [`verify_offset`].

use crate::geom::{intersect, overlapping_pairs, Aabb, Contour, Intersection, Pocket, Point, PreparedPocket};
use thiserror::Error;

/// How near to `d` every point of an offset at distance `d` lies, relative to max(d, 1 mm).
pub const OFFSET_ACCURACY: f64 = 1e-6;

/// Points judged on each segment of a loop: its ends and this many intervals between.
const INTERVALS: usize = 8;

/// How an offset fails its definition.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OffsetFault {
    /// A segment does not end where the next one starts.
    #[error("loop {ring} is open after segment {segment}: it ends at {end}, the next starts at {start}")]
    Open {
        /// Which loop.
        ring: usize,
        /// Which segment.
        segment: usize,
        /// Where it ends.
        end: Point,
        /// Where the next starts.
        start: Point,
    },
    /// A point of a loop is not at the distance from the walls.
    #[error("{at} on loop {ring} is {distance} mm from the walls, not {expected} mm")]
    Distance {
        /// Which loop.
        ring: usize,
        /// The point.
        at: Point,
        /// Its distance from the walls, mm.
        distance: f64,
        /// The offset distance, mm.
        expected: f64,
    },
    /// A point of a loop lies outside the pocket (beyond the boundary or in an island).
    #[error("{at} on loop {ring} lies outside the pocket")]
    Outside {
        /// Which loop.
        ring: usize,
        /// The point.
        at: Point,
    },
    /// Two loops cross or touch.
    #[error("loops {a} and {b} meet at {at}")]
    LoopsMeet {
        /// One loop.
        a: usize,
        /// The other.
        b: usize,
        /// Where.
        at: Point,
    },
}

/// Checks that `loops` can be the offset of `pocket` by `d` > 0: each loop closed to within
/// [`OFFSET_ACCURACY`] mm, and its segments' ends and eight points between them at distance `d`
/// from the walls (within `OFFSET_ACCURACY` · max(d, 1 mm)) and inside the pocket. It does not
/// check that nothing is missing (the area tests do).
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Pocket, Segment, Tolerance};
/// use pocketeer::offset::{offset_pocket, verify_offset, OffsetFault};
/// let c = Point::new(0.0, 0.0);
/// let pocket = Pocket { boundary: Contour::new(vec![Segment::Arc(Arc::circle(c, 10.0))]), islands: vec![] };
/// let loops = offset_pocket(&pocket, 3.0, &Tolerance::default()).unwrap();
/// assert_eq!(verify_offset(&pocket, &loops, 3.0), Ok(()));
/// let wrong = vec![Contour::new(vec![Segment::Arc(Arc::circle(c, 6.0))])];
/// assert!(matches!(verify_offset(&pocket, &wrong, 3.0), Err(OffsetFault::Distance { .. })));
/// ```
pub fn verify_offset(pocket: &Pocket, loops: &[Contour], d: f64) -> Result<(), OffsetFault> {
    let prepared = PreparedPocket::new(pocket);
    let within = OFFSET_ACCURACY * d.max(1.0);
    for (ring, l) in loops.iter().enumerate() {
        let n = l.segments.len();
        for (segment, s) in l.segments.iter().enumerate() {
            let (end, start) = (s.end(), l.segments[(segment + 1) % n].start());
            if end.distance(start) >= OFFSET_ACCURACY {
                return Err(OffsetFault::Open {
                    ring,
                    segment,
                    end,
                    start,
                });
            }
            for k in 0..=INTERVALS {
                let at = s.point_at(k as f64 / INTERVALS as f64);
                let distance = prepared.distance(at);
                if (distance - d).abs() > within {
                    return Err(OffsetFault::Distance {
                        ring,
                        at,
                        distance,
                        expected: d,
                    });
                }
                // A point at d > 0 from the walls is on no contour: the winding test is exact.
                if !prepared.contains(at) {
                    return Err(OffsetFault::Outside { ring, at });
                }
            }
        }
    }
    Ok(())
}

/// The first two of `loops` that cross or touch, and where, when any do: the loops of an
/// offset are disjoint except where walls drawn exactly 2d apart make them touch.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Segment};
/// use pocketeer::offset::loops_meet;
/// let disc = |x: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::new(x, 0.0), 1.0))]);
/// assert!(loops_meet(&[disc(0.0), disc(3.0)]).is_none());
/// assert!(loops_meet(&[disc(0.0), disc(1.5)]).is_some());
/// ```
pub fn loops_meet(loops: &[Contour]) -> Option<OffsetFault> {
    let mut owner = Vec::new();
    let mut boxes: Vec<Aabb> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        for s in &l.segments {
            owner.push((k, *s));
            boxes.push(s.bbox());
        }
    }
    overlapping_pairs(&boxes).into_iter().find_map(|(i, j)| {
        let ((a, sa), (b, sb)) = (owner[i], owner[j]);
        if a == b {
            return None;
        }
        let hit = intersect(&sa, &sb, 1e-9);
        let at = hit.iter().next().map(|h| match h {
            Intersection::Point { point, .. } => point,
            Intersection::Overlap { a: (t, _), .. } => sa.point_at(t),
        })?;
        Some(OffsetFault::LoopsMeet {
            a: a.min(b),
            b: a.max(b),
            at,
        })
    })
}
