//! Which of the directions sampled round the tool an earlier tool position covered, found as
//! whole ranges of directions at once instead of one direction at a time.
//!
//! The engagement ([`super::engagement`]) asks, for each of the [`DIRECTIONS`] points
//! `q = c + r·u` round the tool (c its centre, r its radius, u at (k + ½) steps from the x
//! axis), whether an earlier move swept it: whether `q` lies nearer than ρ to the move's
//! path. Every piece of that region is a disc or a half-plane, and a point of the tool's
//! circle lies in either exactly when `cos(θ − φ) ≥ λ` for an angle φ and a bound λ that
//! depend on the piece alone. So each piece gives one range of directions (one `acos`), and a
//! path's region is a few of them combined:
//! - a line from A to B: the discs round A and B, and the strip beside it (between the
//!   normals at A and B, nearer the line than ρ), the intersection of four half-planes;
//! - an arc: the discs round its ends, and the ring between radii R − ρ and R + ρ inside the
//!   wedge of its sweep (two half-planes through the centre).
//!
//! The answer is the point test's for every direction except one lying within rounding of a
//! region's edge.

use crate::geom::rounding::{ceil, floor};
use crate::geom::{Point, Segment, Vector};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Directions sampled round the tool: one a degree.
pub const DIRECTIONS: usize = 360;

const WORDS: usize = DIRECTIONS.div_ceil(64);

/// A set of the [`DIRECTIONS`] directions: bit k is the direction at (k + ½)·360°/DIRECTIONS.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Directions([u64; WORDS]);

impl Directions {
    /// No direction.
    pub const NONE: Directions = Directions([0; WORDS]);

    /// Every direction.
    pub fn all() -> Directions {
        let mut d = Directions([u64::MAX; WORDS]);
        d.trim();
        d
    }

    /// How many directions are in the set.
    pub fn count(&self) -> usize {
        self.0.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// True when direction `k` is in the set.
    pub fn contains(&self, k: usize) -> bool {
        k < DIRECTIONS && self.0[k / 64] >> (k % 64) & 1 == 1
    }

    /// True when every direction is in the set.
    pub fn is_all(&self) -> bool {
        self.count() == DIRECTIONS
    }

    /// The directions in both.
    pub fn and(self, o: Directions) -> Directions {
        Directions(std::array::from_fn(|i| self.0[i] & o.0[i]))
    }

    /// The directions in either.
    pub fn or(self, o: Directions) -> Directions {
        Directions(std::array::from_fn(|i| self.0[i] | o.0[i]))
    }

    /// The directions not in the set.
    pub fn not(self) -> Directions {
        let mut d = Directions(std::array::from_fn(|i| !self.0[i]));
        d.trim();
        d
    }

    /// The directions within `w` radians of the angle `phi` (all of them from π on).
    pub fn around(phi: f64, w: f64) -> Directions {
        if w.is_nan() || w < 0.0 || !phi.is_finite() {
            return Directions::NONE;
        }
        if w >= PI {
            return Directions::all();
        }
        // Direction k is at (k + ½)·step: those from phi − w to phi + w.
        let per_radian = DIRECTIONS as f64 / TAU;
        let first = ceil((phi - w) * per_radian - 0.5);
        let last = floor((phi + w) * per_radian - 0.5);
        if last < first {
            return Directions::NONE;
        }
        let (first, last) = (first as i64, last as i64);
        let n = ((last - first) as usize + 1).min(DIRECTIONS);
        let start = first.rem_euclid(DIRECTIONS as i64) as usize;
        let mut d = Directions::NONE;
        d.set_run(start, n.min(DIRECTIONS - start));
        if start + n > DIRECTIONS {
            d.set_run(0, start + n - DIRECTIONS);
        }
        d
    }

    /// The directions u with `cos(angle(u) − phi) ≥ lambda`.
    fn cos_at_least(phi: f64, lambda: f64) -> Directions {
        if lambda <= -1.0 {
            Directions::all()
        } else if lambda > 1.0 || lambda.is_nan() {
            Directions::NONE
        } else {
            Directions::around(phi, lambda.acos())
        }
    }

    /// Sets the `n` directions from `start` (with `start + n ≤ DIRECTIONS`).
    fn set_run(&mut self, start: usize, n: usize) {
        let mut k = start;
        let end = start + n;
        while k < end {
            let (word, bit) = (k / 64, k % 64);
            let take = (64 - bit).min(end - k);
            let mask = if take == 64 {
                u64::MAX
            } else {
                ((1u64 << take) - 1) << bit
            };
            self.0[word] |= mask;
            k += take;
        }
    }

    /// Clears the bits past the last direction.
    fn trim(&mut self) {
        let spare = WORDS * 64 - DIRECTIONS;
        if spare > 0 {
            self.0[WORDS - 1] &= u64::MAX >> spare;
        }
    }
}

/// The unit vector of each direction, by index: direction k at (k + ½)·360°/[`DIRECTIONS`]
/// from the x axis, made once.
pub fn unit_vectors() -> &'static [Vector] {
    static TABLE: std::sync::OnceLock<Vec<Vector>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let step = TAU / DIRECTIONS as f64;
        (0..DIRECTIONS)
            .map(|k| Vector::from_angle((k as f64 + 0.5) * step))
            .collect()
    })
}

