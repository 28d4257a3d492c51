//! Strategies and shape helpers shared by the collision integration tests.
#![allow(dead_code)]

use proptest::prelude::*;
use tumble::{Capsule, Cone, Cuboid, Cylinder, DQuat, DVec3, Shape, Sphere, Transform};

pub fn vec3(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A uniformly distributed rotation (Shoemake's method).
pub fn rotation() -> impl Strategy<Value = DQuat> {
    (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(u1, u2, u3)| {
        let tau = std::f64::consts::TAU;
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        DQuat::from_xyzw(
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        )
        .normalize()
    })
}

pub fn pose() -> impl Strategy<Value = Transform> {
    (vec3(5.0), rotation()).prop_map(|(t, r)| Transform::new(t, r))
}

pub fn size() -> impl Strategy<Value = f64> {
    0.1..3.0f64
}

/// One of the primitive convex shapes with random dimensions.
pub fn convex_shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        size().prop_map(|r| Shape::Sphere(Sphere::new(r).unwrap())),
        (size(), size(), size())
            .prop_map(|(x, y, z)| Shape::Cuboid(Cuboid::new(DVec3::new(x, y, z)).unwrap())),
        (size(), size()).prop_map(|(r, h)| Shape::Capsule(Capsule::new(r, h).unwrap())),
        (size(), size()).prop_map(|(r, h)| Shape::Cylinder(Cylinder::new(r, h).unwrap())),
        (size(), size()).prop_map(|(r, h)| Shape::Cone(Cone::new(r, h).unwrap())),
    ]
}

/// Membership of a local point in the shape with every defining inequality relaxed by `delta`
/// (negative `delta` shrinks). Written from the shape definitions, independently of the code
/// under test.
pub fn inside_local(shape: &Shape, p: DVec3, delta: f64) -> bool {
    let rho = (p.x * p.x + p.y * p.y).sqrt();
    match shape {
        Shape::Sphere(s) => p.length() <= s.radius + delta,
        Shape::Cuboid(c) => (p.abs() - c.half_extents).max_element() <= delta,
        Shape::Capsule(c) => {
            let axis = DVec3::new(0.0, 0.0, p.z.clamp(-c.half_height, c.half_height));
            (p - axis).length() <= c.radius + delta
        }
        Shape::Cylinder(c) => rho <= c.radius + delta && p.z.abs() <= c.half_height + delta,
        Shape::Cone(c) => {
            let k = c.radius / (2.0 * c.half_height);
            // The lateral surface offset by delta along its normal widens the radius by δ·√(1+k²).
            p.z.abs() <= c.half_height + delta
                && rho <= k * (c.half_height - p.z) + delta * (1.0 + k * k).sqrt()
        }
        _ => unimplemented!("inside_local is for convex primitives"),
    }
}

/// A characteristic size of a shape, to scale tolerances.
pub fn scale(shape: &Shape) -> f64 {
    match shape {
        Shape::Sphere(s) => s.radius,
        Shape::Cuboid(c) => c.half_extents.max_element(),
        Shape::Capsule(c) => c.radius + c.half_height,
        Shape::Cylinder(c) => c.radius.max(c.half_height),
        Shape::Cone(c) => c.radius.max(c.half_height),
        _ => 1.0,
    }
}

/// The 12 outward-wound triangles of a box with the given half extents.
pub fn box_mesh(h: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let vertices: Vec<DVec3> = (0..8)
        .map(|i| {
            let s = |bit: u32| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            DVec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
        })
        .collect();
    // Vertex i has x from bit 0, y from bit 1, z from bit 2. Faces wound counter-clockwise seen
    // from outside.
    #[rustfmt::skip]
    let triangles = vec![
        [0, 2, 3], [0, 3, 1], // −z
        [4, 5, 7], [4, 7, 6], // +z
        [0, 1, 5], [0, 5, 4], // −y
        [2, 6, 7], [2, 7, 3], // +y
        [0, 4, 6], [0, 6, 2], // −x
        [1, 3, 7], [1, 7, 5], // +x
    ];
    (vertices, triangles)
}
