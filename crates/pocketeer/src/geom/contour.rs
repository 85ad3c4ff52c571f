//! Closed contours of lines and arcs: area, orientation, point containment.

use super::{Aabb, Line, Point, Segment};
use std::f64::consts::PI;

/// A closed chain of segments, each starting where the previous one ends and the last ending
/// where the first starts.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Segment};
/// use std::f64::consts::PI;
/// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(3.0, 4.0), 2.0))]);
/// assert!((disc.signed_area() - 4.0 * PI).abs() < 1e-12);
/// assert!(disc.contains(Point::new(3.5, 4.5)));
/// assert!((disc.reversed().signed_area() + 4.0 * PI).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Contour {
    /// The segments, in order of travel.
    pub segments: Vec<Segment>,
}

impl Contour {
    /// A contour from segments already joined end to start.
    pub fn new(segments: Vec<Segment>) -> Contour {
        Contour { segments }
    }

    /// The closed polygon through `points`: a line from each to the next, and from the last back
    /// to the first (repeated points are skipped).
    ///
    /// ```
    /// use pocketeer::geom::{Contour, Point};
    /// let square = Contour::polygon(&[Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0), Point::new(0.0, 2.0)]);
    /// assert_eq!(square.signed_area(), 4.0);
    /// ```
    pub fn polygon(points: &[Point]) -> Contour {
        let n = points.len();
        Contour::new(
            (0..n)
                .map(|k| (points[k], points[(k + 1) % n]))
                .filter(|(a, b)| a != b)
                .map(|(a, b)| Segment::Line(Line::new(a, b)))
                .collect(),
        )
    }

    /// Exact signed area: positive for counter-clockwise contours. Arcs count with their
    /// circular segment, not their chord.
    pub fn signed_area(&self) -> f64 {
        signed_area(&self.segments)
    }

    /// True when the contour runs counter-clockwise.
    pub fn is_ccw(&self) -> bool {
        self.signed_area() > 0.0
    }

    /// The contour run the other way.
    pub fn reversed(&self) -> Contour {
        Contour::new(self.segments.iter().rev().map(Segment::reversed).collect())
    }

    /// The contour run counter-clockwise when `ccw`, clockwise otherwise (itself when it
    /// already runs that way).
    ///
    /// ```
    /// use pocketeer::geom::{Contour, Point};
    /// let p = Point::new;
    /// let cw = Contour::polygon(&[p(0.0, 0.0), p(0.0, 1.0), p(1.0, 1.0), p(1.0, 0.0)]);
    /// assert!(cw.clone().oriented(true).is_ccw());
    /// assert_eq!(cw.clone().oriented(false), cw);
    /// ```
    pub fn oriented(mut self, ccw: bool) -> Contour {
        if self.is_ccw() != ccw {
            self.reverse();
        }
        self
    }

    /// Runs the contour the other way, in place ([`Contour::reversed`] without a copy).
    ///
    /// ```
    /// use pocketeer::geom::{Contour, Point};
    /// let p = Point::new;
    /// let mut c = Contour::polygon(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
    /// let copy = c.reversed();
    /// c.reverse();
    /// assert_eq!(c, copy);
    /// ```
    pub fn reverse(&mut self) {
        self.segments.reverse();
        for s in &mut self.segments {
            *s = s.reversed();
        }
    }

