//! Joint features, VALIDATION.md J5: limits hold (0.5°, 1 mm), motors reach their speed (1%),
//! springs ring at their frequency (2%); the fixed joint holds a cantilever (1 mm); distance
//! joints are rigid, ropes or springs. Each test prints what it measured. Breaking and bad input
//! are in `joint_api.rs`.

use tumble::{
    BallJoint, BodyDef, BodyId, BodyKind, Cuboid, Cylinder, DVec3, DistanceJoint, FixedJoint, HingeJoint,
    JointDef, JointKind, Limits, Motor, Shape, SliderJoint, Sphere, SpringSettings, World,
};

mod common;
use common::{mean_interval, sign_changes};

const DT: f64 = 1.0 / 60.0;
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

/// A disc about the vertical axis (gravity does not turn it).
fn disc() -> Shape {
    Shape::Cylinder(Cylinder::new(0.3, 0.05).unwrap())
}

/// Steps for `seconds`, calling `sample(world, t)` after every step.
fn run(world: &mut World, seconds: f64, mut sample: impl FnMut(&World, f64)) {
    let steps = (seconds / DT).round() as u32;
    for n in 1..=steps {
        world.step(DT).unwrap();
        sample(world, f64::from(n) * DT);
    }
}

/// Period of an oscillating signal from its sign changes.
fn period_of(times: &[f64], values: &[f64]) -> f64 {
    2.0 * mean_interval(&sign_changes(times, values))
}

// ---- limits ---------------------------------------------------------------------------------

/// A horizontal rod on a hinge falls under gravity into its upper limit (0.6 rad) and stays there.
#[test]
fn j5_hinge_limit_holds_a_falling_rod() {
    let mut world = World::default();
    let pivot = DVec3::new(0.0, 0.0, 1.0);
    let ground = static_body(&mut world, pivot);
    let rod_shape = Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 0.025, 0.025)).unwrap());
    let rod = dynamic_body(&mut world, "rod", rod_shape, pivot + DVec3::new(0.5, 0.0, 0.0));
    let limits = Limits::new(-0.3, 0.6);
    let hinge = HingeJoint { limits: Some(limits), ..Default::default() };
    let joint = world
        .add_joint(JointDef::new(ground, rod, pivot, JointKind::Hinge(hinge)).with_axis(DVec3::Y))
        .unwrap();
    let mut max_angle = f64::NEG_INFINITY;
    run(&mut world, 3.0, |w, _| max_angle = max_angle.max(w.joint_angle(joint).unwrap()));
    let end = world.joint_angle(joint).unwrap();
    println!(
        "J5 hinge limit (gravity): upper {:.4} rad, largest angle {max_angle:.4} rad (over by {:.3}°), final {end:.4} rad",
        limits.upper,
        (max_angle - limits.upper).to_degrees()
    );
    assert!(max_angle <= limits.upper + 0.5_f64.to_radians());
    assert!((end - limits.upper).abs() < 0.5_f64.to_radians());
}

/// A motor drives a disc on a vertical hinge into its lower limit; the limit wins (the motor is
/// weaker than the limit is stiff) within 0.5°.
#[test]
fn j5_hinge_limit_holds_against_a_motor() {
    let mut world = World::default();
    let ground = static_body(&mut world, DVec3::ZERO);
    let wheel = dynamic_body(&mut world, "wheel", disc(), DVec3::new(0.0, 0.0, 1.0));
    let limits = Limits::new(-1.0, 1.0);
    let hinge =
        HingeJoint { limits: Some(limits), motor: Some(Motor::new(-3.0, 20.0)), ..Default::default() };
    let joint = world
        .add_joint(JointDef::new(ground, wheel, DVec3::new(0.0, 0.0, 1.0), JointKind::Hinge(hinge)))
        .unwrap();
    let mut min_angle = f64::INFINITY;
    run(&mut world, 3.0, |w, _| min_angle = min_angle.min(w.joint_angle(joint).unwrap()));
    let end = world.joint_angle(joint).unwrap();
    println!(
        "J5 hinge limit (motor): lower {:.4} rad, smallest angle {min_angle:.4} rad (past by {:.3}°), final {end:.4} rad",
        limits.lower,
        (limits.lower - min_angle).to_degrees()
    );
    assert!(min_angle >= limits.lower - 0.5_f64.to_radians());
    assert!((end - limits.lower).abs() < 0.5_f64.to_radians());
}

