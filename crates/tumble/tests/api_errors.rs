//! Bad input through the public API: each case is a clear error naming what and where, and a
//! failed call leaves the world unchanged.

use tumble::{BodyDef, BodyKind, Cuboid, DQuat, DVec3, MassError, Shape, Sphere, World, WorldError};

fn ball(name: &str) -> BodyDef {
    BodyDef { name: name.into(), shape: Some(Shape::Sphere(Sphere::new(0.5).unwrap())), ..Default::default() }
}

#[test]
fn stale_id_is_an_error_not_another_body() {
    let mut world = World::default();
    let a = world.add_body(ball("a")).unwrap();
    world.remove_body(a).unwrap();
    let b = world.add_body(ball("b")).unwrap();
    assert_eq!(a.index(), b.index(), "the slot is reused");
    let err = world.body(a).unwrap_err();
    assert_eq!(err, WorldError::StaleBody(a));
    assert!(err.to_string().contains("does not name a body"), "{err}");
    assert!(world.apply_force(a, DVec3::X).is_err());
    assert!(world.remove_body(a).is_err());
    assert_eq!(world.body(b).unwrap().name(), "b");
}

#[test]
fn invalid_body_definitions_name_the_body_and_the_value() {
    let mut world = World::default();
    let cases: Vec<(BodyDef, &str)> = vec![
        (BodyDef { density: -2.0, ..ball("arm") }, "density must be finite and > 0, got -2"),
        (BodyDef { mass: Some(0.0), ..ball("arm") }, "mass"),
        (BodyDef { position: DVec3::new(f64::NAN, 0.0, 0.0), ..ball("arm") }, "position must be finite"),
        (BodyDef { linear_velocity: DVec3::new(0.0, f64::INFINITY, 0.0), ..ball("arm") }, "linear_velocity"),
        (BodyDef { orientation: DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0), ..ball("arm") }, "unit quaternion"),
        (BodyDef { linear_damping: -1.0, ..ball("arm") }, "linear_damping must be finite and >= 0"),
        (BodyDef { name: "arm".into(), ..Default::default() }, "needs a shape or mass_properties"),
    ];
    for (def, expected) in cases {
        let err = world.add_body(def).unwrap_err();
        let message = err.to_string();
        assert!(message.contains("body \"arm\""), "message names the body: {message}");
        assert!(message.contains(expected), "expected `{expected}` in: {message}");
    }
    assert_eq!(world.body_count(), 0, "failed adds leave the world unchanged");
}

#[test]
fn invalid_shapes_are_errors() {
    assert!(matches!(Sphere::new(-1.0), Err(MassError::NotPositive { .. })));
    assert!(Sphere::new(f64::NAN).is_err());
    let err = Cuboid::new(DVec3::new(1.0, 0.0, 1.0)).unwrap_err();
    assert!(err.to_string().contains("box half extent y"), "{err}");
}

#[test]
fn non_finite_forces_and_steps_are_rejected_without_changing_state() {
    let mut world = World::default();
    let id = world.add_body(ball("a")).unwrap();
    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    for err in [
        world.apply_force(id, nan).unwrap_err(),
        world.apply_torque(id, nan).unwrap_err(),
        world.apply_force_at_point(id, DVec3::X, nan).unwrap_err(),
        world.apply_impulse_at_point(id, nan, DVec3::ZERO).unwrap_err(),
        world.set_linear_velocity(id, nan).unwrap_err(),
        world.set_gravity(nan).unwrap_err(),
    ] {
        assert!(err.to_string().contains("must be finite"), "{err}");
    }
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = world.step(dt).unwrap_err();
        assert!(matches!(err, WorldError::InvalidTimeStep(_)), "{err:?}");
        assert!(err.to_string().contains(&format!("time step must be finite and > 0, got {dt}")), "{err}");
    }
    let body = world.body(id).unwrap();
    assert_eq!(body.force(), DVec3::ZERO);
    assert_eq!(body.linear_velocity(), DVec3::ZERO);
    assert_eq!(world.time(), 0.0);
}

#[test]
fn static_and_kinematic_bodies_ignore_forces_and_keep_their_motion() {
    let mut world = World::default();
    let ground = world
        .add_body(BodyDef { kind: BodyKind::Static, linear_velocity: DVec3::X, ..ball("ground") })
        .unwrap();
    let lift = world
        .add_body(BodyDef {
            kind: BodyKind::Kinematic,
            linear_velocity: DVec3::new(0.0, 0.0, 1.0),
            angular_velocity: DVec3::new(0.0, 0.0, 2.0),
            ..ball("lift")
        })
        .unwrap();
    world.apply_force(lift, DVec3::new(100.0, 0.0, 0.0)).unwrap();
    world.apply_impulse_at_point(lift, DVec3::new(100.0, 0.0, 0.0), DVec3::ZERO).unwrap();
    for _ in 0..100 {
        world.step(0.01).unwrap();
    }
    let g = world.body(ground).unwrap();
    assert_eq!(g.position(), DVec3::ZERO, "static bodies never move");
    assert_eq!(g.linear_velocity(), DVec3::ZERO);
    let l = world.body(lift).unwrap();
    assert!((l.position() - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-12, "{}", l.position());
    let expected = DQuat::from_rotation_z(2.0);
    assert!(l.orientation().dot(expected).abs() > 1.0 - 1e-12);
    assert_eq!(world.kinetic_energy(), 0.0, "only dynamic bodies carry energy");
}

#[test]
fn simulated_time_does_not_drift() {
    let mut world = World::default();
    for _ in 0..72_000 {
        world.step(1.0 / 240.0).unwrap();
    }
    assert_eq!(world.time(), 300.0, "72,000 steps of 1/240 s are exactly 300 s");
    assert_eq!(world.step_count(), 72_000);
}
