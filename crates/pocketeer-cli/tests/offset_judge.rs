//! `pocketeer offset` judged as the issue judges it, on one drawing of each kind it names: the
//! drawing is written as DXF, offset by the command, the loops read back from its output, and
//! compared with the true boundary of the region eroded by d, found here independently of the
//! library by brute force.
//!
//! The oracle: every point at distance exactly d from the profile that lies inside the region
//! and no nearer than d to any element is on the eroded boundary, and every point of that
//! boundary lies on an element moved by d, a concentric arc of radius r ± d, or a circle of
//! radius d round an element's end. So points sampled along those curves and kept when valid
//! are samples of the true boundary; they must all lie on the loops read back (Hausdorff, one
//! way), every point of the loops must be at distance d from the profile and inside the region
//! (the other way), and the samples must fall into as many connected groups as there are loops.
//! Samples from which no step goes deeper than d are left out: where walls lie exactly 2d
//! apart the points between are at distance d but bound no area, and the offset drops them.
//! The geometry, distances and region test here are written for this test alone; only the
//! grouping of samples uses the library (`geom::cluster_points`, which the offset does not).

#[path = "../../pocketeer/tests/common/corpus.rs"]
mod corpus;
mod judge;

use judge::*;
use std::f64::consts::TAU;
use std::path::Path;
use std::process::Command;

/// How the drawing writes its contours.
#[derive(Clone, Copy, PartialEq)]
enum Style {
    /// Closed LWPOLYLINEs with bulges (full circles as CIRCLE).
    Polylines,
    /// Separate LINE and ARC entities in shuffled order, every other line drawn backwards.
    Shuffled,
}

/// One judged drawing: its contours in drawing units, each +1 (bounds material to remove) or
/// -1 (an island), the units (`$INSUNITS`: 4 mm, 1 inch) and the tool radius in mm.
#[derive(Clone)]
struct Case {
    name: &'static str,
    contours: Vec<(Vec<El>, i32)>,
    style: Style,
    insunits: i32,
    d: f64,
}

impl Case {
    fn mm(&self) -> f64 {
        if self.insunits == 1 {
            25.4
        } else {
            1.0
        }
    }

    fn dxf(&self) -> String {
        let mut s = format!(
            "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n{}\n0\nENDSEC\n",
            self.insunits
        );
        s += "0\nSECTION\n2\nENTITIES\n";
        let mut entities: Vec<String> = Vec::new();
        for (els, _) in &self.contours {
            if let [El::Arc { c, r, sweep, .. }] = els.as_slice() {
                if sweep.abs() >= TAU {
                    entities.push(format!(
                        "0\nCIRCLE\n8\nparts\n10\n{}\n20\n{}\n40\n{}\n",
                        c.0, c.1, r
                    ));
                    continue;
                }
            }
            match self.style {
                Style::Polylines => {
                    let mut e = format!("0\nLWPOLYLINE\n8\nparts\n90\n{}\n70\n1\n", els.len());
                    for el in els {
                        let p = el.start();
                        e += &format!("10\n{}\n20\n{}\n", p.0, p.1);
                        if let El::Arc { sweep, .. } = el {
                            e += &format!("42\n{}\n", (sweep / 4.0).tan());
                        }
                    }
                    entities.push(e);
                }
                Style::Shuffled => {
                    for (k, el) in els.iter().enumerate() {
                        entities.push(match *el {
                            El::Line(p, q) => {
                                let (p, q) = if k % 2 == 1 { (q, p) } else { (p, q) };
                                format!(
                                    "0\nLINE\n8\nparts\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n",
                                    p.0, p.1, q.0, q.1
                                )
                            }
                            El::Arc { c, r, a0, sweep } => {
                                // DXF arcs run counter-clockwise, in degrees.
                                let (from, to) = if sweep > 0.0 {
                                    (a0, a0 + sweep)
                                } else {
                                    (a0 + sweep, a0)
                                };
                                format!(
                                    "0\nARC\n8\nparts\n10\n{}\n20\n{}\n40\n{}\n50\n{}\n51\n{}\n",
                                    c.0,
                                    c.1,
                                    r,
                                    from.to_degrees(),
                                    to.to_degrees()
                                )
                            }
                        });
                    }
                }
            }
        }
        if self.style == Style::Shuffled {
            // A fixed shuffle: every seventh entity first, then the rest backwards.
            let (mut head, mut tail): (Vec<String>, Vec<String>) = (Vec::new(), Vec::new());
            for (k, e) in entities.into_iter().enumerate() {
                if k % 7 == 3 {
                    head.push(e);
                } else {
                    tail.push(e);
                }
            }
            tail.reverse();
            entities = head.into_iter().chain(tail).collect();
        }
        s + &entities.concat() + "0\nENDSEC\n0\nEOF\n"
    }

