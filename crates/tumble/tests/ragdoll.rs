//! Joints and contacts together: VALIDATION.md J6, a ragdoll of 11 bodies (boxes, capsules and a
//! ball) on ball joints with swing and twist limits and hinges with limits, dropped on the ground.

use std::f64::consts::FRAC_PI_2;
use tumble::{
    BallJoint, BodyDef, BodyId, Capsule, DQuat, DVec3, HingeJoint, JointDef, JointId, JointKind, Limits,
    Shape, World,
};

mod contact_support;
use contact_support::*;

fn capsule(radius: f64, half_height: f64) -> Option<Shape> {
    Some(Shape::Capsule(Capsule::new(radius, half_height).unwrap()))
}

/// Joint friction, N·m: small beside the limbs' gravity torques (a 3 kg shin 0.2 m from the knee
/// takes 6 N·m), but without any a limb lying on the ground rolls to and fro between its joint
/// limits for ever (rolling on the ground dissipates nothing).
const JOINT_FRICTION: f64 = 0.5;

fn ball(swing: f64, twist: f64) -> JointKind {
    JointKind::Ball(BallJoint {
        swing_limit: Some(swing),
        twist_limits: Some(Limits::new(-twist, twist)),
        friction_torque: JOINT_FRICTION,
    })
}

fn hinge(lower: f64, upper: f64) -> JointKind {
    JointKind::Hinge(HingeJoint {
        limits: Some(Limits::new(lower, upper)),
        friction_torque: JOINT_FRICTION,
        ..Default::default()
    })
}

/// Builds a standing ragdoll (arms out sideways) with its feet `lift` above the ground, tipped
/// forward by `tilt` about X so it falls over. Returns the bodies and joints.
fn ragdoll(world: &mut World, lift: f64, tilt: f64) -> (Vec<BodyId>, Vec<JointId>) {
    let turn = DQuat::from_rotation_x(tilt);
    let base = DVec3::new(0.0, 0.0, lift);
    let place = |p: DVec3| base + turn * p;
    let mut bodies = Vec::new();
    let mut add = |world: &mut World, name: &str, shape: Option<Shape>, at: DVec3, orientation: DQuat| {
        let id = world
            .add_body(BodyDef {
                name: name.into(),
                shape,
                position: place(at),
                orientation: turn * orientation,
                ..Default::default()
            })
            .unwrap();
        bodies.push(id);
        id
    };
    let along_x = DQuat::from_rotation_y(FRAC_PI_2);
    let pelvis =
        add(world, "pelvis", cuboid(DVec3::new(0.15, 0.1, 0.1)), DVec3::new(0.0, 0.0, 1.0), DQuat::IDENTITY);
    let torso =
        add(world, "torso", cuboid(DVec3::new(0.17, 0.1, 0.2)), DVec3::new(0.0, 0.0, 1.3), DQuat::IDENTITY);
    let head = add(world, "head", sphere(0.1), DVec3::new(0.0, 0.0, 1.62), DQuat::IDENTITY);
    let mut joints = Vec::new();
    let mut join = |world: &mut World, a: BodyId, b: BodyId, anchor: DVec3, axis: DVec3, kind: JointKind| {
        joints
            .push(world.add_joint(JointDef::new(a, b, place(anchor), kind).with_axis(turn * axis)).unwrap());
    };
    join(world, pelvis, torso, DVec3::new(0.0, 0.0, 1.1), DVec3::Z, ball(0.5, 0.4));
    join(world, torso, head, DVec3::new(0.0, 0.0, 1.5), DVec3::Z, ball(0.6, 0.8));
    for side in [-1.0, 1.0] {
        let s = if side < 0.0 { "left" } else { "right" };
        let upper_arm = add(
            world,
            &format!("{s} upper arm"),
            capsule(0.05, 0.1),
            DVec3::new(side * 0.32, 0.0, 1.45),
            along_x,
        );
        let forearm = add(
            world,
            &format!("{s} forearm"),
            capsule(0.045, 0.1),
            DVec3::new(side * 0.62, 0.0, 1.45),
            along_x,
        );
        let thigh = add(
            world,
            &format!("{s} thigh"),
            capsule(0.06, 0.13),
            DVec3::new(side * 0.09, 0.0, 0.71),
            DQuat::IDENTITY,
        );
        let shin = add(
            world,
            &format!("{s} shin"),
            capsule(0.05, 0.14),
            DVec3::new(side * 0.09, 0.0, 0.33),
            DQuat::IDENTITY,
        );
        join(world, torso, upper_arm, DVec3::new(side * 0.17, 0.0, 1.45), DVec3::X * side, ball(1.2, 0.8));
        join(world, upper_arm, forearm, DVec3::new(side * 0.47, 0.0, 1.45), DVec3::Z, hinge(0.0, 2.4));
        join(world, pelvis, thigh, DVec3::new(side * 0.09, 0.0, 0.9), -DVec3::Z, ball(1.0, 0.5));
        join(world, thigh, shin, DVec3::new(side * 0.09, 0.0, 0.52), DVec3::X, hinge(0.0, 2.4));
    }
    (bodies, joints)
}

