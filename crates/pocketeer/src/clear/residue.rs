//! Clean-up paths where a stepover above the tool radius would leave material: in sharp
//! corners of the loops, at necks where a level splits, and in the middle of each branch.
//!
//! Take a gap between levels d_k and d_(k+1) = d_k + g with r < g < 2r, and the loop L_h half
//! way, at d_k + g/2. A point p of the gap that the tool misses is farther than r from L_k, so
//! its distance to the walls exceeds d_k + g/2: it lies at u < g/2 < r along the normal from a
//! point m of L_h (its foot on the way to the nearest wall). A tool following L_h near m
//! therefore removes it. So it suffices to cut the pieces of L_h whose normals, for u in
//! [0, g/2), pass points not already within r of L_k, of L_(k+1), or inside level k+1.
//!
//! The test runs on short sub-pieces of L_h, each proven clean (every point of its normals
//! covered with a margin larger than the sub-piece's spread) or kept. Margins come from exact
//! distances and the fact that distances change no faster than the points move, so the test
//! never misses material; it errs only by keeping a little more path than needed.

use super::tree::enclosing;
use super::{ClearParams, ClearPlan, Path};
use crate::geom::PreparedPocket;
use crate::geom::{Contour, Point, Segment, SegmentIndex, Tolerance, Vector};
use crate::offset::{OffsetError, Sources};
use std::sync::Arc;

/// Adds to each part of `plan` the clean-up paths for the gap below it.
pub fn add_cleanups(
    plan: &mut ClearPlan,
    pocket: &PreparedPocket,
    sources: &[Arc<Sources>],
    params: &ClearParams,
    tol: &Tolerance,
) -> Result<(), OffsetError> {
    let r = params.tool_radius;
    let levels = plan.distances.len();
    let mut by_level: Vec<Vec<usize>> = vec![Vec::new(); levels];
    for (i, n) in plan.parts.iter().enumerate() {
        by_level[n.level].push(i);
    }
    let nominal = |k: usize| {
        if k + 1 < levels {
            plan.distances[k + 1]
        } else if k == 0 && params.allowance > 0.0 {
            plan.distances[0] + params.allowance
        } else {
            plan.distances[k] + params.stepover
        }
    };
    let gaps: Vec<usize> = (0..levels)
        .filter(|&k| nominal(k) - plan.distances[k] > r)
        .collect();
    if gaps.is_empty() {
        return Ok(());
    }
    let half: Vec<(f64, usize)> = gaps
        .iter()
        .map(|&k| (0.5 * (plan.distances[k] + nominal(k)), k))
        .collect();
    // Each half level from the sources of the level just outside it.
    let half_loops = crate::parallel::map_each(&half, |&(d, k)| {
        pocket
            .offset_with_sources(d, tol, sources.get(k).map(|s| &**s))
            .map(|l| l.0)
    })
    .into_iter()
    .collect::<Result<Vec<_>, _>>()?;
    let loops_of = |k: usize| -> Vec<Segment> {
        by_level
            .get(k)
            .into_iter()
            .flatten()
            .flat_map(|&i| plan.parts[i].loops())
            .flat_map(|c| c.segments.iter().copied())
            .collect()
    };
    let mut found: Vec<(usize, Path)> = Vec::new();
    for (gi, &k) in gaps.iter().enumerate() {
        if half_loops[gi].is_empty() {
            continue;
        }
        let gap = Gap {
            pocket,
            here: SegmentIndex::from_vec(loops_of(k)),
            below: SegmentIndex::from_vec(loops_of(k + 1)),
            next_distance: nominal(k),
            radius: r,
            reach: nominal(k) - half[gi].0,
            slack: 0.1 * r,
        };
        for l in &half_loops[gi] {
            for path in gap.needed(l) {
                let owner = enclosing(&plan.parts, &by_level[k], path.segments[0].start());
                found.push((owner, path));
            }
        }
    }
    for (owner, path) in found {
        plan.parts[owner].cleanups.push(path);
    }
    Ok(())
}

/// One gap between two levels, ready for coverage tests.
struct Gap<'a> {
    pocket: &'a PreparedPocket,
    /// Loops of level k.
    here: SegmentIndex,
    /// Loops of level k + 1 (empty for the last level).
    below: SegmentIndex,
    /// d_(k+1).
    next_distance: f64,
    radius: f64,
    /// g/2: how far along its normal a point of the half loop answers for.
    reach: f64,
    /// Largest distance between a sample and the points it answers for.
    slack: f64,
}

