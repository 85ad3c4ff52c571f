//! Joining drawn elements, in any order and direction, into closed contours.
//!
//! In: the [`Element`]s (lines and arcs with their layer) the curve stage made. Out:
//! [`Chains`]: closed contours, open chains with their free ends, counts of what was dropped
//! and joined, and [`ImportWarning`]s.
//!
//! End points within the coincidence distance are one node (`nodes.rs`); free ends are
//! then joined in pairs, snapped within the join tolerance or bridged by a straight segment
//! (`free_ends.rs`). Duplicates (the same element drawn twice, or one lying on another)
//! and zero-length elements are dropped first. Chains whose ends meet nothing are reported with
//! their free end coordinates.

use super::dangles::{remove_dangles, Stroke, Strokes};
use super::faces::{bounded_faces, Edge};
use super::free_ends::{join_free_ends, UNAMBIGUOUS};
use super::nodes::{node_distance, Nodes};
use super::Element;
use crate::geom::{distance_from_segment, Aabb, Arc, BoxIndex, Contour, Line, Point, Segment, Tolerance};
use crate::import::ImportWarning;
use std::collections::{HashMap, HashSet};

/// A closed contour found by chaining.
#[derive(Debug, Clone)]
pub struct ChainedContour {
    /// The contour, in the direction it was found.
    pub contour: Contour,
    /// Layer index (into the drawing's layers).
    pub layer: usize,
    /// The drawing elements it was built from (indices into the drawing's elements).
    pub elements: Vec<usize>,
}

impl ChainedContour {
    /// The same layer and elements with `contour` in place of this contour (not copied first:
    /// `ChainedContour { contour, ..c.clone() }` copies every segment only to drop them).
    pub fn with_contour(&self, contour: Contour) -> ChainedContour {
        ChainedContour {
            contour,
            layer: self.layer,
            elements: self.elements.clone(),
        }
    }
}

/// A chain of elements that does not close.
#[derive(Debug, Clone)]
pub struct OpenChain {
    /// Layer index.
    pub layer: usize,
    /// First free end.
    pub start: Point,
    /// Last free end.
    pub end: Point,
    /// The drawing elements of the chain.
    pub elements: Vec<usize>,
    /// The chain's segments in order from `start` to `end`, ends moved onto their nodes
    /// (bridged gaps included).
    pub segments: Vec<Segment>,
    /// The nearest other free end on its layer to an end of this chain (its own other end
    /// included).
    pub nearest_gap: Option<NearestGap>,
}

/// The gap from an open chain's end to the nearest other free end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearestGap {
    /// Its width, mm: a join tolerance above it joins the two ends.
    pub length: f64,
    /// True when no third free end lies within five times the width of either end: a
    /// gap-closing length above it bridges the gap.
    pub unambiguous: bool,
}

/// The result of chaining.
#[derive(Debug, Clone, Default)]
pub struct Chains {
    /// Closed contours.
    pub contours: Vec<ChainedContour>,
    /// Chains that stay open.
    pub open: Vec<OpenChain>,
    /// Elements dropped because another element covers them.
    pub duplicates_dropped: usize,
    /// Elements dropped because they have no length.
    pub zero_length_dropped: usize,
    /// Nodes where end points that did not coincide exactly were joined.
    pub gaps_closed: usize,
    /// The largest distance an end point was moved to join its node.
    pub largest_gap: f64,
    /// Remarks (branches, closed gaps).
    pub warnings: Vec<ImportWarning>,
}

/// End `0` (start) or `1` (end) of an element.
pub(super) type End = (usize, u8);

