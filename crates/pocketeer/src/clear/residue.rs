//! Clean-up paths where a stepover above the tool radius would leave material: in sharp
//! corners of the loops, at necks where a level splits, and in the middle of each branch.
//!
//! Take a gap between levels d_k and d_(k+1) = d_k + g with r < g < 2r, and the loop L_h at
//! d_k + δ, g − r ≤ δ ≤ g/2 (see [`path_offset`]). A point p of the gap that the tool misses
//! is farther than r from L_k, so its distance w to the walls exceeds d_k + r (on the way from
//! p straight to its nearest wall the distance falls as fast as the tool goes, so L_k is
//! crossed w − d_k from p): it lies at r − δ < u < g − δ ≤ r along the normal from a point m
//! of L_h (its foot on the way to the nearest wall). A tool following L_h near m therefore
//! removes it. So it suffices to cut the pieces of L_h whose normals, for u in [0, g − δ),
//! pass points not already within r of L_k, of L_(k+1), or inside level k+1.
//!
//! The test runs on short sub-pieces of L_h, each proven clean (every point of its normals
//! covered with a margin larger than the sub-piece's spread) or split in halves and each half
//! tested again, down to [`FINEST_SPLITS`] halvings, the last kept. Margins come from exact
//! distances and the fact that distances change no faster than the points move, so the test
//! never misses material; it errs only by keeping a little more path than needed, less the
//! finer the last halves are.
//!
//! A needed piece small enough, or a run of neighbouring ones, is then tried as a spot (see
//! [`Gap::spot_for`], [`Gap::with_spots`]): the tool standing at one point c, sweeping the
//! disc of 0.95 r round it, taken as one more cover in the same test. Where that proves every
//! point the pieces answer for covered, they give way to a short path ending at c. On the
//! 8-island rectangle at 80 % stepover most clean-up paths are such pieces: three sides of a
//! little triangle in the cusp between the loops round two islands and the walls' loops,
//! followed round where the tool need only step in.

use super::tree::enclosing;
use super::{ClearParams, ClearPlan, Path};
use crate::geom::PreparedPocket;
use crate::geom::{
    bbox_of, closest_point, distance_from_segment, enclosing_circle, nearest_on, outline_points, Aabb,
    Contour, Line, Point, Segment, SegmentIndex, Tolerance, Vector,
};
use crate::offset::{OffsetError, Sources};
use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::sync::Arc;

/// How many times a sub-piece not proven clean is halved before it is kept: the margin a
/// proof needs is proportional to the sub-piece's spread, so the paths kept at the first
/// spread (a tenth of the tool radius) ran up to 0.19 mm of a 3 mm radius past the material
/// on both ends; halved three times, the 8-island rectangle at 70 % stepover keeps 139 mm of
/// clean-up path where it kept 230 mm.
const FINEST_SPLITS: u32 = 3;

/// The length of a spot's path, in tool radii at most (see [`Gap::spot_for`]).
const SPOT_LENGTH_RADII: f64 = 0.1;

/// How far apart, in tool radii, neighbouring needed pieces of a half loop may end and still
/// be tried as one spot (see [`Gap::with_spots`]). Measured on the linking bench, the 8-island
/// rectangle: at 90 % 354.3 s with each piece alone, 350.3 s with runs within two radii; at
/// 80 % 346.6 -> 342.4 s. Within one radius (pairs, tried first to last) 350.9 s at 90 %.
const RUN_GAP_RADII: f64 = 2.0;

/// How near, in tool radii, needed pieces of one gap lie to one another to be tried as one
/// group (see [`Gap::clear`]), in turn, the pieces of the groups taken left out of the next:
/// the two sides of a patch between two islands lie up to twice the reach of a piece apart
/// (2 (g − δ) < 2r) and the patch's width more; where groups that wide fail (the four
/// patches round a leaf between four islands), nearer pieces may still be one.
const GROUP_GAPS_RADII: [f64; 3] = [3.0, 1.5, 0.75];

/// How far in from the ends of a group of pieces a straight pass may start and end, in tool
/// radii, tried in turn (see [`Gap::pass_for`]): the pieces run past the material's ends.
const PASS_TRIMS_RADII: [f64; 4] = [0.75, 0.5, 0.25, 0.0];

/// Where across a group of pieces a straight pass may run, as shares of the way from one
/// side to the other, tried in turn (see [`Gap::pass_for`]): half way first; the material
/// of a triangle lies nearer its wide side.
const PASS_ACROSS: [f64; 3] = [0.5, 0.35, 0.65];

/// How near, in tool radii, the material a spot of a path through spots answers for must lie
/// to it, sampled (see [`Gap::path_through_spots`]): below the reach of 0.95 r, room for
/// what the samples miss (the exact test decides).
const SPOTS_FIT_RADII: f64 = 0.85;

/// How far apart the samples of the material are, in tool radii (see [`Gap::material`]):
/// they only propose spots and refuse passes early, the exact test decides. At 0.1 the
/// sampling took a quarter of the 300-hole plate's planning at 90 % stepover (1.64 s against
/// 1.37 s at 0.2, programs the same but for four drawings, each as long or shorter).
const MATERIAL_STEP_RADII: f64 = 0.2;

/// How many times the material is parted among the spots of a path (see [`spots_over`]).
const SPOT_ROUNDS: usize = 4;

/// How many times the way a spot may be moved towards the nearest loop is halved in the
/// search for how far it can go while it still clears what it answers for (see
/// [`Gap::spot_at`]): to 1/64 of the way.
const SPOT_PULL_HALVINGS: usize = 6;

/// How much nearer than the tool radius a clean-up path's tool reaches the farthest point it
/// answers for, in tool radii (see [`path_offset`]): room for rounding.
pub(super) const REACH_MARGIN_RADII: f64 = 0.05;