/// A box on a vertical slider falls 0.5 m onto its lower limit; another is pushed up into its
/// upper limit by a motor. Both stop within 1 mm.
#[test]
fn j5_slider_limits_hold() {
    let mut world = World::default();
    let start = DVec3::new(0.0, 0.0, 2.0);
    let ground = static_body(&mut world, DVec3::ZERO);
    let falling = dynamic_body(&mut world, "falling", cube(0.1), start);
    let lifted = dynamic_body(&mut world, "lifted", cube(0.1), start + DVec3::X);
    let falling_slider = SliderJoint { limits: Some(Limits::new(-0.5, 0.5)), ..Default::default() };
    // 8 kg box: 500 N lifts it against its 78 N weight.
    let lifted_slider = SliderJoint {
        limits: Some(Limits::new(-0.5, 0.3)),
        motor: Some(Motor::new(2.0, 500.0)),
        ..Default::default()
    };
    let j_fall =
        world.add_joint(JointDef::new(ground, falling, start, JointKind::Slider(falling_slider))).unwrap();
    let j_lift = world
        .add_joint(JointDef::new(ground, lifted, start + DVec3::X, JointKind::Slider(lifted_slider)))
        .unwrap();
    let (mut lowest, mut highest) = (f64::INFINITY, f64::NEG_INFINITY);
    run(&mut world, 3.0, |w, _| {
        lowest = lowest.min(w.joint_translation(j_fall).unwrap());
        highest = highest.max(w.joint_translation(j_lift).unwrap());
    });
    let (end_fall, end_lift) =
        (world.joint_translation(j_fall).unwrap(), world.joint_translation(j_lift).unwrap());
    println!(
        "J5 slider limits: fell to {lowest:.5} m (limit -0.5, final {end_fall:.5}); motor pushed to {highest:.5} m (limit 0.3, final {end_lift:.5})"
    );
    assert!(lowest >= -0.5 - 1e-3 && (end_fall + 0.5).abs() < 1e-3);
    assert!(highest <= 0.3 + 1e-3 && (end_lift - 0.3).abs() < 1e-3);
    // The slider kept the box upright and on its line.
    let sideways = world.joint_separation(j_fall).unwrap().truncate().length();
    assert!(sideways < 1e-4, "off the axis by {sideways} m");
}

