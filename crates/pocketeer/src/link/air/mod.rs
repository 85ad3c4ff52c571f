//! Runs of a tool path that cut nothing, and the straight moves that replace them.
//!
//! The linker cuts every loop and clean-up path of the plan whole, but where loops of several
//! levels and links at depth crowd together (between islands a grid apart, round the tips of a
//! level's small parts) some of that length sweeps only stock already cut: on the 10 × 6 island
//! grid at 40 % stepover 1.5 m of its 7.9 m of loops. [`shortcut_air`] takes the finished path
//! walk by walk (runs of feed moves at one height, each starting where the one before ends),
//! finds by probes the stretches that may sweep nothing new and that a straight move would
//! shorten, proves each (see [`proof::sweeps_nothing`]) and replaces it by straight moves
//! between its points that are proven to sweep nothing either. What the path leaves of the
//! stock is the same, and so is the engagement of every move that touches stock: only moves
//! through cleared stock change.

mod cover;
mod proof;
mod rows;

use super::walk::emit;
use crate::geom::{Line, Point, Segment, Vector};
use crate::toolpath::{Feed, Move, Point3, Toolpath};
use cover::{Cover, Held, Sweep};
use proof::{first_reach, sweeps_nothing, Earlier, Proof, Scratch, ACROSS, PROBE_STEP_RADII};
use std::collections::BTreeMap;

/// The least a stretch that may sweep nothing new must be longer than the straight way between
/// its ends, in tool radii, to be proven: in the middle of a straight move, or along a gentle
/// curve, nothing is gained.
const LEAST_GAIN_RADII: f64 = 0.5;

/// The least a straight move must be shorter than the stretch it replaces, in tool radii.
const LEAST_CHORD_GAIN_RADII: f64 = 0.05;

/// How many stations apart the coarse probes of a walk are (see [`Walk::stretches`]).
const COARSE_STEP: usize = 4;

/// How many coarse stations apart the first probed along a walk are (a power of two; see
/// [`Station`]).
const WIDEST_COARSE: usize = 4;

/// What is known of a coarse station of a walk. The coarse stations are probed widest apart
/// first, then halfway between: one between two in stock is probed only where the walk between
/// those two could gain enough (as a stretch must, and none between them gains more), and is
/// sealed otherwise, as is one beside a sealed one (it lies between the same two). A coarse
/// station is asked first only the probes most likely to lie in stock (see
/// [`Probes::maybe_covered`]): where they lie in earlier sweeps, the station may be covered,
/// and its other probes are asked only where a stretch through it could gain enough.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Station {
    Unknown,
    MaybeCovered,
    InStock,
    /// Not probed: no stretch through it can gain enough.
    Sealed,
}

/// Most coarse stations of a walk for each of its moves, and besides (the bench's drawings
/// probe 3 to 25 for each).
const MOST_STATIONS_PER_MOVE: usize = 64;
/// See [`MOST_STATIONS_PER_MOVE`].
const MOST_STATIONS: usize = 4096;

/// Probes of a station in front of the tool, in tool radii along and across its way (beside
/// those across it, [`ACROSS`]): where the moves are short, the one just before covers all the
/// probes across the next, but none of these.
const AHEAD: [(f64, f64); 3] = [(0.999_999, 0.0), (DIAGONAL, DIAGONAL), (DIAGONAL, -DIAGONAL)];

/// Along and across for a probe in front of the tool at 45°, just inside its circle.
const DIAGONAL: f64 = 0.999_999 * std::f64::consts::FRAC_1_SQRT_2;

/// Probes of a station in all.
const PROBES: usize = ACROSS.len() + AHEAD.len();

/// The probes a coarse station is asked first (besides the one that lay in stock at the last
/// station not covered), as most likely to lie in stock: at both edges of the sweep and
/// straight ahead.
const FIRST_PROBES: [usize; 3] = [0, 1, ACROSS.len()];

/// The shortest stretch that is split to be proven in parts, in tool radii.
const FINEST_STRETCH_RADII: f64 = 0.5;

