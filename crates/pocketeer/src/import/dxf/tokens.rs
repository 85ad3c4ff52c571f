//! Group-code level reading of ASCII and binary DXF: bytes in, `(code, value)` pairs out, one at
//! a time. A group borrows its value from the file's bytes: nothing is allocated per group, and
//! a number is parsed only when someone asks for it (most groups of a drawing are skipped).

use super::number;
use crate::import::error::{ImportError, Pos};
use std::borrow::Cow;

/// The 22-byte sentinel that starts a binary DXF.
const BINARY_SENTINEL: &[u8] = b"AutoCAD Binary DXF\r\n\x1a\0";

/// A group value: the text as written in an ASCII file (or a binary file's strings), or typed
/// as stored in a binary file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value<'a> {
    /// Text, as bytes of the file: UTF-8, or a code page for older files (read as Latin-1).
    /// Keywords and names (codes 0–9, 100 and 102) of an ASCII file come without the blanks
    /// around them; other values as written (a text may begin with a blank).
    Text(&'a [u8]),
    /// A floating-point number from a binary file.
    Real(f64),
    /// An integer from a binary file.
    Int(i64),
    /// Binary data (skipped).
    Bytes,
}

/// One group: a code and its value, with where it was read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Group<'a> {
    /// Group code.
    pub code: i32,
    /// Value.
    pub value: Value<'a>,
    /// Position of the code in the file.
    pub pos: Pos,
}

impl Group<'_> {
    /// The value as text (numbers are printed).
    pub fn text(&self) -> String {
        match &self.value {
            Value::Text(s) => decode(s).into_owned(),
            Value::Real(x) => x.to_string(),
            Value::Int(i) => i.to_string(),
            Value::Bytes => String::new(),
        }
    }

    /// True when the value is the text `s` (case-sensitive, as DXF keywords are written).
    pub fn is(&self, code: i32, s: &str) -> bool {
        self.code == code && matches!(&self.value, Value::Text(t) if *t == s.as_bytes())
    }

    /// The value as a number: `None` when it is empty or not a number.
    pub fn real(&self) -> Option<f64> {
        match &self.value {
            Value::Text(s) => number::real(s),
            Value::Real(x) => Some(*x),
            Value::Int(i) => Some(*i as f64),
            Value::Bytes => None,
        }
    }

    /// The value as an integer: `None` when it is empty or not a number.
    pub fn int(&self) -> Option<i64> {
        match &self.value {
            Value::Text(s) => number::int(s).or_else(|| number::real(s).and_then(whole)),
            Value::Real(x) => whole(*x),
            Value::Int(i) => Some(*i),
            Value::Bytes => None,
        }
    }
}

/// `x` as an integer when it is one (and small enough to be held exactly).
fn whole(x: f64) -> Option<i64> {
    (x.fract() == 0.0 && x.abs() < 1e15).then_some(x as i64)
}

/// Decodes text: UTF-8 when valid, otherwise Latin-1 (older DXF files use a code page).
pub fn decode(text: &[u8]) -> Cow<'_, str> {
    match std::str::from_utf8(text) {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(text.iter().map(|&b| b as char).collect()),
    }
}

/// How the groups are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    /// Two lines a group: the code, then the value.
    Ascii,
    /// Binary, with two-byte group codes (`wide`, R13 and later) or one-byte ones (R12).
    Binary { wide: bool },
}

/// Reads the groups of a file one at a time, packed; after an error or `0 EOF`, nothing more.
struct Reader<'a> {
    bytes: &'a [u8],
    format: Format,
    /// Byte offset of the next group.
    at: usize,
    /// Line of the next group's code (ASCII).
    line: usize,
    /// Groups read so far.
    count: usize,
    done: bool,
    saw_eof: bool,
}

