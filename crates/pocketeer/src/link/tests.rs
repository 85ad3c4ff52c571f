//! The linker's unit tests: gouge-free moves, entries, retracts and the milling side.
use super::*;
use crate::clear::{plan_pocket, ClearParams};
use crate::geom::Pocket;
use crate::geom::{distance_from_segment, Arc, Contour};
use crate::toolpath::Move;

fn params(entry: Entry) -> LinkParams {
    LinkParams {
        depth: 2.0,
        step_down: 2.0,
        safe_z: 5.0,
        feed_height: 1.0,
        direction: Direction::Climb,
        entry,
        ramp_angle: 3f64.to_radians(),
        time: crate::machining_time::TimeModel::default(),
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Contour {
    let p = Point::new;
    Contour::polygon(&[p(x0, y0), p(x1, y0), p(x1, y1), p(x0, y1)])
}

/// The plan of `pocket` for a 6 mm tool at `stepover`, and the pocket prepared.
fn planned(pocket: &Pocket, stepover: f64) -> (ClearPlan, PreparedPocket) {
    let clear = ClearParams {
        tool_radius: 3.0,
        stepover,
        allowance: 0.0,
    };
    let plan = plan_pocket(pocket, &clear, &Tolerance::default()).unwrap();
    (plan, PreparedPocket::new(pocket))
}

fn linked(pocket: &Pocket, stepover: f64, entry: Entry) -> (Linked, PreparedPocket) {
    let (l, _, prepared) = linked_plan(pocket, stepover, entry);
    (l, prepared)
}

/// [`linked`] with the plan it linked, its moves checked for gouges.
fn linked_plan(pocket: &Pocket, stepover: f64, entry: Entry) -> (Linked, ClearPlan, PreparedPocket) {
    let (plan, prepared) = planned(pocket, stepover);
    let l = link(&[(&prepared, &plan)], &params(entry), &Tolerance::default()).unwrap();
    assert_no_gouge(&l.toolpath, &prepared);
    (l, plan, prepared)
}

/// A `width` × `height` rectangle with two round islands of radius 4 on its middle line, at
/// `xs`.
fn two_islands(width: f64, height: f64, xs: [f64; 2]) -> Pocket {
    let island =
        |x: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::new(x, 0.5 * height), 4.0))]).reversed();
    Pocket {
        boundary: rect(0.0, 0.0, width, height),
        islands: xs.map(island).to_vec(),
    }
}

/// Every feed move below the stock top keeps the tool centre at least the radius from the
/// walls (lines exactly, arcs by dense samples).
/// The linking bench's 200 x 120 rectangle with two rows of four round islands of radius 8.
fn eight_island_rectangle() -> Pocket {
    let island =
        |x: f64, y: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::new(x, y), 8.0))]).reversed();
    Pocket {
        boundary: rect(0.0, 0.0, 200.0, 120.0),
        islands: [35.0, 78.0, 121.0, 164.0]
            .into_iter()
            .flat_map(|x| [island(x, 35.0), island(x, 85.0)])
            .collect(),
    }
}

fn assert_no_gouge(path: &Toolpath, prepared: &PreparedPocket) {
    let tol = Tolerance::default();
    let mut at = path.start;
    for m in &path.moves {
        let below = at.z.min(m.to().z) < 0.0;
        match *m {
            Move::Line { to, .. } if below => {
                let s = Segment::Line(crate::geom::Line::new(at.xy(), to.xy()));
                assert!(
                    !prepared.segment_nearer_than(&s, 3.0 - 1e-6, &tol),
                    "line to {to:?}"
                );
            }
            Move::Arc { center, sweep, .. } if below => {
                let v = at.xy() - center;
                for k in 0..=64 {
                    let p = center
                        + crate::geom::Vector::from_angle(v.angle() + sweep * k as f64 / 64.0) * v.length();
                    assert!(
                        prepared.distance(p) >= 3.0 - 1e-6 && prepared.contains(p),
                        "arc at {p:?}"
                    );
                }
            }
            // Below the top only straight up, out of the column just cut, or straight down
            // onto a floor already cut (which check verifies on whole programs).
            Move::Rapid { to } => assert!(
                at.z >= 0.0 && to.z >= 0.0 || to.xy() == at.xy(),
                "rapid below the top from {at:?} to {to:?}"
            ),
            _ => {}
        }
        at = m.to();
    }
}

/// Largest descent angle (radians) of any move that goes down below the stock top.
fn steepest(path: &Toolpath) -> f64 {
    let mut at = path.start;
    let mut worst: f64 = 0.0;
    for m in &path.moves {
        let to = m.to();
        if to.z < at.z && to.z < 0.0 && !matches!(m, Move::Rapid { .. }) {
            let run = m.length(at).powi(2) - (at.z - to.z).powi(2);
            let horizontal = run.max(0.0).sqrt();
            // Above the floor of the previous pass the tool moves through air.
            let dz = at.z.min(0.0) - to.z;
            worst = worst.max(dz.atan2(horizontal));
        }
        at = to;
    }
    worst
}

#[test]
fn one_branch_is_cut_without_retracting_between_loops() {
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 40.0, 30.0),
        islands: vec![],
    };
    let (l, prepared) = linked(&pocket, 2.4, Entry::Helix);
    assert!(l.warnings.is_empty());
    // Only the final retract.
    assert_eq!(l.toolpath.stats().retracts, 1);
    assert_no_gouge(&l.toolpath, &prepared);
    assert!(steepest(&l.toolpath) <= 3f64.to_radians() + 1e-9);
    // The helix is an arc descending at the pass start.
    assert!(l
        .toolpath
        .moves
        .iter()
        .any(|m| matches!(m, Move::Arc { to, .. } if to.z < 0.0 && to.z > -2.0)));
}

#[test]
fn branches_around_a_bar_island_are_never_crossed_at_depth() {
    let bar = rect(10.0, 13.0, 50.0, 17.0).reversed();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 60.0, 30.0),
        islands: vec![bar],
    };
    let (l, prepared) = linked(&pocket, 2.0, Entry::Helix);
    // The second branch is reached round the bar's end, at depth or over the top: never
    // through the bar.
    assert_no_gouge(&l.toolpath, &prepared);
}

/// Length of the feed moves at depth `z` that are not the plan's loops: links, helix
/// run-outs and clean-up paths.
fn feed_at_depth_beyond_loops(path: &Toolpath, plan: &ClearPlan, z: f64) -> f64 {
    let mut at = path.start;
    let mut total = 0.0;
    for m in &path.moves {
        if !matches!(m, Move::Rapid { .. }) && at.z == z && m.to().z == z {
            total += m.length(at);
        }
        at = m.to();
    }
    let loops: f64 = (plan.parts.iter())
        .flat_map(|p| p.loops())
        .flat_map(|l| &l.segments)
        .map(Segment::length)
        .sum();
    total - loops
}

