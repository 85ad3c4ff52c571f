//! The interactive preview: one self-contained HTML page holding the drawing, the pockets,
//! a program and its report, drawn on a canvas by a script inside the page.
//!
//! The page needs no network: its script and style are inside it, a content security policy
//! forbids it every request, and the geometry travels packed ([`pack`]): the drawing's
//! contours flattened to points, the program's moves with their kinds ([`classify`]),
//! lines, feeds and the time each ends at in the time model of [`crate::machining_time`].
//! What the page shows and how it is driven is in `page.js`.
//!
//! [`classify`]: crate::simulate::classify

pub mod pack;

use crate::geom::{Contour, Pocket, Point, Segment};
use crate::simulate::classify::{classify_with_tools, MoveKind};
use crate::simulate::gcode::{Motion, ProgramMove};
use pack::{quantize, Cursor, Packer};
use serde::Serialize;

/// The page's script.
const SCRIPT: &str = include_str!("page.js");
/// The page's style.
const STYLE: &str = include_str!("page.css");

/// A place marked on the drawing, numbered in the page's list.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mark {
    /// What it is.
    pub kind: MarkKind,
    /// Where, mm.
    pub x: f64,
    /// Where, mm.
    pub y: f64,
    /// What to say of it.
    pub text: String,
}

/// Kinds of [`Mark`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MarkKind {
    /// A place the importer repaired (a gap closed, a crossing filled, a stroke removed).
    Repair,
    /// A pocket the program does not cut.
    NotCut,
    /// The deepest gouge into a wall or an island.
    Gouge,
    /// Material left where the tool could reach.
    Leftover,
    /// Anything else worth a look (a rapid into the stock, a plunge).
    Warning,
}

/// Everything the page shows.
#[derive(Debug, Clone)]
pub struct Preview<'a> {
    /// The page's title: the drawing and the program.
    pub title: String,
    /// Show lengths in inches (the program's unit) instead of millimetres.
    pub inches: bool,
    /// The tool's diameter, mm (the first tool's, in a program of several).
    pub tool_diameter: f64,
    /// In a program of several tools: from which move on each tool cuts, and its diameter.
    pub tool_changes: Vec<(usize, f64)>,
    /// The drawing's pockets, cut or not.
    pub pockets: &'a [Pocket],
    /// Which of them the program does not cut (indices).
    pub not_cut: Vec<usize>,
    /// Open chains of the drawing that were ignored.
    pub open_chains: Vec<Vec<Segment>>,
    /// Pieces of material left (polygons, outer ring first), from a check.
    pub leftovers: Vec<Vec<Vec<[f64; 2]>>>,
    /// Marked places.
    pub marks: Vec<Mark>,
    /// The program's moves.
    pub moves: &'a [ProgramMove],
    /// Seconds of dwell in the program, counted before the first move (where a spindle's
    /// wait is).
    pub dwell: f64,
    /// Rapid rate for the elapsed time, mm/min.
    pub rapid_rate: f64,
    /// The fixed cost of a retract, seconds.
    pub per_retract: f64,
    /// The summary: (what, value) pairs, in order.
    pub summary: Vec<(String, String)>,
    /// Further text (warnings, a check's report), shown as it is.
    pub report: String,
}

/// The page's data, as the script reads it.
#[derive(Serialize)]
struct PageData<'a> {
    title: &'a str,
    inches: bool,
    tool: f64,
    tools: Vec<(usize, f64)>,
    quantum: f64,
    extent: [f64; 4],
    summary: &'a [(String, String)],
    report: &'a str,
    marks: &'a [Mark],
    not_cut: &'a [usize],
    kinds: Vec<MoveKind>,
    pockets: PackedRings,
    open: PackedRings,
    leftovers: PackedRings,
    moves: PackedMoves,
}

/// Rings or polylines: how many, then for each its tag, its number of points and the points
/// as differences.
#[derive(Serialize)]
struct PackedRings {
    count: usize,
    data: String,
}

/// The moves: see [`pack_moves`].
#[derive(Serialize)]
struct PackedMoves {
    count: usize,
    start: [f64; 3],
    data: String,
}

