//! Model space with every block insertion expanded: each drawn curve in world coordinates, with
//! the layer it is drawn on and the entity it comes from.

use super::curve::{ocs_to_world, Affine, Curve};
use super::dxf::{Document, Group, RawEntity};
use super::entities::{curves_of, Drawn};
use super::error::{EntityRef, ImportError};
use crate::geom::Vector;

/// Deepest block nesting followed.
const MAX_NESTING: usize = 64;
/// Most curves block insertions may produce (guards against exponential nesting).
pub const MAX_CURVES: usize = 2_000_000;

/// One curve of the drawing in world coordinates (millimetres once the root map scales to them).
pub struct Placed {
    /// The curve.
    pub curve: Curve,
    /// The layer it is drawn on (block entities on layer 0 take the layer of their INSERT).
    pub layer: String,
    /// The entity (inside blocks, the innermost one), for messages.
    pub entity: EntityRef,
    /// For the curves of one closed polyline (one placement of it): a number shared by them,
    /// which are a contour by themselves, in order.
    pub closed_group: Option<usize>,
}

/// Walks model space, expanding INSERTs, and collects every curve.
pub struct Expander<'a> {
    doc: &'a Document,
    /// Curves found.
    pub placed: Vec<Placed>,
    /// Remarks (unknown blocks).
    pub warnings: Vec<String>,
    stack: Vec<String>,
    groups: usize,
}

impl<'a> Expander<'a> {
    /// An expander over `doc`.
    pub fn new(doc: &'a Document) -> Self {
        Expander {
            doc,
            placed: Vec::new(),
            warnings: Vec::new(),
            stack: Vec::new(),
            groups: 0,
        }
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
            match curves_of(e) {
                Ok(Drawn::Curves { curves, closed }) => {
                    let closed_group = closed.then(|| {
                        self.groups += 1;
                        self.groups
                    });
                    // Once per entity: finding the handle scans the entity's groups, which
                    // for a long polyline are many.
                    let reference = e.reference(&layer);
                    for c in curves {
                        let curve = c.transformed(m);
                        if let Err(p) = curve.check_coordinates(super::MAX_COORDINATE) {
                            return Err(ImportError::BadEntity {
                                entity: reference,
                                what: format!(
                                    "coordinate ({}, {}) is not a number or lies beyond ±{:e} mm",
                                    super::error::fmt_number(p.x),
                                    super::error::fmt_number(p.y),
                                    super::MAX_COORDINATE
                                ),
                            });
                        }
                        self.placed.push(Placed {
                            curve,
                            layer: layer.clone(),
                            entity: reference.clone(),
                            closed_group,
                        });
                    }
                    if self.placed.len() > MAX_CURVES {
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
        let real = |code: i32, default: f64| e.group(code).and_then(Group::real).unwrap_or(default);
        let int = |code: i32, default: i64| e.group(code).and_then(Group::int).unwrap_or(default);
        let name = e.text(2).unwrap_or_default().trim().to_owned();
        let Some(block) = self.doc.blocks.get(&name.to_uppercase()) else {
            self.warnings.push(format!(
                "{}: block '{name}' is not defined; ignored",
                e.reference(layer)
            ));
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
        let rotation = real(50, 0.0).to_radians();
        let ins = Vector::new(real(10, 0.0), real(20, 0.0));
        let (cols, rows) = (int(70, 1).max(1), int(71, 1).max(1));
        let (dx, dy) = (real(44, 0.0), real(45, 0.0));
        if cols.saturating_mul(rows) > MAX_CURVES as i64 {
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
}