/// Joins `elements` into closed contours, per layer: ends within the coincidence distance are
/// one node, free ends within the join tolerance `tol.join` are snapped together, and free
/// ends up to `close_gaps` apart that are unambiguously each other's (see
/// `free_ends.rs`) are bridged by a straight segment, reported as
/// [`ImportWarning::GapBridged`]. `close_gaps` 0 bridges nothing.
///
/// ```
/// use pocketeer::geom::{Line, Point, Segment, Tolerance};
/// use pocketeer::import::{chain, Element};
/// let p = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.02, 10.0)];
/// let elements: Vec<Element> = (0..3)
///     .map(|k| Element {
///         segment: Segment::Line(Line::new(Point::new(p[k].0, p[k].1), Point::new(p[k + 1].0, p[k + 1].1))),
///         layer: 0,
///         source: k,
///         closed_group: None,
///     })
///     .chain([Element {
///         segment: Segment::Line(Line::new(Point::new(0.0, 9.98), Point::new(0.0, 0.0))),
///         layer: 0,
///         source: 3,
///         closed_group: None,
///     }])
///     .collect();
/// let tol = Tolerance::for_scale(10.0, 0.001);
/// assert_eq!(chain(&elements, &tol, 0.05).contours.len(), 1);
/// assert_eq!(chain(&elements, &tol, 0.0).open.len(), 1);
/// ```
pub fn chain(elements: &[Element], tol: &Tolerance, close_gaps: f64) -> Chains {
    let mut out = Chains::default();
    let mut alive = vec![true; elements.len()];
    take_closed_polylines(elements, &mut alive, tol, &mut out);
    out.duplicates_dropped = drop_covered(elements, &mut alive, tol);
    take_full_circles(elements, &mut alive, tol, &mut out);

    let mut nodes = Nodes::build(elements, &alive, tol);
    // An element whose ends fall into one node has no length worth keeping, unless it is long
    // (an arc of almost 360°), which closes on itself.
    for (i, e) in elements.iter().enumerate() {
        if alive[i]
            && nodes.node((i, 0)) == nodes.node((i, 1))
            && e.segment.length() <= 4.0 * node_distance(tol)
        {
            alive[i] = false;
            out.zero_length_dropped += 1;
        }
    }
    for (count, warning) in [
        (
            out.duplicates_dropped,
            ImportWarning::DuplicatesDropped {
                count: out.duplicates_dropped,
            },
        ),
        (
            out.zero_length_dropped,
            ImportWarning::ZeroLengthDropped {
                count: out.zero_length_dropped,
            },
        ),
    ] {
        if count > 0 {
            out.warnings.push(warning);
        }
    }
    let bridges = join_free_ends(elements, &alive, &mut nodes, tol.join, close_gaps);
    out.gaps_closed = nodes.gaps_closed;
    out.largest_gap = nodes.largest_gap;
    if nodes.gaps_closed > 0 {
        out.warnings.push(ImportWarning::GapsClosed {
            count: nodes.gaps_closed,
            largest: nodes.largest_gap,
            at: nodes.largest_gap_at,
        });
    }
    let drawn = elements.len();
    let mut all = std::borrow::Cow::Borrowed(elements);
    for b in &bridges {
        let (from, to) = (nodes.point(b.from), nodes.point(b.to));
        out.warnings.push(ImportWarning::GapBridged {
            length: from.distance(to),
            from,
            to,
        });
        let e = &elements[b.from.0];
        all.to_mut().push(Element {
            segment: Segment::Line(Line::new(from, to)),
            layer: e.layer,
            source: e.source,
            closed_group: None,
        });
        nodes.attach(nodes.node(b.from), nodes.node(b.to));
        alive.push(true);
    }
    let elements = &all[..];
    let (dangles, left) = remove_dangles(&mut alive, &nodes);
    for d in dangles {
        out.warnings.push(ImportWarning::StrokeRemoved {
            elements: d.elements,
            from: d.from,
            to: d.to,
        });
    }
    take_faces(elements, drawn, &mut alive, &nodes, &left, &mut out);
    let partner = pair_ends(elements, &alive, &nodes, &mut out.warnings);
    let mut used = vec![false; elements.len()];
    for first in 0..elements.len() {
        if alive[first] && !used[first] {
            let (walk, closed) = walk_from(first, &partner, &mut used);
            add_walk(elements, drawn, &walk, closed, &nodes, &mut out);
        }
    }
    measure_gaps(&mut out.open);
    // Report contours in drawing order.
    out.contours
        .sort_by_cached_key(|c| c.elements.iter().copied().min());
    out
}

