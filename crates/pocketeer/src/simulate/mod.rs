//! Replaying programs: reading G-code back and measuring what the tool would do to the part
//! (`pocketeer check`).

pub mod check;
pub mod gcode;
pub mod history;
pub mod polygon;
pub mod side;

pub use check::{check_program, CheckParams, CheckReport, PocketCheck};
pub use gcode::{read_program, GcodeError, Program};
