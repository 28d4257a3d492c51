//! Contact and sensor events (`events.rs`): begin and end per pair of bodies, once, in order.

use tumble::{
    BodyDef, BodyId, BodyKind, Compound, CompoundChild, Cuboid, DQuat, DVec3, Shape, Sphere, Transform, World,
};

fn ball(z: f64) -> BodyDef {
    BodyDef {
        name: "ball".into(),
        shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())),
        position: DVec3::new(0.0, 0.0, z),
        ..Default::default()
    }
}

fn slab(z: f64, sensor: bool) -> BodyDef {
    BodyDef {
        kind: BodyKind::Static,
        shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(2.0, 2.0, 0.5)).unwrap())),
        position: DVec3::new(0.0, 0.0, z),
        is_sensor: sensor,
        ..Default::default()
    }
}

fn pair(a: BodyId, b: BodyId) -> (BodyId, BodyId) {
    (a.min(b), a.max(b))
}

#[derive(Debug, PartialEq)]
enum Event {
    ContactBegin(usize),
    ContactEnd(usize),
    SensorBegin(usize),
    SensorEnd(usize),
}

/// Steps `n` times and returns every event with its step number.
fn run(world: &mut World, n: usize, mut each: impl FnMut(&World, usize)) -> Vec<Event> {
    let mut events = Vec::new();
    for step in 0..n {
        world.step(1.0 / 60.0).unwrap();
        events.extend(world.contact_begin_events().iter().map(|_| Event::ContactBegin(step)));
        events.extend(world.contact_end_events().iter().map(|_| Event::ContactEnd(step)));
        events.extend(world.sensor_begin_events().iter().map(|_| Event::SensorBegin(step)));
        events.extend(world.sensor_end_events().iter().map(|_| Event::SensorEnd(step)));
        each(world, step);
    }
    events
}

#[test]
fn a_ball_dropped_through_a_sensor_gives_begin_then_end() {
    let mut world = World::default();
    let sensor = world.add_body(slab(0.0, true)).unwrap();
    let ball = world.add_body(ball(2.0)).unwrap();
    let mut inside_steps = Vec::new();
    let events = run(&mut world, 120, |w, step| {
        for &(a, b) in w.sensor_begin_events().iter().chain(w.sensor_end_events()) {
            assert_eq!((a, b), pair(sensor, ball));
        }
        let z = w.body(ball).unwrap().position().z;
        if z.abs() < 0.6 - 1e-9 {
            inside_steps.push(step);
        }
    });
    assert!(world.body(ball).unwrap().position().z < -1.0, "the sensor does not stop the ball");
    let (first, last) = (inside_steps[0], *inside_steps.last().unwrap());
    // The narrow phase runs before the solve: a step reports the overlap of the poses it started
    // from, i.e. the poses after the previous step.
    assert_eq!(events, [Event::SensorBegin(first + 1), Event::SensorEnd(last + 2)], "sensor events");
    assert_eq!(world.contact_count(), 0);
}

#[test]
fn a_ball_landing_on_the_ground_gives_one_contact_begin_and_removal_an_end() {
    let mut world = World::default();
    let ground = world.add_body(slab(-0.5, false)).unwrap();
    let ball = world.add_body(ball(1.0)).unwrap();
    let events = run(&mut world, 120, |w, step| {
        if let Some(&p) = w.contact_begin_events().first() {
            assert_eq!(p, pair(ground, ball));
            let z = w.body(ball).unwrap().position().z;
            assert!(z < 0.2, "step {step}: begins within the speculative margin, ball at {z}");
        }
    });
    assert_eq!(events.len(), 1, "{events:?}");
    assert!(matches!(events[0], Event::ContactBegin(_)));
    assert!((world.body(ball).unwrap().position().z - 0.1).abs() < 0.01, "the ball rests on the ground");

    world.remove_body(ball).unwrap();
    world.step(1.0 / 60.0).unwrap();
    assert_eq!(world.contact_end_events(), [pair(ground, ball)], "removal ends the contact (stale id)");
    world.step(1.0 / 60.0).unwrap();
    assert!(world.contact_end_events().is_empty(), "events last one step");
}

#[test]
fn a_compound_touching_with_two_parts_gives_one_event_per_pair() {
    let mut world = World::default();
    let ground = world.add_body(slab(-0.5, false)).unwrap();
    let foot = |x: f64| CompoundChild {
        pose: Transform::new(DVec3::new(x, 0.0, 0.0), DQuat::IDENTITY),
        shape: Shape::Sphere(Sphere::new(0.1).unwrap()),
    };
    let feet = Compound::new(vec![foot(-0.5), foot(0.5)]).unwrap();
    let body = world
        .add_body(BodyDef {
            shape: Some(Shape::Compound(feet)),
            position: DVec3::new(0.0, 0.0, 0.5),
            ..Default::default()
        })
        .unwrap();
    let events = run(&mut world, 90, |_, _| {});
    assert_eq!(events.len(), 1, "{events:?}");
    assert_eq!(world.contacts().len(), 2, "two leaf contacts");
    world.set_linear_velocity(body, DVec3::new(0.0, 0.0, 5.0)).unwrap();
    let events = run(&mut world, 30, |w, _| {
        for &p in w.contact_end_events() {
            assert_eq!(p, pair(ground, body));
        }
    });
    assert_eq!(events.len(), 1, "one end when both feet leave: {events:?}");
}
