//! Ray casts against single shapes.
//!
//! Every cast is done in the shape's local frame (where the primitives are axis-aligned and
//! centred) and mapped back: rotations preserve distance, so the local hit distance is the world
//! one. The hit point is recomputed in world space as `origin + distance·direction`, which is more
//! accurate far from the origin than transforming the local point back.
//!
//! ## Conventions
//! - Solid convex shapes (sphere, cuboid, capsule, cylinder, cone): a ray whose origin is inside
//!   the shape or on its surface hits at distance 0, at its origin, with normal `−direction`.
//!   This is what a "what is in front of me" query wants — the closest solid is the one it is in —
//!   and the normal choice keeps `normal · direction < 0` for every convex hit.
//! - Triangle meshes are treated as surfaces: the ray reports its first crossing of any triangle,
//!   front or back face, with that triangle's outward normal. A hit with `normal · direction > 0`
//!   means the ray started inside the closed mesh and is leaving it.
//! - A plane is a solid half-space (origin inside → distance 0, like the convex solids). Height
//!   fields are surfaces like meshes: first crossing from either side, with the triangle's
//!   upward normal. Meshes and height fields use their BVH / cell walk.
//! - Compounds report the closest hit over their children.
//! - Hits farther than `max_distance` are misses.

use crate::math::{DVec3, Transform};
use crate::shape::{Capsule, Cone, Cuboid, Cylinder, Shape};

/// A half-line `origin + t·direction` for `t` in `[0, max_distance]`; `direction` is unit length.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
    pub max_distance: f64,
}

impl Ray {
    /// A ray along `direction` (normalized here; it must be non-zero and finite).
    pub fn new(origin: DVec3, direction: DVec3, max_distance: f64) -> Self {
        let direction = direction.normalize();
        debug_assert!(direction.is_finite(), "Ray::new: direction must be non-zero and finite");
        Self { origin, direction, max_distance }
    }

    /// The point at distance `t` along the ray.
    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.direction
    }
}

/// Where a ray first meets a shape. `normal` is unit length, in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RayHit {
    pub distance: f64,
    pub point: DVec3,
    pub normal: DVec3,
}

/// A hit in the shape's local frame: distance along the ray and the local outward normal.
/// `normal == None` marks "the origin is inside" (reported with normal `−direction`).
type LocalHit = (f64, Option<DVec3>);

/// The first hit of `ray` (world) on `shape` placed at `pose`, or `None` for a miss.
pub fn ray_cast_shape(shape: &Shape, pose: &Transform, ray: &Ray) -> Option<RayHit> {
    if let Shape::Compound(c) = shape {
        return c
            .children()
            .iter()
            .filter_map(|child| ray_cast_shape(&child.shape, &pose.mul_transform(&child.pose), ray))
            .min_by(|a, b| a.distance.total_cmp(&b.distance));
    }
    let inv_rotation = pose.rotation.inverse();
    let origin_local = inv_rotation * (ray.origin - pose.translation);
    let direction_local = inv_rotation * ray.direction;
    let (o, d, max_t) = (origin_local, direction_local, ray.max_distance);
    let local: Option<LocalHit> = match shape {
        Shape::Sphere(s) => sphere_local(o, d, s.radius),
        Shape::Cuboid(c) => cuboid_local(o, d, c),
        Shape::Capsule(c) => capsule_local(o, d, c),
        Shape::Cylinder(c) => cylinder_local(o, d, c),
        Shape::Cone(c) => cone_local(o, d, c),
        Shape::TriMesh(m) => m.ray_cast_local(o, d, max_t).map(|(t, n_local, _)| (t, Some(n_local))),
        Shape::HeightField(h) => h.ray_cast_local(o, d, max_t).map(|(t, n_local, _)| (t, Some(n_local))),
        Shape::Plane(p) => plane_local(o, d, p),
        Shape::ConvexHull(h) => hull_local(o, d, h),
        Shape::Compound(_) => unreachable!("handled above"),
    };
    let (distance, normal_local) = local?;
    if distance > max_t {
        return None;
    }
    let normal = match normal_local {
        Some(n_local) => pose.rotation * n_local,
        None => -ray.direction,
    };
    Some(RayHit { distance, point: ray.at(distance), normal })
}