impl<'a> Reader<'a> {
    /// A reader of `bytes`, a whole ASCII or binary DXF file. Refuses, before reading a group,
    /// text with binary data in it.
    fn new(bytes: &'a [u8]) -> Result<Reader<'a>, ImportError> {
        let mut reader = Reader {
            bytes,
            format: Format::Ascii,
            at: 0,
            line: 1,
            count: 0,
            done: false,
            saw_eof: false,
        };
        if bytes.starts_with(BINARY_SENTINEL) {
            // R12 binary files write one-byte group codes (255 escapes a two-byte code); later
            // versions write two bytes. The first group is `0 SECTION`, or a `999` comment
            // before it: a zero second byte, or 999 in two bytes (one-byte codes would write
            // 999 as 255 and two bytes), means two-byte codes.
            reader.at = BINARY_SENTINEL.len();
            let first = bytes.get(reader.at..reader.at + 2);
            let wide = first.is_some_and(|b| b[1] == 0 || i16::from_le_bytes([b[0], b[1]]) == 999);
            reader.format = Format::Binary { wide };
            return Ok(reader);
        }
        let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        if find_byte(0, body).is_some() {
            return Err(ImportError::NotDxf(
                "the file contains binary data but no binary DXF header".into(),
            ));
        }
        reader.at = bytes.len() - body.len();
        Ok(reader)
    }

    /// The next group, `None` at the end (of the bytes, or after `0 EOF`).
    fn next(&mut self) -> Result<Option<Packed>, ImportError> {
        if self.done {
            return Ok(None);
        }
        let read = match self.format {
            Format::Ascii => self.next_ascii(),
            Format::Binary { wide } => self.next_binary(wide),
        };
        match read {
            Ok(Some(p)) => {
                self.count += 1;
                if p.code == 0 && self.value(&p) == b"EOF" {
                    self.saw_eof = true;
                    self.done = true;
                }
                Ok(Some(p))
            }
            Ok(None) => {
                self.done = true;
                if self.count == 0 {
                    return Err(ImportError::NotDxf("the file is empty".into()));
                }
                Ok(None)
            }
            Err(e) => {
                self.done = true;
                Err(e)
            }
        }
    }

    /// The bytes of a group's value.
    fn value(&self, p: &Packed) -> &'a [u8] {
        let from = p.value as usize;
        self.bytes.get(from..from + p.len as usize).unwrap_or_default()
    }

    /// The next line of an ASCII file, as where it starts and where it ends without its line
    /// break; `None` at the end of the bytes.
    #[inline(always)]
    fn line(&mut self) -> Option<(usize, usize)> {
        let (start, len) = (self.at, self.bytes.len());
        // Past the end once the last line (empty after a final line break) has been read.
        if start > len {
            return None;
        }
        let mut end = match line_break(&self.bytes[start..]) {
            Some(n) => start + n,
            None => len,
        };
        self.at = end + 1;
        self.line += 1;
        if end > start && self.bytes[end - 1] == b'\r' {
            end -= 1;
        }
        Some((start, end))
    }

    fn next_ascii(&mut self) -> Result<Option<Packed>, ImportError> {
        loop {
            let line_no = self.line;
            let Some((from, to)) = self.line() else {
                return Ok(None);
            };
            let code_text = self.bytes[from..to].trim_ascii();
            if code_text.is_empty() {
                // Blank lines before the first group or at the very end are harmless.
                if self.count == 0 {
                    continue;
                }
                let rest = self.bytes.get(self.at..).unwrap_or_default();
                if rest.iter().all(u8::is_ascii_whitespace) {
                    return Ok(None);
                }
            }
            let Some(code) = group_code(code_text) else {
                let shown: String = decode(code_text).chars().take(40).collect();
                if self.count == 0 {
                    return Err(ImportError::NotDxf(format!(
                        "line 1 should be a group code, found '{shown}'"
                    )));
                }
                return Err(ImportError::Syntax {
                    pos: Pos::Line(line_no),
                    what: format!("expected a group code, found '{shown}'"),
                });
            };
            let Some((mut from, mut to)) = self.line() else {
                return Err(ImportError::Syntax {
                    pos: Pos::Line(line_no),
                    what: format!("group code {code} has no value: the file ends here"),
                });
            };
            // Keywords and names: surrounding blanks are never meaningful.
            if (0..=9).contains(&code) || code == 100 || code == 102 {
                while from < to && self.bytes[from].is_ascii_whitespace() {
                    from += 1;
                }
                while to > from && self.bytes[to - 1].is_ascii_whitespace() {
                    to -= 1;
                }
            }
            return Ok(Some(Packed {
                code,
                value: from as u32,
                len: (to - from) as u32,
                pos: line_no as u32,
            }));
        }
    }

