//! What the feed moves at one height sweep, in the order they are cut, for asking "did the tool
//! reach this point before that move?" without a list of neighbours per move.
//!
//! Moves much shorter than the tool (a profile of 100 000 lines makes moves of hundredths of a
//! millimetre) are taken in runs: a run whose moves all lie within a small deviation `δ` of the
//! straight line between its ends stands for them as that line, with a radius smaller by `δ`.
//! Its sweep lies inside theirs, so what is proven against it holds against them.

use super::rows::row_spans;
use crate::geom::{distance_from_segment, Aabb, Line, Point, Segment};

/// Most cells of a cover's grid: where the tool is small against the drawing the cells grow
/// beyond the tool radius (a query then scans more moves, but the grid stays in memory).
const MOST_CELLS: f64 = 4.0e6;

/// Most cells a cover's grid spans for each run, and besides (the bench's drawings span 8 to
/// 80 for each).
const MOST_CELLS_PER_RUN: usize = 256;
/// See [`MOST_CELLS_PER_RUN`].
const MOST_LISTED: usize = 1 << 20;

/// Runs from which the cells they reach are found on more than one thread.
const PARALLEL_RUNS: usize = 1024;

/// Moves shorter than this, in tool radii, may be taken in runs.
const SHORT_RADII: f64 = 0.125;

/// Longest run of short moves taken as one line, in tool radii.
const LONGEST_RUN_RADII: f64 = 0.5;

/// How far a run's moves may lie from the line that stands for them, in tool radii (the
/// radius of that line's sweep is smaller by as much): a thousandth, the finest interval the
/// proofs look at.
const DEVIATION_RADII: f64 = 0.001;

/// One feed move at the cover's height: its planar path, its box, and whether the next move of
/// the cover follows it on at once in the same direction (the circle round that joint then
/// holds no point of the edge of the two sweeps but the ends of their offsets).
#[derive(Clone, Copy, Debug)]
pub struct Sweep {
    pub segment: Segment,
    /// Its index among the path's moves.
    pub order: usize,
    pub smooth_next: bool,
}

/// What stands for a run of consecutive sweeps (most often one): a path whose sweep with the
/// radius less `shrink` lies in theirs.
#[derive(Clone, Copy, Debug)]
pub struct Run {
    pub segment: Segment,
    pub bbox: Aabb,
    /// 0 where the run is one sweep, its path exactly.
    pub shrink: f64,
    /// Its first sweep and one past its last.
    pub first: usize,
    pub end: usize,
    /// Whether the next run follows it on at once in the same direction.
    pub smooth_next: bool,
}

/// The run that reached a point last (see [`Cover::reaches_held`]): how near, its path less
/// its shrink, it came to where.
#[derive(Clone, Copy, Debug)]
pub struct Held {
    run: usize,
    at: Point,
    near: f64,
}

impl Default for Held {
    fn default() -> Held {
        Held {
            run: 0,
            at: Point::new(0.0, 0.0),
            near: f64::INFINITY,
        }
    }
}

/// The sweeps of the tool (every point within `r` of a move's centre path) of the feed moves at
/// one height, in path order, as runs on a uniform grid: each cell lists, in path order, the
/// runs whose sweep reaches into it. The runs before a given one are then a prefix of each
/// list.
pub struct Cover {
    pub sweeps: Vec<Sweep>,
    pub runs: Vec<Run>,
    /// The run that holds each sweep.
    run_of: Vec<u32>,
    pub r: f64,
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Where each cell's list starts in `entries` (one more than the cells).
    starts: Vec<u32>,
    entries: Vec<u32>,
}

