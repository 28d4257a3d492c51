//! Ball-and-socket joint: the anchors coincide (three point rows); rotation is free, optionally
//! within a cone (swing limit) and a twist range about the joint axis.
//!
//! The limits use the swing–twist decomposition of the relative rotation (`frames.rs`):
//!
//! * **Swing** `θ = ∠(z_a, z_b)`, the angle between the two frames' Z axes. From
//!   `cos θ = z_a·z_b` and `d/dt (z_a·z_b) = (ω_b − ω_a)·(z_b × z_a)`,
//!   `θ̇ = (ω_b − ω_a)·n` with `n = (z_a × z_b)/|z_a × z_b|`: an angular row about `n` keeping
//!   `C = θ_max − θ ≥ 0` (Jacobian axis `−n`). At `θ = 0` the axis is undefined, but the cone is
//!   then far from its edge and the row is skipped.
//! * **Twist** `φ = 2·atan2(q_z, q_w)` of `q = F_a⁻¹ F_b`. Its rate is `(ω_b − ω_a)` about the
//!   half-way axis `(z_a + z_b)/|z_a + z_b|` (exact without swing, and the usual choice with it,
//!   as in Jolt's swing–twist part): rows `φ − lower ≥ 0` and `upper − φ ≥ 0`.

use super::equality::EqualityRows;
use super::frames::JointPose;
use super::hard_softness;
use super::limit_rows::LimitRows;
use super::parts::{AngularAxisPart, AngularFrictionPart, PointPart, RowDrive};
use super::settings::{check_angle_limits, check_non_negative, Limits};
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Settings of a ball joint.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BallJoint {
    /// Largest angle between the joint axes of the two bodies (the cone's half-angle), rad, in
    /// `[0, π]`. `None`: free.
    pub swing_limit: Option<f64>,
    /// Range of the twist of body b about the joint axis relative to body a, rad, within
    /// `[−π, π]`. `None`: free.
    pub twist_limits: Option<Limits>,
    /// Largest torque the joint's friction exerts against relative rotation, N·m (default 0:
    /// frictionless). A ragdoll's joints need some to come to rest: without it a limb lying on
    /// the ground can roll to and fro between its limits for ever.
    #[serde(default)]
    pub friction_torque: f64,
}

/// Solver state of a ball joint.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct BallParts {
    point: PointPart,
    swing: AngularAxisPart,
    twist_lower: AngularAxisPart,
    twist_upper: AngularAxisPart,
    friction: AngularFrictionPart,
}

/// The swing row now: its Jacobian axis and `C = θ_max − θ`, or `None` when the axes are aligned.
fn swing_row(pose: &JointPose, half_angle: f64) -> Option<(DVec3, f64)> {
    let (z_a, z_b) = (pose.axis_a(), pose.axis_b());
    let normal = z_a.cross(z_b);
    let sin = normal.length();
    let theta = sin.atan2(z_a.dot(z_b));
    Some((swing_axis(z_a, normal, sin, || theta)?, half_angle - theta))
}

/// The swing row's Jacobian axis alone (`swing_row`), for the warm start: the angle `θ`, an
/// arctangent, only when the axes are aligned to round-off (a ragdoll's warm starts spent a
/// third of its arctangents on angles they never used).
fn swing_row_axis(pose: &JointPose) -> Option<DVec3> {
    let (z_a, z_b) = (pose.axis_a(), pose.axis_b());
    let normal = z_a.cross(z_b);
    let sin = normal.length();
    swing_axis(z_a, normal, sin, || sin.atan2(z_a.dot(z_b)))
}

/// The swing row's axis from `normal = z_a × z_b` and its length `sin`, with `theta` the swing
/// angle (asked for only when `sin` is too small to give the axis).
fn swing_axis(z_a: DVec3, normal: DVec3, sin: f64, theta: impl FnOnce() -> f64) -> Option<DVec3> {
    let n = if sin > 1e-9 {
        normal / sin
    } else if theta() > FRAC_PI_2 {
        // Turned right over: any perpendicular axis brings it back.
        z_a.any_orthonormal_vector()
    } else {
        return None;
    };
    Some(-n)
}

/// The twist rows' axis now (half-way between the two joint axes).
fn twist_axis(pose: &JointPose) -> Option<DVec3> {
    (pose.axis_a() + pose.axis_b()).try_normalize()
}

impl BallJoint {
    pub fn new() -> BallJoint {
        BallJoint::default()
    }

