//! Rounding to whole numbers without the C library: `f64::ceil` and `f64::floor` are calls
//! into it on the baseline x86-64 target (its rounding instruction needs SSE4.1), and the
//! boxes of arcs and the directions round the tool round numbers in hot loops.

/// `x.ceil()`, through an integer for the finite values within ±1e15; beyond (and NaN),
/// `f64::ceil`.
pub(crate) fn ceil(x: f64) -> f64 {
    if x.abs() < 1e15 {
        let t = x as i64 as f64;
        // The truncation rounds towards zero; a positive fraction goes up one.
        if t < x {
            t + 1.0
        } else {
            // (-0.5 gives 0.0 where `f64::ceil` gives -0.0: the same number.)
            t
        }
    } else {
        x.ceil()
    }
}

/// `x.floor()`, as [`ceil`].
pub(crate) fn floor(x: f64) -> f64 {
    if x.abs() < 1e15 {
        let t = x as i64 as f64;
        // The truncation rounds towards zero; a negative fraction goes down one.
        if t > x {
            t - 1.0
        } else {
            t
        }
    } else {
        x.floor()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn rounding_through_an_integer_is_the_library_rounding() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            1e15,
            -1e15,
            3e15,
            f64::MAX,
            f64::MIN,
        ];
        values.extend((-4000..=4000).map(|k| k as f64 * 0.001 * std::f64::consts::FRAC_PI_2));
        values.extend((-8..=8).flat_map(|k| {
            let x = k as f64;
            [x.next_down(), x, x.next_up()]
        }));
        for x in values {
            assert_eq!(super::ceil(x), x.ceil(), "{x}");
            assert_eq!(super::floor(x), x.floor(), "{x}");
        }
    }
}
