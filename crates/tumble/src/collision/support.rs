//! Support functions: the point of a convex shape farthest along a direction.
//!
//! Every convex shape here is a *core* swept by a ball: `shape = core ⊕ ball(radius)`. A sphere is a
//! point core with its radius, a capsule a segment core with its radius, the polyhedral and curved
//! solids have radius 0. GJK runs on the cores and adds the radii afterwards, which keeps spheres and
//! capsules exact (their cores are a point and a segment, where GJK converges in one or two steps
//! instead of crawling over a curved surface) and lets rounded shapes touch without any penetration
//! solver.

use crate::math::{DVec3, Transform};
use crate::shape::{ConvexHull, Shape};

/// The inner convex set of a shape, in the shape's local frame.
#[derive(Clone, Copy, Debug)]
pub enum Core<'a> {
    /// The origin.
    Point,
    /// The segment from (0, 0, −half_height) to (0, 0, +half_height).
    Segment {
        half_height: f64,
    },
    Cuboid {
        half_extents: DVec3,
    },
    Cylinder {
        radius: f64,
        half_height: f64,
    },
    /// Base disc at z = −half_height, apex at z = +half_height.
    Cone {
        radius: f64,
        half_height: f64,
    },
    Hull(&'a ConvexHull),
    /// A triangle (corners counter-clockwise about its front normal): a flat core, for contacts
    /// against meshes and height fields.
    Triangle([DVec3; 3]),
}

/// A shape as core plus radius: the set of points within `radius` of the core.
#[derive(Clone, Copy, Debug)]
pub struct Rounded<'a> {
    pub core: Core<'a>,
    pub radius: f64,
}

impl<'a> Rounded<'a> {
    /// The core/radius split of a convex shape; `None` for meshes and compounds (not convex).
    pub fn of(shape: &'a Shape) -> Option<Rounded<'a>> {
        let (core, radius) = match shape {
            Shape::Sphere(s) => (Core::Point, s.radius),
            Shape::Capsule(c) => (Core::Segment { half_height: c.half_height }, c.radius),
            Shape::Cuboid(b) => (Core::Cuboid { half_extents: b.half_extents }, 0.0),
            Shape::Cylinder(c) => (Core::Cylinder { radius: c.radius, half_height: c.half_height }, 0.0),
            Shape::Cone(c) => (Core::Cone { radius: c.radius, half_height: c.half_height }, 0.0),
            Shape::ConvexHull(h) => (Core::Hull(h), 0.0),
            Shape::TriMesh(_) | Shape::Compound(_) | Shape::Plane(_) | Shape::HeightField(_) => return None,
        };
        Some(Rounded { core, radius })
    }

    /// Farthest point of the whole shape along `dir_local` (need not be unit length).
    pub fn support_local(&self, dir_local: DVec3) -> DVec3 {
        self.core.support_local(dir_local) + dir_local.normalize_or_zero() * self.radius
    }

    /// A length scale of the shape (radius of a ball about the origin that contains it).
    pub fn bounding_radius(&self) -> f64 {
        self.core.bounding_radius() + self.radius
    }
}

impl Core<'_> {
    /// Farthest point of the core along `dir_local` (need not be unit length). Ties resolve to a
    /// fixed choice, so repeated queries give the same point.
    pub fn support_local(&self, d: DVec3) -> DVec3 {
        match *self {
            Core::Point => DVec3::ZERO,
            Core::Segment { half_height } => DVec3::new(0.0, 0.0, sign(d.z) * half_height),
            Core::Cuboid { half_extents } => {
                DVec3::new(sign(d.x) * half_extents.x, sign(d.y) * half_extents.y, sign(d.z) * half_extents.z)
            }
            Core::Cylinder { radius, half_height } => {
                disc_support(d, radius) + DVec3::new(0.0, 0.0, sign(d.z) * half_height)
            }
            Core::Cone { radius, half_height } => {
                let apex = DVec3::new(0.0, 0.0, half_height);
                let rim = disc_support(d, radius) - DVec3::new(0.0, 0.0, half_height);
                if apex.dot(d) >= rim.dot(d) {
                    apex
                } else {
                    rim
                }
            }
            Core::Hull(h) => h.vertices()[h.support_index(d)],
            Core::Triangle(v) => {
                let (d0, d1, d2) = (v[0].dot(d), v[1].dot(d), v[2].dot(d));
                if d0 >= d1 && d0 >= d2 {
                    v[0]
                } else if d1 >= d2 {
                    v[1]
                } else {
                    v[2]
                }
            }
        }
    }

