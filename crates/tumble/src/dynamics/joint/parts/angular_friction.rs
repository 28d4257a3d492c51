//! Three angular rows resisting relative rotation with a bounded torque: joint friction (a ball
//! joint's, like the friction of a shoulder or hip).
//!
//! ```text
//! Ċ = ω_b − ω_a,   J = [ 0  −1  0  1 ],   K = I_a⁻¹ + I_b⁻¹
//! λ_acc ← clamp_disc(λ_acc − K⁻¹ Ċ, τ_max h)
//! ```
//!
//! The accumulated impulse is clamped to a ball of radius `τ_max h` (the largest friction torque
//! over a substep), as Coulomb friction is clamped to its disc: below the limit the joint sticks,
//! above it it slips with the full friction torque opposing the motion. Friction has no position
//! error, so the solve and relax passes are the same.

use super::{apply_angular_impulse, invert_or_zero};
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct AngularFrictionPart {
    /// Accumulated angular impulse on body b (−impulse on a), world frame.
    pub impulse: DVec3,
}

impl AngularFrictionPart {
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        apply_angular_impulse(a, b, self.impulse);
    }

    /// One solve with the substep's largest friction impulse `max_impulse` (torque × h).
    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, max_impulse: f64) {
        let cdot = b.w - a.w;
        let old = self.impulse;
        let mut new = old - invert_or_zero(a.inv_inertia + b.inv_inertia) * cdot;
        let length = new.length();
        if length > max_impulse {
            new *= max_impulse / length;
        }
        self.impulse = new;
        apply_angular_impulse(a, b, new - old);
    }
}