/// A rod on a ball joint thrown sideways stays inside its 0.5 rad cone; a disc spun about the
/// joint axis stays inside its ±0.4 rad twist range. Both within 0.5°.
#[test]
fn j5_ball_swing_and_twist_limits_hold() {
    let mut world = World::default();
    let pivot = DVec3::new(0.0, 0.0, 2.0);
    let ground = static_body(&mut world, pivot);
    let rod = world
        .add_body(BodyDef {
            name: "rod".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.025, 0.025, 0.5)).unwrap())),
            position: pivot - DVec3::new(0.0, 0.0, 0.5),
            // Swinging about the pivot: v = ω × (x − pivot). Enough energy for a 1.1 rad swing.
            angular_velocity: DVec3::new(4.0, 1.0, 0.0),
            linear_velocity: DVec3::new(4.0, 1.0, 0.0).cross(DVec3::new(0.0, 0.0, -0.5)),
            ..Default::default()
        })
        .unwrap();
    let (cone, twist) = (0.5, Limits::new(-0.4, 0.4));
    // The joint axis points down the rod: the swing is the rod's angle from the vertical.
    let ball = BallJoint { swing_limit: Some(cone), ..Default::default() };
    let j_cone = world
        .add_joint(JointDef::new(ground, rod, pivot, JointKind::Ball(ball)).with_axis(-DVec3::Z))
        .unwrap();

    let top = pivot + DVec3::X * 2.0;
    let wheel = world
        .add_body(BodyDef {
            name: "wheel".into(),
            shape: Some(disc()),
            position: top - DVec3::Z * 0.2,
            angular_velocity: DVec3::new(0.0, 0.0, 4.0),
            ..Default::default()
        })
        .unwrap();
    let ball = BallJoint { swing_limit: Some(0.3), twist_limits: Some(twist), ..Default::default() };
    let j_twist = world.add_joint(JointDef::new(ground, wheel, top, JointKind::Ball(ball))).unwrap();

    let (mut max_swing, mut max_twist, mut min_twist) = (0.0_f64, f64::NEG_INFINITY, f64::INFINITY);
    let mut max_separation: f64 = 0.0;
    run(&mut world, 4.0, |w, _| {
        let (j, a, b) = (w.joint(j_cone).unwrap(), w.body(ground).unwrap(), w.body(rod).unwrap());
        max_swing = max_swing.max(j.swing_angle(a, b));
        let t = w.joint_angle(j_twist).unwrap();
        (max_twist, min_twist) = (max_twist.max(t), min_twist.min(t));
        max_separation = max_separation.max(w.joint_separation(j_cone).unwrap().length());
    });
    println!(
        "J5 ball limits: largest swing {max_swing:.4} rad (cone {cone}, over by {:.3}°); twist in [{min_twist:.4}, {max_twist:.4}] (limits ±0.4); joint error {:.3} mm",
        (max_swing - cone).max(0.0).to_degrees(),
        1e3 * max_separation
    );
    assert!(max_swing > cone - 0.05, "the throw reaches the cone");
    assert!(max_swing <= cone + 0.5_f64.to_radians());
    assert!(max_twist > 0.35, "the spin reaches the twist limit");
    assert!(
        max_twist <= twist.upper + 0.5_f64.to_radians() && min_twist >= twist.lower - 0.5_f64.to_radians()
    );
}

// ---- motors ---------------------------------------------------------------------------------

/// A hinge motor with a torque cap accelerates a disc at `τ/I` and then holds the target speed.
#[test]
fn j5_hinge_motor_reaches_its_speed() {
    let mut world = World::default();
    let ground = static_body(&mut world, DVec3::ZERO);
    let anchor = DVec3::new(0.0, 0.0, 1.0);
    let wheel = dynamic_body(&mut world, "wheel", disc(), anchor);
    let (target, torque) = (5.0, 2.0);
    let hinge = HingeJoint { motor: Some(Motor::new(target, torque)), ..Default::default() };
    let joint = world.add_joint(JointDef::new(ground, wheel, anchor, JointKind::Hinge(hinge))).unwrap();
    let inertia = world.body(wheel).unwrap().inertia_principal().z;
    let mut speed_at_1s = 0.0;
    run(&mut world, 6.0, |w, t| {
        if (t - 1.0).abs() < 1e-9 {
            speed_at_1s = w.joint_angular_speed(joint).unwrap();
        }
    });
    let speed = world.joint_angular_speed(joint).unwrap();
    let ramp = torque / inertia;
    println!(
        "J5 hinge motor: speed {speed:.5} rad/s for target {target} ({:+.4}%); at 1 s {speed_at_1s:.5} rad/s, τ t/I = {ramp:.5} ({:+.4}%)",
        100.0 * (speed - target) / target,
        100.0 * (speed_at_1s - ramp) / ramp
    );
    assert!(((speed - target) / target).abs() < 0.01);
    assert!(((speed_at_1s - ramp) / ramp).abs() < 0.01);
}

