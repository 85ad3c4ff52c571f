//! Section-level structure of a DXF file: header variables, layers, blocks and entities.
//!
//! The reader is tolerant where real files are sloppy (a header variable written after its
//! section ended, several ENTITIES sections, a missing EOF, unknown tables and objects) and strict
//! where sloppiness would change the drawing (a file cut off inside its entities).

use super::tokens::{Group, GroupList, Groups};
use crate::import::error::{EntityRef, ImportError, Pos};
use crate::import::ImportWarning;
use std::borrow::Cow;
use std::collections::HashMap;

/// One entity as read: its type, its groups (a span of the file, read again when asked for),
/// the groups every entity may have, and (for POLYLINE) its vertices.
#[derive(Debug, Clone)]
pub struct RawEntity<'a> {
    /// Entity type (`LINE`, `ARC`, ...), upper case.
    pub kind: Cow<'a, str>,
    /// The groups after the `0` group.
    pub body: Groups<'a>,
    /// Position of the `0` group.
    pub pos: Pos,
    /// The first layer group (8).
    layer: Option<Group<'a>>,
    /// The first handle group (5).
    handle: Option<Group<'a>>,
    /// True for an entity in paper space (its first group 67 is 1).
    paper_space: bool,
    /// VERTEX entities of a POLYLINE.
    pub vertices: Vec<RawEntity<'a>>,
}

impl<'a> RawEntity<'a> {
    /// The groups after the `0` group, in order.
    pub fn groups(&self) -> impl Iterator<Item = Group<'a>> + '_ {
        self.body.iter()
    }

    /// The first group with `code`.
    pub fn group(&self, code: i32) -> Option<Group<'a>> {
        self.groups().find(|g| g.code == code)
    }

    /// The first value of `code` as text.
    pub fn text(&self, code: i32) -> Option<String> {
        self.group(code).map(|g| g.text())
    }

    /// Layer name (group 8), `0` when absent.
    pub fn layer(&self) -> String {
        self.layer
            .map(|g| g.text().trim().to_owned())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "0".into())
    }

    /// True for an entity in paper space (group 67 = 1).
    pub fn in_paper_space(&self) -> bool {
        self.paper_space
    }

    /// A reference to this entity for messages, with the layer it is drawn on.
    pub fn reference(&self, layer: &str) -> EntityRef {
        EntityRef {
            kind: self.kind.clone().into_owned(),
            handle: self.handle.map(|h| h.text().trim().to_owned()),
            layer: layer.to_owned(),
            pos: self.pos,
        }
    }
}

/// A block definition.
#[derive(Debug, Clone)]
pub struct Block<'a> {
    /// Name as written.
    pub name: String,
    /// Base point (x, y, z).
    pub base: [f64; 3],
    /// Entities of the block.
    pub entities: Vec<RawEntity<'a>>,
}

/// The parts of a DXF file the importer uses, borrowing the file's bytes.
#[derive(Debug, Default)]
pub struct Document<'a> {
    /// Header variables (`$INSUNITS`, ...) with their groups.
    pub header: HashMap<String, Vec<Group<'a>>>,
    /// Layer names from the LAYER table, in file order.
    pub layers: Vec<String>,
    /// Block definitions by upper-case name.
    pub blocks: HashMap<String, Block<'a>>,
    /// Entities of the ENTITIES section(s), model and paper space.
    pub entities: Vec<RawEntity<'a>>,
    /// Remarks about the file's structure.
    pub warnings: Vec<ImportWarning>,
    /// True for a binary DXF.
    pub binary: bool,
}

impl Document<'_> {
    /// The first value of header variable `name`.
    pub fn header_value(&self, name: &str) -> Option<&Group<'_>> {
        self.header.get(name).and_then(|g| g.first())
    }
}

/// A cursor over the groups of the file.
struct Cursor<'a> {
    groups: Groups<'a>,
    at: usize,
}

impl<'a> Cursor<'a> {
    fn peek(&self) -> Option<Group<'a>> {
        self.groups.get(self.at)
    }
    fn next(&mut self) -> Option<Group<'a>> {
        let g = self.groups.get(self.at)?;
        self.at += 1;
        Some(g)
    }
    /// Position of the file's last group.
    fn last_pos(&self) -> Pos {
        self.groups
            .get(self.groups.len().wrapping_sub(1))
            .map_or(Pos::Line(1), |g| g.pos)
    }
    /// Skips to the next group with code 0.
    fn skip_to_next_zero(&mut self) {
        while self.groups.code(self.at).is_some_and(|c| c != 0) {
            self.at += 1;
        }
    }
}

