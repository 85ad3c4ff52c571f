//! The loops round one island at several levels, cut one after the other towards it (a
//! ladder), and the way out of them to the next path: along the innermost loop, then straight
//! on as soon as the way is clear (see [`Linker::cut_enclosed_holes`], [`Linker::leave_ladder`]).

use super::{clearance_slack, loop_path, route, walk, Direction, Linker, Reach};
use crate::clear::Path;
use crate::geom::nearest_on;
use crate::geom::{Aabb, BoxIndex, Point, Segment};
use crate::toolpath::{Feed, Point3};

impl<'a> Linker<'a> {
    /// The loop round islands of the parent of part `n` that `n`'s loop round islands `j`
    /// encloses, when it encloses one only: that loop lies between the islands and `n`'s, and
    /// is cut right after it (see [`Linker::cut_enclosed_holes`]). None when the parent has
    /// clean-up paths (they are cut on the way round its loops) or a finishing loop with
    /// leads, and for a loop round many islands (the merged loop round a grid of them), whose
    /// islands' loops the parent links nearest first.
    pub(super) fn enclosed_hole(&mut self, n: usize, j: usize) -> Option<usize> {
        let plan = self.plan();
        let found = self.enclosed.entry(n).or_insert_with(|| {
            let part = &plan.parts[n];
            let mut found = vec![None; part.holes.len()];
            let Some(parent) = part.parent.map(|p| &plan.parts[p]) else {
                return found;
            };
            if parent.holes.is_empty() || !parent.cleanups.is_empty() || plan.allowance > 0.0 {
                return found;
            }
            let boxes: Vec<Aabb> = parent.holes.iter().map(|h| h.bbox()).collect();
            let index = BoxIndex::new(&boxes);
            for (i, h) in part.holes.iter().enumerate() {
                let b = h.bbox();
                let inside: Vec<usize> = index
                    .intersecting(&b)
                    .filter(|&k| {
                        b.contains_box(&boxes[k])
                            && (parent.holes[k].segments.first())
                                .is_some_and(|s| h.winding_number(s.start()) != 0)
                    })
                    .collect();
                if let [k] = inside[..] {
                    found[i] = Some(k);
                }
            }
            found
        });
        found.get(j).copied().flatten()
    }

    /// After the loop round islands `j` of part `n`: the loops round the same islands in the
    /// parts around `n`, each enclosing the next, cut one after the other towards the islands
    /// from where the tool is, instead of each with its own part, reached by a link of its
    /// own (on the 300-hole plate the loops round the holes at two levels were two chains of
    /// 300 links). The tool is left on the innermost of them, and the way back out is chosen
    /// with the next path (see [`Linker::leave_ladder`]). Cutting them early changes nothing
    /// they cut: a loop's tool disc reaches no farther from its islands than the loop it
    /// follows plus the radius, where everything the other loops of that loop's part could
    /// clear is farther out.
    pub(super) fn cut_enclosed_holes(&mut self, n: usize, j: usize) -> Option<Ladder> {
        let (back_to, outer) = (self.here(), self.last.clone());
        let (mut at, mut hole, mut nearest_walls) = (n, j, None);
        while let (Some(parent), Some(h)) = (self.plan().parts[at].parent, self.enclosed_hole(at, hole)) {
            if !self.cut_early.insert((parent, h)) {
                break;
            }
            let part = &self.plan().parts[parent];
            let reach = Reach {
                distance: part.distance,
                cut: &[],
            };
            self.cut_path(parent, &loop_path(&part.holes[h].segments), false, reach);
            (at, hole, nearest_walls) = (parent, h, Some(part.distance));
        }
        Some(Ladder {
            back_to,
            outer,
            inner_distance: nearest_walls?,
        })
    }

    /// Back out from the innermost of the loops round one island (see
    /// [`Linker::cut_enclosed_holes`]) towards `next`, the path cut next (at `distance` from
    /// the walls, as the outermost loop): along the innermost loop to its point nearest where
    /// the way along the outermost would leave it for `next`, then straight out to that point,
    /// when that is shorter than straight out to the outermost loop's end and along it (the
    /// innermost is the shortest of them: on the 300-hole plate, 7 mm round the holes where
    /// the outermost is 9.4 mm). Else, and when `next` is none or is reached straight from the
    /// outermost loop's end, straight back to that end: the links onward are then the same as
    /// without the loops cut on the way.
    pub(super) fn leave_ladder(&mut self, ladder: Ladder, next: Option<&Path>, distance: f64) {
        if !self.down {
            return;
        }
        let Ladder {
            back_to,
            outer,
            inner_distance,
        } = ladder;
        let here = self.here();
        let way_out = next.and_then(|next| self.way_out(&outer, back_to, next, distance, inner_distance));
        match way_out {
            Some(WayOut {
                moves,
                to,
                onto_outer,
            }) => {
                walk::follow(&mut self.path, &moves, self.z);
                self.path.line(Point3::at(to, self.z), Feed::Cut);
                self.last = if onto_outer {
                    // The outermost loop walked from there: the tool is at its end again.
                    (
                        walk::walk_from(&loop_path(&outer.0), to, false, self.tol.eps),
                        true,
                    )
                } else {
                    // On the next path: no way along a path is needed to reach it.
                    (Vec::new(), false)
                };
            }
            None if self.stays_inside(here, back_to, inner_distance) => {
                self.path.line(Point3::at(back_to, self.z), Feed::Cut);
                self.stepped_out = Some(self.path.moves.len());
                self.last = outer;
            }
            None => {}
        }
    }