/// Takes the closed polylines out of the chaining: each is a contour as drawn, not taken
/// apart and chained with others, so that two polylines sharing an edge both stay whole. One
/// shorter than the join tolerance is dropped, one drawn there and back again ignored.
fn take_closed_polylines(elements: &[Element], alive: &mut [bool], tol: &Tolerance, out: &mut Chains) {
    // A closed entity's elements are placed one after another: its group is found as runs
    // of consecutive elements (one look-up per element in a map of groups was a tenth of the
    // import of traced art), the runs of each group then taken in order of group.
    let mut runs: Vec<(usize, std::ops::Range<usize>)> = Vec::new();
    for (i, e) in elements.iter().enumerate() {
        if let Some(g) = e.closed_group {
            alive[i] = false;
            match runs.last_mut() {
                Some((h, run)) if *h == g && run.end == i => run.end = i + 1,
                _ => runs.push((g, i..i + 1)),
            }
        }
    }
    // Stable: the runs of one group stay in the order of their elements.
    runs.sort_by_key(|(g, _)| *g);
    let groups: Vec<Vec<usize>> = runs
        .chunk_by(|a, b| a.0 == b.0)
        .map(|same| same.iter().flat_map(|(_, run)| run.clone()).collect())
        .collect();
    // Each closed polyline is a contour alone, and traced art has thousands: shared out among
    // the cores, taken in order.
    let taken = crate::parallel::map_sized(&groups, Vec::len, |members| {
        closed_polyline(elements, members, tol)
    });
    for (members, t) in groups.into_iter().zip(taken) {
        match t {
            ClosedPolyline::Contour(contour) => out.contours.push(ChainedContour {
                contour,
                layer: elements[members[0]].layer,
                elements: members,
            }),
            ClosedPolyline::ZeroLength => out.zero_length_dropped += members.len(),
            ClosedPolyline::NoArea(at) => out.warnings.push(ImportWarning::NoArea {
                elements: members.len(),
                at,
            }),
        }
    }
}

/// What the elements of one closed polyline make.
enum ClosedPolyline {
    /// A contour.
    Contour(Contour),
    /// Nothing: they are no longer than the node distance together.
    ZeroLength,
    /// Nothing: drawn there and back again, a line and not an outline (where it starts).
    NoArea(Point),
}

/// The contour of the closed polyline made of `members` (indices into `elements`, in order).
fn closed_polyline(elements: &[Element], members: &[usize], tol: &Tolerance) -> ClosedPolyline {
    let segs: Vec<Segment> = members.iter().map(|&i| elements[i].segment).collect();
    let length: f64 = segs.iter().map(Segment::length).sum();
    if length <= node_distance(tol) {
        return ClosedPolyline::ZeroLength;
    }
    let contour = Contour::new(close_ring(segs));
    if contour.signed_area().abs() <= node_distance(tol) * length
        && runs_back_over_itself(&contour.segments, tol)
    {
        return ClosedPolyline::NoArea(contour.segments[0].start());
    }
    ClosedPolyline::Contour(contour)
}