    /// Radius of a ball about the local origin containing the core.
    pub fn bounding_radius(&self) -> f64 {
        match *self {
            Core::Point => 0.0,
            Core::Segment { half_height } => half_height,
            Core::Cuboid { half_extents } => half_extents.length(),
            Core::Cylinder { radius, half_height } | Core::Cone { radius, half_height } => {
                radius.hypot(half_height)
            }
            Core::Hull(h) => h.bounding_radius(),
            Core::Triangle(v) => v.iter().fold(0.0_f64, |m, p| m.max(p.length())),
        }
    }

    /// True for the cores whose Minkowski differences with anything have volume (EPA needs it).
    pub fn is_solid(&self) -> bool {
        !matches!(self, Core::Point | Core::Segment { .. } | Core::Triangle(_))
    }
}

/// Farthest point of the shape along `dir_world` for a shape at `pose`; `None` if not convex.
pub fn support_world(shape: &Shape, pose: &Transform, dir_world: DVec3) -> Option<DVec3> {
    let rounded = Rounded::of(shape)?;
    let dir_local = pose.rotation.inverse() * dir_world;
    Some(pose.transform_point(rounded.support_local(dir_local)))
}

/// `+1` for non-negative values, `−1` otherwise: a sign with no zero, so supports never fall in
/// the middle of a face.
#[inline]
pub(crate) fn sign(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Support of the disc of `radius` in the local XY plane.
#[inline]
fn disc_support(d: DVec3, radius: f64) -> DVec3 {
    let len = d.x.hypot(d.y);
    if len > 0.0 {
        DVec3::new(d.x / len * radius, d.y / len * radius, 0.0)
    } else {
        DVec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{Cone, Cuboid, Cylinder};

    /// The support value must dominate every sampled surface point of the shape.
    fn dominates(shape: &Shape, samples: &[DVec3]) {
        let r = Rounded::of(shape).unwrap();
        for k in 0..200 {
            let t = k as f64 * 0.7;
            let d = DVec3::new(t.cos() * (0.3 * t).sin(), t.sin() * (0.3 * t).sin(), (0.3 * t).cos());
            let s = r.support_local(d).dot(d);
            for p in samples {
                assert!(p.dot(d) <= s + 1e-12, "{shape:?}: sample {p} beats support along {d}");
            }
        }
    }

    #[test]
    fn supports_dominate_samples() {
        let mut rim = Vec::new();
        for k in 0..64 {
            let a = k as f64 / 64.0 * std::f64::consts::TAU;
            rim.push(DVec3::new(0.5 * a.cos(), 0.5 * a.sin(), 0.0));
        }
        let cyl: Vec<DVec3> = rim.iter().flat_map(|&p| [p + DVec3::Z * 0.7, p - DVec3::Z * 0.7]).collect();
        dominates(&Shape::Cylinder(Cylinder::new(0.5, 0.7).unwrap()), &cyl);
        let mut cone: Vec<DVec3> = rim.iter().map(|&p| p - DVec3::Z * 0.7).collect();
        cone.push(DVec3::Z * 0.7);
        dominates(&Shape::Cone(Cone::new(0.5, 0.7).unwrap()), &cone);
        let he = DVec3::new(0.1, 0.2, 0.3);
        let corners: Vec<DVec3> = (0..8)
            .map(|i| {
                he * DVec3::new(
                    sign((i & 1) as f64 - 0.5),
                    sign((i & 2) as f64 - 1.0),
                    sign((i & 4) as f64 - 2.0),
                )
            })
            .collect();
        dominates(&Shape::Cuboid(Cuboid::new(he).unwrap()), &corners);
    }
}
