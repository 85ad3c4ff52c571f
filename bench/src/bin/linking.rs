//! The tool paths themselves, not the time to make them: machining time at fixed rates, cutting
//! length, retracts and the tool's engagement of the program `pocket` writes with default
//! flags, on drawings of the kinds the shop cuts, each checked for gouge and leftover.
//! `cargo run --release --bin linking [-- --only NAME] [--dxf DIR] [--freecad DIR]`
//!
//! `--dxf DIR` writes each drawing to `DIR/<name>.dxf` (and `DIR/drawings.tsv`: name, tool
//! diameter, stepover %); `--freecad DIR` reads FreeCAD's program
//! for it from `DIR/<name>.nc` (made by `scripts/freecad-compare`, which runs both) and adds its
//! time, retracts, check and our time's ratio to it, both checked and timed alike.
//!
//! `--breakdown` prints instead where each program's time goes: the plan's loops, its clean-up
//! paths and spots, each cut once at the feed; the feed moves at depth off the plan; the rest
//! of the cutting (entries, descents at the feed, helices at the cutting feed); rapids. With
//! `--freecad DIR`, FreeCAD's time beside it.
//!
//! "off the plan" is the length of feed moves at depth that follow no loop, clean-up path or
//! spot of the plan: links, steps from loop to loop, ways out to clean-up paths and back.
//!
//! The rates are the ones the FreeCAD comparison of issue 18 uses: feed 1000, plunge 300,
//! rapid 5000 mm/min, entries, retracts and links all counted by length; the first time column
//! has no fixed cost per retract (a time from lengths alone, as that comparison computes it),
//! the second adds the half second a retract that `pocket` weighs its choices with by default.

use pocketeer::clear::ClearParams;
use pocketeer::export::dxf::{write_dxf, LayeredContour};
use pocketeer::geom::{Pocket, Segment, SegmentIndex, Tolerance};
use pocketeer::import::Units;
use pocketeer::job::pocket_job;
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Dialect, ProgramSettings, ProgramUnits};
use pocketeer::simulate::CheckReport;
use pocketeer::simulate::{check_program, read_program, CheckParams};
use pocketeer::toolpath::{Move, Toolpath};
use pocketeer_bench::cases::{self, Ring};
use std::f64::consts::{PI, TAU};
use std::path::PathBuf;

const FEED: f64 = 1000.0;
const PLUNGE: f64 = 300.0;
const RAPID: f64 = 5000.0;

struct Drawing {
    name: String,
    pockets: Vec<Pocket>,
    tool: f64,
    stepover: f64,
}

fn pocket_of(rings: Vec<Ring>) -> Pocket {
    pocketeer_bench::pocket(&cases::Case {
        name: String::new(),
        rings,
        distances: Vec::new(),
    })
}

fn rect_ccw(x: f64, y: f64, w: f64, h: f64) -> Ring {
    vec![(x, y, 0.0), (x + w, y, 0.0), (x + w, y + h, 0.0), (x, y + h, 0.0)]
}

fn rect_cw(x: f64, y: f64, w: f64, h: f64) -> Ring {
    vec![(x, y, 0.0), (x, y + h, 0.0), (x + w, y + h, 0.0), (x + w, y, 0.0)]
}

fn circle_cw(cx: f64, cy: f64, r: f64) -> Ring {
    vec![(cx + r, cy, -1.0), (cx - r, cy, -1.0)]
}

fn circle_ccw(cx: f64, cy: f64, r: f64) -> Ring {
    vec![(cx + r, cy, 1.0), (cx - r, cy, 1.0)]
}

/// A rectangle with corner fillets of radius `f`, counter-clockwise.
fn filleted(w: f64, h: f64, f: f64) -> Ring {
    let b = (PI / 8.0).tan();
    vec![
        (f, 0.0, 0.0),
        (w - f, 0.0, b),
        (w, f, 0.0),
        (w, h - f, b),
        (w - f, h, 0.0),
        (f, h, b),
        (0.0, h - f, 0.0),
        (0.0, f, b),
    ]
}

