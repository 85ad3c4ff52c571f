//! What each move of a program does, for drawing it: cut stock, link through stock already
//! cut, enter the stock, travel at rapid speed or retract.
//!
//! Rapids and moves that change height are told apart by their ends. A feed move at one height
//! below the stock top is a cut when the tool meets stock somewhere along it and a link when
//! it only moves through what earlier moves cleared: that is decided on a [`ZMap`] of cells of
//! a twelfth of the (smallest) tool radius (at most 2 048 across the program), testing the tool's disc
//! shrunk by half a cell (what an earlier sample half a cell away covered), at points one cell
//! apart along the moves. A move that takes off less
//! than about a cell of stock may therefore show as a link; a link never shows as a cut.

use super::gcode::{Motion, ProgramMove};
use super::zmap::ZMap;
use crate::geom::Aabb;
use serde::Serialize;

/// What a move does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MoveKind {
    /// A feed move at one height that meets stock.
    Cut,
    /// A feed move through stock already cut, or through the air.
    Link,
    /// A feed move down: a plunge, a ramp or a helix.
    Entry,
    /// A rapid that does not rise.
    Rapid,
    /// A rapid upwards.
    Retract,
}

impl MoveKind {
    /// All kinds, in the order of their codes.
    pub const ALL: [MoveKind; 5] = [
        MoveKind::Cut,
        MoveKind::Link,
        MoveKind::Entry,
        MoveKind::Rapid,
        MoveKind::Retract,
    ];
}

/// Cells across the program's extent, at most.
const MAX_CELLS_ACROSS: f64 = 2048.0;

/// The kind of every move of `moves`, for a tool of radius `r` (see the module's
/// documentation).
///
/// ```
/// use pocketeer::simulate::{classify::{classify, MoveKind}, read_program};
/// let p = read_program("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 F1000\nG1 X0\nG0 Z5\nG0 X50\n").unwrap();
/// let kinds = classify(&p.moves, 3.0);
/// use MoveKind::*;
/// assert_eq!(kinds, vec![Entry, Cut, Link, Retract, Rapid]);
/// ```
pub fn classify(moves: &[ProgramMove], r: f64) -> Vec<MoveKind> {
    classify_with_tools(moves, &[(0, r)])
}

/// [`classify`] for a program of several tools: `radii` gives, for the first move of each
/// tool, its radius (sorted by move; the first tool's radius before the first entry).
pub fn classify_with_tools(moves: &[ProgramMove], radii: &[(usize, f64)]) -> Vec<MoveKind> {
    let smallest = radii.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
    let largest = radii.iter().map(|t| t.1).fold(0.0, f64::max);
    let r_smallest = if smallest.is_finite() { smallest } else { 1.0 };
    let mut extent = Aabb::EMPTY;
    for m in moves {
        extent = extent.union(&m.footprint().bbox());
    }
    let extent = extent.inflated(largest.max(0.0));
    let across = if extent.is_empty() {
        0.0
    } else {
        extent.width().max(extent.height())
    };
    let cell = (r_smallest / 12.0).max(across / MAX_CELLS_ACROSS).max(1e-3);
    let mut tool = 0;
    let mut r = radii.first().map_or(r_smallest, |t| t.1);
    let mut map = ZMap::new(extent, cell);
    let mut kinds = vec![MoveKind::Link; moves.len()];
    // The moves at one height since the last test point (each test judges the way to it),
    // and the distance travelled since that point.
    let mut pending: Vec<usize> = Vec::new();
    let mut since = f64::INFINITY;
    for (k, m) in moves.iter().enumerate() {
        while tool + 1 < radii.len() && radii[tool + 1].0 <= k {
            finish_stretch(&mut map, moves, &mut pending, &mut kinds, r, cell);
            since = f64::INFINITY;
            tool += 1;
            r = radii[tool].1;
        }
        let rise = m.to.z - m.from.z;
        let level = m.motion != Motion::Rapid && rise.abs() <= 1e-9 && m.from.z < 0.0;
        if !level {
            finish_stretch(&mut map, moves, &mut pending, &mut kinds, r, cell);
            since = f64::INFINITY;
            kinds[k] = match m.motion {
                Motion::Rapid if rise > 1e-9 => MoveKind::Retract,
                Motion::Rapid => MoveKind::Rapid,
                _ if rise < -1e-9 => {
                    stamp_along(&mut map, m, r);
                    MoveKind::Entry
                }
                _ => MoveKind::Link,
            };
            continue;
        }
        let len = m.footprint().length();
        // Test points a cell apart along the stretch at this height, from its start.
        if !since.is_finite() {
            map.stamp(m.from.xy(), r, m.from.z);
            since = 0.0;
        }
        let mut next = cell - since;
        let mut tested = false;
        let mut cut = false;
        while next <= len {
            let p = m.point_at(if len > 0.0 { next / len } else { 0.0 });
            let meets = map.meets_stock(p.xy(), r - 0.5 * cell, p.z);
            map.stamp(p.xy(), r, p.z);
            if !tested {
                judge(&mut pending, &mut kinds, meets);
            }
            tested = true;
            cut |= meets;
            next += cell;
        }
        if tested {
            kinds[k] = if cut { MoveKind::Cut } else { MoveKind::Link };
            since = len - (next - cell);
        } else {
            pending.push(k);
            since += len;
        }
    }
    finish_stretch(&mut map, moves, &mut pending, &mut kinds, r, cell);
    kinds
}

