//! The importer answers every input with a result or an error, never a panic: random bytes,
//! and real drawings truncated and mutated at random (deterministic seeds, so failures
//! reproduce).

mod common;

use common::{fixture, Rng};
use pocketeer::{analyze, ImportOptions};

fn fixtures() -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for path in common::corpus::dxf_files(&fixture("corpus")) {
        let bytes = std::fs::read(&path).unwrap();
        if bytes.len() <= 60_000 {
            out.push(bytes);
        }
    }
    out
}

#[test]
fn random_bytes() {
    let mut rng = Rng(0x5eed);
    for n in 0..300 {
        let len = rng.below(4000);
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        if n % 3 == 0 {
            // Random text shaped like group codes.
            bytes = (0..len / 4)
                .flat_map(|_| format!("{}\n{}\n", rng.below(1100), rng.next() % 1000).into_bytes())
                .collect();
        }
        let _ = analyze(&bytes, &ImportOptions::default());
    }
}

#[test]
fn truncated_drawings() {
    let mut rng = Rng(42);
    for bytes in fixtures() {
        for _ in 0..15 {
            let cut = rng.below(bytes.len());
            let _ = analyze(&bytes[..cut], &ImportOptions::default());
        }
    }
}

#[test]
fn mutated_drawings() {
    let mut rng = Rng(4242);
    let interesting: [&[u8]; 10] = [
        b"0",
        b"-",
        b"1e308",
        b"nan",
        b"",
        b"\n",
        b"999999999",
        b"SECTION",
        b"INSERT",
        b"-1e-300",
    ];
    for bytes in fixtures() {
        for _ in 0..20 {
            let mut m = bytes.clone();
            for _ in 0..1 + rng.below(8) {
                let at = rng.below(m.len());
                match rng.below(4) {
                    0 => m[at] = rng.next() as u8,
                    1 => {
                        let end = (at + rng.below(40)).min(m.len());
                        m.drain(at..end);
                    }
                    2 => {
                        let piece = interesting[rng.below(interesting.len())];
                        m.splice(at..at, piece.iter().copied());
                    }
                    _ => {
                        // Duplicate a slice: repeats entities and groups.
                        let end = (at + rng.below(200)).min(m.len());
                        let copy = m[at..end].to_vec();
                        m.splice(at..at, copy);
                    }
                }
            }
            let _ = analyze(&m, &ImportOptions::default());
        }
    }
}

#[test]
fn drawings_with_mutated_values() {
    // Line-level mutations keep the group structure, so the reader gets past the syntax and
    // the odd values reach the geometry.
    let mut rng = Rng(777);
    let values = [
        "0",
        "-0",
        "1e308",
        "-1e308",
        "nan",
        "inf",
        "",
        "1e-300",
        "3",
        "-1",
        "360",
        "0.0000001",
        "64",
        "2147483647",
    ];
    let mut reached_geometry = 0;
    for bytes in fixtures() {
        let Ok(text) = String::from_utf8(bytes) else {
            continue;
        };
        let lines: Vec<&str> = text.lines().collect();
        for _ in 0..40 {
            let mut m: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
            for _ in 0..1 + rng.below(5) {
                let at = rng.below(m.len() / 2) * 2 + 1; // a value line
                m[at] = values[rng.below(values.len())].to_owned();
            }
            let joined = m.join("\n");
            match analyze(joined.as_bytes(), &ImportOptions::default()) {
                Ok(_) => reached_geometry += 1,
                Err(e) => {
                    if !matches!(
                        e,
                        pocketeer::ImportError::Syntax { .. } | pocketeer::ImportError::NotDxf(_)
                    ) {
                        reached_geometry += 1;
                    }
                }
            }
        }
    }
    assert!(
        reached_geometry > 100,
        "only {reached_geometry} mutated drawings got past the reader"
    );
}

#[test]
fn a_hundred_thousand_coincident_lines_are_one_line() {
    // Quadratic passes would take minutes here; the importer hashes exact copies away first.
    let mut ents: Vec<common::Entity> = (0..100_000)
        .map(|_| common::line("0", 0.0, 0.0, 10.0, 0.0))
        .collect();
    ents.push(common::rect_poly("0", 20.0, 0.0, 30.0, 10.0));
    let text = common::Drawing::new(ents).text();
    let a = analyze(text.as_bytes(), &ImportOptions::default()).unwrap();
    assert_eq!(a.chains.duplicates_dropped, 99_999);
    assert_eq!(a.nesting.pockets.len(), 1);
}
