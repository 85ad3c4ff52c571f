//! From one DXF entity to the curves it draws, in world XY of the entity's own space.

use super::curve::{ocs_to_world, Affine, Curve, EllipseArc, Nurbs};
use super::dxf::{Group, RawEntity};
use crate::geom::{Arc, Point, Vector};
use smallvec::SmallVec;
use std::f64::consts::TAU;

/// What reading one entity gave.
pub enum Drawn {
    /// It draws curves, handed out as they were read (possibly none, e.g. a one-point
    /// polyline); `closed` when they form a closed contour by themselves, in order (a closed
    /// polyline, a closed or periodic spline): such a contour is whole by construction, and is
    /// never chained with other elements nor cut by duplicate removal.
    Curves {
        /// True for a closed entity.
        closed: bool,
    },
    /// An entity type that draws no outline (text, dimension, hatch, ...).
    Ignored,
}

/// Values of one entity, by group code: its groups read once (an entity's groups are a span of
/// the file, read again on every pass over them).
pub struct Fields<'a>(SmallVec<[Group<'a>; 24]>);

impl<'a> Fields<'a> {
    /// The groups of `e`.
    pub fn of(e: &RawEntity<'a>) -> Self {
        Fields(e.groups().collect())
    }
    /// The first group with `code`.
    pub fn group(&self, code: i32) -> Option<&Group<'a>> {
        self.0.iter().find(|g| g.code == code)
    }
    /// The first value of `code` as a number.
    pub fn real(&self, code: i32) -> Option<f64> {
        self.group(code).and_then(Group::real)
    }
    /// The first value of `code` as a number, `default` when absent or not a number.
    pub fn real_or(&self, code: i32, default: f64) -> f64 {
        self.real(code).unwrap_or(default)
    }
    /// The first value of `code` as an integer, `default` when absent or not one.
    pub fn int_or(&self, code: i32, default: i64) -> i64 {
        self.group(code).and_then(Group::int).unwrap_or(default)
    }
    fn point(&self, code: i32) -> Option<Point> {
        Some(Point::new(self.real(code)?, self.real_or(code + 10, 0.0)))
    }
    fn extrusion(&self) -> [f64; 3] {
        extrusion([self.real(210), self.real(220), self.real(230)])
    }
    fn ocs(&self, elevation: f64) -> Affine {
        ocs_to_world(self.extrusion(), elevation)
    }
    /// Every value of `code`, in order.
    fn all(&self, code: i32) -> Vec<f64> {
        self.0
            .iter()
            .filter(|g| g.code == code)
            .map(|g| g.real().unwrap_or(f64::NAN))
            .collect()
    }
}

/// The curves of a drawing entity, each handed to `emit` in order (a polyline of a million
/// vertices is not first made a list). Errors are messages about this entity.
pub fn curves_of(e: &RawEntity, emit: &mut dyn FnMut(Curve)) -> Result<Drawn, String> {
    if e.kind == "LWPOLYLINE" {
        // Read in one pass: a polyline's groups are mostly its vertices' and may be millions.
        return Ok(lwpolyline(e, emit));
    }
    let f = Fields::of(e);
    let mut all = |curves: Vec<Curve>, closed: bool| {
        curves.into_iter().for_each(&mut *emit);
        Ok(Drawn::Curves { closed })
    };
    match e.kind.as_ref() {
        "LINE" => all(line(&f)?, false),
        "CIRCLE" | "ARC" => all(circle_or_arc(e, &f)?, false),
        "ELLIPSE" => {
            let curves = ellipse(&f)?;
            // A full ellipse is a contour by itself, as a closed spline is.
            let closed = curves
                .iter()
                .all(|c| matches!(c, Curve::Ellipse(e) if e.sweep.abs() == TAU));
            all(curves, closed)
        }
        "POLYLINE" => old_polyline(e, &f, emit),
        "SPLINE" => {
            let curves = spline(&f)?;
            // Closed (bit 1) or periodic (bit 2), and the curve really comes back to its start.
            let flagged = f.int_or(70, 0) & 3 != 0;
            let closed = flagged
                && curves
                    .iter()
                    .all(|c| matches!(c, Curve::Spline(s) if s.is_closed()));
            all(curves, closed)
        }
        // Text, dimensions, hatches, meshes, solids, images, ...: no outline.
        _ => Ok(Drawn::Ignored),
    }
}