    /// The profile in millimetres, with each contour's sign.
    fn profile_mm(&self) -> Vec<(Vec<El>, i32)> {
        placed(&self.contours, self.mm(), 0.0, (0.0, 0.0))
    }
}

/// Every element of `contours` [`El::placed`].
fn placed(contours: &[(Vec<El>, i32)], k: f64, angle: f64, shift: P) -> Vec<(Vec<El>, i32)> {
    contours
        .iter()
        .map(|(els, sign)| (els.iter().map(|el| el.placed(k, angle, shift)).collect(), *sign))
        .collect()
}

/// Runs `pocketeer offset` on the case and judges its loops.
fn judge(case: &Case, dir: &Path) {
    let input = dir.join(format!("{}.dxf", case.name));
    std::fs::write(&input, case.dxf()).unwrap();
    let loops = offset_loops(&input, case.d, case.mm(), dir).unwrap_or_else(|e| panic!("{}: {e}", case.name));
    if let Err(e) = judge_loops(&Region::new(&case.profile_mm()), &loops, case.d, true) {
        panic!("{}: {e}", case.name);
    }
}

/// The loops `pocketeer offset` writes for `input` at distance `d` mm, read back in mm (`mm`:
/// millimetres per drawing unit).
fn offset_loops(input: &Path, d: f64, mm: f64, dir: &Path) -> Result<Vec<Vec<El>>, String> {
    let output = dir.join("loops.dxf");
    let res = Command::new(env!("CARGO_BIN_EXE_pocketeer"))
        .args(["offset", input.to_str().unwrap(), "--distance", &format!("{d}mm")])
        .args(["-o", output.to_str().unwrap()])
        .output()
        .unwrap();
    if !res.status.success() {
        return Err(String::from_utf8_lossy(&res.stderr).into_owned());
    }
    Ok(read_loops(&std::fs::read_to_string(&output).unwrap(), mm))
}

/// Islands whose facing edges lie 2d + `gap` apart (d = 3) beside a wall 2d + `gap` from one
/// of them and a small round island, all turned by 0.3 rad so that no coordinate is exact:
/// offsets that coincide to within the precision of a drawing.
fn near_2d(gap: f64) -> Vec<(Vec<El>, i32)> {
    let w = 6.0 + gap;
    let upright = [
        (rounded(0.0, 0.0, 100.0, 60.0, 2.0), 1),
        (rounded(w, 8.0, 40.0, 30.0, 2.0), -1),
        (rounded(40.0 + w, 20.0, 70.0, 45.0, 2.0), -1),
        (circle((44.0, 36.0), 0.45), -1),
    ];
    placed(&upright, 1.0, 0.3, (0.0, 0.0))
}

