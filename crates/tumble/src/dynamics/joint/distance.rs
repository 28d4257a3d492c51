//! Distance joint: keeps the distance `L = |d|` between an anchor on a and an anchor on b
//! (`d` = anchor b − anchor a) at a length, within a range, or on a spring.
//!
//! With `n = d/|d|`, `L̇ = n·ḋ` exactly (the rotation of `n` is perpendicular to `n`), so every
//! row is a point-pair axis row along `n` (`parts/axis.rs`):
//! `J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ]`.
//!
//! * rigid (`spring: None`, or `min_length == max_length`): `C = L − length`, two-sided, with the
//!   joint softness;
//! * spring: `C = L − length` with the spring's softness (`hertz = 0`: no spring force);
//! * range: `L − min_length ≥ 0` and `max_length − L ≥ 0`, one-sided and speculative. A rope is a
//!   zero spring with only `max_length`.

use super::frames::JointPose;
use super::hard_softness;
use super::parts::{AxisJacobian, AxisPart, RowDrive};
use super::settings::{check_non_negative, check_spring, SpringSettings};
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;

/// Settings of a distance joint. The anchor on b is `JointDef::anchor_b_world` (default: the
/// same point as the anchor on a, which only makes sense with `min_length = 0`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DistanceJoint {
    /// The rigid length, or the spring's rest length, m. `None`: the distance at creation
    /// (clamped into `[min_length, max_length]`).
    pub length: Option<f64>,
    /// Shortest allowed distance, m (default 0).
    pub min_length: f64,
    /// Longest allowed distance, m (default ∞).
    pub max_length: f64,
    /// `None`: rigid at `length`. `Some`: a spring–damper towards `length`, free within
    /// `[min_length, max_length]`; `hertz = 0` gives no spring force.
    pub spring: Option<SpringSettings>,
}

impl Default for DistanceJoint {
    fn default() -> Self {
        DistanceJoint { length: None, min_length: 0.0, max_length: f64::INFINITY, spring: None }
    }
}

/// Solver state of a distance joint.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct DistanceParts {
    axial: AxisPart,
    lower: AxisPart,
    upper: AxisPart,
}

impl DistanceJoint {
    /// Rigid at the distance at creation.
    pub fn rigid() -> DistanceJoint {
        DistanceJoint::default()
    }

    /// A rope: the distance may shrink freely but not exceed `max_length`.
    pub fn rope(max_length: f64) -> DistanceJoint {
        DistanceJoint {
            length: Some(max_length),
            max_length,
            spring: Some(SpringSettings::new(0.0, 0.0)),
            ..DistanceJoint::default()
        }
    }

    /// A spring of `hertz` and `damping_ratio` whose rest length is the distance at creation.
    pub fn spring(hertz: f64, damping_ratio: f64) -> DistanceJoint {
        DistanceJoint { spring: Some(SpringSettings::new(hertz, damping_ratio)), ..DistanceJoint::default() }
    }

    fn is_rigid(&self) -> bool {
        self.spring.is_none() || self.min_length >= self.max_length
    }

    pub(crate) fn validate(&self) -> Result<(), String> {
        check_non_negative("distance min_length", self.min_length)?;
        if self.max_length.is_nan() || self.max_length < self.min_length {
            return Err(format!(
                "distance max_length ({}) must be >= min_length ({})",
                self.max_length, self.min_length
            ));
        }
        if let Some(length) = self.length {
            check_non_negative("distance length", length)?;
            if length < self.min_length || length > self.max_length {
                return Err(format!(
                    "distance length {length} must lie within [min_length, max_length] = [{}, {}]",
                    self.min_length, self.max_length
                ));
            }
        }
        if let Some(spring) = &self.spring {
            check_spring("distance spring", spring)?;
        }
        Ok(())
    }

    /// The settings with `length` fixed to the distance at creation if it was left open.
    pub(crate) fn resolved(&self, initial_distance: f64) -> DistanceJoint {
        let length = self.length.unwrap_or(initial_distance.clamp(self.min_length, self.max_length));
        DistanceJoint { length: Some(length), ..self.clone() }
    }

    fn length(&self) -> f64 {
        self.length.unwrap_or(0.0)
    }

    /// The row along the anchors' line now and the current distance. When the anchors coincide
    /// the direction is undefined; the joint axis of a stands in.
    fn row(pose: &JointPose) -> (AxisJacobian, f64) {
        let distance = pose.separation.length();
        let n = if distance > 1e-9 { pose.separation / distance } else { pose.axis_a() };
        (AxisJacobian::between_points(n, pose.r_a, pose.r_b), distance)
    }

    pub(crate) fn warm_start(
        &self,
        parts: &DistanceParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let (row, _) = Self::row(pose);
        parts.axial.warm_start(a, b, &row);
        parts.lower.warm_start(a, b, &row);
        parts.upper.warm_start(a, b, &row.negated());
    }

    pub(crate) fn solve(
        &self,
        parts: &mut DistanceParts,
        pose: &JointPose,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
        _solve_equality: bool,
    ) {
        let softness = hard_softness(ctx, use_bias);
        let (row, distance) = Self::row(pose);
        if self.is_rigid() {
            parts.axial.solve(a, b, &row, RowDrive::soft(distance - self.length(), softness));
            return;
        }
        // Once per substep, as the hinge spring (see hinge.rs).
        if let Some(spring) = self.spring.filter(|s| s.hertz > 0.0 && use_bias) {
            let drive = RowDrive::soft(
                distance - self.length(),
                Softness::new(spring.hertz, spring.damping_ratio, ctx.h),
            );
            parts.axial.solve(a, b, &row, drive);
        }
        if self.min_length > 0.0 {
            parts.lower.solve(a, b, &row, RowDrive::limit(distance - self.min_length, ctx.inv_h, softness));
        }
        if self.max_length.is_finite() {
            let drive = RowDrive::limit(self.max_length - distance, ctx.inv_h, softness);
            parts.upper.solve(a, b, &row.negated(), drive);
        }
    }

    /// Magnitude of the accumulated (per-substep) impulse along the line.
    pub(crate) fn impulses(parts: &DistanceParts) -> (f64, f64) {
        ((parts.axial.impulse + parts.lower.impulse - parts.upper.impulse).abs(), 0.0)
    }
}
