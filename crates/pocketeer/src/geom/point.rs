//! Points and vectors in the plane.

use serde::Serialize;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A position in the plane, in millimetres inside the library.
///
/// ```
/// use pocketeer::geom::{Point, Vector};
/// let p = Point::new(1.0, 2.0) + Vector::new(0.5, -1.0);
/// assert_eq!(p, Point::new(1.5, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
}

/// A displacement in the plane.
///
/// ```
/// use pocketeer::geom::Vector;
/// let v = Vector::new(3.0, 4.0);
/// assert_eq!(v.length(), 5.0);
/// assert_eq!(v.perp(), Vector::new(-4.0, 3.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Vector {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
}

/// `(x, y)` with four decimals, as messages name places (exponent form when huge).
///
/// ```
/// use pocketeer::geom::Point;
/// assert_eq!(Point::new(1.5, -2.0).to_string(), "(1.5000, -2.0000)");
/// assert_eq!(Point::new(3e12, 0.0).to_string(), "(3e12, 0.0000)");
/// ```
impl std::fmt::Display for Point {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let part = |x: f64| {
            if x.is_finite() && x.abs() < 1e9 {
                format!("{x:.4}")
            } else {
                format!("{x:e}")
            }
        };
        write!(f, "({}, {})", part(self.x), part(self.y))
    }
}

impl Point {
    /// The point (x, y).
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }

    /// The origin.
    pub const ORIGIN: Point = Point::new(0.0, 0.0);

    /// Euclidean distance to `other`.
    pub fn distance(self, other: Point) -> f64 {
        (other - self).length()
    }

    /// Squared distance to `other`.
    pub fn distance_sq(self, other: Point) -> f64 {
        (other - self).length_sq()
    }

    /// The vector from the origin to this point.
    pub fn to_vector(self) -> Vector {
        Vector::new(self.x, self.y)
    }

    /// The point halfway to `other`.
    pub fn midpoint(self, other: Point) -> Point {
        Point::new(0.5 * (self.x + other.x), 0.5 * (self.y + other.y))
    }

    /// Linear interpolation: `self` at t = 0, `other` at t = 1.
    pub fn lerp(self, other: Point, t: f64) -> Point {
        self + (other - self) * t
    }

    /// True when both coordinates are finite numbers.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl Vector {
    /// The vector (x, y).
    pub const fn new(x: f64, y: f64) -> Self {
        Vector { x, y }
    }

    /// The unit vector at `angle` radians from the x axis.
    pub fn from_angle(angle: f64) -> Self {
        let (s, c) = super::sin_cos(angle);
        Vector::new(c, s)
    }

    /// Dot product.
    pub fn dot(self, o: Vector) -> f64 {
        self.x * o.x + self.y * o.y
    }

    /// z component of the cross product: positive when `o` lies counter-clockwise of `self`.
    pub fn cross(self, o: Vector) -> f64 {
        self.x * o.y - self.y * o.x
    }

    /// Length. (A plain square root: coordinates are bounded far below where squaring could
    /// overflow, and `hypot` costs several times more in the hot loops.)
    pub fn length(self) -> f64 {
        (self.x * self.x + self.y * self.y).sqrt()
    }

    /// Squared length.
    pub fn length_sq(self) -> f64 {
        self.dot(self)
    }

    /// The vector turned 90° counter-clockwise.
    pub fn perp(self) -> Vector {
        Vector::new(-self.y, self.x)
    }

    /// Angle from the x axis in (-π, π].
    pub fn angle(self) -> f64 {
        self.y.atan2(self.x)
    }

    /// This vector scaled to length 1, or `None` for the zero vector.
    pub fn normalized(self) -> Option<Vector> {
        let l = self.length();
        (l > 0.0 && l.is_finite()).then(|| self / l)
    }
}

impl Add<Vector> for Point {
    type Output = Point;
    fn add(self, v: Vector) -> Point {
        Point::new(self.x + v.x, self.y + v.y)
    }
}
impl AddAssign<Vector> for Point {
    fn add_assign(&mut self, v: Vector) {
        *self = *self + v;
    }
}
impl Sub<Vector> for Point {
    type Output = Point;
    fn sub(self, v: Vector) -> Point {
        Point::new(self.x - v.x, self.y - v.y)
    }
}
impl SubAssign<Vector> for Point {
    fn sub_assign(&mut self, v: Vector) {
        *self = *self - v;
    }
}
impl Sub for Point {
    type Output = Vector;
    fn sub(self, o: Point) -> Vector {
        Vector::new(self.x - o.x, self.y - o.y)
    }
}
impl Add for Vector {
    type Output = Vector;
    fn add(self, o: Vector) -> Vector {
        Vector::new(self.x + o.x, self.y + o.y)
    }
}
impl Sub for Vector {
    type Output = Vector;
    fn sub(self, o: Vector) -> Vector {
        Vector::new(self.x - o.x, self.y - o.y)
    }
}
impl Mul<f64> for Vector {
    type Output = Vector;
    fn mul(self, s: f64) -> Vector {
        Vector::new(self.x * s, self.y * s)
    }
}
impl Div<f64> for Vector {
    type Output = Vector;
    fn div(self, s: f64) -> Vector {
        Vector::new(self.x / s, self.y / s)
    }
}
impl Neg for Vector {
    type Output = Vector;
    fn neg(self) -> Vector {
        Vector::new(-self.x, -self.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cross_sign_is_counter_clockwise() {
        assert!(Vector::new(1.0, 0.0).cross(Vector::new(0.0, 1.0)) > 0.0);
        assert_eq!(Vector::new(0.0, 0.0).normalized(), None);
    }
}
