//! The level distances of a clearing.

use super::{ClearError, ClearParams, MAX_LEVELS};

/// Distances r, (r + allowance), r + allowance + k·stepover, ... up to the first one beyond
/// `depth` (an upper bound of the distance from the walls to any point of the pocket).
pub fn level_distances(p: &ClearParams, depth: f64) -> Result<Vec<f64>, ClearError> {
    let first = p.tool_radius + p.allowance;
    let steps = ((depth - first) / p.stepover).max(0.0).floor() + 2.0;
    if steps.is_nan() || steps > MAX_LEVELS as f64 {
        return Err(ClearError::TooManyLevels {
            levels: steps,
            stepover: p.stepover,
            depth,
            limit: MAX_LEVELS,
        });
    }
    let mut out = Vec::with_capacity(steps as usize + 1);
    if p.allowance > 0.0 {
        out.push(p.tool_radius);
    }
    out.extend((0..steps as usize).map(|k| first + k as f64 * p.stepover));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_start_at_the_radius_and_step_by_the_stepover() {
        let p = ClearParams {
            tool_radius: 3.0,
            stepover: 2.0,
            allowance: 0.0,
        };
        assert_eq!(level_distances(&p, 10.0).unwrap(), vec![3.0, 5.0, 7.0, 9.0, 11.0]);
        let p = ClearParams { allowance: 0.5, ..p };
        assert_eq!(level_distances(&p, 6.0).unwrap(), vec![3.0, 3.5, 5.5, 7.5]);
    }

    #[test]
    fn too_many_levels_are_refused() {
        let p = ClearParams {
            tool_radius: 3.0,
            stepover: 1e-6,
            allowance: 0.0,
        };
        assert!(matches!(
            level_distances(&p, 1000.0),
            Err(ClearError::TooManyLevels { .. })
        ));
    }
}