    fn next_binary(&mut self, wide: bool) -> Result<Option<Packed>, ImportError> {
        let bytes = self.bytes;
        let start = self.at;
        if start >= bytes.len() {
            return Ok(None);
        }
        let truncated = |pos: usize| ImportError::Syntax {
            pos: Pos::Byte(pos),
            what: "the binary file ends inside a group".into(),
        };
        let mut at = start;
        let take = |at: &mut usize, n: usize| -> Result<&'a [u8], ImportError> {
            let s = bytes.get(*at..*at + n).ok_or_else(|| truncated(*at))?;
            *at += n;
            Ok(s)
        };
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
        let value_at = at;
        let len = match kind_of(code) {
            Kind::Text => {
                let rest = bytes.get(at..).unwrap_or_default();
                let n = find_byte(0, rest).ok_or_else(|| truncated(start))?;
                take(&mut at, n + 1)?;
                n
            }
            Kind::Real | Kind::I64 => take(&mut at, 8)?.len(),
            Kind::I8 => take(&mut at, 1)?.len(),
            Kind::I16 => take(&mut at, 2)?.len(),
            Kind::I32 => take(&mut at, 4)?.len(),
            Kind::Bytes => {
                let n = take(&mut at, 1)?[0] as usize;
                take(&mut at, n)?;
                0
            }
        };
        self.at = at;
        Ok(Some(Packed {
            code,
            value: value_at as u32,
            len: len as u32,
            pos: start as u32,
        }))
    }
}

/// Where the first line break of `bytes` is. A DXF line is a few bytes long, too short for a
/// vector search to pay for its set-up: eight bytes at a time are tested in a word, by the
/// borrow trick (the lowest byte flagged is exactly the first zero byte of `word ^ '\n'`).
#[inline(always)]
fn line_break(bytes: &[u8]) -> Option<usize> {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGHS: u64 = 0x8080_8080_8080_8080;
    let mut at = 0;
    while let Some(chunk) = bytes.get(at..at + 8) {
        let word = u64::from_le_bytes(array(chunk)) ^ (ONES * u64::from(b'\n'));
        let zeros = word.wrapping_sub(ONES) & !word & HIGHS;
        if zeros != 0 {
            return Some(at + (zeros.trailing_zeros() / 8) as usize);
        }
        at += 8;
        if at >= 64 {
            // A long line (a text): the vector search pays now.
            return find_byte(b'\n', &bytes[at..]).map(|n| at + n);
        }
    }
    bytes[at..].iter().position(|&b| b == b'\n').map(|n| at + n)
}

/// Where `needle` first occurs in `haystack`, by a vector search.
///
/// On x86-64 the SSE2 search is taken directly: every x86-64 processor has SSE2, so nothing is
/// asked of the processor at run time. `memchr::memchr` would first ask which vector units it
/// has (CPUID), once per process; on a virtual machine each CPUID traps to the hypervisor, and
/// the question took 67 µs on ours: more than reading and searching a drawing of a few
/// kilobytes.
fn find_byte(needle: u8, haystack: &[u8]) -> Option<usize> {
    #[cfg(target_arch = "x86_64")]
    if let Some(finder) = memchr::arch::x86_64::sse2::memchr::One::new(needle) {
        return finder.find(haystack);
    }
    memchr::memchr(needle, haystack)
}

/// The first `N` bytes of `b`, which has `N` (zeros where it has fewer).
fn array<const N: usize>(b: &[u8]) -> [u8; N] {
    let mut a = [0u8; N];
    let n = b.len().min(N);
    a[..n].copy_from_slice(&b[..n]);
    a
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

/// A group as the list of a file's groups holds it: its code and where its value and its code
/// are in the file, without the value itself (16 bytes, where a drawing's text spends about 12
/// a group).
#[derive(Debug, Clone, Copy)]
struct Packed {
    code: i32,
    /// Byte offset of the value.
    value: u32,
    /// Length of the value in bytes.
    len: u32,
    /// The line of the code (ASCII) or its byte offset (binary).
    pos: u32,
}

/// Every group of a DXF file up to `0 EOF`, read in one pass: what the document reader walks
/// through, and what an entity's groups are a slice of.
#[derive(Debug)]
pub struct GroupList<'a> {
    bytes: &'a [u8],
    binary: bool,
    saw_eof: bool,
    packed: Vec<Packed>,
}

/// Largest file read: positions are held in 32 bits.
pub const MAX_FILE_BYTES: usize = u32::MAX as usize;

