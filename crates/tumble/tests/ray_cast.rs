//! Ray casts against shapes: analytic answers for spheres and rotated boxes, surface and
//! emptiness checks for every convex primitive, meshes against boxes, compounds.

mod shape_strategies;

use proptest::prelude::*;
use shape_strategies::{box_mesh, convex_shape, inside_local, pose, rotation, scale, size, vec3};
use tumble::collision::ray::ray_cast_mesh_local;
use tumble::collision::{ray_cast_shape, Ray};
use tumble::{Compound, CompoundChild, Cuboid, DMat3, DVec3, Shape, Sphere, Transform};

/// A ray from `origin` aimed at `center + aim` (so that about half the rays hit).
fn aimed_ray(origin: DVec3, center: DVec3, aim: DVec3) -> Ray {
    Ray::new(origin, center + aim - origin, 100.0)
}

/// The textbook sphere hit: the smaller root of t² + 2bt + c = 0. `None` also for grazing rays
/// (closest approach within 1% of the radius), where the hit distance is ill-conditioned.
fn analytic_sphere(center: DVec3, r: f64, ray: &Ray) -> Option<Option<f64>> {
    let oc = ray.origin - center;
    let b = oc.dot(ray.direction);
    let c = oc.length_squared() - r * r;
    let closest = (oc - b * ray.direction).length();
    if (closest - r).abs() < 0.01 * r {
        return None; // ambiguous: skip
    }
    let disc = b * b - c;
    if disc < 0.0 {
        return Some(None);
    }
    let t = -b - disc.sqrt();
    Some((t >= 0.0 && t <= ray.max_distance).then_some(t))
}

