//! The order the parts of the clearing tree are cut in: each after the parts inside it that
//! it waits for, the ready parts of every branch one pool, the next the nearest that needs no
//! entry, else the first of a short tour over those to enter (see [`Linker::cut`]); and which
//! leaves a part cuts on its way round its paths or after them instead of waiting for them.

use super::{loop_path, tour, walk, Direction, Linker, Reach};
use crate::geom::Point;

/// How many of the nearest branches not cut yet are tried for a slot from where the tool is.
const SLOT_CANDIDATES: usize = 4;

/// Most parts to enter that the choice of the next is made by a tour over (see
/// [`Linker::to_enter`]); beyond it, the nearest. The tour is made again at every entry, a
/// few times the square of their number in steps.
const MAX_TOURED_ENTRIES: usize = 64;

/// The least distance between the levels of a plain leaf of nested loops (see
/// [`Linker::chain`]), in tool radii: 0.8, a stepover of 40 % of the diameter. Measured on the
/// linking bench, such leaves cut from their surroundings at any stepover raised the 30 %
/// rectangle's p95 engagement from 144° to 180° (its share above 150° 4.6 -> 9.0 %) for
/// 53 s; at 40 % and more the p95 was 180° before on every drawing.
const CHAIN_MIN_STEP_RADII: f64 = 0.8;

impl<'a> Linker<'a> {
    /// Cuts the part `n` and everything inside it, each part after the parts inside it that
    /// it waits for (see [`Linker::visit`]). A part whose children are all cut is ready,
    /// wherever it is in the tree, and the ready parts of every branch are one pool: of them,
    /// the nearest that needs no entry goes next (one with a child cut, reached at depth, or
    /// of the nearest few, one a slot reaches from where the tool is); when none does, small
    /// leaves whose parent has a child cut wait for it (they are cut from the stock it cleared,
    /// without entries of their own); else the nearest ready part is entered, a small leaf
    /// only when nothing else is ready. A branch is not finished before the tool goes on to a
    /// nearer one: on the 30 % rectangle, finishing each first sent the tool from one side to
    /// the other and back three times, 80 to 150 mm each.
    pub(super) fn cut(&mut self, n: usize) {
        self.cut_early.clear();
        self.enclosed.clear();
        let plan = self.plan();
        // Every part to cut, by part: what it waits for and what it cuts after and on its way;
        // and the part waiting for it.
        let mut visits: Vec<Option<Visit>> = Vec::new();
        visits.resize_with(plan.parts.len(), || None);
        let mut waiting_for = vec![usize::MAX; plan.parts.len()];
        let (mut ready, mut stack) = (Vec::new(), vec![n]);
        while let Some(m) = stack.pop() {
            let visit = self.visit(m);
            for &c in &visit.before {
                waiting_for[c] = m;
                stack.push(c);
            }
            if visit.before.is_empty() {
                ready.push(m);
            }
            visits[m] = Some(visit);
        }
        loop {
            let mut pick = self.without_entry(&ready, &visits);
            if pick.is_none() && defer_small_leaves(self, &mut visits, &mut ready) {
                pick = self.without_entry(&ready, &visits);
            }
            let Some(k) = pick.or_else(|| self.to_enter(&ready, &visits)) else {
                break;
            };
            let m = ready.swap_remove(k);
            let Some(Visit {
                part,
                after,
                along,
                cut_any,
                ..
            }) = visits[m].take()
            else {
                unreachable!("a ready part has its visit")
            };
            let children = &plan.parts[part].children;
            let cut: Vec<usize> = (children.iter().copied())
                .filter(|c| !after.contains(c) && !along.contains(c))
                .collect();
            let reach = Reach {
                distance: plan.parts[part].distance,
                cut: &cut,
            };
            self.cut_part_timed(part, !cut_any, reach, &along, after);
            if let Some(parent) = visits.get_mut(waiting_for[m]).and_then(Option::as_mut) {
                parent.before.retain(|&c| c != m);
                parent.cut_any = true;
                if parent.before.is_empty() {
                    ready.push(parent.part);
                }
            }
        }
    }

