//! The process's memory allocator tuned for this program's pattern: a job builds lists of
//! megabytes (a drawing's elements, a level's pieces, an index, the output text), frees them and
//! builds the next of much the same size.
//!
//! glibc's defaults serve each block above 128 KiB (a threshold it raises as such blocks are
//! freed) from a mapping of its own and give it back when freed, and give back the top of the
//! heap once 128 KiB of it is free; every page of the next such list is then a fresh page the
//! kernel must fault in and zero. Blocks up to 32 MiB (glibc's own ceiling for that threshold)
//! from the heap, and 64 MiB of free heap kept, make those pages reused instead: measured on
//! the offset of a 100 000-line drawing, 28.9 thousand page faults fall to 18.3 thousand and
//! the run to 0.90 of its time, at the same peak memory (BENCHMARKS.md, issue 21).
//!
//! The first time, those pages are still fresh, 4 KiB each: the 100 000-line offset faulted
//! 18 thousand times, a quarter of its time in the kernel. [`Allocator`] therefore maps each
//! block of [`LARGE`] or more itself, marked for transparent huge pages (2 MiB: one fault and
//! one clearing each) before anything touches it, and grows it with `mremap`, which moves the
//! pages instead of copying them, where the kernel has transparent huge pages on. The rest
//! goes to glibc, with the thresholds above. Measured on that offset: 18.5 thousand faults
//! fall to 4.5 thousand and the run to 0.79 of its time; on the 100 000-line pocket, 106
//! thousand to 14 thousand (BENCHMARKS.md, issue 21).

use std::alloc::{GlobalAlloc, Layout, System};

/// The system allocator, with blocks of [`LARGE`] or more mapped on their own in huge pages
/// where the kernel offers them (see the module's text).
pub struct Allocator;

/// Blocks from this size on are mapped on their own: a block is rounded up to whole huge
/// pages, so that at most a third of what a block's pages hold lies beyond it.
#[cfg(target_os = "linux")]
const LARGE: usize = 4 << 20;

/// The huge page size of x86-64 and of 4 KiB-page AArch64. Where the kernel's is another, a
/// range advised on this grid is still valid: the kernel uses a huge page only where one lies
/// whole in an advised range.
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// Whether a block of `layout` is mapped on its own: large, page alignment at most (a
/// mapping's), and the kernel gives huge pages to memory that asks for them.
#[cfg(target_os = "linux")]
fn large(layout: &Layout) -> bool {
    layout.size() >= LARGE && layout.align() <= 4096 && huge_pages()
}

/// Whether transparent huge pages are on for memory advised to use them (`always` or
/// `madvise` in the kernel's setting). Where they are off, a block mapped on its own would
/// only lose glibc's reuse of freed memory: every large list would fault in fresh pages.
/// Read once, at the first large block, so that small jobs do not pay for it.
#[cfg(target_os = "linux")]
fn huge_pages() -> bool {
    use std::sync::atomic::{AtomicU8, Ordering};
    // 0: not read yet, 1: on, 2: off.
    static STATE: AtomicU8 = AtomicU8::new(0);
    match STATE.load(Ordering::Relaxed) {
        1 => true,
        2 => false,
        _ => {
            // The first answer stored is everyone's, for good: a block must be freed the way
            // it was made, even should the setting change while two threads read it.
            let read = if huge_pages_setting() { 1 } else { 2 };
            match STATE.compare_exchange(0, read, Ordering::Relaxed, Ordering::Relaxed) {
                Ok(_) => read == 1,
                Err(stored) => stored == 1,
            }
        }
    }
}

/// Reads the kernel's transparent huge page setting, without allocating (this runs inside the
/// allocator): off when it cannot be read.
#[cfg(target_os = "linux")]
fn huge_pages_setting() -> bool {
    let mut text = [0u8; 64];
    // SAFETY: a constant NUL-terminated path; the descriptor is checked before use.
    let fd = unsafe {
        libc::open(
            c"/sys/kernel/mm/transparent_hugepage/enabled".as_ptr(),
            libc::O_RDONLY | libc::O_CLOEXEC,
        )
    };
    if fd < 0 {
        return false;
    }
    // SAFETY: reads at most `text.len()` bytes into `text`, which is that long; `fd` is open
    // and closed once, here.
    let read = unsafe {
        let n = libc::read(fd, text.as_mut_ptr().cast(), text.len());
        libc::close(fd);
        n
    };
    usize::try_from(read)
        .ok()
        .and_then(|n| text.get(..n))
        .is_some_and(huge_pages_on)
}

