//! The two tolerances of the library, named and passed explicitly.

use super::Aabb;

/// Default distance below which two drawn end points are one node, in millimetres.
pub const DEFAULT_JOIN_TOLERANCE: f64 = 0.001;

/// Relative size of the geometric epsilon: a few thousand times f64 rounding at the drawing's scale.
const RELATIVE_EPSILON: f64 = 1e-11;

/// The tolerances every geometric decision uses.
///
/// * `join`: how far apart two drawn end points may be and still be one node (a drawing-level
///   choice, 0.001 mm by default).
/// * `eps`: equality and tangency, relative to the drawing's extent, so that a part drawn at
///   coordinates near 1e5 mm behaves as one drawn at the origin.
///
/// ```
/// use pocketeer::geom::{Aabb, Point, Tolerance};
/// let near = Tolerance::for_extent(&Aabb::from_points(Point::new(0.0, 0.0), Point::new(100.0, 50.0)), 0.001);
/// let far = Tolerance::for_extent(&Aabb::from_points(Point::new(1e5, 1e5), Point::new(1e5 + 100.0, 1e5 + 50.0)), 0.001);
/// assert!(far.eps > near.eps);
/// assert!(far.eps < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Join tolerance in millimetres.
    pub join: f64,
    /// Geometric epsilon in millimetres.
    pub eps: f64,
}

impl Tolerance {
    /// Tolerances for a drawing whose geometry lies in `extent`.
    pub fn for_extent(extent: &Aabb, join: f64) -> Tolerance {
        let scale = extent.magnitude().max(extent.width()).max(extent.height());
        Tolerance::for_scale(scale, join)
    }

    /// Tolerances for coordinates of magnitude up to `scale` millimetres.
    pub fn for_scale(scale: f64, join: f64) -> Tolerance {
        let scale = if scale.is_finite() {
            scale.max(100.0)
        } else {
            100.0
        };
        Tolerance {
            join,
            eps: scale * RELATIVE_EPSILON,
        }
    }
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance::for_scale(100.0, DEFAULT_JOIN_TOLERANCE)
    }
}