#[test]
fn a_ring_round_a_hub_crosses_from_wall_to_hub_once_a_level_at_most() {
    // Levels of a ring are parts of an outer loop and a loop round the hub, each inside the
    // other. The tool leaves a part at one of its loops: the next part's loop beside it goes
    // first, so that the ring is crossed once a level, not there and back (the outer loop
    // always last crossed it twice: 9 levels, 360 mm of links for 178 mm of crossings).
    let circle = |r: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::ORIGIN, r))]);
    let pocket = Pocket {
        boundary: circle(60.0),
        islands: vec![circle(15.0).reversed()],
    };
    let (l, plan, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    // Each level's crossing: from its loop round the hub to its outer loop.
    let crossings: f64 = (plan.parts.iter())
        .filter(|p| !p.holes.is_empty())
        .map(|p| {
            let (outer, hub) = (p.outer.bbox(), p.holes[0].bbox());
            0.5 * ((outer.max.x - outer.min.x) - (hub.max.x - hub.min.x))
        })
        .sum();
    assert!(crossings > 150.0, "{crossings}");
    let links = feed_at_depth_beyond_loops(&l.toolpath, &plan, -2.0);
    // Besides: a stepover from each part to the next, and the way from the helix.
    let slack = 2.4 * plan.parts.len() as f64 + 12.0;
    assert!(
        links <= crossings + slack,
        "{links} mm of links for {crossings} mm of crossings"
    );
}

/// A plate of `nx` x `ny` round holes of radius 4 at a 20 mm pitch, 10 mm in from its edges,
/// and the holes' centres.
fn plate_of_holes(nx: usize, ny: usize) -> (Pocket, Vec<Point>) {
    plate_of_round_islands(nx, ny, 4.0)
}

/// A plate of `nx` x `ny` round islands of radius `r` at a 20 mm pitch, 10 mm from its edges,
/// and their centres.
fn plate_of_round_islands(nx: usize, ny: usize, r: f64) -> (Pocket, Vec<Point>) {
    let hole = |c: Point| Contour::new(vec![Segment::Arc(Arc::circle(c, r))]).reversed();
    let centres: Vec<Point> = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| Point::new(10.0 + 20.0 * i as f64, 10.0 + 20.0 * j as f64)))
        .collect();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 20.0 * nx as f64, 20.0 * ny as f64),
        islands: centres.iter().copied().map(hole).collect(),
    };
    (pocket, centres)
}