fn star(points: usize, outer: f64, inner: f64) -> Ring {
    (0..2 * points)
        .map(|k| {
            let a = PI / 2.0 + k as f64 * PI / points as f64;
            let r = if k % 2 == 0 { outer } else { inner };
            (100.0 + r * a.cos(), 100.0 + r * a.sin(), 0.0)
        })
        .collect()
}

/// Two overlapping circles of radius `r`, centres `gap` apart, as one clockwise island: the
/// outline of their union (two arcs of more than half a turn).
fn two_circles_cw(cx: f64, cy: f64, r: f64, gap: f64) -> Ring {
    let h = (r * r - 0.25 * gap * gap).sqrt();
    let half = (0.5 * gap / r).acos(); // half the angle the meeting points span at a centre
    let sweep = TAU - 2.0 * half;
    let b = -(sweep / 4.0).tan();
    vec![(cx, cy + h, b), (cx, cy - h, b)]
}

/// A `w` x `h` rectangle with `n` round islands of radius 5 to 13 mm placed at random from
/// `seed`, at least 3 mm from one another and from the walls (so some necks are narrower
/// than a 6 mm tool).
fn scattered_islands(w: f64, h: f64, n: usize, seed: u64) -> Vec<Ring> {
    // A linear congruential generator (Knuth's MMIX constants), the high bits as a fraction.
    let mut state = seed;
    let mut unit = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let gap = 3.0;
    let mut islands: Vec<(f64, f64, f64)> = Vec::new();
    for _ in 0..10_000 {
        if islands.len() == n {
            break;
        }
        let r = 5.0 + 8.0 * unit();
        let x = r + gap + (w - 2.0 * (r + gap)) * unit();
        let y = r + gap + (h - 2.0 * (r + gap)) * unit();
        if islands
            .iter()
            .all(|&(a, b, q)| ((x - a).powi(2) + (y - b).powi(2)).sqrt() >= r + q + gap)
        {
            islands.push((x, y, r));
        }
    }
    let mut rings = vec![rect_ccw(0.0, 0.0, w, h)];
    rings.extend(islands.into_iter().map(|(x, y, r)| circle_cw(x, y, r)));
    rings
}

