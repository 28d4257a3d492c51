//! Joint validation: VALIDATION.md J1 onwards.

use tumble::{BallJoint, BodyDef, BodyKind, DVec3, JointDef, JointKind, Shape, Sphere, World};

mod common;
use common::sign_changes;

/// J1: a ball-joint pendulum of length 1 m swinging at 5° has the period 2π√(L/g) within 0.5%, and
/// within 0.1% once corrected for amplitude (T = T₀(1 + θ₀²/16)) and the bob's own inertia; the
/// joint stays together to 0.1 mm.
#[test]
fn j1_ball_joint_pendulum_period() {
    let mut world = World::default();
    let g = 9.81;
    let length = 1.0;
    let radius = 0.02;
    let pivot_point = DVec3::new(0.0, 0.0, 2.0);
    let pivot = world
        .add_body(BodyDef {
            name: "pivot".into(),
            kind: BodyKind::Static,
            position: pivot_point,
            ..Default::default()
        })
        .unwrap();
    let theta0 = 5.0_f64.to_radians();
    let bob_position = pivot_point + length * DVec3::new(theta0.sin(), 0.0, -theta0.cos());
    let bob = world
        .add_body(BodyDef {
            name: "bob".into(),
            shape: Some(Shape::Sphere(Sphere::new(radius).unwrap())),
            position: bob_position,
            ..Default::default()
        })
        .unwrap();
    let joint =
        world.add_joint(JointDef::new(pivot, bob, pivot_point, JointKind::Ball(BallJoint::new()))).unwrap();

    let dt = 1.0 / 60.0;
    let (mut times, mut xs) = (vec![], vec![]);
    let mut max_error: f64 = 0.0;
    for n in 1..=1200 {
        world.step(dt).unwrap();
        let b = world.body(bob).unwrap();
        times.push(f64::from(n) * dt);
        xs.push(b.com_world().x);
        let j = world.joint(joint).unwrap();
        let gap = j.anchor_b_world(b) - j.anchor_a_world(world.body(pivot).unwrap());
        max_error = max_error.max(gap.length());
    }
    let crossings = sign_changes(&times, &xs);
    let period = 2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let simple = std::f64::consts::TAU * (length / g).sqrt();
    // Physical pendulum with a solid ball bob: I_pivot = m L² + 2/5 m r².
    let inertia_factor = (1.0 + 0.4 * radius * radius / (length * length)).sqrt();
    let corrected = simple * inertia_factor * (1.0 + theta0 * theta0 / 16.0);
    println!(
        "J1: period {period:.5} s, 2π√(L/g) = {simple:.5} s ({:+.3}%), corrected {corrected:.5} s ({:+.3}%), joint error {:.2e} m",
        100.0 * (period - simple) / simple,
        100.0 * (period - corrected) / corrected,
        max_error
    );
    assert!(((period - simple) / simple).abs() < 0.005);
    assert!(((period - corrected) / corrected).abs() < 0.001);
    assert!(max_error < 1e-4, "joint separation {max_error} m");
}
