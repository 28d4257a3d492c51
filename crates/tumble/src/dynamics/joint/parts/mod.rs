//! Constraint parts: the pieces every joint is assembled from (after Jolt's `ConstraintPart`s).
//!
//! A part is the math of one small block of rows — its Jacobian, effective mass and impulse
//! application — plus the accumulated impulse it warm starts from. It knows nothing about which
//! joint it belongs to: the joint computes the current geometry (anchors, axes, errors) once per
//! pass and hands each part what it needs, so the same part serves a hinge limit, a slider motor,
//! a distance spring and, later, a contact normal.
//!
//! | part | rows | constraint |
//! |---|---|---|
//! | [`PointPart`] | 3 linear | two material points coincide |
//! | [`AxisPart`] | 1 linear + angular | relative motion along a world direction (limits, motors, springs, contact rows) |
//! | [`AngularAxisPart`] | 1 angular | relative rotation about a world axis (hinge/twist limits, motors, springs) |
//! | [`AngularFrictionPart`] | 3 angular | relative rotation resisted by a bounded torque (joint friction) |
//! | [`HingeRotationPart`] | 2 angular | an axis of a stays aligned with an axis of b |
//! | [`RotationPart`] | 3 angular | the relative orientation is locked |
//!
//! Sign conventions (all parts): the constraint velocity is `Ċ = J_b·(v_b, ω_b) − J_a·(v_a, ω_a)`;
//! an impulse `λ` is applied `+Jᵀλ` to body b and `−Jᵀλ` to body a. Every solve is the soft step
//! of `softness.rs`: `λ = −mass_scale·K⁻¹(Ċ + bias) − impulse_scale·λ_acc`, with the accumulated
//! impulse clamped to the row's bounds.

mod angular_axis;
mod angular_friction;
mod axis;
mod hinge_rotation;
mod point;
mod rotation;

pub(crate) use angular_axis::AngularAxisPart;
pub(crate) use angular_friction::AngularFrictionPart;
pub(crate) use axis::{AxisJacobian, AxisPart};
pub(crate) use hinge_rotation::{HingeAxes, HingeRotationPart};
pub(crate) use point::PointPart;
pub(crate) use rotation::RotationPart;

use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{hat, mat3_max_abs, DMat3, DVec3};

/// Inverts a symmetric positive semi-definite 3×3 effective-mass matrix; a singular one (both
/// bodies fixed, or a degenerate axis) gives zero, which disables the rows instead of producing NaN.
pub(crate) fn invert_or_zero(k: DMat3) -> DMat3 {
    let det = k.determinant();
    let scale = mat3_max_abs(k);
    if scale == 0.0 || det.abs() <= 1e-12 * scale * scale * scale {
        DMat3::ZERO
    } else {
        k.inverse()
    }
}

/// `1/k` for a scalar effective mass, or 0 when the row cannot move either body.
#[inline]
pub(crate) fn invert_scalar_or_zero(k: f64) -> f64 {
    if k > 0.0 {
        1.0 / k
    } else {
        0.0
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

/// How one scalar row is driven in one solve: the velocity `bias` added to `Ċ`, the soft
/// coefficients and the bounds on the accumulated impulse. The constructors are the four ways a
/// joint uses a row (equality, spring, motor, limit), so every joint drives rows the same way.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct RowDrive {
    pub bias: f64,
    pub mass_scale: f64,
    pub impulse_scale: f64,
    pub lower: f64,
    pub upper: f64,
}

impl RowDrive {
    /// A two-sided soft row pulling `C` to 0: the joint's softness for a hard row (and
    /// `RIGID_VELOCITY` in the relax pass), or a spring's own softness — the same formula, since a
    /// soft constraint *is* an implicit spring (`softness.rs`).
    pub fn soft(c: f64, softness: Softness) -> RowDrive {
        RowDrive {
            bias: softness.bias_rate * c,
            mass_scale: softness.mass_scale,
            impulse_scale: softness.impulse_scale,
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
        }
    }

    /// A velocity motor: drives `Ċ` to `target_speed` with `|λ_acc| ≤ max_impulse` per substep
    /// (`max_force · h`). A motor is rigid (full mass, no leak): its softness is the force cap.
    pub fn motor(target_speed: f64, max_impulse: f64) -> RowDrive {
        RowDrive {
            bias: -target_speed,
            mass_scale: 1.0,
            impulse_scale: 0.0,
            lower: -max_impulse,
            upper: max_impulse,
        }
    }

    /// A one-sided row keeping `C ≥ 0` with a pushing impulse `λ_acc ≥ 0` (limits, ropes, later
    /// contacts). While `C > 0` the limit is not reached and the row is *speculative*: the bias
    /// `C/h` allows exactly the approach speed that closes the gap in this substep, rigidly, so a
    /// fast body stops at the limit instead of passing it. At or past the limit the row pushes back
    /// softly with `softness` (the joint's in the solve pass, `RIGID_VELOCITY` in relax).
    /// (Box2D v3's joint limits.)
    pub fn limit(c: f64, inv_h: f64, softness: Softness) -> RowDrive {
        if c > 0.0 {
            RowDrive {
                bias: c * inv_h,
                mass_scale: 1.0,
                impulse_scale: 0.0,
                lower: 0.0,
                upper: f64::INFINITY,
            }
        } else {
            RowDrive { lower: 0.0, ..RowDrive::soft(c, softness) }
        }
    }

    /// One soft solve of a scalar row with effective mass `m = 1/K` and constraint velocity
    /// `cdot`: updates the accumulated impulse (clamped to the bounds) and returns the impulse to
    /// apply now, the change of the accumulated one.
    #[inline]
    pub fn solve(&self, accumulated: &mut f64, m: f64, cdot: f64) -> f64 {
        let lambda = -self.mass_scale * m * (cdot + self.bias) - self.impulse_scale * *accumulated;
        let new = (*accumulated + lambda).clamp(self.lower, self.upper);
        let applied = new - *accumulated;
        *accumulated = new;
        applied
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limit_is_speculative_before_contact_and_soft_after() {
        let s = Softness::new(60.0, 2.0, 1.0 / 240.0);
        let open = RowDrive::limit(0.01, 240.0, s);
        assert_eq!((open.bias, open.mass_scale, open.impulse_scale), (2.4, 1.0, 0.0));
        let closed = RowDrive::limit(-0.01, 240.0, s);
        assert_eq!(closed.bias, -0.01 * s.bias_rate);
        assert_eq!(closed.lower, 0.0);
        // A 1 cm gap in a 1/240 s substep allows 2.4 m/s of approach: at 1 m/s nothing acts, at
        // 5 m/s the row removes exactly the excess 2.6 m/s (unit mass).
        let mut acc = 0.0;
        assert_eq!(open.solve(&mut acc, 1.0, -1.0), 0.0);
        assert!((open.solve(&mut acc, 1.0, -5.0) - 2.6).abs() < 1e-12);
        // Separating rows never pull.
        let mut acc = 0.0;
        assert_eq!(open.solve(&mut acc, 1.0, 5.0), 0.0);
    }

    #[test]
    fn motor_clamps_to_its_force() {
        let drive = RowDrive::motor(10.0, 0.5);
        let mut acc = 0.0;
        let applied = drive.solve(&mut acc, 2.0, 0.0);
        assert_eq!(applied, 0.5);
        assert_eq!(acc, 0.5);
    }
}
