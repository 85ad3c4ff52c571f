//! The tolerances of the library, named in one place: the two a drawing sets (join, epsilon,
//! passed explicitly as [`Tolerance`]), the multiples of epsilon that mean "the same place",
//! and the fixed distances and angles the offset engine decides by, each with what it
//! protects against.

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

impl Tolerance {
    /// Ten epsilons: lengths and distances below this are rounding. A segment this short is a
    /// point, two ends this near are one place, and a gap this small between a writer's
    /// coordinates is not a gap.
    ///
    /// ```
    /// use pocketeer::geom::Tolerance;
    /// let tol = Tolerance::default();
    /// assert_eq!(tol.rounding(), 10.0 * tol.eps);
    /// ```
    pub fn rounding(&self) -> f64 {
        10.0 * self.eps
    }

    /// A hundred epsilons: how far apart points computed from crossings may be and still be
    /// one point. Curves meeting at a shallow angle, or turning back along each other at a
    /// joint, put their computed crossing this far along from where it is; the ends of pieces
    /// cut there are joined at this distance, and a loop thinner than this is no loop.
    ///
    /// ```
    /// use pocketeer::geom::Tolerance;
    /// let tol = Tolerance::default();
    /// assert!(tol.crossing() > tol.rounding());
    /// ```
    pub fn crossing(&self) -> f64 {
        100.0 * self.eps
    }

    /// A thousand epsilons: two pieces whose ends and middles are this near lie on each other
    /// (an outline drawn twice, or the two sides of a sliver that cancel). Still far below the
    /// join tolerance and any machining tolerance.
    ///
    /// ```
    /// use pocketeer::geom::Tolerance;
    /// let tol = Tolerance::default();
    /// assert!(tol.coincident() > tol.crossing() && tol.coincident() < tol.join);
    /// ```
    pub fn coincident(&self) -> f64 {
        1e3 * self.eps
    }
}

/// Distance (mm) within which two raw offset curves count as meeting: they touch where they
/// come this near, and run together where they stay this near. Offsets of walls drawn exactly
/// 2d apart coincide only to the precision of the drawing (a DXF written to six decimals puts
/// them up to a micrometre apart): a crossing missed there leaves a piece that is valid along
/// part of its length and judged whole, and loses the loop it bounds. Pieces cut at such a
/// touch stay within this distance of the offset, inside the accuracy of 1e-6 mm.
pub const TOUCH: f64 = 5e-7;

/// How far inside the offset distance a joining chord may come and still close a loop, mm:
/// far below any machining tolerance, far above rounding.
pub const JOIN_SLACK: f64 = 1e-5;

/// Sine of the angle from a full reversal below which a joint's side is taken from the
/// elements' curvature as well as their tangents (about six degrees: a line meeting a
/// semicircle 0.02 mm across at 179.1° is a slit at the scale of a 0.6 mm offset).
pub const NEAR_REVERSAL: f64 = 0.1;

/// How far inside `d` an offset piece may come and still count as at distance `d`: exact
/// offset pieces are at distance d up to rounding, far below ten epsilons; where offset curves
/// touch or run together to within [`TOUCH`] the split took them as meeting, and the pieces
/// there are as far inside d as the curves are apart. Never more than a thousandth of `d`.
pub fn offset_slack(d: f64, tol: &Tolerance) -> f64 {
    tol.rounding().max(TOUCH).min(1e-3 * d)
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance::for_scale(100.0, DEFAULT_JOIN_TOLERANCE)
    }
}