impl Gap<'_> {
    /// The pieces of `half` (a loop of the half level) that must be cut.
    fn needed(&self, half: &Contour) -> Vec<Path> {
        let mut subs: Vec<SubPiece> = Vec::new();
        for (i, seg) in half.segments.iter().enumerate() {
            // Along an arc the normals fan out: a point u along the normal moves (1 + u/ρ)
            // times as fast as its foot.
            let stretch = match seg {
                Segment::Arc(a) => 1.0 + self.reach / a.radius(),
                Segment::Line(_) => 1.0,
            };
            let n = ((seg.length() * stretch / self.slack).ceil() as usize).clamp(1, 1 << 20);
            for j in 0..n {
                let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
                let t = 0.5 * (t0 + t1);
                // The pocket is on the left of every loop; its inside is further from the walls.
                let normal = seg.tangent_at(t).perp();
                subs.push(SubPiece {
                    segment: i,
                    t0,
                    t1,
                    needed: !self.normal_clean(seg.point_at(t), normal),
                });
            }
        }
        paths_of(half, &subs)
    }

    /// How well `p` is covered: positive when the tool already removes everything within that
    /// distance of `p`.
    fn margin(&self, p: Point) -> f64 {
        // A loop farther than the radius covers nothing there: its term is not positive, and
        // only a positive margin proves anything (see `normal_clean`).
        let by = |loops: &SegmentIndex| {
            (loops.distance_below(p, self.radius)).map_or(f64::NEG_INFINITY, |d| self.radius - d)
        };
        let (by_here, by_below) = (by(&self.here), by(&self.below));
        let inside_below = self.pocket.distance(p) - self.next_distance;
        by_here.max(by_below).max(inside_below)
    }

    /// True when every point within `slack` of the normal segment {m + u·n : 0 ≤ u ≤ reach} is
    /// already covered.
    fn normal_clean(&self, m: Point, n: Vector) -> bool {
        let half_slack = 0.5 * self.slack;
        // Quick proof from both ends: distances to L_k grow at most like u from m, distances
        // to L_(k+1) at most like (reach − u) from the far end.
        let far = m + n * self.reach;
        let (a, b) = (self.here.distance(m), self.below.distance(far));
        if a + b + self.reach + 2.0 * half_slack < 2.0 * self.radius {
            return true;
        }
        // March along the normal, each step as long as the margin proves.
        let mut u = 0.0;
        loop {
            let w = self.margin(m + n * u) - half_slack;
            if w <= 0.125 * self.slack {
                return false;
            }
            u += w;
            if u > self.reach {
                return true;
            }
        }
    }
}

/// A stretch of one segment of a half-level loop, and whether it must be cut.
#[derive(Debug, Clone, Copy)]
struct SubPiece {
    /// The segment of the loop.
    segment: usize,
    /// Where on it the stretch starts and ends, as parameters.
    t0: f64,
    t1: f64,
    /// True when the tool must pass there to leave nothing.
    needed: bool,
}

/// Joins the needed sub-pieces (in loop order) into paths along the loop (wrapping around its
/// start).
fn paths_of(half: &Contour, subs: &[SubPiece]) -> Vec<Path> {
    if subs.iter().all(|s| s.needed) {
        return vec![Path {
            segments: half.segments.clone(),
            closed: true,
        }];
    }
    // Start right after a sub-piece that is not needed, so no path is cut by the wrap.
    let Some(first_clean) = subs.iter().position(|s| !s.needed) else {
        return Vec::new();
    };
    let mut paths = Vec::new();
    let mut current: Vec<(usize, f64, f64)> = Vec::new();
    for k in 1..=subs.len() {
        let SubPiece {
            segment: i,
            t0,
            t1,
            needed,
        } = subs[(first_clean + k) % subs.len()];
        if needed {
            match current.last_mut() {
                Some(last) if last.0 == i && last.2 == t0 => last.2 = t1,
                _ => current.push((i, t0, t1)),
            }
        } else if !current.is_empty() {
            paths.push(std::mem::take(&mut current));
        }
    }
    paths
        .into_iter()
        .map(|pieces| Path {
            segments: pieces
                .into_iter()
                .map(|(i, t0, t1)| half.segments[i].subsegment(t0, t1))
                .collect(),
            closed: false,
        })
        .collect()
}
