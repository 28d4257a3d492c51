//! The shape-pair table's rows for static geometry: planes, height fields and triangle meshes.
//!
//! | pair | routine |
//! |---|---|
//! | plane–convex | closed form (`plane_contact`) |
//! | mesh–convex, height field–convex | per triangle with the internal-edge rule (`mesh_contact`) |
//! | mesh–mesh, mesh–plane, mesh–height field | a closed mesh through its convex hull against the other |
//! | plane–plane, height field–plane, … | nothing: static geometry never meets static geometry |
//!
//! `narrow_phase::collide` sends every pair with a plane, height field or mesh here. A mesh on its
//! own is treated as static triangles; the contact manager hands a *dynamic* body's closed mesh
//! over as its convex hull (`Shape::moving_collision_shape`) before it gets here. When both
//! shapes are meshes, the closed one (B's first) takes part through its hull.

use super::manifold::Manifold;
use super::mesh_contact::collide_triangles_convex;
use super::plane_contact::collide_plane_convex;
use super::support::Rounded;
use crate::math::Transform;
use crate::shape::Shape;

/// True for the shapes this table handles: planes, height fields and triangle meshes.
pub fn is_static_geometry(shape: &Shape) -> bool {
    matches!(shape, Shape::Plane(_) | Shape::HeightField(_) | Shape::TriMesh(_))
}

/// Contact of a pair with at least one static-geometry shape; the normal points from A to B.
pub fn collide_static(
    a: &Shape,
    pose_a: &Transform,
    b: &Shape,
    pose_b: &Transform,
    margin: f64,
) -> Option<Manifold> {
    match (is_static_geometry(a), is_static_geometry(b)) {
        (true, false) => static_convex(a, pose_a, b, pose_b, margin),
        (false, true) => static_convex(b, pose_b, a, pose_a, margin).map(|m| m.flipped()),
        (true, true) => {
            if let Some(hull) = closed_hull(b) {
                static_convex(a, pose_a, hull, pose_b, margin)
            } else if let Some(hull) = closed_hull(a) {
                static_convex(b, pose_b, hull, pose_a, margin).map(|m| m.flipped())
            } else {
                None
            }
        }
        (false, false) => None,
    }
}

fn closed_hull(shape: &Shape) -> Option<&Shape> {
    match shape {
        Shape::TriMesh(m) => m.hull_shape(),
        _ => None,
    }
}

/// Static geometry `s` (A) against the convex shape `c` (B).
fn static_convex(
    s: &Shape,
    pose_s: &Transform,
    c: &Shape,
    pose_c: &Transform,
    margin: f64,
) -> Option<Manifold> {
    match s {
        Shape::Plane(p) => collide_plane_convex(p, pose_s, &Rounded::of(c)?, pose_c, margin),
        Shape::TriMesh(m) => collide_triangles_convex(m, pose_s, c, pose_c, margin),
        Shape::HeightField(h) => collide_triangles_convex(h, pose_s, c, pose_c, margin),
        _ => None,
    }
}