/// How far on either side of where a stretch first reaches stock it is cut back, in tool radii.
const WITNESS_GAP_RADII: f64 = 0.25;

/// Sweeps at one height from which the walks are shortened on more than one thread.
const PARALLEL_SWEEPS: usize = 1024;

/// How many ends along the rest of a stretch a straight move from where the tool stands is
/// tried to, farthest first.
const MOST_CHORD_ENDS: usize = 8;

/// `path` with the stretches of feed moves at depth that sweep nothing the path had not swept
/// before (see the module's documentation) replaced, where shorter, by straight feed moves that
/// sweep nothing either, for a tool of radius `r`.
pub fn shortcut_air(path: Toolpath, r: f64) -> Toolpath {
    if !(r > 0.0 && r.is_finite()) {
        return path;
    }
    // The feed moves at one height, by height.
    let mut levels: BTreeMap<u64, Vec<Sweep>> = BTreeMap::new();
    for (k, (from, m)) in path.moves_from(0).enumerate() {
        if let Some(segment) = level_cut(from, m) {
            levels.entry(from.z.to_bits()).or_default().push(Sweep {
                segment,
                order: k,
                smooth_next: false,
            });
        }
    }
    // Each walk's moves replaced, by the index of its first move: the index of its last and
    // the new moves.
    let mut replaced: BTreeMap<usize, (usize, Vec<Move>)> = BTreeMap::new();
    for (z, mut sweeps) in levels {
        let z = f64::from_bits(z);
        mark_smooth(&mut sweeps, r);
        let Some(cover) = Cover::new(sweeps, r) else {
            continue;
        };
        let walks = walks(&cover);
        let shorten = |walk: &Walk| {
            let kept = walk.shortened(&cover, &mut Scratch::default());
            kept.iter()
                .any(|k| matches!(k, Kept::Chord(_)))
                .then(|| walk.emit(&cover, &kept, &path.moves, z))
        };
        // Walks are few and of very different lengths: shared out one by one, where there is
        // enough work for a second thread.
        let shortened = if cover.sweeps.len() >= PARALLEL_SWEEPS {
            crate::parallel::map_each(&walks, shorten)
        } else {
            walks.iter().map(shorten).collect()
        };
        for (walk, moves) in walks.iter().zip(shortened) {
            if let Some(moves) = moves {
                let last = cover.sweeps[walk.first + walk.ends.len() - 1].order;
                replaced.insert(cover.sweeps[walk.first].order, (last, moves));
            }
        }
    }
    if replaced.is_empty() {
        return path;
    }
    let mut out = Toolpath::new(path.start);
    let mut skip_to = 0;
    for (k, m) in path.moves.into_iter().enumerate() {
        if k < skip_to {
            continue;
        }
        if let Some((last, new)) = replaced.remove(&k) {
            out.moves.extend(new);
            skip_to = last + 1;
        } else {
            out.moves.push(m);
        }
    }
    out
}

/// The planar path of `m` from `from` when it is a feed move at one height that moves in XY.
fn level_cut(from: Point3, m: &Move) -> Option<Segment> {
    let level = (m.to().z - from.z).abs() <= 1e-9;
    let cut = matches!(
        m,
        Move::Line { feed: Feed::Cut, .. } | Move::Arc { feed: Feed::Cut, .. }
    );
    let s = m.planar(from);
    (level && cut && s.length() > 0.0).then_some(s)
}

/// Whether `a` ends where `b` starts (within `eps`).
fn joins(a: &Sweep, b: &Sweep, eps: f64) -> bool {
    b.order == a.order + 1 && a.segment.end().distance(b.segment.start()) <= eps
}

/// Marks the sweeps that the next follows on at once in the same direction.
fn mark_smooth(sweeps: &mut [Sweep], r: f64) {
    let eps = 1e-9 * r;
    for i in 0..sweeps.len().saturating_sub(1) {
        let (a, b) = (&sweeps[i], &sweeps[i + 1]);
        sweeps[i].smooth_next =
            joins(a, b, eps) && (a.segment.tangent_at(1.0) - b.segment.tangent_at(0.0)).length() <= 1e-9;
    }
}