/// The box hit as the nearest front-facing face whose rectangle contains the plane hit, all in
/// world coordinates.
fn analytic_box(h: DVec3, pose: &Transform, ray: &Ray) -> Option<(f64, DVec3)> {
    let axes = DMat3::from_quat(pose.rotation);
    let mut best: Option<(f64, DVec3)> = None;
    for i in 0..3 {
        for s in [-1.0, 1.0] {
            let n = s * axes.col(i);
            let denom = n.dot(ray.direction);
            if denom >= 0.0 {
                continue;
            }
            let face_center = pose.translation + h[i] * n;
            let t = n.dot(face_center - ray.origin) / denom;
            let p = ray.at(t) - pose.translation;
            let on_face =
                (0..3).filter(|&j| j != i).all(|j| p.dot(axes.col(j)).abs() <= h[j] * (1.0 + 1e-12));
            if on_face
                && t >= 0.0
                && t <= ray.max_distance
                && match best {
                    None => true,
                    Some((bt, _)) => t < bt,
                }
            {
                best = Some((t, n));
            }
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn sphere_matches_analytic(r in size(), center in vec3(5.0), origin in vec3(12.0), aim in vec3(3.0)) {
        prop_assume!((origin - center).length() > r * 1.001);
        let shape = Shape::Sphere(Sphere::new(r).unwrap());
        let pose = Transform::new(center, tumble::DQuat::IDENTITY);
        let ray = aimed_ray(origin, center, aim);
        let Some(expected) = analytic_sphere(center, r, &ray) else { return Ok(()) };
        let hit = ray_cast_shape(&shape, &pose, &ray);
        match (expected, hit) {
            (None, None) => {}
            (Some(t), Some(hit)) => {
                prop_assert!((hit.distance - t).abs() <= 1e-9 * (1.0 + t), "{} vs {t}", hit.distance);
                let normal = (hit.point - center) / r;
                prop_assert!((hit.normal - normal).length() <= 1e-9);
            }
            (e, h) => prop_assert!(false, "analytic {e:?}, cast {h:?}"),
        }
    }

    #[test]
    fn rotated_box_matches_analytic(
        hx in size(), hy in size(), hz in size(), pose in pose(), origin in vec3(12.0), aim in vec3(3.0)
    ) {
        let h = DVec3::new(hx, hy, hz);
        let shape = Shape::Cuboid(Cuboid::new(h).unwrap());
        prop_assume!(!inside_local(&shape, pose.inverse_transform_point(origin), 1e-6));
        let ray = aimed_ray(origin, pose.translation, aim);
        match (analytic_box(h, &pose, &ray), ray_cast_shape(&shape, &pose, &ray)) {
            (None, None) => {}
            (Some((t, n)), Some(hit)) => {
                prop_assert!((hit.distance - t).abs() <= 1e-9 * (1.0 + t), "{} vs {t}", hit.distance);
                prop_assert!((hit.point - ray.at(t)).length() <= 1e-9 * (1.0 + t));
                prop_assert!((hit.normal - n).length() <= 1e-9, "{} vs {n}", hit.normal);
            }
            (e, h) => prop_assert!(false, "analytic {e:?}, cast {h:?}"),
        }
    }

    /// For every convex primitive: a hit lies on the surface, the ray before it is outside, the
    /// normal points out; a miss never passes through the inside.
    #[test]
    fn convex_hits_are_first_surface_crossings(
        shape in convex_shape(), pose in pose(), origin in vec3(12.0), aim in vec3(3.0)
    ) {
        let s = scale(&shape);
        let origin_local = pose.inverse_transform_point(origin);
        prop_assume!(!inside_local(&shape, origin_local, 1e-6 * s));
        let ray = aimed_ray(origin, pose.translation, aim);
        let local = |p: DVec3| pose.inverse_transform_point(p);
        let tol = 1e-9 * (1.0 + s);
        match ray_cast_shape(&shape, &pose, &ray) {
            Some(hit) => {
                let p = local(hit.point);
                prop_assert!(inside_local(&shape, p, tol) && !inside_local(&shape, p, -tol), "not on surface: {p}");
                prop_assert!((hit.normal.length() - 1.0).abs() < 1e-12);
                prop_assert!(hit.normal.dot(ray.direction) <= 1e-12, "normal must face the ray");
                let eps = 1e-6 * s;
                prop_assert!(!inside_local(&shape, local(hit.point + eps * hit.normal), 0.0), "normal points in");
                for j in 0..200 {
                    let t = (hit.distance - 1e-6 * s).max(0.0) * j as f64 / 200.0;
                    prop_assert!(!inside_local(&shape, local(ray.at(t)), -tol), "inside before hit at {t}");
                }
            }
            None => {
                for j in 0..=2000 {
                    let t = ray.max_distance * j as f64 / 2000.0;
                    prop_assert!(!inside_local(&shape, local(ray.at(t)), -tol), "missed ray is inside at {t}");
                }
            }
        }
    }

    #[test]
    fn origin_inside_hits_at_zero_against_direction(
        shape in convex_shape(), pose in pose(), u in vec3(1.0), dir in vec3(1.0)
    ) {
        prop_assume!(dir.length() > 1e-3);
        // Shrink a random point of the local bounding box until it is inside.
        let mut p = u * scale(&shape);
        while !inside_local(&shape, p, 0.0) {
            p *= 0.5;
        }
        let ray = Ray::new(pose.transform_point(p), dir, 10.0);
        let hit = ray_cast_shape(&shape, &pose, &ray).expect("inside must hit");
        prop_assert_eq!(hit.distance, 0.0);
        prop_assert_eq!(hit.point, ray.origin);
        prop_assert_eq!(hit.normal, -ray.direction);
    }

    #[test]
    fn box_mesh_matches_cuboid(
        hx in size(), hy in size(), hz in size(), rot in rotation(), origin in vec3(12.0), aim in vec3(3.0)
    ) {
        let h = DVec3::new(hx, hy, hz);
        let shape = Shape::Cuboid(Cuboid::new(h).unwrap());
        let pose = Transform::new(DVec3::ZERO, rot);
        prop_assume!(!inside_local(&shape, pose.inverse_transform_point(origin), 1e-6));
        let ray = aimed_ray(origin, DVec3::ZERO, aim);
        let (vertices, triangles) = box_mesh(h);
        let o_local = pose.inverse_transform_point(ray.origin);
        let d_local = rot.inverse() * ray.direction;
        let mesh = ray_cast_mesh_local(&vertices, &triangles, o_local, d_local, ray.max_distance);
        match (ray_cast_shape(&shape, &pose, &ray), mesh) {
            (None, None) => {}
            (Some(hit), Some((t, n_local))) => {
                prop_assert!((hit.distance - t).abs() <= 1e-9 * (1.0 + t));
                prop_assert!((hit.normal - rot * n_local).length() <= 1e-9);
            }
            // A ray through an edge may slip between two triangles or hit a face edge-on.
            (a, b) => prop_assert!(false, "box {a:?}, mesh {b:?}"),
        }
    }

    #[test]
    fn compound_reports_closest_child(origin in vec3(12.0), aim in vec3(3.0), pose in pose()) {
        let child = |x: f64, shape: Shape| CompoundChild { pose: Transform::new(DVec3::new(x, 0.0, 0.0), tumble::DQuat::IDENTITY), shape };
        let a = Shape::Sphere(Sphere::new(1.0).unwrap());
        let b = Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 1.0, 1.5)).unwrap());
        let compound = Shape::Compound(Compound::new(vec![child(-2.0, a.clone()), child(2.0, b.clone())]).unwrap());
        let ray = aimed_ray(origin, pose.translation, aim);
        let hits = [(a, -2.0), (b, 2.0)].map(|(s, x)| {
            ray_cast_shape(&s, &pose.mul_transform(&Transform::new(DVec3::new(x, 0.0, 0.0), tumble::DQuat::IDENTITY)), &ray)
        });
        let expected = hits.iter().flatten().map(|h| h.distance).fold(f64::INFINITY, f64::min);
        let got = ray_cast_shape(&compound, &pose, &ray).map_or(f64::INFINITY, |h| h.distance);
        prop_assert_eq!(got, expected);
    }
}

