//! Joints: constraints between two bodies, assembled from the parts in `parts/`.
//!
//! A joint is defined in world terms at creation (an anchor point and an axis) and stored as a
//! frame in each body: `frame_a_local` / `frame_b_local` have their origin at the anchor and their
//! Z axis along the joint axis. Joints are rows of the same soft-step solve as contacts.
//!
//! | kind | rows | file |
//! |---|---|---|
//! | ball | point (3) + optional swing cone and twist limits | `ball.rs` |
//! | hinge | point (3) + hinge rotation (2) + optional limits, motor, spring | `hinge.rs` |
//! | slider | rotation (3) + 2 perpendicular rows + optional limits, motor, spring | `slider.rs` |
//! | fixed | point (3) + rotation (3) | `fixed.rs` |
//! | distance | 1 row along the anchors' line: rigid, spring, min/max (rope) | `distance.rs` |
//!
//! The settings (`JointKind`, public) are kept apart from the solver state (`JointParts`,
//! crate-private: accumulated impulses), so users fill settings with `..Default::default()`.
//!
//! Within a joint, the optional rows (spring, motor, limits) are solved first and the rows that
//! hold the joint together last, so the last word goes to what matters most (Box2D's order).

mod ball;
mod distance;
pub(crate) mod equality;
mod fixed;
pub(crate) mod frames;
mod hinge;
pub(crate) mod limit_rows;
pub(crate) mod parts;
mod queries;
mod settings;
mod slider;

pub use ball::BallJoint;
pub use distance::DistanceJoint;
pub use fixed::FixedJoint;
pub use hinge::HingeJoint;
pub use settings::{Limits, Motor, SpringSettings};
pub use slider::SliderJoint;

use crate::body::Body;
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::id::BodyId;
use crate::math::{DQuat, DVec3, Transform};
use frames::{JointFrames, JointPose};

/// The kind of a joint and its settings.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum JointKind {
    /// Ball-and-socket: the anchor points coincide; rotation is free (optionally limited).
    Ball(BallJoint),
    /// Hinge (revolute): one rotation about the joint axis.
    Hinge(HingeJoint),
    /// Slider (prismatic): one translation along the joint axis, no rotation.
    Slider(SliderJoint),
    /// Fixed (weld): no relative motion.
    Fixed(FixedJoint),
    /// Distance: the anchors stay at a distance (rigid, spring, rope).
    Distance(DistanceJoint),
}

impl JointKind {
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Ball(_) => "ball",
            JointKind::Hinge(_) => "hinge",
            JointKind::Slider(_) => "slider",
            JointKind::Fixed(_) => "fixed",
            JointKind::Distance(_) => "distance",
        }
    }

    /// Checks the settings (limits ordered, frequencies and forces >= 0, all finite); the
    /// message says which setting and what it was.
    pub(crate) fn validate(&self) -> Result<(), String> {
        match self {
            JointKind::Ball(j) => j.validate(),
            JointKind::Hinge(j) => j.validate(),
            JointKind::Slider(j) => j.validate(),
            JointKind::Fixed(_) => Ok(()),
            JointKind::Distance(j) => j.validate(),
        }
    }
}

/// The solver state of a joint: the accumulated impulses of its parts.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) enum JointParts {
    Ball(ball::BallParts),
    Hinge(hinge::HingeParts),
    Slider(slider::SliderParts),
    Fixed(fixed::FixedParts),
    Distance(distance::DistanceParts),
}

impl JointParts {
    fn for_kind(kind: &JointKind) -> JointParts {
        match kind {
            JointKind::Ball(_) => JointParts::Ball(Default::default()),
            JointKind::Hinge(_) => JointParts::Hinge(Default::default()),
            JointKind::Slider(_) => JointParts::Slider(Default::default()),
            JointKind::Fixed(_) => JointParts::Fixed(Default::default()),
            JointKind::Distance(_) => JointParts::Distance(Default::default()),
        }
    }
}

/// Matches a joint's settings with its parts (always made together, so always the same kind).
macro_rules! with_parts {
    ($kind:expr, $parts:expr, |$s:ident, $p:ident| $body:expr) => {
        match ($kind, $parts) {
            (JointKind::Ball($s), JointParts::Ball($p)) => $body,
            (JointKind::Hinge($s), JointParts::Hinge($p)) => $body,
            (JointKind::Slider($s), JointParts::Slider($p)) => $body,
            (JointKind::Fixed($s), JointParts::Fixed($p)) => $body,
            (JointKind::Distance($s), JointParts::Distance($p)) => $body,
            _ => unreachable!("a joint's parts are made for its kind"),
        }
    };
}

