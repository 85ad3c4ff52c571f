//! Measuring a program against its drawing: gouge, leftover, rapids in the stock, plunges
//! into uncut material, feed moves without a feed rate, lengths and time.

use super::gcode::{Motion, Program, ProgramMove};
use super::polygon::{largest_inscribed_circle, ring, shape_area, Shape};
use crate::geom::Pocket;
use crate::geom::PreparedPocket;
use crate::geom::{Contour, Point, Segment, SegmentIndex, Tolerance};
use crate::offset::OffsetError;
use crate::toolpath::Point3;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, StrokeStyle};
use serde::Serialize;

/// Chord error of every flattened arc, mm: five times below the tightest tolerance checked.
pub const CHORD: f64 = 0.001;

/// Rapid speed assumed for time estimates unless told, mm/min.
pub const RAPID_RATE: f64 = 5000.0;

/// The largest gouge a program may make unless told otherwise, mm: the design's measure of
/// correct.
pub const GOUGE_TOLERANCE: f64 = 0.01;

/// The thickest leftover a program may leave unless told otherwise, mm: the design's measure
/// of correct.
pub const LEFTOVER_TOLERANCE: f64 = 0.05;

/// What to check against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CheckParams {
    /// Tool radius, mm.
    pub tool_radius: f64,
    /// The pocket depth below Z=0, mm (positive); `None`: the deepest Z of the program.
    pub depth: Option<f64>,
    /// Largest gouge accepted, mm.
    pub gouge_tolerance: f64,
    /// Thickest leftover accepted, mm.
    pub leftover_tolerance: f64,
    /// Rapid speed for the time estimate, mm/min.
    pub rapid_rate: f64,
    /// The fixed cost of each retract in the time estimate, seconds (see
    /// [`crate::machining_time`]).
    pub per_retract: f64,
}

/// A place in the program: where and on which line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Place {
    /// X, mm.
    pub x: f64,
    /// Y, mm.
    pub y: f64,
    /// Line of the program (from 1), 0 when none.
    pub line: usize,
}

/// The figures of one pocket.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PocketCheck {
    /// Area of the pocket, mm².
    pub area: f64,
    /// Area the tool can reach (the pocket opened by the tool disc), mm².
    pub reachable_area: f64,
    /// Largest distance by which the tool disc leaves the pocket below Z=0, mm (0: none).
    pub gouge: f64,
    /// Where the largest gouge is.
    pub gouge_at: Option<Place>,
    /// Reachable area not swept at the final depth, mm².
    pub leftover_area: f64,
    /// The same as a share of the reachable area, percent.
    pub leftover_percent: f64,
    /// Diameter of the largest circle inside a leftover piece, mm.
    pub thickest: f64,
    /// Centre of that circle.
    pub thickest_at: Option<Place>,
    /// Leftover pieces (outer ring first), for drawing.
    #[serde(skip)]
    pub leftover: Vec<Shape>,
}

/// The report of a check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckReport {
    /// One entry per pocket, in the drawing's order.
    pub pockets: Vec<PocketCheck>,
    /// Z of the final depth checked.
    pub final_depth: f64,
    /// Deepest Z the program reaches.
    pub deepest: f64,
    /// Rapid moves through the stock: below Z=0 other than straight up out of the cut, or
    /// straight down onto stock already cut deeper than where the rapid stops.
    pub rapids_into_stock: Vec<Place>,
    /// Feed moves going straight down below Z=0 where the tool disc had not been cut that
    /// deep before.
    pub plunges: Vec<Place>,
    /// Feed moves before any feed rate was set.
    pub feedless: Vec<Place>,
    /// Length of feed moves, mm.
    pub cut_length: f64,
    /// Length of rapid moves, mm.
    pub rapid_length: f64,
    /// Rapid moves upwards.
    pub retracts: usize,
    /// Seconds of dwell (G4).
    pub dwell: f64,
    /// Estimated time, seconds: feed moves at their feed, rapids at the rapid rate, dwells, and
    /// the fixed cost of each retract.
    pub seconds: f64,
    /// Length along the walls at the final depth by the side the material is on (right:
    /// climb milling with an M3 spindle).
    pub wall_sides: super::side::Sides,
    /// Largest gouge over all pockets, mm.
    pub gouge: f64,
    /// Thickest leftover over all pockets, mm.
    pub thickest: f64,
    /// How much of the tool's circumference met the stock along the cutting moves.
    pub engagement: super::engagement::Engagement,
    /// True when gouge and leftover are within the tolerances and no rapid goes into the stock.
    pub passed: bool,
    /// The area swept at the final depth, for drawing.
    #[serde(skip)]
    pub swept: Vec<Shape>,
}