#[test]
fn cylinder_and_capsule_axis_cases() {
    use tumble::{Capsule, Cylinder};
    let cyl = Shape::Cylinder(Cylinder::new(1.0, 2.0).unwrap());
    let cap = Shape::Capsule(Capsule::new(1.0, 2.0).unwrap());
    let id = Transform::IDENTITY;
    let down = Ray::new(DVec3::new(0.5, 0.0, 10.0), -DVec3::Z, 100.0);
    let side = Ray::new(DVec3::new(-10.0, 0.0, 1.5), DVec3::X, 100.0);
    let hit = ray_cast_shape(&cyl, &id, &down).unwrap();
    assert!((hit.distance - 8.0).abs() < 1e-12 && hit.normal == DVec3::Z);
    let hit = ray_cast_shape(&cyl, &id, &side).unwrap();
    assert!((hit.distance - 9.0).abs() < 1e-12 && hit.normal == -DVec3::X);
    // The capsule's top is the ball at z = 2: at x = 0.5 its surface is at z = 2 + √0.75.
    let hit = ray_cast_shape(&cap, &id, &down).unwrap();
    assert!((hit.distance - (8.0 - 0.75f64.sqrt())).abs() < 1e-12);
    let hit = ray_cast_shape(&cap, &id, &side).unwrap();
    assert!((hit.distance - 9.0).abs() < 1e-12);
    // Parallel to the axis just outside the radius: a miss.
    let graze = Ray::new(DVec3::new(1.0 + 1e-9, 0.0, 10.0), -DVec3::Z, 100.0);
    assert!(ray_cast_shape(&cyl, &id, &graze).is_none());
}

#[test]
fn trimesh_shape_matches_cuboid() {
    let h = DVec3::new(1.0, 2.0, 0.5);
    let (vertices, triangles) = box_mesh(h);
    let mesh = Shape::TriMesh(tumble::TriMesh::new(vertices, triangles).unwrap());
    let cuboid = Shape::Cuboid(Cuboid::new(h).unwrap());
    let pose = Transform::new(DVec3::new(1.0, 2.0, 3.0), tumble::DQuat::from_rotation_z(0.3));
    let ray = Ray::new(DVec3::new(-5.0, 2.5, 3.1), DVec3::new(1.0, -0.1, 0.05), 100.0);
    let (a, b) = (ray_cast_shape(&mesh, &pose, &ray).unwrap(), ray_cast_shape(&cuboid, &pose, &ray).unwrap());
    assert!((a.distance - b.distance).abs() < 1e-12 && (a.normal - b.normal).length() < 1e-12);
}