/// A slider motor with a force cap accelerates a box at `F/m` and then holds the target speed.
#[test]
fn j5_slider_motor_reaches_its_speed() {
    let mut world = World::default();
    let ground = static_body(&mut world, DVec3::ZERO);
    let start = DVec3::new(0.0, 0.0, 1.0);
    let block = dynamic_body(&mut world, "block", cube(0.1), start);
    let (target, force) = (1.5, 20.0);
    let slider = SliderJoint { motor: Some(Motor::new(target, force)), ..Default::default() };
    let joint = world
        .add_joint(JointDef::new(ground, block, start, JointKind::Slider(slider)).with_axis(DVec3::X))
        .unwrap();
    let mass = world.body(block).unwrap().mass();
    let mut speed_at_quarter = 0.0;
    run(&mut world, 3.0, |w, t| {
        if (t - 0.25).abs() < 1e-9 {
            speed_at_quarter = w.joint_linear_speed(joint).unwrap();
        }
    });
    let speed = world.joint_linear_speed(joint).unwrap();
    let ramp = force / mass * 0.25;
    println!(
        "J5 slider motor: speed {speed:.5} m/s for target {target} ({:+.4}%); at 0.25 s {speed_at_quarter:.5} m/s, F t/m = {ramp:.5} ({:+.4}%)",
        100.0 * (speed - target) / target,
        100.0 * (speed_at_quarter - ramp) / ramp
    );
    assert!(((speed - target) / target).abs() < 0.01);
    assert!(((speed_at_quarter - ramp) / ramp).abs() < 0.01);
}

// ---- springs --------------------------------------------------------------------------------