    /// `count` points spread evenly along the contour by length (the middles of `count` equal
    /// parts), for deciding which side of another contour it lies on.
    ///
    /// ```
    /// use pocketeer::geom::{Contour, Point};
    /// let square = Contour::polygon(&[
    ///     Point::new(0.0, 0.0), Point::new(4.0, 0.0), Point::new(4.0, 4.0), Point::new(0.0, 4.0),
    /// ]);
    /// let p = square.points_along(4);
    /// assert_eq!(p, vec![Point::new(2.0, 0.0), Point::new(4.0, 2.0), Point::new(2.0, 4.0), Point::new(0.0, 2.0)]);
    /// ```
    pub fn points_along(&self, count: usize) -> Vec<Point> {
        let total = self.length();
        let mut out = Vec::with_capacity(count);
        let mut acc = 0.0;
        let mut k = 0;
        for s in &self.segments {
            let len = s.length();
            while k < count {
                let target = (k as f64 + 0.5) / count as f64 * total;
                if target > acc + len {
                    break;
                }
                let t = if len > 0.0 {
                    ((target - acc) / len).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                out.push(s.point_at(t));
                k += 1;
            }
            acc += len;
        }
        out
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        self.segments.iter().map(Segment::length).sum()
    }

    /// Bounding box.
    pub fn bbox(&self) -> Aabb {
        bbox_of(&self.segments)
    }

    /// Winding number of the contour around `p` (for `p` not on the contour).
    pub fn winding_number(&self, p: Point) -> i32 {
        winding_number(&self.segments, p)
    }

    /// True when `p` lies inside (non-zero winding). Undefined for `p` on the contour.
    pub fn contains(&self, p: Point) -> bool {
        self.winding_number(p) != 0
    }
}

/// The box round `segments` (empty for none).
///
/// ```
/// use pocketeer::geom::{bbox_of, Line, Point, Segment};
/// let l = |x0, y0, x1, y1| Segment::Line(Line::new(Point::new(x0, y0), Point::new(x1, y1)));
/// let b = bbox_of(&[l(0.0, 0.0, 2.0, 1.0), l(2.0, 1.0, -1.0, 3.0)]);
/// assert_eq!((b.min, b.max), (Point::new(-1.0, 0.0), Point::new(2.0, 3.0)));
/// ```
pub fn bbox_of(segments: &[Segment]) -> Aabb {
    segments.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.bbox()))
}

/// Exact signed area enclosed by closed chain `segments` (positive when counter-clockwise).
///
/// Computed about the first start point, so that translating a part far from the origin
/// does not cost precision. Where one segment ends a hair from where the next begins (offset
/// pieces meeting at a node end where their own curves put the node, up to some 1e-8 mm
/// apart along a shallow crossing), the chain is closed by the chord across the gap: left
/// out, each such gap would count the triangle it spans with `o`, 1e-6 mm² for a gap of
/// 2e-8 mm 100 mm away.
pub fn signed_area(segments: &[Segment]) -> f64 {
    let Some(first) = segments.first() else { return 0.0 };
    let o = first.start();
    let mut from = segments[segments.len() - 1].end() - o;
    let mut sum = 0.0;
    for s in segments {
        let start = s.start() - o;
        sum += from.cross(start) + s.area_term(o);
        from = s.end() - o;
    }
    0.5 * sum
}

/// True when the closed chain `segments` bounds a convex region: it turns one way only, its
/// arcs bending the way it runs round and its joints turning that way or not at all (within
/// `eps` of a turn against it, in the sine of the angle). A chain that winds round more than
/// once is not told apart.
///
/// ```
/// use pocketeer::geom::{is_convex, Arc, Contour, Point, Segment};
/// let p = Point::new;
/// let square = Contour::polygon(&[p(0.0, 0.0), p(2.0, 0.0), p(2.0, 2.0), p(0.0, 2.0)]);
/// assert!(is_convex(&square.segments, 1e-9));
/// let notch = Contour::polygon(&[p(0.0, 0.0), p(2.0, 0.0), p(1.0, 1.0), p(2.0, 2.0), p(0.0, 2.0)]);
/// assert!(!is_convex(&notch.segments, 1e-9));
/// // A circle run clockwise (a loop round an island) is convex too.
/// let c = Arc::circle(p(0.0, 0.0), 3.0).reversed();
/// assert!(is_convex(&[Segment::Arc(c)], 1e-9));
/// ```
pub fn is_convex(segments: &[Segment], eps: f64) -> bool {
    let ccw = signed_area(segments) > 0.0;
    let turns_right_way = |turn: f64| if ccw { turn >= -eps } else { turn <= eps };
    let arcs_bend_right_way = segments.iter().all(|s| match s {
        Segment::Arc(a) => a.is_ccw() == ccw,
        Segment::Line(_) => true,
    });
    let n = segments.len();
    arcs_bend_right_way
        && (0..n).all(|k| {
            let (a, b) = (&segments[k], &segments[(k + 1) % n]);
            turns_right_way(a.tangent_at(1.0).cross(b.tangent_at(0.0)))
        })
}

