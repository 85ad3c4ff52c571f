//! Model space with every block insertion expanded: each drawn curve in world coordinates, with
//! the layer it is drawn on and the entity it comes from, placed as elements.

use super::curve::{ocs_to_world, Affine};
use super::dxf::{Document, RawEntity};
use super::entities::{curves_of, Drawn, Fields};
use super::error::{EntityRef, ImportError};
use super::placement::Elements;
use crate::geom::Vector;
use crate::import::ImportWarning;

/// Deepest block nesting followed.
const MAX_NESTING: usize = 64;
/// Most curves block insertions may produce (guards against exponential nesting).
pub const MAX_CURVES: usize = 2_000_000;

/// Walks model space, expanding INSERTs, and places every curve.
pub struct Expander<'a, 'b> {
    doc: &'a Document<'b>,
    /// The elements of the curves found on the layers kept.
    pub elements: Elements,
    /// The entity of each placement that drew curves (inside blocks, the innermost one), for
    /// messages; its layer is the one drawn on (block entities on layer 0 take the layer of
    /// their INSERT). One for all the curves of a polyline: a hundred thousand vertices are not
    /// a hundred thousand copies of its name and layer.
    pub sources: Vec<EntityRef>,
    /// Every layer name: the LAYER table's, then those drawn on but not declared, in the order
    /// they are first drawn on.
    pub layers: Vec<String>,
    /// Remarks (unknown blocks).
    pub warnings: Vec<ImportWarning>,
    /// The layers to keep (all when `None`).
    keep: Option<&'a [String]>,
    /// Curves placed, on every layer.
    curves: usize,
    stack: Vec<String>,
    groups: usize,
    /// Entities each block expands to (memo of [`Expander::expanded_size`]).
    sizes: std::collections::HashMap<String, u64>,
}

impl<'a, 'b> Expander<'a, 'b> {
    /// An expander over `doc` that keeps the curves on the layers `keep` (all when `None`).
    pub fn new(doc: &'a Document<'b>, keep: Option<&'a [String]>) -> Self {
        Expander {
            doc,
            elements: Elements::new(),
            sources: Vec::new(),
            layers: doc.layers.clone(),
            warnings: Vec::new(),
            keep,
            curves: 0,
            stack: Vec::new(),
            groups: 0,
            sizes: std::collections::HashMap::new(),
        }
    }

    /// The index of layer `name` in [`Expander::layers`], added when new; `None` when its
    /// curves are not kept.
    fn layer_index(&mut self, name: &str) -> Option<usize> {
        let index = match self.layers.iter().position(|l| l.eq_ignore_ascii_case(name)) {
            Some(i) => i,
            None => {
                self.layers.push(name.to_owned());
                self.layers.len() - 1
            }
        };
        let kept = self
            .keep
            .is_none_or(|w| w.iter().any(|x| x.eq_ignore_ascii_case(name)));
        kept.then_some(index)
    }

    /// Adds the curves of `entities`, drawn in a space that `m` maps to world coordinates.
    /// Inside a block, entities on layer 0 take `parent_layer`.
    pub fn walk(
        &mut self,
        entities: &[RawEntity],
        m: &Affine,
        parent_layer: Option<&str>,
    ) -> Result<(), ImportError> {
        for e in entities {
            let own = e.layer();
            let layer = match parent_layer {
                Some(p) if own == "0" => p.to_owned(),
                _ => own,
            };
            if e.kind == "INSERT" {
                self.insert(e, m, &layer)?;
                continue;
            }
            // Curves are placed as they are read (a polyline of a million vertices is not
            // first a list of its own), on the layer its entity is drawn on if that is kept.
            let mark = self.elements.mark();
            let source = self.sources.len();
            let (mut layer_index, mut known) = (None, false);
            let mut count = 0;
            let mut bad = None;
            let drawn = curves_of(e, &mut |c| {
                let curve = c.transformed(m);
                count += 1;
                if bad.is_some() {
                    return;
                }
                if let Err(p) = curve.check_coordinates(super::MAX_COORDINATE) {
                    bad = Some(p);
                    return;
                }
                if !known {
                    layer_index = self.layer_index(&layer);
                    known = true;
                }
                if let Some(layer) = layer_index {
                    self.elements.push(curve, layer, source);
                }
            });
            match drawn {
                Ok(Drawn::Curves { closed }) => {
                    if !known {
                        self.layer_index(&layer);
                    }
                    self.sources.push(e.reference(&layer));
                    if let Some(p) = bad {
                        return Err(ImportError::BadEntity {
                            entity: e.reference(&layer),
                            what: format!(
                                "coordinate ({}, {}) is not a number or lies beyond ±{:e} mm",
                                super::error::fmt_number(p.x),
                                super::error::fmt_number(p.y),
                                super::MAX_COORDINATE
                            ),
                        });
                    }
                    if closed {
                        self.groups += 1;
                        self.elements.set_group_since(mark, Some(self.groups));
                    }
                    self.curves += count;
                    if self.curves > MAX_CURVES {
                        return Err(ImportError::TooLarge {
                            limit: MAX_CURVES,
                            pos: e.pos,
                        });
                    }
                }
                Ok(Drawn::Ignored) => {}
                Err(what) => {
                    return Err(ImportError::BadEntity {
                        entity: e.reference(&layer),
                        what,
                    })
                }
            }
        }
        Ok(())
    }

