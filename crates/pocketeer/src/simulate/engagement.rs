//! The tool's engagement along a program: at each point of a cutting move, the arc of the
//! tool's circumference that meets stock not yet removed.
//!
//! The stock at a height z is everything except what a feed move before (or the part of the
//! same move already done) swept at z or below: the tool's disc along it. A point of the
//! circumference is in contact when no earlier position of the tool at that height or deeper
//! covered it. Samples are taken every [`ANGLE_STEP_DEG`] round the tool (the engaged arc is
//! then within one step of the exact one: each end of it within half a step) and at most
//! [`SPACING_PER_RADIUS`] of the radius apart along the cutting moves (along each move at least
//! that long; across a run of shorter moves, where their length reaches it), so a peak shorter
//! than that along the path may be missed. The directions an earlier move covered are found
//! as whole ranges (`tool_circle.rs`), not one by one.
//!
//! Only moves at one height below Z=0 count (the cutting length): helices, ramps and plunges
//! are entries, and their engagement is not a question of stepover or linking. Links through
//! cleared stock count, with their engagement of 0°.

use super::check::Place;
use super::gcode::{Motion, ProgramMove};
use super::history::CutHistory;
use super::tool_circle::{unit_vectors, Swept, ToolCircle, DIRECTIONS};
use crate::geom::distance_from_segment;
use serde::Serialize;

/// Angle between samples round the tool, degrees.
pub const ANGLE_STEP_DEG: f64 = 360.0 / DIRECTIONS as f64;

/// Largest distance between samples along a move, as a share of the tool radius.
pub const SPACING_PER_RADIUS: f64 = 0.125;

/// Most samples along the program: past this the spacing widens (and the report says so), and
/// where two samples a move would exceed it, the samples go at that spacing along the whole
/// program rather than per move.
pub const MAX_SAMPLES: usize = 400_000;

/// Width of the bands of [`Engagement::histogram`], degrees.
pub const BAND_DEG: f64 = 10.0;

/// How the tool met the stock along a program's cutting moves.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Engagement {
    /// Angle between samples round the tool, degrees.
    pub angle_step_deg: f64,
    /// Largest distance between samples along a move, mm.
    pub spacing: f64,
    /// Length of the cutting moves measured (one height, below Z=0), mm.
    pub length: f64,
    /// How many places along them were measured.
    pub samples: usize,
    /// Largest engagement, degrees.
    pub max_deg: f64,
    /// Where it is.
    pub max_at: Option<Place>,
    /// The engagement that 95 % of the cutting length stays at or below, degrees.
    pub p95_deg: f64,
    /// The same over the length where the tool touches stock (more than 0°): a link fed
    /// through cleared stock lowers [`Engagement::p95_deg`] without easing any cut, and one
    /// replaced by a rapid over the top raises it.
    pub p95_in_contact_deg: f64,
    /// Share of the cutting length with more than 90°, percent.
    pub above_90_percent: f64,
    /// Share of the cutting length with more than 150°, percent.
    pub above_150_percent: f64,
    /// Share of the cutting length where the tool touches no stock (0°), percent: links fed
    /// through cleared stock, and loops cut again where the stock is gone already. Time the
    /// program spends cutting air.
    pub untouched_percent: f64,
    /// Cutting length in each band of [`BAND_DEG`] degrees, from 0°: the last band holds 360°.
    pub histogram: Vec<f64>,
}

/// The engagement along `moves` for a tool of radius `r` (see the module's documentation).
pub fn engagement(moves: &[ProgramMove], history: &CutHistory, r: f64) -> Engagement {
    engagement_with(moves, history, r, &crate::progress::Silent)
}

/// [`engagement`], telling `progress` of each cutting move measured.
pub fn engagement_with(
    moves: &[ProgramMove],
    history: &CutHistory,
    r: f64,
    progress: &dyn crate::progress::Progress,
) -> Engagement {
    sampled(moves, history, r, MAX_SAMPLES, progress)
}

