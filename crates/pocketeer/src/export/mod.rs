//! Writing results out: DXF for CAD programs, SVG for a look.

pub mod dxf;
pub mod svg;
