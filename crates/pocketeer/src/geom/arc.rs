//! Circular arcs of any sweep in either direction, full circles included.

use super::rounding::ceil;
use super::{Aabb, Point, Vector};
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, TAU};

/// A circular arc: centre, radius, start angle and signed sweep (positive = counter-clockwise).
///
/// The sweep lies in [-2π, 2π]; a sweep of ±2π is a full circle starting and ending at the
/// start angle. Parameter t ∈ [0, 1] runs from start to end at constant speed.
///
/// ```
/// use pocketeer::geom::{Arc, Point};
/// use std::f64::consts::PI;
/// let a = Arc::new(Point::new(0.0, 0.0), 2.0, 0.0, PI / 2.0);
/// assert!((a.end().x).abs() < 1e-12 && (a.end().y - 2.0).abs() < 1e-12);
/// assert!((a.length() - PI).abs() < 1e-12);
/// assert!(a.is_ccw());
/// ```
///
/// The end points are computed once, when the arc is made: most of what is asked of an arc
/// (its box, its area term, joining it to its neighbours) needs them, and the trigonometry
/// was a fifth of the time of reading a drawing of splines. The fields are therefore read
/// through methods, so that they cannot drift from the end points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Arc {
    center: Point,
    radius: f64,
    start_angle: f64,
    sweep: f64,
    #[serde(skip)]
    start: Point,
    #[serde(skip)]
    end: Point,
}

/// An end this close to the circle, relative to the radius, is on it.
const ON_CIRCLE: f64 = 1e-12;

/// A sweep this close to a whole turn is a full circle.
const FULL_TURN: f64 = TAU * (1.0 - 1e-14);

/// `angle` reduced to [0, 2π).
pub fn normalize_angle(angle: f64) -> f64 {
    let a = rem_euclid_tau(angle);
    if a >= TAU {
        0.0
    } else {
        a
    }
}

/// `angle.rem_euclid(TAU)`, bit for bit, without the division loop of `fmod` for the angles
/// met in practice (differences of two angles, within two turns of zero), where the remainder
/// is `angle` itself or `angle` less one turn: by Sterbenz's lemma that subtraction is exact,
/// as `fmod`'s remainder always is. Angle reductions were a tenth of a small offset's time.
fn rem_euclid_tau(angle: f64) -> f64 {
    let m = angle.abs();
    let r = if m < TAU {
        angle
    } else if m < 2.0 * TAU {
        // fmod's remainder takes the sign of the dividend, a zero too.
        let r = angle - TAU.copysign(angle);
        if r == 0.0 {
            0.0f64.copysign(angle)
        } else {
            r
        }
    } else {
        return angle.rem_euclid(TAU);
    };
    if r < 0.0 {
        r + TAU
    } else {
        r
    }
}

impl Arc {
    /// An arc from its centre, radius, start angle and signed sweep.
    pub fn new(center: Point, radius: f64, start_angle: f64, sweep: f64) -> Arc {
        let start = center + Vector::from_angle(start_angle) * radius;
        let end = if sweep.abs() >= FULL_TURN {
            start
        } else {
            center + Vector::from_angle(start_angle + sweep) * radius
        };
        Arc::with_ends(center, radius, start_angle, sweep, start, end)
    }

    /// Centre.
    pub fn center(&self) -> Point {
        self.center
    }

    /// Radius (> 0).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Angle of the start point, radians.
    pub fn start_angle(&self) -> f64 {
        self.start_angle
    }

    /// Signed sweep, radians: positive counter-clockwise.
    pub fn sweep(&self) -> f64 {
        self.sweep
    }

    /// A full counter-clockwise circle starting at angle 0.
    pub fn circle(center: Point, radius: f64) -> Arc {
        Arc::new(center, radius, 0.0, TAU)
    }

    /// The arc from `start` to `end` with DXF bulge `bulge` = tan(sweep / 4) (positive:
    /// counter-clockwise). Returns `None` when the bulge is zero or the points coincide.
    ///
    /// ```
    /// use pocketeer::geom::{Arc, Point};
    /// let half = Arc::from_bulge(Point::new(1.0, 0.0), Point::new(-1.0, 0.0), 1.0).unwrap();
    /// assert!((half.radius() - 1.0).abs() < 1e-12);
    /// assert!(half.center().distance(Point::new(0.0, 0.0)) < 1e-12);
    /// ```
    pub fn from_bulge(start: Point, end: Point, bulge: f64) -> Option<Arc> {
        let chord = end - start;
        if bulge == 0.0 || !bulge.is_finite() || chord.length_sq() == 0.0 {
            return None;
        }
        let sweep = 4.0 * bulge.atan();
        let center = start.midpoint(end) + chord.perp() * ((1.0 - bulge * bulge) / (4.0 * bulge));
        let radius = center.distance(start);
        let start_angle = (start - center).angle();
        // Both ends are on the arc by construction: kept as given, so that arcs and lines
        // joined end to end in a drawing stay joined exactly.
        Some(Arc::with_ends(center, radius, start_angle, sweep, start, end))
    }

