//! Benchmark inputs shared by the bench binaries.

pub mod cases;
