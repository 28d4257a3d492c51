//! Arithmetic written once for one value (`f64`) and for four side by side in SIMD lanes
//! (`wide::f64x4`), so that a solver stage can run on one constraint or on four at once and give
//! each the very same bits.
//!
//! [`Lane`] is the scalar type's interface: the four operations, comparisons into a mask, and
//! selection by a mask. [`V3`] and [`M3`] are glam's `DVec3` and `DMat3` over a lane type, with
//! glam's order of operations (`dot` is `(x·x' + y·y') + z·z'`, a matrix times a vector adds the
//! columns from the first), so `V3<f64>` gives exactly what `DVec3` gives. IEEE arithmetic is
//! exact per lane, so `f64x4` gives each lane exactly what `f64` gives, whichever instruction set
//! the build targets (two SSE2 halves or one AVX register).
//!
//! Branches become selections: both sides are computed and a mask picks one per lane. `min`,
//! `max` and `clamp` are defined here through comparisons (not the instructions' own minimum,
//! whose answer for two zeros of opposite sign differs between instruction sets) and return what
//! `f64::min`, `f64::max` and `f64::clamp` return for every pair that is not two zeros.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use wide::f64x4;

use crate::math::{DMat3, DVec3};

/// A scalar type with lanes: `f64` (one) or `f64x4` (four).
pub(crate) trait Lane:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// A truth value per lane.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// How many lanes.
    const LANES: usize;

    fn splat(x: f64) -> Self;
    /// The value whose lane `k` is `f(k)`.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// Lane `k`.
    fn lane(self, k: usize) -> f64;
    fn gt(self, rhs: Self) -> Self::Mask;
    fn lt(self, rhs: Self) -> Self::Mask;
    fn ge(self, rhs: Self) -> Self::Mask;
    fn ne(self, rhs: Self) -> Self::Mask;
    fn is_nan(self) -> Self::Mask;
    /// `if_true` where `mask` holds, else `if_false`.
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    fn mask_splat(b: bool) -> Self::Mask;
    fn mask_from_fn(f: impl FnMut(usize) -> bool) -> Self::Mask;
    fn mask_lane(mask: Self::Mask, k: usize) -> bool;
    fn any(mask: Self::Mask) -> bool;

    /// The same value, which the optimiser may no longer trace to where it was read. For a value
    /// read from a place, selected between per lane and written back to the same place
    /// (`*p = select(mask, new, p.opaque())`): without it the compiler turns that into a masked
    /// store of `new` (`vmaskmovpd`), which on AMD's Zen processors costs far more than the blend
    /// and the plain store it replaces, and whose value a load that follows cannot take from the
    /// store queue (the still manifolds' passes, contact_lanes.rs: about 3% of the matched
    /// pyramid's substeps). The same bits.
    #[inline(always)]
    fn opaque(self) -> Self {
        self
    }

    /// `if_true` where `mask` holds, else `if_false`, for masks.
    #[inline(always)]
    fn select_mask(mask: Self::Mask, if_true: Self::Mask, if_false: Self::Mask) -> Self::Mask {
        (mask & if_true) | (!mask & if_false)
    }

    /// As `f64::max`: the larger, or the one that is not NaN.
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        Self::select(rhs.is_nan() | self.gt(rhs), self, rhs)
    }

    /// As `f64::min`: the smaller, or the one that is not NaN.
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        Self::select(rhs.is_nan() | self.lt(rhs), self, rhs)
    }

    /// As `f64::clamp` (with `lower ≤ upper`).
    #[inline(always)]
    fn clamp(self, lower: Self, upper: Self) -> Self {
        let x = Self::select(self.lt(lower), lower, self);
        Self::select(x.gt(upper), upper, x)
    }
}