/// Takes the parts of the drawing that branch (a node where an odd number of three or more
/// ends meet, once the strokes that bound nothing are gone) out of the chaining: their strokes
/// are the edges of a planar graph, and its bounded faces the contours (`faces.rs`).
fn take_faces(
    elements: &[Element],
    drawn: usize,
    alive: &mut [bool],
    nodes: &Nodes,
    left: &Strokes,
    out: &mut Chains,
) {
    let (strokes, degree) = (&left.strokes, &left.degree);
    let branch = |n: usize| degree[n] >= 3 && degree[n] % 2 == 1;
    if !strokes.iter().any(|s| s.ends.iter().any(|&n| branch(n))) {
        return;
    }
    let mut parts = crate::union_find::UnionFind::new(nodes.pos.len());
    for s in strokes {
        parts.union(s.ends[0], s.ends[1]);
    }
    let mut branched: HashMap<usize, Vec<usize>> = HashMap::new();
    for n in (0..nodes.pos.len()).filter(|&n| branch(n)) {
        branched.entry(parts.find(n)).or_default().push(n);
    }
    let mut strokes_of: HashMap<usize, Vec<&Stroke>> = HashMap::new();
    for s in strokes {
        let root = parts.find(s.ends[0]);
        if branched.contains_key(&root) {
            strokes_of.entry(root).or_default().push(s);
        }
    }
    let mut roots: Vec<usize> = branched.keys().copied().collect();
    roots.sort_unstable();
    for root in roots {
        let members = &strokes_of[&root];
        let edges: Vec<Edge> = members
            .iter()
            .map(|s| Edge {
                segments: s
                    .elements
                    .iter()
                    .map(|&(i, rev)| snapped(&elements[i].segment, rev, i, nodes))
                    .collect(),
                ends: s.ends,
            })
            .collect();
        let faces = bounded_faces(&edges);
        let layer = elements[members[0].elements[0].0].layer;
        out.warnings.push(ImportWarning::BranchingOutline {
            at: nodes.pos[branched[&root][0]],
            branches: branched[&root].len(),
            faces: faces.len(),
        });
        for (contour, along) in faces {
            let mut used: Vec<usize> = along
                .iter()
                .flat_map(|&k| members[k].elements.iter().map(|e| e.0))
                .filter(|&i| i < drawn)
                .collect();
            used.sort_unstable();
            used.dedup();
            out.contours.push(ChainedContour {
                contour,
                layer,
                elements: used,
            });
        }
        for s in members {
            for &(i, _) in &s.elements {
                alive[i] = false;
            }
        }
    }
}

/// Takes the full circles out of the chaining: contours by themselves (or points, when smaller
/// than the tolerance).
fn take_full_circles(elements: &[Element], alive: &mut [bool], tol: &Tolerance, out: &mut Chains) {
    for (i, e) in elements.iter().enumerate() {
        if let Segment::Arc(a) = e.segment {
            if alive[i] && a.is_full_circle() {
                alive[i] = false;
                if a.radius() <= node_distance(tol) {
                    out.zero_length_dropped += 1;
                } else {
                    out.contours.push(ChainedContour {
                        contour: Contour::new(vec![e.segment]),
                        layer: e.layer,
                        elements: vec![i],
                    });
                }
            }
        }
    }
}

/// The elements joined to `first` through `partner`, in order, each with whether it runs
/// backwards, and whether they close: forward from its end, then, when that stops at a free
/// end, backward from its start too. Marks them `used`.
fn walk_from(first: usize, partner: &HashMap<End, End>, used: &mut [bool]) -> (Vec<(usize, bool)>, bool) {
    let mut forward = vec![(first, false)];
    used[first] = true;
    let mut closed = false;
    let mut at: End = (first, 1);
    while let Some(&(next, next_end)) = partner.get(&at) {
        if next == first {
            closed = true;
            break;
        }
        if used[next] {
            break;
        }
        used[next] = true;
        forward.push((next, next_end == 1));
        at = (next, 1 - next_end);
    }
    let mut walk = Vec::new();
    if !closed {
        let mut at: End = (first, 0);
        while let Some(&(prev, prev_end)) = partner.get(&at) {
            if used[prev] {
                break;
            }
            used[prev] = true;
            walk.push((prev, prev_end == 0));
            at = (prev, 1 - prev_end);
        }
        walk.reverse();
    }
    walk.extend(forward);
    (walk, closed)
}

