//! Approximation of smooth curves (ellipses, splines) by biarcs: pairs of tangent-continuous
//! circular arcs, subdivided until every sampled curve point is within the tolerance.

use crate::geom::{distance_from_segment, Arc, Line, Point, Segment, Vector};

/// Number of curve samples checked against each biarc.
const SAMPLES: usize = 24;
/// The samples must lie this much closer than the tolerance, so that the curve between them
/// stays within it too.
const MARGIN: f64 = 0.8;
/// Points of each arc checked against the curve.
const ARC_PROBES: usize = 6;
/// Subdivision depth limit: 2^24 pieces is far beyond any drawing.
const MAX_DEPTH: u32 = 24;

/// A curve to fit: its point at a parameter, and its point with its derivative (dearer: only
/// the ends of each piece need it).
pub struct Curve<'a> {
    /// The point at `t`.
    pub point: &'a dyn Fn(f64) -> Point,
    /// The point and the derivative at `t`.
    pub with_derivative: &'a dyn Fn(f64) -> (Point, Vector),
}

/// Appends to `out` lines and arcs that follow `curve` from `t0` to `t1` within `tolerance`.
pub fn fit(curve: &Curve, t0: f64, t1: f64, tolerance: f64, out: &mut Vec<Segment>) {
    fit_rec(curve, t0, t1, tolerance, 0, out);
}

