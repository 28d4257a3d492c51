//! Two angular rows keeping the hinge axis `a₁` of body a aligned with the hinge axis `a₂` of
//! body b, leaving rotation about the axis free.
//!
//! Take `b₂`, `c₂` perpendicular to `a₂` in body b. The axes are aligned when `a₁` is
//! perpendicular to both:
//!
//! ```text
//! C = ( a₁·b₂ , a₁·c₂ )
//! d/dt (a₁·b₂) = (ω_a × a₁)·b₂ + a₁·(ω_b × b₂) = (ω_b − ω_a)·(b₂ × a₁)
//! J = [ 0  −uᵀ  0  uᵀ ;  0  −wᵀ  0  wᵀ ],   u = b₂ × a₁,  w = c₂ × a₁
//! K = [ uᵀ(I_a⁻¹ + I_b⁻¹)u   uᵀ(I_a⁻¹ + I_b⁻¹)w ;  wᵀ(…)u   wᵀ(…)w ]       (2×2)
//! ```
//!
//! Near alignment `u ≈ −c₂`-ish and `w ≈ b₂`-ish span the plane perpendicular to the axis, so `K`
//! is well conditioned; the two rows are solved together as a 2×2 block.

use super::apply_angular_impulse;
use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{DMat3, DVec3};
use glam::{DMat2, DVec2};

#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct HingeRotationPart {
    /// Accumulated impulses of the two rows.
    pub impulse: DVec2,
}

/// The current geometry of the two rows, all world frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct HingeAxes {
    /// Hinge axis fixed in body a.
    pub axis_a: DVec3,
    /// Two unit vectors perpendicular to the hinge axis fixed in body b.
    pub perpendicular_b: [DVec3; 2],
}

impl HingeAxes {
    pub fn jacobians(&self) -> (DVec3, DVec3) {
        (self.perpendicular_b[0].cross(self.axis_a), self.perpendicular_b[1].cross(self.axis_a))
    }

    /// The position error `C`.
    pub fn error(&self) -> DVec2 {
        DVec2::new(self.axis_a.dot(self.perpendicular_b[0]), self.axis_a.dot(self.perpendicular_b[1]))
    }
}

impl HingeRotationPart {
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody, axes: &HingeAxes) {
        let (u, w) = axes.jacobians();
        apply_angular_impulse(a, b, self.impulse.x * u + self.impulse.y * w);
    }

    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, axes: &HingeAxes, softness: Softness) {
        let (u, w) = axes.jacobians();
        let dw = b.w - a.w;
        let cdot = DVec2::new(u.dot(dw), w.dot(dw));
        let inv_i: DMat3 = a.inv_inertia + b.inv_inertia;
        let (iu, iw) = (inv_i * u, inv_i * w);
        let k = DMat2::from_cols(DVec2::new(u.dot(iu), w.dot(iu)), DVec2::new(u.dot(iw), w.dot(iw)));
        let det = k.determinant();
        // Singular only when neither body can rotate: then the rows are off.
        let m = if det > 1e-12 * (k.x_axis.x * k.y_axis.y).abs() && det > 0.0 {
            k.inverse()
        } else {
            DMat2::ZERO
        };
        let lambda = -softness.mass_scale * (m * (cdot + softness.bias_rate * axes.error()))
            - softness.impulse_scale * self.impulse;
        self.impulse += lambda;
        apply_angular_impulse(a, b, lambda.x * u + lambda.y * w);
    }
}
