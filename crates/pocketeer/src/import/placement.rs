//! The elements of a drawing, written as the walk over model space places its curves: a line or
//! an arc becomes its element at once; an ellipse or a spline waits to be fitted with biarcs,
//! which [`Elements::finish`] does on every core and then sets in its place.

use super::curve::Curve;
use super::{Element, CURVE_TOLERANCE};
use crate::geom::{Aabb, Segment};

/// A curve waiting to be fitted, with what its elements will carry.
struct ToFit {
    /// How many elements come before it.
    before: usize,
    curve: Curve,
    layer: usize,
    source: usize,
    closed_group: Option<usize>,
}

/// Elements in the order their curves were placed.
pub struct Elements {
    /// Elements of the lines and arcs, in order.
    done: Vec<Element>,
    /// Curves to fit, in order.
    to_fit: Vec<ToFit>,
    /// Box round `done`.
    extent: Aabb,
}

/// Runs the fitting is cut into, at least one curve each: enough for the parallel map to share
/// them out (it works alone below 256 items).
const RUNS: usize = 1024;
/// Most curves in one run.
const MAX_CURVES_PER_RUN: usize = 64;

impl Elements {
    /// No element yet.
    pub fn new() -> Self {
        Elements {
            done: Vec::new(),
            to_fit: Vec::new(),
            extent: Aabb::EMPTY,
        }
    }

    /// Where the next curve goes, for [`Elements::set_group_since`]: the elements written and
    /// the curves waiting so far.
    pub fn mark(&self) -> (usize, usize) {
        (self.done.len(), self.to_fit.len())
    }

    /// Places `curve`, drawn on layer `layer` by source `source`.
    pub fn push(&mut self, curve: Curve, layer: usize, source: usize) {
        match curve.exact() {
            Some(segment) => {
                self.extent = self.extent.union(&segment.bbox());
                self.done.push(Element {
                    segment,
                    layer,
                    source,
                    closed_group: None,
                });
            }
            None => self.to_fit.push(ToFit {
                before: self.done.len(),
                curve,
                layer,
                source,
                closed_group: None,
            }),
        }
    }

    /// Gives the curves placed since `mark` the closed group `group`.
    pub fn set_group_since(&mut self, mark: (usize, usize), group: Option<usize>) {
        for e in &mut self.done[mark.0..] {
            e.closed_group = group;
        }
        for f in &mut self.to_fit[mark.1..] {
            f.closed_group = group;
        }
    }

    /// Every element in order, and the box round them. Fitting arcs to splines and ellipses is
    /// most of the time a drawing of traced art takes to read, and each curve is fitted alone:
    /// the curves are shared out among the cores in runs, each run writing one list. With
    /// nothing to fit, the list is the one written already.
    pub fn finish(self) -> (Vec<Element>, Aabb) {
        let Elements {
            done,
            to_fit,
            mut extent,
        } = self;
        if to_fit.is_empty() {
            return (done, extent);
        }
        let run = (to_fit.len() / RUNS).clamp(1, MAX_CURVES_PER_RUN);
        let runs: Vec<&[ToFit]> = to_fit.chunks(run).collect();
        let fitted = crate::parallel::map(&runs, |run| {
            let mut segments: Vec<Segment> = Vec::new();
            let mut elements = Vec::with_capacity(run.len());
            let mut counts = Vec::with_capacity(run.len());
            let mut extent = Aabb::EMPTY;
            for f in run.iter() {
                segments.clear();
                f.curve.to_segments(CURVE_TOLERANCE, &mut segments);
                counts.push(segments.len());
                elements.extend(segments.iter().map(|&segment| {
                    extent = extent.union(&segment.bbox());
                    Element {
                        segment,
                        layer: f.layer,
                        source: f.source,
                        closed_group: f.closed_group,
                    }
                }));
            }
            (elements, counts, extent)
        });
        let total = done.len() + fitted.iter().map(|(e, _, _)| e.len()).sum::<usize>();
        let mut out = Vec::with_capacity(total);
        let mut done = done.into_iter();
        let mut written = 0;
        let curves = to_fit.iter();
        let mut counts = fitted.iter().flat_map(|(_, c, _)| c.iter());
        let mut pieces = fitted.iter().flat_map(|(e, _, _)| e.iter());
        for f in curves {
            out.extend(done.by_ref().take(f.before - written));
            written = f.before;
            let n = counts.next().copied().unwrap_or(0);
            out.extend(pieces.by_ref().take(n).cloned());
        }
        out.extend(done);
        for (_, _, b) in &fitted {
            extent = extent.union(b);
        }
        (out, extent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Arc, Point};
    use crate::import::curve::Nurbs;

    fn spline(from: f64) -> Curve {
        let points: Vec<Point> = (0..5)
            .map(|i| Point::new(from + i as f64, (i as f64).sin()))
            .collect();
        Curve::Spline(Nurbs::through(&points).expect("distinct points"))
    }

    #[test]
    fn fitted_curves_keep_their_place_among_lines_and_arcs() {
        let mut e = Elements::new();
        e.push(spline(-10.0), 0, 0);
        e.push(Curve::Line(Point::new(0.0, 0.0), Point::new(1.0, 0.0)), 0, 1);
        let m = e.mark();
        e.push(spline(10.0), 1, 2);
        e.push(Curve::Arc(Arc::circle(Point::new(5.0, 5.0), 1.0)), 1, 3);
        e.set_group_since(m, Some(7));
        e.push(Curve::Line(Point::new(0.0, 0.0), Point::new(0.0, 1.0)), 0, 4);
        e.push(spline(20.0), 0, 5);
        let (elements, extent) = e.finish();
        let sources: Vec<usize> = elements.iter().map(|e| e.source).collect();
        let mut expected = sources.clone();
        expected.sort();
        assert_eq!(sources, expected, "elements in the order of their curves");
        for s in [0, 2, 5] {
            assert!(
                sources.iter().filter(|&&x| x == s).count() > 1,
                "spline {s} fitted"
            );
        }
        assert!(elements
            .iter()
            .all(|e| (e.closed_group == Some(7)) == (e.source == 2 || e.source == 3)));
        assert!(extent.min.x <= -10.0 && extent.max.x >= 24.0 && extent.max.y >= 6.0);
    }
}
