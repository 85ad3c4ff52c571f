//! Section-level structure of a DXF file: header variables, layers, blocks and entities.
//!
//! The reader is tolerant where real files are sloppy (a header variable written after its
//! section ended, several ENTITIES sections, a missing EOF, unknown tables and objects) and strict
//! where sloppiness would change the drawing (a file cut off inside its entities).

use super::tokens::{Group, Groups, Value};
use crate::import::error::{EntityRef, ImportError, Pos};
use crate::import::ImportWarning;
use std::collections::HashMap;

/// One entity as read: its type, its groups, and (for POLYLINE) its vertices.
#[derive(Debug, Clone)]
pub struct RawEntity {
    /// Entity type (`LINE`, `ARC`, ...), upper case.
    pub kind: String,
    /// The groups after the `0` group.
    pub groups: Vec<Group>,
    /// Position of the `0` group.
    pub pos: Pos,
    /// VERTEX entities of a POLYLINE.
    pub vertices: Vec<RawEntity>,
}

impl RawEntity {
    /// The first group with `code`.
    pub fn group(&self, code: i32) -> Option<&Group> {
        self.groups.iter().find(|g| g.code == code)
    }

    /// The first value of `code` as text.
    pub fn text(&self, code: i32) -> Option<String> {
        self.group(code).map(Group::text)
    }

    /// Layer name (group 8), `0` when absent.
    pub fn layer(&self) -> String {
        self.text(8)
            .map(|s| s.trim().to_owned())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "0".into())
    }

    /// True for an entity in paper space (group 67 = 1).
    pub fn in_paper_space(&self) -> bool {
        self.group(67).and_then(Group::int) == Some(1)
    }

    /// A reference to this entity for messages, with the layer it is drawn on.
    pub fn reference(&self, layer: &str) -> EntityRef {
        EntityRef {
            kind: self.kind.clone(),
            handle: self.text(5).map(|h| h.trim().to_owned()),
            layer: layer.to_owned(),
            pos: self.pos,
        }
    }
}

/// A block definition.
#[derive(Debug, Clone)]
pub struct Block {
    /// Name as written.
    pub name: String,
    /// Base point (x, y, z).
    pub base: [f64; 3],
    /// Entities of the block.
    pub entities: Vec<RawEntity>,
}

/// The parts of a DXF file the importer uses.
#[derive(Debug, Default)]
pub struct Document {
    /// Header variables (`$INSUNITS`, ...) with their groups.
    pub header: HashMap<String, Vec<Group>>,
    /// Layer names from the LAYER table, in file order.
    pub layers: Vec<String>,
    /// Block definitions by upper-case name.
    pub blocks: HashMap<String, Block>,
    /// Entities of the ENTITIES section(s), model and paper space.
    pub entities: Vec<RawEntity>,
    /// Remarks about the file's structure.
    pub warnings: Vec<ImportWarning>,
}

impl Document {
    /// The first value of header variable `name`.
    pub fn header_value(&self, name: &str) -> Option<&Group> {
        self.header.get(name).and_then(|g| g.first())
    }
}

/// A cursor over the groups, handing each one out by value (moved, not copied: a drawing's
/// groups are most of the memory an import takes).
struct Cursor {
    groups: Vec<Group>,
    at: usize,
}

impl Cursor {
    fn peek(&self) -> Option<&Group> {
        self.groups.get(self.at)
    }
    fn next(&mut self) -> Option<Group> {
        let slot = self.groups.get_mut(self.at)?;
        self.at += 1;
        let placeholder = Group {
            code: -1,
            value: Value::Bytes,
            pos: slot.pos,
        };
        Some(std::mem::replace(slot, placeholder))
    }
    fn last_pos(&self) -> Pos {
        self.groups.last().map(|g| g.pos).unwrap_or(Pos::Line(1))
    }
    /// How many groups come before the next one with code 0.
    fn until_next_zero(&self) -> usize {
        let rest = self.groups.get(self.at..).unwrap_or_default();
        rest.iter().position(|g| g.code == 0).unwrap_or(rest.len())
    }
    /// Skips to the next group with code 0.
    fn skip_to_next_zero(&mut self) {
        while let Some(g) = self.peek() {
            if g.code == 0 {
                break;
            }
            self.at += 1;
        }
    }
}

