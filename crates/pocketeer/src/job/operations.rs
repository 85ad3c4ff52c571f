//! A job of several operations: each clears the pockets on some layers with one tool of the
//! job's library, to its own depth; the operations run in order, and the program changes
//! tools between them.

use super::{JobError, PocketJob};
use crate::clear::ClearParams;
use crate::geom::{Pocket, Tolerance};
use crate::link::LinkParams;
use crate::post::ToolSection;

/// A tool of the job's library.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tool {
    /// Its number in the machine's tool table (`T n`).
    pub number: u32,
    /// Diameter, mm.
    pub diameter: f64,
    /// Cutting feed, mm/min.
    pub feed: f64,
    /// Plunge feed, mm/min.
    pub plunge_feed: f64,
    /// Spindle speed, rpm.
    pub spindle: f64,
}

/// One operation: the pockets on `layers` cleared with tool `tool`.
#[derive(Debug, Clone, PartialEq)]
pub struct Operation {
    /// The layers whose pockets it clears.
    pub layers: Vec<String>,
    /// The number of its tool.
    pub tool: u32,
    /// Stepover, mm.
    pub stepover: f64,
    /// Material left on walls and islands by the roughing loops, mm.
    pub allowance: f64,
    /// Depth, passes, heights, direction and entries. Its time model's feeds are replaced by
    /// the tool's.
    pub link: LinkParams,
    /// Cut only what the earlier operations on the same layers left for this tool.
    pub rest: bool,
}

/// A job: a tool library and the operations, in the order they run.
///
/// ```
/// use pocketeer::geom::{Contour, Point, Pocket, Tolerance};
/// use pocketeer::job::{run_job, Job, Operation, Tool};
/// use pocketeer::link::LinkParams;
/// let square = Contour::polygon(&[
///     Point::new(0.0, 0.0), Point::new(40.0, 0.0), Point::new(40.0, 30.0), Point::new(0.0, 30.0),
/// ]);
/// let pockets = vec![Pocket { boundary: square, islands: vec![] }];
/// let tool = Tool { number: 1, diameter: 6.0, feed: 1200.0, plunge_feed: 300.0, spindle: 12000.0 };
/// let op = Operation {
///     layers: vec!["0".into()], tool: 1, stepover: 2.4, allowance: 0.0,
///     link: LinkParams { depth: 3.0, step_down: 3.0, ..LinkParams::default() }, rest: false,
/// };
/// let job = Job { tools: vec![tool], operations: vec![op] };
/// let tol = Tolerance::default();
/// let done = run_job(&job, &|_layers: &[String]| Some((pockets.as_slice(), &tol))).unwrap();
/// assert_eq!(done.len(), 1);
/// assert_eq!(done[0].tool.number, 1);
/// assert!(done[0].pocketed.is_some());
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Job {
    /// The tools.
    pub tools: Vec<Tool>,
    /// The operations.
    pub operations: Vec<Operation>,
}

/// What one operation made.
#[derive(Debug, Clone, PartialEq)]
pub struct OperationResult {
    /// Which operation (0-based).
    pub operation: usize,
    /// Its tool.
    pub tool: Tool,
    /// Its plans and tool path; `None` for a rest operation that found nothing to cut.
    pub pocketed: Option<PocketJob>,
    /// What the machinist should know (a rest that could not be computed exactly).
    pub notes: Vec<String>,
}

/// True when the two lists name the same layers (in any case and order).
fn same_layers(a: &[String], b: &[String]) -> bool {
    let norm = |l: &[String]| {
        let mut v: Vec<String> = l.iter().map(|s| s.to_lowercase()).collect();
        v.sort();
        v.dedup();
        v
    };
    norm(a) == norm(b)
}

impl OperationResult {
    /// An operation that cuts nothing, and why.
    fn nothing(operation: usize, tool: Tool, notes: Vec<String>) -> OperationResult {
        OperationResult {
            operation,
            tool,
            pocketed: None,
            notes,
        }
    }

    /// The program section of this operation (none when it cuts nothing); `change` when its
    /// tool must be loaded (it is not the one the section before used).
    pub fn section(&self, change: bool, remark: String) -> Option<ToolSection<'_>> {
        Some(ToolSection {
            toolpath: &self.pocketed.as_ref()?.linked.toolpath,
            tool: change.then_some(self.tool.number),
            feed: self.tool.feed,
            plunge_feed: self.tool.plunge_feed,
            spindle: self.tool.spindle,
            remark,
        })
    }
}