fn fit_rec(curve: &Curve, t0: f64, t1: f64, tol: f64, depth: u32, out: &mut Vec<Segment>) {
    let (p0, d0) = (curve.with_derivative)(t0);
    let (p1, d1) = (curve.with_derivative)(t1);
    if p0.distance(p1) <= tol * 1e-6 {
        return; // a negligible piece: the chain closes the gap within the join tolerance
    }
    // Going from t0 to t1 the curve heads along its derivative, or against it where t1 < t0
    // (a clockwise elliptical arc): with the tangents reversed no biarc fits, and every piece
    // was halved down to MAX_DEPTH, 16 million lines for one arc.
    let ahead = if t1 >= t0 { 1.0 } else { -1.0 };
    let candidate = match ((d0 * ahead).normalized(), (d1 * ahead).normalized()) {
        (Some(a), Some(b)) => biarc(p0, a, p1, b),
        _ => None,
    };
    let target = tol * MARGIN;
    // Largest distance between the curve and the arcs, both ways: every curve sample near an arc,
    // and every arc near the curve (an arc may swing out and back between samples near it). The
    // cheaper way first: most failed fits fail there.
    let deviation = |segs: &[Segment]| {
        let samples: Vec<(f64, Point)> = (0..=SAMPLES)
            .map(|i| t0 + (t1 - t0) * i as f64 / SAMPLES as f64)
            .map(|t| (t, (curve.point)(t)))
            .collect();
        let curve_to_arcs = samples
            .iter()
            .map(|&(_, p)| {
                segs.iter()
                    .map(|s| distance_from_segment(s, p))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        if curve_to_arcs > target {
            return curve_to_arcs;
        }
        let arcs_to_curve = segs
            .iter()
            .flat_map(|s| (1..ARC_PROBES).map(move |k| s.point_at(k as f64 / ARC_PROBES as f64)))
            .map(|q| distance_to_curve(curve.point, &samples, q))
            .fold(0.0, f64::max);
        curve_to_arcs.max(arcs_to_curve)
    };
    let error = candidate.as_ref().map_or(f64::INFINITY, |segs| deviation(segs));
    match candidate {
        Some(segs) if depth >= MAX_DEPTH || error <= target => out.extend(segs),
        None if depth >= MAX_DEPTH => out.push(Segment::Line(Line::new(p0, p1))),
        _ => {
            // Halving: where the first try failed, the error is rarely spread evenly enough for
            // a finer even split to pay off (measured on ellipses and splines).
            let pieces = 2;
            for i in 0..pieces {
                let a = t0 + (t1 - t0) * i as f64 / pieces as f64;
                let b = t0 + (t1 - t0) * (i + 1) as f64 / pieces as f64;
                fit_rec(curve, a, b, tol, depth + 1, out);
            }
        }
    }
}

/// Distance from `q` to the curve near the closest of its `samples` (parameter, point): a
/// golden-section search between the neighbouring samples, to a ten-thousandth of their
/// spacing (the distance is flat at its minimum: its error is the square of that, relative).
fn distance_to_curve(point: &dyn Fn(f64) -> Point, samples: &[(f64, Point)], q: Point) -> f64 {
    let Some(i) = (0..samples.len()).min_by(|&a, &b| {
        samples[a]
            .1
            .distance_sq(q)
            .total_cmp(&samples[b].1.distance_sq(q))
    }) else {
        return f64::INFINITY;
    };
    let (mut lo, mut hi) = (
        samples[i.saturating_sub(1)].0,
        samples[(i + 1).min(samples.len() - 1)].0,
    );
    let dist = |t: f64| point(t).distance(q);
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let (mut a, mut b) = (hi - INV_PHI * (hi - lo), lo + INV_PHI * (hi - lo));
    let (mut fa, mut fb) = (dist(a), dist(b));
    for _ in 0..20 {
        if fa < fb {
            hi = b;
            b = a;
            fb = fa;
            a = hi - INV_PHI * (hi - lo);
            fa = dist(a);
        } else {
            lo = a;
            a = b;
            fa = fb;
            b = lo + INV_PHI * (hi - lo);
            fb = dist(b);
        }
    }
    fa.min(fb).min(samples[i].1.distance(q))
}

/// The equal-tangent-length biarc from `p0` (unit tangent `t0`) to `p1` (unit tangent `t1`).
pub fn biarc(p0: Point, t0: Vector, p1: Point, t1: Vector) -> Option<Vec<Segment>> {
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
            return Some(vec![Segment::Line(Line::new(p0, p1))]);
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
    let first = arc_from_tangent(p0, t0, j)?;
    let second = arc_from_tangent(p1, -t1, j)?.reversed();
    Some([first, second].into_iter().filter(|s| s.length() > 0.0).collect())
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

    #[test]
    fn a_biarc_is_tangent_at_both_ends() {
        let (p0, t0) = (Point::new(0.0, 0.0), Vector::new(1.0, 0.0));
        let (p1, t1) = (Point::new(10.0, 3.0), Vector::new(0.0, 1.0));
        let segs = biarc(p0, t0, p1, t1).unwrap();
        assert_eq!(segs.len(), 2);
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
        let eval = |t: f64| {
            (
                Point::new(7.3 * t.cos(), 6.9 * t.sin()),
                Vector::new(-7.3 * t.sin(), 6.9 * t.cos()),
            )
        };
        let (t0, t1) = (-1.45, -1.45 - 0.103);
        let mut out = Vec::new();
        fit(
            &Curve {
                point: &|t| eval(t).0,
                with_derivative: &eval,
            },
            t0,
            t1,
            0.001,
            &mut out,
        );
        assert!(!out.is_empty() && out.len() <= 4, "{} pieces", out.len());
        assert!(out[0].start().distance(eval(t0).0) < 1e-9);
        assert!(out[out.len() - 1].end().distance(eval(t1).0) < 1e-9);
        for i in 0..=100 {
            let p = eval(t0 + (t1 - t0) * i as f64 / 100.0).0;
            let d = out
                .iter()
                .map(|s| distance_from_segment(s, p))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.001, "{d}");
        }
    }

    #[test]
    fn an_ellipse_quarter_fits_within_tolerance() {
        let eval = |t: f64| {
            (
                Point::new(30.0 * t.cos(), 10.0 * t.sin()),
                Vector::new(-30.0 * t.sin(), 10.0 * t.cos()),
            )
        };
        let mut out = Vec::new();
        fit(
            &Curve {
                point: &|t| eval(t).0,
                with_derivative: &eval,
            },
            0.0,
            std::f64::consts::FRAC_PI_2,
            0.001,
            &mut out,
        );
        assert!(out.iter().all(|s| matches!(s, Segment::Arc(_))));
        assert!(out.len() < 40, "{} arcs", out.len());
        for i in 0..=1000 {
            let p = eval(i as f64 / 1000.0 * std::f64::consts::FRAC_PI_2).0;
            let d = out
                .iter()
                .map(|s| distance_from_segment(s, p))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.001, "deviation {d}");
        }
    }
}
