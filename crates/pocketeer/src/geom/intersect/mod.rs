//! Intersections of lines and arcs: crossings, tangencies and overlapping spans.
//!
//! Every test is in vector form (no slopes), and every "equal" or "on" decision uses the
//! geometric epsilon `eps` in millimetres, so vertical lines and tiny or huge coordinates are
//! treated alike.

use super::{closest_param, distance_from_segment, Arc, Line, Point, Segment};
use std::f64::consts::TAU;

/// One place where two segments meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Intersection {
    /// The segments meet at one point (crossing or touching), at parameter `ta` on the first
    /// and `tb` on the second.
    Point {
        /// Where they meet.
        point: Point,
        /// Parameter on the first segment.
        ta: f64,
        /// Parameter on the second segment.
        tb: f64,
    },
    /// The segments share a span of positive length (collinear lines or co-circular arcs):
    /// `a` = (t0, t1) with t0 < t1 on the first segment, `b` = the parameters of the same two
    /// points on the second (decreasing when the second runs the other way).
    Overlap {
        /// Parameter range on the first segment.
        a: (f64, f64),
        /// Parameters of the same points on the second segment.
        b: (f64, f64),
    },
}

impl Intersection {
    /// The same intersection seen from the other segment.
    pub fn swapped(self) -> Intersection {
        match self {
            Intersection::Point { point, ta, tb } => Intersection::Point {
                point,
                ta: tb,
                tb: ta,
            },
            Intersection::Overlap { a, b } => {
                if b.0 <= b.1 {
                    Intersection::Overlap { a: b, b: a }
                } else {
                    Intersection::Overlap {
                        a: (b.1, b.0),
                        b: (a.1, a.0),
                    }
                }
            }
        }
    }
}

/// At most three intersections, stored inline: two segments of these kinds never meet more often.
#[derive(Debug, Clone, Copy, Default)]
pub struct Intersections {
    items: [Option<Intersection>; 3],
    len: usize,
}

impl Intersections {
    fn push(&mut self, i: Intersection) {
        if self.len < self.items.len() {
            self.items[self.len] = Some(i);
            self.len += 1;
        }
    }

    /// Number of intersections.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the segments do not meet.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The intersections in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = Intersection> + '_ {
        self.items[..self.len].iter().flatten().copied()
    }

    fn swapped(self) -> Intersections {
        let mut out = Intersections::default();
        for i in self.iter() {
            out.push(i.swapped());
        }
        out
    }
}

/// All intersections of `a` and `b`, parameters given on each.
///
/// ```
/// use pocketeer::geom::{intersect, Intersection, Line, Point, Segment};
/// let a = Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(2.0, 2.0)));
/// let b = Segment::Line(Line::new(Point::new(0.0, 2.0), Point::new(2.0, 0.0)));
/// let hits = intersect(&a, &b, 1e-9);
/// assert_eq!(hits.len(), 1);
/// match hits.iter().next().unwrap() {
///     Intersection::Point { point, ta, tb } => {
///         assert!(point.distance(Point::new(1.0, 1.0)) < 1e-12);
///         assert!((ta - 0.5).abs() < 1e-12 && (tb - 0.5).abs() < 1e-12);
///     }
///     _ => unreachable!(),
/// };
/// ```
pub fn intersect(a: &Segment, b: &Segment, eps: f64) -> Intersections {
    match (a, b) {
        (Segment::Line(l1), Segment::Line(l2)) => line_line(l1, l2, eps),
        (Segment::Line(l), Segment::Arc(c)) => line_arc(l, c, eps),
        (Segment::Arc(c), Segment::Line(l)) => line_arc(l, c, eps).swapped(),
        (Segment::Arc(c1), Segment::Arc(c2)) => arc_arc(c1, c2, eps),
    }
}

fn clamp01(t: f64) -> f64 {
    t.clamp(0.0, 1.0)
}

