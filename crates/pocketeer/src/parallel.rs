//! Independent work shared out among the machine's cores: the import fits curves and checks
//! contours one at a time, and drawings of traced art hold thousands of them.

/// Below this many items the work runs on the calling thread: starting threads costs more
/// than it saves.
const MIN_ITEMS: usize = 256;

/// Chunks of work per thread.
const CHUNKS_PER_THREAD: usize = 16;

/// Most threads used: the work is memory-light, and machines with more cores are shared.
const MAX_THREADS: usize = 8;

/// `items.iter().map(f).collect()`, in order, computed on up to [`MAX_THREADS`] threads when
/// there are at least [`MIN_ITEMS`] items.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(MAX_THREADS);
    if threads < 2 || items.len() < MIN_ITEMS {
        return items.iter().map(f).collect();
    }
    // Many more chunks than threads, each taken by the next free thread: one slow item or a
    // core busy with another program holds up only its own chunk.
    let chunk = items.len().div_ceil(threads * CHUNKS_PER_THREAD).max(1);
    let chunks: Vec<&[T]> = items.chunks(chunk).collect();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (f, chunks, next) = (&f, &chunks, &next);
    let mut done: Vec<(usize, Vec<R>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(move || {
                    let mut mine = Vec::new();
                    loop {
                        let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(part) = chunks.get(k) else { break };
                        mine.push((k, part.iter().map(f).collect::<Vec<R>>()));
                    }
                    mine
                })
            })
            .collect();
        workers
            .into_iter()
            // A worker only panics if `f` does, which the serial path would too.
            .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    done.sort_unstable_by_key(|(k, _)| *k);
    done.into_iter().flat_map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_results_come_in_the_order_of_the_items() {
        for n in [0, 1, 255, 256, 1001] {
            let items: Vec<u64> = (0..n).collect();
            let squares = super::map(&items, |x| x * x);
            assert_eq!(squares, items.iter().map(|x| x * x).collect::<Vec<_>>());
        }
    }
}