/// Splits the groups of a file into header, layers, blocks and entities.
pub fn parse_document<'a>(list: &'a GroupList<'a>) -> Result<Document<'a>, ImportError> {
    let mut cur = Cursor {
        groups: list.all(),
        at: 0,
    };
    let mut doc = read_sections(&mut cur)?;
    doc.binary = list.binary();
    if !list.saw_eof() {
        doc.warnings.push(ImportWarning::NoEofMarker);
    }
    Ok(doc)
}

fn read_sections<'a>(cur: &mut Cursor<'a>) -> Result<Document<'a>, ImportError> {
    let mut doc = Document::default();
    let mut saw_section = false;
    while let Some(g) = cur.next() {
        if g.is(0, "EOF") {
            break;
        }
        if g.code == 9 {
            // A header variable outside the HEADER section: some writers put one after ENDSEC.
            read_header_variable(cur, &g, &mut doc);
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
            "HEADER" => read_header(cur, &mut doc),
            "TABLES" => read_tables(cur, &mut doc),
            "BLOCKS" => read_blocks(cur, &mut doc),
            "ENTITIES" => {
                let (entities, closed) = read_entities(cur, &["ENDSEC"]);
                doc.entities.extend(entities);
                closed
            }
            _ => skip_section(cur),
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
    Ok(doc)
}

fn read_header_variable<'a>(cur: &mut Cursor<'a>, name: &Group<'a>, doc: &mut Document<'a>) {
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
fn read_header<'a>(cur: &mut Cursor<'a>, doc: &mut Document<'a>) -> bool {
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

fn skip_section(cur: &mut Cursor<'_>) -> bool {
    while let Some(g) = cur.next() {
        if g.is(0, "ENDSEC") {
            return true;
        }
    }
    false
}

fn read_tables(cur: &mut Cursor<'_>, doc: &mut Document<'_>) -> bool {
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

fn read_blocks<'a>(cur: &mut Cursor<'a>, doc: &mut Document<'a>) -> bool {
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
fn read_entities<'a>(cur: &mut Cursor<'a>, stop: &[&str]) -> (Vec<RawEntity<'a>>, bool) {
    let mut out: Vec<RawEntity<'a>> = Vec::new();
    while let Some(g) = cur.peek() {
        if g.code != 0 {
            cur.next(); // stray group between entities
            continue;
        }
        let kind = entity_kind(&g);
        if stop.contains(&kind.as_ref()) {
            return (out, true);
        }
        if kind == "EOF" || kind == "SECTION" {
            return (out, false);
        }
        let pos = g.pos;
        cur.next();
        let from = cur.at;
        let (mut layer, mut handle, mut paper) = (None, None, None);
        while let Some(code) = cur.groups.code(cur.at).filter(|&c| c != 0) {
            match code {
                8 => layer = layer.or(cur.peek()),
                5 => handle = handle.or(cur.peek()),
                67 => paper = paper.or(cur.peek()),
                _ => {}
            }
            cur.at += 1;
        }
        let entity = RawEntity {
            kind,
            body: cur.groups.slice(from..cur.at),
            pos,
            layer,
            handle,
            paper_space: paper.and_then(|g| g.int()) == Some(1),
            vertices: Vec::new(),
        };
        match entity.kind.as_ref() {
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

/// The entity type a `0` group names, upper case: borrowed from the file when it is written
/// so, as it nearly always is.
fn entity_kind<'a>(g: &Group<'a>) -> Cow<'a, str> {
    if let super::Value::Text(t) = g.value {
        let as_written = |b: &u8| b.is_ascii() && !b.is_ascii_lowercase() && !b.is_ascii_whitespace();
        if t.iter().all(as_written) {
            // ASCII, hence UTF-8.
            if let Ok(s) = std::str::from_utf8(t) {
                return Cow::Borrowed(s);
            }
        }
    }
    Cow::Owned(g.text().trim().to_uppercase())
}
