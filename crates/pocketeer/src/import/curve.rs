//! The curves a DXF entity can describe, before they become lines and arcs: lines, elliptical
//! arcs in conjugate form (circles and circular arcs included), and NURBS. All of them map exactly
//! under the affine transforms of block insertion and object coordinate systems.

use super::biarc::SmoothCurve;
use super::span_polynomial::SpanRun;
use crate::geom::{Arc, Line, Point, Segment, Vector};

/// An arc that strays less than this from its chord (mm) is a line: huge radii only cost
/// precision in every later computation.
pub const FLAT_ARC: f64 = 1e-7;

/// A 2D affine map: `x' = a·x + b·y + e`, `y' = c·x + d·y + f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Linear part, first row.
    pub a: f64,
    /// Linear part, first row.
    pub b: f64,
    /// Linear part, second row.
    pub c: f64,
    /// Linear part, second row.
    pub d: f64,
    /// Translation x.
    pub e: f64,
    /// Translation y.
    pub f: f64,
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        a: 1.0,
        b: 0.0,
        c: 0.0,
        d: 1.0,
        e: 0.0,
        f: 0.0,
    };

    /// Uniform scale about the origin.
    pub fn scale(s: f64) -> Affine {
        Affine::scale_xy(s, s)
    }

    /// Scale by `sx`, `sy` about the origin.
    pub fn scale_xy(sx: f64, sy: f64) -> Affine {
        Affine {
            a: sx,
            d: sy,
            ..Affine::IDENTITY
        }
    }

    /// Translation by `v`.
    pub fn translate(v: Vector) -> Affine {
        Affine {
            e: v.x,
            f: v.y,
            ..Affine::IDENTITY
        }
    }

    /// Rotation by `angle` radians about the origin.
    pub fn rotate(angle: f64) -> Affine {
        let (s, c) = angle.sin_cos();
        Affine {
            a: c,
            b: -s,
            c: s,
            d: c,
            e: 0.0,
            f: 0.0,
        }
    }

    /// The map that applies `inner` first, then `self`.
    pub fn then(&self, inner: &Affine) -> Affine {
        let o = self;
        Affine {
            a: o.a * inner.a + o.b * inner.c,
            b: o.a * inner.b + o.b * inner.d,
            c: o.c * inner.a + o.d * inner.c,
            d: o.c * inner.b + o.d * inner.d,
            e: o.a * inner.e + o.b * inner.f + o.e,
            f: o.c * inner.e + o.d * inner.f + o.f,
        }
    }

    /// Image of a point.
    pub fn point(&self, p: Point) -> Point {
        Point::new(
            self.a * p.x + self.b * p.y + self.e,
            self.c * p.x + self.d * p.y + self.f,
        )
    }

    /// Image of a vector (translation ignored).
    pub fn vector(&self, v: Vector) -> Vector {
        Vector::new(self.a * v.x + self.b * v.y, self.c * v.x + self.d * v.y)
    }

    /// Determinant of the linear part: negative for a mirroring map.
    pub fn det(&self) -> f64 {
        self.a * self.d - self.b * self.c
    }

    /// The scale factor when the map keeps shapes (a rotation or mirroring, a uniform scale and
    /// a translation): circles stay circles. `None` for any other map.
    ///
    /// ```
    /// use pocketeer::import::curve::Affine;
    /// assert_eq!(Affine::scale(25.4).similarity(), Some(25.4));
    /// assert_eq!(Affine::scale_xy(1.0, -1.0).similarity(), Some(1.0));
    /// assert_eq!(Affine::scale_xy(2.0, 1.0).similarity(), None);
    /// ```
    pub fn similarity(&self) -> Option<f64> {
        let turning = self.a == self.d && self.b == -self.c;
        let mirroring = self.a == -self.d && self.b == self.c;
        let scale = (self.a * self.a + self.c * self.c).sqrt();
        ((turning || mirroring) && scale > 0.0 && scale.is_finite()).then_some(scale)
    }
}

