//! One knot span of a NURBS as a polynomial in power form, evaluated by Horner's rule with its
//! first and second derivatives: the curve fitting evaluates each span hundreds of times, and
//! de Boor's algorithm costs a triangle of interpolations per point where Horner costs a row.

use super::curve::{Nurbs, MAX_DEGREE};
use crate::geom::{Point, Vector};
use std::cell::Cell;

/// The piece of a NURBS on one knot span `[a, b]`, as homogeneous coordinates `(x·w, y·w, w)`
/// that are polynomials in `s = (t − a) / (b − a)` ∈ [0, 1].
///
/// ```
/// use pocketeer::geom::Point;
/// use pocketeer::import::curve::Nurbs;
/// use pocketeer::import::span_polynomial::SpanPolynomial;
/// let pts = [Point::new(0.0, 0.0), Point::new(1.0, 2.0), Point::new(3.0, 3.0), Point::new(4.0, 0.0), Point::new(6.0, 1.0)];
/// let s = Nurbs::through(&pts).unwrap();
/// for (k, a, b) in s.spans() {
///     let poly = SpanPolynomial::new(&s, k);
///     let t = 0.3 * a + 0.7 * b;
///     assert!(poly.point(t).distance(s.point_in_span(k, t)) < 1e-12);
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpanPolynomial {
    degree: usize,
    /// The span's first parameter.
    start: f64,
    /// 1 / (b − a): ds/dt.
    rate: f64,
    /// Coefficients of s^0 … s^degree of (x·w, y·w, w).
    coefficients: [[f64; 3]; MAX_DEGREE + 1],
    /// False when w is 1 throughout (every weight 1, as in most drawings): the point is then
    /// (x·w, y·w) itself, and the division by w, the longest step of an evaluation, is left out.
    rational: bool,
}

impl SpanPolynomial {
    /// The piece of `nurbs` on its knot span `k` (one of [`Nurbs::spans`], which have
    /// `knots[k] < knots[k + 1]`).
    pub fn new(nurbs: &Nurbs, k: usize) -> SpanPolynomial {
        let p = nurbs.degree;
        let (a, b) = (nurbs.knots[k], nurbs.knots[k + 1]);
        // The span's Bézier control points are the blossom of the piece at (a, …, a, b, …, b):
        // i copies of b for the i-th. De Boor's algorithm with a parameter of its own at each
        // level computes exactly the blossom.
        let mut bezier = [[0.0f64; 3]; MAX_DEGREE + 1];
        for (i, point) in bezier.iter_mut().enumerate().take(p + 1) {
            *point = blossom(nurbs, k, |level| if level <= i { b } else { a });
        }
        // Bézier to power form: c_j = C(p, j) Σ_{i ≤ j} (−1)^(j−i) C(j, i) B_i.
        let mut coefficients = [[0.0f64; 3]; MAX_DEGREE + 1];
        for (j, c) in coefficients.iter_mut().enumerate().take(p + 1) {
            for (i, point) in bezier.iter().enumerate().take(j + 1) {
                let sign = if (j - i) % 2 == 0 { 1.0 } else { -1.0 };
                let f = sign * binomial(j, i);
                for (cv, bv) in c.iter_mut().zip(point) {
                    *cv += f * bv;
                }
            }
            let f = binomial(p, j);
            for cv in c.iter_mut() {
                *cv *= f;
            }
        }
        let rational = coefficients[0][2] != 1.0 || coefficients[1..=p].iter().any(|c| c[2] != 0.0);
        SpanPolynomial {
            degree: p,
            start: a,
            rate: 1.0 / (b - a),
            coefficients,
            rational,
        }
    }

    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> Point {
        let s = (t - self.start) * self.rate;
        let c = &self.coefficients;
        if !self.rational {
            // With w = 1 exactly, n · (1 / w) is n exactly: the same point as below.
            let (mut x, mut y) = (c[self.degree][0], c[self.degree][1]);
            for cj in c[..self.degree].iter().rev() {
                x = x * s + cj[0];
                y = y * s + cj[1];
            }
            return Point::new(x, y);
        }
        let mut n = c[self.degree];
        for cj in c[..self.degree].iter().rev() {
            for (nv, cv) in n.iter_mut().zip(cj) {
                *nv = *nv * s + cv;
            }
        }
        let w = 1.0 / n[2];
        Point::new(n[0] * w, n[1] * w)
    }