/// Whether the kernel's transparent huge page setting (`text`, the bracketed word chosen:
/// "always [madvise] never") gives huge pages to advised memory.
#[cfg(target_os = "linux")]
fn huge_pages_on(text: &[u8]) -> bool {
    let chosen = |word: &[u8]| text.windows(word.len()).any(|w| w == word);
    chosen(b"[always]") || chosen(b"[madvise]")
}

/// The length of the mapping that holds a block of `size` bytes.
#[cfg(target_os = "linux")]
fn mapped(size: usize) -> usize {
    size.next_multiple_of(HUGE_PAGE)
}

/// A fresh mapping of `len` bytes (zeroed), marked for huge pages; null when none is left.
#[cfg(target_os = "linux")]
fn map(len: usize) -> *mut u8 {
    // SAFETY: an anonymous private mapping at an address of the kernel's choice touches no
    // existing memory; the result is checked before use.
    let p = unsafe {
        libc::mmap(
            std::ptr::null_mut(),
            len,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        )
    };
    if p == libc::MAP_FAILED {
        return std::ptr::null_mut();
    }
    // SAFETY: `[p, p + len)` is the mapping just made. MADV_HUGEPAGE changes only how the
    // kernel backs its pages, never their contents; it fails where huge pages are disabled,
    // which leaves the pages as they were, so its result is not needed.
    unsafe { libc::madvise(p, len, libc::MADV_HUGEPAGE) };
    p.cast()
}

// SAFETY: a block is served by `System` or mapped here, and which one follows from its layout
// (`large`), which the caller passes back unchanged to `dealloc` and `realloc`, and from the
// kernel's setting, read once and fixed for the process (`huge_pages`); a mapped block is
// `mapped(size)` bytes from a page boundary, so it is aligned for any layout `large` accepts,
// zeroed, and released or moved only as a whole mapping.
unsafe impl GlobalAlloc for Allocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        #[cfg(target_os = "linux")]
        if large(&layout) {
            return map(mapped(layout.size()));
        }
        // SAFETY: the caller's contract for `GlobalAlloc::alloc`, passed on.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        #[cfg(target_os = "linux")]
        if large(&layout) {
            // A fresh anonymous mapping reads as zeros.
            return map(mapped(layout.size()));
        }
        // SAFETY: as for `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        #[cfg(target_os = "linux")]
        if large(&layout) {
            // SAFETY: `ptr` is a mapping made by `map` for this layout's size; nothing uses it
            // after `dealloc`. munmap fails only for an invalid range, which this is not.
            unsafe { libc::munmap(ptr.cast(), mapped(layout.size())) };
            return;
        }
        // SAFETY: `ptr` came from `System` with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        #[cfg(target_os = "linux")]
        {
            // SAFETY: the caller's contract: `new_size` is valid for `layout`'s alignment.
            let new = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
            match (large(&layout), large(&new)) {
                (false, false) => {}
                (true, true) => {
                    let (old_len, new_len) = (mapped(layout.size()), mapped(new_size));
                    if old_len == new_len {
                        return ptr;
                    }
                    // SAFETY: `ptr` is a whole mapping of `old_len` bytes made by `map`; the
                    // kernel moves its pages (keeping their huge-page advice) to a mapping of
                    // `new_len`, which may be elsewhere; the old address is not used again.
                    let p = unsafe { libc::mremap(ptr.cast(), old_len, new_len, libc::MREMAP_MAYMOVE) };
                    return if p == libc::MAP_FAILED {
                        std::ptr::null_mut()
                    } else {
                        p.cast()
                    };
                }
                _ => {
                    // Between the two kinds: a new block, the bytes both hold, the old freed.
                    // SAFETY: `new` is a valid non-zero layout (`new_size` > 0 by contract).
                    let p = unsafe { self.alloc(new) };
                    if !p.is_null() {
                        // SAFETY: both blocks are live, distinct, and at least this long.
                        unsafe {
                            std::ptr::copy_nonoverlapping(ptr, p, layout.size().min(new_size));
                            self.dealloc(ptr, layout);
                        }
                    }
                    return p;
                }
            }
        }
        // SAFETY: as for `dealloc`, and the caller's contract for `new_size`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Largest block served from the heap rather than a mapping of its own.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 32 << 20;