/// [`engagement_with`] with at most about `budget` samples.
fn sampled(
    moves: &[ProgramMove],
    history: &CutHistory,
    r: f64,
    budget: usize,
    progress: &dyn crate::progress::Progress,
) -> Engagement {
    let cutting: Vec<usize> = (0..moves.len()).filter(|&k| is_cutting(&moves[k])).collect();
    progress.stage("measuring the tool's engagement", Some(cutting.len() as u64));
    let length: f64 = cutting.iter().map(|&k| moves[k].length()).sum();
    let mut spacing = SPACING_PER_RADIUS * r;
    if length / spacing > budget as f64 {
        spacing = length / budget as f64;
    }
    // A move at least the spacing long is sampled along itself: at least twice, at most the
    // spacing apart, the last sample at its end. Shorter moves in a row (a finely divided
    // wall, a curve written as short lines) share samples: one at the end of the move where
    // their length since the last sample reaches the spacing, and one at the end of the last
    // of them. Sampling each such move would measure a program of moves a tenth of the
    // spacing long twenty times as densely as the spacing says, and take that much longer.
    let long = |len: f64| len >= spacing;
    let per_move = |len: f64| ((len / spacing).ceil() as usize).max(2);
    let (mut along_long, mut short) = (0usize, 0.0);
    for &k in &cutting {
        let len = moves[k].length();
        if long(len) {
            along_long += per_move(len) + 1;
        } else {
            short += len;
        }
    }
    // Within the budget, as above; past it, the samples go at the spacing along the whole
    // program, each standing for the length since the last.
    let by_move = along_long as f64 + short / spacing <= budget as f64;
    let mut since_last = 0.0;
    // The short move the length since the last sample ends on.
    let mut pending: Option<usize> = None;
    // (engagement in degrees, length it stands for)
    let mut samples: Vec<(f64, f64)> = Vec::new();
    let mut max: (f64, Option<Place>) = (0.0, None);
    // The places to measure: (move, parameter, length it stands for).
    let mut places: Vec<(usize, f64, f64)> = Vec::new();
    for (i, &k) in cutting.iter().enumerate() {
        progress.advance(1);
        let len = moves[k].length();
        places.clear();
        if by_move && long(len) {
            if let Some(p) = pending.take() {
                places.push((p, 1.0, since_last));
                since_last = 0.0;
            }
            let n = per_move(len);
            places.extend((1..=n).map(|j| (k, j as f64 / n as f64, len / n as f64)));
        } else if by_move {
            since_last += len;
            pending = Some(k);
            if since_last >= spacing || i + 1 == cutting.len() {
                places.push((k, 1.0, since_last));
                since_last = 0.0;
                pending = None;
            }
        } else {
            // The first sample where the length since the last reaches the spacing, then
            // every spacing; what is left over counts towards the next move's.
            let mut along = spacing - since_last;
            let mut from = 0.0;
            while along <= len {
                places.push((
                    k,
                    along / len,
                    along - from + if from == 0.0 { since_last } else { 0.0 },
                ));
                from = along;
                along += spacing;
            }
            since_last = if places.is_empty() {
                since_last + len
            } else {
                len - from
            };
        }
        for &(j, t, w) in &places {
            let deg = engagement_at(moves, history, j, t, r);
            samples.push((deg, w));
            if deg > max.0 || max.1.is_none() {
                let m = &moves[j];
                let c = m.point_at(t);
                max = (
                    deg,
                    Some(Place {
                        x: c.x,
                        y: c.y,
                        line: m.line,
                    }),
                );
            }
        }
    }
    summarize(samples, length, spacing, max)
}

/// A feed move at one height below the stock top.
fn is_cutting(m: &ProgramMove) -> bool {
    m.motion != Motion::Rapid
        && m.from.z < 0.0
        && (m.to.z - m.from.z).abs() <= 1e-9
        && m.from.xy().distance(m.to.xy()) > 0.0
}

