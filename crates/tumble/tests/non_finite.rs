//! Non-finite state (`non_finite.rs`): a body whose numbers overflow is isolated and reported, and
//! the rest of the world keeps stepping with finite state and the right motion.

use tumble::{
    BallJoint, BodyDef, BodyId, BodyKind, Cuboid, DVec3, JointDef, JointKind, NonFiniteBody, Shape, World,
};

const DT: f64 = 1.0 / 60.0;

fn unit_box(world: &mut World, name: &str, position: DVec3) -> BodyId {
    world
        .add_body(BodyDef {
            name: name.into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).unwrap())),
            position,
            ..Default::default()
        })
        .unwrap()
}

/// Ground with its top at z = 0 and three stacks of four unit boxes, 1.5 m apart.
fn pile() -> (World, Vec<Vec<BodyId>>) {
    let mut world = World::default();
    world
        .add_body(BodyDef {
            name: "ground".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(20.0, 20.0, 0.5)).unwrap())),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        })
        .unwrap();
    let stacks = (0..3)
        .map(|s| {
            (0..4)
                .map(|i| {
                    let position = DVec3::new(1.5 * (s as f64 - 1.0), 0.0, 0.5 + i as f64);
                    unit_box(&mut world, &format!("box {s}.{i}"), position)
                })
                .collect()
        })
        .collect();
    (world, stacks)
}

fn is_finite_body(world: &World, id: BodyId) -> bool {
    let s = world.body(id).unwrap().state();
    s.com_world.is_finite()
        && s.rotation.is_finite()
        && s.linear_velocity.is_finite()
        && s.angular_velocity.is_finite()
}

/// Steps `world` 100 times; checks every body but `culprit` stays finite, above the ground and
/// slow, and returns the events of each step.
fn step_100(world: &mut World, culprit: BodyId) -> Vec<Vec<NonFiniteBody>> {
    let mut events = Vec::new();
    for step in 0..100 {
        world.step(DT).unwrap();
        events.push(world.non_finite_events().to_vec());
        for (id, body) in world.bodies() {
            assert!(is_finite_body(world, id), "step {step}: {} is not finite", body.name());
            if id != culprit && body.kind() == BodyKind::Dynamic {
                assert!(body.com_world().z > 0.0, "step {step}: {} fell through", body.name());
                assert!(body.linear_velocity().length() < 20.0, "step {step}: {} flies off", body.name());
            }
        }
        assert!((world.kinetic_energy() + world.potential_energy()).is_finite());
    }
    events
}

#[test]
fn huge_force_isolates_only_the_body_it_acts_on() {
    let (mut world, stacks) = pile();
    let culprit = stacks[1][1];
    let start = world.body(culprit).unwrap().position();
    // 1e308 N per component on a 1000 kg box: one step's velocity squared overflows.
    world.apply_force(culprit, DVec3::splat(1e308)).unwrap();
    let events = step_100(&mut world, culprit);

    assert_eq!(events[0], vec![NonFiniteBody { body: culprit }], "the first step reports the body");
    assert!(events[1..].iter().all(|e| e.is_empty()), "reported once");
    assert_eq!(world.isolated_bodies().collect::<Vec<_>>(), vec![culprit]);
    let body = world.body(culprit).unwrap();
    assert!(body.is_isolated());
    assert_eq!(body.position(), start, "kept at its last finite pose");
    assert_eq!(body.linear_velocity(), DVec3::ZERO);
    assert!(world.contacts().iter().all(|c| c.body_a != culprit && c.body_b != culprit));

    // The side stacks are untouched; the boxes that stood on the culprit fell onto the one below.
    for &stack in &[0, 2] {
        for (i, &id) in stacks[stack].iter().enumerate() {
            let z = world.body(id).unwrap().position().z;
            assert!((z - (0.5 + i as f64)).abs() < 0.05, "box {stack}.{i} at z = {z}");
        }
    }
    let middle: Vec<f64> = stacks[1].iter().map(|&id| world.body(id).unwrap().position().z).collect();
    assert!((middle[2] - 1.5).abs() < 0.05 && (middle[3] - 2.5).abs() < 0.05, "middle stack at {middle:?}");
}

#[test]
fn forces_adding_up_to_infinity_are_caught() {
    // Each call is finite and accepted; their sum is not.
    let (mut world, stacks) = pile();
    let culprit = stacks[0][0];
    world.apply_force(culprit, DVec3::new(0.0, 0.0, 1e308)).unwrap();
    world.apply_force(culprit, DVec3::new(0.0, 0.0, 1e308)).unwrap();
    let events = step_100(&mut world, culprit);
    assert_eq!(events[0], vec![NonFiniteBody { body: culprit }]);
}

#[test]
fn huge_velocity_is_isolated_before_it_reaches_a_contact() {
    let (mut world, stacks) = pile();
    let culprit = stacks[2][3];
    world.set_linear_velocity(culprit, DVec3::new(-1e200, 0.0, 0.0)).unwrap();
    let events = step_100(&mut world, culprit);
    assert_eq!(events[0], vec![NonFiniteBody { body: culprit }]);
    assert_eq!(world.isolated_bodies().count(), 1);
}

#[test]
fn joints_to_an_isolated_body_break_and_pass_nothing_on() {
    // A chain of five boxes hanging from a static anchor by ball joints, 1.2 m apart.
    let mut world = World::default();
    let anchor = world
        .add_body(BodyDef { name: "anchor".into(), kind: BodyKind::Static, ..Default::default() })
        .unwrap();
    let mut previous = anchor;
    let mut links = Vec::new();
    for i in 0..5 {
        let position = DVec3::new(0.0, 0.0, -1.2 * (i + 1) as f64);
        let id = unit_box(&mut world, &format!("link {i}"), position);
        let def = JointDef::new(
            previous,
            id,
            position + DVec3::new(0.0, 0.0, 0.6),
            JointKind::Ball(BallJoint::default()),
        );
        world.add_joint(def).unwrap();
        links.push(id);
        previous = id;
    }
    // Swing it, then blow up the middle link.
    world.set_linear_velocity(links[4], DVec3::new(2.0, 0.0, 0.0)).unwrap();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let culprit = links[2];
    world.apply_torque(culprit, DVec3::splat(1e308)).unwrap();
    world.apply_torque(culprit, DVec3::splat(1e308)).unwrap();
    let mut reported = Vec::new();
    for _ in 0..100 {
        world.step(DT).unwrap();
        reported.extend_from_slice(world.non_finite_events());
        for (id, _) in world.bodies() {
            assert!(is_finite_body(&world, id));
        }
    }
    assert_eq!(reported, vec![NonFiniteBody { body: culprit }]);
    let broken: Vec<bool> = world.joints().map(|(_, j)| j.is_broken()).collect();
    assert_eq!(broken, vec![false, false, true, true, false], "the culprit's two joints broke");
    // The two links above still hang from the anchor; the two below fell free.
    assert!((world.body(links[0]).unwrap().com_world().length() - 1.2).abs() < 0.05);
    assert!(world.body(links[4]).unwrap().com_world().z < -10.0);
}

#[test]
fn an_isolated_body_survives_a_snapshot() {
    let (mut world, stacks) = pile();
    let culprit = stacks[1][0];
    world.apply_force(culprit, DVec3::splat(1e308)).unwrap();
    world.step(DT).unwrap();
    let restored = World::restore(&world.snapshot()).unwrap();
    assert_eq!(restored.state_hash(), world.state_hash());
    assert_eq!(restored.isolated_bodies().collect::<Vec<_>>(), vec![culprit]);
    assert_eq!(restored.non_finite_events(), world.non_finite_events());
}
