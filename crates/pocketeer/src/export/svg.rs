//! SVG previews: contours drawn with exact arcs (SVG's `A` command), y pointing up.

use crate::geom::{Aabb, Contour, Segment};
use std::fmt::Write;

/// A set of contours drawn in one style.
#[derive(Clone, Copy)]
pub struct Layer<'a> {
    /// Name shown as the group's id.
    pub name: &'a str,
    /// Stroke colour (any SVG colour).
    pub stroke: &'a str,
    /// Fill colour, or `none`.
    pub fill: &'a str,
    /// The contours.
    pub contours: &'a [Contour],
    /// Open paths.
    pub paths: &'a [Vec<Segment>],
}

/// The path data of one contour.
///
/// ```
/// use pocketeer::export::svg::path_data;
/// use pocketeer::geom::{Arc, Contour, Point, Segment};
/// let disc = Contour::new(vec![Segment::Arc(Arc::circle(Point::new(0.0, 0.0), 1.0))]);
/// assert!(path_data(&disc).starts_with("M1 0 A1 1 0 0 1 -1 0"));
/// ```
pub fn path_data(c: &Contour) -> String {
    let mut d = open_path_data(&c.segments);
    if !d.is_empty() {
        d.push_str(" Z");
    }
    d
}

/// The path data of segments joined end to start, not closed.
pub fn open_path_data(segments: &[Segment]) -> String {
    let mut d = String::new();
    let Some(first) = segments.first() else { return d };
    let p = first.start();
    let _ = write!(d, "M{} {}", num(p.x), num(p.y));
    for s in segments {
        match s {
            Segment::Line(l) => {
                let _ = write!(d, " L{} {}", num(l.end.x), num(l.end.y));
            }
            Segment::Arc(a) => {
                // SVG cannot draw a whole circle in one arc: draw it in halves.
                let halves = if a.sweep().abs() > std::f64::consts::PI * 1.5 {
                    2
                } else {
                    1
                };
                for h in 0..halves {
                    let piece = a.subsegment(h as f64 / halves as f64, (h + 1) as f64 / halves as f64);
                    let e = piece.end();
                    let large = u8::from(piece.sweep().abs() > std::f64::consts::PI);
                    let sweep = u8::from(piece.sweep() > 0.0);
                    let r = num(a.radius());
                    let _ = write!(d, " A{r} {r} 0 {large} {sweep} {} {}", num(e.x), num(e.y));
                }
            }
        }
    }
    d
}

fn num(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// An SVG document showing `layers`, scaled to fit, y up.
pub fn svg_document(layers: &[Layer]) -> String {
    let extent = layers
        .iter()
        .flat_map(|l| {
            l.contours
                .iter()
                .map(Contour::bbox)
                .chain(l.paths.iter().flatten().map(Segment::bbox))
        })
        .fold(Aabb::EMPTY, |b, c| b.union(&c));
    let extent = if extent.is_empty() {
        Aabb::from_points(Default::default(), Default::default())
    } else {
        extent
    };
    let margin = 0.05 * extent.width().max(extent.height()).max(1.0);
    let b = extent.inflated(margin);
    let stroke_width = 0.002 * b.width().max(b.height());
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="1000" height="{}">"#,
        num(b.min.x),
        num(-b.max.y),
        num(b.width()),
        num(b.height()),
        (1000.0 * b.height() / b.width().max(1e-9)).round()
    );
    let _ = writeln!(
        s,
        r#"<g transform="scale(1,-1)" stroke-width="{}" fill-rule="evenodd">"#,
        num(stroke_width)
    );
    for l in layers {
        let _ = writeln!(
            s,
            r#"<g id="{}" stroke="{}" fill="{}">"#,
            escape(l.name),
            escape(l.stroke),
            escape(l.fill)
        );
        // One path per layer, so that the even-odd fill leaves islands open.
        let mut d: Vec<String> = l.contours.iter().map(path_data).collect();
        d.extend(l.paths.iter().map(|p| open_path_data(p)));
        let _ = writeln!(s, r#"<path d="{}"/>"#, d.join(" "));
        let _ = writeln!(s, "</g>");
    }
    let _ = writeln!(s, "</g>\n</svg>");
    s
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('"', "&quot;")
}

/// The moves of `path` seen from above: feed moves and rapids, each as runs of segments.
pub fn toolpath_segments(path: &crate::toolpath::Toolpath) -> (Vec<Vec<Segment>>, Vec<Vec<Segment>>) {
    use crate::geom::{Arc, Line};
    use crate::toolpath::Move;
    let (mut feeds, mut rapids): (Vec<Vec<Segment>>, Vec<Vec<Segment>>) = (Vec::new(), Vec::new());
    let mut at = path.start;
    let mut last_rapid: Option<bool> = None;
    for m in &path.moves {
        let (a, b) = (at.xy(), m.to().xy());
        let seg = match *m {
            Move::Arc { center, sweep, .. } => {
                let v = a - center;
                Segment::Arc(Arc::new(center, v.length(), v.angle(), sweep))
            }
            _ => Segment::Line(Line::new(a, b)),
        };
        at = m.to();
        if seg.length() <= 0.0 {
            continue;
        }
        let rapid = matches!(m, Move::Rapid { .. });
        let runs = if rapid { &mut rapids } else { &mut feeds };
        match runs.last_mut() {
            Some(run) if last_rapid == Some(rapid) => run.push(seg),
            _ => runs.push(vec![seg]),
        }
        last_rapid = Some(rapid);
    }
    (feeds, rapids)
}