/// The map from an entity's object coordinate system (normal `n`, elevation `z`) to world XY,
/// by DXF's arbitrary-axis algorithm followed by projection on the XY plane.
pub fn ocs_to_world(n: [f64; 3], elevation: f64) -> Affine {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len.is_nan() || len <= 0.0 || !len.is_finite() {
        return Affine::IDENTITY;
    }
    let n = [n[0] / len, n[1] / len, n[2] / len];
    if n[0] == 0.0 && n[1] == 0.0 && n[2] > 0.0 {
        return Affine::IDENTITY;
    }
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let ax = if n[0].abs() < 1.0 / 64.0 && n[1].abs() < 1.0 / 64.0 {
        unit(cross([0.0, 1.0, 0.0], n))
    } else {
        unit(cross([0.0, 0.0, 1.0], n))
    };
    let ay = unit(cross(n, ax));
    Affine {
        a: ax[0],
        b: ay[0],
        c: ax[1],
        d: ay[1],
        e: n[0] * elevation,
        f: n[1] * elevation,
    }
}

/// An elliptical arc in conjugate form: `P(t) = center + u·cos t + v·sin t` for t from `t0` to
/// `t0 + sweep`. A circle has |u| = |v| and u ⊥ v.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseArc {
    /// Centre.
    pub center: Point,
    /// Point at t = 0, relative to the centre.
    pub u: Vector,
    /// Point at t = π/2, relative to the centre.
    pub v: Vector,
    /// First parameter.
    pub t0: f64,
    /// Signed parameter sweep.
    pub sweep: f64,
}

impl EllipseArc {
    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> Point {
        let (s, c) = t.sin_cos();
        self.center + self.u * c + self.v * s
    }

    /// The derivative at parameter `t`.
    pub fn derivative(&self, t: f64) -> Vector {
        let (s, c) = t.sin_cos();
        self.v * c - self.u * s
    }

    /// The exact circular arc when this is one.
    pub fn as_circular(&self) -> Option<Arc> {
        let (lu, lv) = (self.u.length(), self.v.length());
        if lu == 0.0 || lv == 0.0 {
            return None;
        }
        let round = (lu - lv).abs() <= 1e-10 * lu && self.u.dot(self.v).abs() <= 1e-10 * lu * lv;
        if !round {
            return None;
        }
        let ccw = self.u.cross(self.v) > 0.0;
        let base = self.u.angle();
        let (start, sweep) = if ccw {
            (base + self.t0, self.sweep)
        } else {
            (base - self.t0, -self.sweep)
        };
        Some(Arc::new(self.center, 0.5 * (lu + lv), start, sweep))
    }

    /// The circular arc `arc` in conjugate form.
    pub fn of_arc(arc: &Arc) -> EllipseArc {
        let r = arc.radius();
        EllipseArc {
            center: arc.center(),
            u: Vector::new(r, 0.0),
            v: Vector::new(0.0, r),
            t0: arc.start_angle(),
            sweep: arc.sweep(),
        }
    }

    /// The image under `m`.
    pub fn transformed(&self, m: &Affine) -> EllipseArc {
        EllipseArc {
            center: m.point(self.center),
            u: m.vector(self.u),
            v: m.vector(self.v),
            ..*self
        }
    }
}

impl SmoothCurve for EllipseArc {
    fn point(&self, t: f64) -> Point {
        EllipseArc::point(self, t)
    }

    fn derivatives(&self, t: f64) -> (Point, Vector, Vector) {
        let (s, c) = t.sin_cos();
        let radial = self.u * c + self.v * s;
        (self.center + radial, self.v * c - self.u * s, -radial)
    }
}

impl SmoothCurve for SpanRun {
    fn point(&self, t: f64) -> Point {
        SpanRun::point(self, t)
    }

    fn derivatives(&self, t: f64) -> (Point, Vector, Vector) {
        SpanRun::derivatives(self, t)
    }
}

/// Highest spline degree read.
pub const MAX_DEGREE: usize = 11;