/// Undamped joint springs ring at their `hertz` (slider, hinge, distance) within 2%.
#[test]
fn j5_springs_ring_at_their_frequency() {
    let mut world = World::default();
    let ground = static_body(&mut world, DVec3::ZERO);

    let slider_start = DVec3::new(0.0, 0.0, 1.0);
    let block = world
        .add_body(BodyDef {
            name: "block".into(),
            shape: Some(cube(0.1)),
            position: slider_start,
            linear_velocity: DVec3::new(0.5, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap();
    let slider_hertz = 2.0;
    let slider = SliderJoint { spring: Some(SpringSettings::new(slider_hertz, 0.0)), ..Default::default() };
    let j_slider = world
        .add_joint(JointDef::new(ground, block, slider_start, JointKind::Slider(slider)).with_axis(DVec3::X))
        .unwrap();

    let hinge_anchor = DVec3::new(2.0, 0.0, 1.0);
    let wheel = world
        .add_body(BodyDef {
            name: "wheel".into(),
            shape: Some(disc()),
            position: hinge_anchor,
            angular_velocity: DVec3::new(0.0, 0.0, 1.0),
            ..Default::default()
        })
        .unwrap();
    let hinge_hertz = 1.5;
    let hinge = HingeJoint { spring: Some(SpringSettings::new(hinge_hertz, 0.0)), ..Default::default() };
    let j_hinge =
        world.add_joint(JointDef::new(ground, wheel, hinge_anchor, JointKind::Hinge(hinge))).unwrap();

    // A ball hanging on a distance spring from a point 1 m above it: gravity moves the rest point
    // (by g/ω²) but not the frequency.
    let top = DVec3::new(4.0, 0.0, 3.0);
    let bob = dynamic_body(&mut world, "bob", Shape::Sphere(Sphere::new(0.1).unwrap()), top - DVec3::Z);
    let distance_hertz = 2.5;
    let j_distance = world
        .add_joint(JointDef {
            anchor_b_world: Some(top - DVec3::Z),
            ..JointDef::new(ground, bob, top, JointKind::Distance(DistanceJoint::spring(distance_hertz, 0.0)))
        })
        .unwrap();
    let rest = 1.0 + G / (std::f64::consts::TAU * distance_hertz).powi(2);

    let (mut times, mut x, mut angle, mut stretch) = (vec![], vec![], vec![], vec![]);
    run(&mut world, 6.0, |w, t| {
        times.push(t);
        x.push(w.joint_translation(j_slider).unwrap());
        angle.push(w.joint_angle(j_hinge).unwrap());
        stretch.push(w.joint_separation(j_distance).unwrap().length() - rest);
    });
    for (what, signal, hertz) in
        [("slider", &x, slider_hertz), ("hinge", &angle, hinge_hertz), ("distance", &stretch, distance_hertz)]
    {
        let period = period_of(&times, signal);
        let error = period * hertz - 1.0;
        println!(
            "J5 {what} spring: period {period:.5} s, 1/hertz = {:.5} s ({:+.3}%)",
            1.0 / hertz,
            100.0 * error
        );
        assert!(error.abs() < 0.02, "{what} spring period off by {:.3}%", 100.0 * error);
    }
}

// ---- fixed and distance joints ------------------------------------------------------------------

/// A 1 m beam welded at one end to a wall sags less than 1 mm at its tip.
#[test]
fn j5_fixed_joint_holds_a_cantilever() {
    let mut world = World::default();
    let root = DVec3::new(0.0, 0.0, 1.0);
    let wall = static_body(&mut world, DVec3::ZERO);
    let beam_shape = Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 0.05, 0.05)).unwrap());
    let beam = dynamic_body(&mut world, "beam", beam_shape, root + DVec3::new(0.5, 0.0, 0.0));
    let joint =
        world.add_joint(JointDef::new(wall, beam, root, JointKind::Fixed(FixedJoint::new()))).unwrap();
    let tip = |w: &World| w.body(beam).unwrap().transform().transform_point(DVec3::new(0.5, 0.0, 0.0));
    let tip_start = tip(&world);
    let mut worst: f64 = 0.0;
    run(&mut world, 5.0, |w, t| {
        if t > 1.0 {
            worst = worst.max((tip(w) - tip_start).length());
        }
    });
    let separation = world.joint_separation(joint).unwrap().length();
    println!(
        "J5 fixed joint: tip moved {:.4} mm (largest after 1 s {:.4} mm), anchor separation {:.4} mm",
        1e3 * (tip(&world) - tip_start).length(),
        1e3 * worst,
        1e3 * separation
    );
    assert!(worst < 1e-3, "tip sag {worst} m");
}

/// A rigid distance joint keeps a swinging ball at 1 m to 1 mm.
#[test]
fn j5_distance_joint_is_rigid() {
    let mut world = World::default();
    let pivot = DVec3::new(0.0, 0.0, 2.0);
    let ground = static_body(&mut world, pivot);
    let angle = 30.0_f64.to_radians();
    let start = pivot + DVec3::new(angle.sin(), 0.0, -angle.cos());
    let bob = dynamic_body(&mut world, "bob", Shape::Sphere(Sphere::new(0.1).unwrap()), start);
    let def = JointDef {
        anchor_b_world: Some(start),
        ..JointDef::new(ground, bob, pivot, JointKind::Distance(DistanceJoint::rigid()))
    };
    let joint = world.add_joint(def).unwrap();
    let mut worst: f64 = 0.0;
    run(&mut world, 5.0, |w, _| worst = worst.max((w.joint_separation(joint).unwrap().length() - 1.0).abs()));
    println!("J5 rigid distance: largest length error {:.4} mm", 1e3 * worst);
    assert!(worst < 1e-3);
}

