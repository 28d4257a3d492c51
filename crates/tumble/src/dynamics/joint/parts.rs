//! Constraint parts: the pieces every joint is assembled from (after Jolt's `ConstraintPart`s).
//! Each part owns its rows' effective mass and accumulated impulse and knows how to warm start
//! and solve itself between two bodies. Anchors are stored relative to each body's centre of
//! mass in the body frame and rotated with the body's current orientation at every substep.
//!
//! Sign conventions: the constraint velocity is `Ċ = J_b·(v_b, ω_b) − J_a·(v_a, ω_a)`, an impulse
//! `λ` is applied `+` to body b and `−` to body a.

use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{hat, DMat3, DVec3};

/// Inverts a symmetric positive semi-definite 3×3 effective-mass matrix; a singular one (both
/// bodies fixed, or a degenerate axis) gives zero, which disables the rows instead of producing NaN.
pub(crate) fn invert_or_zero(k: DMat3) -> DMat3 {
    let det = k.determinant();
    let scale = k.to_cols_array().iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    if scale == 0.0 || det.abs() <= 1e-12 * scale * scale * scale {
        DMat3::ZERO
    } else {
        k.inverse()
    }
}

/// `K(r, r)` of one body for a point at offset `r`: `(1/m)·1 − r̂ I⁻¹ r̂`.
#[inline]
pub(crate) fn point_mass_matrix(body: &SolverBody, r: DVec3) -> DMat3 {
    let rh = hat(r);
    DMat3::from_diagonal(DVec3::splat(body.inv_mass)) - rh * body.inv_inertia * rh
}

/// Applies the linear impulse `p` at offsets `r_a`, `r_b`: `−p` to a, `+p` to b.
#[inline]
pub(crate) fn apply_point_impulse(a: &mut SolverBody, b: &mut SolverBody, r_a: DVec3, r_b: DVec3, p: DVec3) {
    a.v -= a.inv_mass * p;
    a.w -= a.inv_inertia * r_a.cross(p);
    b.v += b.inv_mass * p;
    b.w += b.inv_inertia * r_b.cross(p);
}

/// Applies the angular impulse `l`: `−l` to a, `+l` to b.
#[inline]
pub(crate) fn apply_angular_impulse(a: &mut SolverBody, b: &mut SolverBody, l: DVec3) {
    a.w -= a.inv_inertia * l;
    b.w += b.inv_inertia * l;
}

/// Three rows that make two material points coincide: the ball-and-socket constraint
/// `C = (x_b + r_b) − (x_a + r_a) = 0`, `Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a`,
/// effective mass `K = K_a(r_a, r_a) + K_b(r_b, r_b)`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PointPart {
    /// Anchor offsets from each centre of mass, body frames.
    pub r_a_local: DVec3,
    pub r_b_local: DVec3,
    /// `x_b − x_a` at the start of the step (positions then move by the bodies' `dp`).
    pub delta_center: DVec3,
    pub impulse: DVec3,
}

impl PointPart {
    /// Current anchor offsets, world frame.
    #[inline]
    pub fn offsets(&self, a: &SolverBody, b: &SolverBody) -> (DVec3, DVec3) {
        (a.q * self.r_a_local, b.q * self.r_b_local)
    }

    /// The position error `C` now.
    #[inline]
    pub fn error(&self, a: &SolverBody, b: &SolverBody) -> DVec3 {
        let (r_a, r_b) = self.offsets(a, b);
        (b.dp - a.dp) + self.delta_center + (r_b - r_a)
    }

    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        let (r_a, r_b) = self.offsets(a, b);
        apply_point_impulse(a, b, r_a, r_b, self.impulse);
    }

    /// One soft solve of the three rows; `softness` is `RIGID_VELOCITY` in the relax pass.
    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, softness: Softness) {
        let (r_a, r_b) = self.offsets(a, b);
        let c = (b.dp - a.dp) + self.delta_center + (r_b - r_a);
        let cdot = b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a);
        let k = point_mass_matrix(a, r_a) + point_mass_matrix(b, r_b);
        let bias = softness.bias_rate * c;
        let p = -softness.mass_scale * (invert_or_zero(k) * (cdot + bias))
            - softness.impulse_scale * self.impulse;
        self.impulse += p;
        apply_point_impulse(a, b, r_a, r_b, p);
    }
}