    /// The arc around `center` from `start` to `end` (the end is projected on the circle through
    /// `start`), counter-clockwise when `ccw`. Equal start and end give a full circle.
    pub fn from_center(center: Point, start: Point, end: Point, ccw: bool) -> Arc {
        let radius = center.distance(start);
        let a0 = (start - center).angle();
        let a1 = (end - center).angle();
        let mut sweep = if ccw {
            normalize_angle(a1 - a0)
        } else {
            -normalize_angle(a0 - a1)
        };
        if sweep == 0.0 {
            sweep = if ccw { TAU } else { -TAU };
        }
        if sweep.abs() >= FULL_TURN {
            return Arc::with_ends(center, radius, a0, sweep, start, start);
        }
        // An end on the circle to within rounding is kept as given (the meeting point of two
        // arcs stays one point); one off it is moved onto it.
        let off = end - center;
        let reach = off.length();
        let end = if reach == 0.0 {
            center + Vector::from_angle(a1) * radius
        } else if (reach - radius).abs() <= ON_CIRCLE * radius {
            end
        } else {
            center + off * (radius / reach)
        };
        Arc::with_ends(center, radius, a0, sweep, start, end)
    }

    /// The arc with its end points given, on it to within rounding (the import maps a
    /// polyline's arcs with their vertices kept exactly as their ends).
    pub(crate) fn with_ends(
        center: Point,
        radius: f64,
        start_angle: f64,
        sweep: f64,
        start: Point,
        end: Point,
    ) -> Arc {
        Arc {
            center,
            radius,
            start_angle,
            sweep,
            start,
            end,
        }
    }

    /// DXF bulge: tan(sweep / 4).
    pub fn bulge(&self) -> f64 {
        (self.sweep / 4.0).tan()
    }

    /// Largest distance between the arc and its chord (for sweeps up to a half turn; larger
    /// arcs are far from flat anyway).
    ///
    /// ```
    /// use pocketeer::geom::{Arc, Point};
    /// let half = Arc::new(Point::new(0.0, 0.0), 2.0, 0.0, std::f64::consts::PI);
    /// assert!((half.sagitta() - 2.0).abs() < 1e-12);
    /// ```
    pub fn sagitta(&self) -> f64 {
        let s = (self.sweep.abs().min(std::f64::consts::PI) / 4.0).sin();
        2.0 * self.radius * s * s
    }

    /// Angle of the end point.
    pub fn end_angle(&self) -> f64 {
        self.start_angle + self.sweep
    }

    /// True when the arc runs counter-clockwise.
    pub fn is_ccw(&self) -> bool {
        self.sweep > 0.0
    }

    /// True for a full circle.
    pub fn is_full_circle(&self) -> bool {
        self.sweep.abs() >= FULL_TURN
    }

    /// Angle at parameter `t`.
    pub fn angle_at(&self, t: f64) -> f64 {
        self.start_angle + self.sweep * t
    }

    /// The point at parameter `t` (exactly [`Arc::start`] at 0 and [`Arc::end`] at 1, so that a
    /// full circle closes on itself without rounding).
    pub fn point_at(&self, t: f64) -> Point {
        if t == 1.0 {
            return self.end();
        }
        self.point_at_angle(self.angle_at(t))
    }

    /// The point of the circle at `angle`.
    pub fn point_at_angle(&self, angle: f64) -> Point {
        self.center + Vector::from_angle(angle) * self.radius
    }

    /// Start point.
    pub fn start(&self) -> Point {
        self.start
    }

    /// End point.
    pub fn end(&self) -> Point {
        self.end
    }

    /// Unit tangent in the direction of travel at parameter `t`.
    pub fn tangent_at(&self, t: f64) -> Vector {
        let radial = Vector::from_angle(self.angle_at(t));
        if self.sweep >= 0.0 {
            radial.perp()
        } else {
            -radial.perp()
        }
    }

