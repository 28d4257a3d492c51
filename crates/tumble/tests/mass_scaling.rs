//! Mass scaling: rigid bodies under gravity, contacts with Coulomb friction and restitution, and
//! joints move the same way whatever the unit of mass. Multiply every density by `s` and every
//! mass, inertia and impulse is `s` times larger while every velocity and position stays the
//! same: nothing in the equations compares a mass, a force or an impulse with a fixed amount.
//!
//! With `s` a power of two the scaling is exact in floating point too, so the two runs must agree
//! bit for bit: any tolerance, threshold or regularisation that is not relative to the quantity it
//! guards shows up as a difference. (The friction rows' tangent mass once was: it was inverted
//! with a threshold relative to a unit entry, and a body over about a thousand tonnes lost its
//! friction altogether.)

use tumble::{
    BallJoint, BodyDef, BodyKind, Capsule, DQuat, DVec3, HingeJoint, JointDef, JointKind, Limits, Material,
    Shape, World,
};

mod contact_support;
use contact_support::{cuboid, ground, material, sphere, world, DT};

/// A little of everything, every density times `scale`: a box sliding and spinning, a ball
/// rolling with rolling and torsional friction, a bouncing ball, a stack of three boxes with a
/// capsule dropped on it, a ball-jointed pendulum and a two-link arm on a hinge with limits.
fn scene(scale: f64) -> World {
    let mut world = world(Default::default());
    ground(&mut world, material(0.5, 0.0));
    let mut add = |shape: Option<Shape>, density: f64, position: DVec3, v: DVec3, w: DVec3, m: Material| {
        world
            .add_body(BodyDef {
                shape,
                density: density * scale,
                position,
                orientation: DQuat::from_rotation_z(0.1),
                linear_velocity: v,
                angular_velocity: w,
                material: m,
                ..Default::default()
            })
            .unwrap()
    };
    add(
        cuboid(DVec3::new(0.5, 0.3, 0.2)),
        800.0,
        DVec3::new(-4.0, 0.0, 0.2),
        DVec3::X * 3.0,
        DVec3::Z * 2.0,
        material(0.4, 0.0),
    );
    let rolling =
        Material { friction: 0.8, restitution: 0.0, rolling_friction: 0.01, torsional_friction: 0.02 };
    add(sphere(0.3), 1200.0, DVec3::new(0.0, -4.0, 0.3), DVec3::Y * 2.0, DVec3::Z * 3.0, rolling);
    add(sphere(0.2), 500.0, DVec3::new(3.0, 3.0, 1.5), DVec3::ZERO, DVec3::ZERO, material(0.3, 0.7));
    for level in 0..3 {
        let z = 0.25 + 0.5 * f64::from(level);
        add(
            cuboid(DVec3::splat(0.25)),
            1000.0 + 300.0 * f64::from(level),
            DVec3::new(4.0, -2.0, z),
            DVec3::ZERO,
            DVec3::ZERO,
            material(0.6, 0.0),
        );
    }
    let capsule = Some(Shape::Capsule(Capsule::new(0.1, 0.4).unwrap()));
    add(
        capsule,
        900.0,
        DVec3::new(4.1, -2.0, 2.2),
        DVec3::ZERO,
        DVec3::new(1.0, 0.5, 0.0),
        material(0.6, 0.2),
    );

    // A pendulum on a ball joint from a static post, and a two-link arm hinged with limits.
    let post = world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            position: DVec3::new(-3.0, 4.0, 3.0),
            ..Default::default()
        })
        .unwrap();
    let link = |world: &mut World, position: DVec3| {
        world
            .add_body(BodyDef {
                shape: cuboid(DVec3::new(0.3, 0.05, 0.05)),
                density: 700.0 * scale,
                position,
                ..Default::default()
            })
            .unwrap()
    };
    let bob = link(&mut world, DVec3::new(-2.7, 4.0, 3.0));
    let elbow = link(&mut world, DVec3::new(-2.1, 4.0, 3.0));
    let ball = JointKind::Ball(BallJoint::default());
    world.add_joint(JointDef::new(post, bob, DVec3::new(-3.0, 4.0, 3.0), ball)).unwrap();
    let hinge = HingeJoint { limits: Some(Limits::new(-0.6, 0.6)), ..Default::default() };
    let mut def = JointDef::new(bob, elbow, DVec3::new(-2.4, 4.0, 3.0), JointKind::Hinge(hinge));
    def.axis_world = DVec3::Y;
    world.add_joint(def).unwrap();
    world
}

/// Every body's pose and velocities, bit for bit.
fn state(world: &World) -> Vec<[u64; 13]> {
    world
        .bodies()
        .map(|(_, body)| {
            let (p, q) = (body.position(), body.orientation());
            let (v, w) = (body.linear_velocity(), body.angular_velocity());
            [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z].map(f64::to_bits)
        })
        .collect()
}

#[test]
fn a_scene_moves_the_same_whatever_the_unit_of_mass() {
    let scales = [1.0, 2f64.powi(-20), 2f64.powi(30)];
    let mut worlds: Vec<World> = scales.iter().map(|&s| scene(s)).collect();
    let mut moved = 0.0_f64;
    for step in 0..240 {
        for world in &mut worlds {
            world.step(DT).unwrap();
        }
        let reference = state(&worlds[0]);
        for (world, scale) in worlds.iter().zip(scales).skip(1) {
            assert!(
                state(world) == reference,
                "with every density times {scale:e} the scene moved differently by step {}",
                step + 1
            );
        }
        moved = moved.max(worlds[0].bodies().map(|(_, b)| b.linear_velocity().length()).fold(0.0, f64::max));
    }
    // The scene is not at rest: the comparison says something.
    assert!(moved > 1.0, "fastest speed {moved}");
}
