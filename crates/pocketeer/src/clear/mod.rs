//! Clearing a pocket: the levels of contour-parallel loops, each taken from the original
//! region, arranged in a tree, plus clean-up paths wherever the levels alone would leave
//! material: nothing the tool could reach is left uncut.
//!
//! In: a [`PreparedPocket`] and [`ClearParams`] (tool radius, stepover, allowance). Out: a
//! [`ClearPlan`], the tree of [`Part`]s (one connected piece of one level: an outer loop and
//! the loops around the islands inside it) with their clean-up [`Path`]s; the linker turns it
//! into moves. `levels.rs` picks the distances, `tree.rs` nests the loops, `residue.rs` finds
//! what the levels leave between them, `spots.rs` clears small leaves from one spot each.
//!
//! Why the levels and the clean-up paths leave nothing: a point p of the region whose distance
//! to the walls is t, with d_k ≤ t < d_(k+1), lies t − d_k from the loop at level k along the
//! straight line to its nearest wall point. When no gap d_(k+1) − d_k exceeds the tool radius,
//! every point the tool centre may reach is within the radius of a loop, and the loop at d = r
//! sweeps the rest of what the tool can reach. Wider gaps (stepovers above the radius) are
//! filled where needed by pieces of the loop half way between, see the `residue` module.

mod levels;
mod residue;
pub mod rest;
mod spots;
mod tree;

use crate::geom::Pocket;
use crate::geom::PreparedPocket;
use crate::geom::{Contour, Point, Segment, Tolerance};
use thiserror::Error;

/// How a pocket is cleared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClearParams {
    /// Radius of the tool, mm.
    pub tool_radius: f64,
    /// Distance between neighbouring levels, mm (at most the tool diameter).
    pub stepover: f64,
    /// Material left on walls and islands by the roughing levels and removed by a finishing
    /// loop at the tool radius, mm (0: no finishing loop).
    pub allowance: f64,
}

/// Why a pocket cannot be planned.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ClearError {
    /// The tool diameter is not positive.
    #[error("the tool diameter must be positive (got {0} mm)")]
    ToolDiameter(f64),
    /// The stepover is not positive.
    #[error("the stepover must be positive (got {0} mm)")]
    Stepover(f64),
    /// The stepover is not less than the tool diameter.
    #[error("the stepover ({stepover} mm) must be less than the tool diameter ({diameter} mm)")]
    StepoverTooLarge {
        /// The stepover, mm.
        stepover: f64,
        /// The tool diameter, mm.
        diameter: f64,
    },
    /// The allowance is negative or not a number.
    #[error("the allowance must be zero or positive (got {0} mm)")]
    Allowance(f64),
    /// The allowance is not less than the tool diameter.
    #[error("the allowance ({allowance} mm) must be less than the tool diameter ({diameter} mm)")]
    AllowanceTooLarge {
        /// The allowance, mm.
        allowance: f64,
        /// The tool diameter, mm.
        diameter: f64,
    },
    /// Too many levels would be needed.
    #[error("{levels} levels would be needed (stepover {stepover} mm over a pocket {depth:.3} mm deep); the limit is {limit}")]
    TooManyLevels {
        /// Levels needed.
        levels: f64,
        /// The stepover.
        stepover: f64,
        /// Upper bound of the distance from the walls to the pocket's middle.
        depth: f64,
        /// The largest number allowed.
        limit: usize,
    },
    /// An offset of the pocket cannot be computed.
    #[error(transparent)]
    Offset(#[from] crate::offset::OffsetError),
}

/// The most levels one pocket may have: a million loops is hours of machining already.
pub const MAX_LEVELS: usize = 100_000;

/// An open or closed path of exact segments that the tool centre follows.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    /// The segments, joined end to start.
    pub segments: Vec<Segment>,
    /// True when the last segment ends where the first starts.
    pub closed: bool,
}

impl Path {
    /// Where the path starts and where it ends (the same point for a closed one).
    ///
    /// ```
    /// use pocketeer::clear::Path;
    /// use pocketeer::geom::{Line, Point, Segment};
    /// let (a, b) = (Point::new(0.0, 0.0), Point::new(3.0, 0.0));
    /// let path = Path { segments: vec![Segment::Line(Line::new(a, b))], closed: false };
    /// assert_eq!(path.ends(), (a, b));
    /// ```
    pub fn ends(&self) -> (Point, Point) {
        (
            self.segments[0].start(),
            self.segments[self.segments.len() - 1].end(),
        )
    }
}