#[test]
fn the_loops_round_one_island_at_two_levels_are_cut_one_after_the_other() {
    // A plate of 4 x 3 holes at a 20 mm pitch: at 5.4 mm from the walls the loops round the
    // two inner holes still lie in one part with the others, at 3 mm inside them. Each inner
    // hole's loop at 3 mm is cut right after its loop at 5.4 mm, 2.4 mm away, instead of with
    // the other loops at 3 mm, each reached by a link of its own.
    let (pocket, centres) = plate_of_holes(4, 3);
    let (l, _, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    // The arcs at depth round a hole's centre at 3 and 5.4 mm from its wall, in order.
    let mut rounds: Vec<(usize, bool)> = Vec::new();
    let mut at = l.toolpath.start;
    for m in &l.toolpath.moves {
        if let Move::Arc { to, center, .. } = *m {
            let r = center.distance(at.xy());
            let near = |d: f64| (r - 4.0 - d).abs() < 1e-6;
            if let Some(k) = centres.iter().position(|c| c.distance(center) < 1e-6) {
                if at.z == -2.0 && to.z == -2.0 && (near(3.0) || near(5.4)) {
                    let round = (k, near(5.4));
                    if rounds.last() != Some(&round) {
                        rounds.push(round);
                    }
                }
            }
        }
        at = m.to();
    }
    for inner in [Point::new(30.0, 30.0), Point::new(50.0, 30.0)] {
        let k = centres.iter().position(|&c| c == inner).unwrap();
        let outer_loop = rounds.iter().position(|&r| r == (k, true)).unwrap();
        assert_eq!(
            rounds.get(outer_loop + 1),
            Some(&(k, false)),
            "hole {k}: {rounds:?}"
        );
    }
}

#[test]
fn the_way_on_from_a_hole_is_along_the_innermost_of_its_loops() {
    // A plate of 6 x 5 holes: after the loops round a hole at 5.4 and 3 mm from its wall, the
    // tool goes on along the loop at 3 mm (radius 7) to where it faces the next path and
    // straight out from there, not straight out and then along the loop at 5.4 mm (radius
    // 9.4), a quarter longer (before, seven of the holes had their loop at 9.4 mm followed a
    // quarter or more of a turn again).
    let (pocket, centres) = plate_of_holes(6, 5);
    let (l, _, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    // By hole, the sweep of the arcs at depth round it at each radius.
    let mut swept = vec![(0.0, 0.0); centres.len()];
    let mut at = l.toolpath.start;
    for m in &l.toolpath.moves {
        if let Move::Arc {
            to, center, sweep, ..
        } = *m
        {
            let r = center.distance(at.xy());
            if let Some(k) = centres.iter().position(|c| c.distance(center) < 1e-6) {
                if at.z == -2.0 && to.z == -2.0 {
                    if (r - 7.0).abs() < 1e-6 {
                        swept[k].0 += sweep.abs();
                    } else if (r - 9.4).abs() < 1e-6 {
                        swept[k].1 += sweep.abs();
                    }
                }
            }
        }
        at = m.to();
    }
    let full = std::f64::consts::TAU + 1e-6;
    assert!(
        swept.iter().filter(|s| s.0 > full).count() >= 2,
        "the tool goes on along the loops at radius 7: {swept:?}"
    );
    assert!(
        swept.iter().all(|s| s.1 <= full),
        "never along the loops at radius 9.4: {swept:?}"
    );
}

#[test]
fn the_way_on_from_a_hole_leaves_its_innermost_loop_straight_for_the_next_path() {
    // The same plate: from the loop at radius 7 round a hole the tool goes straight to the
    // next path as soon as that move clears the hole (the moves are checked against the walls
    // by `linked_plan`), not on to the point of the loop nearest the next path and out across
    // the 2.4 mm between the loops, which turns a corner.
    let (pocket, centres) = plate_of_holes(6, 5);
    let (l, plan, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    let mut at = l.toolpath.start;
    let mut at_depth = 0.0;
    for m in &l.toolpath.moves {
        if at.z == -2.0 && m.to().z == -2.0 {
            at_depth += m.length(at);
        }
        at = m.to();
    }
    let paths: f64 = (plan.parts.iter())
        .flat_map(|p| std::iter::once(&p.outer).chain(&p.holes))
        .map(|c| c.segments.iter().map(Segment::length).sum::<f64>())
        .sum();
    // With the spaces between four holes cut from spots (see `clear::spots`), 530.6 mm of
    // moves at depth besides the loops going out to the loop at 9.4 first, 508.1 straight on.
    let links = at_depth - paths;
    assert!(
        links < 519.0,
        "{links} mm of links at depth round {} holes",
        centres.len()
    );
}

#[test]
fn the_space_between_four_holes_is_cut_from_the_last_loop_round_them() {
    // The same plate: at 7.8 mm from the walls what is left between four holes is a small
    // diamond, cleared by the tool standing at its middle (see `clear::spots`). The tool goes
    // there once the loops at 5.4 mm round its four holes are cut, straight out from the
    // last of them and back, instead of first, through full stock; and only as far as where
    // it first sweeps all that is left there, short of the middle.
    let (pocket, centres) = plate_of_holes(4, 3);
    let (l, plan, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    let diamonds: Vec<Point> = (1..4)
        .flat_map(|i| (1..3).map(move |j| Point::new(20.0 * i as f64, 20.0 * j as f64)))
        .collect();
    let spots: usize = plan.parts.iter().map(|p| p.spots.len()).sum();
    assert_eq!(spots, diamonds.len(), "a spot in each space between four holes");
    // By move: where it starts.
    let mut from = l.toolpath.start;
    let mut moves = Vec::new();
    for m in &l.toolpath.moves {
        moves.push((from, *m));
        from = m.to();
    }
    let on_ring = |c: Point, at: Point3| at.z == -2.0 && (c.distance(at.xy()) - 9.4).abs() < 1e-6;
    let arc_round = |k: usize, c: Point| match moves[k] {
        (at, Move::Arc { to, center, .. }) => to.z == -2.0 && center == c && on_ring(c, at),
        _ => false,
    };
    for d in diamonds {
        let four: Vec<Point> = centres.iter().copied().filter(|c| c.distance(d) < 15.0).collect();
        assert_eq!(four.len(), 4);
        let spot = (plan.parts.iter().flat_map(|p| &p.spots))
            .find(|s| s.path.ends().1.distance(d) < 1e-6)
            .unwrap_or_else(|| panic!("a spot at the middle of the diamond at {d:?}"));
        let first = (0..moves.len())
            .find(|&k| moves[k].1.to().z == -2.0 && spot.clears_from(moves[k].1.to().xy()))
            .unwrap_or_else(|| panic!("the tool sweeps what is left of the diamond at {d:?}"));
        let stop = moves[first].1.to().xy();
        // What is left is a star whose four points reach 2.67 mm from the middle, between the
        // holes, to be within 2.85 mm of the tool: the tool may stop 0.25 mm short, no more,
        // and stops within 1/256 of its way in (4.74 mm) of that.
        let short = stop.distance(d);
        assert!(
            (0.25 - 4.74 / 256.0..0.25).contains(&short),
            "the tool stops {short} mm short of the middle of the diamond at {d:?}"
        );
        // Out from a loop round one of the four holes: straight to the spot's path, then along
        // it to the middle, or straight to the middle.
        let (out, host) = [first, first - 1]
            .into_iter()
            .find_map(|k| {
                four.iter()
                    .copied()
                    .find(|&c| on_ring(c, moves[k].0))
                    .map(|c| (k, c))
            })
            .unwrap_or_else(|| panic!("the diamond at {d:?} is reached from a loop round one of its holes"));
        assert!(
            (out..=first).all(|k| matches!(moves[k].1, Move::Line { .. })),
            "straight out to the diamond at {d:?}"
        );
        // The loop it is reached from goes on after it; the other three are done.
        for &c in &four {
            let ring: Vec<usize> = (0..moves.len()).filter(|&k| arc_round(k, c)).collect();
            assert!(
                ring[0] < first,
                "the loop round {c:?} begun before the diamond at {d:?}"
            );
            assert!(
                c == host || ring[ring.len() - 1] < first,
                "the loop round {c:?} done before the diamond at {d:?}"
            );
        }
    }
}

#[test]
fn nested_loops_between_four_islands_are_cut_from_the_loops_round_them() {
    // Islands of radius 5 at a 20 mm pitch: at 2.4 mm stepover, what is left between four of
    // them is a part of two nested loops, a star and a small diamond inside it. They are cut
    // after the loops round the islands, the star from the last of them and the diamond from
    // the star, each reached by a step at depth, instead of first, the diamond reached through
    // full stock by a slot or an entry.
    let (pocket, _) = plate_of_round_islands(4, 3, 5.0);
    let (l, plan, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    let chains: Vec<(usize, usize)> = (plan.parts.iter().enumerate())
        .filter(|(_, p)| p.holes.is_empty() && p.children.len() == 1)
        .map(|(k, p)| (k, p.children[0]))
        .filter(|&(_, c)| plan.parts[c].children.is_empty())
        .collect();
    assert_eq!(
        chains.len(),
        6,
        "a star and its diamond between every four islands"
    );
    let mut from = l.toolpath.start;
    let mut moves = Vec::new();
    for m in &l.toolpath.moves {
        moves.push((from, *m));
        from = m.to();
    }
    // The first move at depth along the loop of part `k`.
    let first_on = |k: usize| {
        let on = |p: Point| (plan.parts[k].outer.segments.iter()).any(|s| distance_from_segment(s, p) < 1e-6);
        (0..moves.len())
            .find(|&i| {
                let (at, m) = moves[i];
                at.z == -2.0 && m.to().z == -2.0 && on(at.xy()) && on(m.to().xy())
            })
            .unwrap_or_else(|| panic!("the loop of part {k} is cut"))
    };
    for (star, diamond) in chains {
        let (s, d) = (first_on(star), first_on(diamond));
        assert!(s < d, "the star before its diamond");
        for i in [s, d] {
            let (at, step) = moves[i - 1];
            assert!(
                matches!(step, Move::Line { .. }) && at.z == -2.0,
                "reached by a step at depth: {step:?}"
            );
        }
    }
}

#[test]
fn leaves_with_clean_up_paths_are_cut_after_the_loops_around_them() {
    // Four islands of radius 8 at the 8-island rectangle's pitch, at 5.4 mm stepover (90 % of
    // the diameter): what is left between them, and between them and the walls, are parts
    // of nested loops with clean-up paths. Those are cut after the loops round them, from the
    // outermost in, reached at depth, not first, from their innermost loop out, reached
    // through full stock by a slot or an entry.
    let island =
        |x: f64, y: f64| Contour::new(vec![Segment::Arc(Arc::circle(Point::new(x, y), 8.0))]).reversed();
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 86.0, 100.0),
        islands: vec![
            island(21.5, 25.0),
            island(64.5, 25.0),
            island(21.5, 75.0),
            island(64.5, 75.0),
        ],
    };
    let (l, plan, _) = linked_plan(&pocket, 5.4, Entry::Helix);
    let leaves: Vec<usize> = (0..plan.parts.len())
        .filter(|&k| {
            let p = &plan.parts[k];
            p.parent.is_some() && p.holes.is_empty() && p.children.len() <= 1 && !p.cleanups.is_empty()
        })
        .collect();
    assert!(!leaves.is_empty(), "leaves with clean-up paths");
    let mut from = l.toolpath.start;
    let mut moves = Vec::new();
    for m in &l.toolpath.moves {
        moves.push((from, *m));
        from = m.to();
    }
    // The first move at depth along one of `loops`.
    let first_on = |loops: Vec<&Contour>| {
        let on =
            |p: Point| (loops.iter().flat_map(|c| &c.segments)).any(|s| distance_from_segment(s, p) < 1e-6);
        (0..moves.len()).find(|&i| {
            let (at, m) = moves[i];
            at.z == -2.0 && m.to().z == -2.0 && on(at.xy()) && on(m.to().xy())
        })
    };
    for k in leaves {
        let parent = &plan.parts[plan.parts[k].parent.unwrap()];
        let leaf = first_on(vec![&plan.parts[k].outer]).unwrap();
        let around = first_on(parent.loops().collect()).unwrap();
        assert!(leaf > around, "part {k} cut after the loops around it");
        let (at, step) = moves[leaf - 1];
        assert!(
            at.z == -2.0 && !matches!(step, Move::Rapid { .. }),
            "reached at depth"
        );
    }
}

#[test]
fn a_long_way_across_at_depth_goes_over_the_top_when_that_is_faster() {
    // Two islands 60 mm apart: their loops at the walls' level are 46 mm apart, 2.8 s at the
    // cutting feed against about 1.3 s up, across at rapid, down and a retract's half second.
    let (l, plan, _) = linked_plan(&two_islands(120.0, 40.0, [30.0, 90.0]), 2.4, Entry::Helix);
    let params = params(Entry::Helix);
    let on_a_path = |p: Point| {
        (plan.parts.iter())
            .flat_map(|q| {
                q.loops()
                    .flat_map(|c| &c.segments)
                    .chain(q.cleanups.iter().flat_map(|c| &c.segments))
            })
            .any(|s| distance_from_segment(s, p) < 1e-6)
    };
    // The longest straight link at depth worth feeding: where its time reaches a hop's.
    let t = &params.time;
    let hop = |across: f64| t.hop_seconds(7.0, across, 6.0) + t.feed_seconds(1.0, t.plunge_feed);
    let longest = (1..200)
        .map(f64::from)
        .find(|&d| t.feed_seconds(d, t.feed) > hop(d))
        .unwrap();
    let mut at = l.toolpath.start;
    for m in &l.toolpath.moves {
        if let Move::Line { to, feed: Feed::Cut } = *m {
            let link = !(on_a_path(at.xy()) && on_a_path(to.xy()) && on_a_path(at.xy().midpoint(to.xy())));
            if link && at.z == -2.0 && to.z == -2.0 {
                assert!(
                    at.distance(to) <= longest + 3.0,
                    "{at:?} to {to:?}: longer than {longest} mm"
                );
            }
        }
        at = m.to();
    }
}

#[test]
fn clean_up_paths_beside_a_loop_are_cut_on_its_way_round() {
    // At 90 % stepover the levels leave residues between the loops round the islands and the
    // loops inside them: clean-up paths. Each one whose ends both lie within a tool diameter
    // of the nearest point of a loop of its part is cut from a loop, out and back, not
    // reached by a link of its own (when that way is chosen: see the next test), also when
    // one end lies beyond the tool's disc there (before 495456c, cut as its own item). The
    // linking bench's rectangle with 8 round islands.
    let pocket = eight_island_rectangle();
    let (plan, prepared) = planned(&pocket, 5.4);
    let job = [(&prepared, &plan)];
    let l = link_hosting(
        &job,
        &params(Entry::Helix),
        &Tolerance::default(),
        &crate::progress::Silent,
        Some(Hosting::Everywhere),
    )
    .unwrap();
    assert_no_gouge(&l.toolpath, &prepared);
    // A tool diameter.
    let reach = 6.0;
    // A loop of the part, or of a part inside it: a leaf cut after the part cuts the clean-up
    // paths its loop passes nearer than the part's own (see `Linker::cut_part`).
    let on_loop = |part: &Part, p: Point| {
        let inside = part.children.iter().map(|&c| &plan.parts[c]);
        std::iter::once(part)
            .chain(inside)
            .flat_map(|n| n.loops())
            .flat_map(|c| &c.segments)
            .any(|s| distance_from_segment(s, p) < 1e-6)
    };
    let (mut beside, mut beyond_radius) = (0, 0);
    // Of the parts with loops round islands: a plain leaf's clean-up paths, and those of the
    // nested loops of one, are cut after their loops, nearest first (see
    // `Linker::cut_small_leaves`).
    for part in plan.parts.iter().filter(|p| !p.holes.is_empty()) {
        for c in &part.cleanups {
            let ends = [c.segments[0].start(), c.segments[c.segments.len() - 1].end()];
            // Of the nearest points of its loops to either end, the least distance from it to
            // the farther end.
            let farther = (part.loops())
                .flat_map(|l| {
                    ends.map(|e| {
                        let s = (l.segments.iter()).min_by(|a, b| {
                            distance_from_segment(a, e).total_cmp(&distance_from_segment(b, e))
                        });
                        let p = crate::geom::closest_point(s.unwrap(), e);
                        ends.iter().map(|&f| p.distance(f)).fold(0.0, f64::max)
                    })
                })
                .fold(f64::INFINITY, f64::min);
            if farther > reach - 1e-6 {
                continue;
            }
            beside += 1;
            if farther > 3.0 {
                beyond_radius += 1;
            }
            // The move onto the path comes from a loop of its part.
            let mut at = l.toolpath.start;
            let from_loop = l.toolpath.moves.iter().any(|m| {
                let hit = matches!(m, Move::Line { feed: Feed::Cut, .. })
                    && ends.iter().any(|&e| m.to().xy().distance(e) < 1e-9)
                    && on_loop(part, at.xy());
                at = m.to();
                hit
            });
            assert!(from_loop, "clean-up path from {:?} to {:?}", ends[0], ends[1]);
        }
    }
    assert!(beside >= 4, "{beside} clean-up paths beside a loop");
    assert!(
        beyond_radius >= 4,
        "{beyond_radius} of them beyond the tool's disc"
    );
}

#[test]
fn the_loops_of_leaves_cut_after_the_loops_round_them_all_meet_stock() {
    // At 90 % stepover the triangles between two of the 8-island rectangle's islands and a
    // wall are leaves cut after the loops round them, and the part round them leaves clean-up
    // paths by their corners. Cut one after the other, those paths were joined by straight
    // moves along the triangles' edges, through the triangles' stock, and each triangle's
    // loop then went along its edge cutting nothing: 134 mm of such loops in the program at
    // the linking bench's depth. Each such path now goes to the loop of the leaf that passes
    // nearest, and is cut on its way round or among the leaves. Replayed, the loops of the
    // leaves meet stock but for a few millimetres.
    use crate::simulate::classify::{classify, MoveKind};
    let (l, plan, _) = linked_plan(&eight_island_rectangle(), 5.4, Entry::Helix);
    let settings = crate::post::ProgramSettings::default();
    let text = crate::post::write_gcode(&l.toolpath, &settings, crate::post::Dialect::LinuxCnc);
    let program = crate::simulate::read_program(&text).unwrap();
    let kinds = classify(&program.moves, plan.tool_radius);
    let leaves: Vec<&Part> = (plan.parts.iter())
        .filter(|p| p.parent.is_some() && p.children.is_empty() && p.holes.is_empty())
        .collect();
    let on_a_leaf = |p: Point| {
        (leaves.iter().flat_map(|n| &n.outer.segments)).any(|s| distance_from_segment(s, p) < 1e-3)
    };
    let (mut on_leaves, mut idle) = (0.0, 0.0);
    for (m, k) in program.moves.iter().zip(&kinds) {
        let s = m.footprint();
        if m.from.z != m.to.z || !on_a_leaf(s.start()) || !on_a_leaf(s.point_at(0.5)) {
            continue;
        }
        on_leaves += m.length();
        if *k == MoveKind::Link {
            idle += m.length();
        }
    }
    assert!(on_leaves > 500.0, "{on_leaves} mm along the leaves' loops");
    assert!(idle < 5.0, "{idle} mm of the leaves' loops cut nothing");
    // The clean-up paths with no loop to cut them on its way round are cut among the leaves
    // when one passes within reach: the passes along the lenses between the rows of islands
    // go from one diamond between four islands to the next, not round the diamonds to the
    // next pass and back later: 587 mm at depth off the plan's paths, where it was 913 mm
    // before these paths went to the leaves.
    let paths: Vec<&Segment> = (plan.parts.iter())
        .flat_map(|p| {
            p.loops()
                .flat_map(|c| &c.segments)
                .chain(p.paths().flat_map(|c| &c.segments))
        })
        .collect();
    let on_paths = |p: Point| paths.iter().any(|q| distance_from_segment(q, p) < 1e-3);
    let off: f64 = (program.moves.iter())
        .filter(|m| m.from.z == -2.0 && m.to.z == -2.0 && m.motion != crate::simulate::gcode::Motion::Rapid)
        .filter(|m| !(on_paths(m.footprint().start()) && on_paths(m.footprint().point_at(0.5))))
        .map(|m| m.length())
        .sum();
    assert!(off < 650.0, "{off} mm at depth off the plan's paths");
}

#[test]
fn the_tool_retracts_from_where_it_cut_not_after_a_step_through_cleared_stock() {
    // Leaving the loops round one island, the tool stepped straight back out to the outermost
    // of them so that the links onward were as without them; where it then retracted, that
    // step cut nothing: on the linking bench's 8-island rectangle (corners of radius 10) at
    // 90 % stepover, 3 mm deep, 5.4 mm before each of seven retracts. Replayed, the feed
    // moves right before retracts that meet no stock are a few millimetres in all.
    use crate::simulate::classify::{classify, MoveKind};
    let (p, line) = (Point::new, |a, b| Segment::Line(crate::geom::Line::new(a, b)));
    let corner = |x: f64, y: f64, from: f64| {
        Segment::Arc(Arc::new(
            p(x, y),
            10.0,
            from.to_radians(),
            std::f64::consts::FRAC_PI_2,
        ))
    };
    let boundary = Contour::new(vec![
        line(p(10.0, 0.0), p(190.0, 0.0)),
        corner(190.0, 10.0, -90.0),
        line(p(200.0, 10.0), p(200.0, 110.0)),
        corner(190.0, 110.0, 0.0),
        line(p(190.0, 120.0), p(10.0, 120.0)),
        corner(10.0, 110.0, 90.0),
        line(p(0.0, 110.0), p(0.0, 10.0)),
        corner(10.0, 10.0, 180.0),
    ]);
    let pocket = Pocket {
        boundary,
        ..eight_island_rectangle()
    };
    let (plan, prepared) = planned(&pocket, 5.4);
    let deep = LinkParams {
        depth: 3.0,
        step_down: 3.0,
        ..params(Entry::Helix)
    };
    let l = link(&[(&prepared, &plan)], &deep, &Tolerance::default()).unwrap();
    assert_no_gouge(&l.toolpath, &prepared);
    let settings = crate::post::ProgramSettings::default();
    let text = crate::post::write_gcode(&l.toolpath, &settings, crate::post::Dialect::LinuxCnc);
    let program = crate::simulate::read_program(&text).unwrap();
    let kinds = classify(&program.moves, plan.tool_radius);
    let (mut retracts, mut idle) = (0, Vec::new());
    for k in 1..program.moves.len() {
        if kinds[k] != MoveKind::Retract || program.moves[k].from.z > -2.9 {
            continue;
        }
        retracts += 1;
        let before = &program.moves[k - 1];
        if kinds[k - 1] == MoveKind::Link && before.from.z == before.to.z {
            idle.push(before.length());
        }
    }
    assert!(retracts >= 5, "{retracts} retracts from depth");
    // Seven steps of 5.4 mm before; two moves of 3.4 and 3.7 mm remain, the last of a
    // clean-up path whose stock something else cut.
    let total: f64 = idle.iter().sum();
    assert!(total < 10.0, "retracts after {idle:?} mm through cleared stock");
}

/// A rectangle with 4 × 3 round islands of radius 5, `pitch` apart and from its corner.
fn island_grid(pitch: f64) -> Pocket {
    Pocket {
        boundary: rect(0.0, 0.0, 5.0 * pitch, 4.0 * pitch),
        islands: (0..12)
            .map(|k| {
                let c = Point::new(pitch * (1 + k % 4) as f64, pitch * (1 + k / 4) as f64);
                Contour::new(vec![Segment::Arc(Arc::circle(c, 5.0))]).reversed()
            })
            .collect(),
    }
}

/// The time of the program linked with its clean-up paths cut where `hosting` says (`None`:
/// the fastest way, part by part), checked for gouges.
fn hosted_seconds(plan: &ClearPlan, prepared: &PreparedPocket, hosting: Option<Hosting>) -> f64 {
    let p = params(Entry::Helix);
    let job = [(prepared, plan)];
    let l = link_hosting(&job, &p, &Tolerance::default(), &crate::progress::Silent, hosting).unwrap();
    assert_no_gouge(&l.toolpath, prepared);
    p.time.toolpath(&l.toolpath).total()
}

#[test]
fn clean_up_paths_are_cut_the_faster_way_part_by_part() {
    // Excursions from the loops save time on the two-island rectangle at 70 % stepover; on an
    // island grid (18 mm apart) at 80 % the clean-up paths between the islands are cut
    // faster one after another, as paths of their own (103.1 s against 104.2 s; at 20 mm
    // apart and 85 %, where this was so before the clean-up pieces round one patch of
    // material gave way to one spot or pass, excursions are now the faster by 6 s). Either
    // way the program takes the least time of the two.
    let grid = island_grid(18.0);
    let mut slower = [0, 0];
    for (pocket, stepover) in [(two_islands(120.0, 60.0, [35.0, 85.0]), 4.2), (grid, 4.8)] {
        let (plan, prepared) = planned(&pocket, stepover);
        let seconds = |hosting| hosted_seconds(&plan, &prepared, hosting);
        let (timed, hosted, own) = (
            seconds(None),
            seconds(Some(Hosting::Everywhere)),
            seconds(Some(Hosting::Never)),
        );
        assert!(
            timed <= hosted.min(own) + 1e-9,
            "{timed} s, {hosted} s hosted, {own} s as their own"
        );
        slower[usize::from(hosted > own)] += 1;
    }
    assert_eq!(slower, [1, 1], "each way the faster on one of the two");
}

#[test]
fn neighbouring_branches_are_linked_by_a_short_slot_instead_of_a_new_entry() {
    // A 3 x 3 grid of 8 mm holes at a 28 mm pitch: the levels split into a branch in every cell
    // between four holes, each a leaf to enter (at a 20 mm pitch the tool clears each cell
    // from one spot, see `clear::spots`). Neighbouring cells see each other through the gaps
    // between the holes.
    let circle = |x: f64, y: f64| {
        Contour::new(vec![Segment::Arc(
            crate::geom::Arc::circle(Point::new(x, y), 4.0).reversed(),
        )])
    };
    let mut islands = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            islands.push(circle(14.0 + 28.0 * i as f64, 14.0 + 28.0 * j as f64));
        }
    }
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 84.0, 84.0),
        islands,
    };
    let tol = Tolerance::default();
    let (plan, prepared) = planned(&pocket, 2.4);
    let leaves = plan.parts.iter().filter(|p| p.children.is_empty()).count();
    assert!(leaves >= 4, "{leaves} leaves");
    let cells = [(28.0, 28.0), (56.0, 28.0), (28.0, 56.0), (56.0, 56.0)].map(|(x, y)| Point::new(x, y));
    let branch_in = |c: Point| {
        (plan.parts.iter()).any(|p| {
            let b = p.outer.bbox();
            p.children.is_empty() && b.min.midpoint(b.max).distance(c) < 1.0
        })
    };
    assert!(
        cells.into_iter().all(branch_in),
        "a leaf in each cell, not a spot"
    );
    // Linked with a retract costing its lengths only, and with half a second more.
    let with = |per_retract: f64| {
        let mut p = params(Entry::Helix);
        p.time.per_retract = per_retract;
        let l = link(&[(&prepared, &plan)], &p, &tol).unwrap();
        assert_no_gouge(&l.toolpath, &prepared);
        l
    };
    let (free, dear) = (with(0.0), with(0.5));
    // A slot to the next branch beats a retract and a helix either way.
    for l in [&free, &dear] {
        assert!(
            entries(l) < leaves / 2,
            "{} entries for {leaves} leaves",
            entries(l)
        );
    }
    // Dearer retracts: more of the ways between the loops round the holes go along the loop
    // just cut instead of over the top.
    let (r0, r1) = (free.toolpath.stats().retracts, dear.toolpath.stats().retracts);
    assert!(r1 < r0, "{r1} retracts at 0.5 s each, {r0} at none");
}

