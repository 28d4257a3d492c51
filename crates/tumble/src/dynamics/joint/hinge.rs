//! Hinge (revolute) joint: the anchors coincide (point part) and the hinge axes stay aligned
//! (hinge rotation part), leaving one rotation about the axis. The hinge angle `θ` is the twist of
//! frame b about the axis relative to frame a (`frames.rs`); its rate is `a₁·(ω_b − ω_a)` with
//! `a₁` the axis as fixed in body a, so limits, motor and spring are angular rows about `a₁`:
//!
//! * limits: `θ − lower ≥ 0` (axis `a₁`) and `upper − θ ≥ 0` (axis `−a₁`), speculative until
//!   reached;
//! * motor: `θ̇ → target_speed` with `|τ| ≤ max_force` (N·m);
//! * spring: `C = θ − target` with the spring's own softness, `k = I_eff (2π·hertz)²`.

use super::equality::EqualityRows;
use super::frames::{wrap_angle, JointPose};
use super::hard_softness;
use super::limit_rows::LimitRows;
use super::parts::{AngularAxisPart, HingeAxes, HingeRotationPart, PointPart, RowDrive};
use super::settings::{
    check_angle_limits, check_finite, check_motor, check_non_negative, check_spring, Limits, Motor,
    SpringSettings,
};
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// Settings of a hinge joint. The hinge axis is the joint axis (`JointDef::axis_world`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HingeJoint {
    /// Range of the hinge angle, rad, within `[−π, π]`. `None`: free.
    pub limits: Option<Limits>,
    /// Drives the angular speed of b relative to a about the axis (rad/s), max torque in N·m.
    pub motor: Option<Motor>,
    /// Pulls the hinge angle towards `spring_target_angle`.
    pub spring: Option<SpringSettings>,
    /// Rest angle of the spring, rad (the error is wrapped into `(−π, π]`).
    pub spring_target_angle: f64,
    /// Largest torque the hinge's friction exerts against rotation about its axis, N·m (default
    /// 0: frictionless).
    #[serde(default)]
    pub friction_torque: f64,
}

/// Solver state of a hinge joint.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct HingeParts {
    point: PointPart,
    rotation: HingeRotationPart,
    lower: AngularAxisPart,
    upper: AngularAxisPart,
    motor: AngularAxisPart,
    spring: AngularAxisPart,
    friction: AngularAxisPart,
}

fn hinge_axes(pose: &JointPose) -> HingeAxes {
    HingeAxes {
        axis_a: pose.axis_a(),
        perpendicular_b: [pose.rotation_b * DVec3::X, pose.rotation_b * DVec3::Y],
    }
}

impl HingeJoint {
    pub(crate) fn validate(&self) -> Result<(), String> {
        if let Some(limits) = &self.limits {
            check_angle_limits("hinge limits", limits)?;
        }
        if let Some(motor) = &self.motor {
            check_motor("hinge motor", motor)?;
        }
        if let Some(spring) = &self.spring {
            check_spring("hinge spring", spring)?;
        }
        check_non_negative("hinge friction_torque", self.friction_torque)?;
        check_finite("hinge spring_target_angle", self.spring_target_angle)
    }

    pub(crate) fn warm_start(
        &self,
        parts: &HingeParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let axis = pose.axis_a();
        parts.spring.warm_start(a, b, axis);
        parts.friction.warm_start(a, b, axis);
        parts.motor.warm_start(a, b, axis);
        parts.lower.warm_start(a, b, axis);
        parts.upper.warm_start(a, b, -axis);
        parts.rotation.warm_start(a, b, &hinge_axes(pose));
        parts.point.warm_start(a, b, pose.r_a, pose.r_b);
    }

    pub(crate) fn solve(
        &self,
        parts: &mut HingeParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
        solve_equality: bool,
    ) {
        let softness = hard_softness(ctx, use_bias);
        let axis = pose.axis_a();
        let angle = pose.twist_angle();
        // The spring is a real force, applied once per substep: warm start + this solve is exactly
        // one implicit-Euler step of the spring (softness.rs); a second application in the relax
        // pass would stiffen it.
        if let Some(spring) = self.spring.filter(|s| s.hertz > 0.0 && use_bias) {
            let c = wrap_angle(angle - self.spring_target_angle);
            let drive = RowDrive::soft(c, Softness::new(spring.hertz, spring.damping_ratio, ctx.h));
            parts.spring.solve(a, b, axis, drive);
        }
        if self.friction_torque > 0.0 {
            parts.friction.solve(a, b, axis, RowDrive::motor(0.0, self.friction_torque * ctx.h));
        }
        if let Some(motor) = &self.motor {
            parts.motor.solve(a, b, axis, RowDrive::motor(motor.target_speed, motor.max_force * ctx.h));
        }
        if let Some(limits) = &self.limits {
            parts.lower.solve(a, b, axis, RowDrive::limit(angle - limits.lower, ctx.inv_h, softness));
            parts.upper.solve(a, b, -axis, RowDrive::limit(limits.upper - angle, ctx.inv_h, softness));
        }
        if solve_equality {
            parts.rotation.solve(a, b, &hinge_axes(pose), softness);
            parts.point.solve(a, b, pose.r_a, pose.r_b, pose.separation, softness);
        }
    }

    /// The point and hinge-rotation rows (`equality.rs`).
    pub(crate) fn push_equality_rows(pose: &JointPose, rows: &mut EqualityRows) {
        rows.push_point(pose);
        rows.push_hinge_rotation(&hinge_axes(pose));
    }

    /// The two sides of the angle range (`limit_rows.rs`): lower, upper.
    pub(crate) fn push_limit_rows(&self, parts: &HingeParts, pose: &JointPose, rows: &mut LimitRows) {
        if let Some(limits) = &self.limits {
            let (axis, angle) = (pose.axis_a(), pose.twist_angle());
            rows.push_angular(Some(axis), angle - limits.lower, parts.lower.impulse);
            rows.push_angular(Some(-axis), limits.upper - angle, parts.upper.impulse);
            rows.choose_nearer_side(0);
        }
    }

    /// Adds an impulse found for limit row `k` (0 lower, 1 upper) to its part's.
    pub(crate) fn add_limit_impulse(parts: &mut HingeParts, k: usize, lambda: f64) {
        match k {
            0 => parts.lower.impulse += lambda,
            _ => parts.upper.impulse += lambda,
        }
    }

    /// Adds impulses found for the equality rows to the accumulated ones.
    pub(crate) fn add_equality_impulse(parts: &mut HingeParts, lambda: &[f64]) {
        parts.point.impulse += DVec3::new(lambda[0], lambda[1], lambda[2]);
        parts.rotation.impulse += glam::DVec2::new(lambda[3], lambda[4]);
    }

    /// Magnitudes of the accumulated (per-substep) linear and angular impulses.
    pub(crate) fn impulses(parts: &HingeParts) -> (f64, f64) {
        let axial = parts.spring.impulse + parts.motor.impulse + parts.lower.impulse - parts.upper.impulse;
        (parts.point.impulse.length(), parts.rotation.impulse.length().hypot(axial))
    }
}