/// The pockets on some layers, with the tolerance they were read with (`None`: no pocket
/// there).
pub type PocketsOn<'a> = dyn Fn(&[String]) -> Option<(&'a [Pocket], &'a Tolerance)> + 'a;

/// Runs the operations of `job` in order on the pockets `pockets_on` gives for their layers.
pub fn run_job<'a>(job: &Job, pockets_on: &PocketsOn<'a>) -> Result<Vec<OperationResult>, JobError> {
    run_job_with(job, pockets_on, &crate::progress::Silent)
}

/// [`run_job`], telling `progress` of each operation's stages.
pub fn run_job_with<'a>(
    job: &Job,
    pockets_on: &PocketsOn<'a>,
    progress: &dyn crate::progress::Progress,
) -> Result<Vec<OperationResult>, JobError> {
    let mut numbers: Vec<u32> = job.tools.iter().map(|t| t.number).collect();
    numbers.sort_unstable();
    if let Some(w) = numbers.windows(2).find(|w| w[0] == w[1]) {
        return Err(JobError::DuplicateTool(w[0]));
    }
    let mut out = Vec::new();
    // The first operation whose tool fit nowhere, for a job that cuts nothing.
    let mut nowhere: Option<JobError> = None;
    for (k, op) in job.operations.iter().enumerate() {
        let mut notes = Vec::new();
        let tool = *job
            .tools
            .iter()
            .find(|t| t.number == op.tool)
            .ok_or_else(|| JobError::UnknownTool {
                operation: k,
                tool: op.tool,
                known: numbers.clone(),
            })?;
        let (pockets, tol) = pockets_on(&op.layers)
            .filter(|(p, _)| !p.is_empty())
            .ok_or_else(|| JobError::NoPockets {
                operation: k,
                layers: op.layers.clone(),
            })?;
        let fail = |e: JobError| JobError::Operation {
            operation: k,
            error: Box::new(e),
        };
        // A rest operation clears what the earlier ones on the same layers, as deep or
        // deeper, left for its tool.
        let rest: Vec<Pocket>;
        let pockets = if op.rest {
            let earlier: Vec<f64> = job.operations[..k]
                .iter()
                .filter(|o| same_layers(&o.layers, &op.layers) && o.link.depth >= op.link.depth - 1e-9)
                .filter_map(|o| job.tools.iter().find(|t| t.number == o.tool))
                .map(|t| 0.5 * t.diameter)
                .collect();
            let mut left = Vec::new();
            for (i, p) in pockets.iter().enumerate() {
                let (rest, exact) =
                    crate::clear::rest::rest_pockets_exact(p, 0.5 * tool.diameter, &earlier, tol)
                        .map_err(|e| fail(JobError::Clear(e.into())))?;
                if !exact {
                    notes.push(format!(
                        "pocket {}: its rest could not be computed exactly (loops that nearly touch); the {} mm tool clears the whole pocket",
                        i + 1,
                        tool.diameter
                    ));
                }
                left.extend(rest);
            }
            rest = left;
            if rest.is_empty() {
                out.push(OperationResult::nothing(k, tool, notes));
                continue;
            }
            &rest[..]
        } else {
            pockets
        };
        let clear = ClearParams {
            tool_radius: 0.5 * tool.diameter,
            stepover: op.stepover,
            allowance: op.allowance,
        };
        let mut link = op.link;
        link.time.feed = tool.feed;
        link.time.plunge_feed = tool.plunge_feed;
        progress.stage(&format!("operation {}", k + 1), None);
        let pocketed = match super::pocket_job_with(pockets, &clear, &link, tol, progress) {
            Ok(p) => p,
            // Rest pieces too narrow for the tool (slivers the larger tools' rounding left).
            Err(JobError::ToolFitsNowhere { .. }) if op.rest => {
                out.push(OperationResult::nothing(k, tool, notes));
                continue;
            }
            // Another operation may cut these pockets with a smaller tool: said, not refused,
            // unless no operation cuts anything (below).
            Err(e @ JobError::ToolFitsNowhere { .. }) if job.operations.len() > 1 => {
                notes.push(format!("{e}: nothing cut"));
                out.push(OperationResult::nothing(k, tool, notes));
                nowhere.get_or_insert(fail(e));
                continue;
            }
            Err(e) => return Err(fail(e)),
        };
        out.push(OperationResult {
            operation: k,
            tool,
            pocketed: Some(pocketed),
            notes,
        });
    }
    // A job that cuts nothing at all because its tools fit nowhere is refused, as a pocket is.
    if out.iter().all(|r| r.pocketed.is_none()) {
        if let Some(e) = nowhere {
            return Err(e);
        }
    }
    Ok(out)
}
