//! Approximation of smooth curves (ellipses, splines) by biarcs: pairs of tangent-continuous
//! circular arcs, subdivided until every sampled curve point is within the tolerance.

use crate::geom::distance::{in_sweep, line_point_distance};
use crate::geom::{Arc, Line, Point, Segment, Vector};

/// Number of curve samples checked against each biarc.
const SAMPLES: usize = 24;
/// The samples must lie this much closer than the tolerance, so that the curve between them
/// stays within it too.
const MARGIN: f64 = 0.8;
/// Points of each arc checked against the curve.
const ARC_PROBES: usize = 6;
/// Subdivision depth limit: 2^24 pieces is far beyond any drawing.
const MAX_DEPTH: u32 = 24;
/// Newton steps at most when projecting a point on the curve: it converges in three or four.
const NEWTON_STEPS: usize = 12;

/// A smooth curve to fit, by its point and its first two derivatives at a parameter.
pub trait SmoothCurve {
    /// The point at `t`.
    fn point(&self, t: f64) -> Point;
    /// The point at `t` and the first and second derivatives with respect to `t` there.
    fn derivatives(&self, t: f64) -> (Point, Vector, Vector);
}

/// Appends to `out` lines and arcs that follow `curve` from `t0` to `t1` within `tolerance`.
pub fn fit(curve: &impl SmoothCurve, t0: f64, t1: f64, tolerance: f64, out: &mut Vec<Segment>) {
    fit_rec(curve, t0, t1, tolerance, 0, out);
}

fn fit_rec(curve: &impl SmoothCurve, t0: f64, t1: f64, tol: f64, depth: u32, out: &mut Vec<Segment>) {
    let (p0, d0, _) = curve.derivatives(t0);
    let (p1, d1, _) = curve.derivatives(t1);
    if p0.distance(p1) <= tol * 1e-6 {
        return; // a negligible piece: the chain closes the gap within the join tolerance
    }
    // Going from t0 to t1 the curve heads along its derivative, or against it where t1 < t0
    // (a clockwise elliptical arc): with the tangents reversed no biarc fits, and every piece
    // was halved down to MAX_DEPTH, 16 million lines for one arc.
    let candidate = match (
        heading(curve, t0, t1, p0, d0),
        heading(curve, t1, t0, p1, d1).map(|v| -v),
    ) {
        (Some(a), Some(b)) => biarc(p0, a, p1, b),
        _ => None,
    };
    let target = tol * MARGIN;
    let fits = candidate
        .as_ref()
        .is_some_and(|pieces| follows(curve, t0, t1, pieces, target));
    match candidate {
        Some(pieces) if depth >= MAX_DEPTH || fits => out.extend(pieces.iter().flatten().copied()),
        None if depth >= MAX_DEPTH => out.push(Segment::Line(Line::new(p0, p1))),
        _ => {
            // Halving: where the first try failed, the error is rarely spread evenly enough for
            // a finer even split to pay off (measured on ellipses and splines).
            let mid = 0.5 * (t0 + t1);
            fit_rec(curve, t0, mid, tol, depth + 1, out);
            fit_rec(curve, mid, t1, tol, depth + 1, out);
        }
    }
}

/// The unit direction in which the curve leaves `t` towards `toward`: its derivative, or where
/// that vanishes (control points repeated at a spline's end), the chord to a point a little way
/// on, widened until the curve visibly moves.
fn heading(curve: &impl SmoothCurve, t: f64, toward: f64, p: Point, d: Vector) -> Option<Vector> {
    let span = toward - t;
    let scale = 1.0 + p.to_vector().length();
    if d.length() * span.abs() > 1e-10 * scale {
        return (d * span.signum()).normalized();
    }
    [1e-7, 1e-5, 1e-3, 1e-2].into_iter().find_map(|rel| {
        let q = curve.point(t + span * rel);
        (q.distance(p) > 1e-12 * scale)
            .then(|| (q - p).normalized())
            .flatten()
    })
}

/// True when `q` is within `limit` of the piece `s` of a biarc (sign tests against an arc's
/// stored ends, squared distances).
fn is_near(s: &Segment, q: Point, limit: f64) -> bool {
    match s {
        Segment::Line(l) => line_point_distance(l, q) <= limit,
        Segment::Arc(a) => {
            let v = q - a.center();
            let (start, end) = (a.start(), a.end());
            if in_sweep(a.sweep(), start - a.center(), end - a.center(), v) {
                // | |v| − r | ≤ limit without the square root.
                let (lo, hi) = ((a.radius() - limit).max(0.0), a.radius() + limit);
                let vv = v.length_sq();
                vv <= hi * hi && vv >= lo * lo
            } else {
                let ll = limit * limit;
                start.distance_sq(q) <= ll || end.distance_sq(q) <= ll
            }
        }
    }
}