/// Helix entries from above the stock (ramping arcs that start at or above the top).
fn entries(l: &Linked) -> usize {
    let mut at = l.toolpath.start;
    let mut n = 0;
    for m in &l.toolpath.moves {
        if matches!(
            m,
            Move::Arc {
                feed: crate::toolpath::Feed::Ramp,
                ..
            }
        ) && at.z >= 0.0
        {
            n += 1;
        }
        at = m.to();
    }
    n
}

/// `pocket` linked for a 6 mm tool at 2.4 mm stepover with helix entries, its plan having at
/// least `leaves` leaves, checked for gouges.
fn linked_with_leaves(pocket: &Pocket, leaves: usize) -> Linked {
    let (plan, prepared) = planned(pocket, 2.4);
    let n = plan.parts.iter().filter(|p| p.children.is_empty()).count();
    assert!(n >= leaves, "{n} leaves");
    linked_helix(&plan, &prepared)
}

/// `plan` linked with helix entries, checked for gouges.
fn linked_helix(plan: &ClearPlan, prepared: &PreparedPocket) -> Linked {
    let l = link(&[(prepared, plan)], &params(Entry::Helix), &Tolerance::default()).unwrap();
    assert_no_gouge(&l.toolpath, prepared);
    l
}

#[test]
fn a_branch_behind_an_island_is_reached_by_a_slot_round_it() {
    // Two branches either side of a round island: the straight way from one to the other
    // goes through the island, the way round it is short. One entry, then a slot round.
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 36.0, 26.0),
        islands: vec![Contour::new(vec![Segment::Arc(
            crate::geom::Arc::circle(Point::new(18.0, 13.0), 3.0).reversed(),
        )])],
    };
    let l = linked_with_leaves(&pocket, 2);
    assert_eq!(entries(&l), 1);
    assert_eq!(l.toolpath.stats().retracts, 1, "only the last");
}