/// Largest distance of a flattened arc from the true one, as a share of the drawing's size.
const CHORD_SHARE: f64 = 2e-5;

/// The page for `p`: a complete HTML document.
///
/// ```
/// use pocketeer::export::preview::{page, Preview};
/// use pocketeer::geom::{Contour, Point, Pocket};
/// use pocketeer::simulate::read_program;
/// let square = Contour::polygon(&[
///     Point::new(0.0, 0.0), Point::new(30.0, 0.0), Point::new(30.0, 20.0), Point::new(0.0, 20.0),
/// ]);
/// let pockets = [Pocket { boundary: square, islands: vec![] }];
/// let program = read_program("G0 X10 Y10 Z5\nG1 Z-1 F300\nG1 X20 F1000\nG0 Z5\n").unwrap();
/// let html = page(&Preview {
///     title: "square".into(), inches: false, tool_diameter: 6.0, tool_changes: vec![], pockets: &pockets, not_cut: vec![],
///     open_chains: vec![], leftovers: vec![], marks: vec![], moves: &program.moves, dwell: 0.0,
///     rapid_rate: 5000.0, per_retract: 0.5, summary: vec![], report: String::new(),
/// });
/// assert!(html.starts_with("<!DOCTYPE html>"));
/// assert!(html.contains("\"count\":3"));
/// assert!(!html.contains("src=\"http"));
/// ```
pub fn page(p: &Preview) -> String {
    let mut extent = crate::geom::Aabb::EMPTY;
    for c in p.pockets.iter().flat_map(Pocket::contours) {
        extent = extent.union(&c.bbox());
    }
    for s in p.open_chains.iter().flatten() {
        extent = extent.union(&s.bbox());
    }
    if extent.is_empty() {
        for m in p.moves {
            extent = extent.union(&m.footprint().bbox());
        }
    }
    if extent.is_empty() {
        extent = crate::geom::Aabb::from_points(Point::new(0.0, 0.0), Point::new(1.0, 1.0));
    }
    let chord = (CHORD_SHARE * extent.width().max(extent.height())).max(1e-4);
    let mut tools = vec![(0, p.tool_diameter)];
    tools.extend(p.tool_changes.iter().copied());
    tools.sort_by_key(|t| t.0);
    let radii: Vec<(usize, f64)> = tools.iter().map(|&(k, d)| (k, 0.5 * d)).collect();
    let kinds = classify_with_tools(p.moves, &radii);
    let data = PageData {
        title: &p.title,
        inches: p.inches,
        tool: p.tool_diameter,
        tools,
        quantum: pack::QUANTUM,
        extent: [extent.min.x, extent.min.y, extent.max.x, extent.max.y],
        summary: &p.summary,
        report: &p.report,
        marks: &p.marks,
        not_cut: &p.not_cut,
        kinds: MoveKind::ALL.to_vec(),
        pockets: pack_pockets(p.pockets, chord),
        open: pack_paths(&p.open_chains, chord),
        leftovers: pack_leftovers(&p.leftovers),
        moves: pack_moves(p.moves, &kinds, p.dwell, p.rapid_rate, p.per_retract),
    };
    // serde_json writes no raw '<', so "</script>" cannot occur in it; escape it anyway in
    // case a file name carries one.
    let json = serde_json::to_string(&data)
        .unwrap_or_else(|_| "{}".to_string())
        .replace("</", "<\\/");
    let title = html_escape(&p.title);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title} — pocketeer preview</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n\
         <script type=\"application/json\" id=\"data\">{json}</script>\n<script>\n{SCRIPT}</script>\n</body>\n</html>\n"
    )
}

/// `s` with the characters HTML gives a meaning escaped.
fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Packs one flattened ring or polyline: its tag, its number of points, the points.
fn pack_points(out: &mut Packer, tag: u64, points: &[[f64; 2]]) {
    out.uint(tag);
    out.uint(points.len() as u64);
    let mut c = Cursor::default();
    for q in points {
        c.point(out, q[0], q[1]);
    }
}