impl Cover {
    /// The cover of `sweeps` (in path order) for a tool of radius `r`, or None where its
    /// grid would list more than a few dozen cells for each run (moves far longer than the
    /// tool: a drawing in metres read as millimetres).
    pub fn new(sweeps: Vec<Sweep>, r: f64) -> Option<Cover> {
        let runs = runs_of(&sweeps, r);
        let mut all = Aabb::EMPTY;
        for s in &runs {
            all = all.union(&s.bbox);
        }
        if all.is_empty() {
            all = Aabb::from_points(Point::new(0.0, 0.0), Point::new(0.0, 0.0));
        }
        let all = all.inflated(r);
        let area = all.width() * all.height();
        let cell = r.max((area / MOST_CELLS).sqrt()).max(f64::MIN_POSITIVE);
        let count = |extent: f64| ((extent / cell).ceil() as usize).clamp(1, MOST_CELLS as usize);
        let (nx, ny) = (count(all.width()), count(all.height()));
        let mut run_of = vec![0u32; sweeps.len()];
        for (k, run) in runs.iter().enumerate() {
            run_of[run.first..run.end].fill(k as u32);
        }
        let mut cover = Cover {
            sweeps,
            runs,
            run_of,
            r,
            origin: all.min,
            cell,
            nx,
            ny,
            starts: vec![0; nx * ny + 1],
            entries: Vec::new(),
        };
        let spans: usize = (cover.runs.iter())
            .map(|run| {
                let (x0, y0, x1, y1) = cover.cell_range(&run.bbox.inflated(r));
                (x1 - x0 + 1) * (y1 - y0 + 1)
            })
            .sum();
        if spans > MOST_CELLS_PER_RUN * cover.runs.len() + MOST_LISTED {
            return None;
        }
        // The runs each cell lists, gathered in path order and sorted by cell (stable, by
        // counting): each list ends up in path order.
        // The runs in pieces, in order, shared out among threads where they are many.
        let n = cover.runs.len();
        let pieces = if n >= PARALLEL_RUNS {
            16 * crate::parallel::cores()
        } else {
            1
        };
        let piece = n.div_ceil(pieces).max(1);
        let ranges: Vec<std::ops::Range<usize>> =
            (0..n).step_by(piece).map(|a| a..(a + piece).min(n)).collect();
        let pairs: Vec<Vec<(u32, u32)>> = crate::parallel::map_each(&ranges, |range| {
            let mut pairs = Vec::with_capacity(spans * range.len() / n.max(1));
            for i in range.clone() {
                cover.for_each_cell_reached(i, |c| pairs.push((c as u32, i as u32)));
            }
            pairs
        });
        let mut counts = vec![0u32; nx * ny + 1];
        for &(c, _) in pairs.iter().flatten() {
            counts[c as usize + 1] += 1;
        }
        for c in 0..nx * ny {
            counts[c + 1] += counts[c];
        }
        cover.starts.copy_from_slice(&counts);
        let mut entries = vec![0u32; counts[nx * ny] as usize];
        for &(c, i) in pairs.iter().flatten() {
            entries[counts[c as usize] as usize] = i;
            counts[c as usize] += 1;
        }
        cover.entries = entries;
        Some(cover)
    }

    /// How many runs lie wholly before sweep `i`: what a move from sweep `i` on is proven
    /// against (the run that holds it and the sweeps of that run before it are left out).
    pub fn runs_before(&self, i: usize) -> usize {
        self.run_of[i] as usize
    }

    /// Calls `f` with every cell that holds a point within the radius of run `i`'s path (and
    /// maybe a few more): those of the cells its box spans whose centre lies within the radius
    /// and half a cell's diagonal, row by row.
    fn for_each_cell_reached(&self, i: usize, mut f: impl FnMut(usize)) {
        let s = &self.runs[i];
        let (x0, y0, x1, y1) = self.cell_range(&s.bbox.inflated(self.r));
        // A hair more, so that rounding in the spans loses no centre at the limit.
        let reach = (self.r + 0.5 * std::f64::consts::SQRT_2 * self.cell) * (1.0 + 1e-9);
        for y in y0..=y1 {
            let centre_y = self.origin.y + (y as f64 + 0.5) * self.cell;
            for (lo, hi) in row_spans(&s.segment, &s.bbox, centre_y, reach)
                .into_iter()
                .flatten()
            {
                // The columns whose centres lie in the span, within the box's: from the first
                // whole column at or after its start to the last at or before its end.
                let (a, b) = (
                    (lo - self.origin.x) / self.cell - 0.5,
                    (hi - self.origin.x) / self.cell - 0.5,
                );
                if !(a <= x1 as f64 && b >= x0 as f64) {
                    continue;
                }
                let a = a.max(x0 as f64);
                let first = floor_of_positive(a) + usize::from(a > floor_of_positive(a) as f64);
                let last = floor_of_positive(b.min(x1 as f64)).min(x1);
                for x in first..=last {
                    f(y * self.nx + x);
                }
            }
        }
    }