/// The walks of a cover: runs of its sweeps, each starting where the one before ends.
fn walks(cover: &Cover) -> Vec<Walk> {
    let eps = 1e-9 * cover.r;
    let mut out: Vec<Walk> = Vec::new();
    for (i, s) in cover.sweeps.iter().enumerate() {
        let len = s.segment.length();
        match out.last_mut() {
            Some(w) if joins(&cover.sweeps[i - 1], s, eps) => {
                let end = w.ends[w.ends.len() - 1] + len;
                w.ends.push(end);
            }
            _ => out.push(Walk {
                first: i,
                ends: vec![len],
            }),
        }
    }
    out
}

/// The runs of two or more stations from 0 to `n` that are all `covered`, by first and last.
fn covered_runs(n: usize, covered: impl Fn(usize) -> bool) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i <= n {
        let mut j = i;
        while covered(i) && j < n && covered(j + 1) {
            j += 1;
        }
        if j > i {
            out.push((i, j));
        }
        i = j + 1;
    }
    out
}

/// A run of a cover's sweeps, each starting where the one before ends, measured along.
struct Walk {
    /// Its first sweep.
    first: usize,
    /// The length along the walk to the end of each of its sweeps.
    ends: Vec<f64>,
}

/// The probes of a walk's stations, asked in order along it.
struct Probes<'w> {
    walk: &'w Walk,
    cover: &'w Cover,
    /// For each probe, the run that held it last (asked first, and not measured while the
    /// probe stays near enough to where it held it): the runs beside a walk change seldom, and
    /// each side has its own.
    held: [Held; PROBES],
    /// The probe that lay in stock at the last station that was not covered.
    failed: usize,
}

impl<'w> Probes<'w> {
    /// The probes of `walk`'s stations against `cover`, nothing asked yet.
    fn new(walk: &'w Walk, cover: &'w Cover) -> Probes<'w> {
        Probes {
            walk,
            cover,
            held: [Held::default(); PROBES],
            failed: 0,
        }
    }

    /// True when the station `s` along the walk has all its probes (across the sweep and in
    /// front) in what the moves before its own swept.
    fn covered(&mut self, s: f64) -> bool {
        self.covered_by(s, usize::MAX)
    }

    /// False when the station `s` is not covered, as [`Probes::covered`] tells, by one of the
    /// probes most likely to lie in stock ([`FIRST_PROBES`], after the one that did at the
    /// last station not covered); true where it may be.
    fn maybe_covered(&mut self, s: f64) -> bool {
        self.covered_by(s, FIRST_PROBES.len() + 1)
    }

    /// True when the first `count` of the station's probes (all of them, from [`PROBES`] on)
    /// lie in what the moves before it swept: the one that lay in stock at the last station
    /// not covered, then those of [`FIRST_PROBES`], then the rest.
    fn covered_by(&mut self, s: f64, count: usize) -> bool {
        let (walk, cover) = (self.walk, self.cover);
        let r = cover.r;
        let (i, t) = walk.locate(s);
        let segment = &cover.sweeps[i].segment;
        let (p, tangent) = (segment.point_at(t), segment.tangent_at(t));
        let reach = r * (1.0 + 1e-9);
        let before = cover.runs_before(i);
        let probe = |k: usize| probe_point(p, tangent, k, r);
        // The probe that lay in stock at the last station first: along a loop that cuts, the
        // same one does at the next. (A probe asked twice answers the second time from where
        // it was held.)
        let first = self.failed;
        let held = &mut self.held;
        let rest = (1..PROBES)
            .map(|k| (first + k) % PROBES)
            .filter(|k| !FIRST_PROBES.contains(k));
        match (std::iter::once(first).chain(FIRST_PROBES).chain(rest))
            .take(count)
            .find(|&k| !cover.reaches_held(probe(k), reach, before, &mut held[k]))
        {
            Some(k) => {
                self.failed = k;
                false
            }
            None => true,
        }
    }
}