/// The engagement, degrees, of the tool at parameter `t` of move `k`.
pub fn engagement_at(moves: &[ProgramMove], history: &CutHistory, k: usize, t: f64, r: f64) -> f64 {
    let m = &moves[k];
    let c = m.point_at(t);
    let z = c.z;
    let here = c.xy();
    // What may have cut round the tool: earlier moves within 2r of its centre at this height
    // or deeper, and this move up to here.
    let earlier: Vec<usize> = history
        .near(k, here, 2.0 * r)
        .into_iter()
        .filter(|&j| {
            let e = &moves[j];
            e.from.z.min(e.to.z) <= z + 1e-4 && distance_from_segment(history.footprint(j), here) < 2.0 * r
        })
        .collect();
    // Moves at one height (nearly all) cut wherever they passed; a helix or a ramp only where
    // it was deep enough.
    let level = |j: usize| (moves[j].from.z - moves[j].to.z).abs() <= 1e-9;
    // A point exactly on an earlier disc's edge is cut: the tool's own circumference at the
    // start of a slot touches only its centre's path behind it.
    let covered = r * (1.0 - 1e-9);
    let circle = ToolCircle {
        center: here,
        radius: r,
    };
    let mut swept = Swept::new(circle, covered);
    let own = (t > 0.0).then(|| history.footprint(k).subsegment(0.0, t));
    for s in earlier
        .iter()
        .filter(|&&j| level(j))
        .map(|&j| history.footprint(j))
        .chain(&own)
    {
        swept.add(s);
        if swept.directions().is_all() {
            return 0.0;
        }
    }
    let swept = swept.directions();
    let sloped: Vec<usize> = earlier.into_iter().filter(|&j| !level(j)).collect();
    let engaged = unit_vectors()
        .iter()
        .enumerate()
        .filter(|&(i, &u)| {
            !swept.contains(i) && {
                let q = here + u * r;
                !sloped.iter().any(|&j| history.passed(j, q, z, covered))
            }
        })
        .count();
    engaged as f64 * ANGLE_STEP_DEG
}

/// The figures of [`Engagement`] from the samples (degrees, length).
fn summarize(
    mut samples: Vec<(f64, f64)>,
    length: f64,
    spacing: f64,
    max: (f64, Option<Place>),
) -> Engagement {
    let bands = (360.0 / BAND_DEG).round() as usize;
    let mut histogram = vec![0.0; bands];
    let (mut above_90, mut above_150) = (0.0, 0.0);
    for &(deg, len) in &samples {
        histogram[((deg / BAND_DEG) as usize).min(bands - 1)] += len;
        if deg > 90.0 {
            above_90 += len;
        }
        if deg > 150.0 {
            above_150 += len;
        }
    }
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = samples.iter().map(|s| s.1).sum();
    let p95 = percentile(&samples, 0.95);
    let in_contact = samples.partition_point(|s| s.0 <= 0.0);
    let p95_in_contact = percentile(&samples[in_contact..], 0.95);
    let untouched: f64 = samples[..in_contact].iter().map(|s| s.1).sum();
    let percent = |x: f64| if total > 0.0 { 100.0 * x / total } else { 0.0 };
    Engagement {
        angle_step_deg: ANGLE_STEP_DEG,
        spacing,
        length,
        samples: samples.len(),
        max_deg: max.0,
        max_at: max.1,
        p95_deg: p95,
        p95_in_contact_deg: p95_in_contact,
        above_90_percent: percent(above_90),
        above_150_percent: percent(above_150),
        untouched_percent: percent(untouched),
        histogram,
    }
}