    /// The cells a box spans, clamped to the grid: first and last column, first and last row.
    fn cell_range(&self, b: &Aabb) -> (usize, usize, usize, usize) {
        let at = |v: f64, o: f64, n: usize| floor_of_positive((v - o) / self.cell).min(n - 1);
        (
            at(b.min.x, self.origin.x, self.nx),
            at(b.min.y, self.origin.y, self.ny),
            at(b.max.x, self.origin.x, self.nx),
            at(b.max.y, self.origin.y, self.ny),
        )
    }

    /// The runs listed in cell `c`, in path order.
    fn listed_in(&self, c: usize) -> &[u32] {
        &self.entries[self.starts[c] as usize..self.starts[c + 1] as usize]
    }

    /// The runs before `before` listed in cell `c`.
    fn listed_before(&self, c: usize, before: usize) -> &[u32] {
        let list = self.listed_in(c);
        &list[..list.partition_point(|&i| (i as usize) < before)]
    }

    /// The cell holding `p`, if the grid does (no sweep reaches a point outside it).
    fn cell_of(&self, p: Point) -> Option<usize> {
        let x = (p.x - self.origin.x) / self.cell;
        let y = (p.y - self.origin.y) / self.cell;
        let (cx, cy) = (floor_of_positive(x), floor_of_positive(y));
        (x >= 0.0 && y >= 0.0 && cx < self.nx && cy < self.ny).then(|| cy * self.nx + cx)
    }

    /// By how much one of the runs before `before` is proven to reach nearer to `p` than
    /// `reach` (at most the tool radius), if one does: how much nearer than `reach` less its
    /// shrink its path comes to `p` (every point nearer to `p` than that is reached by it
    /// too). `hint` is the one that answered last (asked first) and is left at the one that
    /// answers.
    pub fn reaches_by(&self, p: Point, reach: f64, before: usize, hint: &mut usize) -> Option<f64> {
        if reach <= 0.0 {
            return None;
        }
        let by = |s: &Run| Some(reach - s.shrink - distance_from_segment(&s.segment, p)).filter(|&m| m > 0.0);
        if let Some(m) = self.runs[..before.min(self.runs.len())].get(*hint).and_then(by) {
            return Some(m);
        }
        let c = self.cell_of(p)?;
        let reach_sq = reach * reach;
        // The list is in path order: scanned up to `before` (no search for where that is).
        let (i, m) = (self.listed_in(c).iter())
            .take_while(|&&i| (i as usize) < before)
            .filter(|&&i| self.runs[i as usize].bbox.distance_sq(p) < reach_sq)
            .find_map(|&i| by(&self.runs[i as usize]).map(|m| (i as usize, m)))?;
        *hint = i;
        Some(m)
    }

    /// Whether one of the runs before `before` reaches nearer to `p` than `reach` (see
    /// [`Cover::reaches_by`]), for queries near one another (along a walk, along an edge):
    /// `held` is what answered the last, and a point that lies near enough to where it held
    /// answers without a distance (distances change no faster than the point moves).
    pub fn reaches_held(&self, p: Point, reach: f64, before: usize, held: &mut Held) -> bool {
        if held.run < before && held.near + p.distance(held.at) < reach {
            return true;
        }
        match self.reaches_by(p, reach, before, &mut held.run) {
            Some(by) => {
                (held.at, held.near) = (p, reach - by);
                true
            }
            None => {
                held.near = f64::INFINITY;
                false
            }
        }
    }

