//! Islands and sleep: resting islands fall asleep together and stop moving; forces, velocity
//! changes and new joints wake the whole island.

use tumble::{BallJoint, BodyDef, BodyKind, DVec3, JointDef, JointKind, Shape, Sphere, World};

/// A damped double pendulum (two balls on ball joints) comes to rest, sleeps as one island, and
/// a push on the lower ball wakes both.
#[test]
fn damped_pendulum_sleeps_as_one_island_and_wakes_together() {
    let mut world = World::default();
    let pivot = world.add_body(BodyDef { kind: BodyKind::Static, ..Default::default() }).unwrap();
    let ball = |name: &str, z: f64| BodyDef {
        name: name.into(),
        shape: Some(Shape::Sphere(Sphere::new(0.05).unwrap())),
        position: DVec3::new(0.2, 0.0, z),
        linear_damping: 2.0,
        angular_damping: 2.0,
        ..Default::default()
    };
    let upper = world.add_body(ball("upper", -0.5)).unwrap();
    let lower = world.add_body(ball("lower", -1.0)).unwrap();
    world.add_joint(JointDef::new(pivot, upper, DVec3::ZERO, JointKind::Ball(BallJoint::new()))).unwrap();
    world
        .add_joint(JointDef::new(upper, lower, DVec3::new(0.2, 0.0, -0.5), JointKind::Ball(BallJoint::new())))
        .unwrap();
    assert_eq!(world.awake_body_count(), 2);

    let dt = 1.0 / 60.0;
    let mut slept_at = None;
    for n in 0..1200 {
        world.step(dt).unwrap();
        if world.awake_body_count() == 0 {
            slept_at = Some(f64::from(n) * dt);
            break;
        }
        // Islands sleep whole: never one ball without the other.
        assert_eq!(
            world.body(upper).unwrap().is_awake(),
            world.body(lower).unwrap().is_awake(),
            "the joint links both balls into one island"
        );
    }
    let slept_at = slept_at.expect("the damped pendulum comes to rest and sleeps within 20 s");
    println!("slept after {slept_at:.2} s");
    let rest = world.body(lower).unwrap().position();
    for _ in 0..60 {
        world.step(dt).unwrap();
    }
    assert_eq!(world.body(lower).unwrap().position(), rest, "a sleeping body does not move at all");

    world.apply_force(lower, DVec3::new(5.0, 0.0, 0.0)).unwrap();
    assert!(world.body(upper).unwrap().is_awake(), "waking one body wakes its island");
    assert_eq!(world.awake_body_count(), 2);
    world.step(dt).unwrap();
    assert!(world.body(lower).unwrap().linear_velocity().x > 0.0);
}

#[test]
fn a_body_that_may_not_sleep_stays_awake() {
    let mut world = World::new(tumble::WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap();
    let id = world
        .add_body(BodyDef {
            shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())),
            allow_sleep: false,
            ..Default::default()
        })
        .unwrap();
    let other = world
        .add_body(BodyDef {
            shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())),
            position: DVec3::new(5.0, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert!(world.body(id).unwrap().is_awake());
    assert!(!world.body(other).unwrap().is_awake(), "a free body at rest in zero gravity sleeps");
}