/// The engagement that the share `q` of the samples' length (sorted by engagement) stays at
/// or below; 0 for no samples.
fn percentile(sorted: &[(f64, f64)], q: f64) -> f64 {
    let total: f64 = sorted.iter().map(|s| s.1).sum();
    let mut acc = 0.0;
    sorted
        .iter()
        .find(|s| {
            acc += s.1;
            acc >= q * total
        })
        .map_or(0.0, |s| s.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::Point3;

    fn feed(line: usize, from: (f64, f64, f64), to: (f64, f64, f64)) -> ProgramMove {
        ProgramMove {
            line,
            motion: Motion::Line,
            from: Point3::new(from.0, from.1, from.2),
            to: Point3::new(to.0, to.1, to.2),
            feed: Some(1000.0),
        }
    }

    #[test]
    fn a_straight_slot_engages_half_the_tool() {
        let r = 3.0;
        let moves = vec![
            feed(1, (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)),
            feed(2, (0.0, 0.0, -1.0), (50.0, 0.0, -1.0)),
        ];
        let history = CutHistory::new(&moves, r);
        let e = engagement(&moves, &history, r);
        assert!((e.length - 50.0).abs() < 1e-9);
        assert!((e.max_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{}", e.max_deg);
        assert!((e.p95_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{}", e.p95_deg);
        assert!(e.above_150_percent > 99.0);
        for t in [0.1, 0.5, 0.9] {
            let deg = engagement_at(&moves, &history, 1, t, r);
            assert!((deg - 180.0).abs() <= ANGLE_STEP_DEG, "{deg} at {t}");
        }
    }

    #[test]
    fn a_side_cut_engages_the_closed_form_angle() {
        // A slot along y = 0, then back along y = a: radial width a, engagement
        // arccos(1 − a/r), for widths from a sliver to just under the radius.
        let r = 3.0;
        for a in [0.3, 1.2, 2.4, 2.9] {
            let moves = vec![
                feed(1, (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)),
                feed(2, (0.0, 0.0, -1.0), (60.0, 0.0, -1.0)),
                feed(3, (60.0, 0.0, -1.0), (60.0, a, -1.0)),
                feed(4, (60.0, a, -1.0), (0.0, a, -1.0)),
            ];
            let history = CutHistory::new(&moves, r);
            let exact = (1.0 - a / r).acos().to_degrees();
            for t in [0.2, 0.5, 0.8] {
                let deg = engagement_at(&moves, &history, 3, t, r);
                assert!(
                    (deg - exact).abs() <= ANGLE_STEP_DEG,
                    "a = {a}: {deg} against {exact}"
                );
            }
        }
    }

    #[test]
    fn a_pass_at_a_new_depth_meets_stock_again_and_a_link_through_cleared_stock_none() {
        let r = 2.0;
        let moves = vec![
            feed(1, (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)),
            feed(2, (0.0, 0.0, -1.0), (30.0, 0.0, -1.0)),
            // Back along the slot at the same depth: nothing left to meet.
            feed(3, (30.0, 0.0, -1.0), (0.0, 0.0, -1.0)),
            feed(4, (0.0, 0.0, -1.0), (0.0, 0.0, -2.0)),
            // The same slot one step deeper: a slot again.
            feed(5, (0.0, 0.0, -2.0), (30.0, 0.0, -2.0)),
        ];
        let history = CutHistory::new(&moves, r);
        assert_eq!(engagement_at(&moves, &history, 2, 0.5, r), 0.0);
        let deg = engagement_at(&moves, &history, 4, 0.5, r);
        assert!((deg - 180.0).abs() <= ANGLE_STEP_DEG, "{deg}");
    }

    #[test]
    fn a_slot_of_many_tiny_moves_is_sampled_within_the_budget_and_is_still_a_slot() {
        // 1000 moves of 0.01 mm with a budget of 100 samples: the samples go every eighth of
        // the radius (0.25 mm) along the program, 40 in all, each standing for 0.25 mm.
        let r = 2.0;
        let moves: Vec<ProgramMove> = (0..1000)
            .map(|k| {
                feed(
                    k + 1,
                    (0.01 * k as f64, 0.0, -1.0),
                    (0.01 * (k + 1) as f64, 0.0, -1.0),
                )
            })
            .collect();
        let history = CutHistory::new(&moves, r);
        let e = sampled(&moves, &history, r, 100, &crate::progress::Silent);
        assert!((e.spacing - 0.25).abs() < 1e-12, "{e:?}");
        assert_eq!(e.samples, 40);
        let weighed: f64 = e.histogram.iter().sum();
        assert!((10.0 - 0.25 - 1e-9..=10.0 + 1e-9).contains(&weighed), "{weighed}");
        assert!((e.p95_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{e:?}");
        // Within a larger budget, the moves, each shorter than the spacing, share samples: one
        // where their length since the last reaches it (25 moves), 40 in all, and the length
        // of every move counted.
        let full = sampled(&moves, &history, r, 2000, &crate::progress::Silent);
        assert_eq!(full.samples, 40, "{full:?}");
        assert!((full.histogram.iter().sum::<f64>() - 10.0).abs() < 1e-9);
        assert!((full.p95_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{full:?}");
    }

    #[test]
    fn short_moves_between_long_ones_get_one_sample_that_counts_their_length() {
        // 1 mm, ten moves of 0.01 mm, 1 mm, along one slot (spacing 0.25 mm): four samples on
        // each long move, one at the end of the short ones for their 0.1 mm.
        let r = 2.0;
        let mut moves = vec![feed(1, (0.0, 0.0, -1.0), (1.0, 0.0, -1.0))];
        for k in 0..10 {
            let x = 1.0 + 0.01 * k as f64;
            moves.push(feed(k + 2, (x, 0.0, -1.0), (x + 0.01, 0.0, -1.0)));
        }
        moves.push(feed(12, (1.1, 0.0, -1.0), (2.1, 0.0, -1.0)));
        let e = engagement(&moves, &CutHistory::new(&moves, r), r);
        assert_eq!(e.samples, 9, "{e:?}");
        assert!((e.histogram.iter().sum::<f64>() - 2.1).abs() < 1e-9, "{e:?}");
        assert!((e.p95_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{e:?}");
    }

    #[test]
    fn the_p95_in_contact_leaves_out_the_length_that_meets_no_stock() {
        // A slot 40 mm long, then 50 times back and forth along its middle through nothing but
        // air: 1000 of 1040 mm meet no stock, so 95 % of the length stays at 0°; the slot is
        // still a slot.
        let r = 2.0;
        let mut moves = vec![feed(1, (0.0, 0.0, -1.0), (40.0, 0.0, -1.0))];
        moves.push(feed(2, (40.0, 0.0, -1.0), (30.0, 0.0, -1.0)));
        for k in 0..50 {
            let (a, b) = if k % 2 == 0 { (30.0, 10.0) } else { (10.0, 30.0) };
            moves.push(feed(k + 3, (a, 0.0, -1.0), (b, 0.0, -1.0)));
        }
        let e = engagement(&moves, &CutHistory::new(&moves, r), r);
        assert!((e.length - 1050.0).abs() < 1e-9);
        assert_eq!(e.p95_deg, 0.0, "{e:?}");
        assert!((e.p95_in_contact_deg - 180.0).abs() <= ANGLE_STEP_DEG, "{e:?}");
        assert!(e.histogram[0] >= 1009.0, "{e:?}");
        // 1010 of the 1050 mm touch no stock, to a sample's length.
        let spacing_share = 100.0 * e.spacing / 1050.0;
        assert!(
            (e.untouched_percent - 100.0 * 1010.0 / 1050.0).abs() <= spacing_share,
            "{e:?}"
        );
    }

    #[test]
    fn a_slot_touches_stock_all_along() {
        let r = 3.0;
        let moves = vec![feed(1, (0.0, 0.0, -1.0), (50.0, 0.0, -1.0))];
        let e = engagement(&moves, &CutHistory::new(&moves, r), r);
        assert_eq!(e.untouched_percent, 0.0, "{e:?}");
    }
}