/// Splits the groups of a file into header, layers, blocks and entities.
pub fn parse_document(read: Groups) -> Result<Document, ImportError> {
    let mut doc = Document::default();
    let saw_eof = read.saw_eof;
    let mut cur = Cursor {
        groups: read.groups,
        at: 0,
    };
    let mut saw_section = false;
    while let Some(g) = cur.next() {
        if g.is(0, "EOF") {
            break;
        }
        if g.code == 9 {
            // A header variable outside the HEADER section: some writers put one after ENDSEC.
            read_header_variable(&mut cur, &g, &mut doc);
            continue;
        }
        if !g.is(0, "SECTION") {
            continue;
        }
        saw_section = true;
        let name = if cur.peek().is_some_and(|n| n.code == 2) {
            cur.next()
                .map(|n| n.text().trim().to_uppercase())
                .unwrap_or_default()
        } else {
            String::new()
        };
        let closed = match name.as_str() {
            "HEADER" => read_header(&mut cur, &mut doc),
            "TABLES" => read_tables(&mut cur, &mut doc),
            "BLOCKS" => read_blocks(&mut cur, &mut doc),
            "ENTITIES" => {
                let (entities, closed) = read_entities(&mut cur, &["ENDSEC"]);
                doc.entities.extend(entities);
                closed
            }
            _ => skip_section(&mut cur),
        };
        if !closed {
            if matches!(name.as_str(), "ENTITIES" | "BLOCKS") {
                return Err(ImportError::Truncated {
                    pos: cur.last_pos(),
                    section: name,
                });
            }
            doc.warnings
                .push(ImportWarning::SectionNotEnded { section: name });
        }
    }
    if !saw_section {
        return Err(ImportError::NotDxf(
            "no SECTION found: this is not a DXF drawing".into(),
        ));
    }
    if !saw_eof {
        doc.warnings.push(ImportWarning::NoEofMarker);
    }
    Ok(doc)
}

fn read_header_variable(cur: &mut Cursor, name: &Group, doc: &mut Document) {
    let mut values = Vec::new();
    while let Some(g) = cur.peek() {
        if g.code == 0 || g.code == 9 {
            break;
        }
        values.extend(cur.next());
    }
    doc.header.insert(name.text().trim().to_uppercase(), values);
}

/// Reads to ENDSEC; false when the groups ran out first.
fn read_header(cur: &mut Cursor, doc: &mut Document) -> bool {
    while let Some(g) = cur.next() {
        if g.is(0, "ENDSEC") {
            return true;
        }
        if g.code == 9 {
            read_header_variable(cur, &g, doc);
        }
    }
    false
}

fn skip_section(cur: &mut Cursor) -> bool {
    while let Some(g) = cur.next() {
        if g.is(0, "ENDSEC") {
            return true;
        }
    }
    false
}

fn read_tables(cur: &mut Cursor, doc: &mut Document) -> bool {
    while let Some(g) = cur.next() {
        if g.is(0, "ENDSEC") {
            return true;
        }
        if g.is(0, "LAYER") {
            while let Some(h) = cur.peek() {
                if h.code == 0 {
                    break;
                }
                if h.code == 2 {
                    let name = h.text().trim().to_owned();
                    if !doc.layers.iter().any(|l| l.eq_ignore_ascii_case(&name)) {
                        doc.layers.push(name);
                    }
                }
                cur.next();
            }
        }
    }
    false
}

fn read_blocks(cur: &mut Cursor, doc: &mut Document) -> bool {
    while let Some(g) = cur.next() {
        if g.is(0, "ENDSEC") {
            return true;
        }
        if !g.is(0, "BLOCK") {
            continue;
        }
        let mut name = String::new();
        let mut base = [0.0; 3];
        while let Some(h) = cur.peek() {
            if h.code == 0 {
                break;
            }
            match h.code {
                2 => name = h.text().trim().to_owned(),
                10 | 20 | 30 => base[(h.code / 10 - 1) as usize] = h.real().unwrap_or(0.0),
                _ => {}
            }
            cur.next();
        }
        let (entities, closed) = read_entities(cur, &["ENDBLK", "ENDSEC"]);
        if cur.peek().is_some_and(|e| e.is(0, "ENDBLK")) {
            cur.next();
            cur.skip_to_next_zero();
        }
        doc.blocks
            .insert(name.to_uppercase(), Block { name, base, entities });
        if !closed {
            return false;
        }
    }
    false
}

/// Reads entities until a `0` group whose value is one of `stop` (left unread). Returns false
/// when the groups ran out first.
fn read_entities(cur: &mut Cursor, stop: &[&str]) -> (Vec<RawEntity>, bool) {
    let mut out: Vec<RawEntity> = Vec::new();
    while let Some(g) = cur.peek() {
        if g.code != 0 {
            cur.next(); // stray group between entities
            continue;
        }
        let kind = g.text().trim().to_uppercase();
        if stop.contains(&kind.as_str()) {
            return (out, true);
        }
        if kind == "EOF" || kind == "SECTION" {
            return (out, false);
        }
        let pos = g.pos;
        cur.next();
        // Sized once: a polyline of a hundred thousand vertices would otherwise be copied
        // some twenty times as it grew.
        let count = cur.until_next_zero();
        let mut entity = RawEntity {
            kind,
            groups: Vec::with_capacity(count),
            pos,
            vertices: Vec::new(),
        };
        entity.groups.extend((0..count).map_while(|_| cur.next()));
        match entity.kind.as_str() {
            "VERTEX" => {
                if let Some(poly) = out.last_mut().filter(|e| e.kind == "POLYLINE") {
                    poly.vertices.push(entity);
                }
            }
            "SEQEND" | "ATTRIB" => {}
            _ => out.push(entity),
        }
    }
    (out, false)
}