    fn insert(&mut self, e: &RawEntity, m: &Affine, layer: &str) -> Result<(), ImportError> {
        let f = Fields::of(e);
        let real = |code: i32, default: f64| f.real_or(code, default);
        let int = |code: i32, default: i64| f.int_or(code, default);
        let name = f.group(2).map(|g| g.text()).unwrap_or_default().trim().to_owned();
        let Some(block) = self.doc.blocks.get(&name.to_uppercase()) else {
            self.warnings.push(ImportWarning::UndefinedBlock {
                insert: e.reference(layer),
                name,
            });
            return Ok(());
        };
        if self.stack.iter().any(|s| s.eq_ignore_ascii_case(&name)) || self.stack.len() >= MAX_NESTING {
            let mut chain = self.stack.clone();
            chain.push(name.clone());
            return Err(ImportError::RecursiveBlock {
                name,
                chain: chain.join(" → "),
                pos: e.pos,
            });
        }
        let (sx, sy) = (real(41, 1.0), real(42, 1.0));
        if !(sx.is_finite() && sy.is_finite() && sx != 0.0 && sy != 0.0) {
            self.warnings.push(ImportWarning::BlockScaledToNothing {
                insert: e.reference(layer),
                name,
                scale: (sx, sy),
            });
            return Ok(());
        }
        let rotation = real(50, 0.0).to_radians();
        let ins = Vector::new(real(10, 0.0), real(20, 0.0));
        let (cols, rows) = (int(70, 1).max(1), int(71, 1).max(1));
        let (dx, dy) = (real(44, 0.0), real(45, 0.0));
        // Counted before anything is built: nested blocks can multiply out exponentially.
        let cells = u64::try_from(cols.saturating_mul(rows)).unwrap_or(u64::MAX);
        let size = self.expanded_size(&name, 0).saturating_mul(cells);
        if cells > MAX_CURVES as u64 || size.saturating_add(self.curves as u64) > MAX_CURVES as u64 {
            return Err(ImportError::TooLarge {
                limit: MAX_CURVES,
                pos: e.pos,
            });
        }
        let ocs = ocs_to_world([real(210, 0.0), real(220, 0.0), real(230, 1.0)], real(30, 0.0));
        let local =
            Affine::scale_xy(sx, sy).then(&Affine::translate(Vector::new(-block.base[0], -block.base[1])));
        self.stack.push(name);
        for r in 0..rows {
            for c in 0..cols {
                // MINSERT spacing is measured in the rotated, unscaled frame of the insertion.
                let cell = Affine::translate(Vector::new(c as f64 * dx, r as f64 * dy));
                let place = Affine::translate(ins)
                    .then(&Affine::rotate(rotation))
                    .then(&cell)
                    .then(&local);
                self.walk(&block.entities, &m.then(&ocs).then(&place), Some(layer))?;
            }
        }
        self.stack.pop();
        Ok(())
    }

    /// How many entities (other than INSERTs) one insertion of block `name` draws, counting
    /// nested insertions and their arrays; saturating. A block that inserts itself counts its
    /// own entities once (the walk refuses it).
    fn expanded_size(&mut self, name: &str, depth: usize) -> u64 {
        let key = name.to_uppercase();
        if let Some(&n) = self.sizes.get(&key) {
            return n;
        }
        let Some(block) = self.doc.blocks.get(&key) else {
            return 0;
        };
        // Mark as in progress: a cycle counts as nothing more.
        self.sizes.insert(key.clone(), 0);
        let mut n: u64 = 0;
        for e in &block.entities {
            if e.kind != "INSERT" {
                n = n.saturating_add(1);
                continue;
            }
            if depth >= MAX_NESTING {
                continue;
            }
            let f = Fields::of(e);
            let int = |code: i32| f.int_or(code, 1).max(1);
            let cells = u64::try_from(int(70).saturating_mul(int(71))).unwrap_or(u64::MAX);
            let child = f.group(2).map(|g| g.text()).unwrap_or_default().trim().to_owned();
            n = n.saturating_add(self.expanded_size(&child, depth + 1).saturating_mul(cells));
        }
        self.sizes.insert(key, n);
        n
    }
}