fn line(f: &Fields) -> Result<Vec<Curve>, String> {
    let a = f.point(10).ok_or("LINE without a start point")?;
    let b = f.point(11).ok_or("LINE without an end point")?;
    Ok(vec![Curve::Line(a, b)])
}

fn circle_or_arc(e: &RawEntity, f: &Fields) -> Result<Vec<Curve>, String> {
    let c = f.point(10).ok_or("no centre")?;
    let r = f.real(40).ok_or("no radius")?;
    if r.is_nan() || r <= 0.0 {
        return Err(format!("radius {r} is not positive"));
    }
    let (t0, sweep) = if e.kind == "CIRCLE" {
        (0.0, TAU)
    } else {
        let a0 = f.real_or(50, 0.0).to_radians();
        let a1 = f.real_or(51, 360.0).to_radians();
        let mut sweep = (a1 - a0).rem_euclid(TAU);
        if sweep == 0.0 && a1 != a0 {
            sweep = TAU; // 0° to 360°: a whole circle written as an arc
        }
        (a0, sweep)
    };
    let arc = EllipseArc {
        center: c,
        u: Vector::new(r, 0.0),
        v: Vector::new(0.0, r),
        t0,
        sweep,
    };
    let ocs = f.ocs(f.real_or(30, 0.0));
    Ok(if sweep == 0.0 {
        vec![]
    } else {
        vec![Curve::Ellipse(arc.transformed(&ocs))]
    })
}

/// An ELLIPSE whose parameters span a full turn less than this many radians is a full ellipse.
const FULL_TURN_SLACK: f64 = 1e-5;

fn ellipse(f: &Fields) -> Result<Vec<Curve>, String> {
    let c = f.point(10).ok_or("no centre")?;
    let major = Vector::new(f.real_or(11, 0.0), f.real_or(21, 0.0));
    let major_z = f.real_or(31, 0.0);
    let ratio = f.real_or(40, 1.0);
    if major.length() == 0.0 || ratio.is_nan() || ratio <= 0.0 {
        return Err("degenerate ellipse (zero axis)".into());
    }
    let n = f.extrusion();
    // Minor axis = normal × major, scaled by the ratio; projected on XY.
    let minor = Vector::new(n[1] * major_z - n[2] * major.y, n[2] * major.x - n[0] * major_z) * ratio;
    let t0 = f.real_or(41, 0.0);
    let t1 = f.real_or(42, TAU);
    let mut sweep = (t1 - t0).rem_euclid(TAU);
    // 0 to 2π, or 0 to 6.28318 as a writer of six digits puts it (an arc short of a full turn
    // by 1e-5 radians is no arc anyone draws): a whole ellipse.
    if sweep == 0.0 || TAU - sweep < FULL_TURN_SLACK {
        sweep = TAU;
    }
    Ok(vec![Curve::Ellipse(EllipseArc {
        center: c,
        u: major,
        v: minor,
        t0,
        sweep,
    })])
}

fn lwpolyline(e: &RawEntity, emit: &mut dyn FnMut(Curve)) -> Drawn {
    let mut verts: Vec<(Point, f64)> = Vec::new();
    // The entity's own values, first of each as everywhere else.
    let (mut flags, mut elevation) = (None, None);
    let mut extrusion_groups = [None; 3];
    for g in e.groups() {
        match g.code {
            10 => verts.push((Point::new(g.real().unwrap_or(f64::NAN), 0.0), 0.0)),
            20 => {
                if let Some(v) = verts.last_mut() {
                    v.0.y = g.real().unwrap_or(f64::NAN);
                }
            }
            42 => {
                if let Some(v) = verts.last_mut() {
                    v.1 = g.real().unwrap_or(0.0);
                }
            }
            70 => flags = flags.or(Some(g)),
            38 => elevation = elevation.or(Some(g)),
            210 | 220 | 230 => {
                let k = (g.code / 10 - 21) as usize;
                extrusion_groups[k] = extrusion_groups[k].or(Some(g));
            }
            _ => {}
        }
    }
    let closed = flags.and_then(|g| g.int()).unwrap_or(0) & 1 == 1;
    let normal = extrusion(extrusion_groups.map(|g| g.and_then(|g| g.real())));
    let elevation = elevation.and_then(|g| g.real()).unwrap_or(0.0);
    polyline(&verts, closed, &ocs_to_world(normal, elevation), emit);
    Drawn::Curves { closed }
}