    /// Adds to `cells` the cells that `b` spans.
    pub fn cells_of(&self, b: &Aabb, cells: &mut Vec<usize>) {
        let (x0, y0, x1, y1) = self.cell_range(b);
        for y in y0..=y1 {
            cells.extend((x0..=x1).map(|x| y * self.nx + x));
        }
    }

    /// The runs before `before` listed in cell `c`.
    pub fn listed(&self, c: usize, before: usize) -> impl Iterator<Item = usize> + '_ {
        self.listed_before(c, before).iter().map(|&i| i as usize)
    }

    /// The exact paths of the sweeps before `before` (a run index) that come within `eps` of
    /// `p`, and maybe others (of runs that do).
    pub fn sweeps_at(&self, p: Point, before: usize, eps: f64) -> impl Iterator<Item = Segment> + '_ {
        let list = self.cell_of(p).map_or(&[][..], |c| self.listed_before(c, before));
        (list.iter())
            .map(|&i| &self.runs[i as usize])
            .filter(move |run| run.bbox.distance_sq(p) <= (eps + run.shrink).powi(2))
            .filter(move |run| distance_from_segment(&run.segment, p) <= eps + run.shrink)
            .flat_map(move |run| self.sweeps[run.first..run.end].iter().map(|s| s.segment))
    }
}

/// The floor of `v`, or 0 where it is negative (or not a number): a truncation, as `floor` is a
/// call on x86-64's baseline instruction set, and this runs for every probe.
fn floor_of_positive(v: f64) -> usize {
    v.max(0.0) as usize
}