    /// The point at parameter `t` with the curve's first and second derivatives there (with
    /// respect to `t`).
    pub fn derivatives(&self, t: f64) -> (Point, Vector, Vector) {
        let s = (t - self.start) * self.rate;
        let c = &self.coefficients;
        // Horner's rule for the value, the first derivative and half the second at once.
        let mut n = c[self.degree];
        let mut n1 = [0.0f64; 3];
        let mut n2 = [0.0f64; 3];
        for cj in c[..self.degree].iter().rev() {
            for v in 0..3 {
                n2[v] = n2[v] * s + n1[v];
                n1[v] = n1[v] * s + n[v];
                n[v] = n[v] * s + cj[v];
            }
        }
        let w = n[2];
        let (w1, w2) = (n1[2], 2.0 * n2[2]);
        let p = Vector::new(n[0] / w, n[1] / w);
        // The quotient rule for (x·w, y·w) / w.
        let d1 = (Vector::new(n1[0], n1[1]) - p * w1) / w;
        let d2 = (Vector::new(2.0 * n2[0], 2.0 * n2[1]) - d1 * (2.0 * w1) - p * w2) / w;
        (Point::new(p.x, p.y), d1 * self.rate, d2 * (self.rate * self.rate))
    }
}

/// Consecutive knot spans of a NURBS joined where the curve is at least tangent-continuous
/// (an inner knot of multiplicity below the degree), evaluated as one curve: the curve fitting
/// then places its arcs by the curve's shape, not by where the knots fall, and a run of short
/// spans takes as few arcs as its shape needs.
///
/// ```
/// use pocketeer::geom::Point;
/// use pocketeer::import::curve::Nurbs;
/// use pocketeer::import::span_polynomial::SpanRun;
/// let pts = [Point::new(0.0, 0.0), Point::new(1.0, 2.0), Point::new(3.0, 3.0), Point::new(4.0, 0.0), Point::new(6.0, 1.0)];
/// let s = Nurbs::through(&pts).unwrap();
/// let runs = SpanRun::runs(&s);
/// assert_eq!(runs.len(), 1); // a cubic through points is smooth at every inner knot
/// let (a, b) = runs[0].domain();
/// for i in 0..=10 {
///     let t = a + (b - a) * i as f64 / 10.0;
///     assert!(runs[0].point(t).distance(s.point(t)) < 1e-12);
/// }
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpanRun {
    /// The spans' first parameters, increasing.
    starts: Vec<f64>,
    /// The last span's end.
    end: f64,
    /// One polynomial per span.
    pieces: Vec<SpanPolynomial>,
    /// The span the last evaluation fell in: the fitting evaluates along the curve, so the
    /// next one almost always falls in it too.
    last: Cell<usize>,
}

impl SpanRun {
    /// The curve's spans grouped into runs, in order: a new run starts at a knot where the
    /// curve may turn a corner or jump (multiplicity at least the degree), and at every knot
    /// of a degree-1 spline.
    pub fn runs(nurbs: &Nurbs) -> Vec<SpanRun> {
        let mut runs: Vec<SpanRun> = Vec::new();
        for (k, a, b) in nurbs.spans() {
            // The knots do not decrease (the reader refuses others), and knots[k + 1] > a:
            // the copies of a end at k.
            let multiplicity = nurbs.knots[..=k].iter().rev().take_while(|&&u| u == a).count();
            let smooth = multiplicity < nurbs.degree;
            let piece = SpanPolynomial::new(nurbs, k);
            match runs.last_mut() {
                Some(run) if smooth && run.end == a => {
                    run.starts.push(a);
                    run.pieces.push(piece);
                    run.end = b;
                }
                _ => runs.push(SpanRun {
                    starts: vec![a],
                    end: b,
                    pieces: vec![piece],
                    last: Cell::new(0),
                }),
            }
        }
        runs
    }

    /// The first and last parameter.
    pub fn domain(&self) -> (f64, f64) {
        (self.starts[0], self.end)
    }

    /// The span holding `t` (the first or last one beyond the domain).
    fn piece(&self, t: f64) -> &SpanPolynomial {
        let holds =
            |k: usize| self.starts[k] <= t && t < self.starts.get(k + 1).copied().unwrap_or(f64::INFINITY);
        let last = self.last.get();
        // The span of the last evaluation or its neighbour: a try's samples step along the
        // curve in short steps, backwards only when they start over.
        let k = if holds(last) {
            last
        } else {
            let k = if last + 1 < self.starts.len() && holds(last + 1) {
                last + 1
            } else {
                self.starts.partition_point(|&s| s <= t).saturating_sub(1)
            };
            self.last.set(k);
            k
        };
        &self.pieces[k]
    }

    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> Point {
        self.piece(t).point(t)
    }

    /// The point at parameter `t` with the first and second derivatives there.
    pub fn derivatives(&self, t: f64) -> (Point, Vector, Vector) {
        self.piece(t).derivatives(t)
    }
}

