//! Collision and mass shapes. One file per shape; this enum dispatches over them.
//!
//! Axis conventions: capsule, cylinder and cone lie along their local Z axis, centred on the origin
//! (the cone's base disc at z = −half_height, its apex at z = +half_height).

use crate::mass::{MassError, MassProperties};

mod compound;
mod convex_hull;
mod primitives;
mod trimesh;

pub use compound::{Compound, CompoundChild};
pub use convex_hull::{ConvexHull, HullEdge, HullError, HullFace};
pub use primitives::{Capsule, Cone, Cuboid, Cylinder, Sphere};
pub use trimesh::TriMesh;

/// A shape attached to a body.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Cuboid(Cuboid),
    Capsule(Capsule),
    Cylinder(Cylinder),
    Cone(Cone),
    /// A convex polyhedron (quickhull of a point cloud).
    ConvexHull(ConvexHull),
    /// A closed triangle mesh (its mass properties by the Mirtich–Eberly volume integrals).
    TriMesh(TriMesh),
    Compound(Compound),
}

impl Shape {
    /// Mass properties of this shape filled with uniform `density` (kg/m³), in the shape's frame.
    pub fn mass_properties(&self, density: f64) -> Result<MassProperties, MassError> {
        match self {
            Shape::Sphere(s) => MassProperties::sphere(s.radius, density),
            Shape::Cuboid(s) => MassProperties::cuboid(s.half_extents, density),
            Shape::Capsule(s) => MassProperties::capsule(s.radius, s.half_height, density),
            Shape::Cylinder(s) => MassProperties::cylinder(s.radius, s.half_height, density),
            Shape::Cone(s) => MassProperties::cone(s.radius, s.half_height, density),
            Shape::ConvexHull(h) => MassProperties::from_mesh(h.vertices(), &h.triangles(), density),
            Shape::TriMesh(m) => MassProperties::from_mesh(m.vertices(), m.triangles(), density),
            Shape::Compound(c) => {
                let parts = c
                    .children()
                    .iter()
                    .map(|child| Ok(child.shape.mass_properties(density)?.transformed(&child.pose)))
                    .collect::<Result<Vec<_>, MassError>>()?;
                MassProperties::combine(&parts)
            }
        }
    }

    /// A short lower-case name of the shape kind ("box", "sphere", …) for messages and files.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Cuboid(_) => "box",
            Shape::Capsule(_) => "capsule",
            Shape::Cylinder(_) => "cylinder",
            Shape::Cone(_) => "cone",
            Shape::ConvexHull(_) => "hull",
            Shape::TriMesh(_) => "mesh",
            Shape::Compound(_) => "compound",
        }
    }
}

/// Checks that a length is finite and strictly positive.
pub(crate) fn check_positive(what: &'static str, value: f64) -> Result<f64, MassError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MassError::NotPositive { what, value })
    }
}
