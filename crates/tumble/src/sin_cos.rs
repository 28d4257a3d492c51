//! Sine and cosine together, written once over the lane type (`lanes.rs`), so four angles cost
//! about what one does and each gets the same bits alone or beside three others.
//!
//! The free rotation flow (`integrate.rs`) takes five sines and cosines per body and step; in a
//! scene of ten thousand tumbling bodies the C library's `sincos`, called once per angle, was a
//! seventh of the step. Here the angle is reduced to `r ∈ [−π/4, π/4]` by the nearest multiple
//! `k π/2` (Cody and Waite: π/2 split into three parts, the first two with short mantissas so
//! that `k` times them is exact for `|k| < 2²⁸`), then the two minimax polynomials of Cephes
//! (S. L. Moshier, *Methods and Programs for Mathematical Functions*, 1989) give `sin r` and
//! `cos r`, and the quadrant `k mod 4` swaps them and sets their signs.
//!
//! Only the four operations, comparisons and selections: no fused multiply–add, whose presence
//! depends on the instruction set, so the bits are the same on every x86-64 build and in every
//! lane. Rounding to the nearest integer is done by adding and subtracting 1.5·2⁵² (exact for
//! `|x| < 2⁵¹`). The error is at most about one and a half units in the last place (the tests
//! bound it against the C library). Angles beyond [`REDUCED_UP_TO`], where the three-part
//! reduction loses digits, and infinities go to the C library lane by lane; a NaN stays NaN.

use crate::lanes::Lane;

/// Largest `|x|` reduced here; beyond it the C library's reduction (exact for any `x`) is used.
const REDUCED_UP_TO: f64 = 1.0e8;

/// π/2 in three parts: `PIO2_HI` (25 significant bits) and `PIO2_MID` (24) are short enough that
/// their products with a multiple `|k| < 2²⁸` are exact, `PIO2_LO` is the rest. (Below
/// [`REDUCED_UP_TO`], `|k| < 2²⁶`.)
const PIO2_HI: f64 = 1.5707963109016418;
const PIO2_MID: f64 = 1.5893254712295857e-8;
const PIO2_LO: f64 = 6.123233995736766e-17;

/// Adding and subtracting this rounds a double below 2⁵¹ in magnitude to the nearest integer
/// (ties to even): the sum has no bits below the units.
const ROUNDING: f64 = 1.5 * 4_503_599_627_370_496.0;

/// `sin r = r + r³·S(r²)` on `[−π/4, π/4]`, highest coefficient first.
const SIN: [f64; 6] = [
    1.5896230157654656e-10,
    -2.5050747762857807e-8,
    2.7557313621385722e-6,
    -0.0001984126982958954,
    0.008333333333322118,
    -0.1666666666666663,
];

/// `cos r = 1 − r²/2 + r⁴·C(r²)` on `[−π/4, π/4]`, highest coefficient first.
const COS: [f64; 6] = [
    -1.1358536521387682e-11,
    2.087570084197473e-9,
    -2.755731417929674e-7,
    2.4801587288851704e-5,
    -0.0013888888888873056,
    0.041666666666666595,
];

/// The polynomial of the coefficients `c` (highest first) at `z`, by Estrin's scheme: three pairs
/// `c z + c'` side by side, then joined with `z²` and `z⁴` — five dependent operations deep
/// instead of Horner's ten.
#[inline(always)]
fn polynomial<L: Lane>(c: &[f64; 6], z: L) -> L {
    let pair = |high: f64, low: f64| L::splat(high) * z + L::splat(low);
    let (z2, z4) = (z * z, (z * z) * (z * z));
    pair(c[0], c[1]) * z4 + (pair(c[2], c[3]) * z2 + pair(c[4], c[5]))
}

