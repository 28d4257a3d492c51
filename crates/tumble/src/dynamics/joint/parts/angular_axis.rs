//! One angular row about a world axis `n`: the relative rotation rate of b about `n`.
//! Used for hinge angle limits, motors and springs, and for the ball joint's swing and twist
//! limits.
//!
//! ```text
//! Ċ = n·(ω_b − ω_a),   J = [ 0  −nᵀ  0  nᵀ ],   K = nᵀ (I_a⁻¹ + I_b⁻¹) n
//! ```
//!
//! The axis is whatever the angle's rate is measured about: the hinge axis for a hinge angle,
//! the normal of the plane of the two axes for a swing (cone) angle, the half-way axis for a twist.

use super::{invert_scalar_or_zero, RowDrive};
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct AngularAxisPart {
    /// Accumulated angular impulse about the row's axis.
    pub impulse: f64,
}

#[inline]
fn effective_mass(a: &SolverBody, b: &SolverBody, axis: DVec3) -> f64 {
    invert_scalar_or_zero(axis.dot(a.inv_inertia * axis) + axis.dot(b.inv_inertia * axis))
}

#[inline]
fn apply(a: &mut SolverBody, b: &mut SolverBody, axis: DVec3, lambda: f64) {
    let l = lambda * axis;
    a.w -= a.inv_inertia * l;
    b.w += b.inv_inertia * l;
}

impl AngularAxisPart {
    /// `n·(ω_b − ω_a)`.
    #[inline]
    pub fn velocity(a: &SolverBody, b: &SolverBody, axis: DVec3) -> f64 {
        axis.dot(b.w - a.w)
    }

    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody, axis: DVec3) {
        if self.impulse != 0.0 {
            apply(a, b, axis, self.impulse);
        }
    }

    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, axis: DVec3, drive: RowDrive) {
        let m = effective_mass(a, b, axis);
        let applied = drive.solve(&mut self.impulse, m, Self::velocity(a, b, axis));
        apply(a, b, axis, applied);
    }
}
