//! Time of impact by conservative advancement: the first fraction of a body's motion over a step
//! at which its convex shape comes within a target separation of a fixed convex shape or
//! half-space.
//!
//! ## The sweep
//!
//! Only the poses at the start and the end of the step are known, so the motion between them is
//! taken to be the simplest one that joins them (as in Box2D): the centre of mass moves on the
//! straight line `c(t) = c₀ + t Δc` and the body turns at a constant rate about one fixed axis,
//! `q(t) = exp(t θ â / 2) q₀`, where `θ â` is the shortest rotation from `q₀` to `q₁` (`θ ≤ π`), for
//! `t ∈ [0, 1]`. A body that turns by more than half a turn in one step is swept the short way.
//!
//! ## The bound
//!
//! Let `n` be the unit normal from the fixed shape A to the moving shape B at their closest points
//! at time `t`, and `d(t)` their distance. Because A and B are convex, `d` is the largest
//! separation over all directions, so for every later `t'` it is at least the separation along
//! this one `n`:
//!
//! `d(t') ≥ min_{b ∈ B(t')} n·b − max_{a ∈ A} n·a`.
//!
//! A point of B at offset `r` from the centre of mass moves from `c(t) + R(t) r` to
//! `c(t') + R(t') r`; the rotation `R(t') R(t)ᵀ` is a turn by `θ (t' − t)` about `â`, which moves
//! `R(t) r` by at most the arc `θ (t' − t) |r|`. So every point of B advances towards A along
//! `n` by at most `(t' − t) μ` with
//!
//! `μ = −n·Δc + θ r_max`,
//!
//! `r_max` the largest distance of a point of B from the centre of mass. (That is the bound
//! `|Δx| + ω_max r_max` on how fast a point can approach, with the translation projected on the
//! normal: still a rigorous bound, and a body sliding along a wall is not slowed down by its
//! speed along it.) Hence `d(t') ≥ d(t) − (t' − t) μ`, and the distance cannot fall to the target
//! `s` before `t + (d(t) − s)/μ`.
//!
//! ## The iteration
//!
//! Conservative advancement (Mirtich 1996) steps to exactly that time and repeats: each step is
//! safe (the shapes are never closer than `s` at any fraction it reaches), and the steps shrink as
//! the gap closes. It stops when the distance is within `tolerance` of the target (a hit), when the
//! next step would pass `t = 1` (no hit within the step), or when `μ ≤ 0` (B is moving away
//! along `n` faster than it can turn towards A: no hit ever, by the same bound). The fraction
//! returned is therefore never later than the true time of impact, and the separation there is
//! in `[s, s + tolerance]`.
//!
//! Distances come from GJK between the cores (`gjk.rs`), less the radii; a half-space's distance is
//! in closed form (the lowest point of B against the surface).

use super::gjk::{gjk, ConvexPair};
use super::support::Rounded;
use crate::math::{DQuat, DVec3, Transform};

/// Most advancement steps; a hit needs a handful, a near miss at a shallow angle more. A query
/// that runs out reports a hit at the last (safe) fraction.
pub const MAX_ITERATIONS: u32 = 50;

/// A body's motion over one step: the centre of mass on a straight line, the rotation at a
/// constant rate about a fixed axis (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    /// Centre of mass in the body frame.
    pub com_local: DVec3,
    pub com_start_world: DVec3,
    pub com_end_world: DVec3,
    pub rotation_start: DQuat,
    pub rotation_end: DQuat,
    /// Unit axis of the turn from start to end, world frame (X when there is no turn).
    axis_world: DVec3,
    /// Angle of that turn, rad, in `[0, π]`.
    angle: f64,
}

impl Sweep {
    pub fn new(
        com_local: DVec3,
        (com_start_world, rotation_start): (DVec3, DQuat),
        (com_end_world, rotation_end): (DVec3, DQuat),
    ) -> Sweep {
        // The turn q₁ q₀⁻¹, taken the short way (q and −q are the same rotation).
        let mut turn = rotation_end * rotation_start.conjugate();
        if turn.w < 0.0 {
            turn = -turn;
        }
        let sin_half = DVec3::new(turn.x, turn.y, turn.z).length();
        let (axis_world, angle) = if sin_half > 0.0 && sin_half.is_finite() {
            (DVec3::new(turn.x, turn.y, turn.z) / sin_half, 2.0 * sin_half.atan2(turn.w))
        } else {
            (DVec3::X, 0.0)
        };
        Sweep { com_local, com_start_world, com_end_world, rotation_start, rotation_end, axis_world, angle }
    }