/// A rope lets a ball fall freely until it is taut, then holds it at its length to 1 mm.
#[test]
fn j5_distance_joint_rope() {
    let mut world = World::default();
    let pivot = DVec3::new(0.0, 0.0, 3.0);
    let ground = static_body(&mut world, pivot);
    let start = pivot - DVec3::new(0.0, 0.0, 0.5);
    let bob = dynamic_body(&mut world, "bob", Shape::Sphere(Sphere::new(0.1).unwrap()), start);
    let def = JointDef {
        anchor_b_world: Some(start),
        ..JointDef::new(ground, bob, pivot, JointKind::Distance(DistanceJoint::rope(1.0)))
    };
    let joint = world.add_joint(def).unwrap();
    // Slack for the first 0.3 s (it is taut at √(2·0.5/g) = 0.32 s): the ball falls as if free,
    // which for semi-implicit Euler with n substeps of h is z₀ − g h² n(n+1)/2.
    let h = DT / f64::from(world.solver_settings().substeps);
    let mut free_fall_error: f64 = 0.0;
    let mut longest: f64 = 0.0;
    run(&mut world, 4.0, |w, t| {
        let length = w.joint_separation(joint).unwrap().length();
        longest = longest.max(length);
        if t < 0.3 {
            let n = (t / h).round();
            let z = start.z - G * h * h * n * (n + 1.0) / 2.0;
            free_fall_error = free_fall_error.max((w.body(bob).unwrap().com_world().z - z).abs());
        }
    });
    let end = world.joint_separation(joint).unwrap().length();
    println!(
        "J5 rope: slack phase off free fall by {free_fall_error:.2e} m; longest {longest:.5} m, final {end:.5} m (rope 1 m)"
    );
    assert!(free_fall_error < 1e-9, "the slack rope pulled");
    assert!(longest < 1.0 + 1e-3 && (end - 1.0).abs() < 1e-3);
}

/// A carriage on a sprung slider (a joint the row-by-row solve keeps), down a slope from a rail
/// at its centre, with a link of its own mass welded to it (a tree of one joint), swinging under
/// gravity: the slider keeps the carriage on its axis and the weld keeps the link in place, both
/// within 1 mm, no speed exceeds the undamped oscillation's, and the spring's damping brings the
/// pair to rest. Regression: the tree's position projection moved the pair back onto the weld
/// alone, off the slider, whose rows pushed it off the weld again; the two corrections fed each
/// other: the carriage left its axis by 18 cm and reached 58 m/s (and, with the rail half a metre
/// above it, 10¹⁵⁰ m/s within three seconds).
#[test]
fn j5_a_welded_link_on_a_sprung_slider_comes_to_rest() {
    let mut world = World::default();
    let centre = DVec3::new(0.0, 0.0, 1.5);
    let rail = static_body(&mut world, centre);
    let link = || Shape::Cuboid(Cuboid::new(DVec3::new(0.3, 0.05, 0.05)).unwrap());
    let carriage = dynamic_body(&mut world, "carriage", link(), centre);
    let rider = dynamic_body(&mut world, "rider", link(), centre + DVec3::new(0.6, 0.0, 0.0));
    let axis = DVec3::new(0.0, 0.6, -0.8);
    let (hertz, target) = (2.0, 0.3);
    let spring = SpringSettings { hertz, damping_ratio: 0.2 };
    let slider = SliderJoint { spring: Some(spring), spring_target_position: target, ..Default::default() };
    let def = JointDef::new(rail, carriage, centre, JointKind::Slider(slider));
    world.add_joint(def.with_axis(axis)).unwrap();
    let weld = JointKind::Fixed(FixedJoint::new());
    world.add_joint(JointDef::new(carriage, rider, centre + DVec3::new(0.3, 0.0, 0.0), weld)).unwrap();

    // The spring is `hertz` for the carriage's mass m (the row acts at its centre) and carries
    // 2m: it swings at ω/√2 about `target` plus the sag 2g·0.8/ω², from rest at 0, so no speed
    // can exceed that amplitude times ω/√2.
    let omega = std::f64::consts::TAU * hertz;
    let amplitude = target + 2.0 * G * 0.8 / (omega * omega);
    let undamped_peak = amplitude * omega / 2f64.sqrt();
    let (mut off_axis, mut weld_error, mut peak, mut last_second) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    run(&mut world, 10.0, |world, t| {
        let (c, r) = (world.body(carriage).unwrap(), world.body(rider).unwrap());
        let moved = c.position() - centre;
        off_axis = off_axis.max((moved - moved.dot(axis) * axis).length());
        let welded = c.position() + c.orientation() * DVec3::new(0.6, 0.0, 0.0);
        weld_error = weld_error.max((r.position() - welded).length());
        let speed = c.linear_velocity().length();
        peak = peak.max(speed);
        if t > 9.0 {
            last_second = last_second.max(speed);
        }
    });
    println!(
        "J5 sprung slider with a welded link: off the axis {:.3} mm, weld {:.3} mm, peak speed {peak:.3} m/s \
         (undamped {undamped_peak:.3}), fastest in the last second {last_second:.2e} m/s",
        off_axis * 1e3,
        weld_error * 1e3
    );
    assert!(off_axis < 1e-3 && weld_error < 1e-3);
    assert!(peak < undamped_peak, "peak {peak} m/s");
    assert!(last_second < 1e-3 * peak, "still moving at {last_second} m/s");
}

