//! Group-code level reading of ASCII and binary DXF: bytes in, `(code, value)` pairs out.

use crate::import::error::{ImportError, Pos};

/// The 22-byte sentinel that starts a binary DXF.
const BINARY_SENTINEL: &[u8] = b"AutoCAD Binary DXF\r\n\x1a\0";

/// A group value: text as written in an ASCII file, or typed as stored in a binary one.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Text (every value of an ASCII file, strings of a binary one).
    Text(String),
    /// A floating-point number from a binary file.
    Real(f64),
    /// An integer from a binary file.
    Int(i64),
    /// Binary data (skipped).
    Bytes,
}

/// One group: a code and its value, with where it was read.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Group code.
    pub code: i32,
    /// Value.
    pub value: Value,
    /// Position of the code in the file.
    pub pos: Pos,
}

impl Group {
    /// The value as text (numbers are printed).
    pub fn text(&self) -> String {
        match &self.value {
            Value::Text(s) => s.clone(),
            Value::Real(x) => x.to_string(),
            Value::Int(i) => i.to_string(),
            Value::Bytes => String::new(),
        }
    }

    /// True when the value is the text `s` (case-sensitive, as DXF keywords are written).
    pub fn is(&self, code: i32, s: &str) -> bool {
        self.code == code && matches!(&self.value, Value::Text(t) if t == s)
    }

    /// The value as a number: `None` when it is empty or not a number.
    pub fn real(&self) -> Option<f64> {
        match &self.value {
            Value::Text(s) => s.trim().parse::<f64>().ok(),
            Value::Real(x) => Some(*x),
            Value::Int(i) => Some(*i as f64),
            Value::Bytes => None,
        }
    }

    /// The value as an integer: `None` when it is empty or not a number.
    pub fn int(&self) -> Option<i64> {
        match &self.value {
            Value::Text(s) => {
                let s = s.trim();
                s.parse::<i64>().ok().or_else(|| {
                    s.parse::<f64>()
                        .ok()
                        .filter(|x| x.fract() == 0.0 && x.abs() < 1e15)
                        .map(|x| x as i64)
                })
            }
            Value::Real(x) => (x.fract() == 0.0 && x.abs() < 1e15).then_some(*x as i64),
            Value::Int(i) => Some(*i),
            Value::Bytes => None,
        }
    }
}

/// The groups of a DXF file, and whether the `EOF` marker was reached.
#[derive(Debug, Default)]
pub struct Groups {
    /// All groups up to `0 EOF` (or the end of the bytes).
    pub groups: Vec<Group>,
    /// True when `0 EOF` was read (anything after it is ignored).
    pub saw_eof: bool,
    /// True for a binary DXF.
    pub binary: bool,
}

/// Reads the group codes of an ASCII or binary DXF.
pub fn read_groups(bytes: &[u8]) -> Result<Groups, ImportError> {
    if bytes.starts_with(BINARY_SENTINEL) {
        read_binary(bytes)
    } else {
        read_ascii(bytes)
    }
}

/// Decodes a line: UTF-8 when valid, otherwise Latin-1 (older DXF files use a code page).
fn decode(line: &[u8]) -> String {
    match std::str::from_utf8(line) {
        Ok(s) => s.to_owned(),
        Err(_) => line.iter().map(|&b| b as char).collect(),
    }
}

