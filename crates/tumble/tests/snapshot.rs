//! Exact snapshots: restore-then-step is bit-identical to stepping on, also after bodies and
//! joints were added and removed; damaged snapshots are clear errors.

use tumble::{
    BallJoint, BodyDef, BodyKind, Capsule, Cuboid, DQuat, DVec3, HingeJoint, JointDef, JointKind, Shape,
    SnapshotError, Sphere, World,
};

fn busy_world() -> World {
    let mut world = World::default();
    world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(8.0, 8.0, 0.5)).unwrap())),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        })
        .unwrap();
    for i in 0..10 {
        let f = f64::from(i);
        let shape = match i % 3 {
            0 => Shape::Cuboid(Cuboid::new(DVec3::new(0.3, 0.2, 0.25)).unwrap()),
            1 => Shape::Sphere(Sphere::new(0.2).unwrap()),
            _ => Shape::Capsule(Capsule::new(0.1, 0.2).unwrap()),
        };
        world
            .add_body(BodyDef {
                name: format!("body{i}"),
                shape: Some(shape),
                position: DVec3::new(0.4 * (f * 1.7).sin(), 0.4 * (f * 0.9).cos(), 0.4 + 0.55 * f),
                orientation: DQuat::from_rotation_x(0.3 * f),
                angular_velocity: DVec3::new(0.5, -0.2 * f, 0.1),
                ..Default::default()
            })
            .unwrap();
    }
    world
}

#[test]
fn restore_then_step_is_bit_identical_after_adds_and_removes() {
    let mut world = busy_world();
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    // Change the world mid-run: remove a body, add two, join them, remove another joint later.
    let removed = world.find_body("body4").unwrap();
    world.remove_body(removed).unwrap();
    let a = world
        .add_body(BodyDef {
            name: "late_a".into(),
            shape: Some(Shape::Sphere(Sphere::new(0.15).unwrap())),
            position: DVec3::new(2.0, 0.0, 1.0),
            ..Default::default()
        })
        .unwrap();
    let b = world
        .add_body(BodyDef {
            name: "late_b".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.15)).unwrap())),
            position: DVec3::new(2.0, 0.0, 1.5),
            ..Default::default()
        })
        .unwrap();
    world
        .add_joint(JointDef::new(a, b, DVec3::new(2.0, 0.0, 1.25), JointKind::Ball(BallJoint::new())))
        .unwrap();
    let hinge = world
        .add_joint(
            JointDef::new(
                a,
                world.find_body("body1").unwrap(),
                DVec3::new(1.0, 0.0, 1.0),
                JointKind::Hinge(HingeJoint::default()),
            )
            .with_axis(DVec3::Y),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    world.remove_joint(hinge).unwrap();
    for _ in 0..10 {
        world.step(1.0 / 60.0).unwrap();
    }

    let bytes = world.snapshot();
    let mut restored = World::restore(&bytes).unwrap();
    assert_eq!(restored.state_hash(), world.state_hash());
    assert_eq!(restored.snapshot(), bytes, "a restored world snapshots to the same bytes");
    for step in 0..240 {
        world.step(1.0 / 60.0).unwrap();
        restored.step(1.0 / 60.0).unwrap();
        assert_eq!(restored.state_hash(), world.state_hash(), "diverged at step {step} after the restore");
    }
    // The ids still work, stale ones stay stale.
    assert!(restored.body(a).is_ok());
    assert!(restored.body(removed).is_err());
    println!(
        "snapshot of {} bodies, {} joints: {} bytes",
        restored.body_count(),
        restored.joint_count(),
        bytes.len()
    );
}

#[test]
fn damaged_snapshots_are_clear_errors() {
    let world = busy_world();
    let bytes = world.snapshot();
    assert_eq!(World::restore(b"hello").err(), Some(SnapshotError::NotASnapshot));
    assert!(matches!(World::restore(&bytes[..bytes.len() / 2]).err(), Some(SnapshotError::Truncated { .. })));
    assert!(matches!(World::restore(&bytes[..20]).err(), Some(SnapshotError::Truncated { .. })));
    let mut corrupt = bytes.clone();
    let middle = corrupt.len() / 2;
    corrupt[middle] ^= 0x40;
    assert_eq!(World::restore(&corrupt).err(), Some(SnapshotError::Corrupt));
    let mut newer = bytes.clone();
    newer[8] = 99;
    let err = World::restore(&newer).err().unwrap();
    assert!(matches!(err, SnapshotError::UnsupportedVersion { found: 99, .. }), "{err:?}");
    assert!(err.to_string().contains("version 99"), "{err}");
}