/// A half-space is solid: an origin inside (or on the surface) hits at 0; otherwise the ray
/// enters where it crosses the surface, if it is heading towards it.
fn plane_local(o: DVec3, d: DVec3, p: &crate::shape::Plane) -> Option<LocalHit> {
    let height = p.signed_distance(o);
    if height <= 0.0 {
        return Some((0.0, None));
    }
    let rate = p.normal.dot(d);
    (rate < 0.0).then(|| (height / -rate, Some(p.normal)))
}

/// The smaller root `t` of `|o + t·d − center|² = r²` for a unit `d`, if the line meets the
/// sphere. Uses the closest-approach form (Haines et al., *Ray Tracing Gems* ch. 7) because the
/// textbook discriminant `b² − c` cancels catastrophically for a far-away origin.
fn sphere_entry(o: DVec3, d: DVec3, center: DVec3, r: f64) -> Option<f64> {
    let oc = o - center;
    let b = oc.dot(d);
    let closest = oc - b * d;
    let disc = r * r - closest.length_squared();
    (disc >= 0.0).then(|| -b - disc.sqrt())
}

fn sphere_local(o: DVec3, d: DVec3, r: f64) -> Option<LocalHit> {
    if o.length_squared() <= r * r {
        return Some((0.0, None));
    }
    let t = sphere_entry(o, d, DVec3::ZERO, r).filter(|&t| t >= 0.0)?;
    Some((t, Some((o + t * d) / r)))
}

/// A convex polytope is the intersection of its face half-spaces: clip the ray's parameter
/// interval against each plane (Cyrus–Beck); the entering plane gives the normal.
fn hull_local(o: DVec3, d: DVec3, hull: &crate::shape::ConvexHull) -> Option<LocalHit> {
    let (mut t_enter, mut t_exit) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut normal = None;
    for face in hull.faces() {
        let distance = face.normal.dot(o) - face.offset; // > 0: origin outside this plane
        let rate = face.normal.dot(d);
        if rate == 0.0 {
            if distance > 0.0 {
                return None; // parallel and outside
            }
            continue;
        }
        let t = -distance / rate;
        if rate < 0.0 {
            if t > t_enter {
                t_enter = t;
                normal = Some(face.normal);
            }
        } else {
            t_exit = t_exit.min(t);
        }
    }
    if t_enter > t_exit || t_exit < 0.0 {
        return None;
    }
    if t_enter <= 0.0 {
        return Some((0.0, None)); // the origin is inside
    }
    Some((t_enter, normal))
}

fn cuboid_local(o: DVec3, d: DVec3, c: &Cuboid) -> Option<LocalHit> {
    let h = c.half_extents;
    if o.abs().cmple(h).all() {
        return Some((0.0, None));
    }
    let (mut t_enter, mut t_exit, mut axis) = (f64::NEG_INFINITY, f64::INFINITY, 0);
    for i in 0..3 {
        if d[i] == 0.0 {
            if o[i].abs() > h[i] {
                return None;
            }
            continue;
        }
        let inv = 1.0 / d[i];
        let (t0, t1) = ((-h[i] - o[i]) * inv, (h[i] - o[i]) * inv);
        let (near, far) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
        if near > t_enter {
            t_enter = near;
            axis = i;
        }
        t_exit = t_exit.min(far);
    }
    // The origin is outside, so some slab has a finite entry; t_enter < 0 means the box is behind.
    if t_enter > t_exit || t_enter < 0.0 {
        return None;
    }
    let mut n = DVec3::ZERO;
    n[axis] = -d[axis].signum();
    Some((t_enter, Some(n)))
}

/// Entry into the infinite cylinder `x² + y² ≤ r²` around local Z, for an origin outside it.
fn side_entry(o: DVec3, d: DVec3, r: f64) -> Option<f64> {
    let a = d.x * d.x + d.y * d.y;
    if a == 0.0 || o.x * o.x + o.y * o.y <= r * r {
        return None;
    }
    let b = o.x * d.x + o.y * d.y;
    let t_closest = -b / a;
    let (cx, cy) = (o.x + t_closest * d.x, o.y + t_closest * d.y);
    let disc = r * r - (cx * cx + cy * cy);
    (disc >= 0.0).then(|| t_closest - (disc / a).sqrt()).filter(|&t| t >= 0.0)
}