fn read_ascii(bytes: &[u8]) -> Result<Groups, ImportError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    if bytes.contains(&0) {
        return Err(ImportError::NotDxf(
            "the file contains binary data but no binary DXF header".into(),
        ));
    }
    // Two lines a group: sized once, not regrown (a regrowth copies every group read so far).
    let line_count = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
    let mut out = Groups {
        groups: Vec::with_capacity(line_count / 2 + 1),
        ..Groups::default()
    };
    let mut lines = bytes
        .split(|&b| b == b'\n')
        .map(|l| l.strip_suffix(b"\r").unwrap_or(l))
        .enumerate();
    while let Some((i, code_line)) = lines.next() {
        let code_trim = code_line.trim_ascii();
        if code_trim.is_empty() {
            // Blank lines before the first group or at the very end are harmless.
            if out.groups.is_empty() {
                continue;
            }
            if lines.clone().all(|(_, l)| l.iter().all(u8::is_ascii_whitespace)) {
                break;
            }
        }
        let Some(code) = group_code(code_trim) else {
            let shown: String = decode(code_trim).chars().take(40).collect();
            if out.groups.is_empty() {
                return Err(ImportError::NotDxf(format!(
                    "line 1 should be a group code, found '{shown}'"
                )));
            }
            return Err(ImportError::Syntax {
                pos: Pos::Line(i + 1),
                what: format!("expected a group code, found '{shown}'"),
            });
        };
        let Some((_, value_line)) = lines.next() else {
            return Err(ImportError::Syntax {
                pos: Pos::Line(i + 1),
                what: format!("group code {code} has no value: the file ends here"),
            });
        };
        let g = Group {
            code,
            value: ascii_value(code, value_line),
            pos: Pos::Line(i + 1),
        };
        let eof = g.is(0, "EOF");
        out.groups.push(g);
        if eof {
            out.saw_eof = true;
            break;
        }
    }
    if out.groups.is_empty() {
        return Err(ImportError::NotDxf("the file is empty".into()));
    }
    Ok(out)
}

/// A group code as written on its line (blanks trimmed): an optional sign and decimal digits
/// that fit an `i32`, read from the bytes without making a string of them.
fn group_code(text: &[u8]) -> Option<i32> {
    let (negative, digits) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, text),
    };
    if digits.is_empty() {
        return None;
    }
    let mut value: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        value = value * 10 + i64::from(d - b'0');
        if value > i64::from(i32::MAX) + 1 {
            return None;
        }
    }
    i32::try_from(if negative { -value } else { value }).ok()
}

/// The value of an ASCII group: numbers of the codes that hold them are stored as numbers
/// (a drawing of a million lines holds millions of them, and a string each would cost several
/// times the file's size), everything else as text.
fn ascii_value(code: i32, line: &[u8]) -> Value {
    let number = std::str::from_utf8(line).ok().map(str::trim);
    match (kind_of(code), number) {
        (Kind::Real, Some(t)) => {
            if let Ok(x) = t.parse::<f64>() {
                return Value::Real(x);
            }
        }
        (Kind::I16 | Kind::I32 | Kind::I64 | Kind::I8, Some(t)) => {
            if let Ok(i) = t.parse::<i64>() {
                return Value::Int(i);
            }
        }
        _ => {}
    }
    let value = decode(line);
    if (0..=9).contains(&code) || code == 100 || code == 102 {
        // Keywords and names: surrounding blanks are never meaningful.
        Value::Text(value.trim().to_owned())
    } else {
        Value::Text(value)
    }
}

/// Storage class of a group code's value in a binary DXF.
enum Kind {
    Text,
    Real,
    I8,
    I16,
    I32,
    I64,
    Bytes,
}

fn kind_of(code: i32) -> Kind {
    match code {
        10..=59 | 110..=149 | 210..=239 | 460..=469 | 1010..=1059 => Kind::Real,
        60..=79 | 170..=179 | 270..=289 | 370..=389 | 400..=409 | 1060..=1070 => Kind::I16,
        90..=99 | 420..=429 | 440..=459 | 1071 => Kind::I32,
        160..=169 => Kind::I64,
        290..=299 => Kind::I8,
        310..=319 | 1004 => Kind::Bytes,
        _ => Kind::Text,
    }
}