#[test]
fn a_loop_behind_an_island_with_no_floor_cut_near_it_is_reached_round_the_island() {
    // A plate of 8 x 6 holes: going from the loops round one hole to those round the next,
    // the straight way often crosses a hole, and near the next hole nothing is cut yet, so
    // going over the top means a new entry (a helix of some 3.4 s here) where the way round
    // the hole, along the loop just cut, takes under two seconds.
    let (pocket, _) = plate_of_holes(8, 6);
    let (l, _, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    assert_eq!(entries(&l), 1);
}

#[test]
fn small_leaves_in_the_corners_of_a_channel_are_cut_without_entries_of_their_own() {
    // A 10 mm channel round two islands: the level beyond the first leaves a small leaf in
    // each corner and at each junction, far apart. The loops at 3 mm reach all that the
    // corners' leaves would cut, and the tool clears each junction from a spot (see
    // `clear::spots`). Entering each would take two helices; cut after the channel's loops,
    // from the stock they clear, they take none.
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 80.0, 40.0),
        islands: vec![
            rect(10.0, 10.0, 35.0, 30.0).reversed(),
            rect(45.0, 10.0, 70.0, 30.0).reversed(),
        ],
    };
    let (plan, prepared) = planned(&pocket, 2.4);
    let leaves = (plan.parts.iter()).filter(|p| p.parent.is_some()).count();
    let spots: usize = plan.parts.iter().map(|p| p.spots.len()).sum();
    assert_eq!((leaves, spots), (0, 2), "leaves and spots");
    assert_eq!(entries(&linked_helix(&plan, &prepared)), 1);
}