/// Intersections of two lines.
pub fn line_line(l1: &Line, l2: &Line, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    let (len1, len2) = (l1.length(), l2.length());
    if len1 <= eps || len2 <= eps {
        // A degenerate line is a point: it meets the other where it lies on it.
        let (p, other, p_on_first) = if len1 <= len2 {
            (l1.start.midpoint(l1.end), l2, true)
        } else {
            (l2.start.midpoint(l2.end), l1, false)
        };
        let t = clamp01(other.param_of(p));
        if other.point_at(t).distance(p) <= eps {
            let (ta, tb) = if p_on_first { (0.0, t) } else { (t, 0.0) };
            out.push(Intersection::Point { point: p, ta, tb });
        }
        return out;
    }
    // Signed distances of each line's ends from the other line.
    let hc = l1.signed_distance(l2.start);
    let hd = l1.signed_distance(l2.end);
    let ha = l2.signed_distance(l1.start);
    let hb = l2.signed_distance(l1.end);
    let collinear = (hc.abs() <= eps && hd.abs() <= eps) || (ha.abs() <= eps && hb.abs() <= eps);
    if collinear {
        return collinear_lines(l1, l2, len1, eps);
    }
    if (hc > eps && hd > eps)
        || (hc < -eps && hd < -eps)
        || (ha > eps && hb > eps)
        || (ha < -eps && hb < -eps)
    {
        return out;
    }
    // An end of one line that lies on the other (within eps), meeting it where it projects:
    // lines meeting at a small angle can have an end within eps of the other line far from
    // where their carriers cross (h / sin of the angle), beyond the end. Failing that, the
    // crossing of the carriers.
    let end_on = |h0: f64, h1: f64| {
        if h0.abs() <= eps {
            Some(0.0)
        } else if h1.abs() <= eps {
            Some(1.0)
        } else {
            None
        }
    };
    let crossing = |h0: f64, h1: f64| clamp01(h0 / (h0 - h1));
    let candidates = [
        end_on(ha, hb).map(|t| (t, clamp01(l2.param_of(l1.point_at(t))))),
        end_on(hc, hd).map(|u| (clamp01(l1.param_of(l2.point_at(u))), u)),
        Some((crossing(ha, hb), crossing(hc, hd))),
    ];
    for (t, u) in candidates.into_iter().flatten() {
        let pa = l1.point_at(t);
        let pb = l2.point_at(u);
        if pa.distance(pb) <= 2.0 * eps {
            out.push(Intersection::Point {
                point: pa.midpoint(pb),
                ta: t,
                tb: u,
            });
            break;
        }
    }
    out
}

fn collinear_lines(l1: &Line, l2: &Line, len1: f64, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    let tc = l1.param_of(l2.start);
    let td = l1.param_of(l2.end);
    let lo = tc.min(td).max(0.0);
    let hi = tc.max(td).min(1.0);
    let slack = eps / len1;
    if hi < lo - slack {
        return out;
    }
    if (hi - lo) * len1 <= eps {
        let t = clamp01(0.5 * (lo + hi));
        let p = l1.point_at(t);
        out.push(Intersection::Point {
            point: p,
            ta: t,
            tb: clamp01(l2.param_of(p)),
        });
    } else {
        let b0 = clamp01(l2.param_of(l1.point_at(lo)));
        let b1 = clamp01(l2.param_of(l1.point_at(hi)));
        out.push(Intersection::Overlap {
            a: (lo, hi),
            b: (b0, b1),
        });
    }
    out
}

/// Intersections of a line (first) and an arc (second).
pub fn line_arc(l: &Line, c: &Arc, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    let len = l.length();
    if len <= eps {
        let p = l.start.midpoint(l.end);
        if (p.distance(c.center()) - c.radius()).abs() <= eps
            && c.contains_angle((p - c.center()).angle(), eps)
        {
            out.push(Intersection::Point {
                point: p,
                ta: 0.0,
                tb: clamp01(c.param_of(p)),
            });
        }
        return out;
    }
    let s = l.param_of(c.center());
    let h = l.signed_distance(c.center());
    let r = c.radius();
    if h.abs() > r + eps {
        return out;
    }
    let slack = eps / len;
    // Within eps of tangency the touching point is the foot of the centre. When it lies off
    // the line or the arc, the two crossings the exact geometry may still have, sqrt(2 r eps)
    // apart at most, are tried instead: a near-tangent piece can end between them.
    let k = ((r - h.abs()) * (r + h.abs())).max(0.0).sqrt() / len;
    let tangent = h.abs() >= r - eps;
    let groups: [&[f64]; 2] = if tangent {
        [&[s], &[s - k, s + k]]
    } else {
        [&[s - k, s + k], &[]]
    };
    for group in groups {
        for &t in group {
            let t = refine_on_line(l, c, t);
            if t < -slack || t > 1.0 + slack {
                continue;
            }
            let t = clamp01(t);
            let p = l.point_at(t);
            let Some(tb) = c.param_within((p - c.center()).angle(), eps) else {
                continue;
            };
            // Clamping to the line's end moves the point by at most eps along the line.
            if (p.distance(c.center()) - r).abs() <= 2.0 * eps {
                out.push(Intersection::Point {
                    point: p,
                    ta: t,
                    tb: clamp01(tb),
                });
            }
        }
        if !out.is_empty() {
            return out;
        }
    }
    end_on_other(&Segment::Line(*l), &Segment::Arc(*c), eps)
}