/// Checks `program` against `pockets` (see [`CheckReport`]).
pub fn check_program(
    pockets: &[Pocket],
    program: &Program,
    params: &CheckParams,
    tol: &Tolerance,
) -> Result<CheckReport, OffsetError> {
    check_program_tools(pockets, program, &[(0, params.tool_radius)], params, tol)
}

/// [`check_program`] for a program of several tools: `radii` gives, from which move on, each
/// tool's radius (sorted by move). Each move's gouge is measured with its own tool's radius,
/// the area swept with each tool's, and the leftover against what the smallest tool can
/// reach: the smallest of `radii` and `params.tool_radius` (a tool that should have cut and
/// has no move still counts). The engagement is measured for a program of one
/// tool only (with several it is left empty): a cut's engagement depends on which tool made
/// each earlier cut.
pub fn check_program_tools(
    pockets: &[Pocket],
    program: &Program,
    radii: &[(usize, f64)],
    params: &CheckParams,
    tol: &Tolerance,
) -> Result<CheckReport, OffsetError> {
    check_program_tools_with(pockets, program, radii, params, tol, &crate::progress::Silent)
}

/// [`check_program_tools`], telling `progress` of its stages: the moves replayed (a step a
/// move), the engagement measured (a step a cutting move) and the area swept.
pub fn check_program_tools_with(
    pockets: &[Pocket],
    program: &Program,
    radii: &[(usize, f64)],
    params: &CheckParams,
    tol: &Tolerance,
    progress: &dyn crate::progress::Progress,
) -> Result<CheckReport, OffsetError> {
    let default = [(0, params.tool_radius)];
    let radii = if radii.is_empty() { &default[..] } else { radii };
    let moves = &program.moves;
    let radius_at = |k: usize| {
        radii
            .iter()
            .take_while(|t| t.0 <= k)
            .last()
            .or(radii.first())
            .map_or(params.tool_radius, |t| t.1)
    };
    let smallest = radii.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
    let r_min = smallest.min(params.tool_radius);
    let deepest = moves.iter().map(|m| m.to.z.min(m.from.z)).fold(0.0, f64::min);
    let final_depth = params.depth.map_or(deepest, |d| -d);
    let walls = Walls::new(pockets);
    let mut report = CheckReport::empty(final_depth, deepest, program.dwell);
    let mut gouges: Vec<(f64, Option<Place>)> = vec![(0.0, None); pockets.len()];
    let history = super::history::CutHistory::with_radii(moves, (0..moves.len()).map(radius_at).collect());
    progress.stage("replaying the moves", Some(moves.len() as u64));
    for (k, m) in moves.iter().enumerate() {
        progress.advance(1);
        let r = radius_at(k);
        let place = |p: Point| Place {
            x: p.x,
            y: p.y,
            line: m.line,
        };
        if m.motion == Motion::Rapid {
            report.tally_rapid(m, params.rapid_rate, params.per_retract);
            if !rapid_through_air(m, k, &history, r) {
                report.rapids_into_stock.push(place(m.to.xy()));
            }
            continue;
        }
        report.tally_feed(m);
        if m.from.z.min(m.to.z) >= 0.0 {
            continue;
        }
        if let Some((i, g, at)) = walls.gouge(&m.footprint(), r, params.gouge_tolerance, tol) {
            if g > gouges[i].0 {
                gouges[i] = (g, Some(place(at)));
            }
        }
        // A feed move straight down below Z=0 must land where the tool has cut that deep.
        let vertical = m.from.xy().distance(m.to.xy()) <= 1e-6 && m.to.z < m.from.z;
        if vertical && m.to.z < 0.0 && !history.cleared(k, m.to.xy(), m.to.z, r) {
            report.plunges.push(place(m.to.xy()));
        }
    }
    if radii.len() <= 1 {
        let r = radius_at(0);
        report.engagement = super::engagement::engagement_with(moves, &history, r, progress);
        report.wall_sides = super::side::material_sides(moves, &|p| walls.of_pocket_at(p), final_depth, r);
    }
    progress.stage("sweeping the area cut", None);
    // The area swept: each tool's moves with its radius.
    let mut bounds: Vec<usize> = radii.iter().map(|t| t.0.min(moves.len())).collect();
    bounds[0] = 0;
    bounds.push(moves.len());
    for (t, w) in bounds.windows(2).enumerate() {
        if w[0] < w[1] {
            report
                .swept
                .extend(swept(&moves[w[0]..w[1]], final_depth, radii[t].1));
        }
    }
    for (i, p) in pockets.iter().enumerate() {
        let pc = pocket_check(p, &walls.prepared[i], &report.swept, gouges[i], r_min, tol)?;
        report.gouge = report.gouge.max(pc.gouge);
        report.thickest = report.thickest.max(pc.thickest);
        report.pockets.push(pc);
    }
    report.passed = report.gouge <= params.gouge_tolerance
        && report.thickest <= params.leftover_tolerance
        && report.rapids_into_stock.is_empty();
    Ok(report)
}