/// A non-uniform rational B-spline (degree at most [`MAX_DEGREE`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    /// Degree (1 = polyline, 3 = the usual cubic).
    pub degree: usize,
    /// Knot vector: control points + degree + 1 values, non-decreasing.
    pub knots: Vec<f64>,
    /// Control points.
    pub points: Vec<Point>,
    /// Weights, one per control point.
    pub weights: Vec<f64>,
}

impl Nurbs {
    /// The non-empty knot spans of the curve's domain: `(k, knots[k], knots[k + 1])`.
    pub fn spans(&self) -> Vec<(usize, f64, f64)> {
        let (p, n) = (self.degree, self.points.len());
        (p..n)
            .map(|k| (k, self.knots[k], self.knots[k + 1]))
            .filter(|(_, a, b)| b > a)
            .collect()
    }

    /// The cubic (or lower degree, for fewer points) B-spline through `points`, parameterised
    /// by chord length with averaged knots: the curve a CAD program draws through a spline's
    /// fit points. `None` for fewer than two distinct points.
    ///
    /// ```
    /// use pocketeer::geom::Point;
    /// use pocketeer::import::curve::Nurbs;
    /// let pts = [Point::new(0.0, 0.0), Point::new(1.0, 2.0), Point::new(3.0, 3.0), Point::new(4.0, 0.0), Point::new(6.0, 1.0)];
    /// let s = Nurbs::through(&pts).unwrap();
    /// assert_eq!(s.degree, 3);
    /// assert!(s.point(0.0).distance(pts[0]) < 1e-9 && s.point(1.0).distance(pts[4]) < 1e-9);
    /// ```
    pub fn through(points: &[Point]) -> Option<Nurbs> {
        let mut q: Vec<Point> = Vec::with_capacity(points.len());
        for &p in points {
            if q.last().is_none_or(|l: &Point| l.distance(p) > 0.0) {
                q.push(p);
            }
        }
        if q.len() < 2 {
            return None;
        }
        let n = q.len() - 1;
        let p = n.min(3);
        // Chord-length parameters.
        let total: f64 = q.windows(2).map(|w| w[0].distance(w[1])).sum();
        let mut u = vec![0.0; n + 1];
        for k in 1..=n {
            u[k] = u[k - 1] + q[k - 1].distance(q[k]) / total;
        }
        u[n] = 1.0;
        // Averaged knots.
        let mut knots = vec![0.0; p + 1];
        for j in 1..=n - p {
            knots.push(u[j..j + p].iter().sum::<f64>() / p as f64);
        }
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        let mut curve = Nurbs {
            degree: p,
            knots,
            points: vec![Point::ORIGIN; n + 1],
            weights: vec![1.0; n + 1],
        };
        // Row k of the collocation matrix holds the p + 1 basis functions that are non-zero at
        // u[k]; the matrix is banded and totally positive, so elimination needs no pivoting.
        let rows: Vec<(usize, Vec<f64>)> = u.iter().map(|&t| curve.basis(t)).collect();
        let x = solve_banded(&rows, &q.iter().map(|p| p.x).collect::<Vec<_>>())?;
        let y = solve_banded(&rows, &q.iter().map(|p| p.y).collect::<Vec<_>>())?;
        curve.points = x.into_iter().zip(y).map(|(x, y)| Point::new(x, y)).collect();
        Some(curve)
    }