fn cases() -> Vec<Case> {
    let shuffled = vec![
        (rounded(0.0, 0.0, 120.0, 80.0, 10.0), 1),
        (circle((60.0, 40.0), 12.0), -1),
    ];
    let far = placed(&shuffled, 1.0, 0.0, (1e5, 1e5));
    let mut islands60: Vec<(Vec<El>, i32)> = vec![(rounded(0.0, 0.0, 200.0, 120.0, 6.0), 1)];
    for i in 0..10 {
        for j in 0..6 {
            islands60.push((circle((15.0 + 19.0 * i as f64, 13.0 + 19.0 * j as f64), 5.0), -1));
        }
    }
    let mm = |name, contours, style, d| Case {
        name,
        contours,
        style,
        insunits: 4,
        d,
    };
    vec![
        mm("shuffled", shuffled, Style::Shuffled, 3.0),
        mm("far", far, Style::Shuffled, 3.0),
        mm(
            "bulged",
            vec![
                (
                    bulged(&[
                        (0.0, 0.0, 0.0),
                        (80.0, 0.0, 0.6),
                        (80.0, 50.0, 0.0),
                        (0.0, 50.0, -0.3),
                    ]),
                    1,
                ),
                (
                    bulged(&[
                        (20.0, 20.0, 1.0),
                        (35.0, 20.0, 0.0),
                        (35.0, 30.0, 1.0),
                        (20.0, 30.0, 0.0),
                    ]),
                    -1,
                ),
            ],
            Style::Polylines,
            2.5,
        ),
        mm(
            "star",
            vec![(star((0.0, 0.0), 7, 50.0, 20.0), 1)],
            Style::Polylines,
            2.0,
        ),
        mm(
            "channels",
            vec![(
                bulged(&[
                    (0.0, 0.0, 0.0),
                    (60.0, 0.0, 0.0),
                    (60.0, 10.0, 0.0),
                    (55.0, 10.0, 0.0),
                    (55.0, 40.0, 0.0),
                    (50.0, 40.0, 0.0),
                    (50.0, 10.0, 0.0),
                    (30.0, 10.0, 0.0),
                    (30.0, 40.0, 0.0),
                    (26.1, 40.0, 0.0),
                    (26.1, 10.0, 0.0),
                    (0.0, 10.0, 0.0),
                ]),
                1,
            )],
            Style::Shuffled,
            2.0,
        ),
        mm(
            "bar",
            vec![
                (rect(0.0, 0.0, 100.0, 60.0), 1),
                (rect(3.0, 28.0, 97.0, 32.0), -1),
            ],
            Style::Polylines,
            3.0,
        ),
        mm(
            "fillets",
            vec![
                (rounded(0.0, 0.0, 70.0, 40.0, 1.0), 1),
                (rounded(20.0, 12.0, 50.0, 28.0, 0.8), -1),
            ],
            Style::Shuffled,
            3.0,
        ),
        mm(
            "gear",
            vec![
                (gear((0.0, 0.0), 24, 40.0, 46.0), 1),
                (circle((0.0, 0.0), 10.0), -1),
            ],
            Style::Polylines,
            1.5,
        ),
        mm("islands60", islands60, Style::Polylines, 2.0),
        mm(
            "pocket_in_island",
            vec![
                (rect(0.0, 0.0, 100.0, 100.0), 1),
                (rect(20.0, 20.0, 80.0, 80.0), -1),
                (rect(35.0, 35.0, 65.0, 65.0), 1),
            ],
            Style::Polylines,
            2.0,
        ),
        mm(
            "overlapping_islands",
            vec![
                (rect(0.0, 0.0, 100.0, 60.0), 1),
                (circle((40.0, 30.0), 12.0), -1),
                (circle((55.0, 30.0), 10.0), -1),
            ],
            Style::Polylines,
            2.0,
        ),
        mm(
            "island_near_wall",
            vec![(rect(0.0, 0.0, 100.0, 60.0), 1), (circle((50.0, 10.5), 10.0), -1)],
            Style::Polylines,
            3.0,
        ),
        mm(
            "arcs_only",
            vec![(
                bulged(&[
                    (0.0, 0.0, 0.3),
                    (60.0, 0.0, 0.3),
                    (60.0, 40.0, 0.3),
                    (0.0, 40.0, 0.3),
                ]),
                1,
            )],
            Style::Shuffled,
            3.0,
        ),
        mm(
            "wider_than_the_pocket",
            vec![(rounded(0.0, 0.0, 120.0, 80.0, 10.0), 1)],
            Style::Polylines,
            45.0,
        ),
        mm("islands_2d_apart", near_2d(0.0), Style::Polylines, 3.0),
        mm(
            "islands_2d_apart_and_a_hair",
            near_2d(3e-7),
            Style::Polylines,
            3.0,
        ),
        mm(
            "islands_2d_apart_less_a_hair",
            near_2d(-3e-7),
            Style::Polylines,
            3.0,
        ),
        Case {
            name: "inch",
            contours: vec![
                (rounded(0.0, 0.0, 4.0, 3.0, 0.25), 1),
                (circle((2.0, 1.5), 0.5), -1),
            ],
            style: Style::Polylines,
            insunits: 1,
            d: 3.0,
        },
    ]
}

