//! Linking: the order in which loops are cut, where each starts, how the tool gets down into
//! the stock, how it goes from one loop to the next, and the depth passes. The result is a
//! [`Toolpath`] of exact lines and arcs.
//!
//! In: each pocket as a [`PreparedPocket`] with its [`ClearPlan`], and [`LinkParams`] (depth,
//! step-down, heights, [`Direction`], [`Entry`]). Out: [`Linked`], the tool path and its
//! [`LinkWarning`]s. The milling direction is chosen here ([`Direction`]); `schedule.rs` the
//! order the parts are cut in, `ladder.rs` the loops round one island cut towards it and the
//! way out of them, `entry.rs` finds helices and ramps, `lead.rs` the arcs onto and off the
//! finishing loop, `walk.rs` where a loop is started, `route.rs` and `detour.rs` the ways at
//! depth, `order.rs` short tours.
//!
//! Each part of the clearing tree is cut after everything inside it (inside-out): its children
//! first, then its clean-up paths and the loops around its islands, along a short tour where
//! they are few (else nearest first), and its outer loop last, or first where it is the
//! nearest (a ring's levels: the outer loop beside the one just cut, not the far side of the
//! ring there and back). Once
//! a part's children are cut, the tool may move at depth anywhere that stays inside the part
//! (every point at least the part's distance from the walls): such a move crosses only the
//! band the part's own loops are about to clear. Other moves retract to the safe height and
//! come down again where the stock is already cleared, or enter anew.

mod air;
mod detour;
mod entry;
mod ladder;
mod lead;
mod order;
mod route;
mod schedule;
mod walk;

pub use detour::detour;
pub use entry::Helix;
pub use order::{path_order, tour, tour_length};

use crate::clear::{ClearPlan, Part, Path, Spot};
use crate::geom::PreparedPocket;
use crate::geom::{bbox_of, nearest_on, Aabb, BoxIndex, Point, Segment, Tolerance};
use crate::machining_time::TimeModel;
use crate::toolpath::{Feed, Point3, Toolpath};
use ladder::Ladder;
use std::cell::OnceCell;

/// Longest move at depth through uncut stock from one branch to the next, in tool radii: a
/// deliberate slot, no wider than the tool, instead of a retract and a new entry.
pub const MAX_SLOT_LINK_RADII: f64 = 8.0;

/// How far from where a part is entered its paths are looked about for a helix, in tool
/// radii, before all of them are (see [`Linker::find_helix`]).
const HELIX_NEAR_RADII: [f64; 2] = [2.0, 10.0];

/// Most walls a way round what is in the way is tested against one by one (see
/// [`Linker::detour_within`]); beyond, through the pocket's index.
const MAX_LOCAL_WALLS: usize = 256;

/// Most paths of a part that the choice of the next is made by a tour over (see
/// [`next_item`]); beyond it, the nearest.
const MAX_TOURED_ITEMS: usize = 32;

/// How far from a loop a clean-up path may lie and still be cut on the loop's way round, in
/// tool radii: both its ends within this of the loop's point nearest to it, and the tool
/// straight back to that point from its far end when that is as near (see
/// [`Linker::host_of`]). Two, a tool diameter: the move out and back each cut at most a
/// slot as long as the tool is wide. Measured on the linking bench, where the faster of the
/// two ways of cutting a part is kept (see [`Linker::cut_part_timed`]): within one radius,
/// the 90 % rectangle took 375.5 s; within two, 363.6 s (its share of cutting above 150°
/// 23.0 -> 22.0 %, p95 the same); three or more gained 1 s more; no other drawing slower.
const HOST_REACH_RADII: f64 = 2.0;

/// Spacing of the lattice a way round what is in the way is searched on, in tool radii: fine
/// enough for the passages between neighbouring loops, coarse enough for a few hundred points.
const DETOUR_STEP_RADII: f64 = 0.25;

/// To what share of the way in to a spot the point where the tool first sweeps all that the
/// spot answers for is found, by halving (see [`Linker::stop_short`]): 1/256, eight halvings,
/// hundredths of a millimetre for the few millimetres a spot lies from a loop. Each halving
/// tests every segment of what is left: on the 300-hole plate at 40 % they are 1.2 % of the
/// instructions of `pocket` (whole, 1.020 of them before the spots stopped short); at 1/64,
/// 0.8 %, and the program 10 mm longer.
const SPOT_STOP_RESOLUTION: f64 = 1.0 / 256.0;

/// Which way the tool goes round, for a spindle turning clockwise seen from above (M3).
///
/// In climb milling the teeth meet the material thick-first, the chip thinning as the tooth
/// leaves it: with an M3 spindle that puts the material on the tool's right as it moves, the
/// side G41 (cutter compensation left) leaves it on. A pocket's wall loop therefore runs
/// counter-clockwise and each island's loop clockwise, the way the clearing plan stores them;
/// helix entries turn counter-clockwise (the material around the helix on the right).
/// Conventional milling is the mirror of each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Material on the tool's right: counter-clockwise along the pocket wall, clockwise
    /// around islands.
    Climb,
    /// Material on the tool's left: clockwise along the pocket wall, counter-clockwise around
    /// islands.
    Conventional,
}

/// How the tool gets down into the stock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Entry {
    /// A helix in the first part cut; a ramp when none fits; a plunge when neither does.
    Helix,
    /// A ramp along the first path; a plunge when it is too short.
    Ramp,
    /// Straight down.
    Plunge,
}

/// How loops become one tool path. The tool's radius is the plans' ([`ClearPlan::tool_radius`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkParams {
    /// Final depth below the stock top, mm (positive).
    pub depth: f64,
    /// Largest depth of one pass, mm.
    pub step_down: f64,
    /// Height above the stock for rapid moves, mm.
    pub safe_z: f64,
    /// How far above the stock (or above the floor already cut at that spot) a rapid descent
    /// stops and the plunge feed takes over, mm.
    pub feed_height: f64,
    /// Climb or conventional.
    pub direction: Direction,
    /// Helix, ramp or plunge.
    pub entry: Entry,
    /// Largest angle of helix and ramp moves from the horizontal, radians.
    pub ramp_angle: f64,
    /// The feeds, rapid rate and retract cost the linking's choices are timed with (the
    /// cutting and plunge feeds the program will have).
    pub time: TimeModel,
}

impl Default for LinkParams {
    /// 1 mm deep in one pass, a 5 mm safe height, a 1 mm feed height, climb milling, helix
    /// entries at most 3°, the default time model.
    fn default() -> LinkParams {
        LinkParams {
            depth: 1.0,
            step_down: 1.0,
            safe_z: 5.0,
            feed_height: 1.0,
            direction: Direction::Climb,
            entry: Entry::Helix,
            ramp_angle: 3f64.to_radians(),
            time: TimeModel::default(),
        }
    }
}

/// Why a tool path cannot be linked: a parameter out of range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkError {
    /// The depth is not positive.
    #[error("the depth must be positive (got {0} mm)")]
    Depth(f64),
    /// The step-down is not positive.
    #[error("the step-down must be positive (got {0} mm)")]
    StepDown(f64),
    /// More passes than any job needs.
    #[error("{depth} mm in steps of {step_down} mm would take more than 10000 passes")]
    TooManyPasses {
        /// The depth, mm.
        depth: f64,
        /// The step-down, mm.
        step_down: f64,
    },
    /// The safe height is not above the stock.
    #[error("the safe height must be above the stock (got {0} mm)")]
    SafeZ(f64),
    /// The ramp angle is not between 0 and 90 degrees.
    #[error("the ramp angle must be between 0 and 90 degrees (got {0})")]
    RampAngle(f64),
}

impl LinkParams {
    /// Checks that every parameter is in range ([`link`] does it first).
    pub fn check(&self) -> Result<(), LinkError> {
        if !(self.depth.is_finite() && self.depth > 0.0) {
            return Err(LinkError::Depth(self.depth));
        }
        if !(self.step_down.is_finite() && self.step_down > 0.0) {
            return Err(LinkError::StepDown(self.step_down));
        }
        if self.depth / self.step_down > 10_000.0 {
            return Err(LinkError::TooManyPasses {
                depth: self.depth,
                step_down: self.step_down,
            });
        }
        if !(self.safe_z.is_finite() && self.safe_z > 0.0) {
            return Err(LinkError::SafeZ(self.safe_z));
        }
        if !(self.ramp_angle > 0.0 && self.ramp_angle < std::f64::consts::FRAC_PI_2) {
            return Err(LinkError::RampAngle(self.ramp_angle.to_degrees()));
        }
        Ok(())
    }
}

/// A linked tool path and what the user should know about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Linked {
    /// The moves.
    pub toolpath: Toolpath,
    /// Remarks, such as plunges where nothing else fitted.
    pub warnings: Vec<LinkWarning>,
}

/// Something about a linked tool path the machinist should know.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkWarning {
    /// Neither a helix nor a ramp fits where a part is entered: the tool plunges straight down.
    #[error("no room for a helix or a ramp at ({:.3}, {:.3}): plunging straight down to Z{z:.3}", .at.x, .at.y)]
    Plunged {
        /// Where, mm.
        at: Point,
        /// The depth plunged to, mm.
        z: f64,
    },
}

/// The Z of each depth pass: equal passes of at most `step_down`, the last at `-depth`.
///
/// ```
/// assert_eq!(pocketeer::link::pass_depths(2.0, 0.8), vec![-2.0 / 3.0, -4.0 / 3.0, -2.0]);
/// assert_eq!(pocketeer::link::pass_depths(2.0, 2.0), vec![-2.0]);
/// ```
pub fn pass_depths(depth: f64, step_down: f64) -> Vec<f64> {
    let n = (depth / step_down - 1e-9).ceil().max(1.0) as usize;
    (1..=n).map(|k| -depth * k as f64 / n as f64).collect()
}

/// Links the plans of several pockets (each with its prepared pocket) into one tool path,
/// starting and ending at the safe height, its parameters checked first.
pub fn link(
    jobs: &[(&PreparedPocket, &ClearPlan)],
    params: &LinkParams,
    tol: &Tolerance,
) -> Result<Linked, LinkError> {
    link_with(jobs, params, tol, &crate::progress::Silent)
}