impl CheckReport {
    /// A report with nothing counted yet.
    fn empty(final_depth: f64, deepest: f64, dwell: f64) -> CheckReport {
        CheckReport {
            pockets: Vec::new(),
            final_depth,
            deepest,
            rapids_into_stock: Vec::new(),
            plunges: Vec::new(),
            feedless: Vec::new(),
            cut_length: 0.0,
            rapid_length: 0.0,
            retracts: 0,
            dwell,
            seconds: dwell,
            wall_sides: super::side::Sides::default(),
            gouge: 0.0,
            thickest: 0.0,
            engagement: super::engagement::Engagement::default(),
            passed: true,
            swept: Vec::new(),
        }
    }

    /// Counts a rapid's length, time and whether it retracts.
    fn tally_rapid(&mut self, m: &ProgramMove, rapid_rate: f64, per_retract: f64) {
        self.rapid_length += m.length();
        self.seconds += m.seconds(rapid_rate, per_retract);
        if m.to.z > m.from.z {
            self.retracts += 1;
        }
    }

    /// Counts a feed move's length and time, or notes that it has no feed rate.
    fn tally_feed(&mut self, m: &ProgramMove) {
        self.cut_length += m.length();
        self.seconds += m.seconds(0.0, 0.0);
        match m.feed {
            Some(f) if f > 0.0 => {}
            _ => self.feedless.push(Place {
                x: m.to.x,
                y: m.to.y,
                line: m.line,
            }),
        }
    }
}

/// True when the rapid `m` (move `k`) moves through air: above the stock, straight up out of
/// a cut, or straight down onto stock cut deeper than where it stops. Any other rapid that is
/// below Z=0 at either end moves through, or down into, the stock.
fn rapid_through_air(m: &ProgramMove, k: usize, history: &super::history::CutHistory, r: f64) -> bool {
    let vertical = m.from.xy().distance(m.to.xy()) <= 1e-6;
    m.from.z.min(m.to.z) >= -1e-9
        || vertical && (m.to.z >= m.from.z || history.cleared(k, m.to.xy(), m.to.z, r))
}

/// The pockets prepared for the gouge measure: each one's walls and islands indexed.
struct Walls {
    prepared: Vec<PreparedPocket>,
}

impl Walls {
    fn new(pockets: &[Pocket]) -> Walls {
        Walls {
            prepared: pockets.iter().map(PreparedPocket::new).collect(),
        }
    }

    /// The walls of the pocket `p` lies in, if any.
    fn of_pocket_at(&self, p: Point) -> Option<&SegmentIndex> {
        self.prepared
            .iter()
            .find(|pocket| pocket.contains(p))
            .map(PreparedPocket::walls)
    }

    /// How far the disc of radius `r` moving along `seg` reaches beyond the walls of the pocket
    /// it is in (by its middle; the nearest pocket when it is in none), where, and which
    /// pocket: `None` when no wall comes within reach.
    fn gouge(
        &self,
        seg: &Segment,
        r: f64,
        gouge_tolerance: f64,
        tol: &Tolerance,
    ) -> Option<(usize, f64, Point)> {
        let mid = seg.point_at(0.5);
        let n = self.prepared.len();
        let inside = (0..n).find(|&i| self.prepared[i].contains(mid));
        let i = inside.or_else(|| {
            (0..n).min_by(|&a, &b| {
                self.prepared[a]
                    .distance(mid)
                    .total_cmp(&self.prepared[b].distance(mid))
            })
        })?;
        let prepared = &self.prepared[i];
        let walls = prepared.walls();
        let g = if inside.is_some() {
            walls
                .nearest_to_segment(seg, r + gouge_tolerance.max(0.0) + 1.0, tol.eps)
                .map(|(d, at)| (r - d, at))
        } else {
            Some((r + walls.distance(mid), mid))
        };
        // A move that touches a wall may leave the pocket: then the deepest point outside
        // decides, found along the move (every 5 µm).
        let g = match g {
            Some(found) if found.0 >= r - 1e-9 => {
                let n = ((seg.length() / 0.005).ceil() as usize).clamp(1, 100_000);
                (0..=n)
                    .map(|k| seg.point_at(k as f64 / n as f64))
                    .filter(|&q| !prepared.contains(q))
                    .map(|q| (r + walls.distance(q), q))
                    .max_by(|a, b| a.0.total_cmp(&b.0))
                    .or(Some(found))
            }
            other => other,
        };
        g.map(|(g, at)| (i, g, at))
    }
}