/// Where the station at `p`, the tool going along `tangent` (of length 1), has its probe `k`
/// (of [`PROBES`]: those across its sweep, then those in front) for a tool of radius `r`.
fn probe_point(p: Point, tangent: Vector, k: usize, r: f64) -> Point {
    let normal = tangent.perp();
    match k.checked_sub(ACROSS.len()) {
        None => p + normal * (ACROSS[k] * r),
        Some(j) => p + (tangent * AHEAD[j].0 + normal * AHEAD[j].1) * r,
    }
}

/// What is emitted along a walk: the walk between two lengths along it, or a straight move.
#[derive(Clone, Copy, Debug)]
enum Kept {
    Along(f64, f64),
    Chord(Line),
}

impl Walk {
    fn length(&self) -> f64 {
        self.ends[self.ends.len() - 1]
    }

    /// The sweep (index in the cover) and its parameter at length `s` along the walk.
    fn locate(&self, s: f64) -> (usize, f64) {
        let j = self.ends.partition_point(|&e| e < s).min(self.ends.len() - 1);
        (self.first + j, self.param_on(j, s))
    }

    /// The parameter on the walk's `j`-th sweep (from its first) at length `s` along the walk.
    fn param_on(&self, j: usize, s: f64) -> f64 {
        let start = if j == 0 { 0.0 } else { self.ends[j - 1] };
        let len = self.ends[j] - start;
        // Within rounding of a move's end is at it.
        let snap = 1e-12 * (1.0 + self.ends[j]);
        if self.ends[j] - s <= snap {
            1.0
        } else if len > 0.0 {
            ((s - start) / len).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The walk's point at length `s` along it: a move's own end exactly where `s` is there (a
    /// straight move to the walk's end ends where the walk did, to the last digit).
    fn point_at(&self, cover: &Cover, s: f64) -> Point {
        let (i, t) = self.locate(s);
        let segment = &cover.sweeps[i].segment;
        match t {
            t if t >= 1.0 => segment.end(),
            t if t <= 0.0 => segment.start(),
            t => segment.point_at(t),
        }
    }

    /// The walk from `a` to `b` along it, as pieces of its sweeps.
    fn pieces(&self, cover: &Cover, a: f64, b: f64) -> Vec<Segment> {
        let ((i0, t0), (i1, t1)) = (self.locate(a), self.locate(b));
        (i0..=i1)
            .map(|i| {
                let (u0, u1) = (if i == i0 { t0 } else { 0.0 }, if i == i1 { t1 } else { 1.0 });
                cover.sweeps[i].segment.subsegment(u0, u1)
            })
            .filter(|s| s.length() > 0.0)
            .collect()
    }

    /// What a stretch starting `a` along the walk is proven against: the sweeps before it.
    fn earlier_at<'c>(&self, cover: &'c Cover, a: f64) -> Earlier<'c> {
        let (i, t) = self.locate(a);
        Earlier {
            cover,
            before: cover.runs_before(i),
            extra: (t > 0.0).then(|| cover.sweeps[i].segment.subsegment(0.0, t)),
        }
    }

    /// Length of the walk from `a` to `b` less the straight way between its points there.
    fn gain(&self, cover: &Cover, a: f64, b: f64) -> f64 {
        (b - a) - self.point_at(cover, a).distance(self.point_at(cover, b))
    }

    /// The stretches of the walk that may sweep nothing new, by length along it: the walk is
    /// probed at stations [`PROBE_STEP_RADII`] tool radii apart (across its sweep and in
    /// front, against what the moves before the station's swept), and only
    /// between stations whose probes all lie in earlier sweeps can it. Coarse stations
    /// ([`COARSE_STEP`] apart) first; where two neighbours both lie in stock, the walk is
    /// taken to cut between. Only the stretches that gain enough are wanted (the rest are
    /// found or not as it comes): stations that could lie only in stretches that gain too
    /// little are not probed.
    fn stretches(&self, cover: &Cover) -> Vec<(f64, f64)> {
        let r = cover.r;
        let length = self.length();
        let coarse = self.coarse_stations(r);
        // The work stays linear in the moves: a walk of moves far longer than the tool (a
        // drawing in metres read as millimetres) is left as it is.
        if coarse > MOST_STATIONS_PER_MOVE * self.ends.len() + MOST_STATIONS {
            return Vec::new();
        }
        let n = coarse * COARSE_STEP;
        let at = |i: usize| length * i as f64 / n as f64;
        let mut probes = Probes::new(self, cover);
        let least = LEAST_GAIN_RADII * r;
        // The coarse stations, widest apart first and then those halfway between (see
        // [`Station`]).
        let mut coarse_at = vec![Station::Unknown; coarse + 1];
        let probe_coarse = |c: usize, probes: &mut Probes| match probes.maybe_covered(at(c * COARSE_STEP)) {
            true => Station::MaybeCovered,
            false => Station::InStock,
        };
        for c in (0..coarse).step_by(WIDEST_COARSE).chain([coarse]) {
            coarse_at[c] = probe_coarse(c, &mut probes);
        }
        let mut half = WIDEST_COARSE / 2;
        while half >= 1 {
            for c in (half..coarse).step_by(2 * half) {
                let (a, b) = (c - half, (c + half).min(coarse));
                // A stretch between two stations in stock holds only the stations between.
                let span = || self.gain(cover, at(a * COARSE_STEP + 1), at(b * COARSE_STEP - 1));
                coarse_at[c] = match (coarse_at[a], coarse_at[b]) {
                    (Station::MaybeCovered, _) | (_, Station::MaybeCovered) => probe_coarse(c, &mut probes),
                    (Station::InStock, Station::InStock) if span() >= least => probe_coarse(c, &mut probes),
                    _ => Station::Sealed,
                };
            }
            half /= 2;
        }
        // Every station: covered, in stock, or not known. The fine ones are probed only beside
        // a coarse one that may be covered (else taken to be in stock).
        let maybe = |c: usize| coarse_at[c] == Station::MaybeCovered;
        let mut known: Vec<Option<bool>> = (0..=n)
            .map(|i| {
                let c = i / COARSE_STEP;
                if i % COARSE_STEP == 0 {
                    (!maybe(c)).then_some(false)
                } else if maybe(c) || maybe(c + 1) {
                    None
                } else {
                    Some(false)
                }
            })
            .collect();
        // Between two stations in stock (or the walk's ends), the stations not known are probed
        // only while the stretch of all between could gain enough (a stretch's gain only grows
        // as it is lengthened): first those at either end, which narrow the span where they lie
        // in stock, then the rest in order, each one in stock splitting it.
        // (A station in stock at 0 leaves no span before it: that span's end wraps past `n`.)
        let bounds: Vec<usize> = (0..=n).filter(|&i| known[i] == Some(false)).collect();
        let spans = (std::iter::once(0).chain(bounds.iter().map(|&b| b + 1)))
            .zip(bounds.iter().map(|&b| b.wrapping_sub(1)).chain([n]));
        for (mut first, mut last) in spans {
            'span: while first < last && last <= n {
                if self.gain(cover, at(first), at(last)) < least {
                    break;
                }
                for end in [first, last] {
                    if known[end].is_none() {
                        let covered = probes.covered(at(end));
                        known[end] = Some(covered);
                        if !covered {
                            (first, last) = if end == first {
                                (first + 1, last)
                            } else {
                                (first, last - 1)
                            };
                            continue 'span;
                        }
                    }
                }
                for (i, k) in known.iter_mut().enumerate().take(last).skip(first + 1) {
                    if k.is_none() {
                        let covered = probes.covered(at(i));
                        *k = Some(covered);
                        if !covered {
                            first = i + 1;
                            continue 'span;
                        }
                    }
                }
                break;
            }
        }
        covered_runs(n, |i| known[i] == Some(true))
            .into_iter()
            .map(|(i, j)| (at(i), at(j)))
            .collect()
    }

