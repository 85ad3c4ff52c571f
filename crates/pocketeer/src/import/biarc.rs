//! Approximation of smooth curves (ellipses, splines) by biarcs: pairs of tangent-continuous
//! circular arcs, subdivided until every sampled curve point is within the tolerance.

use super::biarc_piece::Piece;
use crate::geom::{Line, Point, Segment, Vector};

/// Number of curve samples checked against each biarc.
const SAMPLES: usize = 24;
/// The samples must lie this much closer than the tolerance, so that the curve between them
/// stays within it too.
const MARGIN: f64 = 0.8;
/// Points of each arc checked against the curve.
const ARC_PROBES: usize = 6;
/// The shortest piece is 2^-24 of the curve's parameter range, far beyond any drawing.
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
///
/// The pieces are laid one after the other from `t0`, each as long as fits: a biarc's error
/// grows with the cube of its length, so the error a try measures sets the length of the next
/// try. Pieces come out close to the tolerance (halving a failed piece left most of them at an
/// eighth to a half of it, and twice as many), with about two failed tries for five pieces (on
/// the relief drawing of `bench --bin splines`: 363 659 tries for 519 450 arcs and lines).
pub fn fit(curve: &impl SmoothCurve, t0: f64, t1: f64, tolerance: f64, out: &mut Vec<Segment>) {
    let range = t1 - t0;
    if range == 0.0 || !range.is_finite() {
        return;
    }
    let target = tolerance * MARGIN;
    let shortest = range.abs() * 0.5f64.powi(MAX_DEPTH as i32);
    let (mut t, mut step) = (t0, range);
    let (mut p, mut d, _) = curve.derivatives(t0);
    while (t1 - t) * range.signum() > 0.0 {
        let left = t1 - t;
        // A try reaching nearly to the end takes the rest: no sliver is left behind. (Below
        // 1 / 0.8, the most a failed try shrinks by, so that the try after it is shorter.)
        let e = if step.abs() * 1.2 >= left.abs() {
            t1
        } else {
            t + step
        };
        let tried = e - t;
        let (q, dq, _) = curve.derivatives(e);
        // Twice the shortest: t + step - t may round a little above it.
        let at_floor = tried.abs() <= 2.0 * shortest;
        if p.distance(q) <= tolerance * 1e-6 && (at_floor || negligible(curve, t, e, p, tolerance)) {
            // A negligible piece: the chain closes the gap within the join tolerance.
            (t, p, d) = (e, q, dq);
            continue;
        }
        // Going from t to e the curve heads along its derivative, or against it where e < t
        // (a clockwise elliptical arc): with the tangents reversed no biarc fits, and every
        // piece was cut down to the shortest, 16 million lines for one arc.
        let candidate = match (
            heading(curve, t, e, p, d),
            heading(curve, e, t, q, dq).map(|v| -v),
        ) {
            (Some(a), Some(b)) => biarc_pieces(p, a, q, b),
            _ => None,
        };
        let error = candidate
            .as_ref()
            .map_or(f64::INFINITY, |b| deviation(curve, t, e, b.pieces(), target));
        match candidate {
            Some(biarc) if at_floor || error <= target => {
                out.extend(biarc.pieces().iter().map(Piece::segment));
                (t, p, d) = (e, q, dq);
                step = tried * next_length(error, target).clamp(0.7, 3.0);
            }
            None if at_floor => {
                out.push(Segment::Line(Line::new(p, q)));
                (t, p, d) = (e, q, dq);
            }
            _ => {
                let shorter = tried * next_length(error, target).clamp(0.15, 0.8);
                step = if shorter.abs() < shortest {
                    shortest * range.signum()
                } else {
                    shorter
                };
            }
        }
    }
}

/// The share of a piece's length at which a biarc's error, growing with the cube of the
/// length, would be 90 % of the target; half the length where the error is unknown.
fn next_length(error: f64, target: f64) -> f64 {
    if !error.is_finite() {
        0.5
    } else if error <= 0.0 {
        f64::INFINITY
    } else {
        0.9 * (target / error).cbrt()
    }
}

