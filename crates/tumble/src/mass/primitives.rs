//! Mass properties of the primitive solids, and the operations that move and combine them.

use super::{MassError, MassProperties, PrincipalFrame};
use crate::math::{DMat3, DVec3, Transform};

impl MassProperties {
    /// Solid ball of `radius` at uniform `density`.
    pub fn sphere(radius: f64, density: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// Solid box with `half_extents` at uniform `density`.
    pub fn cuboid(half_extents: DVec3, density: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// Solid capsule along Z (cylinder of `half_height` plus two hemispherical caps).
    pub fn capsule(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// Solid cylinder along Z.
    pub fn cylinder(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// Solid cone along Z, base at −half_height, apex at +half_height.
    pub fn cone(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// The same solid rescaled to total `mass` (the density is whatever gives that mass).
    pub fn with_mass(self, mass: f64) -> Result<Self, MassError> {
        todo!()
    }

    /// The same solid placed at `pose`: the centre of mass is mapped by `pose` and the inertia
    /// rotated, `I' = R I Rᵀ`.
    pub fn transformed(&self, pose: &Transform) -> Self {
        todo!()
    }

    /// The union of non-overlapping parts, all in one frame (parallel-axis theorem).
    pub fn combine(parts: &[MassProperties]) -> Result<Self, MassError> {
        todo!()
    }

    /// Principal moments (ascending) and axes (a rotation whose columns are the axes).
    pub fn principal(&self) -> PrincipalFrame {
        todo!()
    }
}