    /// Angle turned over the whole sweep, rad.
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// Displacement of the centre of mass over the whole sweep.
    pub fn displacement(&self) -> DVec3 {
        self.com_end_world - self.com_start_world
    }

    /// Centre of mass at fraction `t`.
    pub fn com_at(&self, t: f64) -> DVec3 {
        if t >= 1.0 {
            return self.com_end_world;
        }
        self.com_start_world + self.displacement() * t
    }

    /// Rotation at fraction `t` (the end pose exactly at `t = 1`).
    pub fn rotation_at(&self, t: f64) -> DQuat {
        if t <= 0.0 {
            return self.rotation_start;
        }
        if t >= 1.0 {
            return self.rotation_end;
        }
        (DQuat::from_axis_angle(self.axis_world, self.angle * t) * self.rotation_start).normalize()
    }

    /// The body frame's pose at fraction `t`.
    pub fn transform_at(&self, t: f64) -> Transform {
        let rotation = self.rotation_at(t);
        Transform::new(self.com_at(t) - rotation * self.com_local, rotation)
    }
}

/// The fixed shape a sweep is tested against.
#[derive(Clone, Copy, Debug)]
pub enum Target<'a> {
    /// A convex shape (a static body's shape, or one triangle of a mesh) at a world pose.
    Convex { shape: Rounded<'a>, pose: Transform },
    /// The solid half-space `n·x ≤ offset` (a plane shape), world frame.
    HalfSpace { normal_world: DVec3, offset: f64 },
}

/// The moving shape: a convex leaf of the swept body.
#[derive(Clone, Copy, Debug)]
pub struct Moving<'a> {
    pub shape: Rounded<'a>,
    /// The leaf's pose in the body frame.
    pub pose_local: Transform,
}

impl Moving<'_> {
    /// Largest distance of a point of the leaf from the body's centre of mass (`com_local`).
    pub fn max_radius(&self, com_local: DVec3) -> f64 {
        (self.pose_local.translation - com_local).length() + self.shape.bounding_radius()
    }
}

/// Distance between the target and the moving shape at one pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separation {
    /// Distance between the surfaces, m; negative when rounded shapes overlap by less than their
    /// radii (a half-space reports any depth).
    pub distance: f64,
    /// Unit normal from the target towards the moving shape, world frame.
    pub normal_world: DVec3,
}

/// The separation of the moving shape at `pose_world` (the leaf's world pose) from the target, or
/// `None` when the convex cores overlap (the depth is then unknown).
pub fn separation(target: &Target, moving: &Rounded, pose_world: &Transform) -> Option<Separation> {
    match *target {
        Target::Convex { shape, pose } => {
            let pair = ConvexPair::new(shape.core, &pose, moving.core, pose_world);
            let result = gjk(&pair, pair.b_in_a.translation);
            // Touching cores have no direction between them; they count as overlapping.
            if result.overlapping || result.distance <= 1e-12 * pair.scale() {
                return None;
            }
            let normal_local = (result.point_b - result.point_a) / result.distance;
            Some(Separation {
                distance: result.distance - shape.radius - moving.radius,
                normal_world: (pose.rotation * normal_local).normalize(),
            })
        }
        Target::HalfSpace { normal_world, offset } => {
            let down_local = pose_world.rotation.inverse() * -normal_world;
            let lowest = pose_world.transform_point(moving.core.support_local(down_local));
            Some(Separation { distance: normal_world.dot(lowest) - offset - moving.radius, normal_world })
        }
    }
}

/// How a time-of-impact query ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToiState {
    /// The shapes come within the target separation at `fraction`.
    Hit,
    /// They stay farther apart than the target for the whole sweep.
    Separated,
    /// Already within the target (plus the tolerance), or overlapping, at the start of the query.
    Overlapping,
    /// The iteration limit was reached; `fraction` is safe but may be early.
    Failed,
}