/// The softness of the rows that hold a joint together: the joint softness in the solve pass,
/// rigid and without position bias in the relax pass.
#[inline]
pub(crate) fn hard_softness(ctx: &StepContext, use_bias: bool) -> Softness {
    if use_bias {
        ctx.joint_softness
    } else {
        Softness::RIGID_VELOCITY
    }
}

/// Everything needed to create a joint.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct JointDef {
    pub name: String,
    pub body_a: BodyId,
    pub body_b: BodyId,
    /// The anchor point, world frame, at creation.
    pub anchor_world: DVec3,
    /// The anchor on body b, world frame, when it differs from `anchor_world` (distance joints
    /// only; the other joints start with coinciding anchors).
    pub anchor_b_world: Option<DVec3>,
    /// The joint axis (hinge axis, slider direction, cone and twist axis), world frame, at
    /// creation.
    pub axis_world: DVec3,
    pub kind: JointKind,
    /// The joint breaks (and stops acting) when its linear constraint force exceeds this, N.
    pub break_force: Option<f64>,
    /// Whether the two jointed bodies still collide with each other. Default false.
    pub collide_connected: bool,
    /// The joint breaks when its angular constraint torque exceeds this, N·m.
    pub break_torque: Option<f64>,
}

impl JointDef {
    pub fn new(body_a: BodyId, body_b: BodyId, anchor_world: DVec3, kind: JointKind) -> JointDef {
        JointDef {
            name: String::new(),
            body_a,
            body_b,
            anchor_world,
            anchor_b_world: None,
            axis_world: DVec3::Z,
            kind,
            break_force: None,
            collide_connected: false,
            break_torque: None,
        }
    }

    /// The same definition with a name.
    pub fn named(self, name: &str) -> JointDef {
        JointDef { name: name.into(), ..self }
    }

    /// The same definition with the joint axis `axis_world`.
    pub fn with_axis(self, axis_world: DVec3) -> JointDef {
        JointDef { axis_world, ..self }
    }
}

/// A joint in the world.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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
    pub(crate) collide_connected: bool,
    pub(crate) break_torque: Option<f64>,
    pub(crate) broken: bool,
    /// Set by the solver each step: false when neither body can move (both asleep or fixed), so
    /// the joint is skipped and keeps its impulses and forces.
    pub(crate) solving: bool,
    /// Set by the solver each step: true when the joint's equality rows are solved exactly as
    /// part of a joint tree (`dynamics/joint_tree/`) rather than row by row here.
    #[serde(skip)]
    pub(crate) in_tree: bool,
    /// Constraint force and torque magnitudes over the last step, N and N·m.
    pub(crate) force: f64,
    pub(crate) torque: f64,
    pub(crate) frames: JointFrames,
    pub(crate) parts: JointParts,
}

/// The rotation taking Z to `axis` (unit), by the shortest arc.
pub(crate) fn rotation_z_to(axis: DVec3) -> DQuat {
    DQuat::from_rotation_arc(DVec3::Z, axis)
}

