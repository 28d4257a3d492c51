//! Closed triangle meshes: validation, and mass properties by the Mirtich–Eberly volume integrals.

use super::{MassError, MassProperties};
use crate::math::DVec3;

/// Checks that a mesh is finite, non-degenerate, closed, consistently and outwardly wound.
pub fn validate_closed_mesh(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), MassError> {
    todo!()
}

impl MassProperties {
    /// Mass properties of the solid bounded by a closed, outward-wound triangle mesh.
    pub fn from_mesh(vertices: &[DVec3], triangles: &[[u32; 3]], density: f64) -> Result<Self, MassError> {
        todo!()
    }
}
