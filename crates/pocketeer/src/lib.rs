//! pocketeer: contour-parallel pocket milling from DXF drawings.
//!
//! Each stage is a plain function from one value to the next; none reaches back into an
//! earlier one, and only [`import`] (bytes in) and [`post`]/[`export`] (text out) touch the
//! world outside:
//!
//! ```text
//! DXF bytes
//!   └─ import::analyze       read, join end points, nest      → Analysis { nesting.pockets: Vec<geom::Pocket> }
//!      └─ clear::plan_prepared levels r + allowance + k·stepover → ClearPlan (a tree of loops, clean-up paths)
//!         │   (offset: the paper's raw offset → split → prune → stitch, exact lines and arcs)
//!         └─ link::link        order, entries, links, passes    → Linked { toolpath: Toolpath }
//!            ├─ post::write_gcode    GRBL, LinuxCNC, Mach3      → G-code text
//!            ├─ export               DXF of loops, SVG previews → text
//!            └─ simulate::check_program  gouge, leftover, side   → CheckReport
//! ```
//!
//! [`job::pocket_job`] runs the middle two for every pocket of a drawing. The kernel in
//! [`geom`] holds what every stage works on: points, lines, arcs, contours, pockets, their
//! intersections and distances, spatial indexes, and the [`geom::Tolerance`]s.
//!
//! The whole way, from the bytes of a drawing to the text of a program:
//!
//! ```
//! use pocketeer::clear::ClearParams;
//! use pocketeer::link::{Direction, Entry, LinkParams};
//! use pocketeer::post::{write_gcode, Dialect, ProgramSettings};
//!
//! // A 60 x 40 mm pocket round a round island of radius 8, drawn in millimetres.
//! let dxf = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n\
//!            0\nSECTION\n2\nENTITIES\n\
//!            0\nLWPOLYLINE\n8\nplate\n90\n4\n70\n1\n\
//!            10\n0\n20\n0\n10\n60\n20\n0\n10\n60\n20\n40\n10\n0\n20\n40\n\
//!            0\nCIRCLE\n8\nplate\n10\n30\n20\n20\n40\n8\n\
//!            0\nENDSEC\n0\nEOF\n";
//! let analysis = pocketeer::analyze(dxf.as_bytes(), &pocketeer::ImportOptions::default()).unwrap();
//! let pockets = &analysis.nesting.pockets;
//! assert_eq!((pockets.len(), pockets[0].islands.len()), (1, 1));
//!
//! // A 6 mm tool, 40 % stepover, 3 mm deep in two passes, climb milling.
//! let clear = ClearParams { tool_radius: 3.0, stepover: 2.4, allowance: 0.0 };
//! let link = LinkParams {
//!     depth: 3.0,
//!     step_down: 1.5,
//!     safe_z: 5.0,
//!     feed_height: 1.0,
//!     direction: Direction::Climb,
//!     entry: Entry::Helix,
//!     ramp_angle: 3f64.to_radians(),
//!     time: pocketeer::machining_time::TimeModel::default(),
//! };
//! let job = pocketeer::job::pocket_job(pockets, &clear, &link, &analysis.tolerance).unwrap();
//! let gcode = write_gcode(&job.linked.toolpath, &ProgramSettings::default(), Dialect::Grbl);
//! assert!(gcode.starts_with("G21\n"));
//! assert!(gcode.contains("\nM3 S12000\nG4 P2\n"));
//! assert!(gcode.contains("Z-3.0000"));
//! assert!(gcode.ends_with("M5\nM2\n"));
//! ```

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod clear;
pub mod export;
mod fixed;
pub mod geom;
pub mod import;
pub mod job;
pub mod link;
pub mod machining_time;
pub mod offset;
mod parallel;
pub mod post;
pub mod progress;
pub mod simulate;
#[cfg(test)]
mod test_random;
pub mod toolpath;
mod union_find;

pub use import::{analyze, read_drawing, Analysis, Drawing, ImportError, ImportOptions};