    /// Which of the `ready` parts to cut next without a new entry: the nearest (to its box)
    /// of those with a child cut, reached at depth, and those of the nearest few a slot reaches
    /// from where the tool is; none when there is no such part.
    fn without_entry(&self, ready: &[usize], visits: &[Option<Visit>]) -> Option<usize> {
        let here = self.here();
        let to_box = |m: usize| self.boxes[m].distance_sq(here).sqrt();
        let parents = (0..ready.len()).filter(|&k| visits[ready[k]].as_ref().is_some_and(|v| v.cut_any));
        let fresh: Vec<usize> = (0..ready.len())
            .filter(|&k| visits[ready[k]].as_ref().is_some_and(|v| !v.cut_any))
            .map(|k| ready[k])
            .collect();
        let slotted = self
            .next_child(&fresh)
            .and_then(|f| ready.iter().position(|&m| m == fresh[f]));
        parents
            .chain(slotted)
            .min_by(|&a, &b| to_box(ready[a]).total_cmp(&to_box(ready[b])).then(a.cmp(&b)))
    }

    /// Which of the `ready` parts to enter: the nearest (to its box), but for small leaves
    /// whose parent waits for a part that is not one (once that is cut, they wait for their
    /// parent instead of being entered), which go only when nothing else is ready; none when
    /// none is ready.
    fn to_enter(&self, ready: &[usize], visits: &[Option<Visit>]) -> Option<usize> {
        let here = self.here();
        let may_wait = |m: usize| {
            self.is_small_leaf(m)
                && (self.plan().parts[m].parent)
                    .and_then(|p| visits[p].as_ref())
                    .is_some_and(|v| v.before.iter().any(|&c| !self.is_small_leaf(c)))
        };
        let waits: Vec<bool> = ready.iter().map(|&m| may_wait(m)).collect();
        let all_wait = waits.iter().all(|&w| w);
        let candidates: Vec<usize> = (0..ready.len()).filter(|&k| all_wait || !waits[k]).collect();
        if candidates.len() > MAX_TOURED_ENTRIES {
            let to_box = |k: usize| self.boxes[ready[k]].distance_sq(here);
            return candidates
                .into_iter()
                .min_by(|&x, &y| to_box(x).total_cmp(&to_box(y)).then(x.cmp(&y)));
        }
        // The first of a short tour over them, not merely the nearest: the nearest leaves
        // the far ones for a long way back at the end.
        let places: Vec<Point> = (candidates.iter())
            .map(|&k| {
                let b = self.boxes[ready[k]];
                b.min.midpoint(b.max)
            })
            .collect();
        tour(&places, here).first().map(|&i| candidates[i])
    }

    /// The visit of part `n`: its children to cut before it, less the leaves it cuts on its
    /// way (see [`Linker::is_plain_leaf`]) when it has several children (a part with one
    /// child gains nothing: that child is reached without a link either way).
    fn visit(&self, n: usize) -> Visit {
        let (plan, part) = (self.plan(), &self.plan().parts[n]);
        let children = &part.children;
        // A finishing loop has leads, not excursions.
        let leads = part.level == 0 && plan.allowance > 0.0;
        let (along, before) = if children.len() > 1 && !leads {
            children.iter().partition(|&&c| self.is_plain_leaf(c))
        } else {
            (Vec::new(), children.clone())
        };
        Visit {
            part: n,
            before,
            after: Vec::new(),
            along,
            cut_any: false,
        }
    }

    /// True when the part `n` is a leaf its loop alone clears (nothing inside it, no island,
    /// no clean-up path), or one of nested loops (below): such a leaf is cut after the loops
    /// of its parent around it, from the last of them (see [`Linker::cut_part`]), instead of
    /// before them, reached by a slot or an entry of its own. Its loop then cuts what its parent's loops left of it, where
    /// before them it cut a slot in full stock; the price is that the parent's paths beside
    /// it cut the width the leaf's loop would have cleared for them, full width. Measured on
    /// the linking bench: the same p95 engagement on every drawing, a larger share of the
    /// cutting above 150° on some (the 300-hole plate's 16.8 % -> 23.4 %, still below
    /// FreeCAD's 25.9 %), and the plate 205 s faster (its slots between the diamonds between
    /// four holes were 4 m).
    ///
    /// A part whose only child is such a leaf, or such a part, and so on inwards, is cut the
    /// same way, its loops one after the other from the outermost (see [`Linker::chain`]);
    /// one with clean-up paths right after its parent (see [`Linker::cut_small_leaves`]).
    fn is_plain_leaf(&self, n: usize) -> bool {
        self.plan().parts[n].parent.is_some() && self.chain(n).is_some()
    }

