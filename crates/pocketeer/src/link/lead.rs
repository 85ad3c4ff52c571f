//! Leads onto and off the finishing loops: the tool meets a wall along the loop's tangent and
//! leaves it the same way, never straight into it.

use super::Direction;
use crate::clear::ClearPlan;
use crate::geom::PreparedPocket;
use crate::geom::{Arc, Segment, Tolerance};
use std::f64::consts::FRAC_PI_2;

/// Tangent arcs onto and off the finishing loop `segments` (closed, at `d` from the walls of
/// `pocket`, with the `plan`'s allowance left on the walls by the roughing). Each is a quarter circle on
/// the loop's free side (away from the wall), of a radius that starts the lead-in where the
/// roughing has already cut (the allowance away, at least half the tool's radius, at most its
/// radius), halved while an arc would come nearer than `d` to a wall; `None` when none fits.
pub fn leads(
    segments: &[Segment],
    d: f64,
    plan: &ClearPlan,
    pocket: &PreparedPocket,
    direction: Direction,
    tol: &Tolerance,
) -> Option<(Segment, Segment)> {
    let first = segments.first()?;
    let last = segments.last()?;
    let (q_in, q_out) = (first.start(), last.end());
    let t_in = first.tangent_at(0.0).normalized()?;
    let t_out = last.tangent_at(1.0).normalized()?;
    // The loops run with the wall on their right when climbing, on their left otherwise.
    let left = direction == Direction::Climb;
    let side = |t: crate::geom::Vector| if left { t.perp() } else { -t.perp() };
    let sign = if left { 1.0 } else { -1.0 };
    let (r, allowance) = (plan.tool_radius, plan.allowance);
    let slack = super::clearance_slack(d, tol);
    let fits = |s: &Segment| !pocket.segment_nearer_than(s, d - slack, tol);
    let mut rho = allowance.max(0.5 * r).min(r);
    for _ in 0..4 {
        let c_in = q_in + side(t_in) * rho;
        let lead_in = Segment::Arc(Arc::new(c_in, rho, (-t_in).angle(), sign * FRAC_PI_2));
        let c_out = q_out + side(t_out) * rho;
        let lead_out = Segment::Arc(Arc::new(c_out, rho, (-side(t_out)).angle(), sign * FRAC_PI_2));
        if fits(&lead_in) && fits(&lead_out) {
            return Some((lead_in, lead_out));
        }
        rho *= 0.5;
    }
    None
}