/// [`link`], telling `progress` of the loops cut: the stage `linking N loops` with a step for
/// each loop or clean-up path at each pass depth.
pub fn link_with(
    jobs: &[(&PreparedPocket, &ClearPlan)],
    params: &LinkParams,
    tol: &Tolerance,
    progress: &dyn crate::progress::Progress,
) -> Result<Linked, LinkError> {
    let linked = link_hosting(jobs, params, tol, progress, None)?;
    // Stretches through stock already cleared are shortened where every plan has one tool.
    let radius = jobs.first().map(|(_, plan)| plan.tool_radius);
    let toolpath = match radius {
        Some(r) if jobs.iter().all(|(_, plan)| plan.tool_radius == r) => {
            air::shortcut_air(linked.toolpath, r)
        }
        _ => linked.toolpath,
    };
    Ok(Linked { toolpath, ..linked })
}

/// Where a part's clean-up paths are cut (see [`Linker::cut_part`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Hosting {
    /// On the way round the part's loops, or round the loops of the leaves cut after it, and
    /// among those leaves when beside one.
    Everywhere,
    /// On the way round the part's own loops, or among its paths: nothing waits for the leaves.
    OwnLoops,
    /// Each as a path of its own (among the leaves cut after the part when beside one).
    Never,
}

/// [`link_with`] before stretches through cleared stock are shortened (see [`air`]), the
/// clean-up paths cut where `hosting` says, or the way that takes less time, part by part
/// (`None`, see [`Linker::cut_part_timed`]).
fn link_hosting(
    jobs: &[(&PreparedPocket, &ClearPlan)],
    params: &LinkParams,
    tol: &Tolerance,
    progress: &dyn crate::progress::Progress,
    hosting: Option<Hosting>,
) -> Result<Linked, LinkError> {
    params.check()?;
    let passes = pass_depths(params.depth, params.step_down);
    let loops: usize = jobs.iter().map(|(_, plan)| plan.loop_count()).sum();
    progress.stage(
        &format!("linking {loops} loops"),
        Some((loops * passes.len()) as u64),
    );
    let start = Point3::new(0.0, 0.0, params.safe_z);
    let mut linker = Linker {
        params,
        tol,
        progress,
        path: Toolpath::new(start),
        warnings: Vec::new(),
        pocket: jobs.first().map(|j| j.0),
        plan: None,
        z: 0.0,
        z_top: 0.0,
        down: false,
        last: (Vec::new(), false),
        boxes: Vec::new(),
        path_boxes: Vec::new(),
        cut_early: std::collections::HashSet::new(),
        enclosed: std::collections::HashMap::new(),
        uncut: UncutLeaves::default(),
        hosting,
        hosted: 0,
        deferred: 0,
        helices: Vec::new(),
        stepped_out: None,
    };
    // Each separate piece of the job (a root part of a pocket) is cut through all its passes
    // before the next; the pieces in a short tour over the middles of their outer loops.
    let pieces: Vec<(usize, usize)> = (jobs.iter().enumerate())
        .flat_map(|(j, (_, plan))| plan.roots.iter().map(move |&r| (j, r)))
        .collect();
    let places: Vec<Point> = pieces
        .iter()
        .map(|&(j, r)| {
            let b = jobs[j].1.parts[r].outer.bbox();
            b.min.midpoint(b.max)
        })
        .collect();
    for k in tour(&places, start.xy()) {
        let (j, root) = pieces[k];
        let (pocket, plan) = jobs[j];
        linker.pocket = Some(pocket);
        if !linker.plan.is_some_and(|p| std::ptr::eq(p, plan)) {
            linker.helices.clear();
            linker.boxes = plan.parts.iter().map(|p| p.outer.bbox()).collect();
            linker.path_boxes = plan.parts.iter().map(|_| OnceCell::new()).collect();
        }
        linker.plan = Some(plan);
        let mut z_top = 0.0;
        for &z in &passes {
            linker.z = z;
            linker.z_top = z_top;
            linker.cut(root);
            linker.retract();
            z_top = z;
        }
    }
    Ok(Linked {
        toolpath: linker.path,
        warnings: linker.warnings,
    })
}

struct Linker<'a> {
    params: &'a LinkParams,
    tol: &'a Tolerance,
    /// Told of each path cut.
    progress: &'a dyn crate::progress::Progress,
    path: Toolpath,
    warnings: Vec<LinkWarning>,
    pocket: Option<&'a PreparedPocket>,
    plan: Option<&'a ClearPlan>,
    /// Depth of the current pass.
    z: f64,
    /// Floor of the previous pass (0 for the first): the stock is cleared down to it.
    z_top: f64,
    /// True while the tool is down at the pass depth.
    down: bool,
    /// The walk last cut (the tool is at its end), and whether it is a closed loop.
    last: (Vec<Segment>, bool),
    /// The boxes of the plan's parts (their outer loops), by part: asked for at every
    /// choice of the next part and landing, and each a pass over its loop.
    boxes: Vec<Aabb>,
    /// The boxes of each part's paths (its loops, then its clean-up paths), by part, made
    /// when a helix is first looked for in it: a plate's part is entered many times.
    path_boxes: Vec<OnceCell<Vec<Aabb>>>,
    /// Loops round islands (part, index among its holes) cut in this pass before their part,
    /// each right after the loop round the same islands one level in (see
    /// [`Linker::cut_enclosed_holes`]).
    cut_early: std::collections::HashSet<(usize, usize)>,
    /// By part, for each of its loops round islands, the loop of its parent it encloses
    /// alone (see [`Linker::enclosed_hole`]): found once a pass.
    enclosed: std::collections::HashMap<usize, Vec<Option<usize>>>,
    /// The plain leaves of nested loops of the part being cut that wait for its paths (see
    /// [`Linker::is_plain_leaf`]): their stock is not cut, and no link at depth crosses them.
    uncut: UncutLeaves,
    /// Where clean-up paths are cut (see [`Linker::cut_part`]): fixed by the caller, or none,
    /// and [`Linker::cut_part_timed`] tries a part each way that differs (setting it for all
    /// but the first).
    hosting: Option<Hosting>,
    /// How many clean-up paths have been given a loop to be cut from (see
    /// [`Linker::host_of`]).
    hosted: usize,
    /// How many of a part's clean-up paths have been left to be cut with the leaves after it
    /// (see [`Linker::cut_part`]).
    deferred: usize,
    /// The helices found for the entries into the plan's parts (see [`Linker::find_helix`]):
    /// [`Linker::cut_part_timed`] cuts a part twice, every pass enters the same parts, and a
    /// helix looked for about all of a large part's paths took 290 ms of the 300-hole plate's
    /// job at 85 % stepover, each time.
    helices: Vec<FoundHelix>,
    /// The number of moves right after the straight step back out from the loops round one
    /// island (see [`Linker::leave_ladder`]): a retract right after it leaves from where the
    /// step began instead, the step being of no use then.
    stepped_out: Option<usize>,
}

/// Where the linking was before a part was cut, to try cutting it another way (see
/// [`Linker::cut_part_timed`]).
struct Mark {
    moves: usize,
    warnings: usize,
    down: bool,
    last: (Vec<Segment>, bool),
    cut_early: std::collections::HashSet<(usize, usize)>,
}

/// A helix looked for (see [`Linker::find_helix`]) and what it depends on besides the plan:
/// the part, the walk it leads to (its start, end and number of segments) and the leaves not
/// cut yet that the way from the helix may not cross.
struct FoundHelix {
    part: usize,
    walk: (Point, Point, usize),
    uncut: (Vec<usize>, Vec<bool>),
    helix: Option<Helix>,
}

/// What cutting a part one way added and left, to be put back if that way is kept.
struct Tried {
    moves: Vec<crate::toolpath::Move>,
    warnings: Vec<LinkWarning>,
    down: bool,
    last: (Vec<Segment>, bool),
    cut_early: std::collections::HashSet<(usize, usize)>,
    uncut: UncutLeaves,
    stepped_out: Option<usize>,
}

