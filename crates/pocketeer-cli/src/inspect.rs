//! `pocketeer inspect`: what a drawing holds, as one serialisable value rendered as text or
//! JSON; and the importer's warnings, which every command prints.

use crate::display::count;
use pocketeer::geom::Point;
use pocketeer::import::{ImportWarning, NearestGap};
use pocketeer::Analysis;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// The inspection report.
#[derive(Serialize)]
pub struct Report {
    file: String,
    format: &'static str,
    units: String,
    declared_units: Option<String>,
    /// The drawing's extent in mm: [min x, min y, max x, max y].
    extent_mm: Option<[f64; 4]>,
    layers: Vec<LayerRow>,
    entities: BTreeMap<String, usize>,
    elements: usize,
    contours: Vec<ContourRow>,
    open_chains: Vec<OpenRow>,
    pockets: Vec<PocketRow>,
    /// What the importer changed from the drawing as drawn: empty for a clean drawing.
    repairs: Vec<RepairRow>,
    warnings: Vec<String>,
}

#[derive(Serialize)]
struct RepairRow {
    kind: &'static str,
    /// The places, mm.
    at: Vec<Point>,
    message: String,
}

#[derive(Serialize)]
struct LayerRow {
    name: String,
    elements: usize,
}

#[derive(Serialize)]
struct ContourRow {
    layer: String,
    closed: bool,
    level: usize,
    role: &'static str,
    area_mm2: f64,
    elements: usize,
}

#[derive(Serialize)]
struct OpenRow {
    layer: String,
    elements: usize,
    start: Point,
    end: Point,
    nearest_gap_mm: Option<f64>,
}

#[derive(Serialize)]
struct PocketRow {
    area_mm2: f64,
    boundary_area_mm2: f64,
    boundary_elements: usize,
    islands: Vec<IslandRow>,
}

#[derive(Serialize)]
struct IslandRow {
    area_mm2: f64,
    elements: usize,
}

/// The flag that would close `gap`, when closing it is plausible (under a millimetre, farther
/// merges separate shapes): `--close-gaps` when the two ends are unambiguously each other's,
/// else `--join-tolerance`, which pairs nearest ends first.
pub fn gap_flag(gap: NearestGap) -> Option<String> {
    let flag = if gap.unambiguous {
        "--close-gaps"
    } else {
        "--join-tolerance"
    };
    (gap.length <= 1.0).then(|| format!("{flag} {}", suggest_length(gap.length)))
}

/// A round length just above `gap`: 0.0084 → "0.009mm".
fn suggest_length(gap: f64) -> String {
    let mut step = 1e-6;
    while step * 10.0 <= gap {
        step *= 10.0;
    }
    let value = ((gap / step).floor() + 1.0) * step;
    let decimals = (-step.log10()).round().max(0.0) as usize;
    format!("{value:.decimals$}mm")
}

/// Everything the importer has to say about the drawing, once each: what the reader met, the
/// elements dropped, the gaps closed, the open chains ignored, the slivers removed, and how
/// contours were nested. `inspect`, `offset` and `pocket` all print these.
pub fn import_warnings(a: &Analysis) -> Vec<String> {
    let d = &a.drawing;
    let layer_name = |i: usize| d.layers.get(i).cloned().unwrap_or_default();
    let mut warnings: Vec<String> = d.warnings.iter().map(ToString::to_string).collect();
    let ch = &a.chains;
    warnings.extend(ch.warnings.iter().map(ToString::to_string));
    for o in &ch.open {
        let hint = match o.nearest_gap {
            Some(g) => match gap_flag(g) {
                Some(flag) => format!(
                    "; the nearest free end is {:.4} mm away: {flag} would join it",
                    g.length
                ),
                None => format!("; the nearest free end is {:.3} mm away", g.length),
            },
            None => String::new(),
        };
        warnings.push(format!(
            "open chain of {} on layer '{}' ignored: free ends at {} and {}{hint}",
            count(o.elements.len(), "element", "elements"),
            layer_name(o.layer),
            o.start,
            o.end
        ));
    }
    warnings.extend(a.nesting.warnings.iter().map(ToString::to_string));
    warnings
}

/// The importer's repairs: its remarks that change the outlines from the drawing as drawn.
pub fn repairs(a: &Analysis) -> Vec<&ImportWarning> {
    a.chains
        .warnings
        .iter()
        .chain(&a.nesting.warnings)
        .filter(|w| w.is_repair())
        .collect()
}

/// Rounds to three decimals, as the report shows areas.
fn r3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