/// The area swept by the tool at `depth` or deeper (a program may cut below the depth asked
/// for): the chains of feed moves there, stroked with round joins and ends to the tool's width.
fn swept(moves: &[ProgramMove], depth: f64, r: f64) -> Vec<Shape> {
    let at_depth = |z: f64| z <= depth + 1e-4;
    let mut chains: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut last_end: Option<Point3> = None;
    for m in moves {
        if m.motion == Motion::Rapid || !at_depth(m.from.z) || !at_depth(m.to.z) {
            last_end = None;
            continue;
        }
        let pts = super::polygon::flatten(&[m.footprint()], CHORD);
        let continues = last_end.is_some_and(|e| e.distance(m.from) < 1e-9);
        match chains.last_mut() {
            Some(chain) if continues => chain.extend(pts.into_iter().skip(1)),
            _ => chains.push(pts),
        }
        let e = m.to.xy();
        if let Some(chain) = chains.last_mut() {
            chain.push([e.x, e.y]);
        }
        last_end = Some(m.to);
    }
    // Round joins and ends within the chord error: L/R for the segment count.
    let angle = 2.0 * (1.0 - (CHORD / r).min(1.0)).acos();
    let style = StrokeStyle::new(2.0 * r)
        .line_join(LineJoin::Round(angle))
        .start_cap(LineCap::Round(angle))
        .end_cap(LineCap::Round(angle));
    // Points within a fifth of the chord error of the path between their neighbours add
    // nothing the tolerances can see; dropping them makes stroking several times faster.
    let mut chains: Vec<Vec<[f64; 2]>> = chains
        .iter()
        .map(|c| super::polygon::simplify(c, 0.2 * CHORD))
        .collect();
    // A chain that stays in one place strokes to nothing: give it a hair of length.
    for c in &mut chains {
        if c.len() == 1 {
            let p = c[0];
            c.push([p[0] + 1e-6, p[1]]);
        }
    }
    // Stroked whole, a long program's chains made one overlay of every point (1.4 GB for a
    // 3 000-loop program); in pieces united in pairs, each overlay holds two pieces' outlines.
    let strokes = pieces(&chains, STROKE_PIECE)
        .map(|piece| [piece].stroke(style.clone(), false))
        .collect();
    united(strokes)
}

/// Most points of a chain stroked in one go by [`swept`]. Short runs make the most overlays
/// but the cheapest: a run's stroke crosses itself little, and two neighbouring runs' strokes
/// meet mostly along their shared end. On the 300-hole plate's program the check took 0.77 of
/// the time with runs of 100 points that it took with 2 000 (50 and 100 alike, 200 0.81, 500
/// 0.88), the 1 200-hole plate's 0.80 (at 1.2 times the peak memory).
const STROKE_PIECE: usize = 100;

/// `chains` cut into runs of at most `n` points (n ≥ 2), each beginning where the one before
/// ends. With round joins and ends the strokes of the runs unite to the stroke of the chain:
/// both are the chain's points within the tool radius.
fn pieces(chains: &[Vec<[f64; 2]>], n: usize) -> impl Iterator<Item = &[[f64; 2]]> {
    let step = n.max(2) - 1;
    chains.iter().flat_map(move |c| {
        let runs = c.len().saturating_sub(1).div_ceil(step).max(1);
        (0..runs).map(move |k| &c[k * step..(k * step + step + 1).min(c.len())])
    })
}

/// The union of `shapes`, two at a time, the results again two at a time, until one is left:
/// every overlay is of two sets of about equal size.
fn united(mut shapes: Vec<Vec<Shape>>) -> Vec<Shape> {
    while shapes.len() > 1 {
        let mut next = Vec::with_capacity(shapes.len().div_ceil(2));
        let mut them = shapes.into_iter();
        while let Some(a) = them.next() {
            next.push(match them.next() {
                Some(b) => a.overlay(&b, OverlayRule::Union, FillRule::NonZero),
                None => a,
            });
        }
        shapes = next;
    }
    shapes.pop().unwrap_or_default()
}