/// A POLYLINE with its VERTEX entities: 2D (bulges, in its OCS), 3D (projected), or a
/// spline-fit one (its fitted vertices); meshes draw no outline.
fn old_polyline(e: &RawEntity, f: &Fields, emit: &mut dyn FnMut(Curve)) -> Result<Drawn, String> {
    let flags = f.int_or(70, 0);
    if flags & (16 | 64) != 0 {
        return Ok(Drawn::Ignored); // polygon and polyface meshes are surfaces, not outlines
    }
    let is_3d = flags & 8 != 0;
    let spline_fit = flags & 4 != 0;
    let mut verts = Vec::new();
    for v in &e.vertices {
        let vf = Fields::of(v);
        let vflags = vf.int_or(70, 0);
        // A spline-fit polyline lists its frame (control) vertices too: draw the fitted ones.
        if spline_fit && vflags & 16 != 0 {
            continue;
        }
        let p = vf.point(10).ok_or("VERTEX without coordinates")?;
        verts.push((p, if is_3d { 0.0 } else { vf.real_or(42, 0.0) }));
    }
    let m = if is_3d {
        Affine::IDENTITY
    } else {
        f.ocs(f.real_or(30, 0.0))
    };
    let closed = flags & 1 == 1;
    polyline(&verts, closed, &m, emit);
    Ok(Drawn::Curves { closed })
}

/// The extrusion direction from the values of groups 210, 220 and 230, DXF's (0, 0, 1) for
/// those absent.
fn extrusion([x, y, z]: [Option<f64>; 3]) -> [f64; 3] {
    [x.unwrap_or(0.0), y.unwrap_or(0.0), z.unwrap_or(1.0)]
}

/// Lines and bulge arcs through `verts` (point, bulge to the next), mapped by `m`.
fn polyline(verts: &[(Point, f64)], closed: bool, m: &Affine, emit: &mut dyn FnMut(Curve)) {
    let n = verts.len();
    let count = if closed { n } else { n.saturating_sub(1) };
    for i in 0..count {
        let (a, bulge) = verts[i];
        let b = verts[(i + 1) % n].0;
        if a == b {
            continue;
        }
        match Arc::from_bulge(a, b, bulge) {
            Some(arc) => emit(Curve::Arc(arc).transformed(m)),
            None => emit(Curve::Line(m.point(a), m.point(b))),
        }
    }
}

fn spline(f: &Fields) -> Result<Vec<Curve>, String> {
    let degree = f.int_or(71, 3);
    if !(1..=super::curve::MAX_DEGREE as i64).contains(&degree) {
        return Err(format!("spline degree {degree} is not supported"));
    }
    let degree = degree as usize;
    let xs = f.all(10);
    let ys = f.all(20);
    let knots = f.all(40);
    if xs.is_empty() {
        // Only fit points: the curve is the cubic that interpolates them.
        let (fx, fy) = (f.all(11), f.all(21));
        if fx.len() != fy.len() {
            return Err("fit points with missing coordinates".into());
        }
        let fit: Vec<Point> = fx.iter().zip(&fy).map(|(&x, &y)| Point::new(x, y)).collect();
        if fit.iter().any(|p| !p.is_finite()) {
            return Err("a fit point is not a number".into());
        }
        return Ok(Nurbs::through(&fit).map(Curve::Spline).into_iter().collect());
    }
    if xs.len() != ys.len() {
        return Err("control points with missing coordinates".into());
    }
    let points: Vec<Point> = xs.iter().zip(&ys).map(|(&x, &y)| Point::new(x, y)).collect();
    let n = points.len();
    if n < degree + 1 {
        return Err(format!("{n} control points are too few for degree {degree}"));
    }
    if knots.len() != n + degree + 1 {
        return Err(format!(
            "{} knots where {n} control points of degree {degree} need {}",
            knots.len(),
            n + degree + 1
        ));
    }
    if knots.iter().any(|k| !k.is_finite()) || knots.windows(2).any(|w| w[1] < w[0]) {
        return Err("knot values are not a non-decreasing sequence of numbers".into());
    }
    let mut weights = f.all(41);
    if weights.len() != n {
        weights = vec![1.0; n];
    }
    if weights.iter().any(|w| w.is_nan() || *w <= 0.0 || !w.is_finite()) {
        return Err("spline weights must be positive numbers".into());
    }
    Ok(vec![Curve::Spline(Nurbs {
        degree,
        knots,
        points,
        weights,
    })])
}
