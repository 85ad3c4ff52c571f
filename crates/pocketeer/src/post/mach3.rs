//! Mach3: its I/J mode is a setting that may be absolute, so the program states incremental
//! (G91.1); cancels offsets and canned cycles; M30 to end and rewind.

use super::Post;

/// The Mach3 post.
pub struct Mach3;

impl Post for Mach3 {
    fn dwell_remark(&self) -> Option<&'static str> {
        // Mach3's General Config decides whether G4 P is seconds or milliseconds.
        Some("seconds: with G4 in milliseconds in Mach3's config, multiply by 1000")
    }
    fn setup(&self) -> &'static [&'static str] {
        &["G90 G94 G17 G91.1", "G40 G49 G80"]
    }
    fn end(&self) -> &'static str {
        "M30"
    }
}