fn read_binary(bytes: &[u8]) -> Result<Groups, ImportError> {
    let mut out = Groups {
        binary: true,
        ..Groups::default()
    };
    let mut at = BINARY_SENTINEL.len();
    // R12 binary files write one-byte group codes (255 escapes a two-byte code); later versions
    // write two bytes. The first group is `0 SECTION`: a zero second byte means two-byte codes.
    let wide = bytes.get(at + 1) == Some(&0);
    let truncated = |pos: usize| ImportError::Syntax {
        pos: Pos::Byte(pos),
        what: "the binary file ends inside a group".into(),
    };
    let take = |at: &mut usize, n: usize| -> Result<&[u8], ImportError> {
        let s = bytes.get(*at..*at + n).ok_or_else(|| truncated(*at))?;
        *at += n;
        Ok(s)
    };
    while at < bytes.len() {
        let start = at;
        let code = if wide {
            let b = take(&mut at, 2)?;
            i16::from_le_bytes([b[0], b[1]]) as i32
        } else {
            let b = take(&mut at, 1)?[0];
            if b == 255 {
                let b = take(&mut at, 2)?;
                i16::from_le_bytes([b[0], b[1]]) as i32
            } else {
                b as i32
            }
        };
        let value = match kind_of(code) {
            Kind::Text => {
                let rest = bytes.get(at..).unwrap_or_default();
                let n = rest
                    .iter()
                    .position(|&b| b == 0)
                    .ok_or_else(|| truncated(start))?;
                let s = decode(&rest[..n]);
                at += n + 1;
                Value::Text(s)
            }
            Kind::Real => {
                let b = take(&mut at, 8)?;
                let mut a = [0u8; 8];
                a.copy_from_slice(b);
                Value::Real(f64::from_le_bytes(a))
            }
            Kind::I8 => Value::Int(take(&mut at, 1)?[0] as i64),
            Kind::I16 => {
                let b = take(&mut at, 2)?;
                Value::Int(i16::from_le_bytes([b[0], b[1]]) as i64)
            }
            Kind::I32 => {
                let b = take(&mut at, 4)?;
                Value::Int(i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as i64)
            }
            Kind::I64 => {
                let b = take(&mut at, 8)?;
                let mut a = [0u8; 8];
                a.copy_from_slice(b);
                Value::Int(i64::from_le_bytes(a))
            }
            Kind::Bytes => {
                let n = take(&mut at, 1)?[0] as usize;
                take(&mut at, n)?;
                Value::Bytes
            }
        };
        let g = Group {
            code,
            value,
            pos: Pos::Byte(start),
        };
        let eof = g.is(0, "EOF");
        out.groups.push(g);
        if eof {
            out.saw_eof = true;
            break;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_groups_with_crlf_and_padding() {
        let g =
            read_groups(b"  0\r\nSECTION\r\n  2\r\nENTITIES\r\n 10\r\n 1.5 \r\n  0\r\nEOF\r\ntrash").unwrap();
        assert!(g.saw_eof);
        assert_eq!(g.groups.len(), 4);
        assert_eq!(g.groups[2].real(), Some(1.5));
        assert_eq!(g.groups[2].pos, Pos::Line(5));
    }

    #[test]
    fn group_codes_read_like_integers() {
        for (text, code) in [
            ("0", Some(0)),
            ("999", Some(999)),
            ("-5", Some(-5)),
            ("+7", Some(7)),
        ] {
            assert_eq!(group_code(text.as_bytes()), code, "{text}");
        }
        let max = i32::MAX.to_string();
        let min = i32::MIN.to_string();
        assert_eq!(group_code(max.as_bytes()), Some(i32::MAX));
        assert_eq!(group_code(min.as_bytes()), Some(i32::MIN));
        for bad in ["", "-", "1.0", "1 0", "2147483648", "99999999999999999999", "x"] {
            assert_eq!(group_code(bad.as_bytes()), None, "{bad}");
        }
    }

    #[test]
    fn empty_number_is_none_not_an_error() {
        let g = read_groups(b"  0\nSECTION\n 70\n\n  0\nEOF\n").unwrap();
        assert_eq!(g.groups[1].int(), None);
    }

    #[test]
    fn text_is_not_dxf() {
        assert!(matches!(
            read_groups(b"hello world\n"),
            Err(ImportError::NotDxf(_))
        ));
        assert!(matches!(read_groups(b""), Err(ImportError::NotDxf(_))));
    }
}