    /// How many coarse stations apart the walk's ends are, for a tool of radius `r`.
    fn coarse_stations(&self, r: f64) -> usize {
        ((self.length() / (COARSE_STEP as f64 * PROBE_STEP_RADII * r)).ceil() as usize).max(1)
    }

    /// The stretches of the walk proven to sweep nothing new, of those [`Walk::stretches`]
    /// finds that a straight move would shorten: each proven whole, or cut back where it first
    /// reaches stock and the rest tried again, or halved when the proof runs out.
    fn proven(&self, cover: &Cover, scratch: &mut Scratch) -> Vec<(f64, f64)> {
        let r = cover.r;
        let mut out = Vec::new();
        // Only stretches that a straight move would shorten are proven; their parts, once
        // one is split, down to the finest (a part that gains nothing alone may join one
        // that does).
        let mut stack: Vec<(f64, f64)> = (self.stretches(cover).into_iter())
            .filter(|&(a, b)| self.gain(cover, a, b) >= LEAST_GAIN_RADII * r)
            .rev()
            .collect();
        while let Some((a, b)) = stack.pop() {
            if b - a < FINEST_STRETCH_RADII * r {
                continue;
            }
            let chain = self.pieces(cover, a, b);
            match sweeps_nothing(&self.earlier_at(cover, a), &chain, scratch) {
                Proof::Nothing => out.push((a, b)),
                Proof::Cuts => {}
                // The stretch first reaches stock not swept before it at `f`: what comes
                // before may sweep nothing new, and what comes after may, against all swept
                // before it. Each part is shorter by at least the gap (a witness found in
                // front of the stretch's end is first reached just before it), and where
                // the stretch reaches the stock at once, the gap goes as cutting.
                Proof::CutsAt(q) => {
                    let f = a + first_reach(&chain, q, r);
                    let w = WITNESS_GAP_RADII * r;
                    if f - a > w {
                        stack.push((f, b));
                        stack.push((a, f.min(b - w)));
                    } else {
                        stack.push((a + w, b));
                    }
                }
                Proof::Undecided => {
                    if b - a > FINEST_STRETCH_RADII * r {
                        let mid = 0.5 * (a + b);
                        stack.push((mid, b));
                        stack.push((a, mid));
                    }
                }
            }
        }
        // Parts of one stretch proven apart, each against all swept before it, make one run
        // that sweeps nothing new.
        out.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut runs: Vec<(f64, f64)> = Vec::with_capacity(out.len());
        for (a, b) in out {
            match runs.last_mut() {
                Some(last) if a <= last.1 => last.1 = last.1.max(b),
                _ => runs.push((a, b)),
            }
        }
        runs
    }

