//! GRBL 1.1: incremental I/J only (no G91.1 needed, older versions reject it), parenthesis
//! comments, M2 to end.

use super::Post;

/// The GRBL post.
pub struct Grbl;

impl Post for Grbl {
    fn comment(&self, text: &str) -> String {
        format!("({text})")
    }
    fn setup(&self) -> &'static [&'static str] {
        &["G90 G94 G17"]
    }
    fn end(&self) -> &'static str {
        "M2"
    }
}
