//! Slider (prismatic) joint: the relative orientation is locked (rotation part) and the anchor of
//! b may move only along the joint axis `n` fixed in body a (two linear rows along the
//! perpendiculars `n₁`, `n₂`, also fixed in a). The translation is `x = n·d`, `d` = anchor b −
//! anchor a; its rows use the Jacobian of an axis fixed in body a (`parts/axis.rs`), where body
//! a's lever arm is `r_a + d`:
//!
//! * perpendicular rows `C = nᵢ·d = 0`;
//! * limits `x − lower ≥ 0`, `upper − x ≥ 0`, speculative until reached;
//! * motor `ẋ → target_speed` with `|F| ≤ max_force` (N);
//! * spring `C = x − target` with `k = m_eff (2π·hertz)²`.

use super::equality::{EqualityRows, RowJacobian};
use super::frames::JointPose;
use super::hard_softness;
use super::limit_rows::{LimitRow, LimitRows};
use super::parts::{AxisJacobian, AxisPart, RotationPart, RowDrive};
use super::settings::{check_finite, check_limits, check_motor, check_spring, Limits, Motor, SpringSettings};
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// Settings of a slider joint. The slide direction is the joint axis (`JointDef::axis_world`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SliderJoint {
    /// Range of the translation of b's anchor along the axis from a's, m. `None`: free.
    pub limits: Option<Limits>,
    /// Drives the translation speed (m/s), max force in N.
    pub motor: Option<Motor>,
    /// Pulls the translation towards `spring_target_position`.
    pub spring: Option<SpringSettings>,
    /// Rest position of the spring along the axis, m.
    pub spring_target_position: f64,
}

/// Solver state of a slider joint.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct SliderParts {
    rotation: RotationPart,
    perpendicular: [AxisPart; 2],
    lower: AxisPart,
    upper: AxisPart,
    motor: AxisPart,
    spring: AxisPart,
}

/// The Jacobians of the slide axis and of the two perpendicular rows now.
fn jacobians(pose: &JointPose) -> (AxisJacobian, [AxisJacobian; 2]) {
    let row = |local: DVec3| {
        AxisJacobian::along_axis_of_a(pose.rotation_a * local, pose.r_a, pose.r_b, pose.separation)
    };
    (row(DVec3::Z), [row(DVec3::X), row(DVec3::Y)])
}

impl SliderJoint {
    pub(crate) fn validate(&self) -> Result<(), String> {
        if let Some(limits) = &self.limits {
            check_limits("slider limits", limits)?;
        }
        if let Some(motor) = &self.motor {
            check_motor("slider motor", motor)?;
        }
        if let Some(spring) = &self.spring {
            check_spring("slider spring", spring)?;
        }
        check_finite("slider spring_target_position", self.spring_target_position)
    }

    pub(crate) fn warm_start(
        &self,
        parts: &SliderParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let (axis, perpendicular) = jacobians(pose);
        parts.spring.warm_start(a, b, &axis);
        parts.motor.warm_start(a, b, &axis);
        parts.lower.warm_start(a, b, &axis);
        parts.upper.warm_start(a, b, &axis.negated());
        parts.rotation.warm_start(a, b);
        for (part, jacobian) in parts.perpendicular.iter().zip(&perpendicular) {
            part.warm_start(a, b, jacobian);
        }
    }

    pub(crate) fn solve(
        &self,
        parts: &mut SliderParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
        solve_equality: bool,
    ) {
        let softness = hard_softness(ctx, use_bias);
        let (axis, perpendicular) = jacobians(pose);
        let translation = axis.linear.dot(pose.separation);
        // Once per substep, as the hinge spring (see hinge.rs).
        if let Some(spring) = self.spring.filter(|s| s.hertz > 0.0 && use_bias) {
            let c = translation - self.spring_target_position;
            let drive = RowDrive::soft(c, Softness::new(spring.hertz, spring.damping_ratio, ctx.h));
            parts.spring.solve(a, b, &axis, drive);
        }
        if let Some(motor) = &self.motor {
            parts.motor.solve(a, b, &axis, RowDrive::motor(motor.target_speed, motor.max_force * ctx.h));
        }
        if let Some(limits) = &self.limits {
            parts.lower.solve(a, b, &axis, RowDrive::limit(translation - limits.lower, ctx.inv_h, softness));
            let upper = RowDrive::limit(limits.upper - translation, ctx.inv_h, softness);
            parts.upper.solve(a, b, &axis.negated(), upper);
        }
        if !solve_equality {
            return;
        }
        let c_rotation = RotationPart::error(pose.rotation_a, pose.rotation_b);
        parts.rotation.solve(a, b, c_rotation, softness);
        for (part, jacobian) in parts.perpendicular.iter_mut().zip(&perpendicular) {
            let c = jacobian.linear.dot(pose.separation);
            part.solve(a, b, jacobian, RowDrive::soft(c, softness));
        }
    }

    /// The rotation and perpendicular rows (`equality.rs`).
    pub(crate) fn push_equality_rows(pose: &JointPose, rows: &mut EqualityRows) {
        let (_, perpendicular) = jacobians(pose);
        rows.push_rotation(RotationPart::error(pose.rotation_a, pose.rotation_b));
        for jacobian in &perpendicular {
            rows.push_axis(jacobian, jacobian.linear.dot(pose.separation));
        }
    }

    /// The two sides of the translation range (`limit_rows.rs`): lower, upper.
    pub(crate) fn push_limit_rows(&self, parts: &SliderParts, pose: &JointPose, rows: &mut LimitRows) {
        if let Some(limits) = &self.limits {
            let (axis, _) = jacobians(pose);
            let translation = axis.linear.dot(pose.separation);
            let side = |jacobian, error, impulse| LimitRow {
                jacobian: RowJacobian::of_axis(&jacobian),
                error,
                impulse,
                eligible: true,
            };
            rows.push(side(axis, translation - limits.lower, parts.lower.impulse));
            rows.push(side(axis.negated(), limits.upper - translation, parts.upper.impulse));
            rows.choose_nearer_side(0);
        }
    }

    /// Adds an impulse found for limit row `k` (0 lower, 1 upper) to its part's.
    pub(crate) fn add_limit_impulse(parts: &mut SliderParts, k: usize, lambda: f64) {
        match k {
            0 => parts.lower.impulse += lambda,
            _ => parts.upper.impulse += lambda,
        }
    }

    /// Adds impulses found for the equality rows to the accumulated ones.
    pub(crate) fn add_equality_impulse(parts: &mut SliderParts, lambda: &[f64]) {
        parts.rotation.impulse += DVec3::new(lambda[0], lambda[1], lambda[2]);
        parts.perpendicular[0].impulse += lambda[3];
        parts.perpendicular[1].impulse += lambda[4];
    }

    /// Magnitudes of the accumulated (per-substep) linear and angular impulses.
    pub(crate) fn impulses(parts: &SliderParts) -> (f64, f64) {
        let axial = parts.spring.impulse + parts.motor.impulse + parts.lower.impulse - parts.upper.impulse;
        let linear =
            DVec3::new(parts.perpendicular[0].impulse, parts.perpendicular[1].impulse, axial).length();
        (linear, parts.rotation.impulse.length())
    }
}
