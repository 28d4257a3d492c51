//! Joints: constraints between two bodies, built from the parts in `parts.rs`.
//!
//! A joint is defined in world terms at creation (an anchor point and an axis) and stored as a
//! frame in each body: `frame_a_local` / `frame_b_local` have their origin at the anchor and their
//! Z axis along the joint axis. Joints are rows of the same soft-step solve as contacts.

mod ball;
pub(crate) mod parts;

pub use ball::BallJoint;

use crate::body::Body;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::id::BodyId;
use crate::math::{DQuat, DVec3, Transform};

/// The kind of a joint and its settings.
#[derive(Clone, Debug)]
pub enum JointKind {
    /// Ball-and-socket: the anchor points coincide; rotation is free.
    Ball(BallJoint),
}

impl JointKind {
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Ball(_) => "ball",
        }
    }

    /// Checks the settings (limits ordered, positive frequencies, …); the message says which.
    pub(crate) fn validate(&self) -> Result<(), String> {
        match self {
            JointKind::Ball(_) => Ok(()),
        }
    }
}

/// Everything needed to create a joint.
#[derive(Clone, Debug)]
pub struct JointDef {
    pub name: String,
    pub body_a: BodyId,
    pub body_b: BodyId,
    /// The anchor point, world frame, at creation.
    pub anchor_world: DVec3,
    /// The joint axis (hinge axis, slider direction, cone axis), world frame, at creation.
    pub axis_world: DVec3,
    pub kind: JointKind,
    /// The joint breaks (and stops acting) when its constraint force exceeds this, N.
    pub break_force: Option<f64>,
}

impl JointDef {
    pub fn new(body_a: BodyId, body_b: BodyId, anchor_world: DVec3, kind: JointKind) -> JointDef {
        JointDef {
            name: String::new(),
            body_a,
            body_b,
            anchor_world,
            axis_world: DVec3::Z,
            kind,
            break_force: None,
        }
    }
}

/// A joint in the world.
#[derive(Clone, Debug)]
pub struct Joint {
    pub(crate) name: String,
    pub(crate) body_a: BodyId,
    pub(crate) body_b: BodyId,
    /// Joint frame in body a's frame (origin at the anchor, Z along the axis).
    pub(crate) frame_a_local: Transform,
    /// Joint frame in body b's frame.
    pub(crate) frame_b_local: Transform,
    pub(crate) kind: JointKind,
    pub(crate) break_force: Option<f64>,
    pub(crate) broken: bool,
}

/// The rotation taking Z to `axis` (unit), by the shortest arc.
pub(crate) fn rotation_z_to(axis: DVec3) -> DQuat {
    DQuat::from_rotation_arc(DVec3::Z, axis)
}

impl Joint {
    pub(crate) fn new(def: &JointDef, a: &Body, b: &Body) -> Joint {
        let frame_world = Transform::new(def.anchor_world, rotation_z_to(def.axis_world.normalize()));
        Joint {
            name: def.name.clone(),
            body_a: def.body_a,
            body_b: def.body_b,
            frame_a_local: a.transform().inverse().mul_transform(&frame_world),
            frame_b_local: b.transform().inverse().mul_transform(&frame_world),
            kind: def.kind.clone(),
            break_force: def.break_force,
            broken: false,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn body_a(&self) -> BodyId {
        self.body_a
    }
    pub fn body_b(&self) -> BodyId {
        self.body_b
    }
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }
    /// True once the constraint force exceeded `break_force`; a broken joint no longer acts.
    pub fn is_broken(&self) -> bool {
        self.broken
    }

    /// The anchor on body a, world frame.
    pub fn anchor_a_world(&self, a: &Body) -> DVec3 {
        a.transform().transform_point(self.frame_a_local.translation)
    }

    /// The anchor on body b, world frame.
    pub fn anchor_b_world(&self, b: &Body) -> DVec3 {
        b.transform().transform_point(self.frame_b_local.translation)
    }

    /// Stage "prepare": anchors relative to the centres of mass, the step-start separation.
    pub(crate) fn prepare(&mut self, a: &Body, b: &Body, ctx: &StepContext) {
        let frame_a = JointFrame::new(&self.frame_a_local, a);
        let frame_b = JointFrame::new(&self.frame_b_local, b);
        let delta_center = b.com_world() - a.com_world();
        match &mut self.kind {
            JointKind::Ball(j) => j.prepare(frame_a, frame_b, delta_center, ctx),
        }
    }

    /// Forgets the accumulated impulses (no warm start).
    pub(crate) fn reset_impulses(&mut self) {
        match &mut self.kind {
            JointKind::Ball(j) => j.reset_impulses(),
        }
    }

    pub(crate) fn warm_start(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        match &mut self.kind {
            JointKind::Ball(j) => j.warm_start(a, b),
        }
    }

    pub(crate) fn solve(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) {
        match &mut self.kind {
            JointKind::Ball(j) => j.solve(a, b, ctx, use_bias),
        }
    }

    /// The magnitude of the constraint force over the last step (linear impulse / dt), N.
    pub(crate) fn linear_force(&self, ctx: &StepContext) -> f64 {
        match &self.kind {
            JointKind::Ball(j) => j.linear_impulse().length() * ctx.inv_dt,
        }
    }
}

/// A joint frame expressed relative to the body's centre of mass, body axes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointFrame {
    /// Anchor offset from the centre of mass, body frame.
    pub r_local: DVec3,
    /// Orientation of the joint frame in the body frame.
    pub rotation_local: DQuat,
}

impl JointFrame {
    fn new(frame_local: &Transform, body: &Body) -> JointFrame {
        JointFrame {
            r_local: frame_local.translation - body.com_local(),
            rotation_local: frame_local.rotation,
        }
    }
}
