//! Replaying programs: reading G-code back and measuring what the tool would do to the part
//! (`pocketeer check`).
//!
//! In: G-code text ([`read_program`] makes a [`Program`] of moves), the pockets it is meant to
//! clear and [`CheckParams`] (tool radius, depth, tolerances). Out: a [`CheckReport`]: the
//! deepest gouge into a wall or island, the thickest material left where the tool could
//! reach, rapids into stock, plunges, and the wall-following length by milling side.
//! `gcode.rs` reads, `polygon.rs` sweeps the tool, `history.rs` remembers what each move
//! found cut, `side.rs` measures climb against conventional, `engagement.rs` how much of the
//! tool meets the stock.

pub mod check;
pub mod engagement;
pub mod gcode;
mod history;
mod polygon;
mod side;

pub use check::{check_program, CheckParams, CheckReport, PocketCheck};
pub use engagement::Engagement;
pub use gcode::{read_program, GcodeError, Program};
pub use side::{Sides, WALL_SLACK};