/// J6: a ragdoll of 11 bodies dropped from 0.5 m, tipping over as it falls, stays connected (every
/// joint's anchors within 1 cm at every step), comes to rest and falls asleep within 10 s.
///
/// The joints have a little friction (`JOINT_FRICTION`). Measured: largest separation 7.6 mm (at
/// the impact), asleep after 2.1 s.
#[test]
fn j6_ragdoll_falls_connected_and_sleeps() {
    let mut world = world(Default::default());
    ground(&mut world, material(0.6, 0.0));
    let (bodies, joints) = ragdoll(&mut world, 0.5, 0.3);
    assert!(bodies.len() >= 10);
    let mut worst: f64 = 0.0;
    let mut slept_at = None;
    for n in 1..=600 {
        world.step(DT).unwrap();
        for &j in &joints {
            worst = worst.max(world.joint_separation(j).unwrap().length());
        }
        if slept_at.is_none() && world.awake_body_count() == 0 {
            slept_at = Some(f64::from(n) * DT);
        }
    }
    let lowest = bodies.iter().map(|&b| world.body(b).unwrap().position().z).fold(f64::INFINITY, f64::min);
    let highest =
        bodies.iter().map(|&b| world.body(b).unwrap().position().z).fold(f64::NEG_INFINITY, f64::max);
    println!(
        "J6: {} bodies, {} joints: largest joint separation {:.3} mm; asleep after {slept_at:?} s; body centres between z = {lowest:.3} and {highest:.3} m",
        bodies.len(),
        joints.len(),
        1e3 * worst
    );
    assert!(worst < 0.01, "joint separation {worst} m");
    assert!(slept_at.is_some(), "the ragdoll comes to rest and sleeps within 10 s");
    assert!(highest < 0.4, "the ragdoll lies on the ground");
}

/// Runs the J6 ragdoll for 10 s: (largest joint separation, time asleep, steps/s).
fn ragdoll_run(settings: tumble::SolverSettings) -> (f64, Option<f64>, f64) {
    let mut world = world(settings);
    ground(&mut world, material(0.6, 0.0));
    let (_, joints) = ragdoll(&mut world, 0.5, 0.3);
    let (mut worst, mut slept_at): (f64, Option<f64>) = (0.0, None);
    let start = std::time::Instant::now();
    for n in 1..=600 {
        world.step(DT).unwrap();
        for &j in &joints {
            worst = worst.max(world.joint_separation(j).unwrap().length());
        }
        if slept_at.is_none() && world.awake_body_count() == 0 {
            slept_at = Some(f64::from(n) * DT);
        }
    }
    (worst, slept_at, 600.0 / start.elapsed().as_secs_f64())
}

/// Measurement, not a check: J6 across solver settings.
/// Run: `cargo test -p tumble --test ragdoll -- --ignored --nocapture`.
#[test]
#[ignore = "measurement: prints J6 across solver settings"]
fn measure_ragdoll_across_settings() {
    use tumble::SolverSettings;
    let s = |substeps, joint_hertz, contact_hertz, iterations| SolverSettings {
        substeps,
        joint_hertz,
        contact_hertz,
        solve_iterations: iterations,
        relax_iterations: iterations,
        ..Default::default()
    };
    for (name, settings) in [
        ("defaults", SolverSettings::default()),
        ("4 substeps, 2+2 it", s(4, 60.0, 30.0, 2)),
        ("8 substeps, joint 120 Hz", s(8, 120.0, 30.0, 1)),
        ("8 substeps, joint 120 Hz, contact 120 Hz, 2+2 it", s(8, 120.0, 120.0, 2)),
        ("16 substeps, joint 240 Hz", s(16, 240.0, 30.0, 1)),
        ("16 substeps, joint 240 Hz, contact 240 Hz", s(16, 240.0, 240.0, 1)),
    ] {
        let (worst, slept, rate) = ragdoll_run(settings);
        println!(
            "J6 [{name}]: largest joint separation {:.3} mm, asleep after {slept:?} s, {rate:.0} steps/s",
            1e3 * worst
        );
    }
}
