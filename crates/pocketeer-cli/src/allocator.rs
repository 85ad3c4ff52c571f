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
