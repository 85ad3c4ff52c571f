//! A height map of the stock: the lowest Z the tool's end has reached over each cell of a
//! square grid, from the stock top (Z = 0) down.
//!
//! Coarse and cheap where the check's exact swept polygons are costly: stamping a disc costs
//! its number of cells, whatever the program before it. It answers one question well enough
//! for a picture — does the tool at a place meet stock, or move through what is already cut —
//! within about a cell.

use crate::geom::{Aabb, Point};

/// The lowest Z reached over each cell of a grid.
///
/// ```
/// use pocketeer::geom::{Aabb, Point};
/// use pocketeer::simulate::zmap::ZMap;
/// let mut m = ZMap::new(Aabb::from_points(Point::new(0.0, 0.0), Point::new(20.0, 10.0)), 0.25);
/// let p = Point::new(5.0, 5.0);
/// assert!(m.meets_stock(p, 2.5, -1.0));
/// m.stamp(p, 3.0, -1.0);
/// assert!(!m.meets_stock(p, 2.5, -1.0)); // cut there, at that depth
/// assert!(m.meets_stock(p, 2.5, -2.0)); // not that deep
/// assert!(m.meets_stock(Point::new(10.0, 5.0), 2.5, -1.0));
/// ```
#[derive(Debug, Clone)]
pub struct ZMap {
    grid: Grid,
    heights: Vec<f32>,
}

/// The cells' layout.
#[derive(Debug, Clone, Copy)]
struct Grid {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
}

/// Depth below which a cell counts as cut to a Z: the program's own rounding (1 µm).
const Z_SLACK: f32 = 1e-3;

impl ZMap {
    /// A grid of square cells of side `cell` over `extent`, all at the stock top (Z = 0).
    pub fn new(extent: Aabb, cell: f64) -> ZMap {
        let cell = if cell.is_finite() && cell > 0.0 { cell } else { 1.0 };
        let (w, h) = if extent.is_empty() {
            (0.0, 0.0)
        } else {
            (extent.width(), extent.height())
        };
        let nx = (w / cell).ceil() as usize + 1;
        let ny = (h / cell).ceil() as usize + 1;
        let origin = if extent.is_empty() {
            Point::new(0.0, 0.0)
        } else {
            extent.min
        };
        ZMap {
            grid: Grid { origin, cell, nx, ny },
            heights: vec![0.0; nx * ny],
        }
    }

    /// Side of a cell.
    pub fn cell(&self) -> f64 {
        self.grid.cell
    }

    /// Records that the tool's end, a disc of radius `r` at `c`, reached down to `z`.
    pub fn stamp(&mut self, c: Point, r: f64, z: f64) {
        let z = z as f32;
        let heights = &mut self.heights;
        self.grid.for_cells(c, r, |k| {
            if heights[k] > z {
                heights[k] = z;
            }
            false
        });
    }

    /// True when some cell centre within `r` of `c` is higher than `z`: stock a tool there at
    /// that height would meet. Outside the grid there is no stock.
    pub fn meets_stock(&self, c: Point, r: f64, z: f64) -> bool {
        let z = z as f32 + Z_SLACK;
        self.grid.for_cells(c, r, |k| self.heights[k] > z)
    }
}

impl Grid {
    /// Calls `f` with the index of every cell whose centre lies within `r` of `c`, until `f`
    /// returns true; true when it did.
    fn for_cells(&self, c: Point, r: f64, mut f: impl FnMut(usize) -> bool) -> bool {
        if r <= 0.0 {
            return false;
        }
        let (gx, gy) = (
            (c.x - self.origin.x) / self.cell,
            (c.y - self.origin.y) / self.cell,
        );
        let rc = r / self.cell;
        // Cell (i, j) has its centre at (i + ½, j + ½) in grid units.
        let j0 = (gy - rc - 0.5).ceil().max(0.0) as usize;
        let j1 = ((gy + rc - 0.5).floor()).min(self.ny as f64 - 1.0);
        if j1 < 0.0 {
            return false;
        }
        for j in j0..=j1 as usize {
            let dy = j as f64 + 0.5 - gy;
            let half = (rc * rc - dy * dy).max(0.0).sqrt();
            let i0 = (gx - half - 0.5).ceil().max(0.0) as usize;
            let i1 = (gx + half - 0.5).floor().min(self.nx as f64 - 1.0);
            if i1 < 0.0 {
                continue;
            }
            for i in i0..=i1 as usize {
                if f(j * self.nx + i) {
                    return true;
                }
            }
        }
        false
    }
}