/// Signed crossings of the ray from `p` towards +x with the piece from `a` to `b` whose points
/// between have abscissa `x_at(y)`: +1 upwards, -1 downwards, 0 when it passes left of `p`.
/// Half-open in y, so that a ray through a joint counts it once.
fn ray_crossing(a: Point, b: Point, p: Point, x_at: impl Fn(f64) -> f64) -> i32 {
    let up = a.y <= p.y && b.y > p.y;
    let down = b.y <= p.y && a.y > p.y;
    if !(up || down) || x_at(p.y) <= p.x {
        return 0;
    }
    if up {
        1
    } else {
        -1
    }
}

/// Winding contribution of one segment around `p` (the signed crossings of a ray to +x),
/// the segment taken to start at `from`: the end of the segment before it in the chain. A
/// chain closes only up to rounding (a quarter arc ends 1e-14 from where the next begins), and
/// a ray passing through that gap would cross neither; with shared joints it crosses one.
fn crossings(seg: &Segment, from: Point, p: Point) -> i32 {
    let mut b = seg.bbox();
    b.add_point(from);
    if ray_misses(&b, p) {
        return 0;
    }
    crossings_in_box(seg, from, p)
}

/// True when the ray from `p` towards +x cannot meet anything inside the box `b`.
fn ray_misses(b: &Aabb, p: Point) -> bool {
    p.y < b.min.y || p.y > b.max.y || p.x >= b.max.x
}

/// [`crossings`] for a point within the box of the segment and `from` (or left of it).
fn crossings_in_box(seg: &Segment, from: Point, p: Point) -> i32 {
    match seg {
        Segment::Line(l) => ray_crossing(from, l.end, p, |y| {
            let (a, d) = (l.start, l.end - l.start);
            a.x + (y - a.y) * d.x / d.y
        }),
        Segment::Arc(arc) => {
            // Split the arc where its tangent is horizontal (top and bottom of the circle): each
            // piece is monotone in y and lies in one half of the circle. A sweep of at most 2π
            // passes such a point at most three times.
            let mut cuts = [0.0; 5];
            let mut n = 1;
            let (a0, sw) = (arc.start_angle(), arc.sweep());
            let (lo, hi) = (a0.min(a0 + sw), a0.max(a0 + sw));
            let mut angle = PI / 2.0 + ((lo - PI / 2.0) / PI).ceil() * PI;
            while angle < hi && n < 4 {
                if angle > lo {
                    cuts[n] = (angle - a0) / sw;
                    n += 1;
                }
                angle += PI;
            }
            let cuts = &mut cuts[..=n];
            cuts[n] = 1.0;
            // Parameters grow with the angle for a counter-clockwise arc, fall for a clockwise.
            cuts[1..n].sort_unstable_by(f64::total_cmp);
            let mut total = 0;
            for w in cuts.windows(2) {
                let q0 = if w[0] == 0.0 { from } else { arc.point_at(w[0]) };
                let q1 = arc.point_at(w[1]);
                let right = arc.angle_at(0.5 * (w[0] + w[1])).cos() > 0.0;
                total += ray_crossing(q0, q1, p, |y| {
                    let dy = y - arc.center().y;
                    let dx = ((arc.radius() - dy) * (arc.radius() + dy)).max(0.0).sqrt();
                    if right {
                        arc.center().x + dx
                    } else {
                        arc.center().x - dx
                    }
                });
            }
            total
        }
    }
}

/// Winding number of closed chain `segments` around `p` (for `p` not on the chain).
pub fn winding_number(segments: &[Segment], p: Point) -> i32 {
    let Some(last) = segments.last() else { return 0 };
    let mut from = last.end();
    let mut total = 0;
    for s in segments {
        total += crossings(s, from, p);
        from = s.end();
    }
    total
}

