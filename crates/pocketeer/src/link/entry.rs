//! Getting the tool down into the stock: a helix where one fits, else a ramp along the first
//! path, else (with a warning) a straight plunge.

use super::walk::{emit, length};
use crate::geom::PreparedPocket;
use crate::geom::{Point, Segment, Vector};
use crate::toolpath::{Feed, Point3, Toolpath};
use std::f64::consts::TAU;

/// A helix: the circle the tool centre follows down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Helix {
    /// Centre.
    pub center: Point,
    /// Radius.
    pub radius: f64,
}

/// Looks for a helix inside the part that is cut first: its circle at least `tool_radius` from
/// every wall (no gouge), its centre at least `part_distance` from them and inside `outer` (so
/// it lies in that part; `outer` comes with its box), as large as `preferred` if possible and
/// never smaller than `smallest`, then nearest to `target`, and one that `reaches` (from
/// whose end, see [`helix_end`], the tool can go on to `target`). `samples` are points of the
/// part's paths with their normals into the part.
#[allow(clippy::too_many_arguments)]
pub fn find_helix(
    pocket: &PreparedPocket,
    (outer, b): (&crate::geom::Contour, crate::geom::Aabb),
    samples: &[(Point, Vector)],
    part_distance: f64,
    tool_radius: f64,
    preferred: f64,
    smallest: f64,
    target: Point,
    reaches: impl Fn(&Helix) -> bool,
) -> Option<Helix> {
    // Pushed along the normal by these amounts, samples reach the middle of the part, small
    // or large; the middle of its box is a candidate too.
    let size = b.width().min(b.height());
    let pushes = [0.02 * size, 0.1 * size, 0.25 * size, 0.4 * size]
        .into_iter()
        .chain([0.25, 0.5, 1.0, 2.0, 4.0].map(|f| f * tool_radius));
    let candidates = samples
        .iter()
        .flat_map(|&(p, n)| pushes.clone().map(move |u| p + n * u))
        .chain(std::iter::once(b.min.midpoint(b.max)));
    let mut best: Option<(Helix, f64)> = None;
    for c in candidates {
        // No radius is above the preferred one: a candidate that could not beat the best at
        // that radius is not measured (the wall distance is most of a search's time).
        let to_target = c.distance(target);
        if best.is_some_and(|(_, s)| to_target - 1e3 * preferred >= s) {
            continue;
        }
        let clearance = pocket.distance(c);
        // A little less than the room there, for rounding.
        let radius = ((clearance - tool_radius) * (1.0 - 1e-6)).min(preferred);
        // The largest radius first, then the shortest way to the target.
        let score = to_target - 1e3 * radius;
        if clearance < part_distance || radius < smallest || best.is_some_and(|(_, s)| score >= s) {
            continue;
        }
        // The containment tests last: the one on the part's outer loop is linear in its size.
        if !pocket.contains(c) || !outer.contains(c) {
            continue;
        }
        let helix = Helix { center: c, radius };
        if !reaches(&helix) {
            continue;
        }
        best = Some((helix, score));
    }
    best.map(|(h, _)| h)
}

/// Points along `segments` every `step` of length (at least one per path), with the normal to
/// their left: the cost follows the length, not the number of segments.
pub fn samples(segments: &[Segment], step: f64) -> Vec<(Point, Vector)> {
    let mut out = samples_within(segments, step, None);
    if out.is_empty() {
        if let Some(s) = segments.first() {
            out.push((s.point_at(0.5), s.tangent_at(0.5).perp()));
        }
    }
    out
}

/// The points of [`samples`] (the same spacing, from the same start) that lie in `disc`
/// (centre, radius) when one is given; segments that cannot reach the disc are not sampled,
/// so the cost follows the length inside it. None at all when no point is inside.
pub fn samples_within(segments: &[Segment], step: f64, disc: Option<(Point, f64)>) -> Vec<(Point, Vector)> {
    let mut out = Vec::new();
    let mut next = 0.5 * step;
    let mut walked = 0.0;
    for s in segments {
        let len = s.length();
        // Every point of a segment is within its length of its start.
        let far = disc.is_some_and(|(c, r)| s.start().distance(c) > r + len);
        while next <= walked + len {
            if !far {
                let t = if len > 0.0 { (next - walked) / len } else { 0.0 };
                let p = s.point_at(t);
                if disc.is_none_or(|(c, r)| p.distance(c) <= r) {
                    out.push((p, s.tangent_at(t).perp()));
                }
            }
            next += step;
        }
        walked += len;
    }
    out
}

/// Where a helix entry (see [`helix_start`]) ends: the point of its circle nearest to
/// `target`.
pub fn helix_end(helix: &Helix, target: Point) -> Point {
    helix.center + Vector::from_angle((target - helix.center).angle()) * helix.radius
}

/// Goes down along `helix` from `z_top` to `z` at no more than `angle` (radians) from the
/// horizontal, turns once more at `z`, and ends on the circle at the point nearest to
/// `target`. The tool is above the circle's start at `z_top` when this begins; returns that
/// start point.
pub fn helix_start(helix: &Helix, z_top: f64, z: f64, angle: f64, ccw: bool, target: Point) -> (Point, f64) {
    let drop_per_turn = TAU * helix.radius * angle.tan();
    let descend = TAU * ((z_top - z) / drop_per_turn).max(0.0);
    let total = descend + TAU;
    let sign = if ccw { 1.0 } else { -1.0 };
    let end_angle = (target - helix.center).angle();
    let start_angle = end_angle - sign * total;
    (
        helix.center + Vector::from_angle(start_angle) * helix.radius,
        sign * total,
    )
}

