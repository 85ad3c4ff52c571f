//! Writes a drawing like traced relief art: `N` closed cubic SPLINEs (default 7 464, the
//! relief carving of issue 17), wobbly rings of 14 control points on a grid, for timing the
//! import: `cargo run --release --bin splines -- [N] > relief.dxf`, then
//! `pocketeer inspect relief.dxf`.

use std::fmt::Write;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(7464);
    let side = (n as f64).sqrt().ceil() as usize;
    let mut s =
        String::from("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    // A small deterministic generator: the same drawing on every run.
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    const POINTS: usize = 14;
    for k in 0..n {
        let (cx, cy) = ((k % side) as f64 * 12.0, (k / side) as f64 * 12.0);
        let r = 3.0 + 2.0 * rnd();
        let pts: Vec<(f64, f64)> = (0..POINTS)
            .map(|j| {
                let a = j as f64 * std::f64::consts::TAU / POINTS as f64;
                let rr = r * (0.8 + 0.4 * rnd());
                (cx + rr * a.cos(), cy + rr * a.sin())
            })
            .collect();
        // Periodic: the first three control points again at the end, uniform knots.
        let count = POINTS + 3;
        let knots = count + 4;
        let _ = write!(
            s,
            "0\nSPLINE\n8\nrelief\n210\n0.0\n220\n0.0\n230\n1.0\n70\n11\n71\n3\n72\n{knots}\n73\n{count}\n74\n0\n"
        );
        for i in 0..knots {
            let _ = write!(s, "40\n{}\n", i as f64);
        }
        for i in 0..count {
            let (x, y) = pts[i % POINTS];
            let _ = write!(s, "10\n{x:.6}\n20\n{y:.6}\n30\n0.0\n");
        }
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    print!("{s}");
}