#[test]
fn a_slot_too_narrow_for_a_helix_is_entered_by_a_ramp() {
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 40.0, 6.4),
        islands: vec![],
    };
    let (l, prepared) = linked(&pocket, 2.0, Entry::Helix);
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    assert!(!l.toolpath.moves.iter().any(|m| matches!(m, Move::Arc { .. })));
    assert!(steepest(&l.toolpath) <= 3f64.to_radians() + 1e-9);
    assert_no_gouge(&l.toolpath, &prepared);
}

#[test]
fn a_pocket_barely_wider_than_the_tool_is_plunged_with_a_warning() {
    let hole = Contour::new(vec![Segment::Arc(crate::geom::Arc::circle(
        Point::new(0.0, 0.0),
        3.05,
    ))]);
    let pocket = Pocket {
        boundary: hole,
        islands: vec![],
    };
    let (l, _) = linked(&pocket, 2.0, Entry::Helix);
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    assert!(matches!(l.warnings[0], LinkWarning::Plunged { .. }));
    let (l, _) = linked(&pocket, 2.0, Entry::Plunge);
    assert!(l.warnings.is_empty());
}

/// Wall-following length of `path`'s feed moves at the final depth by the side the wall
/// is on: (right, left).
fn wall_sides(path: &Toolpath, pocket: &Pocket, z: f64) -> (f64, f64) {
    let walls: Vec<Segment> = pocket.contours().flat_map(|c| c.segments.clone()).collect();
    let (mut right, mut left) = (0.0, 0.0);
    let mut at = path.start;
    for m in &path.moves {
        let to = m.to();
        let footprint = match *m {
            Move::Line { .. } => Some(Segment::Line(crate::geom::Line::new(at.xy(), to.xy()))),
            Move::Arc { center, sweep, .. } => {
                let v = at.xy() - center;
                Some(Segment::Arc(crate::geom::Arc::new(
                    center,
                    v.length(),
                    v.angle(),
                    sweep,
                )))
            }
            Move::Rapid { .. } => None,
        };
        if let Some(s) = footprint.filter(|_| at.z == z && to.z == z) {
            for k in 0..100 {
                let t = (k as f64 + 0.5) / 100.0;
                let c = s.point_at(t);
                let (d, w) = walls
                    .iter()
                    .map(|w| (distance_from_segment(w, c), crate::geom::closest_point(w, c)))
                    .fold((f64::INFINITY, c), |a, b| if b.0 < a.0 { b } else { a });
                if (d - 3.0).abs() < 1e-3 {
                    if s.tangent_at(t).cross(w - c) < 0.0 {
                        right += s.length() / 100.0;
                    } else {
                        left += s.length() / 100.0;
                    }
                }
            }
        }
        at = to;
    }
    (right, left)
}