/// Winding numbers of one closed chain around many points, faster than a scan of every
/// segment: the segments are filed by horizontal strips, and a point looks only at its strip.
///
/// ```
/// use pocketeer::geom::{winding_number, Line, Point, Segment, WindingIndex};
/// let n = 1000;
/// let pts: Vec<Point> = (0..n).map(|k| {
///     let a = k as f64 / n as f64 * std::f64::consts::TAU;
///     Point::new(10.0 * a.cos(), 10.0 * a.sin())
/// }).collect();
/// let segs: Vec<Segment> = (0..n).map(|k| Segment::Line(Line::new(pts[k], pts[(k + 1) % n]))).collect();
/// let index = WindingIndex::new(&segs);
/// for p in [Point::new(0.0, 0.0), Point::new(9.0, 3.0), Point::new(11.0, 0.0)] {
///     assert_eq!(index.winding(&segs, p), winding_number(&segs, p));
/// }
/// ```
pub struct WindingIndex {
    y0: f64,
    dy: f64,
    /// Strip k's segments are `filed[starts[k]..starts[k + 1]]`: one list for all strips,
    /// filled in two passes (a count, then the entries), not a growing list per strip.
    starts: Vec<u32>,
    filed: Vec<u32>,
    /// Each segment's box with the end of the segment before it, grown by the slack.
    boxes: Vec<Aabb>,
    /// The union of `boxes`.
    extent: Aabb,
}

impl WindingIndex {
    /// Files `segments` by strips.
    pub fn new(segments: &[Segment]) -> WindingIndex {
        let n = segments.len();
        // Each segment also answers for the gap from the end of the one before it.
        let mut from = segments.last().map_or(Point::new(0.0, 0.0), Segment::end);
        let mut boxes: Vec<Aabb> = segments
            .iter()
            .map(|s| {
                let mut b = s.bbox();
                b.add_point(from);
                from = s.end();
                b
            })
            .collect();
        let all = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
        let slack = 1e-9 * all.width().max(all.height()).max(1.0);
        for b in &mut boxes {
            *b = b.inflated(slack);
        }
        let extent = all.inflated(slack);
        let height = all.height();
        if n == 0 || height.is_nan() || height <= 0.0 || n > u32::MAX as usize {
            return WindingIndex {
                y0: 0.0,
                dy: 1.0,
                starts: vec![0, n as u32],
                filed: (0..n as u32).collect(),
                boxes,
                extent,
            };
        }
        // As many strips as keeps the filing within a few entries per segment: long, steep
        // segments are filed in every strip they cross.
        let mut k = ((n as f64).sqrt() * 2.0).ceil().min(65536.0) as usize;
        // The strips each box spans, worked out as `winding` finds a point's strip.
        let spans = |k: usize| -> (f64, Vec<(u32, u32)>) {
            let dy = height / k as f64;
            let strip = |y: f64| (((y - all.min.y) / dy) as usize).min(k - 1) as u32;
            (
                dy,
                boxes.iter().map(|b| (strip(b.min.y), strip(b.max.y))).collect(),
            )
        };
        let (mut dy, mut spanned) = spans(k);
        while k > 1
            && spanned
                .iter()
                .map(|&(lo, hi)| (hi - lo + 1) as usize)
                .sum::<usize>()
                > 8 * n
        {
            k /= 2;
            (dy, spanned) = spans(k);
        }
        let mut starts = vec![0u32; k + 1];
        for &(lo, hi) in &spanned {
            for c in &mut starts[lo as usize + 1..=hi as usize + 1] {
                *c += 1;
            }
        }
        for j in 1..=k {
            starts[j] += starts[j - 1];
        }
        let mut next = starts.clone();
        let mut filed = vec![0u32; starts[k] as usize];
        for (i, &(lo, hi)) in spanned.iter().enumerate() {
            for at in &mut next[lo as usize..=hi as usize] {
                filed[*at as usize] = i as u32;
                *at += 1;
            }
        }
        WindingIndex {
            y0: all.min.y,
            dy,
            starts,
            filed,
            boxes,
            extent,
        }
    }

    /// The box outside which the winding number is 0 without a segment looked at: every
    /// segment's box (with the end before it), grown by the slack. A point's ray (to the
    /// right) crosses none of the segments unless it meets this box.
    pub fn extent(&self) -> Aabb {
        self.extent
    }

