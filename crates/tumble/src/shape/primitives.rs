//! The primitive convex shapes. Constructors validate their sizes, so a shape that exists is valid.

use super::check_positive;
use crate::mass::MassError;
use crate::math::DVec3;

/// A ball of `radius` centred on the origin.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sphere {
    pub radius: f64,
}

impl Sphere {
    pub fn new(radius: f64) -> Result<Self, MassError> {
        Ok(Self { radius: check_positive("sphere radius", radius)? })
    }
}

/// A box with the given half extents along local X, Y, Z, centred on the origin.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cuboid {
    pub half_extents: DVec3,
}

impl Cuboid {
    pub fn new(half_extents: DVec3) -> Result<Self, MassError> {
        check_positive("box half extent x", half_extents.x)?;
        check_positive("box half extent y", half_extents.y)?;
        check_positive("box half extent z", half_extents.z)?;
        Ok(Self { half_extents })
    }
}

/// A segment from (0, 0, −half_height) to (0, 0, +half_height) swept by a ball of `radius`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Capsule {
    pub radius: f64,
    pub half_height: f64,
}

impl Capsule {
    pub fn new(radius: f64, half_height: f64) -> Result<Self, MassError> {
        Ok(Self {
            radius: check_positive("capsule radius", radius)?,
            half_height: check_positive("capsule half_height", half_height)?,
        })
    }
}

/// A solid circular cylinder along local Z, from z = −half_height to z = +half_height.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cylinder {
    pub radius: f64,
    pub half_height: f64,
}

impl Cylinder {
    pub fn new(radius: f64, half_height: f64) -> Result<Self, MassError> {
        Ok(Self {
            radius: check_positive("cylinder radius", radius)?,
            half_height: check_positive("cylinder half_height", half_height)?,
        })
    }
}

/// A solid circular cone along local Z: base disc of `radius` at z = −half_height, apex at
/// z = +half_height. Its centre of mass is at z = −half_height / 2, not at the origin.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cone {
    pub radius: f64,
    pub half_height: f64,
}

impl Cone {
    pub fn new(radius: f64, half_height: f64) -> Result<Self, MassError> {
        Ok(Self {
            radius: check_positive("cone radius", radius)?,
            half_height: check_positive("cone half_height", half_height)?,
        })
    }
}
