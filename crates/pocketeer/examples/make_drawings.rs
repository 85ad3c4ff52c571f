//! Writes the example drawings shipped in the repository's `examples/` folder.
//!
//! Run from the repository root: `cargo run -p pocketeer --example make_drawings`.

use pocketeer::export::dxf::{write_dxf, LayeredContour};
use pocketeer::geom::{Arc, Contour, Line, Point, Segment};
use pocketeer::import::Units;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A rectangle from (x0, y0) to (x1, y1) with corner radius r, counter-clockwise.
fn rounded_rect(x0: f64, y0: f64, x1: f64, y1: f64, r: f64) -> Contour {
    let p = Point::new;
    let mut s = Vec::new();
    let corners = [
        (x1 - r, y0 + r, -FRAC_PI_2),
        (x1 - r, y1 - r, 0.0),
        (x0 + r, y1 - r, FRAC_PI_2),
        (x0 + r, y0 + r, PI),
    ];
    let edges = [
        (p(x0 + r, y0), p(x1 - r, y0)),
        (p(x1, y0 + r), p(x1, y1 - r)),
        (p(x1 - r, y1), p(x0 + r, y1)),
        (p(x0, y1 - r), p(x0, y0 + r)),
    ];
    for k in 0..4 {
        s.push(Segment::Line(Line::new(edges[k].0, edges[k].1)));
        let (cx, cy, a) = corners[k];
        s.push(Segment::Arc(Arc::new(p(cx, cy), r, a, FRAC_PI_2)));
    }
    Contour::new(s)
}

/// A slot (obround) of length `len` between its arc centres and width `2 r`, along x.
fn slot(cx: f64, cy: f64, len: f64, r: f64) -> Contour {
    let p = Point::new;
    let (a, b) = (cx - len / 2.0, cx + len / 2.0);
    Contour::new(vec![
        Segment::Line(Line::new(p(a, cy - r), p(b, cy - r))),
        Segment::Arc(Arc::new(p(b, cy), r, -FRAC_PI_2, PI)),
        Segment::Line(Line::new(p(b, cy + r), p(a, cy + r))),
        Segment::Arc(Arc::new(p(a, cy), r, FRAC_PI_2, PI)),
    ])
}

fn main() -> std::io::Result<()> {
    let outline = rounded_rect(0.0, 0.0, 120.0, 80.0, 6.0);
    let boss_a = Contour::new(vec![Segment::Arc(Arc::new(
        Point::new(28.0, 52.0),
        9.0,
        0.0,
        TAU,
    ))]);
    let boss_b = Contour::new(vec![Segment::Arc(Arc::new(
        Point::new(92.0, 52.0),
        9.0,
        0.0,
        TAU,
    ))]);
    let rib = slot(60.0, 22.0, 40.0, 6.0);
    let drawing = [
        LayeredContour {
            layer: "pocket",
            contour: &outline,
        },
        LayeredContour {
            layer: "islands",
            contour: &boss_a,
        },
        LayeredContour {
            layer: "islands",
            contour: &boss_b,
        },
        LayeredContour {
            layer: "islands",
            contour: &rib,
        },
    ];
    std::fs::create_dir_all("examples")?;
    std::fs::write("examples/bracket.dxf", write_dxf(&drawing, Units::Millimeters))?;
    eprintln!("wrote examples/bracket.dxf");
    plate()
}

/// The two-layer plate of `examples/plate.toml`: on SHALLOW, pockets with sharp inner corners
/// and a slot 4 mm wide (narrower than the 6 mm tool, wider than the 2 mm one); on DEEP, a
/// pocket with two round islands.
fn plate() -> std::io::Result<()> {
    let p = Point::new;
    let square = Contour::polygon(&[p(10.0, 10.0), p(50.0, 10.0), p(50.0, 40.0), p(10.0, 40.0)]);
    let ell = Contour::polygon(&[
        p(60.0, 10.0),
        p(100.0, 10.0),
        p(100.0, 22.0),
        p(74.0, 22.0),
        p(74.0, 40.0),
        p(60.0, 40.0),
    ]);
    let narrow = slot(35.0, 60.0, 40.0, 2.0);
    let deep = rounded_rect(80.0, 45.0, 150.0, 95.0, 5.0);
    let hole = |x: f64, y: f64| Contour::new(vec![Segment::Arc(Arc::new(p(x, y), 6.0, 0.0, TAU))]);
    let (island_a, island_b) = (hole(100.0, 70.0), hole(130.0, 70.0));
    let layered = |layer, contour| LayeredContour { layer, contour };
    let drawing = [
        layered("SHALLOW", &square),
        layered("SHALLOW", &ell),
        layered("SHALLOW", &narrow),
        layered("DEEP", &deep),
        layered("DEEP", &island_a),
        layered("DEEP", &island_b),
    ];
    std::fs::write("examples/plate.dxf", write_dxf(&drawing, Units::Millimeters))?;
    eprintln!("wrote examples/plate.dxf");
    Ok(())
}
