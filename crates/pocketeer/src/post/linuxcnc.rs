//! LinuxCNC: cancels offsets and canned cycles left by an earlier program, incremental arc
//! centres stated (G91.1), path blending held to 0.01 mm (G64 P0.01) so corners are not
//! rounded beyond the tolerances we promise, M2 to end.

use super::Post;

/// The LinuxCNC post.
pub struct LinuxCnc;

impl Post for LinuxCnc {
    fn setup(&self) -> &'static [&'static str] {
        &["G90 G94 G17 G91.1", "G40 G49 G80", "G64 P0.01"]
    }
    fn end(&self) -> &'static str {
        "M2"
    }
}