/// The points dividing the piece `s` into `ARC_PROBES` equal parts, ends excluded (round an
/// arc by rotation: one sine and cosine for all of them).
fn probes(s: &Segment) -> impl Iterator<Item = Point> + '_ {
    let (start, end) = (s.start(), s.end());
    let (center, step) = match s {
        Segment::Arc(a) => (a.center(), a.sweep() / ARC_PROBES as f64),
        Segment::Line(_) => (start, 0.0),
    };
    let (sin, cos) = step.sin_cos();
    let mut radial = start - center;
    (1..ARC_PROBES).map(move |k| match s {
        Segment::Line(_) => start + (end - start) * (k as f64 / ARC_PROBES as f64),
        Segment::Arc(_) => {
            radial = Vector::new(cos * radial.x - sin * radial.y, sin * radial.x + cos * radial.y);
            center + radial
        }
    })
}

/// True when the curve from `t0` to `t1` and the biarc are within `limit` of each other, both
/// ways: every curve sample near the biarc, and every probe of the biarc near the curve (an
/// arc may swing out and back between samples near it). The cheaper way first: most failed
/// fits fail there.
fn follows(curve: &impl SmoothCurve, t0: f64, t1: f64, pieces: &[Option<Segment>; 2], limit: f64) -> bool {
    let pieces: Vec<&Segment> = pieces.iter().flatten().collect();
    let mut samples = [(0.0, Point::ORIGIN); SAMPLES + 1];
    for (i, s) in samples.iter_mut().enumerate() {
        let t = t0 + (t1 - t0) * i as f64 / SAMPLES as f64;
        *s = (t, curve.point(t));
    }
    // The piece the previous sample was near is the likeliest for the next.
    let mut near = 0;
    for &(_, p) in &samples {
        match (0..pieces.len())
            .map(|k| (near + k) % pieces.len())
            .find(|&k| is_near(pieces[k], p, limit))
        {
            Some(k) => near = k,
            None => return false,
        }
    }
    let mut nearest = 0;
    pieces.iter().flat_map(|&piece| probes(piece)).all(|q| {
        nearest = nearest_sample(&samples, q, nearest);
        is_near_curve(curve, &samples, nearest, q, limit)
    })
}

/// The sample nearest to `q` walking from sample `from` while they come nearer: the probes
/// follow the samples in order, so the walk is short. (A farther local minimum only makes the
/// projection below start worse; the distance it finds is never understated.)
fn nearest_sample(samples: &[(f64, Point)], q: Point, from: usize) -> usize {
    let d = |i: usize| samples[i].1.distance_sq(q);
    let mut i = from.min(samples.len() - 1);
    while i + 1 < samples.len() && d(i + 1) <= d(i) {
        i += 1;
    }
    while i > 0 && d(i - 1) < d(i) {
        i -= 1;
    }
    i
}

/// True when `q` is within `limit` of the curve near sample `i` (parameter, point): Newton's
/// method on the squared distance between the neighbouring samples, bisecting where a step
/// would leave them, stopping at the first curve point within the limit.
fn is_near_curve(curve: &impl SmoothCurve, samples: &[(f64, Point)], i: usize, q: Point, limit: f64) -> bool {
    let ll = limit * limit;
    if samples[i].1.distance_sq(q) <= ll {
        return true;
    }
    let (ta, tb) = (
        samples[i.saturating_sub(1)].0,
        samples[(i + 1).min(samples.len() - 1)].0,
    );
    let (mut lo, mut hi) = (ta.min(tb), ta.max(tb));
    let mut t = samples[i].0;
    for _ in 0..NEWTON_STEPS {
        let (p, d1, d2) = curve.derivatives(t);
        let r = p - q;
        if r.length_sq() <= ll {
            return true;
        }
        // g is half the derivative of the squared distance, h half its second derivative.
        let g = r.dot(d1);
        let h = d1.length_sq() + r.dot(d2);
        if g > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        let newton = t - g / h;
        let next = if h > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - t).abs() <= 1e-12 * (1.0 + t.abs()) || hi - lo <= 1e-12 * (1.0 + t.abs()) {
            break;
        }
        t = next;
    }
    false
}

/// The equal-tangent-length biarc from `p0` (unit tangent `t0`) to `p1` (unit tangent `t1`):
/// its one or two pieces, a piece of zero length left out.
pub fn biarc(p0: Point, t0: Vector, p1: Point, t1: Vector) -> Option<[Option<Segment>; 2]> {
    let v = p1 - p0;
    let vv = v.length_sq();
    if vv == 0.0 {
        return None;
    }
    let t = t0 + t1;
    let denom = 2.0 * (1.0 - t0.dot(t1));
    let d = if denom.abs() < 1e-12 {
        // Parallel end tangents: a straight piece, or the symmetric S-curve.
        if v.cross(t0).abs() <= 1e-12 * vv.sqrt() && v.dot(t0) > 0.0 {
            return Some([Some(Segment::Line(Line::new(p0, p1))), None]);
        }
        let vt = v.dot(t1);
        if vt.abs() < 1e-300 {
            return None;
        }
        vv / (4.0 * vt)
    } else {
        let vt = v.dot(t);
        (-vt + (vt * vt + denom * vv).sqrt()) / denom
    };
    if d.is_nan() || d <= 0.0 || !d.is_finite() {
        return None;
    }
    let j = Point::new(
        0.5 * (p0.x + p1.x + d * (t0.x - t1.x)),
        0.5 * (p0.y + p1.y + d * (t0.y - t1.y)),
    );
    // The arcs keep p0, j and p1 as their ends (see `Arc::from_center`).
    let piece = |segment: Segment| (segment.length() > 0.0).then_some(segment);
    let first = arc_from_tangent(p0, t0, j)?;
    let second = arc_from_tangent(p1, -t1, j)?.reversed();
    Some([piece(first), piece(second)])
}

