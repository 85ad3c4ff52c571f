//! SVG previews: contours drawn with exact arcs (SVG's `A` command), y pointing up, framed on
//! the drawing, with a legend and a scale bar below it.

use crate::geom::{Aabb, Contour, Point, Segment};
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
    /// What the legend calls it (no entry when empty).
    pub label: &'a str,
    /// Stroke width in drawing units; 0: a hairline of the drawing's size (see
    /// [`svg_document`]).
    pub width: f64,
    /// Dashed strokes.
    pub dash: bool,
    /// The picture is framed on the layers that say so (the drawing, not the tool's way to
    /// it from the machine's origin); on all of them when none does.
    pub frames: bool,
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
    let s = crate::fixed::fixed(x, 6);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// Width of a hairline, as a share of the framed extent's larger side.
const HAIRLINE: f64 = 0.0015;

/// The box of `layers` (their contours and paths).
fn extent_of<'a>(layers: impl Iterator<Item = &'a Layer<'a>>) -> Aabb {
    layers
        .flat_map(|l| {
            l.contours
                .iter()
                .map(Contour::bbox)
                .chain(l.paths.iter().flatten().map(Segment::bbox))
        })
        .fold(Aabb::EMPTY, |b, c| b.union(&c))
}

/// A length near `target` that reads well on a scale bar: 1, 2 or 5 times a power of ten.
///
/// ```
/// use pocketeer::export::svg::scale_length;
/// assert_eq!(scale_length(37.0), 20.0);
/// assert_eq!(scale_length(0.7), 0.5);
/// assert_eq!(scale_length(100.0), 100.0);
/// ```
pub fn scale_length(target: f64) -> f64 {
    if !(target.is_finite() && target > 0.0) {
        return 1.0;
    }
    let p = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v <= target * (1.0 + 1e-9))
        .unwrap_or(p)
}