fn drawings() -> Vec<Drawing> {
    let mut out = Vec::new();
    let rect_islands = cases::rounded_with_islands().rings;
    for s in [0.3, 0.5, 0.6, 0.7, 0.8, 0.9] {
        out.push(Drawing {
            name: format!("rectangle 200x120, 8 round islands, {:.0} %", 100.0 * s),
            pockets: vec![pocket_of(rect_islands.clone())],
            tool: 6.0,
            stepover: s,
        });
    }
    // Rectangles with round islands scattered at random (a fixed seed each), at the stepovers
    // of the shop: the layout above is the one the linking was tuned on, these are not.
    for (k, (w, h, n)) in [(180.0, 110.0, 7), (160.0, 100.0, 5), (220.0, 130.0, 9)]
        .into_iter()
        .enumerate()
    {
        let rings = scattered_islands(w, h, n, 0x5eed + k as u64);
        for s in [0.4, 0.7, 0.9] {
            out.push(Drawing {
                name: format!(
                    "rectangle {w:.0}x{h:.0}, {n} scattered islands, {:.0} %",
                    100.0 * s
                ),
                pockets: vec![pocket_of(rings.clone())],
                tool: 6.0,
                stepover: s,
            });
        }
    }
    out.push(Drawing {
        name: "7-point star".into(),
        pockets: vec![pocket_of(vec![star(7, 80.0, 35.0)])],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "48-tooth gear, hub island".into(),
        pockets: vec![pocket_of(cases::gear().rings)],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "channel round two islands".into(),
        pockets: vec![pocket_of(vec![
            rect_ccw(0.0, 0.0, 160.0, 80.0),
            rect_cw(10.0, 10.0, 65.0, 60.0),
            rect_cw(85.0, 10.0, 65.0, 60.0),
        ])],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "10x6 island grid".into(),
        pockets: vec![pocket_of(cases::grid_of_islands().rings)],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "pocket in an island".into(),
        pockets: vec![
            pocket_of(vec![
                rect_ccw(0.0, 0.0, 120.0, 100.0),
                rect_cw(30.0, 25.0, 60.0, 50.0),
            ]),
            pocket_of(vec![rect_ccw(40.0, 35.0, 40.0, 30.0)]),
        ],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "overlapping islands".into(),
        pockets: vec![pocket_of(vec![
            rect_ccw(0.0, 0.0, 140.0, 90.0),
            two_circles_cw(45.0, 45.0, 18.0, 20.0),
            two_circles_cw(100.0, 45.0, 15.0, 12.0),
        ])],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "small fillets (r 1 mm)".into(),
        pockets: vec![pocket_of(vec![filleted(100.0, 60.0, 1.0)])],
        tool: 6.0,
        stepover: 0.4,
    });
    out.push(Drawing {
        name: "two pockets".into(),
        pockets: vec![
            pocket_of(vec![rect_ccw(0.0, 0.0, 60.0, 40.0)]),
            pocket_of(vec![circle_ccw(120.0, 20.0, 25.0)]),
        ],
        tool: 6.0,
        stepover: 0.4,
    });
    // Thirty rings (a 20 mm hole in a 12 mm wide ring), drawn in a scrambled order.
    let rings = (0..30usize)
        .map(|k| {
            let s = (k * 11) % 30;
            let (x, y) = (25.0 + 50.0 * (s % 6) as f64, 25.0 + 50.0 * (s / 6) as f64);
            pocket_of(vec![circle_ccw(x, y, 22.0), circle_cw(x, y, 10.0)])
        })
        .collect();
    out.push(Drawing {
        name: "30 rings, drawn in a scrambled order".into(),
        pockets: rings,
        tool: 6.0,
        stepover: 0.4,
    });
    let mut plate = vec![rect_ccw(0.0, 0.0, 400.0, 300.0)];
    for i in 0..20 {
        for j in 0..15 {
            plate.push(circle_cw(10.0 + 20.0 * i as f64, 10.0 + 20.0 * j as f64, 4.0));
        }
    }
    out.push(Drawing {
        name: "plate 400x300, 300 holes of 8 mm".into(),
        pockets: vec![pocket_of(plate)],
        tool: 6.0,
        stepover: 0.4,
    });
    out
}

/// The drawing's file name: its name in lower case, words joined by dashes.
fn slug(name: &str) -> String {
    let words: Vec<String> = name
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_ascii_lowercase)
        .collect();
    words.join("-")
}

/// The drawing as DXF: every pocket's boundary and islands on layer 0.
fn dxf_of(d: &Drawing) -> String {
    let contours: Vec<LayeredContour> = d
        .pockets
        .iter()
        .flat_map(|p| std::iter::once(&p.boundary).chain(&p.islands))
        .map(|contour| LayeredContour { layer: "0", contour })
        .collect();
    write_dxf(&contours, Units::Millimeters)
}

