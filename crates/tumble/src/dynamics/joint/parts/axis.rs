//! One row along a world direction `n`: relative motion of two material points along `n`.
//! Used by slider rows, limits, motors and springs, distance joints, and (later) contact normal
//! and friction rows.
//!
//! For anchors at offsets `r_a`, `r_b` and `C = n·(p_b − p_a)`:
//!
//! * `n` fixed in space, or the unit vector between the anchors (distance joint, contact):
//!   `Ċ = n·(v_b + ω_b × r_b − v_a − ω_a × r_a)`, so
//!   `J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ]`.
//!   (For the distance `|d|`, the rotation of `n` is perpendicular to `n` and drops out.)
//! * `n` fixed in body a (slider): `ṅ = ω_a × n` adds `(ω_a × n)·d` with `d = p_b − p_a`, which
//!   moves body a's lever arm from `r_a` to `r_a + d`:
//!   `J = [ −nᵀ  −((r_a + d) × n)ᵀ  nᵀ  (r_b × n)ᵀ ]`.
//!
//! The effective mass is a scalar,
//! `K = (1/m_a + 1/m_b)|n|² + (ρ_a)ᵀ I_a⁻¹ ρ_a + (ρ_b)ᵀ I_b⁻¹ ρ_b` with `ρ` the angular Jacobians.

use super::{invert_scalar_or_zero, RowDrive};
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// The Jacobian of one linear row: `Ċ = linear·(v_b − v_a) + angular_b·ω_b − angular_a·ω_a`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct AxisJacobian {
    pub linear: DVec3,
    pub angular_a: DVec3,
    pub angular_b: DVec3,
}

impl AxisJacobian {
    /// `n` fixed in space or along the line between the anchors (`r_a`, `r_b` world offsets).
    pub fn between_points(n: DVec3, r_a: DVec3, r_b: DVec3) -> AxisJacobian {
        AxisJacobian { linear: n, angular_a: r_a.cross(n), angular_b: r_b.cross(n) }
    }

    /// `n` fixed in body a; `separation` is anchor b − anchor a, world frame.
    pub fn along_axis_of_a(n: DVec3, r_a: DVec3, r_b: DVec3, separation: DVec3) -> AxisJacobian {
        AxisJacobian { linear: n, angular_a: (r_a + separation).cross(n), angular_b: r_b.cross(n) }
    }

    /// The row with the opposite sign (the upper side of a limit).
    pub fn negated(self) -> AxisJacobian {
        AxisJacobian { linear: -self.linear, angular_a: -self.angular_a, angular_b: -self.angular_b }
    }

    #[inline]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        self.linear.dot(b.v - a.v) + self.angular_b.dot(b.w) - self.angular_a.dot(a.w)
    }

    /// `1/K`, or 0 when the row moves neither body.
    #[inline]
    pub fn effective_mass(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        let k = (a.inv_mass + b.inv_mass) * self.linear.length_squared()
            + self.angular_a.dot(a.inv_inertia * self.angular_a)
            + self.angular_b.dot(b.inv_inertia * self.angular_b);
        invert_scalar_or_zero(k)
    }

    /// Applies `+Jᵀλ` to b and `−Jᵀλ` to a.
    #[inline]
    pub fn apply(&self, a: &mut SolverBody, b: &mut SolverBody, lambda: f64) {
        a.v -= (a.inv_mass * lambda) * self.linear;
        a.w -= a.inv_inertia * (lambda * self.angular_a);
        b.v += (b.inv_mass * lambda) * self.linear;
        b.w += b.inv_inertia * (lambda * self.angular_b);
    }
}

/// A scalar linear row and its accumulated impulse.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct AxisPart {
    pub impulse: f64,
}

impl AxisPart {
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody, jacobian: &AxisJacobian) {
        if self.impulse != 0.0 {
            jacobian.apply(a, b, self.impulse);
        }
    }

    pub fn solve(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        jacobian: &AxisJacobian,
        drive: RowDrive,
    ) {
        let m = jacobian.effective_mass(a, b);
        let applied = drive.solve(&mut self.impulse, m, jacobian.velocity(a, b));
        jacobian.apply(a, b, applied);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::softness::Softness;
    use crate::math::{DMat3, DQuat};

    fn body(inv_mass: f64, inv_inertia: DVec3) -> SolverBody {
        let mut body = SolverBody::FIXED;
        body.inv_mass = inv_mass;
        body.inv_inertia = DMat3::from_diagonal(inv_inertia);
        body
    }

    /// The Jacobian of a row with the axis fixed in body a equals the finite-difference rate of
    /// `C = n(q_a)·(p_b − p_a)`.
    #[test]
    fn body_fixed_axis_jacobian_matches_finite_differences() {
        let mut a = body(1.0, DVec3::ONE);
        let mut b = body(1.0, DVec3::ONE);
        a.v = DVec3::new(0.3, -0.2, 0.5);
        a.w = DVec3::new(1.1, -0.4, 0.7);
        b.v = DVec3::new(-0.6, 0.1, 0.2);
        b.w = DVec3::new(-0.3, 0.9, 0.4);
        let (xa, xb) = (DVec3::new(0.1, 0.2, 0.3), DVec3::new(1.0, -0.5, 0.8));
        let (ra_local, rb_local, n_local) =
            (DVec3::new(0.4, 0.0, -0.2), DVec3::new(-0.3, 0.2, 0.1), DVec3::new(0.0, 0.6, 0.8));
        let c = |t: f64| {
            let qa = DQuat::from_scaled_axis(a.w * t);
            let qb = DQuat::from_scaled_axis(b.w * t);
            let pa = xa + a.v * t + qa * ra_local;
            let pb = xb + b.v * t + qb * rb_local;
            (qa * n_local).dot(pb - pa)
        };
        let eps = 1e-6;
        let numeric = (c(eps) - c(-eps)) / (2.0 * eps);
        let jac =
            AxisJacobian::along_axis_of_a(n_local, ra_local, rb_local, (xb + rb_local) - (xa + ra_local));
        assert!((jac.velocity(&a, &b) - numeric).abs() < 1e-8, "{} vs {numeric}", jac.velocity(&a, &b));
    }

    /// A rigid solve removes the row's relative velocity exactly.
    #[test]
    fn rigid_solve_zeroes_the_row_velocity() {
        let mut a = body(0.5, DVec3::new(2.0, 1.0, 3.0));
        let mut b = body(2.0, DVec3::new(1.0, 4.0, 0.5));
        a.v = DVec3::new(1.0, 2.0, 0.0);
        b.w = DVec3::new(0.0, 3.0, -1.0);
        let jac =
            AxisJacobian::between_points(DVec3::X, DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 0.0, 1.0));
        let mut part = AxisPart::default();
        part.solve(&mut a, &mut b, &jac, RowDrive::soft(0.0, Softness::RIGID_VELOCITY));
        assert!(jac.velocity(&a, &b).abs() < 1e-14);
    }
}