/// `(sin x, cos x)` in every lane.
#[inline(always)]
pub(crate) fn sin_cos<L: Lane>(x: L) -> (L, L) {
    let rounding = L::splat(ROUNDING);
    // The nearest multiple k of π/2, and the remainder r = x − k π/2.
    let k = (x * L::splat(std::f64::consts::FRAC_2_PI) + rounding) - rounding;
    let r = ((x - k * L::splat(PIO2_HI)) - k * L::splat(PIO2_MID)) - k * L::splat(PIO2_LO);
    let z = r * r;
    let sin_r = r + (r * z) * polynomial(&SIN, z);
    let cos_r = (L::splat(1.0) - L::splat(0.5) * z) + (z * z) * polynomial(&COS, z);
    // The quadrant q = k − 4·round(k/4), in {−2, −1, 0, 1, 2} (±2 are the same quadrant).
    let q = k - L::splat(4.0) * ((L::splat(0.25) * k + rounding) - rounding);
    let (half, three_halves) = (L::splat(0.5), L::splat(1.5));
    let odd = q.abs().gt(half) & three_halves.gt(q.abs());
    let (sin_abs, cos_abs) = (L::select(odd, cos_r, sin_r), L::select(odd, sin_r, cos_r));
    // sin is negative in quadrants −1 and ±2, cos in quadrants 1 and ±2.
    let sin_negative = q.lt(-half) | q.gt(three_halves);
    let cos_negative = q.gt(half) | q.lt(-three_halves);
    let (sin, cos) = (L::select(sin_negative, -sin_abs, sin_abs), L::select(cos_negative, -cos_abs, cos_abs));
    let far = x.abs().gt(L::splat(REDUCED_UP_TO));
    if !L::any(far) {
        return (sin, cos);
    }
    let far_sin = L::from_fn(|i| x.lane(i).sin());
    let far_cos = L::from_fn(|i| x.lane(i).cos());
    (L::select(far, far_sin, sin), L::select(far, far_cos, cos))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::rng::SplitMix64;
    use wide::f64x4;

    /// The error of `got` in units of `2⁻⁵²·|want|`, about one unit in the last place. Past
    /// `|x| = 1`, `|want|` is taken as at least 10⁻³: near a zero of sin or cos the remainder's
    /// own rounding (relative to `x`, not to the result) is what limits any reduction.
    fn units(got: f64, want: f64, x: f64) -> f64 {
        let floor = if x.abs() > 1.0 { 1e-3 } else { f64::MIN_POSITIVE };
        (got - want).abs() / (f64::EPSILON * want.abs().max(floor))
    }

    /// Within two units in the last place of the C library (itself correctly rounded in nearly
    /// every case) at angles from 10⁻⁹ to 10⁸ of either sign, and exactly what `f64` gives in
    /// every lane of `f64x4`. A wrong quadrant, sign, coefficient or reduction constant is off
    /// by far more.
    #[test]
    fn agrees_with_the_c_library() {
        let mut rng = SplitMix64::new(7);
        let (mut worst_sin, mut worst_cos) = (0.0f64, 0.0f64);
        let mut quadrants = [0usize; 4];
        for _ in 0..50_000 {
            let angles: [f64; 4] = std::array::from_fn(|_| {
                let magnitude = 10f64.powf(rng.range(-9.0, 8.0));
                if rng.unit() < 0.5 {
                    -magnitude
                } else {
                    magnitude
                }
            });
            let (sin4, cos4) = sin_cos(f64x4::new(angles));
            for (i, &x) in angles.iter().enumerate() {
                let (sin, cos) = sin_cos(x);
                assert_eq!((sin.to_bits(), cos.to_bits()), (sin4.lane(i).to_bits(), cos4.lane(i).to_bits()));
                let (want_sin, want_cos) = x.sin_cos();
                worst_sin = worst_sin.max(units(sin, want_sin, x));
                worst_cos = worst_cos.max(units(cos, want_cos, x));
                quadrants[((x * std::f64::consts::FRAC_2_PI).round() as i64).rem_euclid(4) as usize] += 1;
            }
        }
        assert!(worst_sin <= 2.0 && worst_cos <= 2.0, "sin {worst_sin} ulp, cos {worst_cos} ulp");
        assert!(quadrants.iter().all(|&n| n > 10_000), "{quadrants:?}");
    }

    #[test]
    fn exact_points_and_edges() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(std::f64::consts::FRAC_PI_2);
        assert!((s - 1.0).abs() <= f64::EPSILON && c.abs() < 1e-16, "{s} {c}");
        let (s, c) = sin_cos(-std::f64::consts::PI);
        assert!(s.abs() < 2e-16 && (c + 1.0).abs() <= f64::EPSILON, "{s} {c}");
        // Beyond the reduced range: the C library's answer, lane by lane.
        let big = 3.0e12;
        assert_eq!(sin_cos(big), big.sin_cos());
        let (s4, c4) = sin_cos(f64x4::new([big, 0.5, -big, 1e9]));
        assert_eq!((s4.lane(0), c4.lane(2)), (big.sin(), (-big).cos()));
        assert_eq!((s4.lane(1), c4.lane(1)), sin_cos(0.5));
        assert!(sin_cos(f64::NAN).0.is_nan() && sin_cos(f64::INFINITY).1.is_nan());
    }
}