/// The tool's circle: its centre and radius, the points sampled round it being
/// `center + radius·u_k`.
#[derive(Debug, Clone, Copy)]
pub struct ToolCircle {
    /// Centre.
    pub center: Point,
    /// Radius.
    pub radius: f64,
}

impl ToolCircle {
    /// The directions whose point lies nearer than `rho` to `p`.
    pub fn near_point(&self, p: Point, rho: f64) -> Directions {
        let v = p - self.center;
        let d = v.length();
        let r = self.radius;
        if d == 0.0 {
            return if r < rho {
                Directions::all()
            } else {
                Directions::NONE
            };
        }
        // |q − p|² = d² + r² − 2·r·d·cos(θ − φ) < ρ².
        Directions::cos_at_least(v.angle(), (d * d + r * r - rho * rho) / (2.0 * r * d))
    }

    /// The directions whose point lies farther than `rho` from `p` (the other side of
    /// [`ToolCircle::near_point`]).
    fn beyond_point(&self, p: Point, rho: f64) -> Directions {
        self.near_point(p, rho).not()
    }

    /// The directions whose point q has `n·(q − p) ≥ 0`, for a unit vector `n` at angle
    /// `phi`.
    fn half_plane(&self, n: Vector, phi: f64, p: Point) -> Directions {
        // n·(c − p) + r·cos(θ − φ) ≥ 0.
        Directions::cos_at_least(phi, -n.dot(self.center - p) / self.radius)
    }

    /// The directions whose point lies nearer than `rho` to the segment `s` at a point between
    /// its ends (beside a line, across an arc): with the discs round the ends, the points
    /// nearer than `rho` to the segment.
    fn beside(&self, s: &Segment, rho: f64) -> Directions {
        match s {
            Segment::Line(l) => {
                let (a, b) = (l.start, l.end);
                let Some(d) = (b - a).normalized() else {
                    return Directions::NONE;
                };
                let n = d.perp();
                let phi = d.angle();
                // Between the normals at A and B, and within ρ of the line on either side.
                self.half_plane(d, phi, a)
                    .and(self.half_plane(-d, phi + PI, b))
                    .and(self.half_plane(n, phi + FRAC_PI_2, a - n * rho))
                    .and(self.half_plane(-n, phi - FRAC_PI_2, a + n * rho))
            }
            Segment::Arc(arc) => {
                let c = arc.center();
                let big = arc.radius() + rho;
                let ring = self.near_point(c, big);
                let ring = if arc.radius() > rho {
                    ring.and(self.beyond_point(c, arc.radius() - rho))
                } else {
                    ring
                };
                ring.and(self.wedge(c, arc.start_angle(), arc.sweep()))
            }
        }
    }

    /// The directions whose point lies in the wedge from `c` swept from the angle `from` by
    /// `sweep` (either way).
    fn wedge(&self, c: Point, from: f64, sweep: f64) -> Directions {
        if sweep.abs() >= TAU * (1.0 - 1e-12) {
            return Directions::all();
        }
        // Counter-clockwise from `lo` by |sweep|.
        let lo = if sweep >= 0.0 { from } else { from + sweep };
        let hi = lo + sweep.abs();
        // Left of the ray at `lo`, right of the ray at `hi`.
        let left = self.half_plane(Vector::from_angle(lo + FRAC_PI_2), lo + FRAC_PI_2, c);
        let right = self.half_plane(Vector::from_angle(hi - FRAC_PI_2), hi - FRAC_PI_2, c);
        if sweep.abs() <= PI {
            left.and(right)
        } else {
            left.or(right)
        }
    }
}

/// The directions round one tool position swept by the segments added so far, each nearer
/// than `rho` to a segment (see the module's documentation).
///
/// Segments that follow one another end to start (the moves of a program, in order) share the
/// disc round their common end: it is worked out once.
#[derive(Debug, Clone)]
pub struct Swept {
    circle: ToolCircle,
    rho: f64,
    set: Directions,
    last_end: Option<(Point, Directions)>,
}

impl Swept {
    /// Nothing swept yet round `circle`.
    pub fn new(circle: ToolCircle, rho: f64) -> Swept {
        Swept {
            circle,
            rho,
            set: Directions::NONE,
            last_end: None,
        }
    }

    /// Adds the directions `s` sweeps.
    pub fn add(&mut self, s: &Segment) {
        let start = match self.last_end {
            Some((p, d)) if p == s.start() => d,
            _ => self.circle.near_point(s.start(), self.rho),
        };
        let end = self.circle.near_point(s.end(), self.rho);
        self.last_end = Some((s.end(), end));
        self.set = self.set.or(start).or(end);
        if !self.set.is_all() {
            self.set = self.set.or(self.circle.beside(s, self.rho));
        }
    }

