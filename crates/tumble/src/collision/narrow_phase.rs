//! The shape-pair table: one contact routine per pair of shape kinds.
//!
//! | pair | routine |
//! |---|---|
//! | sphere–sphere, sphere–capsule, capsule–capsule, sphere–box | closed forms (`round`) |
//! | box–box, box–hull, hull–hull | separating axes + face clipping (`sat`) |
//! | everything else convex (cylinder, cone, capsule–box, …) | GJK/EPA + feature clipping (`convex_contact`) |
//!
//! The table is written for one order of each pair (by [`kind_rank`]); the other order calls it
//! with the shapes swapped and flips the result, so `collide(a, b)` and `collide(b, a)` agree up to
//! the direction of the normal. Planes, height fields and triangle meshes go to
//! `static_pairs::collide_static` first; compounds are split into leaves by the contact manager.

use super::convex_contact::collide_convex;
use super::manifold::Manifold;
use super::polytope::Polytope;
use super::round::{box_sphere, capsule_capsule, sphere_capsule, sphere_sphere};
use super::sat::{collide_polytopes, SatCache};
use super::static_pairs::{collide_static, is_static_geometry};
use super::support::Rounded;
use crate::math::{DVec3, Transform};
use crate::shape::Shape;

/// What a pair remembers between steps to make the next query cheaper and its answer stable.
/// Start with `PairCache::default()` and pass the same cache for the same ordered pair each step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PairCache {
    /// The separating-axis test's last axis (box and hull pairs).
    pub sat: SatCache,
    /// Last contact normal in the first shape's frame, GJK's starting direction (other pairs).
    pub normal_local: DVec3,
}

/// Position of a shape kind in the table's pair order; `None` for shapes that are not convex.
pub fn kind_rank(shape: &Shape) -> Option<u8> {
    match shape {
        Shape::Sphere(_) => Some(0),
        Shape::Capsule(_) => Some(1),
        Shape::Cuboid(_) => Some(2),
        Shape::ConvexHull(_) => Some(3),
        Shape::Cylinder(_) => Some(4),
        Shape::Cone(_) => Some(5),
        Shape::TriMesh(_) | Shape::Compound(_) | Shape::Plane(_) | Shape::HeightField(_) => None,
    }
}

/// The contact manifold of two shapes (convex, or convex against static geometry: a plane, height
/// field or triangle mesh) at the given poses, or `None` when they are more
/// than `speculative_margin` apart (contacts within the margin are reported with positive
/// separation, so the solver can stop bodies before they meet). The normal points from A to B.
pub fn collide(
    shape_a: &Shape,
    pose_a: &Transform,
    shape_b: &Shape,
    pose_b: &Transform,
    speculative_margin: f64,
    cache: &mut PairCache,
) -> Option<Manifold> {
    if is_static_geometry(shape_a) || is_static_geometry(shape_b) {
        return collide_static(shape_a, pose_a, shape_b, pose_b, speculative_margin);
    }
    let (ra, rb) = (kind_rank(shape_a)?, kind_rank(shape_b)?);
    if ra > rb {
        return collide_ordered(shape_b, pose_b, shape_a, pose_a, speculative_margin, cache)
            .map(|m| m.flipped());
    }
    collide_ordered(shape_a, pose_a, shape_b, pose_b, speculative_margin, cache)
}

/// The table proper, for `kind_rank(a) <= kind_rank(b)`.
fn collide_ordered(
    a: &Shape,
    pose_a: &Transform,
    b: &Shape,
    pose_b: &Transform,
    margin: f64,
    cache: &mut PairCache,
) -> Option<Manifold> {
    match (a, b) {
        (Shape::Sphere(sa), Shape::Sphere(sb)) => sphere_sphere(sa, pose_a, sb, pose_b, margin),
        (Shape::Sphere(sa), Shape::Capsule(cb)) => sphere_capsule(sa, pose_a, cb, pose_b, margin),
        (Shape::Capsule(ca), Shape::Capsule(cb)) => capsule_capsule(ca, pose_a, cb, pose_b, margin),
        (Shape::Sphere(sa), Shape::Cuboid(bb)) => {
            box_sphere(bb, pose_b, sa, pose_a, margin).map(|m| m.flipped())
        }
        _ => match (polytope(a), polytope(b)) {
            (Some(pa), Some(pb)) => collide_polytopes(&pa, pose_a, &pb, pose_b, margin, &mut cache.sat),
            _ => collide_convex(
                &Rounded::of(a)?,
                pose_a,
                &Rounded::of(b)?,
                pose_b,
                margin,
                &mut cache.normal_local,
            ),
        },
    }
}

fn polytope(shape: &Shape) -> Option<Polytope<'_>> {
    match shape {
        Shape::Cuboid(c) => Some(Polytope::Cuboid { half_extents: c.half_extents }),
        Shape::ConvexHull(h) => Some(Polytope::Hull(h)),
        _ => None,
    }
}
