//! Writing results out: DXF for CAD programs.

pub mod dxf;