/// The result of [`time_of_impact`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToiOutput {
    pub state: ToiState,
    /// Fraction of the sweep reached: the time of impact for a hit, 1 when separated.
    pub fraction: f64,
    /// Separation at `fraction` (`None` for overlapping cores).
    pub separation: Option<Separation>,
    pub iterations: u32,
}

/// The first fraction in `[t_start, 1]` of `sweep` at which `moving` comes within
/// `target_separation` (± `tolerance` above it) of `target`, by conservative advancement (module
/// docs).
pub fn time_of_impact(
    target: &Target,
    moving: &Moving,
    sweep: &Sweep,
    t_start: f64,
    target_separation: f64,
    tolerance: f64,
) -> ToiOutput {
    // Farthest any point of the leaf can travel by turning, per unit fraction.
    let turn = sweep.angle() * moving.max_radius(sweep.com_local);
    let displacement = sweep.displacement();
    let t_start = if t_start.is_finite() { t_start.clamp(0.0, 1.0) } else { 0.0 };
    let mut t = t_start;
    let mut iterations = 0;
    loop {
        let pose = sweep.transform_at(t).mul_transform(&moving.pose_local);
        let sep = separation(target, &moving.shape, &pose);
        let output = |state, fraction| ToiOutput { state, fraction, separation: sep, iterations };
        let Some(s) = sep else {
            // Every step before this one was safe, so only round-off can bring the cores
            // together after the start: report the hit where it was seen.
            return output(if t == t_start { ToiState::Overlapping } else { ToiState::Hit }, t);
        };
        // NaN distances (a NaN pose) compare false everywhere: treat them as no hit.
        if !s.distance.is_finite() {
            return output(ToiState::Separated, 1.0);
        }
        if s.distance < target_separation + tolerance {
            let state = if t == t_start { ToiState::Overlapping } else { ToiState::Hit };
            return output(state, t);
        }
        let approach = -s.normal_world.dot(displacement) + turn;
        if approach <= 0.0 || !approach.is_finite() {
            return output(ToiState::Separated, 1.0);
        }
        let next = t + (s.distance - target_separation) / approach;
        if next >= 1.0 {
            return output(ToiState::Separated, 1.0);
        }
        if iterations >= MAX_ITERATIONS {
            return output(ToiState::Failed, t);
        }
        iterations += 1;
        t = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::support::Core;

    fn ball(radius: f64) -> Moving<'static> {
        Moving { shape: Rounded { core: Core::Point, radius }, pose_local: Transform::IDENTITY }
    }

    #[test]
    fn sweep_interpolates_and_ends_exactly() {
        let q0 = DQuat::from_rotation_z(0.3);
        let q1 = DQuat::from_rotation_z(1.5);
        let sweep = Sweep::new(DVec3::X, (DVec3::ZERO, q0), (DVec3::new(2.0, 0.0, 0.0), q1));
        assert!((sweep.angle() - 1.2).abs() < 1e-14);
        assert_eq!(sweep.rotation_at(1.0), q1);
        let mid = sweep.rotation_at(0.5);
        assert!(mid.angle_between(DQuat::from_rotation_z(0.9)) < 1e-12);
        assert_eq!(sweep.com_at(0.25), DVec3::new(0.5, 0.0, 0.0));
    }

    #[test]
    fn ball_against_half_space_matches_closed_form() {
        // Surface x = 0, solid below; a ball of radius 0.1 from x = −5 to x = +5 (t = (d − r)/v).
        let target = Target::HalfSpace { normal_world: -DVec3::X, offset: 0.0 };
        let sweep = Sweep::new(
            DVec3::ZERO,
            (DVec3::new(-5.0, 0.0, 0.0), DQuat::IDENTITY),
            (DVec3::new(5.0, 0.0, 0.0), DQuat::IDENTITY),
        );
        let out = time_of_impact(&target, &ball(0.1), &sweep, 0.0, 0.0, 1e-6);
        assert_eq!(out.state, ToiState::Hit);
        assert!((out.fraction - 0.49).abs() < 1e-7, "{}", out.fraction);
    }
}