/// The value of flag `name`, when given.
fn flag(args: &[String], name: &str) -> Option<String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let only = flag(&args, "--only");
    let dxf_dir = flag(&args, "--dxf").map(PathBuf::from);
    let freecad_dir = flag(&args, "--freecad").map(PathBuf::from);
    let breakdown = args.iter().any(|a| a == "--breakdown");
    let tol = Tolerance::default();
    if breakdown {
        println!(
            "| drawing | time s | loops s | clean-up paths s | spots s | off the plan s | entries and the rest of the feed s | rapids s | FreeCAD time s |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    } else if freecad_dir.is_some() {
        println!(
            "| drawing | time s | FreeCAD time s | ratio | loops and clean-up alone s | its ratio | retracts | FreeCAD retracts | cutting mm | off the plan mm | FreeCAD cutting mm | FreeCAD gouge mm | FreeCAD thickest leftover mm |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    } else {
        println!(
            "| drawing | time s | time s, 0.5 s a retract | cutting mm | off the plan mm | rapid mm | retracts | p95 engagement ° | p95 touching stock ° | max ° | > 150 % | touching no stock % | gouge mm | thickest leftover mm |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    }
    let (mut total_time, mut total_with, mut total_retracts) = (0.0, 0.0, 0);
    let (mut freecad_time, mut ours_beside_freecad, mut paths_time) = (0.0, 0.0, 0.0);
    let mut breakdown_total = BreakdownTotal::new();
    // With --dxf: each drawing's file name, tool diameter and stepover (%), for the script
    // that has FreeCAD pocket them.
    let mut manifest = String::new();
    for d in drawings() {
        if only.as_ref().is_some_and(|o| !d.name.contains(o.as_str())) {
            continue;
        }
        if let Some(dir) = &dxf_dir {
            let path = dir.join(format!("{}.dxf", slug(&d.name)));
            std::fs::write(&path, dxf_of(&d)).expect("the drawing is written");
            manifest.push_str(&format!(
                "{}\t{}\t{:.0}\n",
                slug(&d.name),
                d.tool,
                100.0 * d.stepover
            ));
        }
        let r = 0.5 * d.tool;
        let clear = ClearParams {
            tool_radius: r,
            stepover: d.stepover * d.tool,
            allowance: 0.0,
        };
        let link = LinkParams {
            depth: 3.0,
            step_down: 3.0,
            safe_z: 5.0,
            feed_height: 1.0,
            direction: Direction::Climb,
            entry: Entry::Helix,
            ramp_angle: 3f64.to_radians(),
            // As `pocket` links by default: half a second a retract.
            time: pocketeer::machining_time::TimeModel {
                feed: FEED,
                plunge_feed: PLUNGE,
                rapid: RAPID,
                per_retract: pocketeer::machining_time::DEFAULT_RETRACT_SECONDS,
            },
        };
        let job = match pocket_job(&d.pockets, &clear, &link, &tol) {
            Ok(j) => j,
            Err(e) => {
                println!("| {} | failed: {e} |", d.name);
                continue;
            }
        };
        let settings = ProgramSettings {
            units: ProgramUnits::Millimetres,
            feed: FEED,
            plunge_feed: PLUNGE,
            spindle_wait: 0.0,
            ..ProgramSettings::default()
        };
        let text = write_gcode(&job.linked.toolpath, &settings, Dialect::LinuxCnc);
        let report = checked(&d, &text, &tol).expect("our program reads back");
        let e = &report.engagement;
        let off = off_the_plan(&job.linked.toolpath, &job.plans, -3.0);
        let with =
            report.seconds + pocketeer::machining_time::DEFAULT_RETRACT_SECONDS * report.retracts as f64;
        total_time += report.seconds;
        total_with += with;
        total_retracts += report.retracts;
        let theirs = freecad_dir.as_ref().map(|dir| freecad_report(dir, &d, &tol));
        if breakdown {
            let parts = Breakdown::of(&job.plans, &link.time, &job.linked.toolpath, off, report.seconds);
            let freecad = theirs.and_then(Result::ok).map(|f| f.seconds);
            parts.print_row(&d.name, freecad);
            breakdown_total.add(&parts, freecad);
            continue;
        }
        if let Some(theirs) = theirs {
            // The least time any linking of these paths can take: every loop and clean-up
            // path at the feed, with no entry, link or rapid.
            let paths = paths_seconds(&job.plans);
            match theirs {
                Ok(f) => {
                    freecad_time += f.seconds;
                    ours_beside_freecad += report.seconds;
                    paths_time += paths;
                    println!(
                        "| {} | {:.1} | {:.1} | {:.3} | {:.1} | {:.3} | {} | {} | {:.1} | {off:.1} | {:.1} | {:.4} | {:.4} |",
                        d.name,
                        report.seconds,
                        f.seconds,
                        report.seconds / f.seconds,
                        paths,
                        paths / f.seconds,
                        report.retracts,
                        f.retracts,
                        report.cut_length,
                        f.cut_length,
                        f.gouge,
                        f.thickest
                    );
                }
                Err(e) => println!("| {} | {:.1} | no FreeCAD program: {e} |", d.name, report.seconds),
            }
            continue;
        }
        println!(
            "| {} | {:.1} | {:.1} | {:.1} | {off:.1} | {:.1} | {} | {:.0} | {:.0} | {:.0} | {:.1} | {:.1} | {:.4} | {:.4} |",
            d.name,
            report.seconds,
            with,
            report.cut_length,
            report.rapid_length,
            report.retracts,
            e.p95_deg,
            e.p95_in_contact_deg,
            e.max_deg,
            e.above_150_percent,
            e.untouched_percent,
            report.gouge,
            report.thickest
        );
    }
    if let Some(dir) = &dxf_dir {
        std::fs::write(dir.join("drawings.tsv"), manifest).expect("the list of drawings is written");
    }
    if breakdown {
        breakdown_total.sum.print_row("total", breakdown_total.freecad);
    } else if freecad_dir.is_some() {
        println!(
            "| total | {ours_beside_freecad:.1} | {freecad_time:.1} | {:.3} | {paths_time:.1} | {:.3} | | | | | | | |",
            ours_beside_freecad / freecad_time,
            paths_time / freecad_time
        );
    } else {
        println!("| total | {total_time:.1} | {total_with:.1} | | | | {total_retracts} | | | | | | | |");
    }
}

/// Length of the feed moves at depth `z` that follow no loop, clean-up path or spot of
/// `plans`: links, steps from loop to loop, the ways out to clean-up paths and back, helix
/// run-outs. Each move is sampled every half millimetre and counted where most of its samples
/// lie off every path of the plan (farther than a micrometre).
fn off_the_plan(path: &Toolpath, plans: &[pocketeer::clear::ClearPlan], z: f64) -> f64 {
    let segments: Vec<Segment> = (plans.iter().flat_map(|p| &p.parts))
        .flat_map(|part| {
            let paths = part.paths().flat_map(|p| &p.segments);
            part.loops().flat_map(|c| &c.segments).chain(paths)
        })
        .copied()
        .collect();
    let index = SegmentIndex::new(&segments);
    let mut at = path.start;
    let mut off = 0.0;
    for m in &path.moves {
        let to = m.to();
        let at_depth = (at.z - z).abs() < 1e-6 && (to.z - z).abs() < 1e-6;
        if at_depth && !matches!(m, Move::Rapid { .. }) {
            let length = m.length(at);
            let n = ((length / 0.5).ceil() as usize).max(2);
            let seen = m.planar(at);
            let away = (0..=n)
                .filter(|&k| !index.any_within(seen.point_at(k as f64 / n as f64), 1e-3))
                .count();
            if 2 * away > n + 1 {
                off += length;
            }
        }
        at = to;
    }
    off
}

/// Where a program's time goes, seconds (see the `--breakdown` flag).
#[derive(Default)]
struct Breakdown {
    seconds: f64,
    loops: f64,
    cleanups: f64,
    spots: f64,
    off_plan: f64,
    rest: f64,
    rapids: f64,
}

impl Breakdown {
    /// The program `path` for `plans`, `off` mm of it at depth off the plan, `seconds` in all,
    /// timed in `time`.
    fn of(
        plans: &[pocketeer::clear::ClearPlan],
        time: &pocketeer::machining_time::TimeModel,
        path: &Toolpath,
        off: f64,
        seconds: f64,
    ) -> Breakdown {
        let lengths = PlanLengths::of(plans);
        let at_feed = |mm: f64| time.feed_seconds(mm, time.feed);
        let (loops, cleanups, spots) = (
            at_feed(lengths.loops),
            at_feed(lengths.cleanups),
            at_feed(lengths.spots),
        );
        let rapids = time.moves(path.moves_from(0)).rapid;
        let off_plan = at_feed(off);
        Breakdown {
            seconds,
            loops,
            cleanups,
            spots,
            off_plan,
            rest: seconds - loops - cleanups - spots - off_plan - rapids,
            rapids,
        }
    }

    /// The table's row `name`, with FreeCAD's time where there is one.
    fn print_row(&self, name: &str, freecad: Option<f64>) {
        println!(
            "| {name} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {} |",
            self.seconds,
            self.loops,
            self.cleanups,
            self.spots,
            self.off_plan,
            self.rest,
            self.rapids,
            freecad.map_or_else(|| "-".to_string(), |f| format!("{f:.1}")),
        );
    }
}

/// The sum of the `--breakdown` table's rows; FreeCAD's time only while every drawing has a
/// program of FreeCAD's.
struct BreakdownTotal {
    sum: Breakdown,
    freecad: Option<f64>,
}

impl BreakdownTotal {
    fn new() -> BreakdownTotal {
        BreakdownTotal {
            sum: Breakdown::default(),
            freecad: Some(0.0),
        }
    }

    fn add(&mut self, b: &Breakdown, freecad: Option<f64>) {
        let s = &mut self.sum;
        s.seconds += b.seconds;
        s.loops += b.loops;
        s.cleanups += b.cleanups;
        s.spots += b.spots;
        s.off_plan += b.off_plan;
        s.rest += b.rest;
        s.rapids += b.rapids;
        self.freecad = self.freecad.zip(freecad).map(|(t, f)| t + f);
    }
}

/// Lengths of a plan's paths, mm: its loops, clean-up paths and spots.
struct PlanLengths {
    loops: f64,
    cleanups: f64,
    spots: f64,
}

impl PlanLengths {
    fn of(plans: &[pocketeer::clear::ClearPlan]) -> PlanLengths {
        let parts = || plans.iter().flat_map(|p| &p.parts);
        // From +0: an empty sum is -0.
        let length = |segments: &mut dyn Iterator<Item = &Segment>| segments.fold(0.0, |t, s| t + s.length());
        PlanLengths {
            loops: length(&mut parts().flat_map(|p| p.loops()).flat_map(|c| &c.segments)),
            cleanups: length(&mut parts().flat_map(|p| &p.cleanups).flat_map(|c| &c.segments)),
            spots: length(&mut parts().flat_map(|p| &p.spots).flat_map(|s| &s.path.segments)),
        }
    }
}

/// Seconds to cut the loops and clean-up paths of `plans` at the feed, nothing else.
fn paths_seconds(plans: &[pocketeer::clear::ClearPlan]) -> f64 {
    let lengths = PlanLengths::of(plans);
    (lengths.loops + lengths.cleanups) / FEED * 60.0
}

/// FreeCAD's program for the drawing `d`, `DIR/<name>.nc`, replayed as [`checked`] does ours.
fn freecad_report(dir: &std::path::Path, d: &Drawing, tol: &Tolerance) -> Result<CheckReport, String> {
    let path = dir.join(format!("{}.nc", slug(&d.name)));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    checked(d, &text, tol)
}

/// The program `text` replayed against the drawing: time at the fixed rates from lengths alone
/// (no cost per retract), gouge and leftover.
fn checked(d: &Drawing, text: &str, tol: &Tolerance) -> Result<CheckReport, String> {
    let program = read_program(text).map_err(|e| format!("cannot read the program: {e}"))?;
    let params = CheckParams {
        tool_radius: 0.5 * d.tool,
        depth: Some(3.0),
        gouge_tolerance: 0.01,
        leftover_tolerance: 0.05,
        rapid_rate: RAPID,
        per_retract: 0.0,
    };
    check_program(&d.pockets, &program, &params, tol).map_err(|e| format!("the check fails: {e}"))
}
