//! Independent work shared out among the machine's cores: the import fits curves and checks
//! contours one at a time, and drawings of traced art hold thousands of them.

/// Below this many items the work runs on the calling thread: starting threads costs more
/// than it saves.
const MIN_ITEMS: usize = 256;

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
    let chunk = items.len().div_ceil(threads);
    let f = &f;
    std::thread::scope(|scope| {
        let workers: Vec<_> = items
            .chunks(chunk)
            .map(|part| scope.spawn(move || part.iter().map(f).collect::<Vec<R>>()))
            .collect();
        workers
            .into_iter()
            // A worker only panics if `f` does, which the serial path would too.
            .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
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
