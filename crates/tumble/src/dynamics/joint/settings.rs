//! Settings shared by several joints — limits, motors, springs — and their validation.
//!
//! Units follow the joint coordinate: radians and N·m for angular joints (hinge), metres and N
//! for linear ones (slider, distance).

use std::f64::consts::PI;

/// A range `[lower, upper]` the joint coordinate must stay in.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Limits {
    pub lower: f64,
    pub upper: f64,
}

impl Limits {
    pub fn new(lower: f64, upper: f64) -> Limits {
        Limits { lower, upper }
    }
}

/// A velocity motor: drives the joint speed to `target_speed` (rad/s or m/s) with at most
/// `max_force` (N·m for angular joints, N for linear ones).
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Motor {
    pub target_speed: f64,
    pub max_force: f64,
}

impl Motor {
    pub fn new(target_speed: f64, max_force: f64) -> Motor {
        Motor { target_speed, max_force }
    }
}

/// A spring–damper on the joint coordinate: natural frequency `hertz` (Hz) and damping ratio
/// (0 = undamped, 1 = critically damped). The stiffness follows from the frequency and the
/// effective mass of the joint row, `k = m_eff (2π·hertz)²`, so a spring keeps its frequency
/// whatever it carries; `hertz = 0` means no spring force.
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct SpringSettings {
    pub hertz: f64,
    pub damping_ratio: f64,
}

impl SpringSettings {
    pub fn new(hertz: f64, damping_ratio: f64) -> SpringSettings {
        SpringSettings { hertz, damping_ratio }
    }
}

/// `what` must be finite.
pub(crate) fn check_finite(what: &str, value: f64) -> Result<(), String> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} must be finite, got {value}"))
    }
}

/// `what` must be finite and >= 0.
pub(crate) fn check_non_negative(what: &str, value: f64) -> Result<(), String> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(format!("{what} must be finite and >= 0, got {value}"))
    }
}

/// Ordered, finite limits.
pub(crate) fn check_limits(what: &str, limits: &Limits) -> Result<(), String> {
    check_finite(&format!("{what} lower"), limits.lower)?;
    check_finite(&format!("{what} upper"), limits.upper)?;
    if limits.lower > limits.upper {
        return Err(format!("{what}: lower ({}) must be <= upper ({})", limits.lower, limits.upper));
    }
    Ok(())
}

/// Ordered angle limits within `[−π, π]` (angles are measured in `(−π, π]`).
pub(crate) fn check_angle_limits(what: &str, limits: &Limits) -> Result<(), String> {
    check_limits(what, limits)?;
    if limits.lower < -PI || limits.upper > PI {
        return Err(format!("{what} must lie within [-pi, pi], got [{}, {}]", limits.lower, limits.upper));
    }
    Ok(())
}

pub(crate) fn check_motor(what: &str, motor: &Motor) -> Result<(), String> {
    check_finite(&format!("{what} target_speed"), motor.target_speed)?;
    check_non_negative(&format!("{what} max_force"), motor.max_force)
}

pub(crate) fn check_spring(what: &str, spring: &SpringSettings) -> Result<(), String> {
    check_non_negative(&format!("{what} hertz"), spring.hertz)?;
    check_non_negative(&format!("{what} damping_ratio"), spring.damping_ratio)
}
