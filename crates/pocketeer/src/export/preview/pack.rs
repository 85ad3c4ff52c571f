//! The compact form the preview page's geometry travels in: integers (coordinates in
//! micrometres, each the difference from the one before) as variable-length bytes, the bytes
//! as base64. A program of a million short moves takes a few bytes a move instead of the
//! thirty of its G-code text; the page's script reads it back (`page.js`, `Reader`).

/// Millimetres per unit of a packed coordinate.
pub const QUANTUM: f64 = 1e-3;

/// Bytes being packed.
#[derive(Debug, Default, Clone)]
pub struct Packer {
    bytes: Vec<u8>,
}

impl Packer {
    /// An unsigned integer, seven bits a byte, low first (LEB128).
    pub fn uint(&mut self, mut v: u64) {
        while v >= 0x80 {
            self.bytes.push((v as u8 & 0x7f) | 0x80);
            v >>= 7;
        }
        self.bytes.push(v as u8);
    }

    /// A signed integer, zigzag-coded (0, −1, 1, −2, … as 0, 1, 2, 3, …).
    pub fn int(&mut self, v: i64) {
        self.uint(((v << 1) ^ (v >> 63)) as u64);
    }

    /// Bytes packed so far.
    pub fn len(&self) -> usize {
        self.bytes.len()
    }

    /// True when nothing was packed.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// The bytes as standard base64 with padding.
    pub fn base64(&self) -> String {
        base64(&self.bytes)
    }
}

/// A length in millimetres as a whole number of [`QUANTUM`]s (saturating far outside any
/// machine).
pub fn quantize(mm: f64) -> i64 {
    (mm / QUANTUM).round() as i64
}

/// Points packed as differences from the previous one, in [`QUANTUM`]s.
#[derive(Debug, Default, Clone, Copy)]
pub struct Cursor {
    x: i64,
    y: i64,
}

impl Cursor {
    /// Packs `(x, y)` (mm) as the difference from the last point packed.
    pub fn point(&mut self, p: &mut Packer, x: f64, y: f64) {
        let (qx, qy) = (quantize(x), quantize(y));
        p.int(qx - self.x);
        p.int(qy - self.y);
        self.x = qx;
        self.y = qy;
    }
}

const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 (RFC 4648) with padding; the page decodes it with the browser's `atob`.
///
/// ```
/// use pocketeer::export::preview::pack::base64;
/// assert_eq!(base64(b"pocket"), "cG9ja2V0");
/// assert_eq!(base64(b"tool"), "dG9vbA==");
/// ```
pub fn base64(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads back what [`Packer`] wrote (the page's reader, in Rust).
    fn read(bytes: &[u8]) -> Vec<i64> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < bytes.len() {
            let (mut v, mut shift) = (0u64, 0);
            loop {
                let b = bytes[i];
                i += 1;
                v |= u64::from(b & 0x7f) << shift;
                shift += 7;
                if b < 0x80 {
                    break;
                }
            }
            out.push(((v >> 1) as i64) ^ -((v & 1) as i64));
        }
        out
    }

    #[test]
    fn integers_come_back_as_they_went_in() {
        let values = [0, 1, -1, 63, -64, 64, 1 << 20, -(1 << 40), i64::MAX, i64::MIN];
        let mut p = Packer::default();
        for &v in &values {
            p.int(v);
        }
        assert_eq!(read(&p.bytes), values);
        // Small differences take one byte.
        let mut q = Packer::default();
        q.int(-64);
        q.int(63);
        assert_eq!(q.len(), 2);
    }

    #[test]
    fn base64_matches_the_standard_vectors() {
        for (raw, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), coded);
        }
    }

    #[test]
    fn a_cursor_packs_differences_without_drift() {
        let mut p = Packer::default();
        let mut c = Cursor::default();
        let mut x = 0.0;
        for _ in 0..1000 {
            x += 0.0004; // under half a quantum each step
            c.point(&mut p, x, -x);
        }
        let v = read(&p.bytes);
        let sx: i64 = v.iter().step_by(2).sum();
        let sy: i64 = v.iter().skip(1).step_by(2).sum();
        assert_eq!((sx, sy), (quantize(x), quantize(-x)));
    }
}