/// Newton steps on t for |l(t) - centre| = radius: the closed form loses precision when the
/// radius is huge (a nearly flat arc), the iteration does not. Skipped near tangency, where
/// the closed form is the better of the two.
fn refine_on_line(l: &Line, c: &Arc, mut t: f64) -> f64 {
    let d = l.delta();
    for _ in 0..3 {
        let v = l.point_at(t) - c.center();
        let dist = v.length();
        let slope = v.dot(d) / dist;
        if slope.is_nan() || slope.abs() <= 1e-3 * d.length() {
            break;
        }
        t -= (dist - c.radius()) / slope;
    }
    t
}

/// Newton steps on p for |p - c1| = r1 and |p - c2| = r2 (see [`refine_on_line`]).
fn refine_on_circles(c1: &Arc, c2: &Arc, mut p: Point) -> Point {
    for _ in 0..3 {
        let (v1, v2) = (p - c1.center(), p - c2.center());
        let (l1, l2) = (v1.length(), v2.length());
        let (g1, g2) = (v1 / l1, v2 / l2);
        let det = g1.cross(g2);
        if det.is_nan() || det.abs() <= 1e-3 {
            break;
        }
        let (f1, f2) = (l1 - c1.radius(), l2 - c2.radius());
        // Solve [g1; g2] δ = -(f1, f2).
        let dx = (-f1 * g2.y + f2 * g1.y) / det;
        let dy = (-g1.x * f2 + g2.x * f1) / det;
        p = Point::new(p.x + dx, p.y + dy);
    }
    p
}

/// Intersections of two arcs.
pub fn arc_arc(c1: &Arc, c2: &Arc, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    let v = c2.center() - c1.center();
    let d = v.length();
    let (r1, r2) = (c1.radius(), c2.radius());
    if d <= eps && (r1 - r2).abs() <= eps {
        return cocircular(c1, c2, eps);
    }
    if d <= eps || d > r1 + r2 + eps || d < (r1 - r2).abs() - eps {
        return out;
    }
    let u = v / d;
    // The crossings measured from the smaller circle's centre: from the larger one, the
    // height h above the line of centres loses precision as r / h when they meet at a
    // shallow angle. Written to avoid cancellation between large squared radii.
    let (c, r, ro, w) = if r1 <= r2 {
        (c1.center(), r1, r2, u)
    } else {
        (c2.center(), r2, r1, -u)
    };
    let a = 0.5 * (d + (r - ro) * (r + ro) / d);
    let h = ((r - a) * (r + a)).max(0.0).sqrt();
    let base = c + w * a;
    let crossings = [base + w.perp() * h, base - w.perp() * h];
    // Within eps of tangency the touching point lies on the line of centres; when it lies off
    // either arc, the two crossings the exact geometry may still have are tried instead (see
    // `line_arc`).
    let tangent = [if (d - (r1 + r2)).abs() <= eps || r1 >= r2 {
        c1.center() + u * r1
    } else {
        c1.center() - u * r1
    }];
    let groups: [&[Point]; 2] = if (d - (r1 + r2)).abs() <= eps || (d - (r1 - r2).abs()).abs() <= eps {
        [&tangent, &crossings]
    } else {
        [&crossings, &[]]
    };
    for group in groups {
        for &p in group {
            let p = refine_on_circles(c1, c2, p);
            // The second angle only for a point on the first arc.
            let on = c1
                .param_within((p - c1.center()).angle(), eps)
                .and_then(|ta| Some((ta, c2.param_within((p - c2.center()).angle(), eps)?)));
            if let Some((ta, tb)) = on {
                out.push(Intersection::Point {
                    point: p,
                    ta: clamp01(ta),
                    tb: clamp01(tb),
                });
            }
        }
        if !out.is_empty() {
            return out;
        }
    }
    end_on_other(&Segment::Arc(*c1), &Segment::Arc(*c2), eps)
}