/// True when the curve from `t0` to `t1`, whose ends lie together at `p`, stays within a
/// millionth of the tolerance of `p` (a degenerate span, not a closed loop).
fn negligible(curve: &impl SmoothCurve, t0: f64, t1: f64, p: Point, tolerance: f64) -> bool {
    (1..4).all(|k| curve.point(t0 + (t1 - t0) * k as f64 / 4.0).distance(p) <= tolerance * 1e-6)
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

/// The points dividing the piece `s` into `ARC_PROBES` equal parts, ends excluded (round an
/// arc by rotation: one sine and cosine for all of them).
fn probes(s: Segment) -> impl Iterator<Item = Point> {
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

/// How far the curve from `t0` to `t1` and the biarc lie apart: the largest distance of a
/// curve sample from the biarc when that is within `limit` and every point of the biarc is
/// within `limit` of the curve, else an estimate above `limit`. The samples first: most failed
/// fits fail there, and their distances say by how much.
///
/// The other way round, from the biarc to the curve, follows from the samples where they
/// project onto the pieces in order, each step forward by a short turn (see
/// [`Piece::steps_forward`]): the curve then crosses every radius of an arc (every normal of a
/// line) near where the samples lie. Where they do not, points along the biarc are projected on
/// the curve one by one (an arc may swing out and back between samples near it).
fn deviation(curve: &impl SmoothCurve, t0: f64, t1: f64, pieces: &[Piece], limit: f64) -> f64 {
    let last = pieces.len() - 1;
    // The ends are the biarc's own ends: no distance to measure.
    let mut samples = [(0.0, Point::ORIGIN); SAMPLES + 1];
    samples[0] = (t0, pieces[0].start());
    samples[SAMPLES] = (t1, pieces[last].end());
    // The piece each sample projects onto, if any.
    let mut onto = [None; SAMPLES + 1];
    (onto[0], onto[SAMPLES]) = (Some(0), Some(last));
    let mut worst = 0.0f64;
    // A point near the biarc projects onto the piece on its side of the normal at the
    // junction; the other piece is measured only where it does not.
    let junction = pieces[0].end();
    let along = pieces[0].end_tangent();
    let step = (t1 - t0) / SAMPLES as f64;
    for (n, &i) in SAMPLE_ORDER.iter().enumerate() {
        let t = t0 + step * i as f64;
        let p = curve.point(t);
        samples[i] = (t, p);
        let guess = usize::from((p - junction).dot(along) > 0.0).min(last);
        let (distance, piece) = match pieces[guess].projected_distance(p) {
            Some(d) => (d, Some(guess)),
            None => nearest_piece(pieces, p),
        };
        onto[i] = piece;
        worst = worst.max(distance);
        // A try that fails on the coarse samples fails at once: their worst says by how much.
        if worst > limit && n + 1 >= COARSE_SAMPLES {
            return worst;
        }
    }
    if worst > limit || in_order(pieces, &samples, &onto, 0.25 * limit) {
        return worst;
    }
    let mut nearest = 0;
    let probes_near = pieces.iter().flat_map(|piece| probes(piece.segment())).all(|q| {
        nearest = nearest_sample(&samples, q, nearest);
        is_near_curve(curve, &samples, nearest, q, limit)
    });
    if probes_near {
        worst
    } else {
        1.3 * limit
    }
}

/// The distance from `p` to the nearest of `pieces`, and that piece where `p` projects onto it.
fn nearest_piece(pieces: &[Piece], p: Point) -> (f64, Option<usize>) {
    let mut best = (f64::INFINITY, None);
    for (k, piece) in pieces.iter().enumerate() {
        let (d, onto) = match piece.projected_distance(p) {
            Some(d) => (d, Some(k)),
            None => (piece.distance(p), None),
        };
        if d < best.0 {
            best = (d, onto);
        }
    }
    best
}

/// True when the samples that project onto a piece go along the pieces from the first one's
/// start to the last one's end, each step forward and turning so little that an arc strays at
/// most `sag` from the chord of the step.
fn in_order(pieces: &[Piece], samples: &[(f64, Point)], onto: &[Option<usize>], sag: f64) -> bool {
    let (mut k, mut at) = (0, pieces[0].start());
    let ends = onto
        .iter()
        .zip(samples)
        .filter_map(|(piece, s)| piece.map(|k| (k, s.1)))
        .chain(std::iter::once((
            pieces.len() - 1,
            pieces[pieces.len() - 1].end(),
        )));
    for (next, p) in ends {
        if next < k {
            return false;
        }
        // Onto the next piece: along this one to its end first.
        while k < next {
            if !pieces[k].steps_forward(at, pieces[k].end(), sag) {
                return false;
            }
            (k, at) = (k + 1, pieces[k + 1].start());
        }
        if !pieces[k].steps_forward(at, p, sag) {
            return false;
        }
        at = p;
    }
    true
}

/// The order the samples between the ends are taken in: every third first, so that the first
/// [`COARSE_SAMPLES`] are spread evenly over the piece, then the rest; each group along the
/// curve, so that consecutive samples mostly fall in the same knot span.
const SAMPLE_ORDER: [usize; SAMPLES - 1] = [
    3, 6, 9, 12, 15, 18, 21, 1, 2, 4, 5, 7, 8, 10, 11, 13, 14, 16, 17, 19, 20, 22, 23,
];
/// The samples after which a try that is already off fails.
const COARSE_SAMPLES: usize = 7;

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
///
/// ```
/// use pocketeer::geom::{Point, Vector};
/// use pocketeer::import::biarc::biarc;
/// // From heading east at the origin to heading north at (10, 3): two arcs turning left.
/// let [first, second] = biarc(Point::ORIGIN, Vector::new(1.0, 0.0), Point::new(10.0, 3.0), Vector::new(0.0, 1.0)).unwrap();
/// assert_eq!(first.unwrap().start(), Point::ORIGIN);
/// assert_eq!(second.unwrap().end(), Point::new(10.0, 3.0));
/// ```
pub fn biarc(p0: Point, t0: Vector, p1: Point, t1: Vector) -> Option<[Option<Segment>; 2]> {
    let b = biarc_pieces(p0, t0, p1, t1)?;
    let mut pieces = b.pieces().iter().map(Piece::segment);
    Some([pieces.next(), pieces.next()])
}

/// The one or two pieces of a biarc.
#[derive(Debug, Clone, Copy)]
struct Biarc {
    list: [Piece; 2],
    count: usize,
}

impl Biarc {
    /// A biarc of one piece (a line, or one of its arcs empty).
    fn one(piece: Piece) -> Biarc {
        Biarc {
            list: [piece; 2],
            count: 1,
        }
    }

    fn pieces(&self) -> &[Piece] {
        &self.list[..self.count]
    }
}

/// [`biarc`] as the fit tries it: pieces not yet made segments.
fn biarc_pieces(p0: Point, t0: Vector, p1: Point, t1: Vector) -> Option<Biarc> {
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
            let line = Piece::Line { start: p0, end: p1 };
            return Some(Biarc::one(line));
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
    let first = arc_from_tangent(p0, t0, j)?;
    let second = arc_from_tangent(p1, -t1, j)?.reversed();
    Some(match (first.is_empty(), second.is_empty()) {
        (false, false) => Biarc {
            list: [first, second],
            count: 2,
        },
        (true, false) => Biarc::one(second),
        (false, true) => Biarc::one(first),
        (true, true) => return None,
    })
}

/// The arc (or line) that leaves `p` along unit tangent `t` and ends at `q`.
fn arc_from_tangent(p: Point, t: Vector, q: Point) -> Option<Piece> {
    let w = q - p;
    let ww = w.length_sq();
    if ww == 0.0 {
        return Some(Piece::Line { start: p, end: q });
    }
    let n = t.perp();
    let nw = n.dot(w);
    // Signed distance from p to the centre along n.
    let s = ww / (2.0 * nw);
    // Distance of the arc from its chord, roughly: a flatter arc is a line.
    let sagitta = 0.5 * nw.abs();
    if !s.is_finite() || sagitta < super::curve::FLAT_ARC {
        return (w.dot(t) > 0.0).then_some(Piece::Line { start: p, end: q });
    }
    let center = p + n * s;
    Some(Piece::Arc {
        center,
        radius: s.abs(),
        start: p,
        end: q,
        ccw: s > 0.0,
    })
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
    fn every_sample_is_taken_once_and_the_coarse_ones_spread_evenly() {
        // The ends (0 and SAMPLES) are the biarc's own; every sample between, once.
        let mut order = SAMPLE_ORDER;
        order.sort_unstable();
        assert!(order.iter().enumerate().all(|(i, &k)| i + 1 == k));
        let mut coarse = SAMPLE_ORDER[..COARSE_SAMPLES].to_vec();
        coarse.sort_unstable();
        assert_eq!(coarse, [3, 6, 9, 12, 15, 18, 21]);
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
