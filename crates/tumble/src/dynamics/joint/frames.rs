//! Joint frames during a step, and the angles measured between them.
//!
//! A joint stores one frame per body (origin at the anchor, Z along the joint axis). At *prepare*
//! the frames are re-expressed relative to each centre of mass ([`JointFrames`]); at every warm
//! start and solve the current world pose of both frames ([`JointPose`]) is rebuilt from the
//! bodies' current orientations and step displacements, so rows always use today's geometry.
//!
//! Angles use the relative rotation `q = F_a⁻¹ F_b` (frame b seen from frame a) and its
//! **swing–twist decomposition** about the joint axis Z: `q = swing · twist`, with `twist` a
//! rotation about Z and `swing` a rotation about an axis perpendicular to Z. Writing
//! `swing = (s_x, s_y, 0, s_w)` and `twist = (0, 0, t_z, t_w)`, the product has
//! `q_z = s_w t_z` and `q_w = s_w t_w`, so the twist is `(0, 0, q_z, q_w)` normalised and the twist
//! angle is `2·atan2(q_z, q_w)`. The swing takes frame a's Z axis onto frame b's; its angle is the
//! angle between the two Z axes. A hinge angle is the twist of a hinge whose axes are aligned.

use crate::body::Body;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{DQuat, DVec3, Transform};
use std::f64::consts::{PI, TAU};

/// The joint frames relative to the centres of mass, fixed for one step.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct JointFrames {
    /// Anchor offsets from each centre of mass, body frames.
    pub r_a_local: DVec3,
    pub r_b_local: DVec3,
    /// Orientations of the joint frames in the body frames.
    pub rotation_a_local: DQuat,
    pub rotation_b_local: DQuat,
    /// `x_b − x_a` at the start of the step (the bodies then move by their `dp`; using the
    /// change of position keeps round-off small far from the origin).
    pub delta_center: DVec3,
}

impl JointFrames {
    pub fn new(frame_a_local: &Transform, frame_b_local: &Transform, a: &Body, b: &Body) -> JointFrames {
        JointFrames {
            r_a_local: frame_a_local.translation - a.com_local(),
            r_b_local: frame_b_local.translation - b.com_local(),
            rotation_a_local: frame_a_local.rotation,
            rotation_b_local: frame_b_local.rotation,
            delta_center: b.com_world() - a.com_world(),
        }
    }

    /// The frames now, from the solver's working state of the two bodies.
    #[inline]
    pub fn pose(&self, a: &SolverBody, b: &SolverBody) -> JointPose {
        let r_a = a.q * self.r_a_local;
        let r_b = b.q * self.r_b_local;
        JointPose {
            r_a,
            r_b,
            separation: (b.dp - a.dp) + self.delta_center + (r_b - r_a),
            rotation_a: a.q * self.rotation_a_local,
            rotation_b: b.q * self.rotation_b_local,
        }
    }
}

/// Both joint frames now, world frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct JointPose {
    /// Anchor offsets from the centres of mass.
    pub r_a: DVec3,
    pub r_b: DVec3,
    /// Anchor b − anchor a: the position error of joints whose anchors coincide.
    pub separation: DVec3,
    /// World orientations of the joint frames.
    pub rotation_a: DQuat,
    pub rotation_b: DQuat,
}

impl JointPose {
    /// The pose of a joint's frames from the bodies themselves (for queries between steps).
    pub fn from_bodies(
        frame_a_local: &Transform,
        frame_b_local: &Transform,
        a: &Body,
        b: &Body,
    ) -> JointPose {
        let r_a = a.orientation() * (frame_a_local.translation - a.com_local());
        let r_b = b.orientation() * (frame_b_local.translation - b.com_local());
        JointPose {
            r_a,
            r_b,
            separation: (b.com_world() + r_b) - (a.com_world() + r_a),
            rotation_a: a.orientation() * frame_a_local.rotation,
            rotation_b: b.orientation() * frame_b_local.rotation,
        }
    }

    /// The joint axis as fixed in body a.
    #[inline]
    pub fn axis_a(&self) -> DVec3 {
        self.rotation_a * DVec3::Z
    }

    /// The joint axis as fixed in body b.
    #[inline]
    pub fn axis_b(&self) -> DVec3 {
        self.rotation_b * DVec3::Z
    }

    /// Frame b seen from frame a.
    #[inline]
    pub fn relative_rotation(&self) -> DQuat {
        self.rotation_a.inverse() * self.rotation_b
    }

    /// The twist angle of frame b about the joint axis, relative to frame a, in `(−π, π]`.
    pub fn twist_angle(&self) -> f64 {
        twist_angle_z(self.relative_rotation())
    }

    /// The swing angle: between the two frames' Z axes, in `[0, π]`.
    pub fn swing_angle(&self) -> f64 {
        self.axis_a().dot(self.axis_b()).clamp(-1.0, 1.0).acos()
    }
}

/// The twist angle about Z of the rotation `q` (swing–twist decomposition), in `(−π, π]`.
pub(crate) fn twist_angle_z(q: DQuat) -> f64 {
    if q.z == 0.0 && q.w == 0.0 {
        // A half-turn swing: the twist is undefined; call it zero.
        return 0.0;
    }
    wrap_angle(2.0 * q.z.atan2(q.w))
}

/// `angle` wrapped into `(−π, π]`.
pub(crate) fn wrap_angle(angle: f64) -> f64 {
    let wrapped = (angle + PI).rem_euclid(TAU) - PI;
    if wrapped <= -PI {
        wrapped + TAU
    } else {
        wrapped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twist_of_swing_times_twist_is_the_twist() {
        for &twist in &[-3.0, -1.2, 0.0, 0.4, 2.9] {
            for &(axis, swing) in
                &[(DVec3::X, 0.0), (DVec3::new(1.0, 1.0, 0.0).normalize(), 0.8), (DVec3::Y, 1.5)]
            {
                let q = DQuat::from_axis_angle(axis, swing) * DQuat::from_rotation_z(twist);
                assert!((twist_angle_z(q) - twist).abs() < 1e-12, "twist {twist}, swing {swing}");
                assert!((twist_angle_z(-q) - twist).abs() < 1e-12, "sign of q does not matter");
            }
        }
    }

    #[test]
    fn wrap_angle_range() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-0.5 - TAU) + 0.5).abs() < 1e-12);
    }
}
