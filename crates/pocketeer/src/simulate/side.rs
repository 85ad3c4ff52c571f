//! Which side of the tool the material is on where the tool follows a wall: climb or
//! conventional milling, measured on the program itself.
//!
//! With the spindle turning clockwise seen from above (M3), climb milling keeps the material on
//! the tool's right as it moves (the side G41 leaves it on); conventional milling keeps it on
//! the left. Along a wall the material is the wall: a feed move at the final depth whose tool
//! disc touches a wall follows it, and the nearest wall point tells the side.

use super::gcode::{Motion, ProgramMove};
use crate::geom::{Point, Segment, SegmentIndex};
use serde::Serialize;

/// How far the tool centre may be from the radius off the wall and still follow it, mm.
pub const WALL_SLACK: f64 = 0.005;

/// Wall-following length by the side the material is on.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Sides {
    /// Length along walls with the material on the tool's right (climb with M3), mm.
    pub right: f64,
    /// Length along walls with the material on the tool's left (conventional with M3), mm.
    pub left: f64,
}

impl Sides {
    /// The share of the wall-following length milled climb (material on the right), in 0..=1;
    /// `None` when the tool follows no wall.
    ///
    /// ```
    /// use pocketeer::simulate::Sides;
    /// assert_eq!(Sides { right: 3.0, left: 1.0 }.climb_share(), Some(0.75));
    /// assert_eq!(Sides::default().climb_share(), None);
    /// ```
    pub fn climb_share(&self) -> Option<f64> {
        let total = self.right + self.left;
        (total > 0.0).then(|| self.right / total)
    }
}

/// Measures the sides along the feed moves of `moves` that lie at `depth` or below (Z ≤
/// `depth`, both ends), for a tool of radius `r`; `walls_at(p)` gives the walls and islands
/// of the pocket the tool centre `p` is in (the walls of other pockets, beyond an island, are
/// not the material being milled). Each move is sampled every tenth of the radius; a sample
/// counts when the tool centre is within [`WALL_SLACK`] of `r` from the nearest wall.
pub fn material_sides<'w>(
    moves: &[ProgramMove],
    walls_at: &dyn Fn(Point) -> Option<&'w SegmentIndex>,
    depth: f64,
    r: f64,
) -> Sides {
    let mut sides = Sides::default();
    for m in moves {
        if m.motion == Motion::Rapid || m.from.z > depth + 1e-4 || m.to.z > depth + 1e-4 {
            continue;
        }
        add_move(&mut sides, &m.footprint(), walls_at, r);
    }
    sides
}

fn add_move<'w>(
    sides: &mut Sides,
    footprint: &Segment,
    walls_at: &dyn Fn(Point) -> Option<&'w SegmentIndex>,
    r: f64,
) {
    let len = footprint.length();
    if len <= 0.0 {
        return;
    }
    let n = ((len / (0.1 * r)).ceil() as usize).clamp(1, 10_000);
    let piece = len / n as f64;
    for k in 0..n {
        let t = (k as f64 + 0.5) / n as f64;
        let c = footprint.point_at(t);
        let Some((w, d)) = walls_at(c).and_then(|walls| walls.nearest(c)) else {
            continue;
        };
        if (d - r).abs() > WALL_SLACK {
            continue;
        }
        let towards_wall = w - c;
        if footprint.tangent_at(t).cross(towards_wall) < 0.0 {
            sides.right += piece;
        } else {
            sides.left += piece;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Contour, Point};
    use crate::toolpath::Point3;

    fn feed(from: (f64, f64), to: (f64, f64), z: f64) -> ProgramMove {
        ProgramMove {
            line: 1,
            motion: Motion::Line,
            from: Point3::new(from.0, from.1, z),
            to: Point3::new(to.0, to.1, z),
            feed: Some(1000.0),
        }
    }

    fn square_walls() -> SegmentIndex {
        let p = Point::new;
        SegmentIndex::new(
            &Contour::polygon(&[p(0.0, 0.0), p(20.0, 0.0), p(20.0, 20.0), p(0.0, 20.0)]).segments,
        )
    }

    #[test]
    fn along_the_bottom_wall_going_right_the_material_is_on_the_right() {
        let walls = square_walls();
        // 3 mm above the bottom wall (y = 0), tool radius 3: following it.
        let east = [feed((5.0, 3.0), (15.0, 3.0), -2.0)];
        let s = material_sides(&east, &|_| Some(&walls), -2.0, 3.0);
        assert!((s.right - 10.0).abs() < 1e-9 && s.left == 0.0, "{s:?}");
        let west = [feed((15.0, 3.0), (5.0, 3.0), -2.0)];
        let s = material_sides(&west, &|_| Some(&walls), -2.0, 3.0);
        assert!((s.left - 10.0).abs() < 1e-9 && s.right == 0.0, "{s:?}");
    }

    #[test]
    fn moves_away_from_walls_or_above_the_depth_do_not_count() {
        let walls = square_walls();
        let moves = [
            feed((5.0, 8.0), (15.0, 8.0), -2.0),
            feed((5.0, 3.0), (15.0, 3.0), -1.0),
        ];
        assert_eq!(
            material_sides(&moves, &|_| Some(&walls), -2.0, 3.0),
            Sides::default()
        );
    }

    #[test]
    fn only_the_walls_of_the_pocket_the_tool_is_in_count() {
        let walls = square_walls();
        // Along y = 3 the bottom wall is 3 away; a pocket elsewhere whose walls are not these
        // (the tool is not in this one at x > 10) has nothing to say.
        let moves = [feed((5.0, 3.0), (15.0, 3.0), -2.0)];
        let s = material_sides(&moves, &|p| (p.x < 10.0).then_some(&walls), -2.0, 3.0);
        assert!((s.right - 5.0).abs() < 1e-9 && s.left == 0.0, "{s:?}");
    }

    #[test]
    fn a_move_below_the_depth_counts() {
        let walls = square_walls();
        let s = material_sides(
            &[feed((5.0, 3.0), (15.0, 3.0), -3.0)],
            &|_| Some(&walls),
            -2.0,
            3.0,
        );
        assert!((s.right - 10.0).abs() < 1e-9);
    }
}