    /// Length.
    pub fn length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }

    /// Parameter of the point of the arc's circle in the direction of `angle` from the centre.
    ///
    /// Inside the arc this is in [0, 1]; outside, the value is continued past the nearer end
    /// (negative before the start, above 1 past the end).
    pub fn param_of_angle(&self, angle: f64) -> f64 {
        let span = self.sweep.abs();
        if span == 0.0 {
            return 0.0;
        }
        let delta = if self.sweep > 0.0 {
            normalize_angle(angle - self.start_angle)
        } else {
            normalize_angle(self.start_angle - angle)
        };
        if delta <= span || delta - span < TAU - delta {
            delta / span
        } else {
            -(TAU - delta) / span
        }
    }

    /// Parameter of the point of the arc nearest in angle to `p` (see [`Arc::param_of_angle`]).
    pub fn param_of(&self, p: Point) -> f64 {
        self.param_of_angle((p - self.center).angle())
    }

    /// True when the direction of `angle` from the centre falls within the arc, allowing
    /// `tol` millimetres along the circle past either end.
    pub fn contains_angle(&self, angle: f64, tol: f64) -> bool {
        self.param_within(angle, tol).is_some()
    }

    /// The parameter of `angle` ([`Arc::param_of_angle`]) when its direction falls within the
    /// arc as [`Arc::contains_angle`] tells, else None: the test and the parameter at once.
    ///
    /// ```
    /// use pocketeer::geom::{Arc, Point};
    /// let quarter = Arc::new(Point::new(0.0, 0.0), 1.0, 0.0, std::f64::consts::FRAC_PI_2);
    /// assert_eq!(quarter.param_within(std::f64::consts::FRAC_PI_4, 0.0), Some(0.5));
    /// assert_eq!(quarter.param_within(std::f64::consts::PI, 0.0), None);
    /// ```
    pub fn param_within(&self, angle: f64, tol: f64) -> Option<f64> {
        let t = self.param_of_angle(angle);
        let slack = if self.length() > 0.0 {
            tol / self.length()
        } else {
            0.0
        };
        (t >= -slack && t <= 1.0 + slack).then_some(t)
    }

    /// Bounding box: the end points and every axis extreme the arc passes.
    pub fn bbox(&self) -> Aabb {
        let mut b = Aabb::from_points(self.start(), self.end());
        let end = self.start_angle + self.sweep;
        let (lo, hi) = (self.start_angle.min(end), self.start_angle.max(end));
        // The axis directions k·π/2 with lo ≤ k·π/2 ≤ hi: at most five for a full circle.
        let first = ceil(lo / FRAC_PI_2);
        for i in 0..5 {
            let k = first + i as f64;
            if k * FRAC_PI_2 > hi {
                break;
            }
            let (dx, dy) = match (k as i64).rem_euclid(4) {
                0 => (1.0, 0.0),
                1 => (0.0, 1.0),
                2 => (-1.0, 0.0),
                _ => (0.0, -1.0),
            };
            b.add_point(Point::new(
                self.center.x + dx * self.radius,
                self.center.y + dy * self.radius,
            ));
        }
        b
    }

    /// The same arc run the other way: its ends swapped exactly.
    pub fn reversed(&self) -> Arc {
        Arc::with_ends(
            self.center,
            self.radius,
            self.end_angle(),
            -self.sweep,
            self.end,
            self.start,
        )
    }

    /// The piece between parameters `t0` and `t1` (an end at 0 or 1 is the arc's own).
    pub fn subsegment(&self, t0: f64, t1: f64) -> Arc {
        let (start_angle, sweep) = (self.angle_at(t0), self.sweep * (t1 - t0));
        if sweep.abs() >= FULL_TURN {
            return Arc::new(self.center, self.radius, start_angle, sweep);
        }
        // Only the ends that are not the arc's own are computed: a sine and cosine each.
        let end_at = |t: f64, angle: f64| {
            if t == 0.0 {
                self.start
            } else if t == 1.0 {
                self.end
            } else {
                self.point_at_angle(angle)
            }
        };
        let start = end_at(t0, start_angle);
        let end = end_at(t1, start_angle + sweep);
        Arc::with_ends(self.center, self.radius, start_angle, sweep, start, end)
    }

    /// The two pieces on either side of parameter `t`.
    pub fn split_at(&self, t: f64) -> (Arc, Arc) {
        (self.subsegment(0.0, t), self.subsegment(t, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn bulge_round_trip_both_directions() {
        for b in [0.3, -0.3, 1.0, -1.0, 2.5, -2.5] {
            let a = Arc::from_bulge(Point::new(3.0, 1.0), Point::new(-2.0, 4.0), b).unwrap();
            assert!(a.start().distance(Point::new(3.0, 1.0)) < 1e-12);
            assert!(a.end().distance(Point::new(-2.0, 4.0)) < 1e-12);
            assert!((a.bulge() - b).abs() < 1e-12);
        }
    }

    #[test]
    fn angles_reduce_as_rem_euclid_does_bit_for_bit() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut angles = vec![
            0.0,
            -0.0,
            TAU,
            -TAU,
            2.0 * TAU,
            -2.0 * TAU,
            PI,
            -PI,
            1e-300,
            -1e-300,
        ];
        // The neighbours of one and two turns, either sign (positive, so one more bit is up).
        for a in [TAU, 2.0 * TAU] {
            let (up, down) = (f64::from_bits(a.to_bits() + 1), f64::from_bits(a.to_bits() - 1));
            angles.extend([up, down, -up, -down]);
        }
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Uniform in (-20, 20): inside and outside the two turns the fast way covers.
            angles.push((x >> 11) as f64 / (1u64 << 53) as f64 * 40.0 - 20.0);
        }
        for a in angles {
            assert_eq!(rem_euclid_tau(a).to_bits(), a.rem_euclid(TAU).to_bits(), "{a:e}");
        }
    }

    #[test]
    fn param_of_continues_past_the_nearer_end() {
        let a = Arc::new(Point::ORIGIN, 1.0, 0.0, PI / 2.0);
        assert!((a.param_of_angle(PI / 4.0) - 0.5).abs() < 1e-12);
        assert!(a.param_of_angle(-0.1) < 0.0);
        assert!(a.param_of_angle(PI / 2.0 + 0.1) > 1.0);
        let cw = a.reversed();
        assert!((cw.param_of_angle(PI / 2.0)).abs() < 1e-12);
        assert!((cw.param_of_angle(0.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bbox_of_a_half_circle_includes_its_top() {
        let a = Arc::new(Point::ORIGIN, 1.0, 0.0, PI);
        let b = a.bbox();
        assert!((b.max.y - 1.0).abs() < 1e-12 && b.min.y.abs() < 1e-12);
        let full = Arc::circle(Point::new(5.0, 5.0), 2.0);
        assert_eq!(full.bbox().width(), 4.0);
    }

    /// A piece's ends at 0 and 1 are the arc's own exactly; the others are the points at
    /// their angles.
    #[test]
    fn subsegment_keeps_the_arcs_own_ends_and_computes_the_others() {
        let a = Arc::from_center(
            Point::new(1.0, 2.0),
            Point::new(4.0, 2.0),
            Point::new(1.0, -1.0),
            true,
        );
        let (head, tail) = a.split_at(0.25);
        assert_eq!(head.start(), a.start());
        assert_eq!(tail.end(), a.end());
        assert_eq!(head.end(), tail.start());
        assert_eq!(head.end(), a.point_at_angle(a.angle_at(0.25)));
        let mid = a.subsegment(0.25, 0.75);
        assert_eq!(mid.start(), a.point_at_angle(a.angle_at(0.25)));
        assert_eq!(mid.end(), a.point_at_angle(a.angle_at(0.75)));
        assert!((mid.sweep() - a.sweep() / 2.0).abs() < 1e-15);
        // A whole circle's whole piece closes on itself.
        let c = Arc::circle(Point::new(0.0, 0.0), 2.0);
        let whole = c.subsegment(0.0, 1.0);
        assert_eq!(whole.start(), whole.end());
    }

    /// The box holds every point of the arc and is tight: arcs starting anywhere (angles
    /// beyond ±2π too), of every sweep, both ways.
    #[test]
    fn bbox_is_the_hull_of_the_arc() {
        for i in 0..40 {
            for &sweep in &[0.01, 0.7, PI / 2.0, 2.5, PI, 4.0, 6.2, TAU, -0.7, -PI, -5.0, -TAU] {
                let a = Arc::new(Point::new(-3.0, 8.0), 1.5, i as f64 * 0.37 - 9.0, sweep);
                let b = a.bbox();
                let mut hull = Aabb::EMPTY;
                for k in 0..=4000 {
                    let p = a.point_at(k as f64 / 4000.0);
                    assert!(b.inflated(1e-12).contains(p), "{a:?}");
                    hull.add_point(p);
                }
                // Samples 1/4000 of the sweep apart miss an extreme by at most r(1 - cos(π/4000)).
                assert!(
                    (b.min.x - hull.min.x).abs() < 1e-6 && (b.max.x - hull.max.x).abs() < 1e-6,
                    "{a:?}"
                );
                assert!(
                    (b.min.y - hull.min.y).abs() < 1e-6 && (b.max.y - hull.max.y).abs() < 1e-6,
                    "{a:?}"
                );
            }
        }
    }
}