    /// The first index `i` and the values of the basis functions N(i..=i+p) at `t`.
    fn basis(&self, t: f64) -> (usize, Vec<f64>) {
        let p = self.degree;
        let n = self.points.len();
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= t {
            k += 1;
        }
        let u = &self.knots;
        // Cox–de Boor, triangular form.
        let mut nv = vec![0.0; p + 1];
        nv[0] = 1.0;
        let mut left = vec![0.0; p + 1];
        let mut right = vec![0.0; p + 1];
        for j in 1..=p {
            left[j] = t - u[k + 1 - j];
            right[j] = u[k + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let denom = right[r + 1] + left[j - r];
                let temp = if denom == 0.0 { 0.0 } else { nv[r] / denom };
                nv[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            nv[j] = saved;
        }
        (k - p, nv)
    }

    /// The point at parameter `t` of the curve's domain (at a knot, the piece that starts there).
    pub fn point(&self, t: f64) -> Point {
        let spans = self.spans();
        let k = spans
            .iter()
            .rev()
            .find(|s| s.1 <= t)
            .or(spans.first())
            .map_or(self.degree, |s| s.0);
        self.point_in_span(k, t)
    }

    /// True when the curve ends where it starts, to within a millionth of a unit (writers
    /// print closed splines' wrapped control points to their precision).
    pub fn is_closed(&self) -> bool {
        let (Some(&t0), Some(&t1)) = (self.knots.get(self.degree), self.knots.get(self.points.len())) else {
            return false;
        };
        self.point(t0).distance(self.point(t1)) <= 1e-6
    }

    /// The point at `t` of the polynomial piece on span `k` (de Boor's algorithm). Evaluating
    /// on an explicit span keeps both ends of a span on that span's piece, which matters where
    /// a knot of full multiplicity lets the curve jump.
    pub fn point_in_span(&self, k: usize, t: f64) -> Point {
        // The point is the blossom at (t, …, t).
        let [x, y, w] = super::span_polynomial::blossom(self, k, |_| t);
        Point::new(x / w, y / w)
    }

    /// The image under `m` (B-splines are affinely invariant: map the control points).
    pub fn transformed(&self, m: &Affine) -> Nurbs {
        Nurbs {
            points: self.points.iter().map(|&p| m.point(p)).collect(),
            ..self.clone()
        }
    }
}

/// Any curve an entity describes.
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// A straight line.
    Line(Point, Point),
    /// A circular arc through given ends (a polyline's bulge): kept exact, ends included, as
    /// long as the maps it goes through keep circles.
    Arc(Arc),
    /// An elliptical or circular arc.
    Ellipse(EllipseArc),
    /// A spline.
    Spline(Nurbs),
}

impl Curve {
    /// The image under `m`.
    pub fn transformed(&self, m: &Affine) -> Curve {
        match self {
            Curve::Line(a, b) => Curve::Line(m.point(*a), m.point(*b)),
            Curve::Arc(arc) => match m.similarity() {
                Some(scale) => {
                    let center = m.point(arc.center());
                    let (start, end) = (m.point(arc.start()), m.point(arc.end()));
                    let keeps_angles = m.b == 0.0 && m.c == 0.0 && m.a > 0.0;
                    let (start_angle, sweep) = if keeps_angles {
                        (arc.start_angle(), arc.sweep())
                    } else {
                        ((start - center).angle(), arc.sweep() * m.det().signum())
                    };
                    Curve::Arc(Arc::with_ends(
                        center,
                        arc.radius() * scale,
                        start_angle,
                        sweep,
                        start,
                        end,
                    ))
                }
                None => Curve::Ellipse(EllipseArc::of_arc(arc).transformed(m)),
            },
            Curve::Ellipse(e) => Curve::Ellipse(e.transformed(m)),
            Curve::Spline(s) => Curve::Spline(s.transformed(m)),
        }
    }

    /// True when every number defining the curve is finite and within `limit` of the origin.
    pub fn check_coordinates(&self, limit: f64) -> Result<(), Point> {
        let ok = |p: Point| p.is_finite() && p.x.abs() <= limit && p.y.abs() <= limit;
        let bad = match self {
            Curve::Line(a, b) => [*a, *b].into_iter().find(|p| !ok(*p)),
            Curve::Arc(arc) => [arc.center(), arc.start(), arc.end()]
                .into_iter()
                .find(|p| !ok(*p))
                .or_else(|| {
                    let defined =
                        arc.radius().is_finite() && arc.start_angle().is_finite() && arc.sweep().is_finite();
                    (!defined).then_some(arc.center())
                }),
            Curve::Ellipse(e) => {
                let pts = [e.center, e.center + e.u, e.center + e.v];
                pts.into_iter()
                    .find(|p| !ok(*p))
                    .or_else(|| (!(e.t0.is_finite() && e.sweep.is_finite())).then_some(e.center))
            }
            Curve::Spline(s) => s.points.iter().copied().find(|p| !ok(*p)),
        };
        bad.map_or(Ok(()), Err)
    }