fn side_normal(p: DVec3) -> DVec3 {
    DVec3::new(p.x, p.y, 0.0).normalize_or(DVec3::X)
}

/// Keeps the closer of two candidate hits.
fn closer(best: Option<LocalHit>, candidate: Option<LocalHit>) -> Option<LocalHit> {
    match (best, candidate) {
        (Some(b), Some(c)) => Some(if c.0 < b.0 { c } else { b }),
        (b, c) => b.or(c),
    }
}

fn capsule_local(o: DVec3, d: DVec3, c: &Capsule) -> Option<LocalHit> {
    let (r, hh) = (c.radius, c.half_height);
    let nearest_on_axis = DVec3::new(0.0, 0.0, o.z.clamp(-hh, hh));
    if (o - nearest_on_axis).length_squared() <= r * r {
        return Some((0.0, None));
    }
    // The capsule is the union of a finite cylinder and two balls; the first entry into a union of
    // solids is the earliest entry into any of them, and the cylinder's flat caps lie inside the
    // balls, so only its side needs testing.
    let mut best = side_entry(o, d, r)
        .filter(|&t| (o.z + t * d.z).abs() <= hh)
        .map(|t| (t, Some(side_normal(o + t * d))));
    for z in [-hh, hh] {
        let center = DVec3::new(0.0, 0.0, z);
        let hit = sphere_entry(o, d, center, r).filter(|&t| t >= 0.0);
        best = closer(best, hit.map(|t| (t, Some((o + t * d - center) / r))));
    }
    best
}

/// Entry through a flat cap at height `z_cap` whose outward normal is `normal_z`·Z, with the disc
/// of radius `r`: only an origin on the outer side can enter through it.
fn cap_entry(o: DVec3, d: DVec3, z_cap: f64, normal_z: f64, r: f64) -> Option<LocalHit> {
    if (o.z - z_cap) * normal_z <= 0.0 || d.z * normal_z >= 0.0 {
        return None;
    }
    let t = (z_cap - o.z) / d.z;
    let p = o + t * d;
    (p.x * p.x + p.y * p.y <= r * r).then_some((t, Some(DVec3::new(0.0, 0.0, normal_z))))
}

fn cylinder_local(o: DVec3, d: DVec3, c: &Cylinder) -> Option<LocalHit> {
    let (r, hh) = (c.radius, c.half_height);
    if o.x * o.x + o.y * o.y <= r * r && o.z.abs() <= hh {
        return Some((0.0, None));
    }
    let side = side_entry(o, d, r)
        .filter(|&t| (o.z + t * d.z).abs() <= hh)
        .map(|t| (t, Some(side_normal(o + t * d))));
    let caps = closer(cap_entry(o, d, hh, 1.0, r), cap_entry(o, d, -hh, -1.0, r));
    closer(side, caps)
}

/// The cone's lateral surface is `x² + y² = (k·u)²` with `u = hh − z ∈ [0, 2·hh]` (distance below
/// the apex) and slope `k = r / (2·hh)`; its base is the disc `z = −hh`.
fn cone_local(o: DVec3, d: DVec3, c: &Cone) -> Option<LocalHit> {
    let (r, hh) = (c.radius, c.half_height);
    let k2 = (r / (2.0 * hh)).powi(2);
    let u0 = hh - o.z;
    let rho2 = o.x * o.x + o.y * o.y;
    if (0.0..=2.0 * hh).contains(&u0) && rho2 <= k2 * u0 * u0 {
        return Some((0.0, None));
    }
    // (o_xy + t·d_xy)² − k²(u0 − t·d_z)² = 0  →  a·t² + 2·b·t + c = 0.
    let a = d.x * d.x + d.y * d.y - k2 * d.z * d.z;
    let b = o.x * d.x + o.y * d.y + k2 * u0 * d.z;
    let c0 = rho2 - k2 * u0 * u0;
    let roots: [Option<f64>; 2] = if a.abs() <= 1e-14 {
        // The ray is parallel to a generator line: one crossing of the double cone at most.
        [(b != 0.0).then(|| -c0 / (2.0 * b)), None]
    } else {
        let disc = b * b - a * c0;
        if disc < 0.0 {
            [None, None]
        } else {
            // Stable pair of roots: q never suffers cancellation, and t1·t2 = c/a.
            let q = -(b + b.signum() * disc.sqrt());
            [Some(q / a), (q != 0.0).then(|| c0 / q)]
        }
    };
    let mut best = cap_entry(o, d, -hh, -1.0, r);
    for t in roots.into_iter().flatten() {
        let u = u0 - t * d.z;
        if t >= 0.0 && (0.0..=2.0 * hh).contains(&u) {
            let p = o + t * d;
            let n = DVec3::new(p.x, p.y, k2 * u).normalize_or(DVec3::Z);
            best = closer(best, Some((t, Some(n))));
        }
    }
    best
}

