//! Changes made between steps reach the next step's broad phase: a body made, or given a speed,
//! right next to a thin wall must have its pair with the wall found in that step — its proxy's fat
//! box has to cover where it is headed, or it passes through the wall without ever touching it.
//! (Until the fat box was required to cover the swept box, a ball at 60 m/s made 0.45 m from a
//! 10 cm wall ended the step 4 m beyond it.)

use tumble::{BodyDef, BodyId, BodyKind, DVec3, World};

mod contact_support;
use contact_support::*;

/// Ball speed, m/s: a metre per step, so the ball would end its first step beyond the wall.
const SPEED: f64 = 60.0;

/// A static wall 0.1 m thick across x = 0, stepped once so its world has proxies in place.
fn walled_world() -> World {
    let mut world = zero_gravity_world();
    world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: cuboid(DVec3::new(0.05, 2.0, 2.0)),
            ..Default::default()
        })
        .unwrap();
    world.step(DT).unwrap();
    world
}

/// A ball of radius 0.1 m at x = −0.6, its surface 0.45 m from the wall.
fn ball(world: &mut World, speed: f64) -> BodyId {
    world
        .add_body(BodyDef {
            shape: sphere(0.1),
            position: DVec3::new(-0.6, 0.0, 0.0),
            linear_velocity: DVec3::new(speed, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap()
}

/// After one step the ball has met the wall: a contact with it exists, and the ball stands
/// before it (its surface at most 5 mm in), its approach stopped.
fn assert_stopped_by_the_wall(world: &mut World, ball: BodyId) {
    world.step(DT).unwrap();
    assert_eq!(world.contact_count(), 1, "the ball's pair with the wall was not found");
    let b = world.body(ball).unwrap();
    let x = b.position().x;
    assert!(x < -0.05 - 0.1 + 0.005, "the ball passed the wall: x = {x}");
    assert!(b.linear_velocity().x < 0.1 * SPEED, "the ball was not stopped: v = {}", b.linear_velocity());
}

#[test]
fn a_fast_body_made_between_steps_meets_the_wall() {
    let mut world = walled_world();
    let ball = ball(&mut world, SPEED);
    assert_stopped_by_the_wall(&mut world, ball);
}

#[test]
fn a_speed_given_between_steps_meets_the_wall() {
    let mut world = walled_world();
    let ball = ball(&mut world, 0.0);
    world.step(DT).unwrap();
    assert_eq!(world.body(ball).unwrap().position().x, -0.6, "at rest");
    world.set_linear_velocity(ball, DVec3::new(SPEED, 0.0, 0.0)).unwrap();
    assert_stopped_by_the_wall(&mut world, ball);
}
