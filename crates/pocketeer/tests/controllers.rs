//! The controllers must take every program we write, with every option: dwell, tool, coolant,
//! park, inches. GRBL 1.1's rules are written out here (the words it knows, one motion and one
//! word of each kind per line, a feed before the first feed move, arc ends on their circle as
//! its error 33 demands, lines of at most 80 characters); LinuxCNC's own interpreter (`rs274`,
//! Debian's linuxcnc-uspace) reads them in an ignored test.

mod common;

use common::shapes::{circle_cw, rect, star};
use pocketeer::clear::ClearParams;
use pocketeer::geom::Pocket;
use pocketeer::geom::{Point, Tolerance};
use pocketeer::link::{Direction, Entry, LinkParams};
use pocketeer::post::{write_gcode, Coolant, Dialect, ProgramSettings, ProgramUnits};

/// Programs for `dialect`: two pockets, passes, an allowance, each entry kind, both
/// directions, millimetres and inches, with and without the options.
fn programs(dialect: Dialect) -> Vec<(String, String)> {
    let pockets = vec![
        Pocket {
            boundary: rect(0.0, 0.0, 70.0, 40.0),
            islands: vec![
                circle_cw(20.0, 20.0, 6.0),
                rect(40.0, 12.0, 55.0, 28.0).reversed(),
            ],
        },
        Pocket {
            boundary: pocketeer::geom::Contour::new(
                star(7, 30.0, 14.0)
                    .segments
                    .iter()
                    .map(|s| s.translated(pocketeer::geom::Vector::new(120.0, 20.0)))
                    .collect(),
            ),
            islands: vec![],
        },
    ];
    let mut out = Vec::new();
    for (k, (entry, direction, units)) in [
        (Entry::Helix, Direction::Climb, ProgramUnits::Millimetres),
        (Entry::Ramp, Direction::Conventional, ProgramUnits::Inches),
        (Entry::Plunge, Direction::Climb, ProgramUnits::Inches),
    ]
    .into_iter()
    .enumerate()
    {
        let clear = ClearParams {
            tool_radius: 3.0,
            stepover: 2.4 + k as f64,
            allowance: 0.25 * k as f64,
        };
        let link = LinkParams {
            depth: 4.0,
            step_down: 1.5,
            safe_z: 5.0,
            feed_height: 1.0,
            direction,
            entry,
            ramp_angle: 3f64.to_radians(),
            time: pocketeer::machining_time::TimeModel::default(),
        };
        let job = pocketeer::job::pocket_job(&pockets, &clear, &link, &Tolerance::default()).expect("job");
        let options = k > 0;
        let settings = ProgramSettings {
            units,
            feed: 1200.0,
            plunge_feed: 300.0,
            spindle: 18000.0,
            safe_z: 5.0,
            header: vec![format!("case {k}"), "a comment (with parentheses)".into()],
            spindle_wait: if options { 1.5 } else { 0.0 },
            tool: options.then_some(7),
            coolant: if options { Coolant::Flood } else { Coolant::Off },
            park: options.then_some(Point::new(-20.0, 150.0)),
        };
        out.push((
            format!("case {k}"),
            write_gcode(&job.linked.toolpath, &settings, dialect),
        ));
    }
    out
}

