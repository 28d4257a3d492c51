//! World bounds of shapes: they contain sampled surface points under random poses and touch the
//! shape's extreme points (tight).

mod shape_strategies;

use proptest::prelude::*;
use shape_strategies::{box_mesh, convex_shape, pose, scale, size};
use tumble::collision::aabb::points_aabb;
use tumble::collision::{shape_aabb, Aabb};
use tumble::{Compound, CompoundChild, Cuboid, DVec3, Shape, Sphere, Transform};

/// Points on the surface of a primitive (local frame): a latitude–longitude net on curved parts,
/// a grid on flat parts, and the exact extreme points along the local axes.
fn surface_points_local(shape: &Shape) -> Vec<DVec3> {
    let tau = std::f64::consts::TAU;
    let ring = |r: f64, z: f64, n: usize| -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = tau * i as f64 / n as f64;
                DVec3::new(r * a.cos(), r * a.sin(), z)
            })
            .collect()
    };
    let mut pts = Vec::new();
    match shape {
        Shape::Sphere(s) => {
            for j in 0..=20 {
                let phi = std::f64::consts::PI * j as f64 / 20.0;
                pts.extend(ring(s.radius * phi.sin(), s.radius * phi.cos(), 40));
            }
        }
        Shape::Cuboid(c) => {
            for i in 0..=6 {
                for j in 0..=6 {
                    let (u, v) = (i as f64 / 3.0 - 1.0, j as f64 / 3.0 - 1.0);
                    let h = c.half_extents;
                    for s in [-1.0, 1.0] {
                        pts.push(DVec3::new(s * h.x, u * h.y, v * h.z));
                        pts.push(DVec3::new(u * h.x, s * h.y, v * h.z));
                        pts.push(DVec3::new(u * h.x, v * h.y, s * h.z));
                    }
                }
            }
        }
        Shape::Capsule(c) => {
            for j in 0..=20 {
                let phi = std::f64::consts::PI * j as f64 / 20.0;
                let z = c.radius * phi.cos();
                let z = if z >= 0.0 { z + c.half_height } else { z - c.half_height };
                pts.extend(ring(c.radius * phi.sin(), z, 40));
            }
        }
        Shape::Cylinder(c) => {
            for j in 0..=10 {
                let z = c.half_height * (j as f64 / 5.0 - 1.0);
                pts.extend(ring(c.radius, z, 60));
            }
            for j in 0..5 {
                pts.extend(ring(c.radius * j as f64 / 5.0, c.half_height, 30));
                pts.extend(ring(c.radius * j as f64 / 5.0, -c.half_height, 30));
            }
        }
        Shape::Cone(c) => {
            for j in 0..=10 {
                let f = j as f64 / 10.0;
                pts.extend(ring(c.radius * f, c.half_height - 2.0 * c.half_height * f, 60));
                pts.extend(ring(c.radius * f, -c.half_height, 30));
            }
        }
        _ => unimplemented!(),
    }
    pts
}

/// The exact point of a primitive furthest along world direction `dir_world`, by each shape's
/// support mapping (written from its definition, independently of `shape_aabb`).
fn support_world(shape: &Shape, pose: &Transform, dir_world: DVec3) -> DVec3 {
    let d = pose.rotation.inverse() * dir_world;
    // Furthest point of a disc of radius r in the plane z = const along d: r · d_xy / |d_xy|.
    let disc = |r: f64, z: f64| {
        let dxy = DVec3::new(d.x, d.y, 0.0);
        let l = dxy.length();
        if l > 0.0 {
            dxy * (r / l) + DVec3::new(0.0, 0.0, z)
        } else {
            DVec3::new(0.0, 0.0, z)
        }
    };
    let local = match shape {
        Shape::Sphere(s) => d * s.radius,
        Shape::Cuboid(c) => c.half_extents * DVec3::new(d.x.signum(), d.y.signum(), d.z.signum()),
        Shape::Capsule(c) => d * c.radius + DVec3::new(0.0, 0.0, c.half_height * d.z.signum()),
        Shape::Cylinder(c) => disc(c.radius, c.half_height * d.z.signum()),
        Shape::Cone(c) => {
            let apex = DVec3::new(0.0, 0.0, c.half_height);
            let rim = disc(c.radius, -c.half_height);
            if apex.dot(d) >= rim.dot(d) {
                apex
            } else {
                rim
            }
        }
        _ => unimplemented!(),
    };
    pose.transform_point(local)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn aabb_contains_surface_points(shape in convex_shape(), pose in pose()) {
        let aabb = shape_aabb(&shape, &pose);
        prop_assert!(aabb.is_valid());
        let grown = aabb.fattened(1e-9 * (1.0 + scale(&shape)));
        for p in surface_points_local(&shape) {
            let w = pose.transform_point(p);
            prop_assert!(grown.contains_point(w), "{w} outside {aabb:?}");
        }
    }

    #[test]
    fn aabb_touches_the_shape(shape in convex_shape(), pose in pose()) {
        let aabb = shape_aabb(&shape, &pose);
        let tol = 1e-9 * (1.0 + scale(&shape) + pose.translation.length());
        for i in 0..3 {
            let mut axis = DVec3::ZERO;
            axis[i] = 1.0;
            let hi = support_world(&shape, &pose, axis)[i];
            let lo = support_world(&shape, &pose, -axis)[i];
            prop_assert!((aabb.max[i] - hi).abs() <= tol, "axis {i}: max {} vs support {hi}", aabb.max[i]);
            prop_assert!((aabb.min[i] - lo).abs() <= tol, "axis {i}: min {} vs support {lo}", aabb.min[i]);
        }
    }

    #[test]
    fn compound_aabb_is_union_of_children(a in convex_shape(), b in convex_shape(), pa in pose(), pb in pose(), pose in pose()) {
        let compound = Shape::Compound(Compound::new(vec![
            CompoundChild { pose: pa, shape: a.clone() },
            CompoundChild { pose: pb, shape: b.clone() },
        ]).unwrap());
        let expected = shape_aabb(&a, &pose.mul_transform(&pa)).union(&shape_aabb(&b, &pose.mul_transform(&pb)));
        prop_assert_eq!(shape_aabb(&compound, &pose), expected);
    }

    #[test]
    fn mesh_points_aabb_is_tight(hx in size(), hy in size(), hz in size(), pose in pose()) {
        let h = DVec3::new(hx, hy, hz);
        let (vertices, _) = box_mesh(h);
        let from_mesh = points_aabb(&vertices, &pose);
        let from_box = shape_aabb(&Shape::Cuboid(Cuboid::new(h).unwrap()), &pose);
        prop_assert!((from_mesh.min - from_box.min).abs().max_element() < 1e-12);
        prop_assert!((from_mesh.max - from_box.max).abs().max_element() < 1e-12);
    }
}

#[test]
fn sphere_bounds_are_exact() {
    let pose = Transform::new(DVec3::new(1.0, -2.0, 3.0), tumble::DQuat::from_rotation_x(0.4));
    let aabb = shape_aabb(&Shape::Sphere(Sphere::new(0.5).unwrap()), &pose);
    assert_eq!(aabb, Aabb::new(DVec3::new(0.5, -2.5, 2.5), DVec3::new(1.5, -1.5, 3.5)));
}