/// Closest crossing of a ray (local frame, unit `direction_local`) with a triangle list, by
/// Möller–Trumbore, both faces. Returns the distance and the triangle's outward normal (from its
/// counter-clockwise winding). Linear in the triangle count (`TriMesh::ray_cast_local` uses the BVH).
pub fn ray_cast_mesh_local(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    origin_local: DVec3,
    direction_local: DVec3,
    max_distance: f64,
) -> Option<(f64, DVec3)> {
    let mut best: Option<(f64, DVec3)> = None;
    let mut t_max = max_distance;
    for tri in triangles {
        let [p0, p1, p2] = tri.map(|i| vertices[i as usize]);
        let (e1, e2) = (p1 - p0, p2 - p0);
        let pvec = direction_local.cross(e2);
        let det = e1.dot(pvec);
        // A ray in the triangle's plane cannot cross it transversally.
        if det.abs() <= f64::EPSILON * e1.length() * e2.length() {
            continue;
        }
        let inv_det = 1.0 / det;
        let s = origin_local - p0;
        let u = s.dot(pvec) * inv_det;
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let qvec = s.cross(e1);
        let v = direction_local.dot(qvec) * inv_det;
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let t = e2.dot(qvec) * inv_det;
        if t >= 0.0 && t <= t_max {
            t_max = t;
            best = Some((t, e1.cross(e2).normalize()));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Sphere;

    #[test]
    fn sphere_head_on() {
        let shape = Shape::Sphere(Sphere::new(1.0).unwrap());
        let ray = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X, 100.0);
        let hit = ray_cast_shape(&shape, &Transform::IDENTITY, &ray).unwrap();
        assert!((hit.distance - 4.0).abs() < 1e-15);
        assert!((hit.normal + DVec3::X).length() < 1e-15);
        let short = Ray { max_distance: 3.9, ..ray };
        assert!(ray_cast_shape(&shape, &Transform::IDENTITY, &short).is_none());
    }

    #[test]
    fn origin_inside_hits_at_zero() {
        let shape = Shape::Sphere(Sphere::new(1.0).unwrap());
        let ray = Ray::new(DVec3::new(0.2, 0.0, 0.0), DVec3::Y, 10.0);
        let hit = ray_cast_shape(&shape, &Transform::IDENTITY, &ray).unwrap();
        assert_eq!(hit.distance, 0.0);
        assert_eq!(hit.point, ray.origin);
        assert_eq!(hit.normal, -DVec3::Y);
    }

    #[test]
    fn cuboid_face_normal() {
        let c = Cuboid::new(DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let hit = cuboid_local(DVec3::new(0.5, 10.0, 0.0), -DVec3::Y, &c).unwrap();
        assert_eq!(hit, (8.0, Some(DVec3::Y)));
        assert!(cuboid_local(DVec3::new(1.5, 10.0, 0.0), -DVec3::Y, &c).is_none());
    }

    #[test]
    fn cone_apex_and_base() {
        let c = Cone::new(1.0, 1.0).unwrap();
        // Straight down onto the apex.
        let (t, _) = cone_local(DVec3::new(0.0, 0.0, 5.0), -DVec3::Z, &c).unwrap();
        assert!((t - 4.0).abs() < 1e-12);
        // Straight up into the base.
        let (t, n) = cone_local(DVec3::new(0.5, 0.0, -5.0), DVec3::Z, &c).unwrap();
        assert!((t - 4.0).abs() < 1e-12 && n == Some(-DVec3::Z));
        // Horizontally through the mid height: radius there is 0.5.
        let (t, _) = cone_local(DVec3::new(-5.0, 0.0, 0.0), DVec3::X, &c).unwrap();
        assert!((t - 4.5).abs() < 1e-12);
    }
}