    /// The directions swept so far.
    pub fn directions(&self) -> Directions {
        self.set
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{distance_from_segment, Arc, Line};
    use proptest::prelude::*;

    fn swept_by(circle: ToolCircle, segments: &[Segment], rho: f64) -> Directions {
        let mut swept = Swept::new(circle, rho);
        for s in segments {
            swept.add(s);
        }
        swept.directions()
    }

    /// Every direction whose point is clearly inside or clearly outside agrees with the point
    /// test; the ones within `slack` of the edge may go either way.
    fn agrees(circle: &ToolCircle, s: &Segment, rho: f64) -> Result<(), String> {
        let got = swept_by(*circle, std::slice::from_ref(s), rho);
        let slack = 1e-9 * (1.0 + circle.radius + rho);
        for k in 0..DIRECTIONS {
            let q = circle.center + unit_vectors()[k] * circle.radius;
            let d = distance_from_segment(s, q);
            if (d - rho).abs() > slack && got.contains(k) != (d < rho) {
                return Err(format!(
                    "direction {k}: distance {d}, rho {rho}, set says {}",
                    got.contains(k)
                ));
            }
        }
        Ok(())
    }

    #[test]
    fn a_range_across_zero_wraps_round() {
        let d = Directions::around(0.0, 2.0f64.to_radians());
        // Directions at 0.5° and 1.5°, and at 358.5° and 359.5°.
        assert_eq!(d.count(), 4);
        assert!(d.contains(0) && d.contains(1) && d.contains(358) && d.contains(359));
        assert_eq!(Directions::around(1.0, PI).count(), DIRECTIONS);
        assert_eq!(Directions::all().not(), Directions::NONE);
    }

    #[test]
    fn the_tool_behind_itself_covers_the_back_half() {
        // The move so far ends at the tool's centre: the half behind is covered.
        let c = Point::new(5.0, 2.0);
        let circle = ToolCircle {
            center: c,
            radius: 3.0,
        };
        let s = Segment::Line(Line::new(Point::new(-5.0, 2.0), c));
        let covered = swept_by(circle, &[s], 3.0 * (1.0 - 1e-9));
        assert_eq!(covered.count(), 180);
        assert!(covered.contains(180) && !covered.contains(0));
    }

    #[test]
    fn lines_and_arcs_of_each_kind_agree_with_the_point_test() {
        let circle = ToolCircle {
            center: Point::new(0.3, -0.2),
            radius: 3.0,
        };
        let p = Point::new;
        let segments = [
            Segment::Line(Line::new(p(-6.0, 1.0), p(6.0, 1.5))),
            Segment::Line(Line::new(p(0.1, 0.1), p(0.2, 0.15))),
            Segment::Line(Line::new(p(4.0, 4.0), p(4.5, 4.1))),
            Segment::Arc(Arc::new(p(0.0, 0.0), 2.4, 0.3, 2.0)),
            Segment::Arc(Arc::new(p(1.0, 0.0), 5.4, 0.3, -4.0)),
            Segment::Arc(Arc::new(p(-1.0, 0.5), 0.5, 1.0, 5.0)),
            Segment::Arc(Arc::circle(p(2.0, 1.0), 4.0)),
        ];
        for s in &segments {
            for rho in [0.5, 2.0, 3.0 * (1.0 - 1e-9), 7.0] {
                agrees(&circle, s, rho).unwrap_or_else(|e| panic!("{s:?}: {e}"));
            }
        }
    }

    #[test]
    fn segments_end_to_start_sweep_what_each_sweeps_alone() {
        // The disc round a shared end is worked out once: the union is the same.
        let circle = ToolCircle {
            center: Point::new(0.5, 0.0),
            radius: 3.0,
        };
        let p = Point::new;
        let a = Segment::Line(Line::new(p(-4.0, 2.0), p(-1.0, 2.5)));
        let b = Segment::Arc(Arc::new(p(-1.0, 0.0), 2.5, FRAC_PI_2, -1.0));
        let c = Segment::Line(Line::new(b.end(), p(4.0, -3.0)));
        let together = swept_by(circle, &[a, b, c], 1.5);
        let apart = [a, b, c].iter().fold(Directions::NONE, |d, s| {
            d.or(swept_by(circle, std::slice::from_ref(s), 1.5))
        });
        assert_eq!(together, apart);
        assert!(together.count() > 0 && !together.is_all());
    }

    proptest! {
        #[test]
        fn any_line_or_arc_agrees_with_the_point_test(
            ax in -8.0..8.0f64, ay in -8.0..8.0f64, bx in -8.0..8.0f64, by in -8.0..8.0f64,
            radius in 0.05..9.0f64, start in -7.0..7.0f64, sweep in -6.9..6.9f64,
            arc in any::<bool>(), rho in 0.1..6.0f64, r in 0.5..4.0f64,
        ) {
            let s = if arc {
                Segment::Arc(Arc::new(Point::new(ax, ay), radius, start, sweep))
            } else {
                Segment::Line(Line::new(Point::new(ax, ay), Point::new(bx, by)))
            };
            let circle = ToolCircle { center: Point::new(0.1, -0.3), radius: r };
            prop_assert!(agrees(&circle, &s, rho).is_ok(), "{:?}", agrees(&circle, &s, rho));
        }
    }
}