#[test]
fn climb_keeps_the_wall_and_the_islands_on_the_tools_right() {
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 60.0, 40.0),
        islands: vec![rect(20.0, 15.0, 35.0, 25.0).reversed()],
    };
    let tol = Tolerance::default();
    let (plan, prepared) = planned(&pocket, 2.4);
    for (direction, wall_on_right) in [(Direction::Climb, true), (Direction::Conventional, false)] {
        let p = LinkParams {
            direction,
            ..params(Entry::Helix)
        };
        let l = link(&[(&prepared, &plan)], &p, &tol).unwrap();
        let (right, left) = wall_sides(&l.toolpath, &pocket, -2.0);
        // Both loops at the walls: 2 (54 + 34) round the wall; round the island its sides
        // and a quarter circle of the tool's radius at each corner.
        let expected = 2.0 * (54.0 + 34.0) + 2.0 * (15.0 + 10.0) + std::f64::consts::TAU * 3.0;
        assert!((right + left - expected).abs() < 0.1, "{right} + {left}");
        let (on, off) = if wall_on_right {
            (right, left)
        } else {
            (left, right)
        };
        assert!(
            off == 0.0,
            "{direction:?}: {on} mm on the expected side, {off} on the other"
        );
    }
}

#[test]
fn linking_reports_a_step_for_each_loop_and_clean_up_path_at_each_pass() {
    // Islands and a wide stepover: loops round islands and clean-up paths besides the outer
    // loops; three passes.
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 60.0, 40.0),
        islands: vec![
            rect(15.0, 15.0, 22.0, 25.0).reversed(),
            rect(38.0, 12.0, 45.0, 28.0).reversed(),
        ],
    };
    let (plan, prepared) = planned(&pocket, 5.0);
    let cleanups: usize = plan.parts.iter().map(|p| p.cleanups.len()).sum();
    let holes: usize = plan.parts.iter().map(|p| p.holes.len()).sum();
    assert!(
        cleanups > 0 && holes > 0,
        "{cleanups} clean-up paths, {holes} loops round islands"
    );
    let p = LinkParams {
        depth: 6.0,
        ..params(Entry::Helix)
    };
    let progress = crate::progress::Recorded::default();
    let l = link_with(&[(&prepared, &plan)], &p, &Tolerance::default(), &progress).unwrap();
    assert_no_gouge(&l.toolpath, &prepared);
    let loops = plan.loop_count();
    assert_eq!(
        progress.stages(),
        vec![(format!("linking {loops} loops"), Some(3 * loops as u64))]
    );
    assert_eq!(progress.steps(), 3 * loops as u64);
}

#[test]
fn entries_into_the_branches_of_a_pocket_follow_a_short_tour() {
    // A 200 x 120 rectangle with two rows of four round islands at 30 % stepover: fifteen
    // branches (corners, the gaps along the walls, between the islands) each entered. The
    // ready branches of the whole tree are one pool, the next entered the first of a short
    // tour over them: before, each branch of the tree was finished before the next, and the
    // tool went from one side to the other and back three times, 80 to 150 mm each.
    let pocket = eight_island_rectangle();
    let (l, _) = linked(&pocket, 1.8, Entry::Helix);
    let mut at = l.toolpath.start;
    let mut across = 0.0;
    for m in &l.toolpath.moves {
        if let Move::Rapid { to } = *m {
            across += at.xy().distance(to.xy());
        }
        at = m.to();
    }
    // 991.5 mm finishing each branch first, 834.3 now.
    assert!(across < 900.0, "{across} mm of rapids");
}