/// Marks the `pending` moves as cuts or links.
fn judge(pending: &mut Vec<usize>, kinds: &mut [MoveKind], meets: bool) {
    for &i in pending.iter() {
        kinds[i] = if meets { MoveKind::Cut } else { MoveKind::Link };
    }
    pending.clear();
}

/// Ends a stretch at one height: the moves since its last test point are judged by a test at
/// the stretch's end.
fn finish_stretch(
    map: &mut ZMap,
    moves: &[ProgramMove],
    pending: &mut Vec<usize>,
    kinds: &mut [MoveKind],
    r: f64,
    cell: f64,
) {
    let Some(&last) = pending.last() else { return };
    let p = moves[last].to;
    let meets = map.meets_stock(p.xy(), r - 0.5 * cell, p.z);
    map.stamp(p.xy(), r, p.z);
    judge(pending, kinds, meets);
}

/// Stamps the tool's disc along an entry, a cell apart.
fn stamp_along(map: &mut ZMap, m: &ProgramMove, r: f64) {
    let n = ((m.footprint().length() / map.cell()).ceil() as usize).clamp(1, 1 << 20);
    for j in 0..=n {
        let p = m.point_at(j as f64 / n as f64);
        map.stamp(p.xy(), r, p.z);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::read_program;
    use MoveKind::*;

    fn kinds(text: &str) -> Vec<MoveKind> {
        classify(&read_program(text).unwrap().moves, 3.0)
    }

    #[test]
    fn a_slot_is_a_cut_and_going_back_along_it_a_link() {
        let k = kinds("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X30 F1000\nG1 X0\nG1 X-10\n");
        assert_eq!(k[1..], [Cut, Link, Cut]);
    }

    #[test]
    fn a_side_cut_wider_than_a_cell_is_a_cut() {
        // A second pass 0.5 mm beside the first: a sixth of the radius.
        let k = kinds("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X30 F1000\nG1 Y0.5\nG1 X0\n");
        assert_eq!(k[3], Cut);
        // Beside it by a hundredth of a millimetre: through what is cut.
        let k = kinds("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X30 F1000\nG1 Y0.01\nG1 X0\n");
        assert_eq!(k[3], Link);
    }

    #[test]
    fn a_deeper_pass_cuts_again_where_the_first_cut() {
        let k = kinds("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X30 F1000\nG1 Z-2 F300\nG1 X0 F1000\n");
        assert_eq!(k[1..], [Cut, Entry, Cut]);
    }

    #[test]
    fn many_short_moves_along_a_cleared_path_are_links() {
        let mut p = String::from("G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X30 F1000\n");
        for k in 0..3000 {
            p.push_str(&format!("G1 X{:.3}\n", 30.0 - 0.01 * (k + 1) as f64));
        }
        let k = kinds(&p);
        let cuts: Vec<usize> = (2..k.len()).filter(|&i| k[i] != Link).collect();
        assert!(cuts.is_empty(), "{cuts:?}");
        // And the same short moves into new stock are cuts.
        let mut p = String::from("G0 X0 Y0 Z5\nG1 Z-1 F300\n");
        for k in 0..3000 {
            p.push_str(&format!("G1 X{:.3} F1000\n", 0.01 * (k + 1) as f64));
        }
        let k = kinds(&p);
        assert!(k[1..].iter().all(|&k| k == Cut), "{:?}", &k[1..10]);
    }

    #[test]
    fn a_helix_clears_its_disc() {
        // Down a helix of radius 1 round (10, 0), a circle at the bottom (which cuts the floor
        // the helix left sloping), then across its centre: inside the swept disc of radius 4,
        // a link; beyond it, a cut.
        let k = kinds("G0 X11 Y0 Z5\nG3 X11 Y0 Z-1 I-1 J0 F300\nG3 X11 Y0 I-1 J0\nG1 X9 F1000\nG1 X20\n");
        assert_eq!(k, [Entry, Cut, Link, Cut]);
    }
}
