//! Joints through the public API: constraint force and breaking, and bad input (clear errors
//! that name the joint and the setting, and leave the world unchanged).

use tumble::{
    BallJoint, BodyDef, BodyId, BodyKind, Cuboid, DVec3, DistanceJoint, FixedJoint, HingeJoint, JointDef,
    JointKind, Limits, Motor, Shape, SliderJoint, Sphere, SpringSettings, World, WorldError,
};

const G: f64 = 9.81;

fn static_body(world: &mut World, position: DVec3) -> BodyId {
    world
        .add_body(BodyDef { name: "ground".into(), kind: BodyKind::Static, position, ..Default::default() })
        .unwrap()
}

fn dynamic_body(world: &mut World, name: &str, shape: Shape, position: DVec3) -> BodyId {
    world.add_body(BodyDef { name: name.into(), shape: Some(shape), position, ..Default::default() }).unwrap()
}

fn cube(half: f64) -> Shape {
    Shape::Cuboid(Cuboid::new(DVec3::splat(half)).unwrap())
}

// ---- breaking ---------------------------------------------------------------------------------

/// The constraint force of a joint holding a weight is its weight (impulse per substep / h), and
/// the joint breaks when that exceeds `break_force`.
#[test]
fn joint_force_and_breaking() {
    let mut world = World::default();
    let pivot = DVec3::new(0.0, 0.0, 2.0);
    let ground = static_body(&mut world, pivot);
    let make = |world: &mut World, x: f64, break_force: f64| {
        let bob = dynamic_body(
            world,
            "bob",
            Shape::Sphere(Sphere::new(0.1).unwrap()),
            pivot + DVec3::new(x, 0.0, -1.0),
        );
        let anchor = pivot + DVec3::X * x;
        let def = JointDef {
            break_force: Some(break_force),
            ..JointDef::new(ground, bob, anchor, JointKind::Fixed(FixedJoint::new()))
        };
        (bob, world.add_joint(def).unwrap())
    };
    let weight = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.001 * G;
    let (_, strong) = make(&mut world, 0.0, 2.0 * weight);
    let (weak_bob, weak) = make(&mut world, 1.0, 0.5 * weight);
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    let force = world.joint(strong).unwrap().constraint_force();
    println!("joint force {force:.4} N holding a weight of {weight:.4} N");
    assert!(((force - weight) / weight).abs() < 0.01);
    assert!(!world.joint(strong).unwrap().is_broken());
    assert!(world.joint(weak).unwrap().is_broken());
    assert!(world.body(weak_bob).unwrap().com_world().z < 0.0, "the broken joint let go");
}

// ---- bad input ----------------------------------------------------------------------------------

#[test]
fn joint_to_a_removed_body_is_an_error_naming_the_joint() {
    let mut world = World::default();
    let a = static_body(&mut world, DVec3::ZERO);
    let b = dynamic_body(&mut world, "b", cube(0.1), DVec3::Z);
    world.remove_body(b).unwrap();
    let def = JointDef::new(a, b, DVec3::ZERO, JointKind::Hinge(HingeJoint::default())).named("arm");
    let err = world.add_joint(def).unwrap_err();
    let message = err.to_string();
    println!("{message}");
    assert!(matches!(err, WorldError::InvalidJoint { .. }));
    assert!(
        message.contains("joint \"arm\"")
            && message.contains("body_b")
            && message.contains("does not name a body")
    );
    assert_eq!(world.joint_count(), 0);

    // Removing a body removes its joints: their ids go stale, and queries say so.
    let c = dynamic_body(&mut world, "c", cube(0.1), DVec3::Z);
    let joint =
        world.add_joint(JointDef::new(a, c, DVec3::ZERO, JointKind::Fixed(FixedJoint::new()))).unwrap();
    world.remove_body(c).unwrap();
    assert_eq!(world.joint_angle(joint).unwrap_err(), WorldError::StaleJoint(joint));
}

#[test]
fn invalid_joint_settings_name_the_joint_and_the_setting() {
    let mut world = World::default();
    let a = static_body(&mut world, DVec3::ZERO);
    let b = dynamic_body(&mut world, "b", cube(0.1), DVec3::Z);
    let hinge = |h: HingeJoint| JointKind::Hinge(h);
    let cases: Vec<(JointKind, Option<DVec3>, &str)> = vec![
        (
            hinge(HingeJoint { limits: Some(Limits::new(0.5, -0.5)), ..Default::default() }),
            None,
            "hinge limits: lower (0.5) must be <= upper (-0.5)",
        ),
        (
            hinge(HingeJoint { spring: Some(SpringSettings::new(-1.0, 0.5)), ..Default::default() }),
            None,
            "hinge spring hertz must be finite and >= 0, got -1",
        ),
        (
            hinge(HingeJoint { limits: Some(Limits::new(-4.0, 0.0)), ..Default::default() }),
            None,
            "hinge limits must lie within [-pi, pi]",
        ),
        (
            JointKind::Slider(SliderJoint { motor: Some(Motor::new(1.0, f64::NAN)), ..Default::default() }),
            None,
            "slider motor max_force must be finite and >= 0, got NaN",
        ),
        (
            JointKind::Slider(SliderJoint { limits: Some(Limits::new(1.0, 0.0)), ..Default::default() }),
            None,
            "slider limits: lower (1) must be <= upper (0)",
        ),
        (
            JointKind::Distance(DistanceJoint { min_length: 2.0, max_length: 1.0, ..Default::default() }),
            None,
            "distance max_length (1) must be >= min_length (2)",
        ),
        (
            JointKind::Ball(BallJoint { swing_limit: Some(-0.1), ..Default::default() }),
            None,
            "ball swing_limit must be within [0, pi], got -0.1",
        ),
        (hinge(HingeJoint::default()), Some(DVec3::Z), "anchor_b_world is only for distance joints"),
    ];
    for (kind, anchor_b_world, expected) in cases {
        let def = JointDef { anchor_b_world, ..JointDef::new(a, b, DVec3::ZERO, kind).named("arm") };
        let message = world.add_joint(def).unwrap_err().to_string();
        assert!(message.starts_with("joint \"arm\": "), "names the joint: {message}");
        assert!(message.contains(expected), "{message:?} should contain {expected:?}");
    }
    assert_eq!(world.joint_count(), 0, "a failed add changes nothing");
}