/// An SVG document showing `layers`, framed on those that frame (see [`Layer::frames`]), y
/// up, with a legend of the labelled layers and a scale bar (in `unit`, e.g. "mm") below.
///
/// ```
/// use pocketeer::export::svg::{svg_document, Layer};
/// use pocketeer::geom::{Contour, Point};
/// let square = [Contour::polygon(&[
///     Point::new(0.0, 0.0), Point::new(100.0, 0.0), Point::new(100.0, 50.0), Point::new(0.0, 50.0),
/// ])];
/// let layer = Layer { name: "drawing", stroke: "black", fill: "none", contours: &square,
///     paths: &[], label: "pocket", width: 0.0, dash: false, frames: true };
/// let svg = svg_document(&[layer], "mm");
/// assert!(svg.contains(">pocket</text>"));
/// assert!(svg.contains(">20 mm</text>")); // the scale bar
/// ```
pub fn svg_document(layers: &[Layer], unit: &str) -> String {
    let framed = extent_of(layers.iter().filter(|l| l.frames));
    let extent = if framed.is_empty() {
        extent_of(layers.iter())
    } else {
        framed
    };
    let extent = if extent.is_empty() {
        Aabb::from_points(Default::default(), Point::new(1.0, 1.0))
    } else {
        extent
    };
    let size = extent.width().max(extent.height()).max(1e-6);
    let margin = 0.05 * size;
    let b = extent.inflated(margin);
    let hairline = HAIRLINE * size;
    // The legend: rows of two entries, then the scale bar, below the drawing.
    let labelled: Vec<&Layer> = layers
        .iter()
        .filter(|l| !l.label.is_empty() && (!l.contours.is_empty() || !l.paths.is_empty()))
        .collect();
    let font = 0.018 * b.width().max(0.6 * b.height());
    let row = 1.6 * font;
    let rows = labelled.len().div_ceil(2) + 1;
    let band = rows as f64 * row + 0.5 * row;
    let height = b.height() + band;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="1000" height="{}">"#,
        num(b.min.x),
        num(-b.max.y),
        num(b.width()),
        num(height),
        (1000.0 * height / b.width().max(1e-9)).round()
    );
    let _ = writeln!(
        s,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="white"/>"#,
        num(b.min.x),
        num(-b.max.y),
        num(b.width()),
        num(height)
    );
    let _ = writeln!(
        s,
        r#"<g transform="scale(1,-1)" fill-rule="evenodd" stroke-linecap="round" stroke-linejoin="round">"#
    );
    let width = |l: &Layer| if l.width > 0.0 { l.width } else { hairline };
    for l in layers {
        let dash = if l.dash {
            format!(
                r#" stroke-dasharray="{} {}""#,
                num(4.0 * width(l)),
                num(3.0 * width(l))
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            r#"<g id="{}" stroke="{}" fill="{}" stroke-width="{}"{dash}>"#,
            escape(l.name),
            escape(l.stroke),
            escape(l.fill),
            num(width(l))
        );
        // One path per layer, so that the even-odd fill leaves islands open.
        let mut d: Vec<String> = l.contours.iter().map(path_data).collect();
        d.extend(l.paths.iter().map(|p| open_path_data(p)));
        let _ = writeln!(s, r#"<path d="{}"/>"#, d.join(" "));
        let _ = writeln!(s, "</g>");
    }
    let _ = writeln!(s, "</g>");
    // Legend and scale bar, in the picture's own y-down units.
    let top = -b.min.y + 0.5 * row;
    let x0 = b.min.x + margin;
    let column = (b.width() - 2.0 * margin) / 2.0;
    let _ = writeln!(
        s,
        r#"<g id="legend" font-family="sans-serif" font-size="{}" fill="black">"#,
        num(font)
    );
    for (k, l) in labelled.iter().enumerate() {
        let x = x0 + (k % 2) as f64 * column;
        let y = top + (k / 2) as f64 * row + 0.5 * row;
        let swatch = 2.0 * font;
        let fill = if l.fill != "none" && l.contours.iter().any(|_| true) {
            format!(
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}" stroke="{}" stroke-width="{}"/>"#,
                num(x),
                num(y - 0.4 * font),
                num(swatch),
                num(0.8 * font),
                escape(l.fill),
                escape(if l.stroke == "none" { l.fill } else { l.stroke }),
                num(0.1 * font)
            )
        } else {
            format!(
                r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="{}"{}/>"#,
                num(x),
                num(y),
                num(x + swatch),
                num(y),
                escape(l.stroke),
                num(0.25 * font),
                if l.dash {
                    format!(r#" stroke-dasharray="{} {}""#, num(0.5 * font), num(0.3 * font))
                } else {
                    String::new()
                }
            )
        };
        let _ = writeln!(
            s,
            r#"{fill}<text x="{}" y="{}" dominant-baseline="middle">{}</text>"#,
            num(x + swatch + 0.5 * font),
            num(y),
            escape(l.label)
        );
    }
    let bar = scale_length(0.2 * extent.width().max(1e-6));
    let y = top + (rows - 1) as f64 * row + 0.5 * row;
    let _ = writeln!(
        s,
        r#"<path d="M{} {} V{} H{} V{}" fill="none" stroke="black" stroke-width="{}"/><text x="{}" y="{}" dominant-baseline="middle">{} {}</text>"#,
        num(x0),
        num(y - 0.4 * font),
        num(y),
        num(x0 + bar),
        num(y - 0.4 * font),
        num(0.15 * font),
        num(x0 + bar + 0.5 * font),
        num(y),
        num(bar),
        escape(unit)
    );
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
    use crate::toolpath::Move;
    let (mut feeds, mut rapids): (Vec<Vec<Segment>>, Vec<Vec<Segment>>) = (Vec::new(), Vec::new());
    let mut at = path.start;
    let mut last_rapid: Option<bool> = None;
    for m in &path.moves {
        let seg = m.planar(at);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Line, Point};

    #[test]
    fn the_picture_is_framed_on_the_drawing_not_on_the_way_to_it() {
        let square = [Contour::polygon(&[
            Point::new(100.0, 100.0),
            Point::new(200.0, 100.0),
            Point::new(200.0, 150.0),
            Point::new(100.0, 150.0),
        ])];
        let rapid = [vec![Segment::Line(Line::new(
            Point::new(0.0, 0.0),
            Point::new(120.0, 110.0),
        ))]];
        let layers = [
            Layer {
                name: "drawing",
                stroke: "black",
                fill: "none",
                contours: &square,
                paths: &[],
                label: "pocket",
                width: 0.0,
                dash: false,
                frames: true,
            },
            Layer {
                name: "rapids",
                stroke: "red",
                fill: "none",
                contours: &[],
                paths: &rapid,
                label: "rapids",
                width: 0.3,
                dash: true,
                frames: false,
            },
        ];
        let svg = svg_document(&layers, "mm");
        // 5 % of the larger side round the square: x from 95, y (flipped) from -155.
        assert!(svg.contains(r#"viewBox="95 -155 110 "#), "{svg}");
        // The rapid keeps its width in drawing units, dashed; the drawing gets a hairline.
        assert!(
            svg.contains(r#"stroke-width="0.3" stroke-dasharray="1.2 0.9""#),
            "{svg}"
        );
        assert!(
            svg.contains(r#"<g id="drawing" stroke="black" fill="none" stroke-width="0.15">"#),
            "{svg}"
        );
        assert!(svg.contains(">rapids</text>"));
    }
}
