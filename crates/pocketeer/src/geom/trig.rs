//! Sine and cosine of one angle at once, for the angles geometry meets (within a few turns of
//! zero), without the C library's call.
//!
//! Points and tangents of arcs are worked out from angles everywhere: in offsets, splitting,
//! linking and the pass through cleared stock. The C library's `sincos` handles every double
//! there is, and its range checks and paths cost some 120 instructions a call and a share of
//! the mispredicted branches of a whole job (on the 300-hole plate, 5 % of them). Here the
//! angle is brought to within a quarter turn of zero by a multiple of π/2 held in three parts
//! (Cody and Waite), and each function is a Taylor polynomial there, the quadrant chosen
//! without a branch.

use std::f64::consts::FRAC_2_PI;

/// π/2 in three parts: the first two of 33 significant bits, so that `k` times either is
/// exact for `|k|` below 2^20; together within 2^-119 of π/2.
const HALF_PI_1: f64 = 1.570_796_326_734_125_6;
const HALF_PI_2: f64 = 6.077_100_506_303_966e-11;
const HALF_PI_3: f64 = 2.022_266_248_795_950_6e-21;

/// Largest angle taken here; larger ones (and NaN, infinities) go to the standard library.
const LARGEST: f64 = 5.0e5;

/// 1.5 · 2^52: adding it rounds a double of magnitude below 2^51 to an integer, held in the
/// low bits of the sum.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// `(sin x, cos x)`, each within about an ulp of the true value.
///
/// ```
/// use pocketeer::geom::sin_cos;
/// let (s, c) = sin_cos(std::f64::consts::FRAC_PI_6);
/// assert!((s - 0.5).abs() < 1e-16 && (c - 0.75f64.sqrt()).abs() < 1e-16);
/// ```
pub fn sin_cos(x: f64) -> (f64, f64) {
    // NaN fails the comparison and goes there too.
    if x.abs().partial_cmp(&LARGEST) != Some(std::cmp::Ordering::Less) {
        return x.sin_cos();
    }
    // The nearest multiple k of π/2, and what is left: |r| ≤ π/4 (and a hair).
    let shifted = x * FRAC_2_PI + ROUNDER;
    let quadrant = shifted.to_bits();
    let k = shifted - ROUNDER;
    // r = hi + lo: x − k·π/2 to twice the precision, the rounding of the second step kept
    // (k times each part is exact, and so is the first difference).
    let y = x - k * HALF_PI_1;
    let t = k * HALF_PI_2;
    let hi = y - t;
    let lo = ((y - hi) - t) - k * HALF_PI_3;
    let (s, c) = kernel(hi, lo);
    // sin(r + kπ/2): k = 0: (s, c); 1: (c, -s); 2: (-s, -c); 3: (-c, s).
    let swap = (quadrant & 1).wrapping_neg();
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let (first, second) = ((sb & !swap) | (cb & swap), (cb & !swap) | (sb & swap));
    let sign_sin = (quadrant & 2) << 62;
    let sign_cos = ((quadrant + 1) & 2) << 62;
    (
        f64::from_bits(first ^ sign_sin),
        f64::from_bits(second ^ sign_cos),
    )
}