#[test]
fn offsets_of_the_judged_kinds_of_drawing_match_an_independent_erosion() {
    let dir = tempfile::tempdir().unwrap();
    for case in cases() {
        judge(&case, dir.path());
        // And at two more distances, odd ones, smaller and larger.
        for k in [0.371, 1.913] {
            judge(
                &Case {
                    d: case.d * k,
                    contours: case.contours.clone(),
                    ..case
                },
                dir.path(),
            );
        }
    }
}

/// The same judgement on every drawing of a corpus folder that imports, at three distances,
/// with the region as pocketeer's importer reads it (the offset, not the import, is judged).
/// Ignored: it needs the folder, named by `POCKETEER_CORPUS`:
/// `POCKETEER_CORPUS=path/to/corpus cargo test --release -p pocketeer-cli --test offset_judge -- --ignored`
#[test]
#[ignore]
fn corpus_offsets_match_an_independent_erosion() {
    let files = corpus::corpus_from_env();
    let dir = tempfile::tempdir().unwrap();
    let mut bad = Vec::new();
    let mut judged = 0;
    for f in &files {
        let Ok(analysis) = pocketeer::analyze(&std::fs::read(f).unwrap(), &Default::default()) else {
            continue;
        };
        let el = |s: &pocketeer::geom::Segment| match s {
            pocketeer::geom::Segment::Line(l) => El::Line((l.start.x, l.start.y), (l.end.x, l.end.y)),
            pocketeer::geom::Segment::Arc(a) => El::Arc {
                c: (a.center().x, a.center().y),
                r: a.radius(),
                a0: a.start_angle(),
                sweep: a.sweep(),
            },
        };
        // Pockets are offset one by one, and may overlap: each is judged with the loops that
        // lie on it.
        let regions: Vec<Region> = analysis
            .nesting
            .pockets
            .iter()
            .map(|p| {
                let profile: Vec<(Vec<El>, i32)> = std::iter::once((&p.boundary, 1))
                    .chain(p.islands.iter().map(|i| (i, -1)))
                    .map(|(c, sign)| (c.segments.iter().map(el).collect(), sign))
                    .collect();
                Region::new(&profile)
            })
            .collect();
        for d in [0.5, 1.5, 3.0] {
            let verdict = offset_loops(f, d, analysis.drawing.units.mm(), dir.path()).and_then(|loops| {
                let on = |r: &Region, l: &Vec<El>| {
                    l.iter()
                        .flat_map(|e| e.samples(0.1))
                        .all(|p| (r.distance(p) - d).abs() <= 1e-5 && r.contains(p))
                };
                if let Some(l) = loops.iter().find(|l| !regions.iter().any(|r| on(r, l))) {
                    return Err(format!("a loop from {:?} lies on no pocket", l[0].start()));
                }
                for r in &regions {
                    let mine: Vec<Vec<El>> = loops.iter().filter(|l| on(r, l)).cloned().collect();
                    judge_loops(r, &mine, d, false)?;
                }
                Ok(loops.len())
            });
            eprintln!("{} at d = {d}: {verdict:?}", f.display());
            judged += 1;
            if let Err(e) = verdict {
                bad.push(format!("{} at d = {d}: {e}", f.display()));
            }
        }
    }
    eprintln!("{judged} offsets judged");
    assert!(bad.is_empty(), "{bad:#?}");
}