/// Every pocket's contours, tagged with the pocket's number times two, plus one for an island.
fn pack_pockets(pockets: &[Pocket], chord: f64) -> PackedRings {
    let mut out = Packer::default();
    let mut count = 0;
    for (i, p) in pockets.iter().enumerate() {
        for (k, c) in p.contours().enumerate() {
            pack_points(&mut out, 2 * i as u64 + u64::from(k > 0), &flattened(c, chord));
            count += 1;
        }
    }
    PackedRings {
        count,
        data: out.base64(),
    }
}

/// A contour as points (closed: the first is not repeated).
fn flattened(c: &Contour, chord: f64) -> Vec<[f64; 2]> {
    crate::simulate::polygon::flatten(&c.segments, chord)
}

/// Open paths as polylines, their last point included.
fn pack_paths(paths: &[Vec<Segment>], chord: f64) -> PackedRings {
    let mut out = Packer::default();
    for path in paths {
        let mut pts = crate::simulate::polygon::flatten(path, chord);
        if let Some(e) = path.last().map(Segment::end) {
            pts.push([e.x, e.y]);
        }
        pack_points(&mut out, 0, &pts);
    }
    PackedRings {
        count: paths.len(),
        data: out.base64(),
    }
}

/// Leftover pieces: rings tagged with the piece's number times two, plus one for a hole.
fn pack_leftovers(shapes: &[Vec<Vec<[f64; 2]>>]) -> PackedRings {
    let mut out = Packer::default();
    let mut count = 0;
    for (i, s) in shapes.iter().enumerate() {
        for (k, ring) in s.iter().enumerate() {
            pack_points(&mut out, 2 * i as u64 + u64::from(k > 0), ring);
            count += 1;
        }
    }
    PackedRings {
        count,
        data: out.base64(),
    }
}

/// Bit of a move's head: an arc, with its centre and sweep following.
const ARC: u64 = 8;
/// Bit of a move's head: a new feed rate follows.
const NEW_FEED: u64 = 16;

/// The moves: for each, a head (the kind's index in [`MoveKind::ALL`] and the bits [`ARC`]
/// and [`NEW_FEED`]), the line's difference from the last move's, the end's difference from
/// the start in quanta (x, y, z); for an arc its centre's offset from the start (x, y) and its
/// sweep in microradians; for a new feed, the feed in thousandths of a mm/min (0: none); then
/// the milliseconds the move ends at less those the last move ended at.
fn pack_moves(
    moves: &[ProgramMove],
    kinds: &[MoveKind],
    dwell: f64,
    rapid_rate: f64,
    per_retract: f64,
) -> PackedMoves {
    let mut out = Packer::default();
    let start = moves.first().map_or([0.0; 3], |m| [m.from.x, m.from.y, m.from.z]);
    let mut at = [quantize(start[0]), quantize(start[1]), quantize(start[2])];
    let mut line = 0i64;
    let mut feed: Option<Option<f64>> = None;
    let mut seconds = dwell;
    let mut millis = 0i64;
    for (m, kind) in moves.iter().zip(kinds) {
        let code = MoveKind::ALL.iter().position(|k| k == kind).unwrap_or(0) as u64;
        let arc = match m.motion {
            Motion::Arc { center, sweep } => Some((center, sweep)),
            _ => None,
        };
        let new_feed = m.motion != Motion::Rapid && feed != Some(m.feed);
        out.uint(code | if arc.is_some() { ARC } else { 0 } | if new_feed { NEW_FEED } else { 0 });
        out.int(m.line as i64 - line);
        line = m.line as i64;
        let to = [quantize(m.to.x), quantize(m.to.y), quantize(m.to.z)];
        for a in 0..3 {
            out.int(to[a] - at[a]);
        }
        if let Some((c, sweep)) = arc {
            out.int(quantize(c.x) - at[0]);
            out.int(quantize(c.y) - at[1]);
            out.int((sweep * 1e6).round() as i64);
        }
        at = to;
        if new_feed {
            out.uint(m.feed.map_or(0, |f| (f * 1e3).round().max(0.0) as u64));
            feed = Some(m.feed);
        }
        seconds += m.seconds(rapid_rate, per_retract);
        let ms = (seconds * 1e3).round() as i64;
        out.int(ms - millis);
        millis = ms;
    }
    PackedMoves {
        count: moves.len(),
        start,
        data: out.base64(),
    }
}