    /// Winding number around `p` of the chain this index was built from.
    pub fn winding(&self, segments: &[Segment], p: Point) -> i32 {
        let s = (p.y - self.y0) / self.dy;
        let strips = self.starts.len() - 1;
        if s.is_nan() || s < 0.0 || s > strips as f64 {
            return 0;
        }
        let k = (s as usize).min(strips - 1);
        let strip = &self.filed[self.starts[k] as usize..self.starts[k + 1] as usize];
        let n = segments.len();
        strip
            .iter()
            .map(|&i| {
                let i = i as usize;
                if ray_misses(&self.boxes[i], p) {
                    return 0;
                }
                crossings_in_box(&segments[i], segments[(i + n - 1) % n].end(), p)
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Arc;
    use std::f64::consts::{PI, TAU};

    fn slot() -> Contour {
        // A 10 x 4 rectangle whose right side is a half circle bulging outwards: area 40 + 2π.
        let p = |x, y| Point::new(x, y);
        Contour::new(vec![
            Segment::Line(Line::new(p(0.0, 0.0), p(10.0, 0.0))),
            Segment::Arc(Arc::new(p(10.0, 2.0), 2.0, -PI / 2.0, PI)),
            Segment::Line(Line::new(p(10.0, 4.0), p(0.0, 4.0))),
            Segment::Line(Line::new(p(0.0, 4.0), p(0.0, 0.0))),
        ])
    }

    #[test]
    fn a_hair_between_segments_counts_as_its_chord_in_the_area() {
        // A 10 mm square 100 mm from the origin whose top edge begins 1e-6 mm right of where
        // the right edge ends: the area is that of the polygon through all five points
        // (100 mm²; a sum that left out the chord across the gap would be 5e-6 mm² off).
        let p = |x, y| Point::new(x, y);
        let pts = [
            p(100.0, 100.0),
            p(110.0, 100.0),
            p(110.0, 110.0),
            p(110.000001, 110.0),
            p(100.0, 110.0),
        ];
        let gapped = Contour::new(vec![
            Segment::Line(Line::new(pts[0], pts[1])),
            Segment::Line(Line::new(pts[1], pts[2])),
            Segment::Line(Line::new(pts[3], pts[4])),
            Segment::Line(Line::new(pts[4], pts[0])),
        ]);
        let polygon = Contour::polygon(&pts).signed_area();
        assert!((gapped.signed_area() - polygon).abs() < 1e-12);
        assert!((polygon - 100.0).abs() < 1e-9);
    }

    #[test]
    fn a_ray_through_a_joint_that_closes_only_up_to_rounding_crosses_once() {
        // Four quarter arcs: each ends 1e-14 or so from where the next begins.
        let quarters = Contour::new(
            (0..4)
                .map(|k| {
                    Segment::Arc(Arc::new(
                        Point::new(0.0, 0.0),
                        50.0,
                        k as f64 * PI / 2.0,
                        PI / 2.0,
                    ))
                })
                .collect(),
        );
        for y in [-1.6e-15, 0.0, 1e-15, -1e-14, 3e-15] {
            let p = Point::new(17.0, y);
            assert_eq!(quarters.winding_number(p), 1, "at y = {y}");
            assert_eq!(
                WindingIndex::new(&quarters.segments).winding(&quarters.segments, p),
                1
            );
        }
    }

    #[test]
    fn area_counts_arc_segments() {
        assert!((slot().signed_area() - (40.0 + 2.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn a_ray_through_the_seam_of_a_full_circle_counts_right() {
        // The circle starts and ends on the ray from a point level with its centre.
        for k in 1..200 {
            let r = k as f64 * 0.37;
            for sweep in [TAU, -TAU] {
                let c = Contour::new(vec![Segment::Arc(Arc::new(
                    Point::new(40.0, 30.0),
                    r,
                    0.0,
                    sweep,
                ))]);
                assert_eq!(c.winding_number(Point::new(40.0 - r - 1e-4, 30.0)), 0, "r = {r}");
                assert_eq!(
                    c.winding_number(Point::new(40.0 - r + 1e-4, 30.0)).abs(),
                    1,
                    "r = {r}"
                );
            }
        }
    }

    #[test]
    fn winding_sees_points_in_the_arc_bulge() {
        let c = slot();
        assert!(c.contains(Point::new(11.5, 2.0)));
        assert!(!c.contains(Point::new(12.5, 2.0)));
        assert!(c.contains(Point::new(5.0, 2.0)));
        assert_eq!(c.reversed().winding_number(Point::new(11.0, 2.0)), -1);
    }
}
