//! C4 of VALIDATION.md: rolling without slipping.

use tumble::{BodyDef, BodyKind, DVec3};

mod common;
mod contact_support;
use common::slope;
use contact_support::*;

/// C4: a solid ball rolling down a 20° incline with μ = 0.8 accelerates at 5/7·g·sinθ within 1%,
/// and its contact point does not slip: the centre's speed equals ω r within 1%.
#[test]
fn c4_sphere_rolls_down_incline() {
    let theta = 20.0_f64.to_radians();
    let radius = 0.1;
    let mut world = world(Default::default());
    let slope_ = incline(&mut world, theta, material(0.8, 0.0));
    let start = slope_.downhill * -15.0 + slope_.normal * radius;
    let ball = world
        .add_body(BodyDef {
            name: "ball".into(),
            shape: sphere(radius),
            position: start,
            material: material(0.8, 0.0),
            ..Default::default()
        })
        .unwrap();
    let axis = slope_.normal.cross(slope_.downhill);
    let (mut times, mut speeds) = (vec![], vec![]);
    let mut worst_slip: f64 = 0.0;
    for n in 1..=150 {
        world.step(DT).unwrap();
        let t = f64::from(n) * DT;
        let b = world.body(ball).unwrap();
        let v = b.linear_velocity().dot(slope_.downhill);
        let w_r = b.angular_velocity().dot(axis) * radius;
        if t >= 0.25 {
            times.push(t);
            speeds.push(v);
            worst_slip = worst_slip.max(((v - w_r) / v).abs());
        }
    }
    let a = slope(&times, &speeds);
    let exact = 5.0 / 7.0 * G * theta.sin();
    let error = (a - exact) / exact;
    println!(
        "C4: acceleration {a:.5} m/s², 5/7 g sinθ = {exact:.5} m/s² ({:+.3}%); largest slip |v − ωr|/v = {:.2e} after 0.25 s",
        100.0 * error,
        worst_slip
    );
    assert!(error.abs() < 0.01, "acceleration error {:.3}%", 100.0 * error);
    assert!(worst_slip < 0.01, "slip {worst_slip}");
}

/// A capsule pinned by a ball joint at its raised end, its other end on the ground, rolling round
/// the pivot without slipping: nothing dissipates (friction does no work on a rolling point), so
/// its kinetic energy must stay constant. The contact's lever arm on a round end must turn with
/// the body within the step; holding it fixed fed the rolling energy exponentially (×2,300 in
/// 10 s).
#[test]
fn capsule_rolling_round_a_pivot_keeps_its_energy() {
    use tumble::{BallJoint, Capsule, DQuat, JointDef, JointKind, Shape};
    let mut world = world(Default::default());
    ground(&mut world, material(0.6, 0.0));
    world.set_sleep_settings(tumble::SleepSettings { enabled: false, ..Default::default() });
    let (radius, half_height, drop): (f64, f64, f64) = (0.045, 0.1, 0.03);
    let tilt = (drop / (2.0 * half_height)).asin();
    let axis = DVec3::new(tilt.cos(), 0.0, -tilt.sin());
    let centre = DVec3::new(0.0, 0.0, radius + drop / 2.0);
    let capsule = world
        .add_body(BodyDef {
            name: "capsule".into(),
            shape: Some(Shape::Capsule(Capsule::new(radius, half_height).unwrap())),
            position: centre,
            orientation: DQuat::from_rotation_y(tilt) * DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
            angular_velocity: 0.3 * axis,
            ..Default::default()
        })
        .unwrap();
    let pivot = world
        .add_body(BodyDef {
            name: "pivot".into(),
            kind: BodyKind::Static,
            position: centre - half_height * axis,
            ..Default::default()
        })
        .unwrap();
    world
        .add_joint(JointDef::new(
            pivot,
            capsule,
            centre - half_height * axis,
            JointKind::Ball(BallJoint::new()),
        ))
        .unwrap();
    // The first half second settles the rolling (the initial spin slips until it rolls).
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let e0 = world.body(capsule).unwrap().kinetic_energy();
    let mut worst: f64 = 0.0;
    for _ in 0..570 {
        world.step(DT).unwrap();
        let e = world.body(capsule).unwrap().kinetic_energy();
        worst = worst.max((e - e0).abs() / e0);
    }
    let speed = world.body(capsule).unwrap().linear_velocity().length();
    println!(
        "rolling round a pivot: energy {e0:.4e} J, largest change {:.2e} relative, speed {speed:.4} m/s",
        worst
    );
    assert!(speed > 1e-3, "it keeps rolling");
    assert!(worst < 1e-4, "energy change {worst:e}");
}
