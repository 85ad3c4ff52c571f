//! A minimal DXF writer: closed contours as LWPOLYLINE entities with bulges (arcs stay exact,
//! a full circle as two half circles), in a file any CAD program reads.

use crate::geom::{Contour, Segment};
use crate::import::Units;
use std::fmt::Write;

/// One contour to write, on a layer.
pub struct LayeredContour<'a> {
    /// Layer name.
    pub layer: &'a str,
    /// The contour (millimetres).
    pub contour: &'a Contour,
}

fn insunits(u: Units) -> i32 {
    match u {
        Units::Inches => 1,
        Units::Feet => 2,
        Units::Millimeters => 4,
        Units::Centimeters => 5,
        Units::Meters => 6,
        Units::Microinches => 8,
        Units::Mils => 9,
        Units::Yards => 10,
        Units::Microns => 13,
        Units::Decimeters => 14,
    }
}

/// DXF text holding `contours`, with coordinates converted from millimetres to `units`.
///
/// ```
/// use pocketeer::export::dxf::{write_dxf, LayeredContour};
/// use pocketeer::geom::{Arc, Contour, Point, Segment};
/// use pocketeer::import::Units;
/// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 5.0))]);
/// let text = write_dxf(&[LayeredContour { layer: "holes", contour: &disc }], Units::Millimeters);
/// assert_eq!(text.matches("LWPOLYLINE").count(), 1);
/// let back = pocketeer::read_drawing(text.as_bytes(), &Default::default()).unwrap();
/// let area: f64 = back.elements.iter().map(|e| e.segment.area_term(Point::new(0.0, 0.0))).sum();
/// assert!((0.5 * area - std::f64::consts::PI * 25.0).abs() < 1e-9);
/// ```
pub fn write_dxf(contours: &[LayeredContour], units: Units) -> String {
    let k = 1.0 / units.mm();
    let mut s = String::new();
    let mut pair = |code: i32, value: &str| {
        let _ = writeln!(s, "{code:>3}\n{value}");
    };
    pair(0, "SECTION");
    pair(2, "HEADER");
    pair(9, "$ACADVER");
    pair(1, "AC1015");
    pair(9, "$INSUNITS");
    pair(70, &insunits(units).to_string());
    pair(0, "ENDSEC");
    pair(0, "SECTION");
    pair(2, "ENTITIES");
    let num = |x: f64| format!("{:.10}", x * k);
    for lc in contours {
        // A bulge gives an arc's sweep as tan(sweep / 4), which a full turn has none of: a
        // circle is written as its two halves. (Not as a CIRCLE entity, which has no
        // direction: a loop round an island runs clockwise.)
        let mut segs = Vec::with_capacity(lc.contour.segments.len() + 1);
        for seg in &lc.contour.segments {
            match seg {
                Segment::Arc(a) if a.is_full_circle() => segs.extend([
                    Segment::Arc(a.subsegment(0.0, 0.5)),
                    Segment::Arc(a.subsegment(0.5, 1.0)),
                ]),
                _ => segs.push(*seg),
            }
        }
        pair(0, "LWPOLYLINE");
        pair(100, "AcDbEntity");
        pair(8, lc.layer);
        pair(100, "AcDbPolyline");
        pair(90, &segs.len().to_string());
        pair(70, "1");
        for seg in &segs {
            let p = seg.start();
            pair(10, &num(p.x));
            pair(20, &num(p.y));
            if let Segment::Arc(a) = seg {
                pair(42, &format!("{:.12}", a.bulge()));
            }
        }
    }
    pair(0, "ENDSEC");
    pair(0, "EOF");
    s
}
