//! Independent work shared out among the machine's cores: the import fits curves and checks
//! contours one at a time, and drawings of traced art hold thousands of them.

use std::sync::OnceLock;

/// Below this many items the work runs on the calling thread: starting threads costs more
/// than it saves.
const MIN_ITEMS: usize = 256;

/// Below this much work in all (see [`map_sized`]: segments, elements) the work runs on the
/// calling thread: a thread costs some 50 µs to start, a segment's share of the work about a
/// tenth of a microsecond to a microsecond.
const MIN_WORK: usize = 4096;

/// Chunks of work per thread.
const CHUNKS_PER_THREAD: usize = 16;

/// Most threads used: the work is memory-light, and machines with more cores are shared.
const MAX_THREADS: usize = 8;

/// The threads work may be shared among: the machine's available cores, at most
/// [`MAX_THREADS`]. Asked of the system once: `std::thread::available_parallelism` reads the
/// control group's files on every call (five files opened on Linux).
pub(crate) fn cores() -> usize {
    static CORES: OnceLock<usize> = OnceLock::new();
    *CORES.get_or_init(|| {
        std::thread::available_parallelism()
            .map_or(1, usize::from)
            .min(MAX_THREADS)
    })
}

/// `items.iter().map(f).collect()`, in order, computed on up to [`cores`] threads when there
/// are at least [`MIN_ITEMS`] items.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    if items.len() < MIN_ITEMS {
        return items.iter().map(f).collect();
    }
    shared(items, f)
}

/// [`map`] for items whose work grows with `size` (a contour's segments, a polyline's
/// elements): on the calling thread alone unless there are [`MIN_ITEMS`] items and
/// [`MIN_WORK`] in all (three hundred circles are not worth a thread).
pub(crate) fn map_sized<T: Sync, R: Send>(
    items: &[T],
    size: impl Fn(&T) -> usize,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    if items.len() < MIN_ITEMS || items.iter().map(size).sum::<usize>() < MIN_WORK {
        return items.iter().map(f).collect();
    }
    shared(items, f)
}

/// [`map`] for a few items, each worth a thread (a level of offsets): shared out whenever
/// there are two or more.
pub(crate) fn map_each<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    if items.len() < 2 {
        return items.iter().map(f).collect();
    }
    shared(items, f)
}

/// `(a(), b())`, the two at once on two threads when the machine has two cores and `work` (as
/// in [`map_sized`]: segments, elements) is worth a thread: two independent halves of one
/// stage, such as the two indexes of a prepared pocket.
pub(crate) fn join<A: Send, B: Send>(
    work: usize,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if work < MIN_WORK || cores() < 2 {
        return (a(), b());
    }
    std::thread::scope(|scope| {
        let helper = scope.spawn(b);
        let a = a();
        // The helper only panics if `b` does, which the serial path would too.
        let b = helper.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
        (a, b)
    })
}

/// `items.iter().map(f).collect()` shared out among [`cores`] threads, the calling one among
/// them.
fn shared<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = cores();
    if threads < 2 {
        return items.iter().map(f).collect();
    }
    // Many more chunks than threads, each taken by the next free thread: one slow item or a
    // core busy with another program holds up only its own chunk.
    let chunk = items.len().div_ceil(threads * CHUNKS_PER_THREAD).max(1);
    let chunks: Vec<&[T]> = items.chunks(chunk).collect();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (f, chunks, next) = (&f, &chunks, &next);
    let work = move || {
        let mut mine = Vec::new();
        loop {
            let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(part) = chunks.get(k) else { break };
            mine.push((k, part.iter().map(f).collect::<Vec<R>>()));
        }
        mine
    };
    let mut done: Vec<(usize, Vec<R>)> = std::thread::scope(|scope| {
        let helpers: Vec<_> = (1..threads).map(|_| scope.spawn(work)).collect();
        let mut done = work();
        for h in helpers {
            // A helper only panics if `f` does, which the serial path would too.
            done.extend(h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)));
        }
        done
    });
    done.sort_unstable_by_key(|(k, _)| *k);
    done.into_iter().flat_map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_results_come_in_the_order_of_the_items() {
        for n in [0, 1, 255, 256, 1001, 20_000] {
            let items: Vec<u64> = (0..n).collect();
            let squares = super::map(&items, |x| x * x);
            assert_eq!(squares, items.iter().map(|x| x * x).collect::<Vec<_>>());
            let sized = super::map_sized(&items, |_| 16, |x| x * x);
            assert_eq!(sized, squares);
            assert_eq!(super::map_each(&items, |x| x * x), squares);
        }
    }

    #[test]
    fn join_gives_both_results_and_shares_large_work() {
        let here = std::thread::current().id();
        let id = || std::thread::current().id();
        assert_eq!(super::join(10, || 1, || "two"), (1, "two"));
        assert_eq!(super::join(10, id, id), (here, here), "small work stays here");
        let (a, b) = super::join(1 << 20, id, id);
        assert_eq!(a, here, "the calling thread takes the first");
        assert_eq!(b != here, super::cores() > 1, "a helper takes the second");
    }

    #[test]
    fn small_work_stays_on_the_calling_thread_and_large_work_is_shared() {
        let here = std::thread::current().id();
        let items: Vec<u64> = (0..1000).collect();
        // 1000 items of size 1: under the work worth a thread.
        let threads = super::map_sized(&items, |_| 1, |_| std::thread::current().id());
        assert!(threads.iter().all(|&t| t == here));
        if super::cores() > 1 {
            let threads = super::map_sized(
                &items,
                |_| 100,
                |_| {
                    // Long enough that the helper gets a chunk before the caller is done.
                    std::thread::sleep(std::time::Duration::from_micros(200));
                    std::thread::current().id()
                },
            );
            assert!(threads.contains(&here), "the calling thread works too");
            assert!(threads.iter().any(|&t| t != here), "a helper works");
        }
    }
}