/// Where the clean-up paths of a gap `g` wide (r < g < 2r) lie, beyond the loops of the level
/// outside it: as near to them as lets the tool reach every point the paths answer for,
/// g − r (plus a margin), and never beyond half way.
///
/// A point the loops miss lies more than r beyond the level outside (see the module's
/// comment) and less than g, so from a loop δ beyond that level it lies between r − δ and
/// g − δ along a normal: within the tool's reach from δ = g − r on. Half way (δ = g/2) leaves
/// the same room on both sides; nearer, each excursion out to a path and back from it is
/// shorter (the 8-island rectangle at 70 % stepover: 379.5 -> 373.1 s; at 80 %: 364.0 ->
/// 361.3 s).
fn path_offset(g: f64, r: f64) -> f64 {
    (0.5 * g).min(g - r + REACH_MARGIN_RADII * r)
}

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
        .map(|&k| {
            let g = nominal(k) - plan.distances[k];
            (plan.distances[k] + path_offset(g, r), k)
        })
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
            delta: half[gi].0 - plan.distances[k],
            slack: 0.1 * r,
            splits: FINEST_SPLITS,
            hints: Default::default(),
            cover: Default::default(),
            eps: tol.eps,
        };
        let pieces = (half_loops[gi].iter()).map(|l| gap.needed(l)).collect();
        for path in gap.clear(pieces) {
            let owner = enclosing(&plan.parts, &by_level[k], path.segments[0].start());
            found.push((owner, path));
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
    /// g − δ: how far along its normal a point of the half loop answers for (see
    /// [`path_offset`]).
    reach: f64,
    /// δ: how far the half loop lies beyond the level outside it.
    delta: f64,
    /// Largest distance between a sample and the points it answers for, at first (see
    /// [`FINEST_SPLITS`]).
    slack: f64,
    /// How many times a sub-piece not proven clean is halved ([`FINEST_SPLITS`]).
    splits: u32,
    /// The segments of `here`, `below` and the walls nearest to the point last measured from
    /// (see [`SegmentIndex::distance_hinted`]): the points come one after another along the
    /// normals and the half loop.
    hints: [Cell<usize>; 3],
    /// Where the tool goes besides the loops while a spot or a path is tried: the corners of
    /// a path of straight moves, one point for a spot; none when empty (see
    /// [`Gap::covered_with`]).
    cover: RefCell<Vec<Point>>,
    /// The geometric epsilon, for the spot's path against the walls.
    eps: f64,
}

