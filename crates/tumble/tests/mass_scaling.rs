//! Mass scaling: rigid bodies under gravity, contacts with Coulomb friction and restitution, and
//! joints move the same way whatever the unit of mass. Multiply every density by `s` and every
//! mass, inertia and impulse is `s` times larger while every velocity and position stays the
//! same: nothing in the equations compares a mass, a force or an impulse with a fixed amount.
//!
//! With `s` a power of two the scaling is exact in floating point too, so the runs must agree
//! bit for bit: any tolerance, threshold or regularisation that is not relative to the quantity it
//! guards shows up as a difference. (The friction rows' tangent mass once was: it was inverted
//! with a threshold relative to a unit entry, and a body over about a thousand tonnes lost its
//! friction altogether.)

use tumble::{
    BallJoint, BodyDef, BodyId, BodyKind, Capsule, ConvexHull, DQuat, DVec3, FixedJoint, HingeJoint,
    JointDef, JointKind, Limits, Material, Shape, SliderJoint, SpringSettings, World,
};

mod contact_support;
use contact_support::{cuboid, ground, material, sphere, world, DT};

/// A free body of the scene: shape, density (before scaling), position, velocity, angular
/// velocity, material.
type Spec = (Option<Shape>, f64, DVec3, DVec3, DVec3, Material);

/// A little of everything, every density times `scale`: a box sliding and spinning, a ball
/// rolling with rolling and torsional friction, a bouncing ball, a stack of three boxes with a
/// capsule dropped on it, a tumbling convex hull, a ball-jointed pendulum with a second link on a
/// hinge with limits, and a sprung slider carrying a welded link.
fn scene(scale: f64) -> World {
    let mut world = world(Default::default());
    ground(&mut world, material(0.5, 0.0));
    let rolling =
        Material { friction: 0.8, restitution: 0.0, rolling_friction: 0.01, torsional_friction: 0.02 };
    let corners =
        [(0.4, 0.0, 0.0), (-0.3, 0.3, 0.0), (-0.2, -0.35, 0.1), (0.0, 0.1, 0.45), (0.1, -0.1, -0.3)];
    let corners: Vec<DVec3> = corners.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
    let (zero, v) = (DVec3::ZERO, DVec3::new);
    let mut specs: Vec<Spec> = vec![
        (
            cuboid(v(0.5, 0.3, 0.2)),
            800.0,
            v(-4.0, 0.0, 0.2),
            v(3.0, 0.0, 0.0),
            v(0.0, 0.0, 2.0),
            material(0.4, 0.0),
        ),
        (sphere(0.3), 1200.0, v(0.0, -4.0, 0.3), v(0.0, 2.0, 0.0), v(0.0, 0.0, 3.0), rolling),
        (sphere(0.2), 500.0, v(3.0, 3.0, 1.5), zero, zero, material(0.3, 0.7)),
        (
            Some(Shape::Capsule(Capsule::new(0.1, 0.4).unwrap())),
            900.0,
            v(4.1, -2.0, 2.2),
            zero,
            v(1.0, 0.5, 0.0),
            material(0.6, 0.2),
        ),
        (
            Some(Shape::ConvexHull(ConvexHull::new(&corners).unwrap())),
            1100.0,
            v(0.0, 2.0, 1.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 3.0, 1.0),
            material(0.5, 0.1),
        ),
    ];
    for level in 0..3 {
        let (density, z) = (1000.0 + 300.0 * f64::from(level), 0.25 + 0.5 * f64::from(level));
        specs.push((cuboid(DVec3::splat(0.25)), density, v(4.0, -2.0, z), zero, zero, material(0.6, 0.0)));
    }
    for (shape, density, position, linear_velocity, angular_velocity, material) in specs {
        world
            .add_body(BodyDef {
                shape,
                density: density * scale,
                position,
                orientation: DQuat::from_rotation_z(0.1),
                linear_velocity,
                angular_velocity,
                material,
                ..Default::default()
            })
            .unwrap();
    }

    // A pendulum on a ball joint from a static post, with a second link hinged to it (limits).
    let post = |world: &mut World, position: DVec3| -> BodyId {
        world.add_body(BodyDef { kind: BodyKind::Static, position, ..Default::default() }).unwrap()
    };
    let link = |world: &mut World, position: DVec3| -> BodyId {
        let shape = cuboid(DVec3::new(0.3, 0.05, 0.05));
        world.add_body(BodyDef { shape, density: 700.0 * scale, position, ..Default::default() }).unwrap()
    };
    let pivot = post(&mut world, v(-3.0, 4.0, 3.0));
    let bob = link(&mut world, v(-2.7, 4.0, 3.0));
    let elbow = link(&mut world, v(-2.1, 4.0, 3.0));
    let ball = JointKind::Ball(BallJoint::default());
    world.add_joint(JointDef::new(pivot, bob, v(-3.0, 4.0, 3.0), ball)).unwrap();
    let hinge = HingeJoint { limits: Some(Limits::new(-0.6, 0.6)), ..Default::default() };
    let def = JointDef::new(bob, elbow, v(-2.4, 4.0, 3.0), JointKind::Hinge(hinge));
    world.add_joint(def.with_axis(DVec3::Y)).unwrap();

    // A carriage on a sprung slider down a slope from a rail, with a link welded to it.
    let rail = post(&mut world, v(3.0, 5.0, 2.0));
    let carriage = link(&mut world, v(3.0, 5.0, 2.0));
    let rider = link(&mut world, v(3.6, 5.0, 2.0));
    let spring = SpringSettings { hertz: 2.0, damping_ratio: 0.2 };
    let slider = SliderJoint { spring: Some(spring), spring_target_position: 0.3, ..Default::default() };
    let def = JointDef::new(rail, carriage, v(3.0, 5.0, 2.0), JointKind::Slider(slider));
    world.add_joint(def.with_axis(v(0.0, 0.6, -0.8))).unwrap();
    let weld = JointKind::Fixed(FixedJoint::default());
    world.add_joint(JointDef::new(carriage, rider, v(3.3, 5.0, 2.0), weld)).unwrap();
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
    let mut fastest = 0.0_f64;
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
        let speeds = worlds[0].bodies().map(|(_, body)| body.linear_velocity().length());
        fastest = fastest.max(speeds.fold(0.0, f64::max));
    }
    // The scene is not at rest (and has not blown up): the comparison says something.
    assert!(fastest > 1.0 && fastest < 20.0, "fastest speed {fastest}");
}