/// Where the curves' crossings lie off the segments: an end of one within eps of the other
/// meets it at its foot. Curves meeting at a shallow angle can have an end that near the
/// other far beyond the end from where the curves cross (h / sin of the angle: 1.2e-6 mm for
/// an end 3e-10 mm off at 2.4e-4 rad), too far for the crossing to count.
fn end_on_other(a: &Segment, b: &Segment, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    // Near the other's carrier first: a subtraction, where the distance to the segment
    // takes an angle.
    let near = |s: &Segment, p: Point| {
        let off = match s {
            Segment::Line(l) => l.signed_distance(p).abs(),
            Segment::Arc(c) => (p.distance(c.center()) - c.radius()).abs(),
        };
        off <= eps && distance_from_segment(s, p) <= eps
    };
    let ends = |s: &Segment| [(0.0, s.start()), (1.0, s.end())];
    if let Some((ta, point)) = ends(a).into_iter().find(|&(_, p)| near(b, p)) {
        out.push(Intersection::Point {
            point,
            ta,
            tb: closest_param(b, point),
        });
    } else if let Some((tb, point)) = ends(b).into_iter().find(|&(_, p)| near(a, p)) {
        out.push(Intersection::Point {
            point,
            ta: closest_param(a, point),
            tb,
        });
    }
    out
}

/// The counter-clockwise angle interval `[lo, lo + len]` an arc covers.
fn ccw_interval(c: &Arc) -> (f64, f64) {
    let len = c.sweep().abs().min(TAU);
    let lo = if c.sweep() >= 0.0 {
        c.start_angle()
    } else {
        c.start_angle() + c.sweep()
    };
    (lo, len)
}

/// Parameter on `c` of the angle `theta`, given in the unwrapped frame where `c` covers
/// `[lo, lo + len]`.
fn param_in_frame(c: &Arc, lo: f64, len: f64, theta: f64) -> f64 {
    let f = if len > 0.0 { (theta - lo) / len } else { 0.0 };
    clamp01(if c.sweep() >= 0.0 { f } else { 1.0 - f })
}

fn cocircular(c1: &Arc, c2: &Arc, eps: f64) -> Intersections {
    let mut out = Intersections::default();
    let r = 0.5 * (c1.radius() + c2.radius());
    let ang_eps = eps / r;
    let (lo1, len1) = ccw_interval(c1);
    let (lo2, len2) = ccw_interval(c2);
    let base = lo1 + (lo2 - lo1).rem_euclid(TAU);
    let mut points: Vec<(f64, f64, f64)> = Vec::new();
    for shift in [base - TAU, base] {
        let lo = lo1.max(shift);
        let hi = (lo1 + len1).min(shift + len2);
        if hi < lo - ang_eps {
            continue;
        }
        if (hi - lo) * r > eps {
            let a = (
                param_in_frame(c1, lo1, len1, lo),
                param_in_frame(c1, lo1, len1, hi),
            );
            let b = (
                param_in_frame(c2, shift, len2, lo),
                param_in_frame(c2, shift, len2, hi),
            );
            let (a, b) = if a.0 <= a.1 {
                (a, b)
            } else {
                ((a.1, a.0), (b.1, b.0))
            };
            out.push(Intersection::Overlap { a, b });
        } else {
            let m = 0.5 * (lo + hi);
            let ta = param_in_frame(c1, lo1, len1, m);
            let tb = param_in_frame(c2, shift, len2, m);
            points.push((m, ta, tb));
        }
    }
    // Touching points that coincide with an overlap's end or with each other are one point.
    for (m, ta, tb) in points {
        let p = c1.point_at_angle(m);
        let dup = out.iter().any(|i| match i {
            Intersection::Point { point, .. } => point.distance(p) <= 2.0 * eps,
            Intersection::Overlap { a, .. } => {
                c1.point_at(a.0).distance(p) <= 2.0 * eps || c1.point_at(a.1).distance(p) <= 2.0 * eps
            }
        });
        if !dup {
            out.push(Intersection::Point { point: p, ta, tb });
        }
    }
    out
}

#[cfg(test)]
mod tests;
