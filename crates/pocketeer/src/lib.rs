//! pocketeer: contour-parallel pocket milling from DXF drawings.
//!
//! The library follows the data flow of the design: [`import`] reads a drawing into segments,
//! chains them into closed contours and nests those into pockets with islands; the geometry
//! kernel in [`geom`] holds the exact lines and arcs every stage works on.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod geom;
