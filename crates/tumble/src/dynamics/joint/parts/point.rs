//! Three rows making two material points coincide (ball-and-socket, and the point half of hinge
//! and fixed joints).
//!
//! With anchors at offsets `r_a`, `r_b` from the centres of mass (world frame),
//!
//! ```text
//! C = (x_b + r_b) − (x_a + r_a)
//! Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a = v_b − r̂_b ω_b − v_a + r̂_a ω_a
//! J = [ −1   r̂_a   1   −r̂_b ]            (columns v_a, ω_a, v_b, ω_b)
//! K = J M⁻¹ Jᵀ = (1/m_a + 1/m_b)·1 − r̂_a I_a⁻¹ r̂_a − r̂_b I_b⁻¹ r̂_b
//! ```
//!
//! `K` is the lecture's point inverse mass matrix `K(r, r)` summed over the two bodies: the
//! velocity change of the relative point per unit impulse. It is symmetric positive definite when
//! either body is dynamic, so the three rows are solved together as one 3×3 block.

use super::{apply_point_impulse, invert_or_zero, point_mass_matrix};
use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct PointPart {
    /// Accumulated linear impulse on body b (−impulse on a), world frame.
    pub impulse: DVec3,
}

impl PointPart {
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody, r_a: DVec3, r_b: DVec3) {
        apply_point_impulse(a, b, r_a, r_b, self.impulse);
    }

    /// One soft solve of the three rows with the position error `c` (anchor b − anchor a);
    /// `softness` is `RIGID_VELOCITY` in the relax pass.
    pub fn solve(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        r_a: DVec3,
        r_b: DVec3,
        c: DVec3,
        softness: Softness,
    ) {
        let cdot = b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a);
        let k = point_mass_matrix(a, r_a) + point_mass_matrix(b, r_b);
        let p = -softness.mass_scale * (invert_or_zero(k) * (cdot + softness.bias_rate * c))
            - softness.impulse_scale * self.impulse;
        self.impulse += p;
        apply_point_impulse(a, b, r_a, r_b, p);
    }
}