    /// The part `n` and the parts nested in it, outermost first, when none has an island or
    /// spots and all but the last exactly one child (the last none): what its loops, cut from the
    /// outermost inwards, and its clean-up paths clear. Of more than one loop only when they
    /// are at least [`CHAIN_MIN_STEP_RADII`] tool radii apart: the paths of the parent beside
    /// such a leaf, cut before it, cut full width what its loops would have cleared, and a
    /// small stepover is chosen for light cuts.
    pub(super) fn chain(&self, n: usize) -> Option<Vec<usize>> {
        let plan = self.plan();
        let parts = &plan.parts;
        let mut chain = vec![n];
        loop {
            let part = &parts[chain[chain.len() - 1]];
            // A part with spots had leaves of its own, two or more (see `clear::spots`): it is
            // cut as it was with them, before its parent, the first loop of its branch.
            if !part.holes.is_empty() || !part.spots.is_empty() {
                return None;
            }
            match part.children[..] {
                [] => return Some(chain),
                [c] if parts[c].distance - part.distance + self.tol.eps
                    >= CHAIN_MIN_STEP_RADII * plan.tool_radius =>
                {
                    chain.push(c)
                }
                _ => return None,
            }
        }
    }

    /// Which of `children` (not cut yet) to cut next without an entry: of the nearest few,
    /// the nearest a slot reaches from where the tool is; none when no slot reaches them.
    fn next_child(&self, children: &[usize]) -> Option<usize> {
        if !self.down {
            return None;
        }
        let here = self.here();
        let mut by_distance: Vec<(f64, usize)> = (children.iter().enumerate())
            .map(|(k, &c)| {
                let b = self.boxes[c];
                (b.min.midpoint(b.max).distance(here), k)
            })
            .collect();
        // Only the nearest few are tried: those picked out, then put in order (a plate's part
        // has a child round every hole, and this is asked once for each).
        let order = |a: &(f64, usize), b: &(f64, usize)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
        if by_distance.len() > SLOT_CANDIDATES {
            by_distance.select_nth_unstable_by(SLOT_CANDIDATES - 1, order);
            by_distance.truncate(SLOT_CANDIDATES);
        }
        by_distance.sort_unstable_by(order);
        (by_distance.iter())
            .find(|&&(_, k)| self.slot_to(children[k]).is_some())
            .map(|&(_, k)| k)
    }

    /// The slot that would reach the part `n`, not cut yet, from where the tool is (see
    /// [`Linker::slot_link`]); none when the tool is not down.
    fn slot_to(&self, n: usize) -> Option<Vec<Point>> {
        if !self.down {
            return None;
        }
        let part = &self.plan().parts[n];
        let reverse = self.params.direction == Direction::Conventional;
        let walk = walk::walk_from(
            &loop_path(&part.outer.segments),
            self.here(),
            reverse,
            self.tol.eps,
        );
        self.slot_link(part, walk.first()?.start())
    }

    /// True when the part `n` is a small leaf: nothing inside it, no island, and its loop
    /// within a square of the tool's diameter, so that every point inside the loop is within
    /// the tool radius of it: the loop alone clears what its parent leaves there.
    fn is_small_leaf(&self, n: usize) -> bool {
        let plan = self.plan();
        let part = &plan.parts[n];
        let b = self.boxes[n];
        let d = 2.0 * plan.tool_radius;
        part.parent.is_some()
            && part.children.is_empty()
            && part.holes.is_empty()
            && b.max.x - b.min.x <= d
            && b.max.y - b.min.y <= d
    }
}

/// A part being cut: the children still to cut before it, the small leaves to cut after it,
/// the leaves to cut on the way round its loops, and whether any child is cut (if none, its
/// first path is an entry).
struct Visit {
    part: usize,
    before: Vec<usize>,
    after: Vec<usize>,
    along: Vec<usize>,
    cut_any: bool,
}

/// Where no ready part is reached without an entry: the parts with a child cut that wait
/// only for small leaves stop waiting for them (the leaves are cut after them, from the stock
/// they clear, see [`Linker::cut_small_leaves`]) and are ready. True when any part is.
fn defer_small_leaves(linker: &Linker, visits: &mut [Option<Visit>], ready: &mut Vec<usize>) -> bool {
    let mut any = false;
    for (m, visit) in visits.iter_mut().enumerate() {
        let Some(v) = visit.as_mut() else { continue };
        if v.cut_any && !v.before.is_empty() && v.before.iter().all(|&c| linker.is_small_leaf(c)) {
            ready.retain(|c| !v.before.contains(c));
            let mut leaves = std::mem::take(&mut v.before);
            v.after.append(&mut leaves);
            ready.push(m);
            any = true;
        }
    }
    any
}