/// A walk as contours (split where it passes a node twice) when it closes, else as an open
/// chain with its free ends. Elements from `drawn` on are bridges, not drawing elements.
fn add_walk(
    elements: &[Element],
    drawn: usize,
    walk: &[(usize, bool)],
    closed: bool,
    nodes: &Nodes,
    out: &mut Chains,
) {
    let drawing_elements = |w: &[(usize, bool)]| w.iter().map(|w| w.0).filter(|&i| i < drawn).collect();
    let layer = elements[walk[0].0].layer;
    if closed {
        for lp in split_at_repeated_nodes(walk, nodes) {
            let segs = lp
                .iter()
                .map(|&(i, rev)| snapped(&elements[i].segment, rev, i, nodes))
                .collect();
            out.contours.push(ChainedContour {
                contour: Contour::new(segs),
                layer,
                elements: drawing_elements(&lp),
            });
        }
    } else {
        let segments: Vec<Segment> = walk
            .iter()
            .map(|&(i, rev)| snapped(&elements[i].segment, rev, i, nodes))
            .collect();
        out.open.push(OpenChain {
            layer,
            start: segments[0].start(),
            end: segments[segments.len() - 1].end(),
            elements: drawing_elements(walk),
            segments,
            nearest_gap: None,
        });
    }
}

/// Fills in [`OpenChain::nearest_gap`] for every open chain.
fn measure_gaps(open: &mut [OpenChain]) {
    let ends: Vec<(usize, Point)> = open
        .iter()
        .flat_map(|o| [(o.layer, o.start), (o.layer, o.end)])
        .collect();
    let boxes: Vec<Aabb> = ends.iter().map(|e| Aabb::from_points(e.1, e.1)).collect();
    let index = BoxIndex::new(&boxes);
    // The nearest end to end `me` other than those in `not`, growing the search box until it
    // finds one or covers a drawing-sized area.
    let nearest = |me: usize, not: &[usize]| {
        let (layer, p) = ends[me];
        let mut r = 1e-3;
        while r < 1e4 {
            let near = index
                .intersecting(&boxes[me].inflated(r))
                .filter(|e| !not.contains(e) && ends[*e].0 == layer)
                .map(|e| (ends[e].1.distance(p), e))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if near.is_some_and(|(d, _)| d <= r) {
                return near;
            }
            r *= 10.0;
        }
        None
    };
    let gaps: Vec<Option<NearestGap>> = (0..open.len())
        .map(|k| {
            let best = [2 * k, 2 * k + 1]
                .into_iter()
                .filter_map(|me| nearest(me, &[me]).map(|(d, other)| (d, me, other)))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            best.map(|(d, me, other)| {
                let third = |e: usize| nearest(e, &[me, other]).map_or(f64::INFINITY, |t| t.0);
                NearestGap {
                    length: d,
                    unambiguous: third(me).min(third(other)) >= UNAMBIGUOUS * d,
                }
            })
        })
        .collect();
    for (o, g) in open.iter_mut().zip(gaps) {
        o.nearest_gap = g;
    }
}

