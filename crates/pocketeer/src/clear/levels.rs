//! The level distances and their loops, computed on every core: each level is an offset of the
//! original region, independent of the others.

use super::{ClearError, ClearParams, MAX_LEVELS};
use crate::geom::{Contour, Tolerance};
use crate::offset::{Region, Sources};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

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

/// One level's loops and the sources they came from.
type Level = (Vec<Contour>, Arc<Sources>);

/// The loops at each of `distances` in turn, up to (not including) the first empty level, with
/// the sources of each level's loops. Each level is offset from the sources of the deepest
/// level already done below it (see [`Region::offset_after`]).
pub fn offsets_until_empty(region: &Region, distances: &[f64], tol: &Tolerance) -> Vec<Level> {
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(distances.len());
    let next = AtomicUsize::new(0);
    // Index of the first empty level found so far: nothing at or beyond it is needed.
    let limit = AtomicUsize::new(distances.len());
    let done: Mutex<BTreeMap<usize, Level>> = Mutex::new(BTreeMap::new());
    let work = || loop {
        let k = next.fetch_add(1, Ordering::Relaxed);
        if k >= limit.load(Ordering::Relaxed) {
            break;
        }
        let smaller = done
            .lock()
            .ok()
            .and_then(|d| d.range(..k).next_back().map(|(_, (_, s))| Arc::clone(s)));
        let (loops, sources) = region.offset_after(distances[k], tol, smaller.as_deref());
        if loops.is_empty() {
            limit.fetch_min(k, Ordering::Relaxed);
            break;
        }
        if let Ok(mut d) = done.lock() {
            d.insert(k, (loops, Arc::new(sources)));
        }
    };
    if workers <= 1 {
        work();
    } else {
        std::thread::scope(|s| {
            for _ in 0..workers {
                s.spawn(work);
            }
        });
    }
    let limit = limit.into_inner();
    let done = done.into_inner().unwrap_or_default();
    done.into_iter()
        .filter(|(k, _)| *k < limit)
        .map(|(_, v)| v)
        .collect()
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
