//! Outward rounding: turning an `f64` result into an `f32` bound that is never
//! on the wrong side.
//!
//! Bounding volumes must contain their primitives *in floating point*, or a
//! query can miss an overlap by one ulp. Fitting code computes in `f64` and
//! rounds the final bound outward with these helpers.

/// Largest `f32` that is `<= v`.
#[inline]
pub fn down(v: f64) -> f32 {
    let f = v as f32;
    if (f as f64) > v {
        f.next_down()
    } else {
        f
    }
}

/// Smallest `f32` that is `>= v`.
#[inline]
pub fn up(v: f64) -> f32 {
    let f = v as f32;
    if (f as f64) < v {
        f.next_up()
    } else {
        f
    }
}

/// Relative slack used by conservative `f32` comparisons (64 ulps).
///
/// An overlap test computed in `f32` may round either way; comparing against a
/// bound widened by this factor makes it err only towards "overlapping".
pub const SLACK: f32 = 64.0 * f32::EPSILON;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_outward() {
        let v = 0.1f64;
        assert!((down(v) as f64) <= v && (up(v) as f64) >= v);
        assert!(down(v) < up(v));
        assert_eq!(down(0.5), 0.5);
        assert_eq!(up(0.5), 0.5);
        let big = 1.0e30f64 + 12345.0;
        assert!((down(big) as f64) <= big && (up(big) as f64) >= big);
    }
}
