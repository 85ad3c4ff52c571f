//! DXF bytes through the whole import: reading, chaining, nesting into pockets.
fn main() {
    afl::fuzz!(|data: &[u8]| {
        if let Ok(a) = pocketeer::analyze(data, &pocketeer::ImportOptions::default()) {
            for p in &a.nesting.pockets {
                assert!(p.area().is_finite());
            }
        }
    });
}