/// One connected part of one level: an outer loop and the loops around the islands inside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Index of the level: 0 is the one nearest the walls.
    pub level: usize,
    /// Distance of the loops from the walls and islands, mm.
    pub distance: f64,
    /// The outer loop, counter-clockwise (the part on its left).
    pub outer: Contour,
    /// Loops around islands inside the outer loop, clockwise.
    pub holes: Vec<Contour>,
    /// Parts of the next level inside this one.
    pub children: Vec<usize>,
    /// The part of the previous level this one lies in.
    pub parent: Option<usize>,
    /// Paths between this part and its children that must also be cut to leave nothing
    /// (empty whenever the stepover is at most the tool radius).
    pub cleanups: Vec<Path>,
    /// The spots from which the tool clears what small leaves of this part would have, in
    /// their place (see [`plan_pocket`]); each lies within a leaf's loop, a stepover or so
    /// inside this part's loops, and is cut from the last of them passing near it.
    pub spots: Vec<Spot>,
}

/// Where the tool clears what a small leaf of a part would have (see [`Part::spots`]): a short
/// path ending at one point, or a pass along the middle of a long narrow leaf; for one point,
/// also what the tool must sweep there, so that it may stop short of the point, on its way in
/// from a loop, where it already sweeps all of that (see [`Spot::clears_from`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Spot {
    /// The path: from a little inside the leaf's loop to the point, or the pass.
    pub path: Path,
    /// For one point: the outlines of what is left for the spot, and how near the tool centre
    /// must be to every point of them (a little less than the tool radius).
    pub left: Option<(Vec<Contour>, f64)>,
}

impl Spot {
    /// True when the tool centre at `p` is near enough to every point of what is left for a
    /// spot at one point to sweep all of it: exact, by the farthest point of each outline
    /// segment; false for a pass.
    ///
    /// ```
    /// use pocketeer::clear::{Path, Spot};
    /// use pocketeer::geom::{Contour, Line, Point, Segment};
    /// let p = Point::new;
    /// // A square of side 2 left round (10, 10), to be within 2 mm of the tool centre.
    /// let left = Contour::polygon(&[p(9.0, 9.0), p(11.0, 9.0), p(11.0, 11.0), p(9.0, 11.0)]);
    /// let path = Path { segments: vec![Segment::Line(Line::new(p(10.0, 9.7), p(10.0, 10.0)))], closed: false };
    /// let spot = Spot { path, left: Some((vec![left], 2.0)) };
    /// assert!(spot.clears_from(p(10.0, 10.0)));
    /// // Below the middle, the far corners are √(1 + 2.2²) > 2 away.
    /// assert!(spot.clears_from(p(10.0, 9.5)) && !spot.clears_from(p(10.0, 8.8)));
    /// ```
    pub fn clears_from(&self, p: Point) -> bool {
        self.left.as_ref().is_some_and(|(left, reach)| {
            (left.iter().flat_map(|c| &c.segments))
                .all(|s| crate::geom::farthest_from_segment(s, p) <= *reach)
        })
    }
}

impl Part {
    /// The outer loop, then the loops around islands.
    pub fn loops(&self) -> impl Iterator<Item = &Contour> {
        std::iter::once(&self.outer).chain(&self.holes)
    }

    /// The clean-up paths, then the spots: what the part cuts besides its loops.
    pub fn paths(&self) -> impl Iterator<Item = &Path> {
        self.cleanups.iter().chain(self.spots.iter().map(|s| &s.path))
    }
}

/// The tree of loops that clears one pocket.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ClearPlan {
    /// All parts of all levels.
    pub parts: Vec<Part>,
    /// The parts of level 0.
    pub roots: Vec<usize>,
    /// The level distances used, mm.
    pub distances: Vec<f64>,
    /// The material the roughing levels leave on the walls for level 0, the finishing loops
    /// at the tool radius, mm (0: no finishing pass).
    pub allowance: f64,
    /// The radius of the tool the plan is for, mm: the linker enters and moves at depth with
    /// the tool centre at least this far from the walls.
    pub tool_radius: f64,
}

impl ClearPlan {
    /// Number of loops to cut, clean-up paths and spots included.
    pub fn loop_count(&self) -> usize {
        self.parts
            .iter()
            .map(|n| 1 + n.holes.len() + n.cleanups.len() + n.spots.len())
            .sum()
    }
}