impl Lane for f64 {
    type Mask = bool;
    const LANES: usize = 1;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(self, _k: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn gt(self, rhs: Self) -> bool {
        self > rhs
    }
    #[inline(always)]
    fn lt(self, rhs: Self) -> bool {
        self < rhs
    }
    #[inline(always)]
    fn ge(self, rhs: Self) -> bool {
        self >= rhs
    }
    #[inline(always)]
    fn ne(self, rhs: Self) -> bool {
        self != rhs
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        f64::is_nan(self)
    }
    #[inline(always)]
    fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
        if mask {
            if_true
        } else {
            if_false
        }
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn mask_splat(b: bool) -> bool {
        b
    }
    #[inline(always)]
    fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> bool {
        f(0)
    }
    #[inline(always)]
    fn mask_lane(mask: bool, _k: usize) -> bool {
        mask
    }
    #[inline(always)]
    fn any(mask: bool) -> bool {
        mask
    }
}

impl Lane for f64x4 {
    type Mask = f64x4;
    const LANES: usize = 4;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        f64x4::new([f(0), f(1), f(2), f(3)])
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.as_array()[k]
    }
    #[inline(always)]
    fn gt(self, rhs: Self) -> f64x4 {
        self.simd_gt(rhs)
    }
    #[inline(always)]
    fn lt(self, rhs: Self) -> f64x4 {
        self.simd_lt(rhs)
    }
    #[inline(always)]
    fn ge(self, rhs: Self) -> f64x4 {
        self.simd_ge(rhs)
    }
    #[inline(always)]
    fn ne(self, rhs: Self) -> f64x4 {
        self.simd_ne(rhs)
    }
    #[inline(always)]
    fn is_nan(self) -> f64x4 {
        f64x4::is_nan(self)
    }
    #[inline(always)]
    fn select(mask: f64x4, if_true: Self, if_false: Self) -> Self {
        mask.select(if_true, if_false)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64x4::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64x4::abs(self)
    }
    #[inline(always)]
    fn mask_splat(b: bool) -> f64x4 {
        if b {
            f64x4::splat(0.0).simd_eq(f64x4::splat(0.0))
        } else {
            f64x4::splat(0.0)
        }
    }
    #[inline(always)]
    fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> f64x4 {
        let bits = |b: bool| if b { f64::from_bits(u64::MAX) } else { 0.0 };
        f64x4::new([bits(f(0)), bits(f(1)), bits(f(2)), bits(f(3))])
    }
    #[inline(always)]
    fn mask_lane(mask: f64x4, k: usize) -> bool {
        mask.to_bitmask() & (1 << k) != 0
    }
    #[inline(always)]
    fn any(mask: f64x4) -> bool {
        mask.any()
    }
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    #[allow(unsafe_code)] // An empty `asm!` on a register, and the casts to and from it.
    #[inline(always)]
    fn opaque(self) -> f64x4 {
        use std::arch::x86_64::__m256d;
        // SAFETY: with AVX, `f64x4` is one `__m256d` (four `f64` in 32 bytes), and any bits are
        // a valid value of either.
        let mut register: __m256d = unsafe { std::mem::transmute::<f64x4, __m256d>(self) };
        // SAFETY: an empty template: it reads and writes nothing but names the register, so the
        // compiler must take its value as unknown.
        unsafe {
            std::arch::asm!("/* {0} */", inout(ymm_reg) register, options(pure, nomem, nostack, preserves_flags))
        };
        // SAFETY: as above.
        unsafe { std::mem::transmute::<__m256d, f64x4>(register) }
    }
}

/// `DVec3` over a lane type.
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lane> V3<L> {
    #[inline(always)]
    pub fn zero() -> Self {
        Self::splat(0.0)
    }

    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        V3 { x: L::splat(x), y: L::splat(x), z: L::splat(x) }
    }

    /// The vector whose lane `k` is `f(k)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> DVec3) -> Self {
        let mut v = [DVec3::ZERO; 4];
        for (k, slot) in v.iter_mut().enumerate().take(L::LANES) {
            *slot = f(k);
        }
        V3 { x: L::from_fn(|k| v[k].x), y: L::from_fn(|k| v[k].y), z: L::from_fn(|k| v[k].z) }
    }

    /// Lane `k`.
    #[inline(always)]
    pub fn lane(self, k: usize) -> DVec3 {
        DVec3::new(self.x.lane(k), self.y.lane(k), self.z.lane(k))
    }

    #[inline(always)]
    pub fn dot(self, rhs: Self) -> L {
        (self.x * rhs.x) + (self.y * rhs.y) + (self.z * rhs.z)
    }

    #[inline(always)]
    pub fn cross(self, rhs: Self) -> Self {
        V3 {
            x: self.y * rhs.z - rhs.y * self.z,
            y: self.z * rhs.x - rhs.z * self.x,
            z: self.x * rhs.y - rhs.x * self.y,
        }
    }

    #[inline(always)]
    pub fn length(self) -> L {
        self.dot(self).sqrt()
    }

    /// Every component times `s` (`DVec3 * f64`, and `f64 * DVec3`: the same products).
    #[inline(always)]
    pub fn scale(self, s: L) -> Self {
        V3 { x: self.x * s, y: self.y * s, z: self.z * s }
    }

    /// Whether any component is not zero (`DVec3 != DVec3::ZERO`).
    #[inline(always)]
    pub fn ne_zero(self) -> L::Mask {
        let zero = L::splat(0.0);
        self.x.ne(zero) | self.y.ne(zero) | self.z.ne(zero)
    }

    #[inline(always)]
    pub fn select(mask: L::Mask, if_true: Self, if_false: Self) -> Self {
        V3 {
            x: L::select(mask, if_true.x, if_false.x),
            y: L::select(mask, if_true.y, if_false.y),
            z: L::select(mask, if_true.z, if_false.z),
        }
    }
}

impl<L: Lane> Add for V3<L> {
    type Output = Self;
    #[inline(always)]
    fn add(self, rhs: Self) -> Self {
        V3 { x: self.x + rhs.x, y: self.y + rhs.y, z: self.z + rhs.z }
    }
}

