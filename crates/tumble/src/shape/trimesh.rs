//! A closed triangle mesh. Construction checks it (finite, closed, consistently wound, outward,
//! non-degenerate), so every `TriMesh` has well-defined mass properties.

use crate::mass::{validate_closed_mesh, MassError};
use crate::math::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct TriMesh {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A closed, outward-wound mesh; anything else is an error naming the problem.
    pub fn new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MassError> {
        validate_closed_mesh(&vertices, &triangles)?;
        Ok(Self { vertices, triangles })
    }

    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The same mesh with every vertex moved by `-offset` (used to put the centre of mass at the
    /// origin, so the body frame is the principal-centred frame of the mesh).
    pub fn translated(&self, offset: DVec3) -> TriMesh {
        TriMesh {
            vertices: self.vertices.iter().map(|&v| v - offset).collect(),
            triangles: self.triangles.clone(),
        }
    }
}