fn pocket_check(
    pocket: &Pocket,
    prepared: &PreparedPocket,
    swept: &[Shape],
    gouge: (f64, Option<Place>),
    r: f64,
    tol: &Tolerance,
) -> Result<PocketCheck, OffsetError> {
    // What the tool can reach: the pocket eroded by the radius, then grown back.
    let centres = prepared.offset(r, tol)?;
    let reach: Vec<Contour> = if centres.is_empty() {
        Vec::new()
    } else {
        PreparedPocket::from_loops(centres).offset(-r, tol)?
    };
    let reach_rings: Vec<Vec<[f64; 2]>> = reach.iter().map(|c| ring(c, CHORD)).collect();
    let reachable_area: f64 = reach.iter().map(Contour::signed_area).sum();
    let leftover: Vec<Shape> = if reach_rings.is_empty() {
        Vec::new()
    } else {
        reach_rings.overlay(&swept.to_vec(), OverlayRule::Difference, FillRule::NonZero)
    };
    let leftover_area: f64 = leftover.iter().map(shape_area).sum();
    let mut thickest: (f64, Option<Place>) = (0.0, None);
    for piece in &leftover {
        // No circle inside a shape is wider than 4·area/perimeter: most pieces are rounding
        // slivers along the walls and need no search.
        let perimeter: f64 = piece.iter().map(|r| super::polygon::ring_length(r)).sum();
        let bound = 4.0 * shape_area(piece) / perimeter.max(1e-300);
        if bound <= thickest.0.max(1e-3) {
            continue;
        }
        let (c, radius) = largest_inscribed_circle(piece, 1e-4);
        if 2.0 * radius > thickest.0 {
            thickest = (
                2.0 * radius,
                Some(Place {
                    x: c.x,
                    y: c.y,
                    line: 0,
                }),
            );
        }
    }
    Ok(PocketCheck {
        area: pocket.area(),
        reachable_area,
        gouge: gouge.0.max(0.0),
        gouge_at: gouge.1,
        leftover_area,
        leftover_percent: if reachable_area > 0.0 {
            100.0 * leftover_area / reachable_area
        } else {
            0.0
        },
        thickest: thickest.0,
        thickest_at: thickest.1,
        leftover,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_cover_each_chain_and_meet_end_to_start() {
        let chain = |n: usize| (0..n).map(|i| [i as f64, 0.0]).collect::<Vec<_>>();
        let chains = vec![chain(1), chain(2), chain(5), chain(9), chain(10)];
        let runs: Vec<&[[f64; 2]]> = pieces(&chains, 4).collect();
        let lens: Vec<usize> = runs.iter().map(|r| r.len()).collect();
        // 1 and 2 points: one run each; 5: 4 + 2; 9: 4 + 4 + 3; 10: 4 + 4 + 4.
        assert_eq!(lens, vec![1, 2, 4, 2, 4, 4, 3, 4, 4, 4]);
        for w in runs[2..4].windows(2) {
            assert_eq!(w[0].last(), w[1].first());
        }
    }

    #[test]
    fn a_chain_stroked_in_pieces_covers_what_it_covers_stroked_whole() {
        // A zigzag of 600 points, its turns closer together than the tool is wide: the pieces'
        // strokes overlap one another where the stroke of the whole overlaps itself.
        let zigzag: Vec<[f64; 2]> = (0..600)
            .map(|i| [0.5 * i as f64, if i % 2 == 0 { 0.0 } else { 1.5 }])
            .collect();
        let r = 3.0;
        let angle = 2.0 * (1.0 - CHORD / r).acos();
        let style = StrokeStyle::new(2.0 * r)
            .line_join(LineJoin::Round(angle))
            .start_cap(LineCap::Round(angle))
            .end_cap(LineCap::Round(angle));
        let area = |shapes: &[Shape]| shapes.iter().map(shape_area).sum::<f64>();
        let whole = [zigzag.clone()].stroke(style.clone(), false);
        let parts: Vec<Vec<Shape>> = pieces(std::slice::from_ref(&zigzag), 50)
            .map(|p| [p].stroke(style.clone(), false))
            .collect();
        assert_eq!(parts.len(), 13);
        let united = united(parts);
        assert_eq!(united.len(), 1, "one region, as the whole stroke is");
        // The two outlines are flattened to within CHORD of the same curves, about 600 mm of
        // them: the areas agree to within that band.
        assert!((area(&united) - area(&whole)).abs() < 600.0 * CHORD);
        assert!(area(&whole) > 299.5 * 7.5);
    }
}
