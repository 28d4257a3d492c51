//! Reading a joint's coordinates: angle and translation along the joint axis, and their rates.
//! Defined for every kind (for a hinge the angle is the hinge angle, for a slider the translation
//! is the slide, for a distance joint `separation().length()` is the length); on `Joint` with the
//! two bodies, and on `World` by id.

use super::Joint;
use crate::body::Body;
use crate::id::JointId;
use crate::math::DVec3;
use crate::world::{World, WorldError};

impl Joint {
    /// Twist of body b's joint frame about the joint axis relative to body a's, rad, in `(−π, π]`
    /// (the hinge angle of a hinge). Positive is counter-clockwise about the axis.
    pub fn angle(&self, a: &Body, b: &Body) -> f64 {
        self.pose(a, b).twist_angle()
    }

    /// Rate of `angle`: `(ω_b − ω_a)·axis`, rad/s, about the axis as fixed in body a.
    pub fn angular_speed(&self, a: &Body, b: &Body) -> f64 {
        self.pose(a, b).axis_a().dot(b.angular_velocity() - a.angular_velocity())
    }

    /// Angle between the two bodies' joint axes (the swing of a ball joint), rad, in `[0, π]`.
    pub fn swing_angle(&self, a: &Body, b: &Body) -> f64 {
        self.pose(a, b).swing_angle()
    }

    /// Anchor b − anchor a, world frame: the position error of joints whose anchors coincide.
    pub fn separation(&self, a: &Body, b: &Body) -> DVec3 {
        self.pose(a, b).separation
    }

    /// Position of b's anchor along the joint axis (fixed in a) from a's anchor, m (the slide of a
    /// slider).
    pub fn translation(&self, a: &Body, b: &Body) -> f64 {
        let pose = self.pose(a, b);
        pose.axis_a().dot(pose.separation)
    }

    /// Rate of `translation`, m/s: `n·ḋ + (ω_a × n)·d` (the axis turns with body a).
    pub fn linear_speed(&self, a: &Body, b: &Body) -> f64 {
        let pose = self.pose(a, b);
        let n = pose.axis_a();
        let d_dot = (b.linear_velocity() + b.angular_velocity().cross(pose.r_b))
            - (a.linear_velocity() + a.angular_velocity().cross(pose.r_a));
        n.dot(d_dot) + a.angular_velocity().cross(n).dot(pose.separation)
    }
}

impl World {
    fn joint_bodies(&self, id: JointId) -> Result<(&Joint, &Body, &Body), WorldError> {
        let joint = self.joint(id)?;
        Ok((joint, self.body(joint.body_a)?, self.body(joint.body_b)?))
    }

    /// The joint's angle about its axis (the hinge angle), rad. See [`Joint::angle`].
    pub fn joint_angle(&self, id: JointId) -> Result<f64, WorldError> {
        let (j, a, b) = self.joint_bodies(id)?;
        Ok(j.angle(a, b))
    }

    /// The joint's angular speed about its axis, rad/s. See [`Joint::angular_speed`].
    pub fn joint_angular_speed(&self, id: JointId) -> Result<f64, WorldError> {
        let (j, a, b) = self.joint_bodies(id)?;
        Ok(j.angular_speed(a, b))
    }

    /// The joint's translation along its axis (the slide), m. See [`Joint::translation`].
    pub fn joint_translation(&self, id: JointId) -> Result<f64, WorldError> {
        let (j, a, b) = self.joint_bodies(id)?;
        Ok(j.translation(a, b))
    }

    /// The joint's speed along its axis, m/s. See [`Joint::linear_speed`].
    pub fn joint_linear_speed(&self, id: JointId) -> Result<f64, WorldError> {
        let (j, a, b) = self.joint_bodies(id)?;
        Ok(j.linear_speed(a, b))
    }

    /// Anchor b − anchor a, world frame, m. See [`Joint::separation`].
    pub fn joint_separation(&self, id: JointId) -> Result<DVec3, WorldError> {
        let (j, a, b) = self.joint_bodies(id)?;
        Ok(j.separation(a, b))
    }
}