impl Gap<'_> {
    /// The pieces of `half` (a loop of the half level) that must be cut.
    fn needed(&self, half: &Contour) -> Vec<Path> {
        let mut subs: Vec<SubPiece> = Vec::new();
        for (i, seg) in half.segments.iter().enumerate() {
            self.classify_segment(seg, i, &mut subs);
        }
        paths_of(half, &subs)
    }

    /// Adds the stretches of `seg` (the `i`-th segment of a half loop) to `subs`, each clean
    /// or needed (see [`Gap::classify`]).
    fn classify_segment(&self, seg: &Segment, i: usize, subs: &mut Vec<SubPiece>) {
        // Along an arc the normals fan out: a point u along the normal moves (1 + u/ρ) times
        // as fast as its foot.
        let stretch = match seg {
            Segment::Arc(a) => 1.0 + self.reach / a.radius(),
            Segment::Line(_) => 1.0,
        };
        let n = ((seg.length() * stretch / self.slack).ceil() as usize).clamp(1, 1 << 20);
        for j in 0..n {
            let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
            self.classify(seg, i, (t0, t1), self.slack, self.splits, subs);
        }
    }

    /// The paths that clear what the needed pieces of this gap's half loops answer for
    /// (`loops`: by half loop, each in loop order; see [`Gap::needed`]). Pieces lying within
    /// [`GROUP_GAPS_RADII`] of one another, across loops too (the two sides of one patch of
    /// material between two islands), are grouped, each group as a whole: the same groups
    /// whatever order the loops and pieces come in. A group that one spot or one straight
    /// pass clears (see [`Gap::spot_for`], [`Gap::pass_for`]) gives way to it; the pieces of
    /// the others are taken loop by loop (see [`Gap::with_spots`]).
    fn clear(&self, loops: Vec<Vec<Path>>) -> Vec<Path> {
        let mut taken: Vec<Vec<bool>> = loops.iter().map(|l| vec![false; l.len()]).collect();
        let mut out = Vec::new();
        // Groups tried and not taken, each tried once (a group apart from all others within
        // the widest join stays one at the narrower ones).
        let mut tried: HashSet<Vec<(usize, usize)>> = HashSet::new();
        for join in GROUP_GAPS_RADII {
            for group in self.groups(&loops, &taken, join * self.radius) {
                if group.len() < 2 || tried.contains(&group) {
                    continue;
                }
                let whole = joined(group.iter().map(|&(i, j)| &loops[i][j]));
                let cover = self.spot_for(&whole).or_else(|| {
                    let material = self.material(&whole);
                    (self.pass_for(&whole, &material)).or_else(|| self.path_through_spots(&whole, &material))
                });
                if let Some(path) = cover {
                    out.push(path);
                    for &(i, j) in &group {
                        taken[i][j] = true;
                    }
                } else {
                    tried.insert(group);
                }
            }
        }
        for (pieces, taken) in loops.into_iter().zip(taken) {
            let left = (pieces.into_iter().zip(taken))
                .filter(|(_, t)| !t)
                .map(|(p, _)| p)
                .collect();
            out.extend(self.with_spots(left));
        }
        out
    }

    /// The open pieces of `loops` (as loop and place in it) not yet `taken`, in groups:
    /// joined where two lie within `join` of each other, each group in loop and place order.
    fn groups(&self, loops: &[Vec<Path>], taken: &[Vec<bool>], join: f64) -> Vec<Vec<(usize, usize)>> {
        let ids: Vec<(usize, usize)> = (loops.iter().enumerate())
            .flat_map(|(i, l)| (l.iter().enumerate()).map(move |(j, p)| (i, j, p)))
            .filter(|&(i, j, p)| !p.closed && !taken[i][j])
            .map(|(i, j, _)| (i, j))
            .collect();
        let piece = |k: usize| &loops[ids[k].0][ids[k].1].segments;
        let boxes: Vec<Aabb> = (0..ids.len()).map(|k| bbox_of(piece(k))).collect();
        let near = |a: usize, b: usize| {
            boxes[a].distance_to_box(&boxes[b]) < join
                && (piece(a).iter()).any(|x| {
                    (piece(b).iter()).any(|y| crate::geom::segment_distance(x, y, self.eps).0 < join)
                })
        };
        // Swept along x: only pieces whose boxes overlap in x, widened by the gap, are
        // measured against each other.
        let mut by_x: Vec<usize> = (0..ids.len()).collect();
        by_x.sort_by(|&a, &b| boxes[a].min.x.total_cmp(&boxes[b].min.x));
        let mut sets = crate::union_find::UnionFind::new(ids.len());
        for (n, &a) in by_x.iter().enumerate() {
            for &b in &by_x[n + 1..] {
                if boxes[b].min.x > boxes[a].max.x + join {
                    break;
                }
                if near(a, b) {
                    sets.union(a, b);
                }
            }
        }
        let mut groups: Vec<Vec<(usize, usize)>> = vec![Vec::new(); ids.len()];
        for (k, &id) in ids.iter().enumerate() {
            groups[sets.find(k)].push(id);
        }
        groups.retain(|g| !g.is_empty());
        groups
    }

    /// A straight pass that clears what the pieces of `path` answer for, or None: along their
    /// principal axis, half way across them, tried shortest first from [`PASS_TRIMS_RADII`]
    /// in from the pieces' ends along it to their full extent; every point of it a tool
    /// radius from the walls, and the pieces' test (see [`Gap::needed`]) finding nothing
    /// needed with the tool along it as one more cover, reaching 0.95 r. Two long pieces on
    /// both sides of a narrow patch give way to one pass along its middle.
    fn pass_for(&self, path: &Path, material: &[Point]) -> Option<Path> {
        let (mean, sxx, sxy, syy) = super::spots::outline_moments(path.segments.iter())?;
        let axis = Vector::from_angle(0.5 * (2.0 * sxy).atan2(sxx - syy));
        // Along the principal axis, then across it: two pieces on both sides of a patch as
        // wide as it is long spread as far along their line as across.
        [axis, axis.perp()]
            .into_iter()
            .find_map(|u| self.pass_along(path, material, mean, u))
    }

    /// [`Gap::pass_for`] along the direction `u` through `mean`, the `material` sampled (see
    /// [`Gap::material`]).
    fn pass_along(&self, path: &Path, material: &[Point], mean: Point, u: Vector) -> Option<Path> {
        let r = self.radius;
        let v = u.perp();
        let (mut along, mut across) = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        for s in &path.segments {
            let n = ((s.length() / (0.25 * r)).ceil() as usize).clamp(1, 1 << 12);
            for k in 0..=n {
                let q = s.point_at(k as f64 / n as f64) - mean;
                let (t, h) = (q.dot(u), q.dot(v));
                along = (along.0.min(t), along.1.max(t));
                across = (across.0.min(h), across.1.max(h));
            }
        }
        // Material a pass clears lies within 0.95 r of it, and a piece lies at most g − δ < r
        // from what it answers for.
        if across.1 - across.0 > 4.0 * r {
            return None;
        }
        let tries = PASS_ACROSS
            .into_iter()
            .flat_map(|f| PASS_TRIMS_RADII.map(|trim| (f, trim)));
        tries.into_iter().find_map(|(f, trim)| {
            let side = v * (across.0 + f * (across.1 - across.0));
            let (t0, t1) = (along.0 + trim * r, along.1 - trim * r);
            if t1 - t0 < SPOT_LENGTH_RADII * r {
                return None;
            }
            let (a, b) = (mean + side + u * t0, mean + side + u * t1);
            let line = Segment::Line(Line::new(a, b));
            // A sample of the material beyond the reach would fail the exact test (it is not
            // covered, and the test measures within half its slack of it): no need to run it.
            if material
                .iter()
                .any(|&p| distance_from_segment(&line, p) > self.reach_of_tool())
            {
                return None;
            }
            if self.near_walls(&line) || !self.covered_with(path, &[a, b]) {
                return None;
            }
            Some(Path {
                segments: vec![line],
                closed: false,
            })
        })
    }

    /// A path of straight moves through two or three spots that clears what the pieces of
    /// `path` answer for, or None: the spots are the centres of the smallest circles round
    /// the material the pieces answer for (`points`, see [`Gap::material`]) parted among them
    /// (farthest first, then each sample to its nearest spot, a few times over), each circle
    /// within [`SPOTS_FIT_RADII`]; the moves every point a tool radius from the walls, shorter
    /// than the pieces together, and the pieces' test (see [`Gap::needed`]) finding nothing
    /// needed with the tool along them as one more cover, reaching 0.95 r. A triangle of
    /// material between two islands and a wall, too wide for one spot or one pass, is
    /// cleared by a Λ over it in place of its three sides.
    fn path_through_spots(&self, path: &Path, points: &[Point]) -> Option<Path> {
        let r = self.radius;
        let length: f64 = path.segments.iter().map(Segment::length).sum();
        (2..=3).find_map(|k| {
            let spots = spots_over(points, k, SPOTS_FIT_RADII * r)?;
            let moves: Vec<Segment> = (spots.windows(2))
                .map(|w| Segment::Line(Line::new(w[0], w[1])))
                .collect();
            let clear_of_walls = !moves.iter().any(|m| self.near_walls(m));
            let shorter = moves.iter().map(Segment::length).sum::<f64>() < length;
            (clear_of_walls && shorter && self.covered_with(path, &spots)).then_some(Path {
                segments: moves,
                closed: false,
            })
        })
    }

    /// What the loops leave of what the pieces of `path` answer for, sampled: the points
    /// along their normals out to the reach, [`MATERIAL_STEP_RADII`] apart, that no loop
    /// covers (see [`Gap::margin`]).
    fn material(&self, path: &Path) -> Vec<Point> {
        let step = MATERIAL_STEP_RADII * self.radius;
        let across = ((self.reach / step).ceil() as usize).max(1);
        let mut out = Vec::new();
        for s in &path.segments {
            let n = ((s.length() / step).ceil() as usize).clamp(1, 1 << 12);
            for k in 0..=n {
                let t = k as f64 / n as f64;
                let (m, normal) = (s.point_at(t), s.tangent_at(t).perp());
                out.extend(
                    (0..=across)
                        .map(|j| m + normal * (self.reach * j as f64 / across as f64))
                        .filter(|&p| self.margin(p) <= 0.0),
                );
            }
        }
        out
    }

    /// The needed `pieces` of a closed half loop (in loop order), each as a spot's path where
    /// one clears it (see [`Gap::spot_for`]), and each run of neighbours that one spot clears
    /// as a whole given way to that spot. A run is a maximal chain of pieces each ending within
    /// [`RUN_GAP_RADII`] of the next one's start, round the loop: the same pieces whichever way
    /// round the loop runs and wherever it starts, so a drawing mirrored or drawn from another
    /// point gets the same spots. Neighbouring pieces are often the two sides of one cusp: one
    /// spot is one excursion out and back where two were.
    fn with_spots(&self, pieces: Vec<Path>) -> Vec<Path> {
        let n = pieces.len();
        let close = |i: usize| {
            let (a, b) = (&pieces[i], &pieces[(i + 1) % n]);
            match (a.segments.last(), b.segments.first()) {
                (Some(x), Some(y)) => x.end().distance(y.start()) < RUN_GAP_RADII * self.radius,
                _ => false,
            }
        };
        // Runs start after each piece not close to the next; none such: one run of all.
        let first = (0..n).find(|&i| !close(i)).map_or(0, |i| (i + 1) % n);
        let mut out = Vec::with_capacity(n);
        let mut run: Vec<usize> = Vec::new();
        for k in 0..n {
            let i = (first + k) % n;
            run.push(i);
            if k + 1 == n || !close(i) {
                let whole = (run.len() > 1)
                    .then(|| joined(run.iter().map(|&j| &pieces[j])))
                    .and_then(|p| self.spot_for(&p));
                match whole {
                    Some(spot) => out.push(spot),
                    None => out.extend(
                        (run.iter()).map(|&j| self.spot_for(&pieces[j]).unwrap_or_else(|| pieces[j].clone())),
                    ),
                }
                run.clear();
            }
        }
        out
    }

    /// A short path ending at a spot c from which the tool clears what is left of all that the
    /// needed piece `path` (under two tool radii across) answers for, or None. c is the centre
    /// of the smallest circle round the piece, else a point beyond the piece's point nearest
    /// that centre, across the band of material the piece answers for: the nearest of three
    /// from where 0.95 r still reaches the band's far edge to its middle (the excursion out to
    /// a spot and back is shorter the nearer it lies). The path runs to c from the piece's
    /// nearest point, at most a tenth of the radius long, every point of it a tool radius
    /// from the walls; and the piece's test (see [`Gap::needed`]) finds nothing needed with
    /// the tool at c as one more cover, reaching 0.95 r.
    fn spot_for(&self, path: &Path) -> Option<Path> {
        let r = self.radius;
        let b = bbox_of(&path.segments);
        if b.width() > 2.0 * r || b.height() > 2.0 * r {
            return None;
        }
        let (c, _) = enclosing_circle(&outline_points(&path.segments))?;
        if let Some(spot) = self.spot_at(path, c) {
            return Some(spot);
        }
        // Then points across the band the piece answers for, along the normal at its point
        // nearest c: the material lies r − δ to g − δ beyond the piece.
        let (k, t, _) = nearest_on(&path.segments, c);
        let seg = path.segments.get(k)?;
        let (foot, normal) = (seg.point_at(t), seg.tangent_at(t).perp());
        let far = 0.5 * (self.radius - self.delta + self.reach);
        let near = (self.reach - self.reach_of_tool()).clamp(0.0, far);
        [0.25, 0.5, 1.0]
            .into_iter()
            .find_map(|f| self.spot_at(path, foot + normal * (near + f * (far - near))))
    }

    /// The spot's path to `c` (see [`Gap::spot_for`]) when the tool at `c` covers what `path`
    /// answers for, the spot moved towards the nearest point of the loops of the level outside
    /// the gap as far as it still covers that (a search by halving, [`SPOT_PULL_HALVINGS`]):
    /// the excursion out to it from the loop and back is shorter.
    fn spot_at(&self, path: &Path, c: Point) -> Option<Path> {
        let line = self.spot_line(path, c)?;
        if !self.covered_with(path, &[c]) {
            return None;
        }
        // Towards the loops of the level outside the gap: the clean-up paths are its part's,
        // cut on the way round its loops (see `link::Linker::host_of`).
        let pulled = self.here.nearest(c).and_then(|(q, _)| {
            // Shares of the way to q: at `lo` the spot covers, at `hi` it was not found to.
            let (mut lo, mut hi, mut best) = (0.0, 1.0, None);
            for _ in 0..SPOT_PULL_HALVINGS {
                let f = 0.5 * (lo + hi);
                let p = c + (q - c) * f;
                match self.spot_line(path, p).filter(|_| self.covered_with(path, &[p])) {
                    Some(line) => (lo, best) = (f, Some(line)),
                    None => hi = f,
                }
            }
            best
        });
        Some(Path {
            segments: vec![pulled.unwrap_or(line)],
            closed: false,
        })
    }

    /// The short path ending at the spot `c` for `path`: from towards the piece's nearest
    /// point, at most [`SPOT_LENGTH_RADII`] long; None where it comes within a tool radius of
    /// the walls.
    fn spot_line(&self, path: &Path, c: Point) -> Option<Segment> {
        let r = self.radius;
        let (k, _, room) = nearest_on(&path.segments, c);
        let toward = (closest_point(path.segments.get(k)?, c) - c).normalized()?;
        let line = Segment::Line(Line::new(c + toward * room.min(SPOT_LENGTH_RADII * r), c));
        (!self.near_walls(&line)).then_some(line)
    }

    /// How far round it the tool at a spot or along a pass is taken to clear: the radius less
    /// [`REACH_MARGIN_RADII`].
    fn reach_of_tool(&self) -> f64 {
        (1.0 - REACH_MARGIN_RADII) * self.radius
    }

    /// True when the straight move `s` comes within a tool radius of the walls.
    fn near_walls(&self, s: &Segment) -> bool {
        self.pocket.walls().segment_within(s, self.radius, self.eps)
    }

    /// True when the test of `path`'s needed pieces (see [`Gap::needed`]) finds nothing
    /// needed with the tool also along the straight moves through the points of `cover` (a
    /// spot: one point), reaching 0.95 r round them.
    fn covered_with(&self, path: &Path, cover: &[Point]) -> bool {
        *self.cover.borrow_mut() = cover.to_vec();
        let mut subs = Vec::new();
        for (i, seg) in path.segments.iter().enumerate() {
            self.classify_segment(seg, i, &mut subs);
        }
        self.cover.borrow_mut().clear();
        subs.iter().all(|s| !s.needed)
    }

    /// Adds the stretch `t` of `seg` (the `i`-th segment of a half loop), whose points lie
    /// within `slack` of its middle's along their normals, to `subs`: clean when proven so,
    /// else each half in turn (halving at most `splits` times more), else needed.
    fn classify(
        &self,
        seg: &Segment,
        i: usize,
        t: (f64, f64),
        slack: f64,
        splits: u32,
        subs: &mut Vec<SubPiece>,
    ) {
        let (t0, t1) = t;
        let m = 0.5 * (t0 + t1);
        // The pocket is on the left of every loop; its inside is further from the walls.
        let clean = self.normal_clean(seg.point_at(m), seg.tangent_at(m).perp(), slack);
        if clean || splits == 0 {
            subs.push(SubPiece {
                segment: i,
                t0,
                t1,
                needed: !clean,
            });
        } else {
            self.classify(seg, i, (t0, m), 0.5 * slack, splits - 1, subs);
            self.classify(seg, i, (m, t1), 0.5 * slack, splits - 1, subs);
        }
    }

    /// How well `p` is covered: positive when the tool already removes everything within that
    /// distance of `p`.
    fn margin(&self, p: Point) -> f64 {
        // A loop farther than the radius covers nothing there: its term is not positive, and
        // only a positive margin proves anything (see `normal_clean`).
        let r = self.radius;
        let here = self.here.distance_hinted(p, r, &self.hints[0]);
        let by_here = here.map_or(f64::NEG_INFINITY, |d| r - d);
        // Only a loop below nearer than the one here raises the margin.
        let nearer = here.map_or(r, |d| d.min(r));
        let by_below =
            (self.below.distance_hinted(p, nearer, &self.hints[1])).map_or(f64::NEG_INFINITY, |d| r - d);
        // The walls are at most d_k beyond the loops of level k, so within r < g of those
        // loops a point is not inside level k + 1: no need to ask the walls.
        let inside_below = match here {
            Some(_) => f64::NEG_INFINITY,
            None => self.pocket.distance_hinted(p, &self.hints[2]) - self.next_distance,
        };
        // The tool at the spot or along the pass being tried sweeps what lies within its reach.
        let by_cover = self.reach_of_tool() - distance_to_moves(p, &self.cover.borrow());
        by_here.max(by_below).max(inside_below).max(by_cover)
    }

    /// True when every point within `slack` of the normal segment {m + u·n : 0 ≤ u ≤ reach} is
    /// already covered.
    fn normal_clean(&self, m: Point, n: Vector, slack: f64) -> bool {
        let half_slack = 0.5 * slack;
        // Quick proof from both ends: distances to L_k grow at most like u from m, distances
        // to L_(k+1) at most like (reach − u) from the far end.
        let far = m + n * self.reach;
        // The room the two distances leave, each asked for only below what is left of it.
        let room = 2.0 * (self.radius - half_slack) - self.reach;
        let Some(a) = self.here.distance_hinted(m, room, &self.hints[0]) else {
            return self.march(m, n, slack);
        };
        if self
            .below
            .distance_hinted(far, room - a, &self.hints[1])
            .is_some()
        {
            return true;
        }
        self.march(m, n, slack)
    }

    /// [`Gap::normal_clean`] the slow way: along the normal, each step as long as the margin
    /// proves.
    fn march(&self, m: Point, n: Vector, slack: f64) -> bool {
        let half_slack = 0.5 * slack;
        let mut u = 0.0;
        loop {
            let w = self.margin(m + n * u) - half_slack;
            if w <= 0.125 * slack {
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

/// The segments of `pieces` one after another, as one open path (for the coverage tests,
/// which take each segment on its own: the pieces need not meet).
fn joined<'p>(pieces: impl Iterator<Item = &'p Path>) -> Path {
    Path {
        segments: pieces.flat_map(|p| p.segments.iter().copied()).collect(),
        closed: false,
    }
}

/// `k` spots in an order to be passed through, each within `fit` of the `points` nearest to
/// it, or None: the first the point farthest from the centre of the smallest circle round
/// all, each next the point farthest from the spots so far, then [`SPOT_ROUNDS`] times each
/// point given to its nearest spot and each spot moved to the centre of the smallest circle
/// round its points. In order along the line through the two farthest apart.
fn spots_over(points: &[Point], k: usize, fit: f64) -> Option<Vec<Point>> {
    let (centre, _) = enclosing_circle(points)?;
    let farthest_from = |spots: &[Point]| {
        (points.iter()).max_by(|a, b| {
            let d = |p: &Point| spots.iter().map(|s| s.distance(*p)).fold(f64::INFINITY, f64::min);
            d(a).total_cmp(&d(b))
        })
    };
    let mut spots = vec![*farthest_from(&[centre])?];
    while spots.len() < k {
        spots.push(*farthest_from(&spots)?);
    }
    let nearest = |spots: &[Point], p: Point| {
        (0..spots.len())
            .min_by(|&a, &b| spots[a].distance(p).total_cmp(&spots[b].distance(p)))
            .unwrap_or(0)
    };
    let mut worst = f64::INFINITY;
    for _ in 0..SPOT_ROUNDS {
        let mut parts: Vec<Vec<Point>> = vec![Vec::new(); k];
        for &p in points {
            parts[nearest(&spots, p)].push(p);
        }
        worst = 0.0;
        for (spot, part) in spots.iter_mut().zip(&parts) {
            if let Some((c, rho)) = enclosing_circle(part) {
                *spot = c;
                worst = f64::max(worst, rho);
            }
        }
    }
    if worst > fit {
        return None;
    }
    // The two farthest apart are the ends; a third lies between them.
    let ends = (0..k)
        .flat_map(|a| (a + 1..k).map(move |b| (a, b)))
        .max_by(|x, y| {
            let d = |(a, b): (usize, usize)| spots[a].distance(spots[b]);
            d(*x).total_cmp(&d(*y))
        })?;
    let first = spots[ends.0];
    spots.sort_by(|a, b| a.distance(first).total_cmp(&b.distance(first)));
    Some(spots)
}

/// The distance from `p` to the straight moves through `corners` (one point: to it; none:
/// infinite).
fn distance_to_moves(p: Point, corners: &[Point]) -> f64 {
    match corners {
        [] => f64::INFINITY,
        [c] => p.distance(*c),
        _ => (corners.windows(2))
            .map(|w| distance_from_segment(&Segment::Line(Line::new(w[0], w[1])), p))
            .fold(f64::INFINITY, f64::min),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Pocket;

    fn square(a: f64, b: f64) -> Contour {
        let p = Point::new;
        Contour::polygon(&[p(a, a), p(b, a), p(b, b), p(a, b)])
    }

    /// One gap in a 40 mm square pocket, tool radius 1: the loop of level k at 1 from the
    /// walls, `below` for level k + 1 at 2.8 (a gap of 1.8 > r), the half level at 1.9, each
    /// sub-piece halved `splits` times at most.
    fn gap_with<'a>(pocket: &'a PreparedPocket, below: &[Segment], splits: u32) -> Gap<'a> {
        Gap {
            pocket,
            here: SegmentIndex::new(&square(1.0, 39.0).segments),
            below: SegmentIndex::new(below),
            next_distance: 2.8,
            radius: 1.0,
            reach: 0.9,
            delta: 0.9,
            slack: 0.1,
            splits,
            hints: Default::default(),
            cover: Default::default(),
            eps: 1e-9,
        }
    }

    fn square_pocket() -> PreparedPocket {
        PreparedPocket::new(&Pocket {
            boundary: square(0.0, 40.0),
            islands: vec![],
        })
    }

    /// The clean-up paths of the gap of [`gap_with`] with level k + 1 whole.
    fn corner_paths(splits: u32) -> Vec<Path> {
        let pocket = square_pocket();
        gap_with(&pocket, &square(2.8, 37.2).segments, splits).needed(&square(1.9, 38.1))
    }

    /// The gap of [`gap_with`] with the bottom loop of level k + 1 broken where `breaks` (x
    /// ranges, in order) say: the tool misses patches above the bottom edge.
    fn broken_gap<'a>(pocket: &'a PreparedPocket, breaks: &[(f64, f64)]) -> Gap<'a> {
        gap_with(pocket, &broken_below(breaks), FINEST_SPLITS)
    }

    /// The loops of level k + 1 of [`broken_gap`].
    fn broken_below(breaks: &[(f64, f64)]) -> Vec<Segment> {
        let line = |a: (f64, f64), b: (f64, f64)| {
            Segment::Line(Line::new(Point::new(a.0, a.1), Point::new(b.0, b.1)))
        };
        let (lo, hi) = (2.8, 37.2);
        let mut x = lo;
        let mut below = Vec::new();
        for &(a, b) in breaks {
            below.push(line((x, lo), (a, lo)));
            x = b;
        }
        below.push(line((x, lo), (hi, lo)));
        below.extend([
            line((hi, lo), (hi, hi)),
            line((hi, hi), (lo, hi)),
            line((lo, hi), (lo, lo)),
        ]);
        below
    }

    /// What the tool leaves in the gap of [`broken_gap`] near the bottom edge, sampled on its
    /// own every 0.01 mm for x in 15..25: within 2.8 of the walls (not inside level k + 1),
    /// farther than r from both levels' loops.
    fn left_by(breaks: &[(f64, f64)]) -> Vec<Point> {
        let loops: Vec<Segment> = (square(1.0, 39.0).segments.into_iter())
            .chain(broken_below(breaks))
            .collect();
        (0..=1000)
            .flat_map(|i| (0..=90).map(move |j| Point::new(15.0 + 0.01 * i as f64, 1.9 + 0.01 * j as f64)))
            .filter(|&p| p.y < 2.8 - 1e-9)
            .filter(|&p| loops.iter().all(|s| closest_point(s, p).distance(p) > 1.0))
            .collect()
    }

    #[test]
    fn two_pieces_beside_one_cusp_give_way_to_one_spot() {
        // The loop below broken twice, 0.2 mm apart: two patches left, one needed piece above
        // each, each clearable from a spot of its own, and both from one.
        let pocket = square_pocket();
        let breaks = [(18.5, 19.9), (20.1, 21.5)];
        let gap = broken_gap(&pocket, &breaks);
        let pieces: Vec<Path> = (gap.needed(&square(1.9, 38.1)).into_iter())
            .filter(|p| (p.segments[0].start().x - 20.0).abs() < 4.0)
            .collect();
        assert_eq!(pieces.len(), 2);
        assert!(pieces.iter().all(|p| gap.spot_for(p).is_some()));
        let out = gap.with_spots(pieces);
        assert_eq!(out.len(), 1, "one spot for both");
        let line = &out[0].segments;
        assert_eq!(line.len(), 1);
        assert!(line[0].length() <= SPOT_LENGTH_RADII + 1e-12);
        // Everything left on both sides, sampled on its own, within the spot's reach.
        let c = line[0].end();
        let left = left_by(&breaks);
        assert!(left.iter().any(|p| p.x < 20.0) && left.iter().any(|p| p.x > 20.0));
        assert!(left.iter().all(|p| p.distance(c) < 0.95), "{c:?}");
    }

    /// The needed piece of the half level above the break round x = 20 of `gap`.
    fn piece_under_break(gap: &Gap) -> Path {
        (gap.needed(&square(1.9, 38.1)).into_iter())
            .find(|p| (p.segments[0].start().x - 20.0).abs() < 2.0)
            .expect("a piece under the break")
    }

    #[test]
    fn a_spot_across_the_band_clears_what_the_centre_does_not() {
        let pocket = square_pocket();
        let gap = broken_gap(&pocket, &[(18.8, 21.2)]);
        let piece = &piece_under_break(&gap);
        let (centre, _) = enclosing_circle(&outline_points(&piece.segments)).expect("a circle");
        assert!(gap.spot_at(piece, centre).is_none(), "the centre is not enough");
        let spot = gap.spot_for(piece).expect("a spot");
        assert_eq!(spot.segments.len(), 1);
        let (from, c) = (spot.segments[0].start(), spot.segments[0].end());
        assert!((c.x - 20.0).abs() < 1e-9, "{c:?}");
        assert!(from.distance(c) <= SPOT_LENGTH_RADII + 1e-12);
        // What the tool leaves, sampled on its own: within 2.8 of the walls (not inside level
        // k + 1), farther than r from both levels' loops. From the centre its farthest point
        // is 0.91 r away, too near the reach of 0.95 r for the test's margins; from the spot
        // (found across the band, then pulled back towards the loop as far as it still
        // clears the patch) all of it lies within reach.
        let left = left_by(&[(18.8, 21.2)]);
        assert!(left.len() > 100, "{}", left.len());
        let farthest = |q: Point| left.iter().map(|p| p.distance(q)).fold(0.0, f64::max);
        assert!(farthest(centre) > 0.9, "{}", farthest(centre));
        assert!(farthest(c) < 0.95, "{}", farthest(c));
    }

    #[test]
    fn a_spot_is_pulled_towards_the_loop_as_far_as_it_still_clears_its_piece() {
        // The patch of `a_spot_across_the_band_clears_what_the_centre_does_not`: its spot is
        // where the excursion out from the loop of level k (y = 1) ends, pulled towards that
        // loop by halving the way: it stops near the lowest point that still clears the
        // patch, so the excursion is nearly as short as it can be.
        let pocket = square_pocket();
        let gap = broken_gap(&pocket, &[(18.8, 21.2)]);
        let piece = &piece_under_break(&gap);
        let spot = gap.spot_for(piece).expect("a spot");
        let c = spot.segments[0].end();
        assert!(gap.covered_with(piece, &[c]));
        // The lowest point straight below that still clears it, by bisection.
        let (mut lo, mut hi) = (1.0, c.y);
        for _ in 0..40 {
            let m = 0.5 * (lo + hi);
            if gap.covered_with(piece, &[Point::new(c.x, m)]) {
                hi = m;
            } else {
                lo = m;
            }
        }
        assert!(c.y - hi < 0.1 * (c.y - 1.0), "{c:?} could come down to y = {hi}");
    }

    #[test]
    fn pieces_beside_one_long_patch_give_way_to_one_pass() {
        // The loop below broken over 9 mm: a strip of material under 0.8 mm high and about
        // 7.4 mm long above the bottom edge, too long for one spot. The needed piece above it,
        // cut in two as the pieces of two loops beside one patch are, gives way to one
        // straight pass over the strip.
        let pocket = square_pocket();
        let breaks = [(15.5, 24.5)];
        let gap = broken_gap(&pocket, &breaks);
        let piece = (gap.needed(&square(1.9, 38.1)).into_iter())
            .find(|p| (p.segments[0].start().x - 20.0).abs() < 6.0)
            .expect("a piece under the break");
        assert_eq!(piece.segments.len(), 1);
        let s = piece.segments[0];
        let half = |t0: f64, t1: f64| Path {
            segments: vec![s.subsegment(t0, t1)],
            closed: false,
        };
        let halves = vec![vec![half(0.0, 0.5)], vec![half(0.5, 1.0)]];
        assert!(halves.iter().all(|h| gap.spot_for(&h[0]).is_none()));
        let out = gap.clear(halves);
        assert_eq!(out.len(), 1, "one pass for both");
        let pass = &out[0].segments;
        assert!(matches!(pass[..], [Segment::Line(_)]), "{pass:?}");
        assert!(
            pass[0].length() < s.length(),
            "{} {}",
            pass[0].length(),
            s.length()
        );
        // Everything left, sampled on its own, within the pass's reach.
        let left = left_by(&breaks);
        assert!(left.len() > 100, "{}", left.len());
        let farthest = (left.iter())
            .map(|&p| distance_from_segment(&pass[0], p))
            .fold(0.0, f64::max);
        assert!(farthest < 0.95, "{farthest}");
    }

    #[test]
    fn a_triangle_too_wide_for_one_spot_is_covered_from_a_path_through_three() {
        // Material in a triangle 7.5 mm wide and 5 mm high (a patch between two islands and a
        // wall), for a 6 mm tool: round it a circle of 3.9 mm, beyond one spot's fit.
        let fit = SPOTS_FIT_RADII * 3.0;
        let inside = |p: &Point| p.y >= 0.0 && p.y <= 5.0 * (1.0 - p.x.abs() / 3.75);
        let points: Vec<Point> = (0..=150)
            .flat_map(|i| (0..=100).map(move |j| Point::new(-3.75 + 0.05 * i as f64, 0.05 * j as f64)))
            .filter(inside)
            .collect();
        assert!(spots_over(&points, 1, fit).is_none());
        let spots = spots_over(&points, 3, fit).expect("three spots");
        assert_eq!(spots.len(), 3);
        // Every point within the fit of the path through them, the ends the two farthest apart.
        let farthest = (points.iter())
            .map(|&p| distance_to_moves(p, &spots))
            .fold(0.0, f64::max);
        assert!(farthest <= fit, "{farthest}");
        let d = |a: usize, b: usize| spots[a].distance(spots[b]);
        assert!(d(0, 2) >= d(0, 1) && d(0, 2) >= d(1, 2), "{spots:?}");
        // Shorter than the triangle's three sides, what the pieces round it were.
        let length = d(0, 1) + d(1, 2);
        assert!(length < 0.5 * (7.5 + 2.0 * 6.25), "{length}");
    }

    #[test]
    fn paths_lie_as_near_the_level_outside_as_the_reach_allows() {
        // 80 % of a 6 mm tool: g − r and a margin, where half way was 2.4.
        assert!((path_offset(4.8, 3.0) - 1.95).abs() < 1e-12);
        // 98 %: half way is nearer.
        assert!((path_offset(5.88, 3.0) - 2.94).abs() < 1e-12);
    }

    #[test]
    fn halving_keeps_what_is_left_and_less_beyond_it() {
        // Along the half level's edge y = 1.9, the tool on the first loop covers y <= 2 and,
        // from its left edge x = 1, x <= 2; at y = 2 the second loop's corner (2.8, 2.8)
        // covers from x = 2.2. Left: the normals from 2 < x < 2.2, 0.2 mm on each edge beside
        // each corner, 0.1 mm from it.
        let on = |paths: &[Path], p: Point| {
            (paths.iter().enumerate()).find_map(|(k, path)| {
                (path.segments.iter())
                    .any(|s| crate::geom::closest_point(s, p).distance(p) < 1e-9)
                    .then_some(k)
            })
        };
        let length = |p: &Path| -> f64 { p.segments.iter().map(Segment::length).sum() };
        let (coarse, fine) = (corner_paths(0), corner_paths(FINEST_SPLITS));
        assert_eq!(
            (coarse.len(), fine.len()),
            (4, 8),
            "the stretches apart only when finer"
        );
        for (cx, cy) in [(1.9, 1.9), (38.1, 1.9), (38.1, 38.1), (1.9, 38.1)] {
            let inward = |c: f64| if c < 20.0 { 1.0 } else { -1.0 };
            for dir in [Point::new(inward(cx), 0.0), Point::new(0.0, inward(cy))] {
                let at = |t: f64| Point::new(cx + t * dir.x, cy + t * dir.y);
                // Both ends of what is left on one path, at either spread: nothing missed.
                for paths in [&coarse, &fine] {
                    let ends = (on(paths, at(0.1 + 1e-6)), on(paths, at(0.3 - 1e-6)));
                    assert!(ends.0.is_some() && ends.0 == ends.1, "{ends:?} at ({cx}, {cy})");
                }
                // The corner itself is covered: only the coarse paths run through it.
                assert!(on(&coarse, at(0.0)).is_some() && on(&fine, at(0.0)).is_none());
            }
        }
        // Each fine path is what is left and at most a few hundredths of a millimetre more, on
        // the coarse paths (halving only proves more clean).
        for f in &fine {
            assert!(length(f) >= 0.2 - 1e-9 && length(f) < 0.25, "{}", length(f));
            for s in &f.segments {
                assert!(on(&coarse, s.start()).is_some() && on(&coarse, s.end()).is_some());
            }
        }
        let total = |paths: &[Path]| paths.iter().map(length).sum::<f64>();
        assert!(
            total(&fine) < 0.5 * total(&coarse),
            "{} {}",
            total(&fine),
            total(&coarse)
        );
    }
}