/// Free memory at the top of the heap kept rather than given back to the system.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 64 << 20;

/// Sets the allocator's thresholds; call first thing in `main`, before any thread starts.
/// Elsewhere than glibc it does nothing.
pub fn tune() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` takes two integers and changes only the allocator's own parameters,
    // under its own lock; no pointer crosses, and nothing allocated before is affected (glibc
    // frees every block by the size recorded in it, whichever way it was served). An
    // unaccepted value makes it return 0 and change nothing, which leaves the defaults.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}

#[cfg(test)]
mod tests {
    use super::Allocator;
    use std::alloc::{GlobalAlloc, Layout};

    /// Fills `len` bytes at `p` with a pattern of their index.
    fn fill(p: *mut u8, len: usize) {
        for k in (0..len).step_by(4093) {
            // SAFETY: `p` holds at least `len` bytes.
            unsafe { *p.add(k) = (k % 251) as u8 };
        }
    }

    /// Whether the first `len` bytes at `p` hold `fill`'s pattern.
    fn filled(p: *const u8, len: usize) -> bool {
        // SAFETY: `p` holds at least `len` bytes, written by `fill`.
        (0..len)
            .step_by(4093)
            .all(|k| unsafe { *p.add(k) } == (k % 251) as u8)
    }

    #[test]
    fn blocks_keep_their_bytes_through_growing_and_shrinking_across_every_kind() {
        let a = Allocator;
        // Small to small, small to large, large to larger (moved or grown in place), large to
        // large within its pages, large to small.
        let sizes = [1000, 200_000, 5 << 20, 13 << 20, (13 << 20) + 100, 3 << 20, 70];
        let layout = Layout::from_size_align(sizes[0], 8).unwrap();
        // SAFETY: a valid non-zero layout.
        let mut p = unsafe { a.alloc(layout) };
        assert!(!p.is_null());
        fill(p, sizes[0]);
        let mut old = layout;
        for &size in &sizes[1..] {
            // SAFETY: `p` is live with layout `old`; `size` > 0.
            p = unsafe { a.realloc(p, old, size) };
            assert!(!p.is_null());
            assert_eq!(p as usize % 8, 0);
            assert!(
                filled(p, old.size().min(size)),
                "bytes lost going from {} to {size}",
                old.size()
            );
            fill(p, size);
            old = Layout::from_size_align(size, 8).unwrap();
        }
        // SAFETY: `p` is live with layout `old`.
        unsafe { a.dealloc(p, old) };
    }

    #[test]
    #[cfg(target_os = "linux")]
    fn huge_pages_are_used_where_the_kernel_gives_them_to_advised_memory() {
        use super::huge_pages_on;
        assert!(huge_pages_on(b"always [madvise] never\n"));
        assert!(huge_pages_on(b"[always] madvise never\n"));
        assert!(!huge_pages_on(b"always madvise [never]\n"));
        assert!(!huge_pages_on(b""));
    }

    #[test]
    fn zeroed_blocks_read_as_zeros_and_are_aligned_small_and_large() {
        let a = Allocator;
        for (size, align) in [(100, 64), (6 << 20, 4096), (6 << 20, 8)] {
            let layout = Layout::from_size_align(size, align).unwrap();
            // SAFETY: a valid non-zero layout.
            let p = unsafe { a.alloc_zeroed(layout) };
            assert!(!p.is_null());
            assert_eq!(p as usize % align, 0);
            // SAFETY: `p` holds `size` bytes.
            assert!((0..size).step_by(997).all(|k| unsafe { *p.add(k) } == 0));
            // SAFETY: `p` is live with `layout`.
            unsafe { a.dealloc(p, layout) };
        }
    }
}
