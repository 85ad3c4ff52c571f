//! The benchmark inputs, built in code: each a pocket (CCW boundary, CW islands) of exact lines
//! and arcs, described as bulged polylines so that every implementation gets the same geometry.

use std::f64::consts::{PI, TAU};

/// A closed polyline: (x, y, bulge to the next vertex).
pub type Ring = Vec<(f64, f64, f64)>;

/// A benchmark case: the rings (boundary first, counter-clockwise; islands clockwise) and the
/// offset distances to compute, each from the original shape.
pub struct Case {
    pub name: String,
    pub rings: Vec<Ring>,
    pub distances: Vec<f64>,
}

fn circle_cw(cx: f64, cy: f64, r: f64) -> Ring {
    // Two half circles, clockwise (bulge -1).
    vec![(cx + r, cy, -1.0), (cx - r, cy, -1.0)]
}

fn rounded_rect(w: f64, h: f64, r: f64) -> Ring {
    let b = (PI / 8.0).tan(); // quarter circle
    vec![
        (r, 0.0, 0.0),
        (w - r, 0.0, b),
        (w, r, 0.0),
        (w, h - r, b),
        (w - r, h, 0.0),
        (r, h, b),
        (0.0, h - r, 0.0),
        (0.0, r, b),
    ]
}

fn levels(step: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|k| k as f64 * step).collect()
}

/// (a) 200 x 120 rounded pocket with 8 circular islands, 25 levels.
pub fn rounded_with_islands() -> Case {
    let mut rings = vec![rounded_rect(200.0, 120.0, 10.0)];
    for i in 0..4 {
        for j in 0..2 {
            rings.push(circle_cw(35.0 + i as f64 * 43.0, 35.0 + j as f64 * 50.0, 8.0));
        }
    }
    Case {
        name: "(a) rounded 200x120, 8 islands, 25 levels".into(),
        rings,
        distances: levels(1.2, 25),
    }
}

/// (b) A 48-tooth gear pocket with a hub island.
pub fn gear() -> Case {
    let teeth = 48;
    let (root, tip) = (90.0, 100.0);
    let mut ring = Vec::new();
    for k in 0..teeth {
        let a = k as f64 / teeth as f64 * TAU;
        let w = TAU / teeth as f64;
        // Root land, flank, rounded tip (an arc), flank.
        let pts = [
            (root, a),
            (tip, a + 0.3 * w),
            (tip, a + 0.6 * w),
            (root, a + 0.9 * w),
        ];
        for (i, &(r, t)) in pts.iter().enumerate() {
            let bulge = if i == 1 { (0.3 * w / 4.0).tan() } else { 0.0 };
            ring.push((r * t.cos(), r * t.sin(), bulge));
        }
    }
    Case {
        name: "(b) 48-tooth gear, hub island".into(),
        rings: vec![ring, circle_cw(0.0, 0.0, 20.0)],
        distances: levels(1.5, 25),
    }
}

/// (c) The smooth profile r = 100 + 8 sin(12 t) with `n` vertices, as lines or as arcs.
pub fn smooth(n: usize, arcs: bool) -> Case {
    let r = |t: f64| 100.0 + 8.0 * (12.0 * t).sin();
    let at = |t: f64| (r(t) * t.cos(), r(t) * t.sin());
    let mut ring = Vec::with_capacity(n);
    for k in 0..n {
        let t0 = k as f64 / n as f64 * TAU;
        let t1 = (k + 1) as f64 / n as f64 * TAU;
        let (p0, p1, m) = (at(t0), at(t1), at(0.5 * (t0 + t1)));
        let bulge = if arcs { bulge_through(p0, m, p1) } else { 0.0 };
        ring.push((p0.0, p0.1, bulge));
    }
    let kind = if arcs { "arcs" } else { "lines" };
    Case {
        name: format!("(c) smooth r=100+8sin(12t), {n} {kind}, 46 levels"),
        rings: vec![ring],
        distances: levels(2.0, 46),
    }
}

/// The bulge of the arc from `a` through `m` to `b`.
fn bulge_through(a: (f64, f64), m: (f64, f64), b: (f64, f64)) -> f64 {
    // The inscribed angle gives the sweep: bulge = tan(sweep / 4), with the sign of the turn.
    let (ux, uy) = (m.0 - a.0, m.1 - a.1);
    let (vx, vy) = (b.0 - m.0, b.1 - m.1);
    let cross = ux * vy - uy * vx;
    let dot = ux * vx + uy * vy;
    // The turn at m is half the sweep.
    let half_sweep = cross.atan2(dot);
    (half_sweep / 2.0).tan()
}

/// (d) A pocket with a 10 x 6 grid of circular islands.
pub fn grid_of_islands() -> Case {
    let mut rings = vec![rounded_rect(220.0, 140.0, 5.0)];
    for i in 0..10 {
        for j in 0..6 {
            rings.push(circle_cw(20.0 + i as f64 * 20.0, 20.0 + j as f64 * 20.0, 5.0));
        }
    }
    Case {
        name: "(d) 10x6 grid of islands, 10 levels".into(),
        rings,
        distances: levels(0.6, 10),
    }
}

/// The smooth profile of [`smooth`] with six round islands of radius 8 on a circle of radius
/// 55: the drawing of the whole-process comparisons (`n` elements in all).
pub fn smooth_with_islands(n: usize, arcs: bool) -> Case {
    let mut case = smooth(n - 6, arcs);
    for k in 0..6 {
        let a = k as f64 * TAU / 6.0;
        case.rings.push(circle_cw(55.0 * a.cos(), 55.0 * a.sin(), 8.0));
    }
    case.name = format!(
        "smooth profile, {n} {}, 6 islands",
        if arcs { "arcs" } else { "lines" }
    );
    case
}

/// A plate with `nx` × `ny` round holes of 8 mm at a 20 mm pitch, 10 mm from its edges (the
/// 300-hole plate of issue 18 and 21 is 20 × 15: 400 × 300 mm).
pub fn plate(nx: usize, ny: usize) -> Case {
    let (w, h) = (20.0 * nx as f64, 20.0 * ny as f64);
    let mut rings = vec![vec![(0.0, 0.0, 0.0), (w, 0.0, 0.0), (w, h, 0.0), (0.0, h, 0.0)]];
    for i in 0..nx {
        for j in 0..ny {
            rings.push(circle_cw(10.0 + 20.0 * i as f64, 10.0 + 20.0 * j as f64, 4.0));
        }
    }
    Case {
        name: format!("plate {w}x{h}, {} holes of 8 mm", nx * ny),
        rings,
        distances: Vec::new(),
    }
}
