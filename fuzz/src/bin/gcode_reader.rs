//! G-code text in: a program or an error naming the line, never a panic.
fn main() {
    afl::fuzz!(|data: &[u8]| {
        let text = String::from_utf8_lossy(data);
        if let Ok(p) = pocketeer::simulate::read_program(&text) {
            for m in &p.moves {
                assert!(m.length().is_finite() || m.length().is_nan());
            }
        }
    });
}