/// Why GRBL 1.1 would refuse `program`, if it would: the first offending line.
fn grbl_refusal(program: &str) -> Option<String> {
    let mut unit = 1.0;
    let mut feed_set = false;
    let mut pos: [Option<f64>; 3] = [None; 3];
    let mut motion = None;
    for (n, raw) in program.lines().enumerate() {
        let line = n + 1;
        if raw.len() > 80 {
            return Some(format!("line {line}: {} characters", raw.len()));
        }
        // Comments: parentheses (not nested) and ';'.
        let mut text = String::new();
        let mut depth = 0;
        for c in raw.chars() {
            match c {
                '(' if depth == 0 => depth = 1,
                '(' => return Some(format!("line {line}: nested comment")),
                ')' if depth == 1 => depth = 0,
                ';' if depth == 0 => break,
                c if depth == 0 && !c.is_whitespace() => text.push(c.to_ascii_uppercase()),
                _ => {}
            }
        }
        if depth != 0 {
            return Some(format!("line {line}: unclosed comment"));
        }
        let mut words: Vec<(char, String)> = Vec::new();
        let mut chars = text.chars().peekable();
        while let Some(l) = chars.next() {
            let mut v = String::new();
            while let Some(&c) = chars
                .peek()
                .filter(|c| c.is_ascii_digit() || **c == '.' || **c == '-')
            {
                v.push(c);
                chars.next();
            }
            if !l.is_ascii_alphabetic() || v.is_empty() || v.parse::<f64>().is_err() {
                return Some(format!("line {line}: bad word {l}{v}"));
            }
            words.push((l, v));
        }
        let mut seen = std::collections::HashSet::new();
        let (mut xyz, mut ij) = ([None; 3], [None::<f64>; 2]);
        let mut motion_here = None;
        let mut dwell = false;
        let mut p = None;
        for (l, v) in &words {
            let x: f64 = v.parse().unwrap_or(f64::NAN);
            let group = match l {
                'G' => match v.as_str() {
                    "0" | "1" | "2" | "3" => {
                        motion_here = Some(x as u32);
                        "motion"
                    }
                    "4" => {
                        dwell = true;
                        "non-modal"
                    }
                    "17" => "plane",
                    "20" | "21" => {
                        unit = if v == "20" { 25.4 } else { 1.0 };
                        "units"
                    }
                    "90" | "91" => "distance",
                    "91.1" => "arc distance",
                    "94" => "feed mode",
                    "40" => "cutter compensation",
                    "49" | "43.1" => "tool length",
                    "54" => "coordinate system",
                    "80" => "motion",
                    other => return Some(format!("line {line}: GRBL has no G{other}")),
                },
                'M' => match v.as_str() {
                    "0" | "1" | "2" | "30" => "stopping",
                    "3" | "4" | "5" => "spindle",
                    "8" | "9" => "coolant",
                    other => return Some(format!("line {line}: GRBL 1.1 has no M{other}")),
                },
                'X' | 'Y' | 'Z' => {
                    xyz[(*l as u8 - b'X') as usize] = Some(x * unit);
                    "axis"
                }
                'I' | 'J' => {
                    ij[(*l as u8 - b'I') as usize] = Some(x * unit);
                    "offset"
                }
                'F' => {
                    if x <= 0.0 {
                        return Some(format!("line {line}: F{v}"));
                    }
                    feed_set = true;
                    "F"
                }
                'S' => "S",
                'T' => {
                    if !(0.0..=255.0).contains(&x) || x.fract() != 0.0 {
                        return Some(format!("line {line}: tool T{v} beyond 255"));
                    }
                    "T"
                }
                'P' => {
                    p = Some(x);
                    "P"
                }
                'N' => "N",
                other => return Some(format!("line {line}: GRBL has no {other} word")),
            };
            let key = match (*l, group) {
                ('X' | 'Y' | 'Z' | 'I' | 'J', _) => l.to_string(),
                (_, g) => g.to_string(),
            };
            if !seen.insert(key) {
                return Some(format!("line {line}: two words of one kind ({group}) in {raw}"));
            }
        }
        if dwell && !p.is_some_and(|p| p >= 0.0) {
            return Some(format!("line {line}: G4 without a P of zero or more"));
        }
        if let Some(m) = motion_here {
            motion = Some(m);
        }
        if xyz.iter().all(Option::is_none) {
            continue;
        }
        let m = match motion {
            Some(m) => m,
            None => return Some(format!("line {line}: a move without a motion mode")),
        };
        if m != 0 && !feed_set {
            return Some(format!("line {line}: feed move before any F (error 22)"));
        }
        let target: Vec<Option<f64>> = (0..3).map(|k| xyz[k].or(pos[k])).collect();
        if m >= 2 {
            let (Some(x0), Some(y0)) = (pos[0], pos[1]) else {
                return Some(format!("line {line}: arc from an unknown place"));
            };
            if ij.iter().all(Option::is_none) {
                return Some(format!("line {line}: arc without I or J"));
            }
            let (cx, cy) = (x0 + ij[0].unwrap_or(0.0), y0 + ij[1].unwrap_or(0.0));
            let (x1, y1) = (target[0].unwrap_or(x0), target[1].unwrap_or(y0));
            let (r0, r1) = ((x0 - cx).hypot(y0 - cy), (x1 - cx).hypot(y1 - cy));
            // GRBL's error 33: the ends' radii differ by more than 0.005 mm and 0.1 %.
            if (r0 - r1).abs() > 0.005 && (r0 - r1).abs() > 0.001 * r0 {
                return Some(format!(
                    "line {line}: arc end off its circle by {} mm",
                    (r0 - r1).abs()
                ));
            }
        }
        pos.copy_from_slice(&target[..3]);
    }
    None
}

#[test]
fn grbl_takes_every_program_with_every_option() {
    for (name, g) in programs(Dialect::Grbl) {
        assert_eq!(grbl_refusal(&g), None, "{name}");
        assert!(!g.contains("M6") && !g.contains("M7"), "{name}");
    }
}

#[test]
fn the_grbl_rules_refuse_what_grbl_refuses() {
    let ok = "G21\nG90 G94 G17\nG0 Z5\nM3 S1000\nG4 P2\nM8\nG0 X10 Y0\nG1 Z-1 F300\nG3 X-10 Y0 I-10 J0\nM5\nM9\nM2\n";
    assert_eq!(grbl_refusal(ok), None);
    for (bad, why) in [
        ("G21\nT1 M6\n", "no M6"),
        ("G21\nM7\n", "no M7"),
        ("G21\nG0 X0 Y0 Z0\nG1 X5\n", "error 22"),
        ("G21\nG0 X10 Y0 Z0\nG3 X-11 Y0 I-10 J0 F100\n", "off its circle"),
        ("G21\nG0 G1 X1\n", "two words"),
        ("G21\nG4\n", "G4 without"),
        (&format!("({})\n", "x".repeat(90)), "characters"),
    ] {
        let refusal = grbl_refusal(bad).unwrap_or_default();
        assert!(refusal.contains(why), "{bad:?}: {refusal:?}");
    }
}

/// LinuxCNC's interpreter reads every program to its end (`rs274 -g`, exit 0, no error).
#[test]
#[ignore = "needs LinuxCNC's rs274 on PATH (Debian: apt-get install linuxcnc-uspace)"]
fn linuxcnc_takes_every_program_with_every_option() {
    let dir = tempfile::tempdir().expect("temporary folder");
    // The machine's tool table holds the tool the programs load (LinuxCNC refuses others).
    let table = dir.path().join("tool.tbl");
    std::fs::write(&table, "T7 P7 D6.0 Z0 ;6 mm end mill\n").expect("write");
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl, Dialect::Mach3] {
        for (name, g) in programs(dialect) {
            let file = dir.path().join("program.ngc");
            std::fs::write(&file, &g).expect("write");
            let out = std::process::Command::new("rs274")
                .arg("-t")
                .arg(&table)
                .arg("-g")
                .arg(&file)
                .output()
                .expect("rs274 runs (install linuxcnc-uspace)");
            let text =
                String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{dialect:?} {name}: {text}");
            assert!(text.contains("PROGRAM_END"), "{dialect:?} {name}: {text}");
        }
    }
}
