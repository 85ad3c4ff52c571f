//! Many offsets of one region at once, on every core: each level is an offset of the original
//! region, the deeper ones offsetting only the sources of one already done.

use super::{OffsetError, Sources, MAX_LEVEL_SEGMENTS};
use crate::geom::{Contour, PreparedPocket, Tolerance};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// One level's loops and the sources they came from.
type Level = (Vec<Contour>, Arc<Sources>);

/// The loops at each of `distances` in turn, up to (not including) the first empty level, with
/// the sources of each level's loops. Each level is offset from the sources of the deepest
/// level already done below it (see [`PreparedPocket::offset_with_sources`]). The first error met ends the
/// work on every core.
pub fn offsets_until_empty(
    region: &PreparedPocket,
    distances: &[f64],
    tol: &Tolerance,
) -> Result<Vec<Level>, OffsetError> {
    // Threads cost tens of microseconds to start: small jobs run on this one.
    let elements: usize = region.contours().iter().map(|c| c.segments.len()).sum();
    let workers = if elements * distances.len() < 20_000 {
        1
    } else {
        crate::parallel::cores().min(distances.len())
    };
    let next = AtomicUsize::new(0);
    // Index of the first empty level found so far: nothing at or beyond it is needed.
    let limit = AtomicUsize::new(distances.len());
    let done: Mutex<BTreeMap<usize, Level>> = Mutex::new(BTreeMap::new());
    let failed: Mutex<Option<OffsetError>> = Mutex::new(None);
    // Segments of all levels so far: the tool path grows as levels × elements.
    let segments = AtomicUsize::new(0);
    let fail = |e: OffsetError| {
        limit.store(0, Ordering::Relaxed);
        if let Ok(mut f) = failed.lock() {
            f.get_or_insert(e);
        }
    };
    let work = || loop {
        let k = next.fetch_add(1, Ordering::Relaxed);
        if k >= limit.load(Ordering::Relaxed) {
            break;
        }
        let smaller = done
            .lock()
            .ok()
            .and_then(|d| d.range(..k).next_back().map(|(_, (_, s))| Arc::clone(s)));
        let (loops, sources) = match region.offset_with_sources(distances[k], tol, smaller.as_deref()) {
            Ok(level) => level,
            Err(e) => {
                fail(e);
                break;
            }
        };
        let here: usize = loops.iter().map(|l| l.segments.len()).sum();
        let total = segments.fetch_add(here, Ordering::Relaxed) + here;
        if total > MAX_LEVEL_SEGMENTS {
            fail(OffsetError::TooLarge {
                distance: distances[k],
                segments: total,
            });
            break;
        }
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
        // The calling thread is one of the workers.
        std::thread::scope(|s| {
            for _ in 1..workers {
                s.spawn(work);
            }
            work();
        });
    }
    if let Some(e) = failed.into_inner().ok().flatten() {
        return Err(e);
    }
    let limit = limit.into_inner();
    let done = done.into_inner().unwrap_or_default();
    Ok(done
        .into_iter()
        .filter(|(k, _)| *k < limit)
        .map(|(_, v)| v)
        .collect())
}
