//! Reading DXF files: our own tolerant reader for the sections pocketeer needs.
//!
//! Why not the `dxf` crate: it reads most drawings but stops on R12 files with unusual DIMSTYLE
//! groups, on a header written after ENDSEC, on an empty number field and on damaged files, and
//! a fallback would have to handle every entity we use anyway. Reading group codes is simple;
//! owning it lets us keep one behaviour, locate every error by line or byte, and skip what we do
//! not use (tables other than LAYER, objects, classes) without parsing it.

pub mod document;
mod number;
pub mod tokens;

pub use document::{parse_document, Block, Document, RawEntity};
pub use tokens::{Group, GroupList, Groups, Value};