impl<'a> GroupList<'a> {
    /// Reads every group of `bytes`, an ASCII or binary DXF file.
    pub fn read(bytes: &'a [u8]) -> Result<GroupList<'a>, ImportError> {
        if bytes.len() > MAX_FILE_BYTES {
            return Err(ImportError::NotDxf(format!(
                "the file is {} bytes long; at most {MAX_FILE_BYTES} are read",
                bytes.len()
            )));
        }
        let mut reader = Reader::new(bytes)?;
        // A group takes at least four bytes of an ASCII file (two of a binary one).
        let mut packed = Vec::with_capacity(bytes.len() / 12);
        while let Some(p) = reader.next()? {
            packed.push(p);
        }
        Ok(GroupList {
            bytes,
            binary: matches!(reader.format, Format::Binary { .. }),
            saw_eof: reader.saw_eof,
            packed,
        })
    }

    /// True for a binary DXF.
    pub fn binary(&self) -> bool {
        self.binary
    }

    /// True when `0 EOF` was read (anything after it is ignored).
    pub fn saw_eof(&self) -> bool {
        self.saw_eof
    }

    /// Every group.
    pub fn all(&self) -> Groups<'_> {
        Groups {
            bytes: self.bytes,
            binary: self.binary,
            packed: &self.packed,
        }
    }
}

/// A run of groups of a file (all of them, or an entity's): a slice of its [`GroupList`].
#[derive(Debug, Clone, Copy)]
pub struct Groups<'a> {
    bytes: &'a [u8],
    binary: bool,
    packed: &'a [Packed],
}

impl<'a> Groups<'a> {
    /// How many groups.
    pub fn len(&self) -> usize {
        self.packed.len()
    }

    /// True when there is none.
    pub fn is_empty(&self) -> bool {
        self.packed.is_empty()
    }

    /// The code of group `i`, without reading its value.
    pub fn code(&self, i: usize) -> Option<i32> {
        self.packed.get(i).map(|p| p.code)
    }