/// The runs that stand for `sweeps`: each sweep alone, but for sweeps shorter than
/// [`SHORT_RADII`] one after another, taken together up to [`LONGEST_RUN_RADII`] while every
/// point of theirs lies within [`DEVIATION_RADII`] of the line between the run's ends.
///
/// Walked from a run's start `a`, each later joint `p` at distance `d` asks the line's
/// direction to lie within `asin(δ/d)` of `p`'s (then `p` is within `δ` of the line, and so is
/// the move before it, a straight line or an arc flatter than the rest of `δ`); the
/// directions allowed narrow as the run grows, and it ends where none is left.
fn runs_of(sweeps: &[Sweep], r: f64) -> Vec<Run> {
    let short = SHORT_RADII * r;
    let delta = DEVIATION_RADII * r;
    // Of the deviation, what an arc's bulge may take, and what is left for the joints.
    let (bulge, joints) = (0.25 * delta, 0.75 * delta);
    let flat = |s: &Segment| match s {
        Segment::Line(_) => true,
        Segment::Arc(a) => {
            let half = 0.5 * a.sweep().abs();
            half < 0.5 * std::f64::consts::PI && a.radius() * (1.0 - half.cos()) <= bulge
        }
    };
    let single = |i: usize| Run {
        segment: sweeps[i].segment,
        bbox: sweeps[i].segment.bbox(),
        shrink: 0.0,
        first: i,
        end: i + 1,
        smooth_next: sweeps[i].smooth_next,
    };
    let mut out: Vec<Run> = Vec::with_capacity(sweeps.len());
    let mut i = 0;
    while i < sweeps.len() {
        let first = &sweeps[i].segment;
        if first.length() >= short || !flat(first) {
            out.push(single(i));
            i += 1;
            continue;
        }
        let a = first.start();
        let Some(axis) = (first.end() - a).normalized() else {
            out.push(single(i));
            i += 1;
            continue;
        };
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut far, mut along, mut last) = (0.0f64, 0.0, i);
        let mut k = i;
        while k < sweeps.len() {
            let s = &sweeps[k];
            let continues = k == i
                || (s.order == sweeps[k - 1].order + 1
                    && sweeps[k - 1].segment.end().distance(s.segment.start()) <= 1e-9 * r);
            along += s.segment.length();
            if !continues || s.segment.length() >= short || !flat(&s.segment) || along > LONGEST_RUN_RADII * r
            {
                break;
            }
            let v = s.segment.end() - a;
            let d = v.length();
            let angle = axis.cross(v).atan2(axis.dot(v));
            if !(lo..=hi).contains(&angle) || d < far {
                break;
            }
            last = k;
            if d > joints {
                let half = (joints / d).asin();
                (lo, hi) = (lo.max(angle - half), hi.min(angle + half));
            }
            far = d;
            k += 1;
        }
        if last == i {
            out.push(single(i));
            i += 1;
            continue;
        }
        let segment = Segment::Line(Line::new(a, sweeps[last].segment.end()));
        out.push(Run {
            segment,
            bbox: segment.bbox(),
            shrink: delta,
            first: i,
            end: last + 1,
            smooth_next: false,
        });
        i = last + 1;
    }
    // A joint is smooth only between two moves taken alone: a run's line leaves in another
    // direction than its first move.
    for k in 0..out.len() {
        let next_alone = out.get(k + 1).is_some_and(|n| n.end - n.first == 1);
        out[k].smooth_next &= out[k].end - out[k].first == 1 && next_alone;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Line;

    fn sweep(x0: f64, y0: f64, x1: f64, y1: f64, order: usize) -> Sweep {
        let segment = Segment::Line(Line::new(Point::new(x0, y0), Point::new(x1, y1)));
        Sweep {
            segment,
            order,
            smooth_next: false,
        }
    }

    #[test]
    fn reaches_only_what_was_swept_before() {
        let cover = Cover::new(
            vec![
                sweep(0.0, 0.0, 50.0, 0.0, 0),
                sweep(0.0, 10.0, 50.0, 10.0, 1),
                sweep(0.0, 40.0, 50.0, 3.0, 2),
            ],
            3.0,
        )
        .unwrap();
        assert_eq!(cover.runs.len(), 3);
        let mut hint = 0;
        let p = Point::new(25.0, 2.9);
        assert!(cover.reaches_by(p, 3.0, 1, &mut hint).is_some());
        assert!(cover.reaches_by(p, 2.8, 1, &mut hint).is_none());
        assert!(cover.reaches_by(p, 3.0, 0, &mut hint).is_none());
        let q = Point::new(25.0, 12.5);
        assert!(cover.reaches_by(q, 3.0, 1, &mut hint).is_none());
        assert!(cover.reaches_by(q, 3.0, 2, &mut hint).is_some());
        assert!(cover
            .reaches_by(Point::new(-100.0, 0.0), 3.0, 3, &mut hint)
            .is_none());
        let mut cells = Vec::new();
        cover.cells_of(
            &Aabb::from_points(Point::new(20.0, 9.0), Point::new(21.0, 11.0)),
            &mut cells,
        );
        let near: Vec<usize> = cells.iter().flat_map(|&c| cover.listed(c, 3)).collect();
        assert!(near.contains(&1) && !near.contains(&0));
    }

    #[test]
    fn what_held_a_point_holds_the_points_near_it_and_no_farther() {
        let cover = Cover::new(
            vec![sweep(0.0, 0.0, 50.0, 0.0, 0), sweep(0.0, 4.0, 50.0, 4.0, 1)],
            3.0,
        )
        .unwrap();
        let mut held = Held::default();
        assert!(cover.reaches_held(Point::new(10.0, 1.0), 3.0, 1, &mut held));
        assert!((held.near - 1.0).abs() < 1e-12);
        // Within 2 of where it held: held still, where it was found.
        assert!(cover.reaches_held(Point::new(10.0, 2.9), 3.0, 1, &mut held));
        assert_eq!(held.at, Point::new(10.0, 1.0));
        // Farther: measured again, and out of reach of the first move.
        assert!(!cover.reaches_held(Point::new(10.0, 3.5), 3.0, 1, &mut held));
        // The second move reaches it, but only from the second on.
        assert!(cover.reaches_held(Point::new(10.0, 3.5), 3.0, 2, &mut held));
        assert!(!cover.reaches_held(Point::new(10.0, 3.4), 3.0, 1, &mut held));
    }

    #[test]
    fn a_cover_built_on_several_threads_answers_as_every_move_measured() {
        // 1600 moves of 5 mm in a raster of 40 rows, more than are listed on one thread;
        // points all over it, each asked of the moves before a changing one.
        let sweeps: Vec<Sweep> = (0..1600)
            .map(|k| {
                let (row, col) = ((k / 40) as f64, (k % 40) as f64);
                let y = row * 2.5 + 0.3 * col;
                sweep(col * 5.0, y, col * 5.0 + 5.0, y + 1.0, k)
            })
            .collect();
        assert!(sweeps.len() >= PARALLEL_RUNS);
        let r = 2.0;
        let cover = Cover::new(sweeps.clone(), r).unwrap();
        let mut random = crate::test_random::Lcg::new(12345);
        let mut next = || random.unit();
        for _ in 0..4000 {
            let p = Point::new(next() * 210.0 - 5.0, next() * 115.0 - 5.0);
            let before = (next() * 1601.0) as usize;
            let measured = sweeps[..before]
                .iter()
                .any(|s| distance_from_segment(&s.segment, p) < r);
            assert_eq!(
                cover.reaches_by(p, r, before, &mut 0).is_some(),
                measured,
                "{p:?} {before}"
            );
        }
    }

    #[test]
    fn every_point_within_the_radius_is_found() {
        // A long diagonal and a point beside it anywhere along: the grid's cells that the
        // move's sweep reaches all list it.
        let cover = Cover::new(vec![sweep(0.0, 0.0, 97.0, 61.0, 0)], 2.0).unwrap();
        let d = Point::new(97.0, 61.0);
        let n = Point::new(-61.0, 97.0);
        let (dl, nl) = ((d.x * d.x + d.y * d.y).sqrt(), (n.x * n.x + n.y * n.y).sqrt());
        for k in 0..=200 {
            let t = k as f64 / 200.0;
            for u in [-1.99, -1.0, 0.0, 1.0, 1.99] {
                let p = Point::new(t * d.x + u * n.x / nl, t * d.y + u * n.y / nl);
                assert!(cover.reaches_by(p, 2.0, 1, &mut 0).is_some(), "{p:?} {dl}");
            }
        }
    }
}

