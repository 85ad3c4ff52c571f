//! A binary DXF reads as its ASCII twin: every drawing shipped with the project (the examples and
//! the corpus fixtures) written again as a binary DXF gives the same elements, layers, entity
//! counts and warnings.

mod common;

use common::corpus::dxf_files;
use pocketeer::{read_drawing, ImportOptions};
use std::path::{Path, PathBuf};

/// An ASCII DXF's groups as a binary DXF (R13 and later: two-byte codes, numbers stored by their
/// code's range, texts ending in a zero byte), or `None` when a value does not fit its code's type
/// (then the ASCII file holds something a binary one cannot, and there is nothing to compare).
fn binary_twin(ascii: &str) -> Option<Vec<u8>> {
    let mut out = b"AutoCAD Binary DXF\r\n\x1a\0".to_vec();
    let mut lines = ascii.lines();
    while let (Some(code), Some(value)) = (lines.next(), lines.next()) {
        let code: i16 = code.trim().parse().ok()?;
        out.extend(code.to_le_bytes());
        let trimmed = value.trim();
        match code {
            10..=59 | 110..=149 | 210..=239 | 460..=469 | 1010..=1059 => {
                out.extend(trimmed.parse::<f64>().ok()?.to_le_bytes())
            }
            60..=79 | 170..=179 | 270..=289 | 370..=389 | 400..=409 | 1060..=1070 => {
                out.extend(trimmed.parse::<i16>().ok()?.to_le_bytes())
            }
            90..=99 | 420..=429 | 440..=459 | 1071 => out.extend(trimmed.parse::<i32>().ok()?.to_le_bytes()),
            160..=169 => out.extend(trimmed.parse::<i64>().ok()?.to_le_bytes()),
            290..=299 => out.push(trimmed.parse::<u8>().ok()?),
            310..=319 | 1004 => {
                // Binary chunks: hexadecimal text in ASCII, a length byte and bytes in binary.
                let bytes: Vec<u8> = (0..trimmed.len() / 2)
                    .map(|i| u8::from_str_radix(&trimmed[2 * i..2 * i + 2], 16).ok())
                    .collect::<Option<_>>()?;
                out.push(u8::try_from(bytes.len()).ok()?);
                out.extend(bytes);
            }
            _ => {
                let text = if (0..=9).contains(&code) || code == 100 || code == 102 {
                    trimmed
                } else {
                    value
                };
                out.extend(text.as_bytes());
                out.push(0);
            }
        }
    }
    Some(out)
}

/// The examples and the corpus fixtures.
fn drawings() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = dxf_files(&root.join("../../examples"));
    files.extend(dxf_files(&root.join("tests/fixtures/corpus")));
    files
}

#[test]
fn binary_twins_read_as_the_ascii_drawings() {
    let options = ImportOptions::default();
    let mut compared = 0;
    for f in drawings() {
        let bytes = std::fs::read(&f).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue; // a binary file or another code page
        };
        let Some(twin) = binary_twin(text) else {
            continue;
        };
        let (Ok(a), Ok(b)) = (
            read_drawing(text.as_bytes(), &options),
            read_drawing(&twin, &options),
        ) else {
            let (a, b) = (
                read_drawing(text.as_bytes(), &options),
                read_drawing(&twin, &options),
            );
            assert_eq!(
                a.is_ok(),
                b.is_ok(),
                "{}: {:?} / {:?}",
                f.display(),
                a.err(),
                b.err()
            );
            continue;
        };
        let name = f.display();
        assert!(b.binary && !a.binary, "{name}");
        assert_eq!(a.layers, b.layers, "{name}");
        assert_eq!(a.entity_counts, b.entity_counts, "{name}");
        assert_eq!(a.warnings.len(), b.warnings.len(), "{name}");
        assert_eq!(a.elements.len(), b.elements.len(), "{name}");
        for (x, y) in a.elements.iter().zip(&b.elements) {
            assert_eq!(x.segment, y.segment, "{name}");
            assert_eq!(
                (x.layer, x.source, x.closed_group),
                (y.layer, y.source, y.closed_group),
                "{name}"
            );
        }
        compared += 1;
    }
    // The two examples and every ASCII corpus fixture but the one with trash after its EOF.
    assert!(compared >= 12, "only {compared} drawings compared");
}