    /// Group `i`.
    pub fn get(&self, i: usize) -> Option<Group<'a>> {
        self.packed.get(i).map(|p| self.unpack(p))
    }

    /// Groups `range` of these.
    pub fn slice(&self, range: std::ops::Range<usize>) -> Groups<'a> {
        Groups {
            packed: self.packed.get(range).unwrap_or_default(),
            ..*self
        }
    }

    /// The groups, in order.
    pub fn iter(&self) -> impl Iterator<Item = Group<'a>> + '_ {
        self.packed.iter().map(|p| self.unpack(p))
    }

    fn unpack(&self, p: &Packed) -> Group<'a> {
        let (from, to) = (p.value as usize, p.value as usize + p.len as usize);
        let raw = self.bytes.get(from..to).unwrap_or_default();
        if !self.binary {
            return Group {
                code: p.code,
                value: Value::Text(raw),
                pos: Pos::Line(p.pos as usize),
            };
        }
        let value = match kind_of(p.code) {
            Kind::Text => Value::Text(raw),
            Kind::Real => Value::Real(f64::from_le_bytes(array(raw))),
            Kind::I8 => Value::Int(raw.first().copied().unwrap_or(0) as i64),
            Kind::I16 => Value::Int(i16::from_le_bytes(array(raw)) as i64),
            Kind::I32 => Value::Int(i32::from_le_bytes(array(raw)) as i64),
            Kind::I64 => Value::Int(i64::from_le_bytes(array(raw))),
            Kind::Bytes => Value::Bytes,
        };
        Group {
            code: p.code,
            value,
            pos: Pos::Byte(p.pos as usize),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every group of `bytes`, and whether the list saw `0 EOF` (the list, which the groups
    /// borrow, is leaked: a test's few bytes).
    fn read_all(bytes: &'static [u8]) -> Result<(Vec<Group<'static>>, bool), ImportError> {
        let list: &'static GroupList<'static> = Box::leak(Box::new(GroupList::read(bytes)?));
        Ok((list.all().iter().collect(), list.saw_eof()))
    }

    /// The line a syntax error names, `None` for any other outcome.
    fn syntax_line<T>(read: Result<T, ImportError>) -> Option<usize> {
        match read {
            Err(ImportError::Syntax {
                pos: Pos::Line(n), ..
            }) => Some(n),
            _ => None,
        }
    }

    #[test]
    fn ascii_groups_with_crlf_and_padding() {
        let (g, eof) =
            read_all(b"  0\r\nSECTION\r\n  2\r\nENTITIES\r\n 10\r\n 1.5 \r\n  0\r\nEOF\r\ntrash").unwrap();
        assert!(eof);
        assert_eq!(g.len(), 4);
        assert!(g[1].is(2, "ENTITIES"));
        assert_eq!(g[2].real(), Some(1.5));
        assert_eq!(g[2].pos, Pos::Line(5));
    }

    #[test]
    fn blank_lines_lead_and_trail_but_do_not_interrupt() {
        let (g, eof) = read_all(b"\n\n  0\nSECTION\n  0\nENDSEC\n\n  \n").unwrap();
        assert!(!eof);
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].pos, Pos::Line(3));
        assert_eq!(syntax_line(read_all(b"  0\nSECTION\n\n  0\nENDSEC\n")), Some(3));
        // A last group without a line break after its value, and a code without a value.
        let (g, _) = read_all(b"0\nSECTION\n0\nEOF").unwrap();
        assert!(g[1].is(0, "EOF"));
        assert_eq!(syntax_line(read_all(b"0\nSECTION\n10")), Some(3));
        // An empty value on the last line is a value.
        let (g, _) = read_all(b"0\nSECTION\n1\n").unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[1].text(), "");
    }

    #[test]
    fn the_list_gives_back_what_was_read() {
        let text = b"0\nSECTION\n2\nENTITIES\n0\nLINE\n8\nA\n10\n1\n0\nEOF\n";
        let (read, _) = read_all(text).unwrap();
        let list = GroupList::read(text).unwrap();
        assert!(list.saw_eof() && !list.binary());
        assert_eq!(list.all().iter().collect::<Vec<_>>(), read);
        let line = list.all().slice(3..5);
        assert_eq!(line.len(), 2);
        assert_eq!(line.get(0).map(|g| g.pos), Some(Pos::Line(7)));
        assert_eq!(line.get(1).and_then(|g| g.real()), Some(1.0));
    }

    #[test]
    fn line_breaks_are_found_where_they_are() {
        for len in 0..150 {
            for at in 0..=len {
                let mut bytes = vec![b'x'; len];
                let expected = (at < len).then(|| {
                    bytes[at] = b'\n';
                    at
                });
                // Bytes next to a line break in value (0x0a ± 1, 0x8a) flag nothing.
                if at + 1 < len {
                    bytes[at + 1] = 0x0b;
                }
                if at > 0 {
                    bytes[at - 1] = 0x8a;
                }
                assert_eq!(line_break(&bytes), expected, "{len} {at}");
            }
        }
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
        let (g, _) = read_all(b"  0\nSECTION\n 70\n\n  0\nEOF\n").unwrap();
        assert_eq!(g[1].int(), None);
    }

    #[test]
    fn a_binary_file_may_begin_with_a_comment() {
        let mut bytes = BINARY_SENTINEL.to_vec();
        for (code, text) in [
            (999i16, "made by hand"),
            (0, "SECTION"),
            (2, "ENTITIES"),
            (0, "ENDSEC"),
            (0, "EOF"),
        ] {
            bytes.extend(code.to_le_bytes());
            bytes.extend(text.as_bytes());
            bytes.push(0);
        }
        let list: &'static GroupList<'static> = Box::leak(Box::new(
            GroupList::read(Box::leak(bytes.into_boxed_slice())).unwrap(),
        ));
        let g: Vec<Group> = list.all().iter().collect();
        assert!(list.binary() && list.saw_eof());
        assert_eq!(g.len(), 5);
        assert!(g[0].code == 999 && g[1].is(0, "SECTION") && g[2].is(2, "ENTITIES"));
    }

    #[test]
    fn text_is_not_dxf() {
        assert!(matches!(read_all(b"hello world\n"), Err(ImportError::NotDxf(_))));
        assert!(matches!(read_all(b""), Err(ImportError::NotDxf(_))));
        assert!(matches!(read_all(b"\n \n"), Err(ImportError::NotDxf(_))));
        assert!(matches!(read_all(b"0\nSECTION\0"), Err(ImportError::NotDxf(_))));
    }
}