impl Joint {
    pub(crate) fn new(def: &JointDef, a: &Body, b: &Body) -> Joint {
        let rotation = rotation_z_to(def.axis_world.normalize());
        let frame_a_world = Transform::new(def.anchor_world, rotation);
        let anchor_b_world = def.anchor_b_world.unwrap_or(def.anchor_world);
        let frame_b_world = Transform::new(anchor_b_world, rotation);
        let kind = match &def.kind {
            JointKind::Distance(j) => {
                JointKind::Distance(j.resolved(anchor_b_world.distance(def.anchor_world)))
            }
            other => other.clone(),
        };
        Joint {
            name: def.name.clone(),
            body_a: def.body_a,
            body_b: def.body_b,
            frame_a_local: a.transform().inverse().mul_transform(&frame_a_world),
            frame_b_local: b.transform().inverse().mul_transform(&frame_b_world),
            parts: JointParts::for_kind(&kind),
            kind,
            break_force: def.break_force,
            collide_connected: def.collide_connected,
            break_torque: def.break_torque,
            broken: false,
            solving: false,
            in_tree: false,
            force: 0.0,
            torque: 0.0,
            frames: JointFrames::default(),
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
    /// The settings (for a distance joint, with `length` resolved at creation).
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }
    /// True once the constraint force or torque exceeded its break limit; a broken joint no
    /// longer acts.
    pub fn is_broken(&self) -> bool {
        self.broken
    }
    /// Magnitude of the linear constraint force over the last step, N.
    pub fn constraint_force(&self) -> f64 {
        self.force
    }
    /// Magnitude of the angular constraint torque over the last step, N·m.
    pub fn constraint_torque(&self) -> f64 {
        self.torque
    }

    /// The joint frame in body a's frame: origin at the anchor, Z along the joint axis.
    pub fn frame_a_local(&self) -> Transform {
        self.frame_a_local
    }

    /// The joint frame in body b's frame: origin at the anchor, Z along the joint axis.
    pub fn frame_b_local(&self) -> Transform {
        self.frame_b_local
    }

    /// The anchor on body a, world frame.
    pub fn anchor_a_world(&self, a: &Body) -> DVec3 {
        a.transform().transform_point(self.frame_a_local.translation)
    }

    /// The anchor on body b, world frame.
    pub fn anchor_b_world(&self, b: &Body) -> DVec3 {
        b.transform().transform_point(self.frame_b_local.translation)
    }

    /// Both joint frames now, from the bodies.
    pub(crate) fn pose(&self, a: &Body, b: &Body) -> JointPose {
        JointPose::from_bodies(&self.frame_a_local, &self.frame_b_local, a, b)
    }

    /// Stage "prepare": the frames relative to the centres of mass and the step-start offsets.
    pub(crate) fn prepare(&mut self, a: &Body, b: &Body, _ctx: &StepContext) {
        self.frames = JointFrames::new(&self.frame_a_local, &self.frame_b_local, a, b);
    }

    /// Forgets the accumulated impulses (no warm start).
    pub(crate) fn reset_impulses(&mut self) {
        self.parts = JointParts::for_kind(&self.kind);
    }

    /// Stage "warm start": applies the accumulated impulses with the current geometry.
    pub(crate) fn warm_start(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        let pose = self.frames.pose(a, b);
        with_parts!(&self.kind, &self.parts, |settings, parts| settings.warm_start(parts, &pose, a, b))
    }

    /// Stage "solve" (`use_bias`) or "relax" (`!use_bias`).
    pub(crate) fn solve(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) {
        // A tree joint has only equality and limit rows (`tree_row_count`), and the tree solves them
        // exactly in the biased pass (`joint_tree/`). A projected tree's rows carry no bias, so
        // there is none to relax either; an unprojected tree's rows are relaxed row by row here,
        // before the contacts, so contacts keep the last word.
        if self.in_tree && (use_bias || ctx.project_joint_trees) {
            return;
        }
        let pose = self.frames.pose(a, b);
        let solve_equality = !self.in_tree || !use_bias;
        with_parts!(&self.kind, &mut self.parts, |settings, parts| {
            settings.solve(parts, &pose, a, b, ctx, use_bias, solve_equality)
        })
    }

    /// The equality rows now (`equality.rs`), or `None` for a kind the joint tree leaves to the
    /// row-by-row solve (distance joints: their rows switch between rigid, rope and spring).
    #[cfg(test)]
    pub(crate) fn equality_rows(&self, a: &SolverBody, b: &SolverBody) -> Option<equality::EqualityRows> {
        let mut rows = equality::EqualityRows::default();
        let mut limits = limit_rows::LimitRows::default();
        self.tree_rows_into(a, b, &mut rows, &mut limits).then_some(rows)
    }

    /// The rows the joint tree solves for this joint now, written over `rows` and `limits`
    /// (whose arrays need not be clear): the equality rows, and the limit rows
    /// (`limit_rows.rs`), which the tree takes in while they push. The tree asks for every
    /// joint's rows several times a substep, and a returned set of rows is 600 bytes built and
    /// then copied. `false` for a kind without equality rows.
    pub(crate) fn tree_rows_into(
        &self,
        a: &SolverBody,
        b: &SolverBody,
        rows: &mut equality::EqualityRows,
        limits: &mut limit_rows::LimitRows,
    ) -> bool {
        let pose = self.frames.pose(a, b);
        rows.len = 0;
        limits.clear();
        match (&self.kind, &self.parts) {
            (JointKind::Ball(j), JointParts::Ball(p)) => {
                BallJoint::push_equality_rows(&pose, rows);
                j.push_limit_rows(p, &pose, limits);
            }
            (JointKind::Hinge(j), JointParts::Hinge(p)) => {
                HingeJoint::push_equality_rows(&pose, rows);
                j.push_limit_rows(p, &pose, limits);
            }
            (JointKind::Slider(j), JointParts::Slider(p)) => {
                SliderJoint::push_equality_rows(&pose, rows);
                j.push_limit_rows(p, &pose, limits);
            }
            (JointKind::Fixed(_), _) => FixedJoint::push_equality_rows(&pose, rows),
            _ => return false,
        }
        true
    }

    /// How many equality rows the joint tree solves for this joint (0: none — distance joints,
    /// and joints with a motor, a spring or friction, or, unless `limits`, a limit). Those rows
    /// act on the figure through effective masses the row-by-row solve gets only approximately;
    /// against a tree's exact rows they fight it: a motor driving a hinge into its limit rocked
    /// ±0.04 rad at the limit instead of resting there. Such joints stay row by row. A limit
    /// need not keep a joint out: the tree takes a limit row into the joint's block while it
    /// pushes (`limit_rows.rs`).
    pub(crate) fn tree_row_count(&self, limits: bool) -> usize {
        let optional = match &self.kind {
            JointKind::Ball(j) => {
                j.friction_torque > 0.0 || (!limits && (j.swing_limit.is_some() || j.twist_limits.is_some()))
            }
            JointKind::Hinge(j) => {
                j.motor.is_some()
                    || j.spring.is_some()
                    || j.friction_torque > 0.0
                    || (!limits && j.limits.is_some())
            }
            JointKind::Slider(j) => {
                j.motor.is_some() || j.spring.is_some() || (!limits && j.limits.is_some())
            }
            JointKind::Fixed(_) | JointKind::Distance(_) => false,
        };
        if optional {
            return 0;
        }
        match &self.kind {
            JointKind::Ball(_) => 3,
            JointKind::Hinge(_) | JointKind::Slider(_) => 5,
            JointKind::Fixed(_) => 6,
            JointKind::Distance(_) => 0,
        }
    }

    /// Adds the impulse the joint tree found for limit row `k` (`tree_rows_into`'s order) to its
    /// part's accumulated one.
    pub(crate) fn add_limit_impulse(&mut self, k: usize, lambda: f64) {
        match (&self.kind, &mut self.parts) {
            (JointKind::Ball(j), JointParts::Ball(p)) => j.add_limit_impulse(p, k, lambda),
            (JointKind::Hinge(_), JointParts::Hinge(p)) => HingeJoint::add_limit_impulse(p, k, lambda),
            (JointKind::Slider(_), JointParts::Slider(p)) => SliderJoint::add_limit_impulse(p, k, lambda),
            _ => {}
        }
    }

    /// Adds the impulses the joint tree found for the equality rows to the accumulated ones.
    pub(crate) fn add_equality_impulse(&mut self, lambda: &[f64]) {
        match &mut self.parts {
            JointParts::Ball(p) => BallJoint::add_equality_impulse(p, lambda),
            JointParts::Hinge(p) => HingeJoint::add_equality_impulse(p, lambda),
            JointParts::Slider(p) => SliderJoint::add_equality_impulse(p, lambda),
            JointParts::Fixed(p) => FixedJoint::add_equality_impulse(p, lambda),
            JointParts::Distance(_) => {}
        }
    }

    /// Stage "store impulses": the constraint force and torque of the step and joint breaking.
    /// Accumulated impulses are re-applied in every substep's warm start, so they are impulses
    /// *per substep*: force = impulse / h.
    pub(crate) fn store(&mut self, ctx: &StepContext) {
        let (linear, angular) = match &self.parts {
            JointParts::Ball(p) => BallJoint::impulses(p),
            JointParts::Hinge(p) => HingeJoint::impulses(p),
            JointParts::Slider(p) => SliderJoint::impulses(p),
            JointParts::Fixed(p) => FixedJoint::impulses(p),
            JointParts::Distance(p) => DistanceJoint::impulses(p),
        };
        self.force = linear * ctx.inv_h;
        self.torque = angular * ctx.inv_h;
        let over = |limit: Option<f64>, value: f64| limit.is_some_and(|l| value > l);
        if over(self.break_force, self.force) || over(self.break_torque, self.torque) {
            self.broken = true;
        }
    }
}
