//! Axis-aligned bounding boxes and the tight world bounds of every shape.
//!
//! The broad phase only ever looks at boxes, so `shape_aabb` must never under-estimate a shape (a
//! missed pair is a missed contact) and should not over-estimate much (every extra pair costs a
//! narrow-phase test). The bounds below are exact for every primitive under any rotation.

use crate::math::{DMat3, DVec3, Transform};
use crate::shape::Shape;

/// An axis-aligned box `[min, max]`. Boxes are closed: touching boxes overlap.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: the identity of `union` (min = +∞, max = −∞), contained in nothing useful.
    pub const EMPTY: Self = Self { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };

    pub fn new(min: DVec3, max: DVec3) -> Self {
        debug_assert!(min.cmple(max).all(), "Aabb::new: min {min} > max {max}");
        Self { min, max }
    }

    pub fn from_center_half_extents(center: DVec3, half_extents: DVec3) -> Self {
        Self { min: center - half_extents, max: center + half_extents }
    }

    /// The smallest box holding every point (`EMPTY` for no points).
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, |b, p| Self { min: b.min.min(p), max: b.max.max(p) })
    }

    /// True when `min <= max` on every axis and all bounds are finite.
    pub fn is_valid(&self) -> bool {
        self.min.cmple(self.max).all() && self.min.is_finite() && self.max.is_finite()
    }

    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    pub fn half_extents(&self) -> DVec3 {
        0.5 * (self.max - self.min)
    }

    /// The smallest box holding both.
    #[inline]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// True when `other` lies entirely inside `self` (boundaries included).
    #[inline]
    pub fn contains(&self, other: &Aabb) -> bool {
        self.min.cmple(other.min).all() && other.max.cmple(self.max).all()
    }

    #[inline]
    pub fn contains_point(&self, p: DVec3) -> bool {
        self.min.cmple(p).all() && p.cmple(self.max).all()
    }

    /// True when the closed boxes share at least one point.
    #[inline]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }

    /// The widest gap between the boxes along a world axis: positive when they are apart (then
    /// every point of one is at least that far from every point of the other), else the least
    /// overlap negated.
    #[inline]
    pub fn gap(&self, other: &Aabb) -> f64 {
        (other.min - self.max).max(self.min - other.max).max_element()
    }

    /// Surface area `2(xy + yz + zx)`: the cost measure of the surface-area heuristic, because the
    /// chance that a random ray or small box hits a convex volume is proportional to its area.
    #[inline]
    pub fn surface_area(&self) -> f64 {
        let e = self.max - self.min;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The eight corners.
    pub fn corners(&self) -> [DVec3; 8] {
        std::array::from_fn(|i| {
            DVec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// The box grown by `margin` on every side.
    #[inline]
    pub fn fattened(&self, margin: f64) -> Aabb {
        let m = DVec3::splat(margin);
        Aabb { min: self.min - m, max: self.max + m }
    }

    /// The box swept by `displacement`: grown on the side each component points to, so a body
    /// expected to move by `displacement` stays inside it.
    #[inline]
    pub fn swept(&self, displacement: DVec3) -> Aabb {
        Aabb { min: self.min + displacement.min(DVec3::ZERO), max: self.max + displacement.max(DVec3::ZERO) }
    }

    /// Slab test: the parameter interval `[t_enter, t_exit]` within `[0, max_t]` on which
    /// `origin + t·direction` lies inside the box, or `None` when it never does.
    ///
    /// `direction` need not be unit length. A zero component is handled explicitly instead of by
    /// `±∞` arithmetic, because `0·∞` would give NaN for an origin exactly on a slab plane.
    pub fn ray_interval(&self, origin: DVec3, direction: DVec3, max_t: f64) -> Option<(f64, f64)> {
        let mut t_enter = 0.0_f64;
        let mut t_exit = max_t;
        for i in 0..3 {
            let (o, d) = (origin[i], direction[i]);
            if d == 0.0 {
                if o < self.min[i] || o > self.max[i] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / d;
            let (mut t0, mut t1) = ((self.min[i] - o) * inv, (self.max[i] - o) * inv);
            if t0 > t1 {
                std::mem::swap(&mut t0, &mut t1);
            }
            t_enter = t_enter.max(t0);
            t_exit = t_exit.min(t1);
            if t_enter > t_exit {
                return None;
            }
        }
        Some((t_enter, t_exit))
    }
}

/// The half extent along each world axis of a disc of `radius` whose unit normal is `axis_world`.
///
/// A disc of radius r with unit normal n reaches `r·sqrt(1 − n_i²)` along world axis i: the
/// extreme of `r·(cos θ u + sin θ v)_i` is `r·sqrt(u_i² + v_i²)`, and `u_i² + v_i² + n_i² = 1`.
fn disc_extent(axis_world: DVec3, radius: f64) -> DVec3 {
    // max(0, ·) guards against n_i² exceeding 1 by round-off.
    let e = |n: f64| radius * (1.0 - n * n).max(0.0).sqrt();
    DVec3::new(e(axis_world.x), e(axis_world.y), e(axis_world.z))
}

/// The tight world-space bounds of `shape` placed at `pose`.
pub fn shape_aabb(shape: &Shape, pose: &Transform) -> Aabb {
    let center = pose.translation;
    // The local Z axis in world coordinates: capsules, cylinders and cones lie along it.
    let axis_world = || pose.transform_vector(DVec3::Z);
    match shape {
        Shape::Sphere(s) => Aabb::from_center_half_extents(center, DVec3::splat(s.radius)),
        Shape::Cuboid(c) => {
            // |R|·h is the half extent of a rotated box (the support in each world axis).
            let r = DMat3::from_quat(pose.rotation);
            let abs_r = DMat3::from_cols(r.x_axis.abs(), r.y_axis.abs(), r.z_axis.abs());
            Aabb::from_center_half_extents(center, abs_r * c.half_extents)
        }
        Shape::Capsule(c) => {
            let half = axis_world().abs() * c.half_height + DVec3::splat(c.radius);
            Aabb::from_center_half_extents(center, half)
        }
        Shape::Cylinder(c) => {
            let a = axis_world();
            let half = a.abs() * c.half_height + disc_extent(a, c.radius);
            Aabb::from_center_half_extents(center, half)
        }
        Shape::Cone(c) => {
            // The cone is the hull of its apex and its base disc.
            let a = axis_world();
            let apex = center + a * c.half_height;
            let base = center - a * c.half_height;
            let disc = disc_extent(a, c.radius);
            Aabb { min: apex.min(base - disc), max: apex.max(base + disc) }
        }
        Shape::TriMesh(m) => points_aabb(m.vertices(), pose),
        Shape::ConvexHull(h) => points_aabb(h.vertices(), pose),
        Shape::Compound(c) => c.children().iter().fold(Aabb::EMPTY, |b, child| {
            b.union(&shape_aabb(&child.shape, &pose.mul_transform(&child.pose)))
        }),
        Shape::Plane(p) => plane_aabb(p, pose),
        Shape::HeightField(h) => {
            let (lo, hi) = h.local_bounds();
            points_aabb(&Aabb::new(lo, hi).corners(), pose)
        }
    }
}

/// A half-space's bounds within the cube of half size `PLANE_EXTENT` about the world origin: the
/// whole cube, except that an axis-aligned plane bounds its own axis at its surface.
fn plane_aabb(plane: &crate::shape::Plane, pose: &Transform) -> Aabb {
    use crate::shape::PLANE_EXTENT;
    let n = pose.rotation * plane.normal;
    let offset = plane.offset + n.dot(pose.translation);
    let mut b = Aabb::from_center_half_extents(DVec3::ZERO, DVec3::splat(PLANE_EXTENT));
    for k in 0..3 {
        if n[k].abs() >= 1.0 - 1e-12 {
            let surface = (offset / n[k]).clamp(-PLANE_EXTENT, PLANE_EXTENT);
            if n[k] > 0.0 {
                b.max[k] = surface;
            } else {
                b.min[k] = surface;
            }
        }
    }
    b
}

/// The world bounds of points given in a local frame placed at `pose` (e.g. mesh vertices).
pub fn points_aabb(points_local: &[DVec3], pose: &Transform) -> Aabb {
    Aabb::from_points(points_local.iter().map(|&p| pose.transform_point(p)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;
    use crate::shape::{Cone, Cylinder, Sphere};

    #[test]
    fn union_overlap_contains() {
        let a = Aabb::new(DVec3::ZERO, DVec3::ONE);
        let b = Aabb::new(DVec3::splat(1.0), DVec3::splat(2.0));
        let c = Aabb::new(DVec3::splat(1.5), DVec3::splat(3.0));
        assert!(a.overlaps(&b), "touching boxes overlap");
        assert!(!a.overlaps(&c));
        let u = a.union(&c);
        assert!(u.contains(&a) && u.contains(&c) && !a.contains(&u));
        assert_eq!(Aabb::EMPTY.union(&a), a);
        assert_eq!(a.surface_area(), 6.0);
        assert_eq!(a.fattened(0.5).surface_area(), 24.0);
    }

    #[test]
    fn swept_grows_towards_motion() {
        let a = Aabb::new(DVec3::ZERO, DVec3::ONE);
        let s = a.swept(DVec3::new(2.0, -1.0, 0.0));
        assert_eq!(s, Aabb::new(DVec3::new(0.0, -1.0, 0.0), DVec3::new(3.0, 1.0, 1.0)));
    }

    #[test]
    fn ray_interval_handles_axis_parallel_rays() {
        let a = Aabb::new(DVec3::ZERO, DVec3::ONE);
        // Origin on the x = 0 plane, moving along +y: inside the x slab.
        assert_eq!(a.ray_interval(DVec3::new(0.0, -1.0, 0.5), DVec3::Y, 10.0), Some((1.0, 2.0)));
        assert_eq!(a.ray_interval(DVec3::new(-0.1, -1.0, 0.5), DVec3::Y, 10.0), None);
        assert_eq!(a.ray_interval(DVec3::new(0.5, -1.0, 0.5), DVec3::Y, 0.5), None);
        assert_eq!(a.ray_interval(DVec3::splat(0.5), DVec3::X, 10.0), Some((0.0, 0.5)));
    }

    #[test]
    fn upright_cylinder_and_cone_bounds() {
        let cyl = Shape::Cylinder(Cylinder::new(0.5, 2.0).unwrap());
        let b = shape_aabb(&cyl, &Transform::IDENTITY);
        assert!((b.max - DVec3::new(0.5, 0.5, 2.0)).abs().max_element() < 1e-15);
        // Lying along X: extent 2 in x, 0.5 in y and z.
        let pose = Transform::new(DVec3::ZERO, DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2));
        let b = shape_aabb(&cyl, &pose);
        assert!((b.max - DVec3::new(2.0, 0.5, 0.5)).abs().max_element() < 1e-12);
        let cone = Shape::Cone(Cone::new(1.0, 1.0).unwrap());
        let b = shape_aabb(&cone, &Transform::IDENTITY);
        assert_eq!(b, Aabb::new(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0)));
        let s = shape_aabb(&Shape::Sphere(Sphere::new(2.0).unwrap()), &Transform::IDENTITY);
        assert_eq!(s.max, DVec3::splat(2.0));
    }
}
