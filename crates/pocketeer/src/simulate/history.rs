//! Where the tool has cut so far, and how deep: whether the stock under a tool disc was cut
//! down to a height before a given move, so that a rapid or a plunge coming straight down there
//! is known to meet no stock.
//!
//! The feed moves below the stock top are sampled along their footprints into a grid of cells
//! the size of the tool; a query looks at the cells around the place asked about and measures
//! the moves found there exactly.

use super::gcode::{Motion, ProgramMove};
use crate::geom::{closest_param, distance_from_segment, Point, Segment, Vector};
use std::collections::HashMap;

/// The feed moves of a program below the stock top, indexed by place.
pub struct CutHistory<'a> {
    moves: &'a [ProgramMove],
    /// Each move's footprint in XY, made once (an arc's takes trigonometry).
    footprints: Vec<Segment>,
    /// The radius of the tool that made each move.
    radii: Vec<f64>,
    /// The largest of them.
    largest: f64,
    cell: f64,
    cells: HashMap<(i64, i64), Vec<u32>>,
}

/// How far a move may be from a sample of the disc and still have cut there, beyond the radius,
/// mm: the programs' rounding.
const SLACK: f64 = 1e-3;

impl<'a> CutHistory<'a> {
    /// Indexes the feed moves of `moves` that go below Z=0, for a tool of radius `r`.
    pub fn new(moves: &'a [ProgramMove], r: f64) -> CutHistory<'a> {
        CutHistory::with_radii(moves, vec![r; moves.len()])
    }

    /// [`CutHistory::new`] for a program of several tools: `radii[k]` is the radius of the
    /// tool that makes move `k`.
    pub fn with_radii(moves: &'a [ProgramMove], radii: Vec<f64>) -> CutHistory<'a> {
        let smallest = radii.iter().copied().fold(f64::INFINITY, f64::min);
        let largest = radii.iter().copied().fold(0.0, f64::max);
        let cell = if smallest.is_finite() {
            smallest.max(1e-3)
        } else {
            1.0
        };
        let mut cells: HashMap<(i64, i64), Vec<u32>> = HashMap::new();
        let footprints: Vec<Segment> = moves.iter().map(ProgramMove::footprint).collect();
        for (k, m) in moves.iter().enumerate() {
            if m.motion == Motion::Rapid || m.from.z.min(m.to.z) >= 0.0 {
                continue;
            }
            let f = footprints[k];
            let n = ((f.length() / (0.5 * cell)).ceil() as usize).clamp(1, 1 << 20);
            let mut last = None;
            for j in 0..=n {
                let key = key(f.point_at(j as f64 / n as f64), cell);
                if last != Some(key) {
                    let list = cells.entry(key).or_default();
                    if list.last() != Some(&(k as u32)) {
                        list.push(k as u32);
                    }
                    last = Some(key);
                }
            }
        }
        CutHistory {
            moves,
            footprints,
            radii,
            largest,
            cell,
            cells,
        }
    }

    /// The footprint of move `k` in XY.
    pub fn footprint(&self, k: usize) -> &Segment {
        &self.footprints[k]
    }

    /// The feed moves below Z=0 before move `before` that may pass within `reach` of `p`
    /// (every one that does, and some that do not), each once, in program order.
    pub fn near(&self, before: usize, p: Point, reach: f64) -> Vec<usize> {
        let mut out = Vec::new();
        self.visit_near(before, p, reach, |k| {
            out.push(k);
            false
        });
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Calls `f` on the moves of [`CutHistory::near`] (some more than once) until it returns
    /// true; true when it did.
    fn visit_near(&self, before: usize, p: Point, reach: f64, mut f: impl FnMut(usize) -> bool) -> bool {
        let (cx, cy) = key(p, self.cell);
        // Samples lie half a cell apart: a move within `reach` of p has one within reach plus
        // a quarter cell.
        let cells = ((reach + 0.25 * self.cell) / self.cell).ceil() as i64 + 1;
        for dx in -cells..=cells {
            for dy in -cells..=cells {
                let Some(list) = self.cells.get(&(cx + dx, cy + dy)) else {
                    continue;
                };
                for &k in list.iter().take_while(|&&k| (k as usize) < before) {
                    if f(k as usize) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// True when, before move `before`, the tools had cut the whole disc of radius `r` around
    /// `p` down to `z` or deeper: every sample of the disc (its centre and two rings) lies
    /// within the radius of the tool of a feed move that passed there at `z` or below.
    pub fn cleared(&self, before: usize, p: Point, z: f64, r: f64) -> bool {
        let mut samples = vec![p];
        for (ring, n) in [(0.5, 8), (0.98, 16)] {
            for k in 0..n {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                samples.push(p + Vector::from_angle(a) * (ring * r));
            }
        }
        samples.iter().all(|&q| self.cut_at(before, q, z))
    }

    /// True when a feed move before `before` passed within its tool's radius of `q` at `z` or
    /// below.
    fn cut_at(&self, before: usize, q: Point, z: f64) -> bool {
        self.visit_near(before, q, self.largest, |k| {
            self.passed(k, q, z, self.radii[k] + SLACK)
        })
    }

    /// True when move `k` passed within `r` of `q` at `z` or below.
    pub fn passed(&self, k: usize, q: Point, z: f64, r: f64) -> bool {
        let (f, m) = (&self.footprints[k], &self.moves[k]);
        if distance_from_segment(f, q) > r {
            return false;
        }
        // A move straight down cut its disc at the bottom.
        let there = if f.length() <= 1e-9 {
            m.from.z.min(m.to.z)
        } else {
            m.point_at(closest_param(f, q)).z
        };
        there <= z + 1e-4
    }
}

fn key(p: Point, cell: f64) -> (i64, i64) {
    ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::Point3;

    fn feed(from: (f64, f64, f64), to: (f64, f64, f64)) -> ProgramMove {
        ProgramMove {
            line: 1,
            motion: Motion::Line,
            from: Point3::new(from.0, from.1, from.2),
            to: Point3::new(to.0, to.1, to.2),
            feed: Some(1000.0),
        }
    }

    #[test]
    fn a_disc_is_cleared_where_passes_cover_it_at_that_depth() {
        // Three passes 2 mm apart at Z-2 along x, a 3 mm tool radius.
        let moves = vec![
            feed((0.0, -2.0, -2.0), (40.0, -2.0, -2.0)),
            feed((40.0, 0.0, -2.0), (0.0, 0.0, -2.0)),
            feed((0.0, 2.0, -2.0), (40.0, 2.0, -2.0)),
        ];
        let h = CutHistory::new(&moves, 3.0);
        let p = Point::new(20.0, 0.0);
        assert!(h.cleared(3, p, -1.0, 3.0));
        assert!(h.cleared(3, p, -2.0, 3.0));
        // Not as deep as asked; not yet cut before the second move; not over the cut.
        assert!(!h.cleared(3, p, -3.0, 3.0));
        assert!(!h.cleared(1, p, -1.0, 3.0));
        assert!(!h.cleared(3, Point::new(20.0, 6.0), -1.0, 3.0));
    }
}
