//! Jobs: the pockets of a drawing cleared with one tool ([`pocket_job`]), and a whole [`Job`]
//! of operations, each on some layers with a tool of the job's library ([`run_job`]).
//!
//! In: the pockets, [`ClearParams`] and [`LinkParams`]. Out: a [`PocketJob`], the plans, the
//! linked tool path and the [`JobWarning`]s (pockets too narrow for the tool).

mod operations;

pub use operations::{run_job, run_job_with, Job, Operation, OperationResult, PocketsOn, Tool};

use crate::clear::{plan_prepared, ClearError, ClearParams, ClearPlan};
use crate::geom::PreparedPocket;
use crate::geom::Tolerance;
use crate::geom::{Pocket, Point};
use crate::link::{link_with, LinkError, LinkParams, Linked};
use thiserror::Error;

/// Why a job cannot be planned.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum JobError {
    /// A clearing parameter is out of range, or a pocket would need too many levels.
    #[error(transparent)]
    Clear(#[from] ClearError),
    /// A linking parameter is out of range.
    #[error(transparent)]
    Link(#[from] LinkError),
    /// The tool fits in no pocket.
    #[error("a {diameter} mm tool fits {}: the widest place is {widest:.3} mm across",
        if *.pockets == 1 { "nowhere in the pocket".to_string() } else { format!("in none of the {} pockets", .pockets) })]
    ToolFitsNowhere {
        /// Tool diameter, mm.
        diameter: f64,
        /// Number of pockets.
        pockets: usize,
        /// The widest place (the diameter of the largest circle in any pocket), mm.
        widest: f64,
    },
    /// An operation names a tool the job's library does not hold.
    #[error("operation {}: no tool {tool} in the job's tools (numbers: {})", .operation + 1,
        .known.iter().map(ToString::to_string).collect::<Vec<_>>().join(", "))]
    UnknownTool {
        /// Which operation (0-based).
        operation: usize,
        /// The number it names.
        tool: u32,
        /// The numbers the library holds.
        known: Vec<u32>,
    },
    /// Two tools of the library share a number.
    #[error("two tools are numbered {0}")]
    DuplicateTool(u32),
    /// An operation's layers hold no pocket.
    #[error("operation {}: no pocket on the layers {}", .operation + 1, .layers.join(", "))]
    NoPockets {
        /// Which operation (0-based).
        operation: usize,
        /// Its layers.
        layers: Vec<String>,
    },
    /// An operation could not be planned.
    #[error("operation {}: {error}", .operation + 1)]
    Operation {
        /// Which operation (0-based).
        operation: usize,
        /// Why.
        error: Box<JobError>,
    },
}

/// A planned and linked job.
#[derive(Debug, Clone, PartialEq)]
pub struct PocketJob {
    /// The clearing plan of each pocket (empty where the tool fits nowhere).
    pub plans: Vec<ClearPlan>,
    /// The tool path and the linker's remarks.
    pub linked: Linked,
    /// The job's own remarks: pockets left uncut.
    pub warnings: Vec<JobWarning>,
}

/// Something about a planned job the machinist should know.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum JobWarning {
    /// The tool fits nowhere in this pocket (others are cut).
    #[error("pocket {} (area {area:.3} mm², near {near}) is too narrow for the tool: not cut", .pocket + 1)]
    TooNarrow {
        /// Which pocket (0-based).
        pocket: usize,
        /// Its area, mm².
        area: f64,
        /// A point of its boundary.
        near: Point,
    },
}

/// Plans and links `pockets`.
pub fn pocket_job(
    pockets: &[Pocket],
    clear: &ClearParams,
    link_params: &LinkParams,
    tol: &Tolerance,
) -> Result<PocketJob, JobError> {
    pocket_job_with(pockets, clear, link_params, tol, &crate::progress::Silent)
}

/// [`pocket_job`], telling `progress` of its stages: planning (a step per pocket) and linking
/// (the loops planned).
pub fn pocket_job_with(
    pockets: &[Pocket],
    clear: &ClearParams,
    link_params: &LinkParams,
    tol: &Tolerance,
    progress: &dyn crate::progress::Progress,
) -> Result<PocketJob, JobError> {
    link_params.check()?;
    let prepared: Vec<PreparedPocket> = pockets.iter().map(PreparedPocket::new).collect();
    progress.stage("planning pockets", Some(pockets.len() as u64));
    let plans = prepared
        .iter()
        .map(|p| {
            let plan = plan_prepared(p, clear, tol);
            progress.advance(1);
            plan
        })
        .collect::<Result<Vec<_>, _>>()?;
    if !pockets.is_empty() && plans.iter().all(|p| p.parts.is_empty()) {
        return Err(JobError::ToolFitsNowhere {
            diameter: 2.0 * clear.tool_radius,
            pockets: pockets.len(),
            widest: 2.0 * widest(pockets, tol)?,
        });
    }
    let jobs: Vec<(&PreparedPocket, &ClearPlan)> = prepared
        .iter()
        .zip(&plans)
        .filter(|(_, p)| !p.parts.is_empty())
        .collect();
    let linked = link_with(&jobs, link_params, tol, progress)?;
    let warnings = (plans.iter().zip(pockets).enumerate())
        .filter(|(_, (plan, _))| plan.parts.is_empty())
        .map(|(i, (_, p))| JobWarning::TooNarrow {
            pocket: i,
            area: p.area(),
            near: p.boundary.segments[0].start(),
        })
        .collect();
    Ok(PocketJob {
        plans,
        linked,
        warnings,
    })
}

/// The radius of the largest circle in any of the pockets.
fn widest(pockets: &[Pocket], tol: &Tolerance) -> Result<f64, ClearError> {
    let mut best: f64 = 0.0;
    for p in pockets {
        best = best.max(crate::offset::largest_inscribed_radius(p, tol).map_err(ClearError::from)?);
    }
    Ok(best)
}
