//! Fixed (weld) joint: the anchors coincide (point part) and the relative orientation is locked
//! (rotation part): six rows, two 3×3 blocks solved one after the other.

use super::frames::JointPose;
use super::hard_softness;
use super::parts::{PointPart, RotationPart};
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;

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
    ) {
        let softness = hard_softness(ctx, use_bias);
        parts.rotation.solve(a, b, RotationPart::error(pose.rotation_a, pose.rotation_b), softness);
        parts.point.solve(a, b, pose.r_a, pose.r_b, pose.separation, softness);
    }

    /// Magnitudes of the accumulated (per-substep) linear and angular impulses.
    pub(crate) fn impulses(parts: &FixedParts) -> (f64, f64) {
        (parts.point.impulse.length(), parts.rotation.impulse.length())
    }
}
