//! GRBL 1.1: incremental I/J only (no G91.1 needed, older versions reject it), parenthesis
//! comments, M2 to end.

use super::Post;

/// The GRBL post.
pub struct Grbl;

impl Post for Grbl {
    fn tool_change(&self, n: u32) -> Vec<String> {
        // GRBL 1.1 takes a T word but refuses M6: the tool is loaded by hand before the start.
        vec![
            self.comment(&format!("tool {n}: load it by hand, GRBL has no tool changer")),
            format!("T{n}"),
        ]
    }
    fn tool_change_during(&self, n: u32) -> Vec<String> {
        // No changer: stop the program (M0) for the machinist to load the tool and press
        // cycle start.
        vec![
            self.comment(&format!("load tool {n}, then press cycle start")),
            format!("T{n}"),
            "M0".to_string(),
        ]
    }
    fn has_mist(&self) -> bool {
        // M7 only in builds with ENABLE_M7, which the stock firmware is not.
        false
    }
    fn setup(&self) -> &'static [&'static str] {
        &["G90 G94 G17"]
    }
    fn end(&self) -> &'static str {
        "M2"
    }
}