/// The arc (or line) that leaves `p` along unit tangent `t` and ends at `q`.
fn arc_from_tangent(p: Point, t: Vector, q: Point) -> Option<Segment> {
    let w = q - p;
    let ww = w.length_sq();
    if ww == 0.0 {
        return Some(Segment::Line(Line::new(p, q)));
    }
    let n = t.perp();
    let nw = n.dot(w);
    // Signed distance from p to the centre along n.
    let s = ww / (2.0 * nw);
    // Distance of the arc from its chord, roughly: a flatter arc is a line.
    let sagitta = 0.5 * nw.abs();
    if !s.is_finite() || sagitta < super::curve::FLAT_ARC {
        return (w.dot(t) > 0.0).then_some(Segment::Line(Line::new(p, q)));
    }
    let center = p + n * s;
    Some(Segment::Arc(Arc::from_center(center, p, q, s > 0.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::distance_from_segment;
    use crate::import::curve::EllipseArc;

    /// The ellipse x = a·cos t, y = b·sin t.
    fn ellipse(a: f64, b: f64) -> EllipseArc {
        EllipseArc {
            center: Point::ORIGIN,
            u: Vector::new(a, 0.0),
            v: Vector::new(0.0, b),
            t0: 0.0,
            sweep: std::f64::consts::TAU,
        }
    }

    #[test]
    fn a_biarc_is_tangent_at_both_ends() {
        let (p0, t0) = (Point::new(0.0, 0.0), Vector::new(1.0, 0.0));
        let (p1, t1) = (Point::new(10.0, 3.0), Vector::new(0.0, 1.0));
        let pieces = biarc(p0, t0, p1, t1).unwrap();
        let segs: Vec<Segment> = pieces.iter().flatten().copied().collect();
        assert_eq!(segs.len(), 2);
        // The pieces keep the points they were made through as their ends.
        assert!(segs[0].start().distance(p0) < 1e-12 && segs[1].end().distance(p1) < 1e-12);
        assert!(segs[0].end().distance(segs[1].start()) < 1e-12);
        assert!(segs[0].start().distance(p0) < 1e-9 && segs[1].end().distance(p1) < 1e-9);
        assert!(segs[0].end().distance(segs[1].start()) < 1e-9);
        assert!((segs[0].tangent_at(0.0) - t0).length() < 1e-9);
        assert!((segs[1].tangent_at(1.0) - t1).length() < 1e-9);
        assert!((segs[0].tangent_at(1.0) - segs[1].tangent_at(0.0)).length() < 1e-9);
    }

    #[test]
    fn an_ellipse_arc_run_backwards_fits_in_a_few_arcs() {
        // A clockwise elliptical arc (t decreasing), as a polyline's negative bulge seen in a
        // tilted plane gives: a fit that mistook the direction would subdivide without end.
        let ellipse = ellipse(7.3, 6.9);
        let (t0, t1) = (-1.45, -1.45 - 0.103);
        let mut out = Vec::new();
        fit(&ellipse, t0, t1, 0.001, &mut out);
        assert!(!out.is_empty() && out.len() <= 4, "{} pieces", out.len());
        assert!(out[0].start().distance(ellipse.point(t0)) < 1e-9);
        assert!(out[out.len() - 1].end().distance(ellipse.point(t1)) < 1e-9);
        for i in 0..=100 {
            let p = ellipse.point(t0 + (t1 - t0) * i as f64 / 100.0);
            let d = out
                .iter()
                .map(|s| distance_from_segment(s, p))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.001, "{d}");
        }
    }

    #[test]
    fn an_ellipse_quarter_fits_within_tolerance() {
        let ellipse = ellipse(30.0, 10.0);
        let mut out = Vec::new();
        fit(&ellipse, 0.0, std::f64::consts::FRAC_PI_2, 0.001, &mut out);
        assert!(out.iter().all(|s| matches!(s, Segment::Arc(_))));
        assert!(out.len() < 40, "{} arcs", out.len());
        for i in 0..=1000 {
            let p = ellipse.point(i as f64 / 1000.0 * std::f64::consts::FRAC_PI_2);
            let d = out
                .iter()
                .map(|s| distance_from_segment(s, p))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.001, "deviation {d}");
        }
    }
}
