//! Fixed (weld) joint: the anchors coincide (point part) and the relative orientation is locked
//! (rotation part): six rows, two 3×3 blocks solved one after the other.

use super::equality::EqualityRows;
use super::frames::JointPose;
use super::hard_softness;
use super::parts::{PointPart, RotationPart};
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// Settings of a fixed joint (none: it holds the bodies as they were at creation).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FixedJoint {}

/// Solver state of a fixed joint.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct FixedParts {
    point: PointPart,
    rotation: RotationPart,
}

impl FixedJoint {
    pub fn new() -> FixedJoint {
        FixedJoint {}
    }

    pub(crate) fn warm_start(
        &self,
        parts: &FixedParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        parts.rotation.warm_start(a, b);
        parts.point.warm_start(a, b, pose.r_a, pose.r_b);
    }

    pub(crate) fn solve(
        &self,
        parts: &mut FixedParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
        solve_equality: bool,
    ) {
        if !solve_equality {
            return;
        }
        let softness = hard_softness(ctx, use_bias);
        parts.rotation.solve(a, b, RotationPart::error(pose.rotation_a, pose.rotation_b), softness);
        parts.point.solve(a, b, pose.r_a, pose.r_b, pose.separation, softness);
    }

    /// The point and rotation rows (`equality.rs`).
    pub(crate) fn push_equality_rows(pose: &JointPose, rows: &mut EqualityRows) {
        rows.push_point(pose);
        rows.push_rotation(RotationPart::error(pose.rotation_a, pose.rotation_b));
    }

    /// Adds impulses found for the equality rows to the accumulated ones.
    pub(crate) fn add_equality_impulse(parts: &mut FixedParts, lambda: &[f64]) {
        parts.point.impulse += DVec3::new(lambda[0], lambda[1], lambda[2]);
        parts.rotation.impulse += DVec3::new(lambda[3], lambda[4], lambda[5]);
    }

    /// Magnitudes of the accumulated (per-substep) linear and angular impulses.
    pub(crate) fn impulses(parts: &FixedParts) -> (f64, f64) {
        (parts.point.impulse.length(), parts.rotation.impulse.length())
    }
}
