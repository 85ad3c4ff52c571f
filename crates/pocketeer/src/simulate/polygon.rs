//! Polygons for the boolean library: exact contours flattened within a chord tolerance, areas,
//! and the largest circle inside a polygon with holes.

use crate::geom::{Contour, Point, Segment};

/// A polygon with holes as the boolean library takes it: the outer ring first.
pub type Shape = Vec<Vec<[f64; 2]>>;

/// Points of `segments` (closed or open), arcs as chords within `chord` of the arc (points on
/// the arc, so the polygon lies inside a convex arc's bulge).
pub fn flatten(segments: &[Segment], chord: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for s in segments {
        let p = s.start();
        out.push([p.x, p.y]);
        if let Segment::Arc(a) = s {
            // Sagitta r(1 − cos(θ/2)) ≤ chord.
            let step = 2.0 * (1.0 - (chord / a.radius()).min(1.0)).acos();
            let n = ((a.sweep().abs() / step.max(1e-6)).ceil() as usize).clamp(1, 1 << 16);
            for k in 1..n {
                let q = a.point_at(k as f64 / n as f64);
                out.push([q.x, q.y]);
            }
        }
    }
    out
}

/// A contour flattened (see [`flatten`]).
pub fn ring(c: &Contour, chord: f64) -> Vec<[f64; 2]> {
    flatten(&c.segments, chord)
}

/// Signed area of a ring (positive counter-clockwise).
pub fn ring_area(r: &[[f64; 2]]) -> f64 {
    let n = r.len();
    if n < 3 {
        return 0.0;
    }
    let o = r[0];
    let mut a = 0.0;
    for k in 1..n - 1 {
        let (p, q) = (r[k], r[k + 1]);
        a += (p[0] - o[0]) * (q[1] - o[1]) - (q[0] - o[0]) * (p[1] - o[1]);
    }
    0.5 * a
}

/// `points` with every point dropped that lies within `tolerance` of the line between the
/// points kept around it (Douglas–Peucker): a path of many short segments strokes far faster,
/// and moves by at most `tolerance`.
pub fn simplify(points: &[[f64; 2]], tolerance: f64) -> Vec<[f64; 2]> {
    let n = points.len();
    if n < 3 {
        return points.to_vec();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0, n - 1)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (points[a], points[b]);
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len2 = dx * dx + dy * dy;
        let mut worst = (0.0, 0);
        for (k, r) in points.iter().enumerate().take(b).skip(a + 1) {
            let t = if len2 > 0.0 {
                (((r[0] - p[0]) * dx + (r[1] - p[1]) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (p[0] + t * dx - r[0]).hypot(p[1] + t * dy - r[1]);
            if d > worst.0 {
                worst = (d, k);
            }
        }
        if worst.0 > tolerance {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

/// Length of a closed ring.
pub fn ring_length(r: &[[f64; 2]]) -> f64 {
    let n = r.len();
    (0..n)
        .map(|k| {
            let (a, b) = (r[k], r[(k + 1) % n]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum()
}

/// Area of a shape: its outer ring less its holes, whatever their orientation.
pub fn shape_area(s: &Shape) -> f64 {
    let mut rings = s.iter();
    let outer = rings.next().map_or(0.0, |r| ring_area(r).abs());
    outer - rings.map(|r| ring_area(r).abs()).sum::<f64>()
}

/// Signed distance from `p` to the shape's boundary: positive inside.
fn signed_distance(s: &Shape, p: [f64; 2]) -> f64 {
    let mut inside = false;
    let mut best = f64::INFINITY;
    for r in s {
        let n = r.len();
        for k in 0..n {
            let (a, b) = (r[k], r[(k + 1) % n]);
            if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) {
                inside = !inside;
            }
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (qx, qy) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
            best = best.min(qx * qx + qy * qy);
        }
    }
    let d = best.sqrt();
    if inside {
        d
    } else {
        -d
    }
}

/// The largest circle inside a shape, within `precision`: its centre and radius. A search
/// over square cells that discards every cell that cannot hold a better centre (the distance
/// at a cell's centre plus its half diagonal bounds what the cell can hold).
pub fn largest_inscribed_circle(s: &Shape, precision: f64) -> (Point, f64) {
    let Some(outer) = s.first().filter(|r| !r.is_empty()) else {
        return (Point::ORIGIN, 0.0);
    };
    let (mut x0, mut y0, mut x1, mut y1) =
        (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for p in outer {
        x0 = x0.min(p[0]);
        y0 = y0.min(p[1]);
        x1 = x1.max(p[0]);
        y1 = y1.max(p[1]);
    }
    let size = (x1 - x0).min(y1 - y0);
    if size.is_nan() || size <= 0.0 {
        return (Point::new(x0, y0), 0.0);
    }
    let h = 0.5 * size;
    // (bound, distance at centre, x, y, half size)
    let mut cells: Vec<(f64, f64, f64, f64, f64)> = Vec::new();
    let push = |cells: &mut Vec<(f64, f64, f64, f64, f64)>, x: f64, y: f64, h: f64| {
        let d = signed_distance(s, [x, y]);
        cells.push((d + h * std::f64::consts::SQRT_2, d, x, y, h));
    };
    let mut x = x0;
    while x < x1 {
        let mut y = y0;
        while y < y1 {
            push(&mut cells, x + h, y + h, h);
            y += 2.0 * h;
        }
        x += 2.0 * h;
    }
    let mut best = (
        Point::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)),
        signed_distance(s, [0.5 * (x0 + x1), 0.5 * (y0 + y1)]),
    );
    let mut rounds = 0;
    while let Some(i) = (0..cells.len()).max_by(|&a, &b| cells[a].0.total_cmp(&cells[b].0)) {
        let (bound, d, x, y, h) = cells.swap_remove(i);
        if d > best.1 {
            best = (Point::new(x, y), d);
        }
        rounds += 1;
        if bound - best.1 <= precision || rounds > 20_000 {
            break;
        }
        let q = 0.5 * h;
        for (dx, dy) in [(-q, -q), (q, -q), (-q, q), (q, q)] {
            push(&mut cells, x + dx, y + dy, q);
        }
    }
    (best.0, best.1.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inscribed_circle_of_a_rectangle_with_a_hole() {
        let rect: Shape = vec![vec![[0.0, 0.0], [10.0, 0.0], [10.0, 4.0], [0.0, 4.0]]];
        let (c, r) = largest_inscribed_circle(&rect, 1e-4);
        assert!((r - 2.0).abs() < 1e-3 && (c.y - 2.0).abs() < 1e-2, "{c:?} {r}");
        let holed: Shape = vec![
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![[2.0, 2.0], [2.0, 8.0], [8.0, 8.0], [8.0, 2.0]],
        ];
        // The widest place of a square ring is in its corners: 4 − 2√2 between the outer
        // corner's sides and the hole's corner.
        let (c, r) = largest_inscribed_circle(&holed, 1e-4);
        assert!((r - (4.0 - 2.0 * 2f64.sqrt())).abs() < 1e-3, "{c:?} {r}");
        assert!((shape_area(&holed) - 64.0).abs() < 1e-12);
    }
}
