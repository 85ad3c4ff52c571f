//! Benchmark inputs shared by the bench binaries.

pub mod cases;

use cases::{Case, Ring};
use pocketeer::geom::Pocket;
use pocketeer::geom::{Arc, Contour, Line, Point, Segment};

/// A bulged polyline as exact lines and arcs.
pub fn contour(ring: &Ring) -> Contour {
    let n = ring.len();
    Contour::new(
        (0..n)
            .map(|k| {
                let (x0, y0, b) = ring[k];
                let (x1, y1, _) = ring[(k + 1) % n];
                let (a, e) = (Point::new(x0, y0), Point::new(x1, y1));
                Arc::from_bulge(a, e, b)
                    .map(Segment::Arc)
                    .unwrap_or(Segment::Line(Line::new(a, e)))
            })
            .collect(),
    )
}

/// The case's rings as closed LWPOLYLINEs on layer 0 of an ASCII DXF, in millimetres (bulges
/// written only where a ring has an arc).
pub fn dxf(case: &Case) -> String {
    use std::fmt::Write;
    let mut s =
        String::from("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    for ring in &case.rings {
        let _ = write!(s, "0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", ring.len());
        for &(x, y, bulge) in ring {
            let _ = write!(s, "10\n{x:.6}\n20\n{y:.6}\n");
            if bulge != 0.0 {
                let _ = write!(s, "42\n{bulge:.9}\n");
            }
        }
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

/// An ASCII DXF's groups written as a binary DXF (R13 and later: two-byte codes, numbers as
/// stored by their code's range, texts ending in a zero byte).
pub fn binary_dxf(ascii: &str) -> Vec<u8> {
    let mut out = b"AutoCAD Binary DXF\r\n\x1a\0".to_vec();
    let mut lines = ascii.lines();
    while let (Some(code), Some(value)) = (lines.next(), lines.next()) {
        let code: i16 = code.trim().parse().expect("a group code");
        out.extend(code.to_le_bytes());
        let value = value.trim();
        match code {
            10..=59 | 110..=149 | 210..=239 | 460..=469 | 1010..=1059 => {
                out.extend(value.parse::<f64>().expect("a real").to_le_bytes())
            }
            60..=79 | 170..=179 | 270..=289 | 370..=389 | 400..=409 | 1060..=1070 => {
                out.extend(value.parse::<i16>().expect("a 16-bit integer").to_le_bytes())
            }
            90..=99 | 420..=429 | 440..=459 | 1071 => {
                out.extend(value.parse::<i32>().expect("a 32-bit integer").to_le_bytes())
            }
            _ => {
                out.extend(value.as_bytes());
                out.push(0);
            }
        }
    }
    out
}

/// The case as a pocket: the first ring its boundary, the others its islands.
pub fn pocket(case: &Case) -> Pocket {
    Pocket {
        boundary: contour(&case.rings[0]),
        islands: case.rings[1..].iter().map(contour).collect(),
    }
}

/// Clipper2 on a 10 nm integer grid, so that rounding stays far below the flattening error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct TenNano;

impl clipper2::PointScaler for TenNano {
    const MULTIPLIER: f64 = 1e5;
}

/// The rings as polygons whose chords stray at most 0.001 mm from the arcs.
pub fn flattened(case: &Case) -> clipper2::Paths<TenNano> {
    let paths: Vec<clipper2::Path<TenNano>> = case
        .rings
        .iter()
        .map(|ring| {
            let mut pts: Vec<(f64, f64)> = Vec::new();
            for s in &contour(ring).segments {
                let steps = match s {
                    pocketeer::geom::Segment::Line(_) => 1,
                    pocketeer::geom::Segment::Arc(a) => {
                        let max_step = 2.0 * (1.0 - 0.001 / a.radius()).clamp(-1.0, 1.0).acos();
                        (a.sweep().abs() / max_step).ceil().max(1.0) as usize
                    }
                };
                for k in 0..steps {
                    let p = s.point_at(k as f64 / steps as f64);
                    pts.push((p.x, p.y));
                }
            }
            pts.into()
        })
        .collect();
    paths.into()
}

/// The area of `paths` eroded by `d` with Clipper2 (round joins), as the benchmarks compare it.
pub fn clipper_eroded_area(paths: &clipper2::Paths<TenNano>, d: f64) -> f64 {
    clipper2::inflate(
        paths.clone(),
        -d,
        clipper2::JoinType::Round,
        clipper2::EndType::Polygon,
        2.0,
    )
    .signed_area()
}