/// Marks elements lying entirely on another element of the same layer as dead; returns how many.
fn drop_covered(elements: &[Element], alive: &mut [bool], tol: &Tolerance) -> usize {
    // Exact copies first, by hashing, so that a drawing of a million identical lines costs a
    // million look-ups rather than a million squared comparisons below.
    let mut dropped = 0;
    let mut seen = HashSet::new();
    for (i, e) in elements.iter().enumerate() {
        if !alive[i] {
            continue;
        }
        let (a, b) = (e.segment.start(), e.segment.end());
        let (a, b) = if (a.x, a.y) <= (b.x, b.y) { (a, b) } else { (b, a) };
        let mut key = vec![
            e.layer as u64,
            a.x.to_bits(),
            a.y.to_bits(),
            b.x.to_bits(),
            b.y.to_bits(),
        ];
        if let Segment::Arc(arc) = e.segment {
            // The same end points and circle, either direction: the same arc only if the
            // other side of the circle is not meant; the midpoint tells.
            let m = arc.point_at(0.5);
            key.extend([
                arc.radius().to_bits(),
                (m.x as f32).to_bits() as u64,
                (m.y as f32).to_bits() as u64,
            ]);
        }
        if !seen.insert(key) {
            alive[i] = false;
            dropped += 1;
        }
    }
    // Only the elements still in play are indexed: traced art's are nearly all closed
    // entities, taken already.
    let live: Vec<usize> = (0..elements.len()).filter(|&i| alive[i]).collect();
    let boxes: Vec<Aabb> = live
        .iter()
        .map(|&i| elements[i].segment.bbox().inflated(node_distance(tol)))
        .collect();
    let index = BoxIndex::new(&boxes);
    for &j in &live {
        if !alive[j] {
            continue;
        }
        let e = &elements[j];
        for i in index.intersecting(&e.segment.bbox()).map(|k| live[k]) {
            if i == j || !alive[i] || elements[i].layer != e.layer {
                continue;
            }
            // Within the node distance, not the join tolerance: a short element beside a long
            // one is part of the outline, however high the tolerance is raised.
            let covered = covers(&elements[i].segment, &e.segment, node_distance(tol));
            // Of two equal elements, keep the first.
            if covered && (i < j || !covers(&e.segment, &elements[i].segment, node_distance(tol))) {
                alive[j] = false;
                dropped += 1;
                break;
            }
        }
    }
    dropped
}

/// True when `inner` lies on `outer` within `tol`.
fn covers(outer: &Segment, inner: &Segment, tol: f64) -> bool {
    let on = |p: Point| distance_from_segment(outer, p) <= tol;
    match (outer, inner) {
        (Segment::Line(_), Segment::Line(l)) => on(l.start) && on(l.end),
        (Segment::Arc(a), Segment::Arc(b)) => {
            a.center().distance(b.center()) <= tol
                && (a.radius() - b.radius()).abs() <= tol
                && (0..=4).all(|k| on(inner.point_at(k as f64 / 4.0)))
        }
        _ => false,
    }
}

/// At every node, pairs the element ends meeting there so that contours pass through it.
/// Two ends pair directly; at a node where 2k ends meet, ends are paired with their angular
/// neighbours so that no two contours cross there; an odd end is left free.
fn pair_ends(
    elements: &[Element],
    alive: &[bool],
    nodes: &Nodes,
    warnings: &mut Vec<ImportWarning>,
) -> HashMap<End, End> {
    let mut at_node: Vec<Vec<End>> = vec![Vec::new(); nodes.pos.len()];
    for (i, e) in elements.iter().enumerate() {
        if !alive[i] {
            continue;
        }
        let (n0, n1) = (nodes.node((i, 0)), nodes.node((i, 1)));
        // An element whose two ends joined (an arc of almost 360°) closes on itself.
        if n0 == n1 && !matches!(e.segment, Segment::Arc(a) if a.is_full_circle()) {
            at_node[n0].push((i, 0));
            at_node[n0].push((i, 1));
            continue;
        }
        at_node[n0].push((i, 0));
        at_node[n1].push((i, 1));
    }
    let mut partner = HashMap::new();
    for (id, ends) in at_node.iter_mut().enumerate() {
        if ends.len() == 2 {
            partner.insert(ends[0], ends[1]);
            partner.insert(ends[1], ends[0]);
            continue;
        }
        if ends.len() < 3 {
            continue;
        }
        if ends.len() % 2 == 1 {
            warnings.push(ImportWarning::OddJunction {
                ends: ends.len(),
                at: nodes.pos[id],
            });
        }
        // Direction leaving the node along each element.
        let angle = |&(i, end): &End| {
            let s = &elements[i].segment;
            let t = if end == 0 {
                s.tangent_at(0.0)
            } else {
                -s.tangent_at(1.0)
            };
            t.angle()
        };
        ends.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
        let m = ends.len() / 2 * 2;
        let gap = |k: usize| {
            let (a, b) = (angle(&ends[k % ends.len()]), angle(&ends[(k + 1) % ends.len()]));
            (b - a).rem_euclid(std::f64::consts::TAU)
        };
        let cost = |offset: usize| (0..m / 2).map(|p| gap(offset + 2 * p)).sum::<f64>();
        let offset = if cost(1) < cost(0) { 1 } else { 0 };
        for p in 0..m / 2 {
            let a = ends[(offset + 2 * p) % ends.len()];
            let b = ends[(offset + 2 * p + 1) % ends.len()];
            partner.insert(a, b);
            partner.insert(b, a);
        }
    }
    partner
}