    /// What is emitted along the whole walk: each proven stretch replaced by straight moves
    /// from where the tool stands to the farthest of a few points along the rest of it that one
    /// proven to sweep nothing reaches (else a step along the stretch as it is).
    fn shortened(&self, cover: &Cover, scratch: &mut Scratch) -> Vec<Kept> {
        let r = cover.r;
        let mut out = Vec::new();
        let mut done = 0.0;
        for (a, b) in self.proven(cover, scratch) {
            if a > done {
                out.push(Kept::Along(done, a));
            }
            let earlier = self.earlier_at(cover, a);
            let mut here = a;
            while here < b {
                let from = self.point_at(cover, here);
                // The ends tried: the stretch's end, the ends of its moves from there back,
                // and points evenly spaced along the rest of it.
                let (first, last) = (self.locate(here).0 - self.first, self.locate(b).0 - self.first);
                let mut ends: Vec<f64> = (first..last)
                    .rev()
                    .take(MOST_CHORD_ENDS)
                    .map(|j| self.ends[j])
                    .collect();
                ends.extend((0..MOST_CHORD_ENDS).map(|j| b - (b - here) * j as f64 / MOST_CHORD_ENDS as f64));
                ends.retain(|&e| e > here);
                ends.sort_by(|x, y| y.total_cmp(x));
                ends.dedup_by(|x, y| (*x - *y).abs() <= 1e-9 * r);
                let chord = ends.iter().find_map(|&to| {
                    let chord = Line::new(from, self.point_at(cover, to));
                    let gainful = (to - here) - chord.length() >= LEAST_CHORD_GAIN_RADII * r;
                    (gainful && sweeps_nothing(&earlier, &[Segment::Line(chord)], scratch) == Proof::Nothing)
                        .then_some((to, chord))
                });
                match chord {
                    Some((to, chord)) => {
                        out.push(Kept::Chord(chord));
                        here = to;
                    }
                    None => {
                        let to = b.min(here + FINEST_STRETCH_RADII * r);
                        out.push(Kept::Along(here, to));
                        here = to;
                    }
                }
            }
            done = b;
        }
        if done < self.length() {
            out.push(Kept::Along(done, self.length()));
        }
        out
    }

