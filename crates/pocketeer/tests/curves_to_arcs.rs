//! Splines and ellipses become arcs that stay within 0.001 mm of the true curve, both ways:
//! every curve point is near an arc, and every arc point is near the curve.

use pocketeer::geom::{distance_from_segment, Point, Segment, Vector};
use pocketeer::import::curve::{Curve, EllipseArc, Nurbs};
use pocketeer::import::CURVE_TOLERANCE;
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Distance from `q` to the curve `eval`: the samples' least, refined in every step between
/// samples that may come within the tolerance, on which the curve lies within about a chord of
/// its ends. (Refining only around the samples nearest `q` misses a cusp: the curve passes
/// `q`, turns on the spot and comes back within one step, its nearest sample two steps off.)
/// Missing the nearest point could only overstate the distance, failing the test, never
/// passing it wrongly.
fn distance_to_curve(q: Point, samples: &[(f64, Point)], eval: &dyn Fn(f64) -> Point) -> f64 {
    let d: Vec<f64> = samples.iter().map(|s| s.1.distance(q)).collect();
    let mut best = d.iter().copied().fold(f64::INFINITY, f64::min);
    for (i, w) in samples.windows(2).enumerate() {
        let chord = w[0].1.distance(w[1].1);
        if d[i].min(d[i + 1]) - 2.0 * chord <= CURVE_TOLERANCE {
            best = best.min(nearest_between(q, w[0].0, w[1].0, eval));
        }
    }
    best
}

/// The least distance from `q` to the curve between parameters `lo` and `hi`: the interval is
/// sampled finely and narrowed around its nearest sample, again and again. (Near a cusp the
/// curve passes `q` twice within one sample step: a search assuming one minimum there may
/// settle on the farther.)
fn nearest_between(q: Point, mut lo: f64, mut hi: f64, eval: &dyn Fn(f64) -> Point) -> f64 {
    const PARTS: usize = 16;
    let mut best = f64::INFINITY;
    for _ in 0..10 {
        let at = |k: usize| lo + (hi - lo) * k as f64 / PARTS as f64;
        let (k, d) = (0..=PARTS)
            .map(|k| (k, eval(at(k)).distance(q)))
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap_or((0, f64::INFINITY));
        best = best.min(d);
        (lo, hi) = (at(k.saturating_sub(1)), at((k + 1).min(PARTS)));
    }
    best
}

/// Checks the arcs of `curve` against `eval` from `t0` to `t1`; `corners` are the parameters
/// where the curve may turn a corner, sampled besides the even spread.
fn check(
    curve: &Curve,
    t0: f64,
    t1: f64,
    corners: &[f64],
    eval: &dyn Fn(f64) -> Point,
) -> Result<(), TestCaseError> {
    let mut segs: Vec<Segment> = Vec::new();
    curve.to_segments(CURVE_TOLERANCE, &mut segs);
    prop_assert!(!segs.is_empty());
    prop_assert!(segs.len() < 400, "{} pieces", segs.len());
    for w in segs.windows(2) {
        prop_assert!(w[0].end().distance(w[1].start()) < 1e-6, "pieces do not join");
    }
    let mut params: Vec<f64> = (0..=2000).map(|i| t0 + (t1 - t0) * i as f64 / 2000.0).collect();
    params.extend(corners.iter().filter(|&&t| t > t0 && t < t1));
    params.sort_by(f64::total_cmp);
    params.dedup();
    let samples: Vec<(f64, Point)> = params.into_iter().map(|t| (t, eval(t))).collect();
    for &(_, p) in &samples {
        let d = segs
            .iter()
            .map(|s| distance_from_segment(s, p))
            .fold(f64::INFINITY, f64::min);
        prop_assert!(d <= CURVE_TOLERANCE, "curve point {p:?} is {d} from the arcs");
    }
    for s in &segs {
        for k in 0..=8 {
            let q = s.point_at(k as f64 / 8.0);
            let d = distance_to_curve(q, &samples, eval);
            prop_assert!(d <= CURVE_TOLERANCE, "arc point {q:?} is {d} from the curve");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn cubic_splines(pts in prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 4..9)) {
        let n = pts.len();
        let degree = 3;
        let mut knots = vec![0.0; degree + 1];
        for k in 1..n - degree {
            knots.push(k as f64);
        }
        knots.extend(vec![(n - degree) as f64; degree + 1]);
        let s = Nurbs { degree, knots, points: pts.iter().map(|&(x, y)| Point::new(x, y)).collect(), weights: vec![1.0; n] };
        let end = (n - degree) as f64;
        check(&Curve::Spline(s.clone()), 0.0, end, &[], &|t| s.point(t))?;
    }

    /// Rational splines of degree 1 to 5 with knots repeated up to the degree: the fit runs
    /// across the knots where the curve is smooth and stops at the corners.
    #[test]
    fn rational_splines_with_repeated_knots(
        degree in 1usize..=5,
        pts in prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64, 0.3..3.0f64), 6..12),
        repeats in prop::collection::vec(1usize..=5, 12),
    ) {
        let n = pts.len();
        prop_assume!(n > degree);
        // Inner knots 1, 2, … each repeated up to the degree, clamped ends.
        let mut knots = vec![0.0; degree + 1];
        let mut value = 0.0;
        let mut r = repeats.iter().cycle();
        while knots.len() < n {
            value += 1.0;
            let times = (*r.next().unwrap_or(&1)).min(degree).min(n - knots.len());
            knots.extend(std::iter::repeat_n(value, times));
        }
        value += 1.0;
        knots.extend(vec![value; degree + 1]);
        let s = Nurbs {
            degree,
            knots,
            points: pts.iter().map(|&(x, y, _)| Point::new(x, y)).collect(),
            weights: pts.iter().map(|&(_, _, w)| w).collect(),
        };
        let corners: Vec<f64> = (1..value as usize).map(|k| k as f64).collect();
        check(&Curve::Spline(s.clone()), 0.0, value, &corners, &|t| s.point(t))?;
    }

    #[test]
    fn ellipse_arcs(a in 1.0..80.0f64, ratio in 0.05..1.0f64, rot in -3.0..3.0f64, t0 in 0.0..TAU, sweep in 0.2..TAU) {
        let u = Vector::from_angle(rot) * a;
        let v = Vector::from_angle(rot).perp() * (a * ratio);
        let e = EllipseArc { center: Point::new(3.0, -7.0), u, v, t0, sweep };
        check(&Curve::Ellipse(e), t0, t0 + sweep, &[], &|t| e.point(t))?;
    }
}