/// Plans the clearing of `pocket`: levels at the tool radius (a finishing loop when there is an
/// allowance), then at r + allowance + k·stepover until nothing is left, each from the
/// original region, arranged in a tree, with clean-up paths where the stepover exceeds the
/// tool radius, and small leaves among siblings cut from one spot (or not at all where their
/// parent's loops clear them) where it does not. An empty plan means the tool fits nowhere in
/// the pocket.
///
/// ```
/// use pocketeer::clear::{plan_pocket, ClearParams};
/// use pocketeer::geom::{Contour, Point, Tolerance};
/// use pocketeer::geom::Pocket;
/// let p = Point::new;
/// let square = Contour::polygon(&[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 40.0), p(0.0, 40.0)]);
/// let pocket = Pocket { boundary: square, islands: vec![] };
/// let params = ClearParams { tool_radius: 3.0, stepover: 2.4, allowance: 0.0 };
/// let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
/// // Levels at 3, 5.4, ..., 19.8 mm: the square's half width is 20.
/// assert_eq!(plan.distances.len(), 8);
/// assert_eq!(plan.roots.len(), 1);
/// ```
pub fn plan_pocket(pocket: &Pocket, params: &ClearParams, tol: &Tolerance) -> Result<ClearPlan, ClearError> {
    plan_prepared(&PreparedPocket::new(pocket), params, tol)
}

/// [`plan_pocket`] for a pocket already prepared as a [`PreparedPocket`].
pub fn plan_prepared(
    pocket: &PreparedPocket,
    params: &ClearParams,
    tol: &Tolerance,
) -> Result<ClearPlan, ClearError> {
    let bbox = pocket.bbox();
    check_params(params)?;
    // No point of the pocket is farther from its boundary than half its smaller extent.
    let depth = 0.5 * bbox.width().min(bbox.height());
    let distances = levels::level_distances(params, depth)?;
    let (loops, sources): (Vec<_>, Vec<_>) = crate::offset::offsets_until_empty(pocket, &distances, tol)?
        .into_iter()
        .unzip();
    let distances = distances[..loops.len()].to_vec();
    let mut plan = tree::build(loops, &distances);
    plan.allowance = params.allowance;
    plan.tool_radius = params.tool_radius;
    residue::add_cleanups(&mut plan, pocket, &sources, params, tol)?;
    spots::clear_leaves_from_spots(&mut plan, params, tol);
    Ok(plan)
}