/// The blossom of the homogeneous piece of `nurbs` on span `k` at the parameters
/// `param(1), …, param(degree)`: de Boor's algorithm with a parameter for each level (the
/// point at t is the blossom at t, …, t).
pub(super) fn blossom(nurbs: &Nurbs, k: usize, param: impl Fn(usize) -> f64) -> [f64; 3] {
    let p = nurbs.degree;
    let mut d = [[0.0f64; 3]; MAX_DEGREE + 1];
    for (j, dj) in d.iter_mut().enumerate().take(p + 1) {
        let i = k + j - p;
        let w = nurbs.weights[i];
        *dj = [nurbs.points[i].x * w, nurbs.points[i].y * w, w];
    }
    for r in 1..=p {
        let t = param(r);
        for j in (r..=p).rev() {
            let i = k + j - p;
            let denom = nurbs.knots[i + p + 1 - r] - nurbs.knots[i];
            let alpha = if denom == 0.0 {
                0.0
            } else {
                (t - nurbs.knots[i]) / denom
            };
            let prev = d[j - 1];
            for (c, v) in d[j].iter_mut().enumerate() {
                *v = (1.0 - alpha) * prev[c] + alpha * *v;
            }
        }
    }
    d[p]
}

/// The binomial coefficient C(n, k), exactly for the small n of spline degrees.
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn spline(degree: usize, points: Vec<(f64, f64)>, weights: Vec<f64>, gaps: Vec<f64>) -> Nurbs {
        let n = points.len();
        let mut knots = Vec::with_capacity(n + degree + 1);
        let mut u = 0.0;
        for g in gaps.iter().take(n + degree + 1) {
            knots.push(u);
            u += g;
        }
        Nurbs {
            degree,
            knots,
            points: points.into_iter().map(|(x, y)| Point::new(x, y)).collect(),
            weights: weights.into_iter().take(n).collect(),
        }
    }

    fn arb_spline() -> impl Strategy<Value = Nurbs> {
        (1usize..=5).prop_flat_map(|degree| {
            (degree + 1..degree + 8).prop_flat_map(move |n| {
                (
                    prop::collection::vec((-100.0..100.0f64, -100.0..100.0f64), n),
                    // Every weight 1 (a plain B-spline, evaluated without dividing) or not.
                    prop_oneof![Just(vec![1.0; n]), prop::collection::vec(0.2..5.0f64, n)],
                    // Zero gaps give repeated knots.
                    prop::collection::vec(prop_oneof![Just(0.0), 0.1..3.0f64], n + degree + 1),
                )
                    .prop_map(move |(p, w, g)| spline(degree, p, w, g))
            })
        })
    }

    proptest! {
        /// The power form agrees with de Boor's algorithm on every span, and its derivatives
        /// with central differences of itself.
        #[test]
        fn the_power_form_is_the_span_de_boor_evaluates(s in arb_spline(), f in 0.0..1.0f64) {
            for (k, a, b) in s.spans() {
                let poly = SpanPolynomial::new(&s, k);
                let t = a + (b - a) * f;
                let scale = 1.0 + s.point_in_span(k, t).to_vector().length();
                prop_assert!(poly.point(t).distance(s.point_in_span(k, t)) <= 1e-9 * scale);
                let (p, d1, d2) = poly.derivatives(t);
                prop_assert!(p.distance(poly.point(t)) <= 1e-9 * scale);
                let h = (b - a) * 1e-5;
                let (pm, pp) = (poly.derivatives(t - h), poly.derivatives(t + h));
                let fd1 = (pp.0 - pm.0) / (2.0 * h);
                let fd2 = (pp.1 - pm.1) / (2.0 * h);
                let size1 = 1.0 + d1.length() + fd1.length();
                let size2 = 1.0 + d2.length() + fd2.length();
                prop_assert!((d1 - fd1).length() <= 1e-4 * size1, "{d1:?} {fd1:?}");
                prop_assert!((d2 - fd2).length() <= 1e-4 * size2, "{d2:?} {fd2:?}");
            }
        }
    }

    #[test]
    fn a_quarter_circle_as_a_rational_quadratic_has_unit_speed_times_its_radius_squared() {
        // The rational quadratic with weights 1, √½, 1 is exactly a quarter of the unit circle.
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let s = Nurbs {
            degree: 2,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points: vec![Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)],
            weights: vec![1.0, r, 1.0],
        };
        let poly = SpanPolynomial::new(&s, 2);
        assert!(poly.rational);
        for i in 0..=10 {
            assert!((poly.point(i as f64 / 10.0).to_vector().length() - 1.0).abs() < 1e-12);
            let (p, d1, _) = poly.derivatives(i as f64 / 10.0);
            assert!((p.to_vector().length() - 1.0).abs() < 1e-12);
            // The tangent is perpendicular to the radius.
            assert!(p.to_vector().dot(d1).abs() < 1e-12);
        }
    }

    #[test]
    fn a_spline_with_every_weight_one_is_evaluated_without_its_weights() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(3.0, 3.0),
            Point::new(4.0, 0.0),
        ];
        let s = Nurbs::through(&pts).expect("distinct points");
        for (k, a, b) in s.spans() {
            let poly = SpanPolynomial::new(&s, k);
            assert!(!poly.rational);
            let t = 0.5 * (a + b);
            assert!(poly.point(t).distance(s.point_in_span(k, t)) < 1e-12);
            assert_eq!(poly.point(t), poly.derivatives(t).0);
        }
    }
}