    /// The way out of [`Linker::leave_ladder`] along the innermost loop (the walk just cut,
    /// the tool at its end): its moves and the point of the outermost loop (walked as `outer`,
    /// to `back_to`) it goes out to, when shorter than going out to `back_to` and along the
    /// outermost, and faster than going over the top.
    fn way_out(
        &self,
        outer: &(Vec<Segment>, bool),
        back_to: Point,
        next: &Path,
        distance: f64,
        inner_distance: f64,
    ) -> Option<WayOut> {
        let (here, eps) = (self.here(), self.tol.eps);
        let reverse = self.params.direction == Direction::Conventional;
        let q = walk::walk_from(next, back_to, reverse, eps)[0].start();
        if !outer.1 || self.stays_inside(back_to, q, distance) {
            return None;
        }
        let (along_outer, b) = route::along_last(&outer.0, true, next, eps, |a, b| {
            self.stays_inside(a, b, distance)
        })?;
        let out = along_outer.last().map_or(back_to, Segment::end);
        let inner = &self.last.0;
        if !self.last.1 || inner.is_empty() {
            return None;
        }
        let (k, at, _) = nearest_on(inner, out);
        let along_inner = route::back_along(inner, true, k, at, eps);
        let a = along_inner.last().map_or(here, Segment::end);
        let inner_length = walk::length(&along_inner) + a.distance(out);
        let outer_length = here.distance(back_to) + walk::length(&along_outer);
        let t = &self.params.time;
        let faster_than_a_hop = t.feed_seconds(inner_length + out.distance(b), t.feed)
            < self.hop_seconds(back_to.distance(q), self.z);
        if !(inner_length < outer_length && faster_than_a_hop && self.stays_inside(a, out, inner_distance)) {
            return None;
        }
        let straight_on = self
            .straight_out(&along_inner, inner, &outer.0, b, (distance, inner_distance))
            .filter(|moves| {
                let p = moves.last().map_or(here, Segment::end);
                walk::length(moves) + p.distance(b) < inner_length + out.distance(b)
            });
        Some(match straight_on {
            Some(moves) => WayOut {
                moves,
                to: b,
                onto_outer: false,
            },
            None => WayOut {
                moves: along_inner,
                to: out,
                onto_outer: true,
            },
        })
    }

    /// The way out of the loops round one island (see [`Linker::way_out`]) straight to `b`,
    /// the next path's point, from the earliest point of `along_inner` (the way along the
    /// innermost loop `inner_loop`, at `inner_distance` from the walls) it can go from: the moves along it
    /// to there. Only where the outermost of the loops, `outer`, is convex (round a convex
    /// island): the move then crosses it once, everything between it and the innermost is
    /// cut, and beyond it the move keeps `distance` from the walls, as every link of the
    /// part does. On the 300-hole plate this cuts the corner the way out along the innermost
    /// loop and straight out to the outermost used to turn.
    fn straight_out(
        &self,
        along_inner: &[Segment],
        inner_loop: &[Segment],
        outer: &[Segment],
        b: Point,
        (distance, inner_distance): (f64, f64),
    ) -> Option<Vec<Segment>> {
        let eps = self.tol.eps;
        if along_inner.is_empty() || !crate::geom::is_convex(outer, 1e-9) {
            return None;
        }
        // The earliest point is where the move grazes the island: a margin keeps it off.
        let inner = inner_distance + clearance_slack(inner_distance, self.tol);
        // Before the point where the move to `b` is tangent to the innermost loop (convex,
        // round a convex island) it would cut into the island: ruled out without measuring.
        let middle = crate::geom::bbox_of(inner_loop);
        let middle = middle.min.midpoint(middle.max);
        let faces_b = |p: Point, t: crate::geom::Vector| {
            let n = t.perp();
            let outward = if (middle - p).dot(n) > 0.0 { -n } else { n };
            (b - p).dot(outward) >= 0.0
        };
        route::leave_early_hinted(along_inner, 0.01, faces_b, |p| {
            let across = Segment::Line(crate::geom::Line::new(p, b));
            // Where the move crosses the outermost loop, nearest `b` (once only, as it is convex).
            let mut crossing: Option<(f64, Point)> = None;
            for o in outer {
                for i in crate::geom::intersect(&across, o, eps).iter() {
                    if let crate::geom::Intersection::Point { point, ta, .. } = i {
                        if crossing.is_none_or(|(t, _)| ta > t) {
                            crossing = Some((ta, point));
                        }
                    }
                }
            }
            crossing.is_some_and(|(_, c)| self.stays_inside(p, c, inner) && self.stays_inside(c, b, distance))
        })
    }
}

/// Where the tool is left by [`Linker::cut_enclosed_holes`]: on the innermost of the loops round
/// one island, at the end of its walk (the walk just cut).
pub(super) struct Ladder {
    /// The end of the walk of the outermost of those loops, from where the way onward is
    /// measured.
    pub(super) back_to: Point,
    /// That walk, and whether it is closed.
    outer: (Vec<Segment>, bool),
    /// The innermost loop's distance from the walls.
    inner_distance: f64,
}

/// The way out of the loops round one island (see [`Linker::leave_ladder`]).
struct WayOut {
    /// The moves along the innermost loop.
    moves: Vec<Segment>,
    /// Where the tool then goes straight: a point of the outermost loop, or of the next path.
    to: Point,
    /// Whether `to` is on the outermost loop.
    onto_outer: bool,
}