fn check_params(p: &ClearParams) -> Result<(), ClearError> {
    let diameter = 2.0 * p.tool_radius;
    if !(p.tool_radius.is_finite() && p.tool_radius > 0.0) {
        return Err(ClearError::ToolDiameter(diameter));
    }
    if !(p.stepover.is_finite() && p.stepover > 0.0) {
        return Err(ClearError::Stepover(p.stepover));
    }
    if p.stepover >= diameter {
        return Err(ClearError::StepoverTooLarge {
            stepover: p.stepover,
            diameter,
        });
    }
    if !(p.allowance.is_finite() && p.allowance >= 0.0) {
        return Err(ClearError::Allowance(p.allowance));
    }
    if p.allowance >= diameter {
        return Err(ClearError::AllowanceTooLarge {
            allowance: p.allowance,
            diameter,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Point};

    fn rect(w: f64, h: f64) -> Contour {
        let p = Point::new;
        Contour::polygon(&[p(0.0, 0.0), p(w, 0.0), p(w, h), p(0.0, h)])
    }

    #[test]
    fn an_island_whose_loop_touches_the_wall_loop_is_kept() {
        // A 1 mm island 2 mm from the end of an 11 mm wide channel: for a 2 mm tool its loop
        // (radius 2) touches the end of the wall's loop at a point. A bar splits the level
        // into two parts, so the loop's owner is looked for (it was dropped when its first
        // point was the point of contact, leaving a ring of material round the island).
        let p = Point::new;
        let bar = Contour::polygon(&[p(18.0, 0.5), p(18.0, 10.5), p(20.0, 10.5), p(20.0, 0.5)]);
        for start in [0.0, 1.0, std::f64::consts::PI] {
            let island = Contour::new(vec![Segment::Arc(Arc::new(
                p(37.0, 5.5),
                1.0,
                start,
                -std::f64::consts::TAU,
            ))]);
            let pocket = Pocket {
                boundary: rect(40.0, 11.0),
                islands: vec![island, bar.clone()],
            };
            let params = ClearParams {
                tool_radius: 1.0,
                stepover: 0.8,
                allowance: 0.0,
            };
            let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
            let roots: Vec<&Part> = plan.roots.iter().map(|&i| &plan.parts[i]).collect();
            assert_eq!(roots.len(), 2, "the bar splits the first level");
            let holes: usize = roots.iter().map(|r| r.holes.len()).sum();
            assert_eq!(holes, 1, "the island's loop, starting at {start}");
        }
    }

    #[test]
    fn parameters_out_of_range_are_refused() {
        let pocket = Pocket {
            boundary: rect(10.0, 10.0),
            islands: vec![],
        };
        let tol = Tolerance::default();
        for (r, s, a) in [
            (0.0, 1.0, 0.0),
            (1.0, 0.0, 0.0),
            (1.0, 2.0, 0.0),
            (1.0, 1.0, -0.1),
            (1.0, f64::NAN, 0.0),
        ] {
            let params = ClearParams {
                tool_radius: r,
                stepover: s,
                allowance: a,
            };
            assert!(plan_pocket(&pocket, &params, &tol).is_err(), "{r} {s} {a}");
        }
    }

    #[test]
    fn a_tool_too_big_gives_an_empty_plan() {
        let pocket = Pocket {
            boundary: rect(10.0, 10.0),
            islands: vec![],
        };
        let params = ClearParams {
            tool_radius: 5.5,
            stepover: 1.0,
            allowance: 0.0,
        };
        let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
        assert!(plan.parts.is_empty());
    }

    #[test]
    fn a_bar_island_splits_the_inner_levels_into_two_branches() {
        // 60 x 30 pocket, a 40 x 4 bar across the middle leaving 13 mm each side.
        let p = Point::new;
        let bar = Contour::polygon(&[p(10.0, 13.0), p(10.0, 17.0), p(50.0, 17.0), p(50.0, 13.0)]);
        let pocket = Pocket {
            boundary: rect(60.0, 30.0),
            islands: vec![bar],
        };
        let params = ClearParams {
            tool_radius: 2.0,
            stepover: 1.5,
            allowance: 0.0,
        };
        let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
        assert_eq!(plan.roots.len(), 1);
        let root = &plan.parts[plan.roots[0]];
        assert_eq!(root.holes.len(), 1);
        // Some level has two parts with the same parent.
        assert!(plan.parts.iter().any(|n| n.children.len() == 2));
        for (i, n) in plan.parts.iter().enumerate() {
            for &c in &n.children {
                assert_eq!(plan.parts[c].parent, Some(i));
                assert_eq!(plan.parts[c].level, n.level + 1);
            }
        }
    }

    #[test]
    fn a_part_in_the_space_between_islands_is_the_child_of_the_part_around_it_there() {
        // 3 x 3 islands of radius 5 at a 20 mm pitch, a 6 mm tool, 2.4 mm stepover: the loops
        // at 5.4 mm round the islands merge into one, a hole of the part along the wall, and
        // leave four parts between four islands each, inside that merged hole. Their parts
        // one level in lie inside the wall part's outer loop too, but in its hole: their
        // parent is the part between the islands (it was the wall part, the first outer loop
        // found round them).
        let islands = (0..9)
            .map(|k| {
                let c = Point::new(20.0 + 20.0 * (k % 3) as f64, 20.0 + 20.0 * (k / 3) as f64);
                Contour::new(vec![Segment::Arc(Arc::new(c, 5.0, 0.0, -std::f64::consts::TAU))])
            })
            .collect();
        let pocket = Pocket {
            boundary: rect(80.0, 80.0),
            islands,
        };
        let params = ClearParams {
            tool_radius: 3.0,
            stepover: 2.4,
            allowance: 0.0,
        };
        let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
        let mut between = 0;
        for part in &plan.parts {
            let Some(parent) = part.parent.map(|i| &plan.parts[i]) else {
                continue;
            };
            let p = part.outer.segments[0].start();
            assert!(parent.outer.contains(p), "inside its parent's outer loop");
            assert!(
                parent.holes.iter().all(|h| h.winding_number(p) == 0),
                "a part at {p:?} (level {}) lies in a hole of its parent",
                part.level
            );
            let b = part.outer.bbox();
            between += usize::from(
                b.min.x > 20.0 && b.max.x < 60.0 && b.min.y > 20.0 && b.max.y < 60.0 && part.level == 2,
            );
        }
        assert_eq!(between, 4, "a level-2 part in each space between four islands");
    }

    #[test]
    fn allowance_adds_a_finishing_level_at_the_tool_radius() {
        let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 20.0))]);
        let pocket = Pocket {
            boundary: disc,
            islands: vec![],
        };
        let params = ClearParams {
            tool_radius: 3.0,
            stepover: 2.0,
            allowance: 0.5,
        };
        let plan = plan_pocket(&pocket, &params, &Tolerance::default()).unwrap();
        assert_eq!(&plan.distances[..3], &[3.0, 3.5, 5.5]);
    }
}