/// Three free spheres of 50, 5 and 3.5 kg in zero gravity, spinning and tumbling, joined by two
/// ball joints at anchors off their centres, one with a swing limit it never reaches: nothing
/// acts on them but the joints, so their kinetic energy cannot grow (it may fall a little, as the
/// joints' soft corrections damp). Regression: with the free joint solved exactly in a joint tree
/// and the limited one row by row beside it, the two fought, and the energy grew from 1 J to
/// 10¹⁸ J in ten seconds; a figure another joint acts on is now solved row by row as a whole.
#[test]
fn j5_a_tree_beside_a_limited_joint_does_not_gain_energy() {
    let mut world = World::new(tumble::WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap();
    let mut sphere = |x: f64, radius: f64, mass: f64, v: DVec3| {
        world
            .add_body(BodyDef {
                shape: Some(Shape::Sphere(Sphere::new(radius).unwrap())),
                mass: Some(mass),
                position: DVec3::new(x, 0.0, 0.0),
                linear_velocity: v,
                angular_velocity: DVec3::new(0.3, -0.2, 0.5),
                ..Default::default()
            })
            .unwrap()
    };
    let heavy = sphere(-0.5, 0.25, 50.0, DVec3::new(0.0, 1.0, 0.3));
    let middle = sphere(0.0, 0.043, 5.0, DVec3::new(0.0, -1.0, 0.5));
    let light = sphere(0.5, 0.15, 3.5, DVec3::new(0.2, 1.0, -1.0));
    let free = JointKind::Ball(BallJoint::default());
    world.add_joint(JointDef::new(heavy, middle, DVec3::new(-0.2, 0.05, 0.0), free)).unwrap();
    let limited = JointKind::Ball(BallJoint { swing_limit: Some(3.0), ..Default::default() });
    world.add_joint(JointDef::new(middle, light, DVec3::new(0.2, -0.05, 0.0), limited)).unwrap();
    let kinetic = |world: &World| -> f64 {
        world
            .bodies()
            .map(|(_, b)| {
                let (v, w) = (b.linear_velocity(), b.angular_velocity());
                0.5 * b.mass() * v.length_squared() + 0.5 * w.dot(b.inertia_world() * w)
            })
            .sum()
    };
    // The joints take up the velocities that pull them apart in the first steps.
    run(&mut world, 0.1, |_, _| {});
    let start = kinetic(&world);
    let mut highest = start;
    run(&mut world, 10.0, |world, _| highest = highest.max(kinetic(world)));
    println!("J5 tree beside a limited joint: kinetic energy {start:.4} J, highest after {highest:.4} J");
    assert!(highest <= 1.001 * start, "{start} J -> {highest} J");
}