/// Emits the helix moves (see [`helix_start`]) from its start, already at `z_top`.
pub fn helix_moves(path: &mut Toolpath, helix: &Helix, z_top: f64, z: f64, sweep: f64) {
    let start = path.position().xy();
    let start_angle = (start - helix.center).angle();
    let descend = sweep - sweep.signum() * TAU;
    // Half turns at most per move; Z falls linearly with the angle.
    let pieces = ((descend.abs() / (0.5 * TAU)).ceil() as usize).max(1);
    let mut angle = start_angle;
    for k in 1..=pieces {
        let a = start_angle + descend * k as f64 / pieces as f64;
        let zk = z_top + (z - z_top) * k as f64 / pieces as f64;
        let to = helix.center + Vector::from_angle(a) * helix.radius;
        path.arc_to(Point3::at(to, zk), helix.center, a - angle, Feed::Ramp);
        angle = a;
    }
    // One flat turn at depth, in two halves, so the floor under the helix is clean.
    for k in 1..=2 {
        let a = angle + 0.5 * sweep.signum() * TAU;
        let to = if k == 2 {
            helix.center + Vector::from_angle(start_angle + sweep) * helix.radius
        } else {
            helix.center + Vector::from_angle(a) * helix.radius
        };
        path.arc_to(Point3::at(to, z), helix.center, a - angle, Feed::Cut);
        angle = a;
    }
}

/// Shortest walk a ramp may use: on less the tool would go down nearly vertically.
pub fn shortest_ramp(tool_radius: f64) -> f64 {
    0.5 * tool_radius
}

/// Ramps down from `z_top` to `z` along `walk` (a closed walk, ending where it starts), so that
/// the tool ends at the walk's start at depth `z`: out along the walk for half the length the
/// angle needs and back (a walk of a wall loop is many times that: a whole lap at that slope
/// took 0.8 m on a plate), or, on a walk shorter than that half, as many laps as the angle
/// needs.
pub fn ramp(path: &mut Toolpath, walk: &[Segment], z_top: f64, z: f64, angle: f64) {
    let lap = length(walk);
    let needed = (z_top - z) / angle.tan();
    if lap >= 0.5 * needed && needed > 0.0 {
        // Out: the walk's first `half`, down to the middle depth; back the same way to `z`.
        let half = 0.5 * needed;
        let mut out: Vec<Segment> = Vec::new();
        let mut done = 0.0;
        for s in walk {
            let l = s.length();
            if done + l >= half {
                out.push(s.subsegment(0.0, ((half - done) / l).clamp(0.0, 1.0)));
                break;
            }
            out.push(*s);
            done += l;
        }
        out.retain(|s| s.length() > 0.0);
        let back: Vec<Segment> = out.iter().rev().map(Segment::reversed).collect();
        let mut done = 0.0;
        for s in out.iter().chain(&back) {
            done += s.length();
            let zs = z_top + (z - z_top) * (done / needed).min(1.0);
            emit(path, s, zs, Feed::Ramp);
        }
        return;
    }
    let laps = (needed / lap).ceil().max(1.0) as usize;
    let total = lap * laps as f64;
    let mut done = 0.0;
    for _ in 0..laps {
        for s in walk {
            done += s.length();
            let zs = z_top + (z - z_top) * (done / total).min(1.0);
            emit(path, s, zs, Feed::Ramp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Contour;

    #[test]
    fn a_ramp_on_a_long_loop_goes_out_and_back_not_round_it() {
        // A 100 mm square walked from (0, 0), 2 mm down at 3 degrees: 38.2 mm of ramp, out
        // 19.1 mm along the bottom edge and back, not a 400 mm lap at a shallower slope.
        let p = Point::new;
        let walk = Contour::polygon(&[p(0.0, 0.0), p(100.0, 0.0), p(100.0, 100.0), p(0.0, 100.0)]).segments;
        let angle = 3f64.to_radians();
        let mut path = Toolpath::new(Point3::new(0.0, 0.0, 0.0));
        ramp(&mut path, &walk, 0.0, -2.0, angle);
        let needed = 2.0 / angle.tan();
        let mut at = path.start;
        let mut planar = 0.0;
        for m in &path.moves {
            let to = m.to();
            let run = at.xy().distance(to.xy());
            // On the walk's bottom edge, never steeper than the angle.
            assert!(
                to.y.abs() < 1e-12 && (0.0..=0.5 * needed + 1e-9).contains(&to.x),
                "{to:?}"
            );
            assert!(at.z - to.z <= run * angle.tan() + 1e-9, "{at:?} -> {to:?}");
            planar += run;
            at = to;
        }
        assert!((planar - needed).abs() < 1e-9, "{planar} mm");
        assert!(
            at.distance(Point3::new(0.0, 0.0, -2.0)) < 1e-9,
            "ends at the start at depth: {at:?}"
        );
        // A loop shorter than half of that is gone round as many times as it takes.
        let small = Contour::polygon(&[p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)]).segments;
        let mut path = Toolpath::new(Point3::new(0.0, 0.0, 0.0));
        ramp(&mut path, &small, 0.0, -2.0, angle);
        assert_eq!(path.moves.len(), 4 * (needed / 16.0).ceil() as usize);
        assert!(path.position().distance(Point3::new(0.0, 0.0, -2.0)) < 1e-9);
    }
}
