//! Writing results out: DXF for CAD programs, SVG for a look, an HTML page to explore.

pub mod dxf;
pub mod preview;
pub mod svg;
