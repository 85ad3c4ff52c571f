//! Replaying programs: reading G-code back and measuring what the tool would do to the part
//! (`pocketeer check`).
//!
//! In: G-code text ([`read_program`] makes a [`Program`] of moves), the pockets it is meant to
//! clear and [`CheckParams`] (tool radius, depth, tolerances). Out: a [`CheckReport`]: the
//! deepest gouge into a wall or island, the thickest material left where the tool could
//! reach, rapids into stock, plunges, and the wall-following length by milling side.
//! `gcode.rs` reads, `polygon.rs` sweeps the tool, `history.rs` remembers what each move
//! found cut, `side.rs` measures climb against conventional, `engagement.rs` how much of the
//! tool meets the stock (`tool_circle.rs` which directions round it were swept),
//! `classify.rs` what each move does (on the height map of `zmap.rs`).

pub mod check;
pub mod classify;
pub mod engagement;
pub mod gcode;
mod history;
pub(crate) mod polygon;
mod side;
pub(crate) mod tool_circle;
pub mod zmap;

pub use check::{
    check_program, check_program_tools, check_program_tools_with, CheckParams, CheckReport, PocketCheck,
};
pub use engagement::Engagement;
pub use gcode::{read_program, GcodeError, Program};
pub use side::{Sides, WALL_SLACK};