#[cfg(test)]
mod run_tests {
    use super::*;
    use crate::geom::Arc;

    #[test]
    fn short_moves_along_a_curve_are_taken_in_runs_inside_their_sweep() {
        // A circle of radius 50 in 20 000 lines (0.016 mm each), tool radius 3: runs of at
        // most 1.5 mm, each within 0.003 mm of its moves, all of them in order.
        let n = 20_000;
        let c = Point::new(0.0, 0.0);
        let at = |k: usize| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            Point::new(c.x + 50.0 * t.cos(), c.y + 50.0 * t.sin())
        };
        let sweeps: Vec<Sweep> = (0..n)
            .map(|k| {
                let segment = Segment::Line(Line::new(at(k), at(k + 1)));
                Sweep {
                    segment,
                    order: k,
                    smooth_next: false,
                }
            })
            .collect();
        let runs = runs_of(&sweeps, 3.0);
        assert!(runs.len() < n / 20, "{}", runs.len());
        let mut next = 0;
        for run in &runs {
            assert_eq!(run.first, next);
            next = run.end;
            assert!(run.segment.length() <= 1.5 + 1e-9);
            for s in &sweeps[run.first..run.end] {
                assert!(distance_from_segment(&run.segment, s.segment.end()) <= run.shrink + 1e-12);
            }
        }
        assert_eq!(next, n);
        // A sharp corner ends a run; long moves and arcs stand alone.
        let corner = [
            Segment::Line(Line::new(Point::new(0.0, 0.0), Point::new(0.1, 0.0))),
            Segment::Line(Line::new(Point::new(0.1, 0.0), Point::new(0.1, 0.1))),
            Segment::Arc(Arc::new(
                Point::new(0.1, 5.1),
                5.0,
                -0.5 * std::f64::consts::PI,
                1.0,
            )),
        ];
        let sweeps: Vec<Sweep> = (corner.iter().enumerate())
            .map(|(k, &segment)| Sweep {
                segment,
                order: k,
                smooth_next: false,
            })
            .collect();
        assert_eq!(runs_of(&sweeps, 3.0).len(), 3);
    }
}