/// Sine and cosine of `r + lo`, |r| ≤ π/4 (a little more is fine) and `lo` below an ulp of
/// `r`: Taylor polynomials to the 17th and 18th power, whose first left-out terms are below
/// 10^-19 of the result there, and `lo` to first order.
fn kernel(r: f64, lo: f64) -> (f64, f64) {
    let z = r * r;
    // sin r = r + r³ (−1/3! + z (1/5! − z (1/7! − ...)))
    let s = -1.0 / 6.0
        + z * (1.0 / 120.0
            + z * (-1.0 / 5040.0
                + z * (1.0 / 362_880.0
                    + z * (-1.0 / 39_916_800.0
                        + z * (1.0 / 6_227_020_800.0
                            + z * (-1.0 / 1_307_674_368_000.0 + z * (1.0 / 355_687_428_096_000.0)))))));
    let half = 0.5 * z;
    let sin = r + (r * z * s + lo * (1.0 - half));
    // cos r = 1 − z/2 + z² (1/4! − z (1/6! − ...))
    let c = 1.0 / 24.0
        + z * (-1.0 / 720.0
            + z * (1.0 / 40_320.0
                + z * (-1.0 / 3_628_800.0
                    + z * (1.0 / 479_001_600.0
                        + z * (-1.0 / 87_178_291_200.0
                            + z * (1.0 / 20_922_789_888_000.0 + z * (-1.0 / 6_402_373_705_728_000.0)))))));
    // 1 − z/2 loses bits when z/2 is near a half: the rounding of the difference is added
    // back.
    let w = 1.0 - half;
    let cos = w + (((1.0 - w) - half) + (z * z * c - r * lo));
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Distance in units in the last place between two doubles of one sign (or both near 0).
    fn ulps(a: f64, b: f64) -> f64 {
        let scale = a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
        (a - b).abs() / (scale * f64::EPSILON)
    }

    #[test]
    fn the_axes_and_the_quadrants() {
        use std::f64::consts::{FRAC_PI_2, PI};
        for k in -8i32..=8 {
            let (s, c) = sin_cos(k as f64 * FRAC_PI_2);
            let (es, ec) = [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)][k.rem_euclid(4) as usize];
            assert!((s - es).abs() < 1e-15 && (c - ec).abs() < 1e-15, "{k}: {s} {c}");
        }
        let (s, c) = sin_cos(0.75 * PI);
        assert!((s - 0.5f64.sqrt()).abs() < 2e-16 && (c + 0.5f64.sqrt()).abs() < 2e-16);
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin_cos(f64::NAN).0.is_nan() && sin_cos(f64::INFINITY).1.is_nan());
        assert_eq!(sin_cos(1e6), 1e6f64.sin_cos());
        // Far out, where the reduction's second rounding once cost two ulps.
        let x = 208_562.997_317_272_8;
        let ((s, c), (es, ec)) = (sin_cos(x), x.sin_cos());
        assert!(ulps(s, es) <= 1.0 && ulps(c, ec) <= 1.0, "{s} {es} {c} {ec}");
    }

    #[test]
    fn within_an_ulp_of_the_standard_library_on_a_fine_sweep() {
        // Every 1/1000 rad over ten turns either way: the worst difference from the C
        // library's (itself within an ulp of the truth), in ulps of the larger value.
        let mut worst: f64 = 0.0;
        for k in -63_000..=63_000 {
            let x = k as f64 * 1e-3;
            let ((s, c), (es, ec)) = (sin_cos(x), x.sin_cos());
            // Near a zero of either, an ulp of 1 is the measure (the reduction's absolute
            // error).
            worst = worst.max(ulps(s, es).min((s - es).abs() / f64::EPSILON));
            worst = worst.max(ulps(c, ec).min((c - ec).abs() / f64::EPSILON));
        }
        assert!(worst <= 1.0, "{worst} ulps");
    }

    proptest! {
        #[test]
        fn within_an_ulp_anywhere_taken(x in -LARGEST..LARGEST) {
            let ((s, c), (es, ec)) = (sin_cos(x), x.sin_cos());
            prop_assert!((s - es).abs() <= f64::EPSILON * es.abs().max(1e-3), "{x}: {s} {es}");
            prop_assert!((c - ec).abs() <= f64::EPSILON * ec.abs().max(1e-3), "{x}: {c} {ec}");
        }

        #[test]
        fn tiny_angles_keep_their_digits(x in -1e-3f64..1e-3) {
            let ((s, c), (es, ec)) = (sin_cos(x), x.sin_cos());
            prop_assert!(ulps(s, es) <= 1.0 && ulps(c, ec) <= 1.0, "{x}");
        }
    }
}
