//! Convex shape against a half-space, in closed form.
//!
//! The plane's surface is flat and unbounded, so the contact is simply the shape's points that
//! come within the margin of it, each with its own height above the surface:
//! - sphere: its centre (one point); capsule: both ends of its core segment (two points when it
//!   lies flat, so it does not rock);
//! - box and hull: every vertex within the margin (a box resting flat gives its four bottom
//!   corners), reduced to the best four;
//! - cylinder and cone: the supporting feature facing the plane (a cap polygon, a side line or a
//!   rim point), reduced to four.
//!
//! Feature ids name the shape's vertex (box corner, hull vertex, capsule end, cap corner), so they
//! stay fixed while the shape slides or turns on the plane.

use smallvec::SmallVec;

use super::feature::supporting_feature;
use super::manifold::{ContactPoint, Manifold};
use super::support::{Core, Rounded};
use crate::math::{DVec3, Transform};
use crate::shape::Plane;

/// Contact of a plane (A) with a convex shape (B); the normal points from the plane to the shape
/// (the plane's outward normal). `None` when the shape is more than `margin` above the surface.
pub fn collide_plane_convex(
    plane: &Plane,
    pose_plane: &Transform,
    convex: &Rounded,
    pose_convex: &Transform,
    margin: f64,
) -> Option<Manifold> {
    let n_world = pose_plane.rotation * plane.normal;
    let offset_world = plane.offset + n_world.dot(pose_plane.translation);
    // The shape's lowest point first: nothing else can touch if it does not.
    let down_local = pose_convex.rotation.inverse() * -n_world;
    let lowest = pose_convex.transform_point(convex.core.support_local(down_local));
    if n_world.dot(lowest) - offset_world - convex.radius > margin {
        return None;
    }
    // The shape's points that may touch, in its local frame, with their ids.
    let mut points: SmallVec<[(DVec3, u32); 16]> = SmallVec::new();
    match convex.core {
        Core::Point => points.push((DVec3::ZERO, 0)),
        Core::Segment { half_height } => {
            points.push((DVec3::new(0.0, 0.0, -half_height), 0));
            points.push((DVec3::new(0.0, 0.0, half_height), 1));
        }
        Core::Cuboid { half_extents } => {
            for i in 0..8u32 {
                let s = |bit: u32| if i & bit == 0 { -1.0 } else { 1.0 };
                points.push((half_extents * DVec3::new(s(1), s(2), s(4)), i));
            }
        }
        Core::Hull(h) => points.extend(h.vertices().iter().enumerate().map(|(i, &v)| (v, i as u32))),
        _ => {
            let feature = supporting_feature(&convex.core, down_local);
            let code = u32::from(feature.code) << 16;
            points.extend(feature.points.iter().enumerate().map(|(k, &p)| (p, code | k as u32)));
        }
    }
    let contact = |p_local: DVec3, id: u32| {
        let p = pose_convex.transform_point(p_local);
        let sep = n_world.dot(p) - offset_world - convex.radius;
        let on_b = p - n_world * convex.radius;
        let mid = on_b - n_world * (0.5 * sep);
        (sep <= margin).then(|| ContactPoint::new(pose_plane, pose_convex, n_world, mid, sep, id))
    };
    let mut candidates: SmallVec<[ContactPoint; 16]> =
        points.iter().filter_map(|&(p, id)| contact(p, id)).collect();
    let curved =
        !matches!(convex.core, Core::Point | Core::Segment { .. } | Core::Cuboid { .. } | Core::Hull(_));
    let shallowest_miss = |c: &[ContactPoint]| {
        let deepest = c.iter().map(|p| p.separation).fold(f64::INFINITY, f64::min);
        deepest - (n_world.dot(lowest) - offset_world - convex.radius) > 1e-6
    };
    if candidates.is_empty() || (curved && shallowest_miss(&candidates)) {
        // A curved feature's polygon (a cylinder's cap rim) can sit above the true lowest point
        // (by 0.6 mm on a tipped 1.5 m disc): then that point is a candidate too. (Not when a
        // polygon corner is as low, so a cylinder standing on its cap keeps fixed corners.)
        candidates.extend(contact(pose_convex.inverse_transform_point(lowest), 0xFFFF));
    }
    Manifold::from_candidates(n_world, &candidates)
}
