//! Arranging the loops of the levels into a tree: each level splits into parts (an outer loop
//! with the loops around islands inside it), and each part lies inside exactly one part of the
//! level before, because eroding further only removes points.

use super::{ClearPlan, Part};
use crate::geom::{Aabb, Contour, Point};

/// The parts of each level, linked to the part of the previous level they lie in.
pub fn build(levels: Vec<Vec<Contour>>, distances: &[f64]) -> ClearPlan {
    let mut plan = ClearPlan {
        distances: distances.to_vec(),
        ..ClearPlan::default()
    };
    let mut previous: Vec<usize> = Vec::new();
    for (level, loops) in levels.into_iter().enumerate() {
        let parts = parts(loops);
        let mut current = Vec::with_capacity(parts.len());
        for (outer, holes) in parts {
            let id = plan.parts.len();
            let parent = if level == 0 {
                plan.roots.push(id);
                None
            } else {
                Some(enclosing(&plan.parts, &previous, outer.segments[0].start()))
            };
            if let Some(p) = parent {
                plan.parts[p].children.push(id);
            }
            plan.parts.push(Part {
                level,
                distance: distances[level],
                outer,
                holes,
                children: Vec::new(),
                parent,
                cleanups: Vec::new(),
                spots: Vec::new(),
            });
            current.push(id);
        }
        previous = current;
    }
    plan
}

/// The index among `candidates` of the part whose outer loop encloses `p`, the innermost of
/// those that do (the nearest by box when rounding puts `p` on no outer loop's inside).
///
/// The outer loops of one level do not cross, but one may lie inside a hole of another: the
/// loop round the space between four islands lies inside the loop round all of them, where
/// that merged loop is a hole of the part along the wall. A point inside both outer loops is
/// in the inner one's part, whose box is the smaller.
pub fn enclosing(parts: &[Part], candidates: &[usize], p: Point) -> usize {
    if candidates.len() == 1 {
        return candidates[0];
    }
    let inside = candidates
        .iter()
        .copied()
        .filter(|&c| parts[c].outer.bbox().contains(p) && parts[c].outer.contains(p))
        .min_by(|&a, &b| box_area(&parts[a].outer.bbox()).total_cmp(&box_area(&parts[b].outer.bbox())));
    inside.unwrap_or_else(|| {
        candidates
            .iter()
            .copied()
            .min_by(|&a, &b| {
                box_gap(&parts[a].outer.bbox(), p).total_cmp(&box_gap(&parts[b].outer.bbox(), p))
            })
            .unwrap_or(0)
    })
}

fn box_area(b: &Aabb) -> f64 {
    (b.max.x - b.min.x) * (b.max.y - b.min.y)
}

fn box_gap(b: &Aabb, p: Point) -> f64 {
    let dx = (b.min.x - p.x).max(p.x - b.max.x).max(0.0);
    let dy = (b.min.y - p.y).max(p.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

/// Points of a hole tested against the outer loops.
const HOLE_PROBES: usize = 8;

/// Groups loops into parts: each clockwise loop goes with the counter-clockwise loop around it,
/// the innermost when several are (an outer loop may lie inside a hole of another, see
/// [`enclosing`]).
fn parts(loops: Vec<Contour>) -> Vec<(Contour, Vec<Contour>)> {
    let (outers, holes): (Vec<Contour>, Vec<Contour>) =
        loops.into_iter().partition(|l| l.signed_area() > 0.0);
    let boxes: Vec<Aabb> = outers.iter().map(Contour::bbox).collect();
    let mut parts: Vec<(Contour, Vec<Contour>)> = outers.into_iter().map(|o| (o, Vec::new())).collect();
    for h in holes {
        // A hole may touch its outer loop at a point (an island whose offset just reaches the
        // wall's), and one probe may fall there, outside by rounding: the owner is the outer
        // loop round most of several probes spread along the hole.
        let probes = h.points_along(HOLE_PROBES);
        let owner = if parts.len() == 1 {
            Some(0)
        } else {
            (0..parts.len())
                .map(|i| {
                    let inside = probes
                        .iter()
                        .filter(|&&p| boxes[i].contains(p) && parts[i].0.contains(p))
                        .count();
                    (i, inside)
                })
                .filter(|&(_, inside)| inside > 0)
                .max_by(|a, b| {
                    let area = |i: usize| box_area(&boxes[i]);
                    a.1.cmp(&b.1).then(area(b.0).total_cmp(&area(a.0)))
                })
                .map(|(i, _)| i)
        };
        // A hole outside every outer loop cannot come from an offset; drop it rather than cut it.
        if let Some(i) = owner {
            parts[i].1.push(h);
        }
    }
    parts
}