impl<L: Lane> Sub for V3<L> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, rhs: Self) -> Self {
        V3 { x: self.x - rhs.x, y: self.y - rhs.y, z: self.z - rhs.z }
    }
}

/// `DMat3` over a lane type, by columns.
#[derive(Clone, Copy, Debug)]
pub(crate) struct M3<L> {
    pub x_axis: V3<L>,
    pub y_axis: V3<L>,
    pub z_axis: V3<L>,
}

impl<L: Lane> M3<L> {
    /// The matrix whose lane `k` is `f(k)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> DMat3) -> Self {
        let mut m = [DMat3::ZERO; 4];
        for (k, slot) in m.iter_mut().enumerate().take(L::LANES) {
            *slot = f(k);
        }
        M3 {
            x_axis: V3::from_fn(|k| m[k].x_axis),
            y_axis: V3::from_fn(|k| m[k].y_axis),
            z_axis: V3::from_fn(|k| m[k].z_axis),
        }
    }

    /// `self * v`, in glam's order.
    #[inline(always)]
    pub fn mul_vec3(&self, v: V3<L>) -> V3<L> {
        let mut res = self.x_axis.scale(v.x);
        res = res + self.y_axis.scale(v.y);
        res + self.z_axis.scale(v.z)
    }
}

impl<L: Lane> Add for M3<L> {
    type Output = Self;
    #[inline(always)]
    fn add(self, rhs: Self) -> Self {
        M3 {
            x_axis: self.x_axis + rhs.x_axis,
            y_axis: self.y_axis + rhs.y_axis,
            z_axis: self.z_axis + rhs.z_axis,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;

    /// Each lane of the four-wide arithmetic gives the bits of the scalar arithmetic, and the
    /// scalar `V3`/`M3` give glam's bits.
    #[test]
    fn four_lanes_give_the_bits_of_one_and_of_glam() {
        let vectors = [
            DVec3::new(0.1, -2.5, 3.7),
            DVec3::new(-1e-17, 4.0, 0.3333),
            DVec3::new(7.25, 1e300, -0.0),
            DVec3::new(0.0, -0.0, 2.0_f64.sqrt()),
        ];
        let other =
            [DVec3::new(-0.7, 0.2, 9.1), DVec3::X, DVec3::new(3.0, -1e-300, 0.5), DVec3::new(1.0, 2.0, 3.0)];
        let matrices: [DMat3; 4] = std::array::from_fn(|k| {
            DMat3::from_quat(DQuat::from_rotation_y(0.3 * k as f64 + 0.1)) * (k as f64 + 0.5)
        });
        let wide_v = V3::<f64x4>::from_fn(|k| vectors[k]);
        let wide_o = V3::<f64x4>::from_fn(|k| other[k]);
        let wide_m = M3::<f64x4>::from_fn(|k| matrices[k]);
        for k in 0..4 {
            let (v, o, m) = (vectors[k], other[k], matrices[k]);
            let (sv, so) = (V3::<f64>::from_fn(|_| v), V3::<f64>::from_fn(|_| o));
            let sm = M3::<f64>::from_fn(|_| m);
            assert_eq!(sv.dot(so).to_bits(), v.dot(o).to_bits());
            assert_eq!(sv.cross(so).lane(0), v.cross(o));
            assert_eq!(sm.mul_vec3(so).lane(0), m * o);
            assert_eq!(wide_v.dot(wide_o).lane(k).to_bits(), v.dot(o).to_bits());
            assert_eq!(wide_v.cross(wide_o).lane(k), v.cross(o));
            assert_eq!(wide_m.mul_vec3(wide_o).lane(k), m * o);
            assert_eq!(wide_v.length().lane(k).to_bits(), v.length().to_bits());
            let (a, b) = (v.x, o.y);
            let (wa, wb) = (wide_v.x, wide_o.y);
            assert_eq!(Lane::max(wa, wb).lane(k).to_bits(), a.max(b).to_bits());
            assert_eq!(Lane::min(wa, wb).lane(k).to_bits(), a.min(b).to_bits());
        }
        // NaN on either side: the other one, as `f64::max` and `f64::min`.
        let (nan, one) = (f64x4::splat(f64::NAN), f64x4::splat(1.0));
        assert_eq!(Lane::max(nan, one).lane(2), 1.0);
        assert_eq!(Lane::min(one, nan).lane(1), 1.0);
        assert_eq!(Lane::max(f64::NAN, 1.0), 1.0);
        assert!(<f64x4 as Lane>::mask_lane(f64x4::mask_from_fn(|k| k == 2), 2));
        assert!(!<f64x4 as Lane>::mask_lane(f64x4::mask_from_fn(|k| k == 2), 1));
        assert!(!f64x4::any(f64x4::mask_splat(false)));
    }
}