    /// The moves of the walk as `kept` has it, at height `z`: whole moves as they were in
    /// `moves`, parts of them and straight moves as new ones.
    fn emit(&self, cover: &Cover, kept: &[Kept], moves: &[Move], z: f64) -> Vec<Move> {
        let mut out = Toolpath::new(Point3::at(cover.sweeps[self.first].segment.start(), z));
        // Nearer than this to a move's end counts as at it.
        let snap = 1e-9 * cover.r;
        for item in kept {
            match *item {
                Kept::Chord(chord) => emit(&mut out, &Segment::Line(chord), z, Feed::Cut),
                Kept::Along(a, b) => {
                    for j in 0..self.ends.len() {
                        let (s0, s1) = (if j == 0 { 0.0 } else { self.ends[j - 1] }, self.ends[j]);
                        let (u0, u1) = (a.max(s0), b.min(s1));
                        if u1 - u0 <= snap {
                            continue;
                        }
                        let sweep = &cover.sweeps[self.first + j];
                        if u0 - s0 <= snap && s1 - u1 <= snap {
                            out.moves.push(moves[sweep.order]);
                        } else {
                            // A piece that reaches a move's end ends there exactly.
                            let len = s1 - s0;
                            let t0 = if u0 - s0 <= snap { 0.0 } else { (u0 - s0) / len };
                            let t1 = if s1 - u1 <= snap { 1.0 } else { (u1 - s0) / len };
                            let piece = sweep.segment.subsegment(t0, t1);
                            emit(&mut out, &piece, z, Feed::Cut);
                        }
                    }
                }
            }
        }
        // The walk ends where its last move did, to the last digit (a move's path in the plane
        // works its end out again, which for an arc may differ in the last place): the moves
        // after it start there.
        let end = moves[cover.sweeps[self.first + self.ends.len() - 1].order].to();
        if let Some(Move::Line { to, .. } | Move::Arc { to, .. }) = out.moves.last_mut() {
            *to = end;
        }
        out.moves
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::distance_from_segment;

    /// The stretches that gain enough when every station is probed that the probes beside a
    /// covered coarse station reach (what [`Walk::stretches`] leaves out of that is proven to
    /// hold none that gain enough).
    fn probing_every_station(walk: &Walk, cover: &Cover) -> Vec<(f64, f64)> {
        let r = cover.r;
        let length = walk.length();
        let coarse = walk.coarse_stations(r);
        let n = coarse * COARSE_STEP;
        let at = |i: usize| length * i as f64 / n as f64;
        let mut probes = Probes::new(walk, cover);
        let mut covered = vec![false; n + 1];
        for c in 0..=coarse {
            covered[c * COARSE_STEP] = probes.covered(at(c * COARSE_STEP));
        }
        for c in 0..coarse {
            let (a, b) = (c * COARSE_STEP, (c + 1) * COARSE_STEP);
            if covered[a] || covered[b] {
                for (i, k) in covered.iter_mut().enumerate().take(b).skip(a + 1) {
                    *k = probes.covered(at(i));
                }
            }
        }
        (covered_runs(n, |i| covered[i]).into_iter())
            .map(|(i, j)| (at(i), at(j)))
            .filter(|&(a, b)| walk.gain(cover, a, b) >= LEAST_GAIN_RADII * r)
            .collect()
    }

    /// A serpentine across a strip, then walks at random over it and beyond, turning sharply
    /// and gently, along lines and arcs: the cover of its moves for a tool of radius 3.
    fn serpentine_and_random_walks() -> Cover {
        let r = 3.0;
        let mut path = Toolpath::new(Point3::new(0.0, 0.0, -2.0));
        for k in 0..12 {
            let y = k as f64 * 2.4;
            let x = if k % 2 == 0 { 60.0 } else { 0.0 };
            path.line(Point3::new(x, y, -2.0), Feed::Cut);
            path.line(Point3::new(x, y + 2.4, -2.0), Feed::Cut);
        }
        let mut random = crate::test_random::Lcg::new(7);
        let mut next = || random.unit();
        for walk in 0..6 {
            path.rapid(Point3::new(next() * 60.0, next() * 28.0, -2.0));
            for _ in 0..40 {
                let to = Point3::new(next() * 70.0 - 5.0, next() * 36.0 - 4.0, -2.0);
                let here = path.position();
                if walk % 2 == 0 {
                    let mid = Point::new(0.5 * (here.x + to.x), 0.5 * (here.y + to.y));
                    path.arc_to(to, mid, std::f64::consts::PI, Feed::Cut);
                } else {
                    path.line(to, Feed::Cut);
                }
            }
        }
        let mut sweeps: Vec<Sweep> = (path.moves_from(0).enumerate())
            .filter_map(|(k, (from, m))| level_cut(from, m).map(|segment| (k, segment)))
            .map(|(order, segment)| Sweep {
                segment,
                order,
                smooth_next: false,
            })
            .collect();
        mark_smooth(&mut sweeps, r);
        Cover::new(sweeps, r).unwrap()
    }

    #[test]
    fn the_stations_left_unprobed_hold_no_stretch_that_gains_enough() {
        let cover = serpentine_and_random_walks();
        let r = cover.r;
        let mut found = 0;
        for walk in walks(&cover) {
            let quick: Vec<(f64, f64)> = (walk.stretches(&cover).into_iter())
                .filter(|&(a, b)| walk.gain(&cover, a, b) >= LEAST_GAIN_RADII * r)
                .collect();
            assert_eq!(quick, probing_every_station(&walk, &cover));
            found += quick.len();
        }
        assert!(found >= 20, "{found} stretches that gain enough");
    }

    #[test]
    fn a_station_is_covered_when_every_probe_lies_in_an_earlier_sweep() {
        // Each station of each walk against every probe measured from every sweep before it;
        // asked first with the probes most likely in stock, then with all.
        let cover = serpentine_and_random_walks();
        let r = cover.r;
        let (mut covered, mut stations) = (0, 0);
        for walk in walks(&cover) {
            let mut probes = Probes::new(&walk, &cover);
            let n = 8 * walk.coarse_stations(r);
            for i in 0..=n {
                let s = walk.length() * i as f64 / n as f64;
                let (k, t) = walk.locate(s);
                let segment = &cover.sweeps[k].segment;
                let (p, tangent) = (segment.point_at(t), segment.tangent_at(t));
                let earlier = &cover.sweeps[..cover.runs[cover.runs_before(k)].first];
                let measured = (0..PROBES).map(|j| probe_point(p, tangent, j, r)).all(|q| {
                    earlier
                        .iter()
                        .any(|e| distance_from_segment(&e.segment, q) < r * (1.0 + 1e-9))
                });
                let maybe = probes.maybe_covered(s);
                assert_eq!(probes.covered(s), measured, "walk at {} station {i}", walk.first);
                assert!(maybe || !measured, "walk at {} station {i}", walk.first);
                covered += usize::from(measured);
                stations += 1;
            }
        }
        assert!(
            covered >= 50 && stations - covered >= 50,
            "{covered} of {stations}"
        );
    }
}