impl Report {
    /// Builds the report of `a` for file `file`.
    pub fn new(file: &str, a: &Analysis) -> Report {
        let d = &a.drawing;
        let layer_name = |i: usize| d.layers.get(i).cloned().unwrap_or_default();
        let mut per_layer = vec![0usize; d.layers.len()];
        for e in &d.elements {
            if let Some(n) = per_layer.get_mut(e.layer) {
                *n += 1;
            }
        }
        let contours = a
            .chains
            .contours
            .iter()
            .zip(&a.nesting.depths)
            .map(|(c, &level)| ContourRow {
                layer: layer_name(c.layer),
                closed: true,
                level,
                role: if level % 2 == 0 {
                    "pocket boundary"
                } else {
                    "island"
                },
                area_mm2: r3(c.contour.signed_area().abs()),
                elements: c.contour.segments.len(),
            })
            .collect();
        let open_chains = a
            .chains
            .open
            .iter()
            .map(|o| OpenRow {
                layer: layer_name(o.layer),
                elements: o.elements.len(),
                start: o.start,
                end: o.end,
                nearest_gap_mm: o.nearest_gap.map(|g| g.length),
            })
            .collect();
        let pockets = a
            .nesting
            .pockets
            .iter()
            .map(|p| {
                // Each area once: a drawing of traced art has half a million arcs.
                let boundary = p.boundary.signed_area();
                let islands: Vec<f64> = p.islands.iter().map(|i| i.signed_area()).collect();
                PocketRow {
                    area_mm2: r3(boundary + islands.iter().sum::<f64>()),
                    boundary_area_mm2: r3(boundary),
                    boundary_elements: p.boundary.segments.len(),
                    islands: (p.islands.iter().zip(&islands))
                        .map(|(i, area)| IslandRow {
                            area_mm2: r3(area.abs()),
                            elements: i.segments.len(),
                        })
                        .collect(),
                }
            })
            .collect();
        let repairs = repairs(a)
            .into_iter()
            .map(|w| RepairRow {
                kind: w.kind(),
                at: w.places(),
                message: w.to_string(),
            })
            .collect();
        let mut warnings = import_warnings(a);
        warnings.extend(crate::sanity::size_warnings(a));
        Report {
            file: file.to_owned(),
            extent_mm: (!d.extent.is_empty()).then_some([
                d.extent.min.x,
                d.extent.min.y,
                d.extent.max.x,
                d.extent.max.y,
            ]),
            format: if d.binary { "binary DXF" } else { "ASCII DXF" },
            units: d.units.to_string(),
            declared_units: d.declared_units.map(|u| u.to_string()),
            layers: d
                .layers
                .iter()
                .zip(per_layer)
                .map(|(n, e)| LayerRow {
                    name: n.clone(),
                    elements: e,
                })
                .collect(),
            entities: d.entity_counts.clone(),
            elements: d.elements.len(),
            contours,
            open_chains,
            pockets,
            repairs,
            warnings,
        }
    }

    /// The report as readable text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let declared = self
            .declared_units
            .as_deref()
            .map_or("none declared".to_owned(), |u| format!("declared {u}"));
        let _ = writeln!(s, "file      {} ({})", self.file, self.format);
        let _ = writeln!(s, "units     {} ({declared}); figures below in mm", self.units);
        let extent = self.extent_mm.map_or(pocketeer::geom::Aabb::EMPTY, |e| {
            pocketeer::geom::Aabb::from_points(Point::new(e[0], e[1]), Point::new(e[2], e[3]))
        });
        let _ = writeln!(
            s,
            "extents   {}",
            crate::sanity::describe_extent(&extent, crate::display::JobUnits::Millimetres)
        );
        let layers: Vec<String> = self
            .layers
            .iter()
            .map(|l| format!("{} ({})", l.name, l.elements))
            .collect();
        let _ = writeln!(s, "layers    {}", layers.join(", "));
        let ents: Vec<String> = self.entities.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let _ = writeln!(s, "entities  {} → {} elements", ents.join(", "), self.elements);
        let _ = writeln!(
            s,
            "contours  {} closed, {} open",
            self.contours.len(),
            self.open_chains.len()
        );
        for (i, c) in self.contours.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {:>3}  closed  level {}  {:<15}  area {:>14.3} mm²  {:>14}  layer {}",
                i + 1,
                c.level,
                c.role,
                c.area_mm2,
                count(c.elements, "element", "elements"),
                c.layer
            );
        }
        for o in &self.open_chains {
            let _ = writeln!(
                s,
                "       open    {}  layer {}  free ends {} and {}",
                count(o.elements, "element", "elements"),
                o.layer,
                o.start,
                o.end
            );
        }
        let _ = writeln!(s, "pockets   {}", self.pockets.len());
        for (i, p) in self.pockets.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {:>3}  area {:.3} mm² (boundary {:.3} mm², {}), {}",
                i + 1,
                p.area_mm2,
                p.boundary_area_mm2,
                count(p.boundary_elements, "element", "elements"),
                count(p.islands.len(), "island", "islands")
            );
            for isl in &p.islands {
                let _ = writeln!(
                    s,
                    "         island  area {:.3} mm²  {}",
                    isl.area_mm2,
                    count(isl.elements, "element", "elements")
                );
            }
        }
        if self.warnings.is_empty() {
            let _ = writeln!(s, "warnings  none");
        } else {
            let _ = writeln!(s, "warnings  {}", self.warnings.len());
            for w in &self.warnings {
                let _ = writeln!(s, "  - {w}");
            }
        }
        s
    }
}
