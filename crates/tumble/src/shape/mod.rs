//! Collision and mass shapes. One file per shape; this enum dispatches over them.
//!
//! Axis conventions: capsule, cylinder and cone lie along their local Z axis, centred on the origin
//! (the cone's base disc at z = −half_height, its apex at z = +half_height).

use crate::mass::{MassError, MassProperties};

mod compound;
mod convex_hull;
mod error;
mod heightfield;
mod plane;
mod primitives;
mod trimesh;

pub use compound::{Compound, CompoundChild};
pub use convex_hull::{ConvexHull, HullEdge, HullError, HullFace};
pub use error::ShapeError;
pub use heightfield::HeightField;
pub use plane::{Plane, PLANE_EXTENT};
pub use primitives::{Capsule, Cone, Cuboid, Cylinder, Sphere};
pub use trimesh::TriMesh;

/// A shape attached to a body.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Shape {
    Sphere(Sphere),
    Cuboid(Cuboid),
    Capsule(Capsule),
    Cylinder(Cylinder),
    Cone(Cone),
    /// A convex polyhedron (quickhull of a point cloud).
    ConvexHull(ConvexHull),
    /// A triangle mesh: closed (mass by the Mirtich–Eberly volume integrals; a dynamic body
    /// collides through its convex hull) or static (`TriMesh::new_static`, possibly open).
    TriMesh(TriMesh),
    Compound(Compound),
    /// A half-space (static bodies only).
    Plane(Plane),
    /// Terrain from a grid of heights (static bodies only).
    HeightField(HeightField),
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
            Shape::ConvexHull(h) => {
                MassProperties::from_hull_triangles(h.vertices(), &h.triangles(), density)
            }
            Shape::TriMesh(m) if !m.is_closed() => Err(MassError::StaticOnly {
                what: "a static (possibly open) triangle mesh from TriMesh::new_static",
            }),
            Shape::TriMesh(m) => MassProperties::from_mesh(m.vertices(), m.triangles(), density),
            Shape::Plane(_) => Err(MassError::StaticOnly { what: "a plane (an infinite half-space)" }),
            Shape::HeightField(_) => Err(MassError::StaticOnly { what: "a height field" }),
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
            Shape::Plane(_) => "plane",
            Shape::HeightField(_) => "heightfield",
        }
    }

    /// The name of the first part of this shape that only a static body may have (a plane or a
    /// height field, also inside a compound), or `None`.
    pub fn static_only_part(&self) -> Option<&'static str> {
        match self {
            Shape::Plane(_) => Some("plane"),
            Shape::HeightField(_) => Some("height field"),
            Shape::Compound(c) => c.children().iter().find_map(|child| child.shape.static_only_part()),
            _ => None,
        }
    }

    /// The shape a *dynamic* body collides as: a closed mesh's convex hull, anything else itself.
    pub fn moving_collision_shape(&self) -> &Shape {
        match self {
            Shape::TriMesh(m) => m.hull_shape().unwrap_or(self),
            other => other,
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
