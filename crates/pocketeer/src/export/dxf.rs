//! A minimal DXF writer: closed contours as LWPOLYLINE entities with bulges (arcs stay exact,
//! a full circle as two half circles), in a file any CAD program reads.

use crate::fixed::{push_digits, push_number, Text};
use crate::geom::{Contour, Segment};
use crate::import::Units;

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
    let mut s = Text::default();
    pair(&mut s, 0, "SECTION");
    pair(&mut s, 2, "HEADER");
    pair(&mut s, 9, "$ACADVER");
    pair(&mut s, 1, "AC1015");
    pair(&mut s, 9, "$INSUNITS");
    pair(&mut s, 70, &insunits(units).to_string());
    pair(&mut s, 0, "ENDSEC");
    pair(&mut s, 0, "SECTION");
    pair(&mut s, 2, "ENTITIES");
    for lc in contours {
        let segments = &lc.contour.segments;
        let count: usize = segments
            .iter()
            .map(|seg| vertices(seg).iter().flatten().count())
            .sum();
        pair(&mut s, 0, "LWPOLYLINE");
        pair(&mut s, 100, "AcDbEntity");
        pair(&mut s, 8, lc.layer);
        pair(&mut s, 100, "AcDbPolyline");
        pair(&mut s, 90, &count.to_string());
        pair(&mut s, 70, "1");
        // Printing numbers is most of writing a large loop: a loop of PARALLEL_VERTICES
        // segments or more is printed in parts at once on the machine's cores, joined in
        // order; a smaller one is a single part, printed here.
        let part = if segments.len() < PARALLEL_VERTICES {
            segments.len().max(1)
        } else {
            segments.len().div_ceil(4 * crate::parallel::cores())
        };
        let parts: Vec<&[Segment]> = segments.chunks(part).collect();
        for text in crate::parallel::map_each(&parts, |part| {
            // About 30 bytes a coordinate: reserved once, not grown by doubling.
            let mut t = Text::default();
            t.reserve(64 * part.len());
            write_vertices(&mut t, part, k);
            t
        }) {
            s.append(&text);
        }
    }
    pair(&mut s, 0, "ENDSEC");
    pair(&mut s, 0, "EOF");
    s.into_string()
}

/// Loops of at least this many segments are printed in parts on several threads.
const PARALLEL_VERTICES: usize = 16_384;

/// The polyline vertices `seg` starts: a bulge gives an arc's sweep as tan(sweep / 4), which a
/// full turn has none of, so a circle is written as its two halves. (Not as a CIRCLE entity,
/// which has no direction: a loop round an island runs clockwise.)
fn vertices(seg: &Segment) -> [Option<Segment>; 2] {
    match seg {
        Segment::Arc(a) if a.is_full_circle() => [
            Some(Segment::Arc(a.subsegment(0.0, 0.5))),
            Some(Segment::Arc(a.subsegment(0.5, 1.0))),
        ],
        _ => [Some(*seg), None],
    }
}

/// Appends the vertex groups of `segments` (10, 20, and 42 for an arc), coordinates scaled by
/// `k`.
fn write_vertices(s: &mut Text, segments: &[Segment], k: f64) {
    for seg in segments.iter().flat_map(vertices).flatten() {
        let p = seg.start();
        number(s, 10, p.x * k, 10);
        number(s, 20, p.y * k, 10);
        if let Segment::Arc(a) = seg {
            number(s, 42, a.bulge(), 12);
        }
    }
}

/// Appends a group code right-aligned in three columns, as AutoCAD writes them (by hand: the
/// formatting machinery was a tenth of writing a large drawing).
fn code(s: &mut Text, code: u16) {
    let digits = match code {
        0..=9 => 1,
        10..=99 => 2,
        _ => 3,
    };
    s.push_str(&"   "[..3usize.saturating_sub(digits)]);
    push_digits(s, u64::from(code), 1);
    s.push('\n');
}

/// Appends a group: its code, then `value`.
fn pair(s: &mut Text, c: u16, value: &str) {
    code(s, c);
    s.push_str(value);
    s.push('\n');
}

/// Appends a group holding `v` with `decimals` decimals.
fn number(s: &mut Text, c: u16, v: f64, decimals: usize) {
    code(s, c);
    push_number(s, v, decimals);
    s.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Contour, Point};

    #[test]
    fn a_loop_printed_in_parts_is_the_loop_printed_whole() {
        // A wavy ring with more segments than are printed on one thread.
        let n = PARALLEL_VERTICES + 1234;
        let points: Vec<Point> = (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = 100.0 + 8.0 * (12.0 * a).sin();
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let ring = Contour::polygon(&points);
        let text = write_dxf(
            &[LayeredContour {
                layer: "offset",
                contour: &ring,
            }],
            Units::Inches,
        );
        let mut whole = Text::default();
        write_vertices(&mut whole, &ring.segments, 1.0 / Units::Inches.mm());
        let whole = whole.into_string();
        assert!(text.contains(&format!("AcDbPolyline\n 90\n{n}\n 70\n1\n{whole}  0\nENDSEC\n")));
    }
}