#[test]
fn a_helix_is_made_only_where_the_tool_goes_on_from_it_at_depth() {
    // The 75-hole plate at 5.4 mm stepover: the helix nearest where the first loop starts
    // (at a corner of the plate) ended where the move on to the loop would touch the wall,
    // and the tool went back up and ramped down again elsewhere. The helix is now chosen
    // among those from whose end the move on is clear.
    let (pocket, _) = plate_of_holes(15, 5);
    let (l, _) = linked(&pocket, 5.4, Entry::Helix);
    let moves = &l.toolpath.moves;
    let mut at = l.toolpath.start;
    for (k, m) in moves.iter().enumerate() {
        let helix_ends = matches!(m, Move::Arc { to, .. } if to.z == -2.0 && at.z > -2.0);
        if helix_ends {
            // The helix's last turn at depth, then on at depth, not up.
            let on = moves[k + 1..]
                .iter()
                .find(|m| !matches!(m, Move::Arc { to, .. } if to.z == -2.0));
            assert!(
                !matches!(on, Some(Move::Rapid { .. })),
                "the helix ending at move {k} is left by a retract"
            );
        }
        at = m.to();
    }
}

#[test]
fn a_part_whose_leaves_became_spots_is_still_cut_before_its_parent() {
    // A 120 x 100 pocket round a 60 x 50 island: at 2.4 mm each side strip's part has a leaf
    // at each end, both taken by spots (see `clear::spots`). The strips are cut first, each
    // the first loop of its branch, as they were with their leaves; cut after the part round
    // them instead, that part's loop went round in full stock (the bench's pocket in an
    // island: 5 retracts where 3 were, 15.6 % of its cutting above 150° where 10.4 % was).
    let pocket = Pocket {
        boundary: rect(0.0, 0.0, 120.0, 100.0),
        islands: vec![rect(30.0, 25.0, 90.0, 75.0).reversed()],
    };
    let (l, plan, _) = linked_plan(&pocket, 2.4, Entry::Helix);
    let strips: Vec<&Part> = plan.parts.iter().filter(|p| p.spots.len() == 2).collect();
    assert_eq!(strips.len(), 2, "two strips with a spot at each end");
    // Where each strip's loop is first reached at depth, against where the part round them is.
    let on = |part: &Part, p: Point| {
        (part.outer.segments.iter()).any(|s| crate::geom::distance_from_segment(s, p) < 1e-6)
    };
    let parent = &plan.parts[strips[0].parent.unwrap()];
    let mut at = l.toolpath.start;
    let (mut strip_first, mut parent_first) = (None, None);
    for (k, m) in l.toolpath.moves.iter().enumerate() {
        let to = m.to();
        if at.z == -2.0 && to.z == -2.0 {
            if strip_first.is_none() && strips.iter().any(|s| on(s, to.xy())) {
                strip_first = Some(k);
            }
            if parent_first.is_none() && on(parent, to.xy()) {
                parent_first = Some(k);
            }
        }
        at = to;
    }
    let (s, p) = (strip_first.unwrap(), parent_first.unwrap());
    assert!(s < p, "a strip's loop at move {s}, the part round them at {p}");
}

#[test]
fn clean_up_paths_stay_on_the_parts_loops_when_that_is_faster_than_going_with_the_leaves() {
    // On the two-island rectangle at 90 % stepover, clean-up paths of the part round the
    // islands can go with the leaves cut after it (`Hosting::Everywhere`), but the program is
    // shorter with them cut on the way round the part's own loops (`OwnLoops`): 106.04 s
    // against 106.96 s, and 119.34 s as paths of their own. The timed choice tries all three
    // ways; before it tried only the first and the last (on FLH-001 at 60 % the leaves took
    // two paths from the loop that cut them, and the program took 3 s longer).
    let pocket = two_islands(120.0, 60.0, [35.0, 85.0]);
    let (plan, prepared) = planned(&pocket, 5.4);
    let seconds = |hosting| hosted_seconds(&plan, &prepared, hosting);
    let (timed, everywhere, own, never) = (
        seconds(None),
        seconds(Some(Hosting::Everywhere)),
        seconds(Some(Hosting::OwnLoops)),
        seconds(Some(Hosting::Never)),
    );
    assert!(
        own + 0.5 < everywhere.min(never),
        "the drawing no longer shows the case: {own} s on the part's loops, {everywhere} s with the \
         leaves, {never} s as paths of their own"
    );
    assert!(
        timed <= own + 1e-9,
        "{timed} s chosen, {own} s on the part's loops"
    );
}

#[test]
fn stretches_through_cleared_stock_are_cut_short_and_the_stock_left_is_the_same() {
    // An island grid 20 mm apart at 40 %: between four islands, the cell's loop cuts only
    // near the middle of its sides, and the small leaf in the cell's middle and the ways to it
    // nothing once the loop is cut. The program is shorter (2342 -> 2222 mm fed, 14.2 -> 9.8 %
    // of its cutting touching no stock); replayed, it gouges nowhere, leaves what the
    // linker's own program leaves, and the tool meets the stock as hard.
    use crate::simulate::{check_program, read_program, CheckParams};
    let grid = island_grid(20.0);
    let (plan, prepared) = planned(&grid, 2.4);
    let p = params(Entry::Helix);
    let job = [(&prepared, &plan)];
    let linker = link_hosting(&job, &p, &Tolerance::default(), &crate::progress::Silent, None).unwrap();
    let short = link(&job, &p, &Tolerance::default()).unwrap();
    assert_no_gouge(&short.toolpath, &prepared);
    let feed_length = |path: &Toolpath| -> f64 {
        (path.moves_from(0))
            .filter(|(_, m)| !matches!(m, Move::Rapid { .. }))
            .map(|(from, m)| m.length(from))
            .sum()
    };
    let (before, after) = (feed_length(&linker.toolpath), feed_length(&short.toolpath));
    assert!(after < before - 50.0, "{before} -> {after} mm");
    let params = CheckParams {
        tool_radius: 3.0,
        depth: Some(2.0),
        gouge_tolerance: 0.01,
        leftover_tolerance: 0.05,
        rapid_rate: crate::simulate::check::RAPID_RATE,
        per_retract: crate::machining_time::DEFAULT_RETRACT_SECONDS,
    };
    let report = |l: &Linked| {
        let settings = crate::post::ProgramSettings::default();
        let text = crate::post::write_gcode(&l.toolpath, &settings, crate::post::Dialect::LinuxCnc);
        let program = read_program(&text).unwrap();
        check_program(
            std::slice::from_ref(&grid),
            &program,
            &params,
            &Tolerance::default(),
        )
        .unwrap()
    };
    let (a, b) = (report(&linker), report(&short));
    assert!(a.passed && b.passed);
    let (pa, pb) = (&a.pockets[0], &b.pockets[0]);
    assert!(
        (pa.leftover_area - pb.leftover_area).abs() < 1e-3,
        "{} {}",
        pa.leftover_area,
        pb.leftover_area
    );
    assert_eq!(pa.gouge, pb.gouge);
    assert_eq!(a.engagement.max_deg, b.engagement.max_deg);
    assert_eq!(a.engagement.p95_in_contact_deg, b.engagement.p95_in_contact_deg);
    assert!(b.engagement.untouched_percent < a.engagement.untouched_percent - 2.0);
}
