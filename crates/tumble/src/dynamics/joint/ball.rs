//! Ball-and-socket joint: the two anchors coincide (three point rows); rotation is free.

use super::parts::PointPart;
use super::JointFrame;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// Settings of a ball joint (none yet beyond the anchor), and its solver state.
#[derive(Clone, Debug, Default)]
pub struct BallJoint {
    point: PointPart,
}

impl BallJoint {
    pub fn new() -> BallJoint {
        BallJoint::default()
    }

    pub(crate) fn prepare(&mut self, a: JointFrame, b: JointFrame, delta_center: DVec3, _ctx: &StepContext) {
        let part = &mut self.point;
        part.r_a_local = a.r_local;
        part.r_b_local = b.r_local;
        part.delta_center = delta_center;
    }

    pub(crate) fn reset_impulses(&mut self) {
        self.point.impulse = DVec3::ZERO;
    }

    pub(crate) fn warm_start(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        self.point.warm_start(a, b);
    }

    pub(crate) fn solve(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) {
        let softness = if use_bias { ctx.joint_softness } else { crate::dynamics::Softness::RIGID_VELOCITY };
        self.point.solve(a, b, softness);
    }

    pub(crate) fn linear_impulse(&self) -> DVec3 {
        self.point.impulse
    }
}
