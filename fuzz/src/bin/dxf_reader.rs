//! DXF bytes in: the reader must answer with a drawing or an error, never panic or hang.
fn main() {
    afl::fuzz!(|data: &[u8]| {
        let _ = pocketeer::import::read_drawing(data, &pocketeer::ImportOptions::default());
    });
}
