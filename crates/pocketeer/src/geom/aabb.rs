//! Axis-aligned bounding boxes.

use super::Point;
use serde::Serialize;

/// An axis-aligned bounding box. An empty box has `min > max`.
///
/// ```
/// use pocketeer::geom::{Aabb, Point};
/// let mut b = Aabb::EMPTY;
/// b.add_point(Point::new(1.0, 2.0));
/// b.add_point(Point::new(-1.0, 5.0));
/// assert_eq!(b.width(), 2.0);
/// assert!(b.contains(Point::new(0.0, 3.0)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Aabb {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl Aabb {
    /// The box that contains nothing.
    pub const EMPTY: Aabb = Aabb {
        min: Point::new(f64::INFINITY, f64::INFINITY),
        max: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    /// The smallest box holding both points.
    pub fn from_points(a: Point, b: Point) -> Aabb {
        Aabb {
            min: Point::new(a.x.min(b.x), a.y.min(b.y)),
            max: Point::new(a.x.max(b.x), a.y.max(b.y)),
        }
    }

    /// True for the empty box.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y
    }

    /// Grows the box to hold `p`.
    pub fn add_point(&mut self, p: Point) {
        self.min.x = self.min.x.min(p.x);
        self.min.y = self.min.y.min(p.y);
        self.max.x = self.max.x.max(p.x);
        self.max.y = self.max.y.max(p.y);
    }

    /// The smallest box holding both boxes.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: Point::new(self.min.x.min(o.min.x), self.min.y.min(o.min.y)),
            max: Point::new(self.max.x.max(o.max.x), self.max.y.max(o.max.y)),
        }
    }

    /// The box grown by `d` on every side.
    pub fn inflated(&self, d: f64) -> Aabb {
        Aabb {
            min: Point::new(self.min.x - d, self.min.y - d),
            max: Point::new(self.max.x + d, self.max.y + d),
        }
    }

    /// True when the boxes share at least one point.
    pub fn intersects(&self, o: &Aabb) -> bool {
        // `&`, not `&&`: the four tests in one go, without a branch each to mispredict (the
        // index searches make millions of these tests whose outcomes follow no pattern).
        (self.min.x <= o.max.x) & (o.min.x <= self.max.x) & (self.min.y <= o.max.y) & (o.min.y <= self.max.y)
    }

    /// True when `p` lies in the box or on its edge.
    pub fn contains(&self, p: Point) -> bool {
        // `&`: see `intersects`.
        (p.x >= self.min.x) & (p.x <= self.max.x) & (p.y >= self.min.y) & (p.y <= self.max.y)
    }

    /// Squared distance from `p` to the box (zero inside it).
    ///
    /// ```
    /// use pocketeer::geom::{Aabb, Point};
    /// let b = Aabb::from_points(Point::new(0.0, 0.0), Point::new(2.0, 1.0));
    /// assert_eq!(b.distance_sq(Point::new(5.0, 5.0)), 25.0);
    /// assert_eq!(b.distance_sq(Point::new(1.0, 0.5)), 0.0);
    /// ```
    pub fn distance_sq(&self, p: Point) -> f64 {
        let dx = (self.min.x - p.x).max(p.x - self.max.x).max(0.0);
        let dy = (self.min.y - p.y).max(p.y - self.max.y).max(0.0);
        dx * dx + dy * dy
    }

    /// The distance between this box and `o`: 0 when they touch or overlap.
    ///
    /// ```
    /// use pocketeer::geom::{Aabb, Point};
    /// let a = Aabb::from_points(Point::new(0.0, 0.0), Point::new(2.0, 1.0));
    /// let b = Aabb::from_points(Point::new(5.0, 5.0), Point::new(6.0, 6.0));
    /// assert_eq!(a.distance_to_box(&b), 5.0);
    /// assert_eq!(a.distance_to_box(&a), 0.0);
    /// ```
    pub fn distance_to_box(&self, o: &Aabb) -> f64 {
        let dx = (self.min.x - o.max.x).max(o.min.x - self.max.x).max(0.0);
        let dy = (self.min.y - o.max.y).max(o.min.y - self.max.y).max(0.0);
        // Not `hypot`: a library call, in the inner loops of the searches that prune by
        // boxes, where coordinates are far from overflowing a square.
        (dx * dx + dy * dy).sqrt()
    }

    /// True when `o` lies entirely inside this box.
    pub fn contains_box(&self, o: &Aabb) -> bool {
        self.contains(o.min) && self.contains(o.max)
    }

    /// Width (x extent).
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    /// Height (y extent).
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }

    /// The largest absolute coordinate of the box: the scale that rounding errors grow with.
    pub fn magnitude(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        self.min
            .x
            .abs()
            .max(self.min.y.abs())
            .max(self.max.x.abs())
            .max(self.max.y.abs())
    }
}
