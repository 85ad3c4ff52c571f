//! Building DXF text for tests: entities as group codes, blocks, and a header with units.

#![allow(dead_code)]

pub mod analysis;
pub mod corpus;
pub mod program;
pub mod replay;
pub mod shapes;

use std::fmt::Write;

/// One entity: its type and its groups after the `0` group.
pub struct Entity {
    pub kind: &'static str,
    pub groups: Vec<(i32, String)>,
}

impl Entity {
    pub fn new(kind: &'static str, layer: &str) -> Entity {
        Entity {
            kind,
            groups: vec![(8, layer.to_owned())],
        }
    }
    pub fn g(mut self, code: i32, v: impl ToString) -> Entity {
        self.groups.push((code, v.to_string()));
        self
    }
}

pub fn line(layer: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> Entity {
    Entity::new("LINE", layer).g(10, x0).g(20, y0).g(11, x1).g(21, y1)
}

pub fn circle(layer: &str, cx: f64, cy: f64, r: f64) -> Entity {
    Entity::new("CIRCLE", layer).g(10, cx).g(20, cy).g(40, r)
}

pub fn arc(layer: &str, cx: f64, cy: f64, r: f64, a0: f64, a1: f64) -> Entity {
    Entity::new("ARC", layer)
        .g(10, cx)
        .g(20, cy)
        .g(40, r)
        .g(50, a0)
        .g(51, a1)
}

/// LWPOLYLINE through (x, y, bulge) vertices.
pub fn lwpoly(layer: &str, pts: &[(f64, f64, f64)], closed: bool) -> Entity {
    let mut e = Entity::new("LWPOLYLINE", layer)
        .g(90, pts.len())
        .g(70, if closed { 1 } else { 0 });
    for &(x, y, b) in pts {
        e = e.g(10, x).g(20, y);
        if b != 0.0 {
            e = e.g(42, b);
        }
    }
    e
}

/// The edges of an axis-aligned rectangle as four LINEs.
pub fn rect_lines(layer: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Entity> {
    vec![
        line(layer, x0, y0, x1, y0),
        line(layer, x1, y0, x1, y1),
        line(layer, x1, y1, x0, y1),
        line(layer, x0, y1, x0, y0),
    ]
}

pub fn rect_poly(layer: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> Entity {
    lwpoly(
        layer,
        &[(x0, y0, 0.0), (x1, y0, 0.0), (x1, y1, 0.0), (x0, y1, 0.0)],
        true,
    )
}

pub fn insert(layer: &str, block: &str, x: f64, y: f64, sx: f64, sy: f64, rot: f64) -> Entity {
    Entity::new("INSERT", layer)
        .g(2, block)
        .g(10, x)
        .g(20, y)
        .g(41, sx)
        .g(42, sy)
        .g(50, rot)
}

/// A whole drawing.
#[derive(Default)]
pub struct Drawing {
    pub insunits: Option<i32>,
    pub blocks: Vec<(String, (f64, f64), Vec<Entity>)>,
    pub entities: Vec<Entity>,
}

impl Drawing {
    pub fn new(entities: Vec<Entity>) -> Drawing {
        Drawing {
            entities,
            ..Default::default()
        }
    }
    pub fn units(mut self, code: i32) -> Drawing {
        self.insunits = Some(code);
        self
    }
    pub fn block(mut self, name: &str, base: (f64, f64), entities: Vec<Entity>) -> Drawing {
        self.blocks.push((name.to_owned(), base, entities));
        self
    }
    pub fn text(&self) -> String {
        let mut s = String::new();
        let mut pair = |c: i32, v: &str| {
            let _ = writeln!(s, "{c:>3}\n{v}");
        };
        pair(0, "SECTION");
        pair(2, "HEADER");
        pair(9, "$ACADVER");
        pair(1, "AC1015");
        if let Some(u) = self.insunits {
            pair(9, "$INSUNITS");
            pair(70, &u.to_string());
        }
        pair(0, "ENDSEC");
        pair(0, "SECTION");
        pair(2, "BLOCKS");
        for (name, base, ents) in &self.blocks {
            pair(0, "BLOCK");
            pair(8, "0");
            pair(2, name);
            pair(70, "0");
            pair(10, &base.0.to_string());
            pair(20, &base.1.to_string());
            for e in ents {
                pair(0, e.kind);
                for (c, v) in &e.groups {
                    pair(*c, v);
                }
            }
            pair(0, "ENDBLK");
        }
        pair(0, "ENDSEC");
        pair(0, "SECTION");
        pair(2, "ENTITIES");
        for e in &self.entities {
            pair(0, e.kind);
            for (c, v) in &e.groups {
                pair(*c, v);
            }
        }
        pair(0, "ENDSEC");
        pair(0, "EOF");
        s
    }
}

/// A small deterministic random number generator (xorshift64*), so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    pub fn shuffle<T>(&mut self, v: &mut [T]) {
        for i in (1..v.len()).rev() {
            let j = self.below(i + 1);
            v.swap(i, j);
        }
    }
}

/// Path of a fixture file.
pub fn fixture(rel: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(rel)
}