impl<'a> Linker<'a> {
    fn plan(&self) -> &'a ClearPlan {
        self.plan
            .unwrap_or_else(|| unreachable!("a plan is set before cutting"))
    }

    fn pocket(&self) -> &'a PreparedPocket {
        self.pocket
            .unwrap_or_else(|| unreachable!("a pocket is set before cutting"))
    }

    fn here(&self) -> Point {
        self.path.position().xy()
    }

    /// Cuts the small leaves of `parent`, just cut, and its plain leaves not cut on the way
    /// round its paths, nearest first: each reached at depth through the parent's region
    /// (cleared but for the leaves' own remains). The parent's clean-up paths `deferred` to
    /// them (see [`Linker::cut_part`]) are cut on the way round the loop of the leaf each
    /// names, or, naming none, whenever one is nearer than every leaf left; a leaf of one
    /// loop cuts its own clean-up paths on its way round where it can (see
    /// [`Linker::host_of`]), the others after its loops, nearest first.
    fn cut_small_leaves(
        &mut self,
        parent: usize,
        mut leaves: Vec<usize>,
        deferred: Vec<(Option<usize>, Path)>,
    ) {
        let plan = self.plan();
        let cut = [parent];
        let reach = Reach {
            distance: plan.parts[parent].distance,
            cut: &cut,
        };
        let (mut loose, mut hosted): (Vec<_>, Vec<_>) = deferred.into_iter().partition(|d| d.0.is_none());
        while !leaves.is_empty() || !loose.is_empty() {
            let here = self.here();
            let to_leaf: Vec<f64> = (leaves.iter())
                .map(|&c| walk::distance_to_start(&loop_path(&plan.parts[c].outer.segments), here))
                .collect();
            let to_loose: Vec<f64> = (loose.iter())
                .map(|(_, p)| walk::distance_to_start(p, here))
                .collect();
            let (k, j) = (nearest(&to_leaf, |&d| d), nearest(&to_loose, |&d| d));
            let nearest_leaf = to_leaf.get(k).copied().unwrap_or(f64::INFINITY);
            if to_loose.get(j).is_some_and(|&d| d < nearest_leaf) {
                let (_, path) = loose.swap_remove(j);
                self.cut_path(parent, &path, false, reach);
                continue;
            }
            let l = leaves.swap_remove(k);
            let leaf = &plan.parts[l];
            self.uncut.cut(l);
            let chain = self.chain(l).unwrap_or_else(|| vec![l]);
            let outer = loop_path(&leaf.outer.segments);
            // On the way round its loop, the parent's clean-up paths given to it, and where the
            // leaf is one loop, its own that the loop passes near (they lie inside it).
            let (mine, others): (Vec<_>, Vec<_>) = hosted.into_iter().partition(|d| d.0 == Some(l));
            hosted = others;
            let mut on_the_way: Vec<Excursion> = mine.into_iter().map(|d| Excursion::Cleanup(d.1)).collect();
            let mut hosted_own = Vec::new();
            if chain.len() == 1 {
                for (i, c) in leaf.cleanups.iter().enumerate() {
                    if self.host_of(c, &outer, &[]).is_some() {
                        self.hosted += 1;
                        on_the_way.push(Excursion::Cleanup(c.clone()));
                        hosted_own.push(i);
                    }
                }
            }
            self.cut_path_with(l, &outer, &on_the_way, false, reach);
            // A plain leaf's nested parts, each from the one around it.
            for w in chain.windows(2) {
                let cut = [w[0]];
                let reach = Reach {
                    distance: plan.parts[w[0]].distance,
                    cut: &cut,
                };
                self.cut_path(w[1], &loop_path(&plan.parts[w[1]].outer.segments), false, reach);
            }
            // Then the clean-up paths of all of them, nearest first, each from the part around
            // its part (they lie between a part's loop and the loop inside it, both cut now).
            let items: Vec<(usize, &Path)> = (chain.iter())
                .flat_map(|&c| plan.parts[c].paths().enumerate().map(move |(i, p)| (c, i, p)))
                .filter(|&(c, i, _)| c != l || !hosted_own.contains(&i))
                .map(|(c, _, p)| (c, p))
                .collect();
            // In the order of least travel on to the nearest of what is cut next, where they
            // are few: nearest first, the tool left the diamond between four islands at
            // 90 % stepover at its far side from the next.
            let here = self.here();
            let next = (leaves
                .iter()
                .map(|&c| nearest_point(&plan.parts[c].outer.segments, here)))
            .chain(loose.iter().map(|(_, p)| p.ends().0))
            .min_by(|a, b| a.distance(here).total_cmp(&b.distance(here)));
            let ways: Vec<(Point, Point)> = items.iter().map(|(_, p)| p.ends()).collect();
            let order = path_order(&ways, here, next);
            for (c, item) in order.into_iter().map(|k| items[k]) {
                let around = [plan.parts[c].parent.unwrap_or(parent)];
                let reach = Reach {
                    distance: plan.parts[around[0]].distance,
                    cut: &around,
                };
                self.cut_path(c, item, false, reach);
            }
        }
    }

    /// Cuts the paths of the part `n` itself, what goes before it being cut (`first` when
    /// nothing inside it is): clean-up paths and loops round islands nearest first, the outer
    /// loop last, or first when it is nearer than all of them. (Nearest first throughout
    /// crosses a ring once a level too, but cutting the outer loop between the others changed
    /// which loop takes the heavier cut where they come close: the 8-island rectangle's p95
    /// engagement rose from 140° to 141°.)
    ///
    /// Each of the leaves `along` is cut on the way round the last of these paths that passes
    /// within a tool diameter of it (whose cut and the leaf's overlap), as an excursion from
    /// its point nearest to the leaf when the leaf's loop is within the tool radius there
    /// (the step across then cuts only what the leaf's loop is about to cut). The leaves
    /// that are not, returned, are cut after the part from the stock it cleared.
    ///
    /// The part's clean-up paths that go with those leaves and with the leaves `after` (the
    /// small leaves cut after it), returned too, are cut with them (see
    /// [`Linker::cut_small_leaves`]): each that a leaf's loop can cut on its way round, from
    /// nearer than any loop of the part, with the leaf it names; each that no loop can, with
    /// one end within reach of a leaf's loop, among the leaves (none). Cut among the part's
    /// own paths before the leaves, such paths were joined by straight moves through the
    /// leaves' stock or round them: on the 90 % rectangle, between two islands and a wall,
    /// along the edge of the triangle there, which its loop then followed cutting nothing.
    fn cut_part(
        &mut self,
        n: usize,
        mut first: bool,
        reach: Reach,
        along: &[usize],
        after: &[usize],
    ) -> (Vec<usize>, Vec<(Option<usize>, Path)>) {
        let part = &self.plan().parts[n];
        // The part's loops, each with the clean-up paths cut on the way round it, and the
        // loops round islands with the index among the part's holes (those cut already, right
        // after the loop enclosing them one level in, left out).
        let mut outer = (loop_path(&part.outer.segments), Vec::new());
        let (mut items, mut hole_of): (Vec<_>, Vec<_>) = (part.holes.iter())
            .enumerate()
            .filter(|&(j, _)| !self.cut_early.contains(&(n, j)))
            .map(|(j, h)| ((loop_path(&h.segments), Vec::new()), Some(j)))
            .unzip();
        let mut loose = Vec::new();
        // The leaves cut after the part (see `cut_small_leaves`): a clean-up path that the loop
        // of one passes nearer than the part's own loops is cut on the way round it. Beside a
        // leaf, the straight way from one such path to the next ran through the leaf's stock
        // the leaf's loop then went round again, cutting nothing.
        // None when the part keeps its clean-up paths to its own loops.
        let later: Vec<usize> = if self.hosting == Some(Hosting::OwnLoops) {
            Vec::new()
        } else {
            (along.iter().copied())
                .filter(|&l| self.waits_for_parent(l))
                .chain(after.iter().copied())
                .collect()
        };
        let mut deferred = Vec::new();
        for c in &part.cleanups {
            let on_part = self.host_of(c, &outer.0, &items);
            match (on_part, self.leaf_host_of(c, &later)) {
                (_, Some((leaf, d))) if on_part.is_none_or(|(_, e)| d < e) => {
                    self.hosted += 1;
                    deferred.push((Some(leaf), c.clone()));
                }
                (Some((k, _)), _) => {
                    self.hosted += 1;
                    let host = if k == 0 { &mut outer.1 } else { &mut items[k - 1].1 };
                    host.push(Excursion::Cleanup(c.clone()));
                }
                _ if self.beside_a_leaf(c, &later) => deferred.push((None, c.clone())),
                _ => loose.push((c.clone(), Vec::new())),
            }
        }
        self.deferred += deferred.len();
        // A finishing loop has leads, nothing on its way round (no part has spots beside one).
        let leads = part.level == 0 && self.plan().allowance > 0.0;
        let spots: &[Spot] = if leads { &[] } else { &part.spots };
        if leads {
            loose.extend(part.spots.iter().map(|s| (s.path.clone(), Vec::new())));
        }
        hole_of.extend(loose.iter().map(|_| None));
        items.extend(loose);
        // The leaves and spots beside each path (the outer loop 0, the items from 1), and how
        // many paths beside each are still to cut.
        let mut leaves = LeavesBeside::new(self, part, &outer.0, &items, along, spots);
        self.uncut = UncutLeaves::new(self.plan(), along);
        let mut ids: Vec<usize> = (1..=items.len()).collect();
        let here = self.here();
        let to_outer = walk::distance_to_start(&outer.0, here);
        let outer_first =
            !items.is_empty() && (items.iter()).all(|p| to_outer < walk::distance_to_start(&p.0, here));
        if outer_first {
            leaves.ready(self, 0, &mut outer);
            self.cut_path_with(n, &outer.0, &outer.1, first, reach);
            first = false;
        }
        // The items' boxes: nearest() measures only those a box does not already rule out.
        let mut boxes: Vec<Aabb> = items.iter().map(|(p, _)| bbox_of(&p.segments)).collect();
        // Where the tool is left on the loops round one island after cutting them towards it,
        // until it is known where it goes next.
        let mut ladder: Option<Ladder> = None;
        while !items.is_empty() {
            let here = ladder.as_ref().map_or_else(|| self.here(), |l| l.back_to);
            let k = next_item(&items, &boxes, here);
            boxes.swap_remove(k);
            let mut item = items.swap_remove(k);
            let hole = hole_of.swap_remove(k);
            leaves.ready(self, ids.swap_remove(k), &mut item);
            if let Some(l) = ladder.take() {
                self.leave_ladder(l, Some(&item.0), reach.distance);
            }
            self.cut_path_with(n, &item.0, &item.1, first, reach);
            first = false;
            if let Some(j) = hole {
                ladder = self.cut_enclosed_holes(n, j);
            }
        }
        if !outer_first {
            leaves.ready(self, 0, &mut outer);
            if let Some(l) = ladder.take() {
                self.leave_ladder(l, Some(&outer.0), reach.distance);
            }
            self.cut_path_with(n, &outer.0, &outer.1, first, reach);
        }
        if let Some(l) = ladder {
            self.leave_ladder(l, None, reach.distance);
        }
        // The spots that no path cut on its way round, nearest first.
        let mut spots = std::mem::take(&mut leaves.left_spots);
        while !spots.is_empty() {
            let here = self.here();
            let k = nearest(&spots, |p| walk::distance_to_start(p, here));
            let spot = spots.swap_remove(k);
            self.cut_path(n, spot, false, reach);
        }
        (leaves.left, deferred)
    }

    /// Cuts the part `n` ([`Linker::cut_part`]) and the leaves that wait for it
    /// ([`Linker::cut_small_leaves`], with `after`), its clean-up paths cut on the way round
    /// its loops or its leaves' where they can be (see [`Linker::host_of`]); when that cut any
    /// so, or left any to the leaves, again each way that differs ([`Hosting`]), keeping the
    /// one that takes least time. None is faster everywhere: a clean-up path beside a loop
    /// costs a step out and back (on the 8-island rectangle at 70 % stepover the excursions
    /// saved 23 s of 403), but a row of short ones is cut in one pass from each to the next
    /// (the 10 × 6 island grid at 85 %: 589 s as paths of their own, 650 s as excursions);
    /// leaving paths to the leaves spared the 90 % rectangle a link through each triangle's
    /// stock, but on FLH-001 at 60 % it took two from the part's loop that cut them on its
    /// way round, and the part's loops were then cut in another order, with a 44 mm link.
    /// What the way chosen does to the link to the next part is not counted.
    fn cut_part_timed(&mut self, n: usize, first: bool, reach: Reach, along: &[usize], after: Vec<usize>) {
        let plan = self.plan();
        let open = plan.allowance == 0.0 && plan.parts[n].cleanups.iter().any(|c| !c.closed);
        let cut = |linker: &mut Linker, mut after: Vec<usize>| {
            let (left, deferred) = linker.cut_part(n, first, reach, along, &after);
            after.extend(left);
            linker.cut_small_leaves(n, after, deferred);
        };
        if !open || self.hosting.is_some() {
            return cut(self, after);
        }
        let (mark, hosted, deferred) = (self.mark(), self.hosted, self.deferred);
        self.hosting = Some(Hosting::Everywhere);
        cut(self, after.clone());
        self.hosting = None;
        // The other ways, where they differ from this one.
        let others = [
            (self.deferred != deferred).then_some(Hosting::OwnLoops),
            (self.hosted != hosted).then_some(Hosting::Never),
        ];
        if others.iter().all(Option::is_none) {
            return;
        }
        let mut best = (self.seconds_since(&mark), self.back_to(&mark));
        // Told to nobody: the steps, one a path each way, were told as the first way was cut.
        let progress = std::mem::replace(&mut self.progress, &crate::progress::Silent);
        for way in others.into_iter().flatten() {
            self.hosting = Some(way);
            cut(self, after.clone());
            let seconds = self.seconds_since(&mark);
            let tried = self.back_to(&mark);
            if seconds < best.0 {
                best = (seconds, tried);
            }
        }
        self.hosting = None;
        self.progress = progress;
        let tried = best.1;
        self.path.moves.extend(tried.moves);
        self.warnings.extend(tried.warnings);
        (self.down, self.last, self.cut_early, self.uncut, self.stepped_out) = (
            tried.down,
            tried.last,
            tried.cut_early,
            tried.uncut,
            tried.stepped_out,
        );
    }

    /// True when an end of the clean-up path `c` lies within [`HOST_REACH_RADII`] tool radii
    /// of the loop of one of the `leaves` cut after its part (see
    /// [`Linker::cut_small_leaves`]): it is cut among them, the tool going on to whichever is
    /// nearest, instead of among the part's own paths before the leaves, when the way from it
    /// to the next path goes round or through a leaf not cut yet.
    fn beside_a_leaf(&self, c: &Path, leaves: &[usize]) -> bool {
        let (b, reach) = (bbox_of(&c.segments), self.host_reach());
        let (start, end) = c.ends();
        (leaves.iter()).any(|&l| {
            let outer = &self.plan().parts[l].outer.segments;
            self.boxes[l].distance_to_box(&b) <= reach
                && [start, end]
                    .iter()
                    .any(|&e| nearest_point(outer, e).distance(e) <= reach)
        })
    }

    /// True when the plain leaf `l` (see [`Linker::is_plain_leaf`]) is cut after its parent
    /// rather than on the way round its parent's loops: it has clean-up paths or spots,
    /// which are cut from the parent's cleared stock.
    fn waits_for_parent(&self, l: usize) -> bool {
        let parts = &self.plan().parts;
        (self.chain(l).unwrap_or_default().iter()).any(|&c| parts[c].paths().next().is_some())
    }

    /// Where the linking is now (see [`Linker::cut_part_timed`]).
    fn mark(&self) -> Mark {
        Mark {
            moves: self.path.moves.len(),
            warnings: self.warnings.len(),
            down: self.down,
            last: self.last.clone(),
            cut_early: self.cut_early.clone(),
        }
    }

    /// The time of the moves made since `mark`, in the time model the choices are made in.
    fn seconds_since(&self, mark: &Mark) -> f64 {
        self.params.time.moves(self.path.moves_from(mark.moves)).total()
    }

    /// Takes back what was done since `mark`, returning it.
    fn back_to(&mut self, mark: &Mark) -> Tried {
        let tried = Tried {
            moves: self.path.moves.split_off(mark.moves),
            warnings: self.warnings.split_off(mark.warnings),
            down: self.down,
            last: std::mem::replace(&mut self.last, mark.last.clone()),
            cut_early: std::mem::replace(&mut self.cut_early, mark.cut_early.clone()),
            uncut: std::mem::take(&mut self.uncut),
            stepped_out: self.stepped_out.take(),
        };
        self.down = mark.down;
        tried
    }

    /// How far from its loop a clean-up path cut on the loop's way round may lie, mm (see
    /// [`HOST_REACH_RADII`]).
    fn host_reach(&self) -> f64 {
        HOST_REACH_RADII * self.plan().tool_radius
    }

    /// The loop (0: `outer`, k: the k-th of `holes`) that cuts the clean-up path `c` on its
    /// way round (see [`Linker::excursions`]): the nearest whose point nearest to an end of
    /// `c` has both ends within [`HOST_REACH_RADII`] tool radii, with nothing in the way to
    /// either, so that the tool goes out straight; none when no loop passes so near (a longer
    /// path is cut from where the tool is, as its own item: going back along it doubled the
    /// clean-up on the 90 % rectangle; allowed for paths up to a tool radius long, before the
    /// faster way was chosen part by part, it made the 70 % one 3.6 s faster and the 90 % one
    /// 5.8 s slower), and for the finishing loop (it has leads).
    fn host_of(&self, c: &Path, outer: &Path, holes: &[(Path, Vec<Excursion>)]) -> Option<(usize, f64)> {
        if !self.may_host(c) {
            return None;
        }
        let loops = std::iter::once(outer).chain(holes.iter().map(|h| &h.0));
        (loops.enumerate())
            .filter_map(|(k, l)| self.hosts(&l.segments, c, true).map(|d| (k, d)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// True when the clean-up path `c` may be cut on a loop's way round at all: it is open,
    /// the loops have no leads (no finishing allowance), and hosting is not switched off (see
    /// [`Linker::host_of`]).
    fn may_host(&self, c: &Path) -> bool {
        !c.closed && self.plan().allowance == 0.0 && self.hosting != Some(Hosting::Never)
    }

    /// Of the `leaves` (parts cut after the clean-up path `c`'s part, see
    /// [`Linker::cut_small_leaves`]), the one whose loop cuts `c` on its way round, as
    /// [`Linker::host_of`] chooses among a part's loops, and how far it passes.
    fn leaf_host_of(&self, c: &Path, leaves: &[usize]) -> Option<(usize, f64)> {
        if leaves.is_empty() || !self.may_host(c) {
            return None;
        }
        let near = bbox_of(&c.segments).inflated(self.host_reach());
        (leaves.iter())
            .filter(|&&l| self.boxes[l].intersects(&near))
            .filter_map(|&l| (self.hosts(&self.plan().parts[l].outer.segments, c, true)).map(|d| (l, d)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// How far the open path `c` lies from the loop `l` (its segments) when `l` can cut it on its way round
    /// (see [`Linker::excursions`]): from `l`'s point nearest to an end of `c`, that end (with
    /// `both_ends`, both) within [`HOST_REACH_RADII`] tool radii with nothing in the way; none
    /// when `l` passes nowhere so near. A spot's pass may run on beyond: the tool comes back
    /// along it, where a clean-up path's way back along it is a second cut of the same.
    fn hosts(&self, l: &[Segment], c: &Path, both_ends: bool) -> Option<f64> {
        let (r, reach) = (self.plan().tool_radius, self.host_reach());
        let ends: [Point; 2] = c.ends().into();
        let mut best: Option<f64> = None;
        for end in ends {
            let p = nearest_point(l, end);
            let d = p.distance(end);
            let reached = |e: Point| p.distance(e) <= reach && self.stays_inside(p, e, r);
            let ok = if both_ends {
                ends.iter().all(|&e| reached(e))
            } else {
                reached(end)
            };
            if d <= reach && best.is_none_or(|b| d < b) && ok {
                best = Some(d);
            }
        }
        best
    }

    /// Cuts one loop or clean-up path of the part `part` (its index); `enter` when the tool comes to it through
    /// uncut stock (the first path of a part with nothing inside it), else reached at depth
    /// within `reach`.
    fn cut_path(&mut self, part: usize, item: &Path, enter: bool, reach: Reach) {
        self.cut_path_with(part, item, &[], enter, reach);
    }

    /// [`Linker::cut_path`], cutting the clean-up paths `on_the_way` as excursions from the
    /// walk of the loop `item` (see [`Linker::excursions`]).
    fn cut_path_with(&mut self, n: usize, item: &Path, on_the_way: &[Excursion], enter: bool, reach: Reach) {
        self.progress.advance(1);
        let part = &self.plan().parts[n];
        // The plan's loops run with the material on their right (outer loops counter-clockwise,
        // loops round islands clockwise): climb as they are.
        let reverse = self.params.direction == Direction::Conventional;
        let leads = item.closed && part.level == 0 && self.plan().allowance > 0.0;
        let here = self.here();
        let mut segments = walk::walk_from(item, here, reverse, self.tol.eps);
        // Where the tool stays down: whether the straight move to the walk's start comes too
        // near a wall, and if so the way round along the path just cut (the walk then starts
        // where that way arrives, and the move across is checked to that start).
        let mut blocked = None;
        let mut route = None;
        if !enter && self.down && !leads {
            let near_wall = !self.stays_inside(here, segments[0].start(), reach.distance);
            if near_wall {
                if let Some((moves, start)) = self.route_along_last(reach.distance, item, segments[0].start())
                {
                    let rerouted = walk::walk_from(item, start, reverse, self.tol.eps);
                    let (a, q) = (moves.last().map_or(here, Segment::end), rerouted[0].start());
                    if self.stays_inside(a, q, reach.distance) {
                        // Off the path just cut as soon as the way across is clear: the corner
                        // from its point nearest the next path is cut.
                        // The earliest point is where the move grazes a wall: a margin keeps
                        // it off.
                        let d = reach.distance + clearance_slack(reach.distance, self.tol);
                        let early = route::leave_early(&moves, 0.01, |p| self.stays_inside(p, q, d));
                        route = Some(early.unwrap_or(moves));
                        segments = rerouted;
                    }
                }
            }
            blocked = Some(near_wall);
        }
        if leads {
            let (plan, pocket) = (self.plan(), self.pocket());
            if let Some((lead_in, lead_out)) = lead::leads(
                &segments,
                part.distance,
                plan,
                pocket,
                self.params.direction,
                self.tol,
            ) {
                segments.insert(0, lead_in);
                segments.push(lead_out);
            }
        }
        let q = segments[0].start();
        if let Some(moves) = route {
            walk::follow(&mut self.path, &moves, self.z);
            self.path.line(Point3::at(q, self.z), Feed::Cut);
        } else if let Some(way) = (enter && self.down).then(|| self.slot_link(part, q)).flatten() {
            // A short slot through stock an enclosing part will clear anyway.
            self.feed_through(&way);
        } else if enter || !self.down {
            self.retract();
            self.enter(n, &segments);
        } else if blocked.unwrap_or_else(|| !self.stays_inside(here, q, reach.distance)) {
            // Round what is in the way, inside the part, when faster than going over the top:
            // down onto a floor cut near `q` and across, or, where there is none, a new entry.
            let landing = self.landing(reach, q);
            let over = match landing {
                Some(p) => self.hop_via(p, q),
                None => self.hop_seconds(here.distance(q), self.z_top) + self.entry_seconds(),
            };
            match self.detour_within(reach.distance, q, over, f64::INFINITY) {
                Some(way) => self.feed_through(&way),
                None => {
                    self.retract();
                    self.come_down_at(landing, n, &segments);
                }
            }
        } else if let Some(p) = self.hop_rather_than(q, reach) {
            // A long way across at the cutting feed: over the top at rapid is faster.
            self.retract();
            self.descend_to(p, self.z);
            self.path.line(Point3::at(q, self.z), Feed::Cut);
        } else {
            self.path.line(Point3::at(q, self.z), Feed::Cut);
        }
        if on_the_way.is_empty() || leads {
            walk::follow(&mut self.path, &segments, self.z);
        } else {
            self.excursions(&segments, on_the_way);
        }
        self.down = true;
        self.last = (segments, item.closed);
        self.stepped_out = None;
    }

    /// Follows the walk `segments` of a loop, cutting each of `cleanups` on the way: where the
    /// walk comes nearest to the clean-up path's nearer end, out to that end (within
    /// [`HOST_REACH_RADII`] tool radii), along the path, and back to the walk straight from its
    /// far end where that is as near and nothing is in the way, else back along it. A closed
    /// path among them is a leaf's loop (see [`Linker::cut_part`]): out from the walk's point
    /// nearest to it, round it from there and straight back. A clean-up path lies between a
    /// loop and the loops inside it, all of them cut when the walk passes: it is reached where
    /// the tool is, instead of by a link across the part (on the 8-island rectangle at 70 %
    /// stepover, 112 clean-up paths of 231 mm took 775 mm of links).
    fn excursions(&mut self, segments: &[Segment], cleanups: &[Excursion]) {
        let r = self.plan().tool_radius;
        let eps = self.tol.eps;
        // Where each excursion leaves the walk: segment index, parameter, the path oriented to
        // start at its nearer end, and for a leaf the way back (see below).
        let reverse = self.params.direction == Direction::Conventional;
        // The walk's segments in an index, made for the first leaf: where the walk passes the
        // point a leaf is nearest to is looked up in it.
        let mut walk_index = None;
        let mut stops: Vec<Stop> = cleanups
            .iter()
            .filter_map(|c| {
                let c = match c {
                    Excursion::Cleanup(c) => c,
                    Excursion::Spot(spot) => match self.stop_short(segments, spot) {
                        SpotStop::Short(stop) => return Some(stop),
                        SpotStop::Swept => return None,
                        SpotStop::AlongPath => &spot.path,
                    },
                    Excursion::Leaf(leaf, chain, from) => {
                        // A leaf's loops: from the walk's point nearest to the outermost, round
                        // it from there, a step in to the next one's nearest point and round it,
                        // and so on; back by the same moves the other way.
                        let walk_index = walk_index.get_or_insert_with(|| path_index(segments));
                        let (k, p) = on_walk(segments, walk_index, *from);
                        let t = crate::geom::closest_param(&segments[k], p);
                        let parts = &self.plan().parts;
                        let loop_of = |c: usize| loop_path(&parts[c].outer.segments);
                        let mut walk = walk::walk_from(&loop_of(chain[0]), p, reverse, eps);
                        let mut path = walk.clone();
                        // The steps in, each from the loop of the part before.
                        let mut steps: Vec<Vec<Segment>> = Vec::new();
                        for w in chain.windows(2) {
                            let next = loop_of(w[1]);
                            let way = self.step_in(&walk, &next, parts[w[0]].distance);
                            let at = way.last().map_or(path[path.len() - 1].end(), Segment::end);
                            walk = walk::walk_from(&next, at, reverse, eps);
                            path.extend(way.iter().copied());
                            path.extend(walk.iter().copied());
                            steps.push(way);
                        }
                        // Back out: the steps the other way, innermost first, then to `p`.
                        let mut back: Vec<Segment> = (steps.iter().rev())
                            .flat_map(|way| way.iter().rev().map(Segment::reversed))
                            .collect();
                        back.push(Segment::Line(crate::geom::Line::new(path[0].start(), p)));
                        return Some((k, t, path, Some((*leaf, back))));
                    }
                };
                let (start, end) = c.ends();
                let (k, t, d_start) = nearest_on(segments, start);
                let (k2, t2, d_end) = nearest_on(segments, end);
                Some(if d_end < d_start {
                    (
                        k2,
                        t2,
                        c.segments.iter().rev().map(Segment::reversed).collect(),
                        None,
                    )
                } else {
                    (k, t, c.segments.clone(), None)
                })
            })
            .collect();
        stops.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let mut stops = stops.into_iter().peekable();
        for (k, s) in segments.iter().enumerate() {
            let mut rest = *s;
            let mut done = 0.0;
            while let Some((_, t, path, back)) = stops.next_if(|stop| stop.0 == k) {
                // `rest` runs over [done, 1] of the segment.
                let local = if done < 1.0 {
                    ((t - done) / (1.0 - done)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (head, tail) = rest.split_at(local);
                if head.length() > eps {
                    walk::emit(&mut self.path, &head, self.z, Feed::Cut);
                }
                (rest, done) = (tail, t.max(done));
                // One step for each loop or clean-up path.
                self.progress
                    .advance(back.as_ref().map_or(1, |b| b.1.len() as u64));
                let p = self.here();
                self.path.line(Point3::at(path[0].start(), self.z), Feed::Cut);
                walk::follow(&mut self.path, &path, self.z);
                match back {
                    // A leaf's loops each end where they began, reached straight from the
                    // loop before it: back the same way.
                    Some((leaf, back)) => {
                        self.uncut.cut(leaf);
                        walk::follow(&mut self.path, &back, self.z);
                    }
                    None => {
                        let far = self.here();
                        if !(far.distance(p) <= self.host_reach() && self.stays_inside(far, p, r)) {
                            let back: Vec<Segment> = path.iter().rev().map(Segment::reversed).collect();
                            walk::follow(&mut self.path, &back, self.z);
                        }
                        self.path.line(Point3::at(p, self.z), Feed::Cut);
                    }
                }
            }
            if rest.length() > eps || done == 0.0 {
                walk::emit(&mut self.path, &rest, self.z, Feed::Cut);
            }
        }
    }

    /// Where a spot at one point is cut from the walk `segments`: straight in from the walk's
    /// point nearest to it, only as far as where the tool first sweeps all the spot answers
    /// for (see [`Spot::clears_from`]), found by halving the way to [`SPOT_STOP_RESOLUTION`]
    /// of it, and back. The tool need not reach the point itself: on the 300-hole plate the spot
    /// between four holes is 4.74 mm from the loops round them, and what is left there, a
    /// star, reaches 2.67 mm from it, within the 2.85 mm the tool must keep: the tool stops
    /// 0.25 mm short.
    fn stop_short(&self, segments: &[Segment], spot: &Spot) -> SpotStop {
        if spot.left.is_none() {
            return SpotStop::AlongPath;
        }
        let c = spot.path.ends().1;
        let (k, t, _) = nearest_on(segments, c);
        let p = segments[k].point_at(t);
        if spot.clears_from(p) {
            return SpotStop::Swept;
        }
        // The way in from `p` towards `c` enters the points the tool sweeps it all from, a
        // convex set (every disc round a point of what is left holds them), once; `c` is one
        // of them (the plan found the spot so), and the halving ends there at worst.
        let within = route::earliest(0.0, 1.0, SPOT_STOP_RESOLUTION, |t| spot.clears_from(p.lerp(c, t)));
        let x = p.lerp(c, within);
        let r = self.plan().tool_radius;
        if self.stays_inside(p, x, r) {
            SpotStop::Short((k, t, vec![Segment::Line(crate::geom::Line::new(p, x))], None))
        } else {
            SpotStop::AlongPath
        }
    }

    /// From the end of `walk` (a leaf's loop just cut, closed, the tool at its end) in to the
    /// next loop of the leaf, `next`: straight to `next`'s nearest point where that keeps
    /// `distance` (the loop's part's) from the walls, else along `walk` to its point from which
    /// `next` is reached straight (a leaf's loop can wrap round an island, its next loop lie in
    /// a corner beyond it: the straight step from the loop's start crossed the island, a gouge
    /// of 1.5 mm that the random pockets test found). The moves, ending on `next`.
    fn step_in(&self, walk: &[Segment], next: &Path, distance: f64) -> Vec<Segment> {
        let (eps, reverse) = (self.tol.eps, self.params.direction == Direction::Conventional);
        let at = walk.last().map_or(self.here(), Segment::end);
        let q = walk::walk_from(next, at, reverse, eps)[0].start();
        let straight = vec![Segment::Line(crate::geom::Line::new(at, q))];
        if self.stays_inside(at, q, distance) {
            return straight;
        }
        match route::along_last(walk, true, next, eps, |a, b| self.stays_inside(a, b, distance)) {
            Some((mut moves, b)) => {
                let a = moves.last().map_or(at, Segment::end);
                moves.push(Segment::Line(crate::geom::Line::new(a, b)));
                moves
            }
            None => straight,
        }
    }

    /// The way at depth to `item` of `part` (whose inside is cut) along the walk just cut and
    /// straight across, staying the part's distance from every wall (see [`route::along_last`]),
    /// when it takes less time than a retract and coming down near `q`, the start the straight
    /// move would have had.
    fn route_along_last(&self, distance: f64, item: &Path, q: Point) -> Option<(Vec<Segment>, Point)> {
        let (walk, closed) = (&self.last.0, self.last.1);
        let here = self.here();
        let (moves, b) = route::along_last(walk, closed, item, self.tol.eps, |a, b| {
            self.stays_inside(a, b, distance)
        })?;
        let a = moves.last().map_or(here, Segment::end);
        let length: f64 = moves.iter().map(Segment::length).sum::<f64>() + a.distance(b);
        let t = &self.params.time;
        (t.feed_seconds(length, t.feed) < self.hop_seconds(here.distance(q), self.z)).then_some((moves, b))
    }

    /// The way at depth by which the tool, down at the pass depth, should reach `q` (where
    /// `part`, not cut yet and with nothing inside it cut, starts) rather than by a retract and
    /// a new entry: a slot at most [`MAX_SLOT_LINK_RADII`] long, straight or round what is in
    /// the way, in the region of the part's root (at least its distance from every wall: stock
    /// the plan clears anyway, so nothing is cut that it would not cut), taking less time than
    /// going up, across, down and entering. The corners of the way, the last being `q`.
    fn slot_link(&self, part: &Part, q: Point) -> Option<Vec<Point>> {
        let plan = self.plan();
        let mut root = part.parent?;
        while let Some(i) = plan.parts[root].parent {
            root = i;
        }
        let seconds = self.hop_seconds(self.here().distance(q), self.z_top) + self.entry_seconds();
        let longest = MAX_SLOT_LINK_RADII * plan.tool_radius;
        self.detour_within(plan.parts[root].distance, q, seconds, longest)
    }

    /// The way at depth from where the tool is to `q` keeping the tool centre at least `d`
    /// from every wall (straight where it can, else round what is in the way), at most
    /// `longest` long, that takes less than `seconds` at the cutting feed.
    fn detour_within(&self, d: f64, q: Point, seconds: f64, longest: f64) -> Option<Vec<Point>> {
        let feed = self.params.time.feed;
        let longest = if feed > 0.0 {
            longest.min(seconds * feed / 60.0)
        } else {
            longest
        };
        let step = DETOUR_STEP_RADII * self.plan().tool_radius;
        let here = self.here();
        // Every move the search tests lies within `longest / 2` of the middle of the way (the
        // search keeps to the ellipse of ways at most `longest` long): the walls that can come
        // within `d` of them are found once, and each move is tested against those alone, not
        // through the whole pocket's index (a way round the islands of a plate tests thousands);
        // when there are many of them, through the index after all.
        let local = longest.is_finite().then(|| {
            let (m, half) = (here.midpoint(q), 0.5 * longest + d);
            let area = Aabb::from_points(
                Point::new(m.x - half, m.y - half),
                Point::new(m.x + half, m.y + half),
            );
            // One more than the most kept, to tell when there are too many without listing all.
            let walls: Vec<(Segment, Aabb)> = (self.pocket().walls_meeting(&area))
                .take(MAX_LOCAL_WALLS + 1)
                .map(|s| (*s, s.bbox()))
                .collect();
            walls
        });
        let local = local.filter(|walls| walls.len() <= MAX_LOCAL_WALLS);
        let (slack, eps) = (clearance_slack(d, self.tol), self.tol.eps);
        let free = |a: Point, b: Point| match &local {
            // As `stays_inside`.
            Some(walls) => {
                let (s, r) = (Segment::Line(crate::geom::Line::new(a, b)), d - slack);
                // As the index's search: the walls whose boxes meet the move's grown by r.
                let near = s.bbox().inflated(r);
                a.distance(b) <= slack
                    || ((r <= 0.0
                        || !(walls.iter()).any(|(w, wb)| {
                            wb.intersects(&near) && crate::geom::segments_nearer_than(w, &s, r, eps)
                        }))
                        && !self.uncut.crossed(self.plan(), a, b, eps))
            }
            None => self.stays_inside(a, b, d),
        };
        let way = detour(here, q, step, longest, free)?;
        (self.params.time.feed_seconds(self.way_length(&way), feed) < seconds).then_some(way)
    }

    /// Length of the way from where the tool is through `corners`.
    fn way_length(&self, corners: &[Point]) -> f64 {
        let mut last = self.here();
        let mut total = 0.0;
        for &c in corners {
            total += last.distance(c);
            last = c;
        }
        total
    }

    /// Straight moves at the pass depth at the cutting feed through `corners`.
    fn feed_through(&mut self, corners: &[Point]) {
        for &c in corners {
            self.path.line(Point3::at(c, self.z), Feed::Cut);
        }
    }

    /// Seconds of a new entry from the floor of the pass before down to this pass's depth: a
    /// ramp or helix at the ramp angle, at the rate [`Feed::Ramp`] gives it.
    fn entry_seconds(&self) -> f64 {
        let (p, t) = (self.params, &self.params.time);
        let drop = self.z_top - self.z;
        let length = drop / p.ramp_angle.sin();
        t.feed_seconds(length, Feed::Ramp.rate(t.feed, t.plunge_feed, length, drop))
    }

    /// Seconds to retract from the pass depth, go `across` at the safe height and come down
    /// onto `floor` as [`Linker::descend_to`] does (rapid to the feed height above it, then
    /// at the plunge feed), a retract's fixed cost included.
    fn hop_seconds(&self, across: f64, floor: f64) -> f64 {
        let (p, t) = (self.params, &self.params.time);
        let approach = (floor + p.feed_height).min(p.safe_z);
        t.hop_seconds(p.safe_z - self.z, across, p.safe_z - approach)
            + t.feed_seconds(approach - floor, t.plunge_feed)
    }

    /// True when the straight move from `a` to `b` keeps the tool centre at least `d` from
    /// every wall and island, and crosses no plain leaf waiting to be cut.
    fn stays_inside(&self, a: Point, b: Point, d: f64) -> bool {
        let slack = clearance_slack(d, self.tol);
        a.distance(b) <= slack
            || (!self.pocket().segment_nearer_than(
                &Segment::Line(crate::geom::Line::new(a, b)),
                d - slack,
                self.tol,
            ) && !self.uncut.crossed(self.plan(), a, b, self.tol.eps))
    }

    /// Straight up to the safe height, rapid: the tool rises through the column it has just
    /// cut its way down to (every pass clears its part down from the floor of the one before),
    /// as `check` accepts and FreeCAD and most CAM programs retract.
    fn retract(&mut self) {
        if self.stepped_out.take() == Some(self.path.moves.len()) {
            self.path.moves.pop();
        }
        let p = self.path.position();
        if p.z < self.params.safe_z {
            self.path.rapid(Point3::new(p.x, p.y, self.params.safe_z));
        }
        self.down = false;
    }

    /// From the safe height to `p` at the height where the stock begins (the previous floor).
    fn descend_to_floor(&mut self, p: Point) {
        self.descend_to(p, self.z_top);
    }

    /// From the safe height down to `floor` at `p`, where the stock has been cut down to
    /// `floor` (or `floor` is the stock top): rapid to the feed height above it, then at the
    /// plunge feed. Every place the tool comes down in a part on a later pass was cleared to
    /// the previous pass's floor by that pass (it clears everything the tool can reach in the
    /// part), so the rapid stops short of the floor, not of the stock top.
    fn descend_to(&mut self, p: Point, floor: f64) {
        let approach = (floor + self.params.feed_height).min(self.params.safe_z);
        self.path.rapid(Point3::at(p, self.params.safe_z));
        self.path.rapid(Point3::at(p, approach));
        self.path.line(Point3::at(p, floor), Feed::Plunge);
    }

    /// Where the tool, down at the pass depth, should come down to reach `q` inside `reach`
    /// after going over the top, when that takes less time than the straight move at the
    /// cutting feed (see [`Linker::landing`]); none when the straight move is faster.
    fn hop_rather_than(&self, q: Point, reach: Reach) -> Option<Point> {
        let t = &self.params.time;
        let straight = t.feed_seconds(self.here().distance(q), t.feed);
        // Not even the hop's fixed part can be saved: no need to look for a landing.
        if self.hop_seconds(0.0, self.z) >= straight {
            return None;
        }
        let p = self.landing(reach, q)?;
        (self.hop_via(p, q) < straight).then_some(p)
    }

    /// Seconds to go over the top from where the tool is down onto the floor at `p`, cut at
    /// this pass's depth, and across to `q` at the cutting feed.
    fn hop_via(&self, p: Point, q: Point) -> f64 {
        let t = &self.params.time;
        self.hop_seconds(self.here().distance(p), self.z) + t.feed_seconds(p.distance(q), t.feed)
    }

    /// Back down after a retract to start `segments` of `part`: straight down onto `landing`
    /// (see [`Linker::landing`]), then across; a new entry when there is none.
    fn come_down_at(&mut self, landing: Option<Point>, part: usize, segments: &[Segment]) {
        let q = segments[0].start();
        match landing {
            Some(p) => {
                // That loop was cut at this pass's depth: down onto its floor.
                self.descend_to(p, self.z);
                self.path.line(Point3::at(q, self.z), Feed::Cut);
            }
            None => self.enter(part, segments),
        }
    }

    /// The point nearest to `q` on the loops of the parts `reach` says are cut and on the walk
    /// just cut (both cut at this pass's depth: the tool was down before going up) when the
    /// straight move from it to `q` stays inside `reach`.
    fn landing(&self, reach: Reach, q: Point) -> Option<Point> {
        let plan = self.plan();
        // The nearest point, and the rank of what it lies on: of points equally near, the one
        // on the part first in `reach.cut`, then the walk just cut (the tool was down at this
        // pass's depth before the retract, so that walk is at it too).
        let mut best: Option<(Point, f64, usize)> = None;
        let consider = |best: &mut Option<(Point, f64, usize)>, segments: &[Segment], rank: usize| {
            for s in segments {
                // Every point of the segment is within its length of its start.
                if best.is_some_and(|(_, bd, _)| q.distance(s.start()) - s.length() > bd) {
                    continue;
                }
                let p = crate::geom::closest_point(s, q);
                let d = p.distance(q);
                if best.is_none_or(|(_, bd, br)| d < bd || (d == bd && rank < br)) {
                    *best = Some((p, d, rank));
                }
            }
        };
        consider(&mut best, &self.last.0, reach.cut.len());
        // The parts nearest by their boxes first; those whose box is farther than the nearest
        // point found so far are not looked into (a plate's parts cut are hundreds of loops).
        let mut parts: Vec<(f64, usize)> = (reach.cut.iter().enumerate())
            .map(|(rank, &c)| (self.boxes[c].distance_sq(q), rank))
            .collect();
        parts.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (box_sq, rank) in parts {
            if best.is_some_and(|(_, bd, _)| box_sq > bd * bd) {
                break;
            }
            for l in plan.parts[reach.cut[rank]].loops() {
                consider(&mut best, &l.segments, rank);
            }
        }
        best.map(|(p, _, _)| p)
            .filter(|&p| self.stays_inside(p, q, reach.distance))
    }

    /// A helix in the part `part` near the start of `segments`; when the part is too small,
    /// in the part around it, and so on outwards (still inside the pocket: no gouge). In each
    /// part the helix is looked for about the paths' points within [`HELIX_NEAR_RADII`] tool
    /// radii of that start, first the nearest of them, and about all the points only when
    /// none of those gives a helix of the preferred radius: a plate's part has a loop round
    /// every hole, it is entered again after each retract, and the helix is found within a
    /// millimetre of the start.
    fn find_helix(&self, part: usize, segments: &[Segment]) -> Option<Helix> {
        let r = self.plan().tool_radius;
        let q = segments[0].start();
        let preferred = 0.5 * r;
        let parts = &self.plan().parts;
        let mut at = Some(part);
        // The walk to start is looked about in the part it is of only.
        let mut walk = Some((segments, bbox_of(segments)));
        while let Some(i) = at {
            let n = &parts[i];
            let paths: Vec<&[Segment]> = (n.loops().map(|h| &h.segments[..]))
                .chain(n.paths().map(|c| &c.segments[..]))
                .collect();
            let boxes = self.path_boxes[i].get_or_init(|| paths.iter().map(|p| bbox_of(p)).collect());
            let all: Vec<(&[Segment], Aabb)> = walk
                .into_iter()
                .chain(paths.iter().copied().zip(boxes.iter().copied()))
                .collect();
            let mut best: Option<Helix> = None;
            for within in HELIX_NEAR_RADII.map(|k| Some(k * r)).into_iter().chain([None]) {
                let mut reaches_out = false;
                let mut samples = Vec::new();
                for &(p, b) in &all {
                    match within {
                        // All the points; a short path's at least once.
                        None => samples.extend(entry::samples(p, 0.5 * r)),
                        // The points within `d` of `q`.
                        Some(d) => {
                            let corners = [
                                b.min,
                                b.max,
                                Point::new(b.min.x, b.max.y),
                                Point::new(b.max.x, b.min.y),
                            ];
                            reaches_out |= corners.iter().any(|c| c.distance(q) > d);
                            if b.distance_sq(q) <= d * d {
                                samples.extend(entry::samples_within(p, 0.5 * r, Some((q, d))));
                            }
                        }
                    }
                }
                let found = entry::find_helix(
                    self.pocket(),
                    (&n.outer, self.boxes[i]),
                    &samples,
                    n.distance,
                    r,
                    preferred,
                    0.1 * r,
                    q,
                    // Else the tool would go back up after the helix and ramp.
                    |h| self.stays_inside(entry::helix_end(h, q), q, r),
                );
                if found.is_some_and(|h| h.radius >= preferred * (1.0 - 1e-5)) {
                    return found;
                }
                // Else the largest found, the nearer search's on a tie.
                if found.is_some_and(|h| best.is_none_or(|b| h.radius > b.radius)) {
                    best = found;
                }
                // A wider search finds the same when every path lies within this one.
                if !reaches_out {
                    break;
                }
            }
            if best.is_some() {
                return best;
            }
            walk = None;
            at = n.parent;
        }
        None
    }

    /// [`Linker::find_helix`], looked for once for each part, walk and state of the leaves not
    /// cut yet (see [`Linker::helices`]).
    fn find_helix_once(&mut self, part: usize, segments: &[Segment]) -> Option<Helix> {
        let walk = (
            segments[0].start(),
            segments[segments.len() - 1].end(),
            segments.len(),
        );
        let same = |f: &FoundHelix| {
            f.part == part && f.walk == walk && f.uncut.0 == self.uncut.parts && f.uncut.1 == self.uncut.cut
        };
        if let Some(found) = self.helices.iter().find(|f| same(f)) {
            return found.helix;
        }
        let helix = self.find_helix(part, segments);
        self.helices.push(FoundHelix {
            part,
            walk,
            uncut: (self.uncut.parts.clone(), self.uncut.cut.clone()),
            helix,
        });
        helix
    }

    /// Enters the stock to start `segments` (a walk of the part `part`) at the pass depth.
    fn enter(&mut self, part: usize, segments: &[Segment]) {
        let (p, r) = (self.params, self.plan().tool_radius);
        let q = segments[0].start();
        if p.entry == Entry::Helix {
            if let Some(h) = self.find_helix_once(part, segments) {
                // The material is outside the helix: on the right when it turns counter-clockwise.
                let ccw = p.direction == Direction::Climb;
                let (start, sweep) = entry::helix_start(&h, self.z_top, self.z, p.ramp_angle, ccw, q);
                self.descend_to_floor(start);
                entry::helix_moves(&mut self.path, &h, self.z_top, self.z, sweep);
                let end = self.here();
                if self.stays_inside(end, q, r) {
                    self.path.line(Point3::at(q, self.z), Feed::Cut);
                    return;
                }
                // The way from the helix to the path would touch a wall: go back up and ramp.
                self.retract();
            }
        }
        let closed = segments[0].start().distance(segments[segments.len() - 1].end()) <= self.tol.rounding();
        let walk: Vec<Segment> = if closed {
            segments.to_vec()
        } else {
            segments
                .iter()
                .copied()
                .chain(segments.iter().rev().map(Segment::reversed))
                .collect()
        };
        if p.entry != Entry::Plunge && walk::length(&walk) >= entry::shortest_ramp(r) {
            self.descend_to_floor(q);
            entry::ramp(&mut self.path, &walk, self.z_top, self.z, p.ramp_angle);
            return;
        }
        if p.entry != Entry::Plunge {
            self.warnings.push(LinkWarning::Plunged { at: q, z: self.z });
        }
        self.descend_to_floor(q);
        self.path.line(Point3::at(q, self.z), Feed::Plunge);
    }
}

/// The leaves and spots a part cuts on the way round its paths (see [`Linker::cut_part`]): for
/// each path (the outer loop 0, then the items), the leaves whose loop and the spots whose
/// path come within a tool diameter of it, and for each how many such paths are still to cut.
/// Each is cut from the last of them: what the others clear round it is cleared by then, so
/// the tool cuts only what is left of it.
struct LeavesBeside<'a> {
    part: &'a Part,
    /// The leaves, by index in `along`; beside and pending count them first, then the spots.
    leaves: Vec<&'a Part>,
    /// The part's spots (see [`crate::clear::Part::spots`]).
    spots: &'a [Spot],
    beside: Vec<Vec<usize>>,
    pending: Vec<usize>,
    /// Leaves that no path of the part passes near enough: cut after the part.
    left: Vec<usize>,
    /// Spots that the last path beside them cannot cut on its way round: cut after the part's
    /// paths.
    left_spots: Vec<&'a Path>,
    ids: Vec<usize>,
    /// The segments of all the paths in one index (a part's outer loop can be long, and it is
    /// beside every leaf), with the path each is of.
    segments: Vec<Segment>,
    owner: Vec<usize>,
    index: BoxIndex,
}

impl<'a> LeavesBeside<'a> {
    fn new(
        linker: &Linker<'a>,
        part: &'a Part,
        outer: &Path,
        items: &[(Path, Vec<Excursion>)],
        along: &[usize],
        spots: &'a [Spot],
    ) -> Self {
        let plan = linker.plan();
        let (reach, eps) = (2.0 * plan.tool_radius, linker.tol.eps);
        let paths: Vec<&Path> = std::iter::once(outer).chain(items.iter().map(|i| &i.0)).collect();
        let owner: Vec<usize> = (paths.iter().enumerate())
            .flat_map(|(k, p)| p.segments.iter().map(move |_| k))
            .collect();
        let segments: Vec<Segment> = paths.iter().flat_map(|p| p.segments.iter().copied()).collect();
        let boxes: Vec<Aabb> = segments.iter().map(Segment::bbox).collect();
        let index = BoxIndex::new(&boxes);
        let mut beside = vec![Vec::new(); paths.len()];
        let mut pending = vec![0; along.len() + spots.len()];
        let shapes = (along.iter().map(|&leaf| &plan.parts[leaf].outer.segments[..]))
            .chain(spots.iter().map(|s| &s.path.segments[..]));
        for (l, leaf_segments) in shapes.enumerate() {
            let leaf_index = path_index(leaf_segments);
            for j in index.intersecting(&bbox_of(leaf_segments).inflated(reach)) {
                let k = owner[j];
                if beside[k].last() == Some(&l) {
                    continue;
                }
                let exact = |o: usize| crate::geom::segment_distance(&segments[j], &leaf_segments[o], eps).0;
                let bound = |b: &Aabb| b.distance_to_box(&boxes[j]);
                if leaf_index.nearest_below(bound, exact, reach).is_some() {
                    beside[k].push(l);
                    pending[l] += 1;
                }
            }
        }
        let left = (along.iter().zip(&pending))
            .filter(|&(_, &p)| p == 0)
            .map(|(&leaf, _)| leaf)
            .collect();
        let left_spots = (spots.iter().zip(&pending[along.len()..]))
            .filter(|&(_, &p)| p == 0)
            .map(|(s, _)| &s.path)
            .collect();
        LeavesBeside {
            part,
            spots,
            left_spots,
            leaves: along.iter().map(|&c| &plan.parts[c]).collect(),
            beside,
            pending,
            left,
            ids: along.to_vec(),
            segments,
            owner,
            index,
        }
    }

    /// The path `id` is about to be cut as `item` (its path and what is cut on the way round
    /// it): the leaves beside no other path still to cut join what is cut on the way, when
    /// they are near enough, else wait for the part to be cut.
    fn ready(&mut self, linker: &Linker, id: usize, item: &mut (Path, Vec<Excursion>)) {
        let (r, eps) = (linker.plan().tool_radius, linker.tol.eps);
        for &l in &self.beside[id] {
            self.pending[l] -= 1;
            if self.pending[l] > 0 {
                continue;
            }
            if let Some(spot) = l.checked_sub(self.leaves.len()).map(|k| &self.spots[k]) {
                match linker.hosts(&item.0.segments, &spot.path, false) {
                    Some(_) => item.1.push(Excursion::Spot(spot.clone())),
                    None => self.left_spots.push(&spot.path),
                }
                continue;
            }
            // The nearest points of the path and the leaf within r; where they come equally
            // near more than once, the first along the path.
            let leaf = &self.leaves[l].outer.segments;
            let mut nearest: Option<(f64, usize, Point, Point)> = None;
            // By the leaf's segments, the nearest segment of the path to each, searched best
            // first below the nearest so far: the leaf and the path can both be thousands of
            // segments long, and short ones (a profile of 100 000 lines) hundreds to a radius.
            for o in leaf {
                let ob = o.bbox();
                let limit = nearest.map_or(r, |n| n.0.min(r));
                let exact = |j: usize| {
                    if self.owner[j] == id {
                        crate::geom::segment_distance(&self.segments[j], o, eps).0
                    } else {
                        f64::INFINITY
                    }
                };
                if let Some((j, _)) = self.index.nearest_below(|b| b.distance_to_box(&ob), exact, limit) {
                    let (d, p, q) = crate::geom::segment_distance(&self.segments[j], o, eps);
                    nearest = Some((d, j, p, q));
                }
            }
            // A leaf with clean-up paths is cut after the part (see `cut_small_leaves`).
            let chain = linker.chain(self.ids[l]).unwrap_or_default();
            match nearest {
                Some((_, _, p, q))
                    if !linker.waits_for_parent(self.ids[l])
                        && linker.stays_inside(p, q, self.part.distance) =>
                {
                    item.1.push(Excursion::Leaf(self.ids[l], chain, p));
                }
                _ => self.left.push(self.ids[l]),
            }
        }
    }
}

/// The segment of `walk` (its segments' boxes in `index`) nearest to `p`, a point of the loop
/// walked, and its point nearest to `p`: where the walk passes `p`.
fn on_walk(walk: &[Segment], index: &BoxIndex, p: Point) -> (usize, Point) {
    let exact = |k: usize| crate::geom::distance_from_segment(&walk[k], p);
    match index.nearest_below(|b| b.distance_sq(p).sqrt(), exact, f64::INFINITY) {
        Some((k, _)) => (k, crate::geom::closest_point(&walk[k], p)),
        None => (0, walk[0].start()),
    }
}

/// The boxes of a path's segments in an index, by segment.
fn path_index(path: &[Segment]) -> BoxIndex {
    let boxes: Vec<Aabb> = path.iter().map(Segment::bbox).collect();
    BoxIndex::new(&boxes)
}

/// The plain leaves of nested loops of a part waiting to be cut after its paths (see
/// [`Linker::cut_part`]), by the boxes of their outer loops. Leaves of one loop are left out:
/// that loop alone clears such a leaf, which is about a stepover across, and a link through it
/// cuts as little as a slot link does; a leaf of nested loops is many stepovers across (a link
/// through one on a plate of two islands was a slot of 36 mm).
#[derive(Default)]
struct UncutLeaves {
    parts: Vec<usize>,
    index: Option<BoxIndex>,
    cut: Vec<bool>,
    left: usize,
}

impl UncutLeaves {
    fn new(plan: &ClearPlan, leaves: &[usize]) -> UncutLeaves {
        let leaves: Vec<usize> = (leaves.iter().copied())
            .filter(|&l| !plan.parts[l].children.is_empty() || plan.parts[l].paths().next().is_some())
            .collect();
        let boxes: Vec<Aabb> = leaves.iter().map(|&l| plan.parts[l].outer.bbox()).collect();
        UncutLeaves {
            index: (!leaves.is_empty()).then(|| BoxIndex::new(&boxes)),
            cut: vec![false; leaves.len()],
            left: leaves.len(),
            parts: leaves,
        }
    }

    /// The leaf `part` is being cut.
    fn cut(&mut self, part: usize) {
        if let Some(k) = self.parts.iter().position(|&p| p == part) {
            if !self.cut[k] {
                self.cut[k] = true;
                self.left -= 1;
            }
        }
    }

    /// True when the straight move from `a` to `b` crosses the outer loop of a leaf not cut yet
    /// (touching it at an end, where a leaf is reached, is not crossing it): it would cut its
    /// stock at full depth.
    fn crossed(&self, plan: &ClearPlan, a: Point, b: Point, eps: f64) -> bool {
        let Some(index) = self.index.as_ref().filter(|_| self.left > 0) else {
            return false;
        };
        let link = Segment::Line(crate::geom::Line::new(a, b));
        let lb = link.bbox();
        index.intersecting(&lb).any(|k| {
            !self.cut[k]
                && plan.parts[self.parts[k]].outer.segments.iter().any(|w| {
                    let (d, _, at) = crate::geom::segment_distance(w, &link, eps);
                    d <= eps && at.distance(a) > eps && at.distance(b) > eps
                })
        })
    }
}

/// Where an excursion leaves the walk of a loop (see [`Linker::excursions`]): the segment of
/// the walk, the parameter on it, the path to follow from there, and for a leaf its part and
/// the way back.
type Stop = (usize, f64, Vec<Segment>, Option<(usize, Vec<Segment>)>);

/// How a spot is cut from a walk (see [`Linker::stop_short`]).
enum SpotStop {
    /// Straight in to where the tool first sweeps all the spot answers for, and back.
    Short(Stop),
    /// Not at all: the tool on the walk sweeps it all already.
    Swept,
    /// Along the spot's path, as any clean-up path: a pass along a long narrow leaf, or a
    /// spot whose straight way in would come nearer the walls than the tool radius or cross a
    /// leaf not cut yet.
    AlongPath,
}

/// What is cut on the way round a loop, as an excursion from it (see [`Linker::excursions`]).
enum Excursion {
    /// A clean-up path.
    Cleanup(Path),
    /// A spot, cut where the tool on its way in first sweeps all it answers for (see
    /// [`Linker::stop_short`]).
    Spot(Spot),
    /// A plain leaf (its part), its nested parts, outermost first (see [`Linker::chain`]),
    /// and the point of the loop it is cut from nearest to it.
    Leaf(usize, Vec<usize>, Point),
}

/// Which of a part's paths `items` (with their `boxes`) to cut next from `here`: the first of
/// a short tour over them (nearest neighbour and 2-opt over the middles of their boxes), where
/// they are few; else the nearest. The nearest alone leaves the far ones for a long way back
/// at the end: on the 90 % rectangle, a clean-up path in a corner 80 mm away, reached by a
/// retract and a new entry.
fn next_item(items: &[(Path, Vec<Excursion>)], boxes: &[Aabb], here: Point) -> usize {
    if items.len() <= 2 || items.len() > MAX_TOURED_ITEMS {
        return nearest_bounded(
            items,
            |k| boxes[k].distance_sq(here).sqrt(),
            |p| walk::distance_to_start(&p.0, here),
        );
    }
    let places: Vec<Point> = boxes.iter().map(|b| b.min.midpoint(b.max)).collect();
    tour(&places, here).first().copied().unwrap_or(0)
}

/// Where the tool may go at depth to reach the next path: anywhere the tool centre keeps
/// `distance` from every wall (the region of a part whose inside is cut), coming down after a
/// retract onto a loop of the parts `cut`.
#[derive(Clone, Copy)]
struct Reach<'r> {
    distance: f64,
    cut: &'r [usize],
}

/// How far a move may come inside `d` of the walls and still count as keeping `d`: the loops
/// are at `d` only up to the offset's accuracy and rounding.
fn clearance_slack(d: f64, tol: &Tolerance) -> f64 {
    1e-6 * d.max(1.0) + tol.rounding()
}

/// The point of `segments` nearest to `p`.
fn nearest_point(segments: &[Segment], p: Point) -> Point {
    let (k, t, _) = nearest_on(segments, p);
    segments[k].point_at(t)
}

fn loop_path(segments: &[Segment]) -> Path {
    Path {
        segments: segments.to_vec(),
        closed: true,
    }
}

/// Index of the item nearest by `distance`.
/// [`nearest`] with a lower bound of each item's distance: the same item (the nearest, the
/// first of those equally near), measuring only items whose bound does not put them beyond
/// the nearest found. The item with the least bound is measured first.
fn nearest_bounded<T>(items: &[T], bound: impl Fn(usize) -> f64, distance: impl Fn(&T) -> f64) -> usize {
    // A distance that is not a number is never the nearest (as in `nearest`).
    let measure = |it: &T| {
        Some(distance(it))
            .filter(|d| !d.is_nan())
            .unwrap_or(f64::INFINITY)
    };
    let bounds: Vec<f64> = (0..items.len()).map(bound).collect();
    let Some(seed) = (0..items.len()).min_by(|&a, &b| bounds[a].total_cmp(&bounds[b])) else {
        return 0;
    };
    let mut best = (seed, measure(&items[seed]));
    for (i, it) in items.iter().enumerate() {
        if i == seed || bounds[i] > best.1 {
            continue;
        }
        let d = measure(it);
        if d < best.1 || (d == best.1 && i < best.0) {
            best = (i, d);
        }
    }
    best.0
}

fn nearest<T>(items: &[T], distance: impl Fn(&T) -> f64) -> usize {
    let mut best = (0, f64::INFINITY);
    for (i, it) in items.iter().enumerate() {
        let d = distance(it);
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0
}

#[cfg(test)]
mod tests;