    /// The curve as its one line or arc, when it is one (an arc that strays less than
    /// [`FLAT_ARC`] from its chord is a line); `None` for an ellipse or a spline, which
    /// [`Curve::to_segments`] fits with biarcs.
    pub fn exact(&self) -> Option<Segment> {
        let arc = match self {
            Curve::Line(a, b) => return Some(Segment::Line(Line::new(*a, *b))),
            Curve::Arc(arc) => *arc,
            Curve::Ellipse(e) => e.as_circular()?,
            Curve::Spline(_) => return None,
        };
        Some(if arc.sagitta() < FLAT_ARC && !arc.is_full_circle() {
            Segment::Line(Line::new(arc.start(), arc.end()))
        } else {
            Segment::Arc(arc)
        })
    }

    /// The curve as exact lines and arcs: lines and circular arcs as they are, ellipses and
    /// splines as biarcs within `tolerance`.
    pub fn to_segments(&self, tolerance: f64, out: &mut Vec<Segment>) {
        if let Some(segment) = self.exact() {
            out.push(segment);
            return;
        }
        match self {
            Curve::Ellipse(e) => {
                // Split at quarter turns so that no piece holds an inflection of its tangent.
                let pieces = (e.sweep.abs() / (std::f64::consts::PI / 2.0)).ceil().max(1.0) as usize;
                for i in 0..pieces {
                    let a = e.t0 + e.sweep * i as f64 / pieces as f64;
                    let b = e.t0 + e.sweep * (i + 1) as f64 / pieces as f64;
                    super::biarc::fit(e, a, b, tolerance, out);
                }
            }
            Curve::Spline(s) => {
                for run in SpanRun::runs(s) {
                    let (a, b) = run.domain();
                    super::biarc::fit(&run, a, b, tolerance, out);
                }
            }
            Curve::Line(..) | Curve::Arc(_) => {}
        }
    }
}

/// Solves `A x = b` for a square matrix whose row `k` is `rows[k].1` starting at column
/// `rows[k].0`, by band elimination without pivoting. `None` for a singular system.
fn solve_banded(rows: &[(usize, Vec<f64>)], b: &[f64]) -> Option<Vec<f64>> {
    let n = rows.len();
    let kl = rows
        .iter()
        .enumerate()
        .map(|(k, (c, _))| k.saturating_sub(*c))
        .max()
        .unwrap_or(0);
    let ku = rows
        .iter()
        .enumerate()
        .map(|(k, (c, v))| (c + v.len()).saturating_sub(k + 1))
        .max()
        .unwrap_or(0);
    let width = kl + ku + 1;
    // band[k][j - k + kl] = A[k][j]; fill-in stays inside the band without pivoting.
    let mut band = vec![vec![0.0; width]; n];
    for (k, (c, v)) in rows.iter().enumerate() {
        for (o, &a) in v.iter().enumerate() {
            let j = c + o;
            if j < n && j + kl >= k && j <= k + ku {
                band[k][j + kl - k] = a;
            }
        }
    }
    let mut rhs = b.to_vec();
    for k in 0..n {
        let pivot = band[k][kl];
        if pivot.abs() < 1e-14 {
            return None;
        }
        for i in k + 1..n.min(k + kl + 1) {
            let factor = band[i][k + kl - i] / pivot;
            if factor == 0.0 {
                continue;
            }
            for j in k..n.min(k + ku + 1) {
                band[i][j + kl - i] -= factor * band[k][j + kl - k];
            }
            rhs[i] -= factor * rhs[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let mut s = rhs[k];
        for j in k + 1..n.min(k + ku + 1) {
            s -= band[k][j + kl - k] * x[j];
        }
        x[k] = s / band[k][kl];
    }
    Some(x)
}
