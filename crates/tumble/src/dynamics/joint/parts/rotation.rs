//! Three angular rows locking the relative orientation of two bodies (fixed joint, slider).
//!
//! With the joint frames' world orientations `F_a`, `F_b` (equal when the constraint holds), the
//! error rotation `q = F_b F_a⁻¹` takes frame a onto frame b. For a small error
//! `q ≈ (θ/2·e, 1)`, so `C = 2·vec(q)` (sign chosen so `w ≥ 0`) is the rotation vector `θ e`.
//! Differentiating, `q̇ = ½ ω_b q − ½ q ω_a ≈ ½ (ω_b − ω_a)` near `q = 1`, so
//!
//! ```text
//! Ċ ≈ ω_b − ω_a,   J = [ 0  −1  0  1 ],   K = I_a⁻¹ + I_b⁻¹
//! ```
//!
//! The Jacobian is exact at `C = 0` and the error is kept small by the solver, which is why the
//! linearisation is enough (as Jolt's `RotationEulerConstraintPart`).

use super::{apply_angular_impulse, invert_or_zero};
use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{DQuat, DVec3};

#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct RotationPart {
    /// Accumulated angular impulse on body b (−impulse on a), world frame.
    pub impulse: DVec3,
}

impl RotationPart {
    /// The rotation vector taking frame a (world orientation `rotation_a`) onto frame b.
    pub fn error(rotation_a: DQuat, rotation_b: DQuat) -> DVec3 {
        let q = rotation_b * rotation_a.inverse();
        let q = if q.w < 0.0 { -q } else { q };
        2.0 * DVec3::new(q.x, q.y, q.z)
    }

    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        apply_angular_impulse(a, b, self.impulse);
    }

    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, c: DVec3, softness: Softness) {
        let cdot = b.w - a.w;
        let k = a.inv_inertia + b.inv_inertia;
        let l = -softness.mass_scale * (invert_or_zero(k) * (cdot + softness.bias_rate * c))
            - softness.impulse_scale * self.impulse;
        self.impulse += l;
        apply_angular_impulse(a, b, l);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_is_the_rotation_vector_for_small_angles() {
        let fa = DQuat::from_rotation_y(0.4);
        let delta = DVec3::new(0.001, -0.002, 0.0005);
        let fb = DQuat::from_scaled_axis(delta) * fa;
        assert!((RotationPart::error(fa, fb) - delta).length() < 1e-9);
    }
}
