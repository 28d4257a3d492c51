//! A joint's equality rows — the rows that hold it together, as opposed to its limits, motors and
//! springs — written out as plain Jacobians, so the joint tree (`dynamics/joint_tree/`) can solve
//! them exactly for a whole articulated figure at once.
//!
//! The rows are the same as the parts' (`parts/`): same Jacobians, same position errors, same
//! sign convention `Ċ = J_b·(v_b, ω_b) − J_a·(v_a, ω_a)`, impulses `+Jᵀλ` on b and `−Jᵀλ` on a.
//! So an impulse the tree finds is added to the parts' accumulated impulses and warm starts the
//! next substep exactly as an iterated one would.
//!
//! | kind | rows |
//! |---|---|
//! | ball | point (3) |
//! | hinge | point (3), hinge rotation (2) |
//! | fixed | point (3), rotation (3) |
//! | slider | rotation (3), perpendicular (2) |

use super::frames::JointPose;
use super::parts::{AxisJacobian, HingeAxes};
use crate::dynamics::solver_body::SolverBody;
use crate::math::DVec3;

/// Most equality rows of any joint (a fixed joint's six).
pub(crate) const MAX_ROWS: usize = 6;

/// One row: `Ċ = linear_b·v_b + angular_b·ω_b − linear_a·v_a − angular_a·ω_a`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct RowJacobian {
    pub linear_a: DVec3,
    pub angular_a: DVec3,
    pub linear_b: DVec3,
    pub angular_b: DVec3,
}

impl RowJacobian {
    /// The row of a linear axis part (`parts/axis.rs`).
    pub fn of_axis(jacobian: &AxisJacobian) -> RowJacobian {
        RowJacobian {
            linear_a: jacobian.linear,
            angular_a: jacobian.angular_a,
            linear_b: jacobian.linear,
            angular_b: jacobian.angular_b,
        }
    }

    /// The row's velocity `Ċ` now.
    #[inline]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        self.linear_b.dot(b.v) + self.angular_b.dot(b.w) - self.linear_a.dot(a.v) - self.angular_a.dot(a.w)
    }
}

/// A joint's equality rows now, with their position errors `C`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct EqualityRows {
    pub len: usize,
    pub rows: [RowJacobian; MAX_ROWS],
    pub error: [f64; MAX_ROWS],
}

impl EqualityRows {
    pub fn push(&mut self, row: RowJacobian, c: f64) {
        self.rows[self.len] = row;
        self.error[self.len] = c;
        self.len += 1;
    }

    /// The point part's three rows (`parts/point.rs`): along the world axes, `C` the separation.
    pub fn push_point(&mut self, pose: &JointPose) {
        for (k, e) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
            let row = RowJacobian {
                linear_a: e,
                angular_a: pose.r_a.cross(e),
                linear_b: e,
                angular_b: pose.r_b.cross(e),
            };
            self.push(row, pose.separation[k]);
        }
    }

    /// One purely angular row about `axis` (rotation and hinge-rotation parts).
    pub fn push_angular(&mut self, axis: DVec3, c: f64) {
        let row =
            RowJacobian { linear_a: DVec3::ZERO, angular_a: axis, linear_b: DVec3::ZERO, angular_b: axis };
        self.push(row, c);
    }

    /// The hinge-rotation part's two rows (`parts/hinge_rotation.rs`).
    pub fn push_hinge_rotation(&mut self, axes: &HingeAxes) {
        let (u, w) = axes.jacobians();
        let c = axes.error();
        self.push_angular(u, c.x);
        self.push_angular(w, c.y);
    }

    /// The rotation part's three rows (`parts/rotation.rs`), `c` its rotation-vector error.
    pub fn push_rotation(&mut self, c: DVec3) {
        for (k, e) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
            self.push_angular(e, c[k]);
        }
    }

    /// One linear axis row (`parts/axis.rs`).
    pub fn push_axis(&mut self, jacobian: &AxisJacobian, c: f64) {
        self.push(RowJacobian::of_axis(jacobian), c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;

    /// The point rows' velocity is the relative velocity of the two anchors.
    #[test]
    fn point_rows_measure_the_anchors_relative_velocity() {
        let pose = JointPose {
            r_a: DVec3::new(0.1, -0.2, 0.3),
            r_b: DVec3::new(-0.4, 0.0, 0.2),
            separation: DVec3::new(1e-3, 2e-3, -1e-3),
            rotation_a: DQuat::IDENTITY,
            rotation_b: DQuat::IDENTITY,
        };
        let mut rows = EqualityRows::default();
        rows.push_point(&pose);
        let mut a = SolverBody::FIXED;
        let mut b = SolverBody::FIXED;
        (a.v, a.w) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.5, 2.0));
        (b.v, b.w) = (DVec3::new(0.5, -1.0, 0.0), DVec3::new(0.3, 0.2, -0.7));
        let expected = (b.v + b.w.cross(pose.r_b)) - (a.v + a.w.cross(pose.r_a));
        for k in 0..3 {
            assert!((rows.rows[k].velocity(&a, &b) - expected[k]).abs() < 1e-15);
            assert_eq!(rows.error[k], pose.separation[k]);
        }
    }
}