/// Splits a closed walk that passes a node twice into loops that each pass it once.
fn split_at_repeated_nodes(walk: &[(usize, bool)], nodes: &Nodes) -> Vec<Vec<(usize, bool)>> {
    let start_node = |&(i, rev): &(usize, bool)| nodes.node((i, if rev { 1 } else { 0 }));
    let mut loops = Vec::new();
    let mut stack: Vec<(usize, bool)> = Vec::new();
    let mut seen: HashMap<usize, usize> = HashMap::new(); // node -> position in stack
    for w in walk {
        let n = start_node(w);
        if let Some(&at) = seen.get(&n) {
            let lp: Vec<(usize, bool)> = stack.drain(at..).collect();
            for x in &lp {
                seen.remove(&start_node(x));
            }
            loops.push(lp);
        }
        seen.insert(n, stack.len());
        stack.push(*w);
    }
    if !stack.is_empty() {
        loops.push(stack);
    }
    loops
}

/// True when every segment lies on another one: a ring drawn there and back again.
fn runs_back_over_itself(segs: &[Segment], tol: &Tolerance) -> bool {
    segs.iter().enumerate().all(|(i, s)| {
        segs.iter()
            .enumerate()
            .any(|(j, o)| i != j && covers(o, s, node_distance(tol)))
    })
}

/// Segments drawn end to start as a ring, each end moved exactly onto the next start.
fn close_ring(mut segs: Vec<Segment>) -> Vec<Segment> {
    let n = segs.len();
    for k in 0..n {
        let next = segs[(k + 1) % n].start();
        if segs[k].end() != next {
            segs[k] = with_ends(&segs[k], segs[k].start(), next);
        }
    }
    segs
}

/// `seg` with its ends moved to `a` and `b` (an arc keeps its bulge).
fn with_ends(seg: &Segment, a: Point, b: Point) -> Segment {
    match seg {
        Segment::Line(_) => Segment::Line(Line::new(a, b)),
        Segment::Arc(arc) => Arc::from_bulge(a, b, arc.bulge())
            .map(Segment::Arc)
            .unwrap_or(Segment::Line(Line::new(a, b))),
    }
}

/// Element `i` oriented (`rev`) and with its ends moved onto their nodes.
fn snapped(seg: &Segment, rev: bool, i: usize, nodes: &Nodes) -> Segment {
    let (a, b) = (nodes.point((i, 0)), nodes.point((i, 1)));
    let s = match seg {
        Segment::Line(_) => Segment::Line(Line::new(a, b)),
        Segment::Arc(arc) => {
            if a == b {
                // Ends joined into one node: a closed arc.
                Segment::Arc(Arc::new(
                    arc.center(),
                    arc.radius(),
                    (a - arc.center()).angle(),
                    arc.sweep().signum() * std::f64::consts::TAU,
                ))
            } else if a.distance(arc.start()) == 0.0 && b.distance(arc.end()) == 0.0 {
                *seg
            } else {
                with_ends(seg, a, b)
            }
        }
    };
    if rev {
        s.reversed()
    } else {
        s
    }
}