    pub(crate) fn validate(&self) -> Result<(), String> {
        if let Some(half_angle) = self.swing_limit {
            if !(0.0..=PI).contains(&half_angle) {
                return Err(format!("ball swing_limit must be within [0, pi], got {half_angle}"));
            }
        }
        if let Some(limits) = &self.twist_limits {
            check_angle_limits("ball twist_limits", limits)?;
        }
        check_non_negative("ball friction_torque", self.friction_torque)
    }

    pub(crate) fn warm_start(
        &self,
        parts: &BallParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        if self.friction_torque > 0.0 {
            parts.friction.warm_start(a, b);
        }
        if self.swing_limit.is_some() {
            if let Some(axis) = swing_row_axis(pose) {
                parts.swing.warm_start(a, b, axis);
            }
        }
        if self.twist_limits.is_some() {
            if let Some(axis) = twist_axis(pose) {
                parts.twist_lower.warm_start(a, b, axis);
                parts.twist_upper.warm_start(a, b, -axis);
            }
        }
        parts.point.warm_start(a, b, pose.r_a, pose.r_b);
    }

    pub(crate) fn solve(
        &self,
        parts: &mut BallParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
        solve_equality: bool,
    ) {
        let softness = hard_softness(ctx, use_bias);
        if self.friction_torque > 0.0 {
            parts.friction.solve(a, b, self.friction_torque * ctx.h);
        }
        if let Some(half_angle) = self.swing_limit {
            match swing_row(pose, half_angle) {
                Some((axis, c)) => parts.swing.solve(a, b, axis, RowDrive::limit(c, ctx.inv_h, softness)),
                None => parts.swing.impulse = 0.0,
            }
        }
        if let Some(limits) = &self.twist_limits {
            match twist_axis(pose) {
                Some(axis) => {
                    let twist = pose.twist_angle();
                    let lower = RowDrive::limit(twist - limits.lower, ctx.inv_h, softness);
                    parts.twist_lower.solve(a, b, axis, lower);
                    let upper = RowDrive::limit(limits.upper - twist, ctx.inv_h, softness);
                    parts.twist_upper.solve(a, b, -axis, upper);
                }
                None => {
                    parts.twist_lower.impulse = 0.0;
                    parts.twist_upper.impulse = 0.0;
                }
            }
        }
        // The point rows last: holding the joint together matters most.
        if solve_equality {
            parts.point.solve(a, b, pose.r_a, pose.r_b, pose.separation, softness);
        }
    }

    /// The point rows (`equality.rs`).
    pub(crate) fn push_equality_rows(pose: &JointPose, rows: &mut EqualityRows) {
        rows.push_point(pose);
    }

    /// The swing and twist limit rows (`limit_rows.rs`): the swing row first, if any.
    pub(crate) fn push_limit_rows(&self, parts: &BallParts, pose: &JointPose, rows: &mut LimitRows) {
        if let Some(half_angle) = self.swing_limit {
            match swing_row(pose, half_angle) {
                Some((axis, c)) => rows.push_angular(Some(axis), c, parts.swing.impulse),
                None => rows.push_angular(None, f64::INFINITY, parts.swing.impulse),
            }
        }
        if let Some(limits) = &self.twist_limits {
            let axis = twist_axis(pose);
            let twist = pose.twist_angle();
            rows.push_angular(axis, twist - limits.lower, parts.twist_lower.impulse);
            rows.push_angular(axis.map(|axis| -axis), limits.upper - twist, parts.twist_upper.impulse);
            rows.choose_nearer_side(rows.len - 2);
        }
    }

    /// Adds an impulse found for limit row `k` (`push_limit_rows`' order) to its part's.
    pub(crate) fn add_limit_impulse(&self, parts: &mut BallParts, mut k: usize, lambda: f64) {
        if self.swing_limit.is_some() {
            if k == 0 {
                parts.swing.impulse += lambda;
                return;
            }
            k -= 1;
        }
        match k {
            0 => parts.twist_lower.impulse += lambda,
            _ => parts.twist_upper.impulse += lambda,
        }
    }

    /// Adds impulses found for the equality rows to the accumulated ones.
    pub(crate) fn add_equality_impulse(parts: &mut BallParts, lambda: &[f64]) {
        parts.point.impulse += DVec3::new(lambda[0], lambda[1], lambda[2]);
    }

    /// Magnitudes of the accumulated (per-substep) linear and angular impulses.
    pub(crate) fn impulses(parts: &BallParts) -> (f64, f64) {
        let angular =
            parts.swing.impulse.abs() + (parts.twist_lower.impulse - parts.twist_upper.impulse).abs();
        (parts.point.impulse.length(), angular)
    }
}
