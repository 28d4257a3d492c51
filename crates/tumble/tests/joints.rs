//! Joint validation: VALIDATION.md J1–J4 (J5 is in `joint_features.rs`). Each test prints its
//! measurement next to the analytic value.

use std::f64::consts::{PI, TAU};
use tumble::{
    BallJoint, BodyDef, BodyId, BodyKind, Capsule, Cuboid, Cylinder, DQuat, DVec3, HingeJoint, JointDef,
    JointKind, Shape, SolverSettings, Sphere, World, WorldDef,
};

mod common;
use common::{mean_interval, sign_changes, slope};

fn static_body(world: &mut World, position: DVec3) -> BodyId {
    world
        .add_body(BodyDef { name: "ground".into(), kind: BodyKind::Static, position, ..Default::default() })
        .unwrap()
}

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

/// J2: a rod (box 0.05 × 0.05 × 1 m) hanging from a hinge at its top end swings with the period
/// of the compound pendulum `2π√(I_pivot/(m g d))` within 0.5% (3° amplitude).
#[test]
fn j2_compound_pendulum_period() {
    let mut world = World::default();
    let g = 9.81;
    let (width, length) = (0.05, 1.0);
    let pivot_point = DVec3::new(0.0, 0.0, 2.0);
    let pivot = static_body(&mut world, pivot_point);
    let theta0 = 3.0_f64.to_radians();
    let orientation = DQuat::from_rotation_y(theta0);
    let rod = world
        .add_body(BodyDef {
            name: "rod".into(),
            shape: Some(Shape::Cuboid(
                Cuboid::new(DVec3::new(width / 2.0, width / 2.0, length / 2.0)).unwrap(),
            )),
            position: pivot_point + orientation * DVec3::new(0.0, 0.0, -length / 2.0),
            orientation,
            ..Default::default()
        })
        .unwrap();
    let hinge =
        JointDef::new(pivot, rod, pivot_point, JointKind::Hinge(HingeJoint::default())).with_axis(DVec3::Y);
    let joint = world.add_joint(hinge).unwrap();

    let dt = 1.0 / 60.0;
    let (mut times, mut xs) = (vec![], vec![]);
    let mut max_error: f64 = 0.0;
    for n in 1..=1800 {
        world.step(dt).unwrap();
        times.push(f64::from(n) * dt);
        xs.push(world.body(rod).unwrap().com_world().x);
        max_error = max_error.max(world.joint_separation(joint).unwrap().length());
    }
    let period = 2.0 * mean_interval(&sign_changes(&times, &xs));
    // Box about its centre, axis along y: m (w² + L²)/12; parallel axis to the end: + m (L/2)².
    let d = length / 2.0;
    let i_pivot_over_m = (width * width + length * length) / 12.0 + d * d;
    let analytic = TAU * (i_pivot_over_m / (g * d)).sqrt();
    let corrected = analytic * (1.0 + theta0 * theta0 / 16.0);
    let error = (period - analytic) / analytic;
    println!(
        "J2: period {period:.5} s, 2π√(I/(mgd)) = {analytic:.5} s ({:+.3}%), amplitude-corrected {corrected:.5} s ({:+.3}%), joint error {max_error:.2e} m",
        100.0 * error,
        100.0 * (period - corrected) / corrected
    );
    assert!(error.abs() < 0.005, "period error {:.3}%", 100.0 * error);
    assert!(max_error < 1e-4, "joint separation {max_error} m");
}

/// J3: a disc spinning fast about its symmetry axis, held horizontal by a ball joint on that axis
/// at distance d from its centre, precesses at `Ω = m g d / (I₃ ω₃)` within 2%. The disc starts
/// with the precession already under way (so there is little nutation); Ω is the slope of the
/// centre's azimuth about the pivot.
#[test]
fn j3_gyroscope_precession() {
    let mut world = World::default();
    let g = 9.81;
    let (radius, half_height, d, spin) = (0.2, 0.02, 0.2, 150.0);
    let pivot_point = DVec3::new(0.0, 0.0, 1.0);
    let pivot = static_body(&mut world, pivot_point);
    // Axis-horizontal top at θ = 90°: steady precession needs m g d = I₃ ω₃ Ω exactly (the Ω² term
    // of the heavy top carries cos θ).
    let i3_over_m = 0.5 * radius * radius;
    let omega = g * d / (i3_over_m * spin);
    let center = pivot_point + DVec3::new(d, 0.0, 0.0);
    let disc = world
        .add_body(BodyDef {
            name: "disc".into(),
            shape: Some(Shape::Cylinder(Cylinder::new(radius, half_height).unwrap())),
            position: center,
            // The cylinder's axis is its local Z; turn it onto world X.
            orientation: DQuat::from_rotation_arc(DVec3::Z, DVec3::X),
            angular_velocity: DVec3::new(spin, 0.0, omega),
            linear_velocity: DVec3::new(0.0, omega * d, 0.0),
            ..Default::default()
        })
        .unwrap();
    let joint = world
        .add_joint(
            JointDef::new(pivot, disc, pivot_point, JointKind::Ball(BallJoint::new())).with_axis(DVec3::X),
        )
        .unwrap();

    let dt = 1.0 / 60.0;
    let (mut times, mut azimuths) = (vec![], vec![]);
    let (mut previous, mut unwrapped) = (0.0_f64, 0.0_f64);
    let (mut max_error, mut max_dip): (f64, f64) = (0.0, 0.0);
    for n in 1..=300 {
        world.step(dt).unwrap();
        let r = world.body(disc).unwrap().com_world() - pivot_point;
        let azimuth = r.y.atan2(r.x);
        unwrapped += (azimuth - previous + PI).rem_euclid(TAU) - PI;
        previous = azimuth;
        let t = f64::from(n) * dt;
        max_error = max_error.max(world.joint_separation(joint).unwrap().length());
        max_dip = max_dip.max((r.z / d).asin().abs());
        if t >= 0.5 {
            times.push(t);
            azimuths.push(unwrapped);
        }
    }
    let measured = slope(&times, &azimuths);
    let error = (measured - omega) / omega;
    println!(
        "J3: precession {measured:.5} rad/s, m g d/(I₃ ω₃) = {omega:.5} rad/s ({:+.3}%), largest dip of the axis {:.2}°, joint error largest {max_error:.2e} m, final {:.2e} m",
        100.0 * error,
        max_dip.to_degrees(),
        world.joint_separation(joint).unwrap().length()
    );
    assert!(error.abs() < 0.02, "precession error {:.3}%", 100.0 * error);
}

/// A hanging chain of 20 capsules on ball joints with a weight of 100 link masses at the end,
/// nudged sideways; returns the largest joint separation at the end of 10 s.
/// (final largest separation, largest over the last 2 s, largest joint index at the end)
fn heavy_chain(settings: SolverSettings, nudge: f64) -> (f64, f64, usize) {
    let mut world = World::new(WorldDef { solver: settings, ..Default::default() }).unwrap();
    let (links, radius, half_height) = (20, 0.05, 0.2);
    let link_length = 2.0 * (half_height + radius);
    let top = DVec3::new(0.0, 0.0, 12.0);
    let ceiling = static_body(&mut world, top);
    let mut previous = ceiling;
    let mut joints = vec![];
    let mut link_mass = 0.0;
    for i in 0..links {
        let anchor = top - DVec3::Z * (link_length * f64::from(i));
        let link = world
            .add_body(BodyDef {
                name: format!("link {i}"),
                shape: Some(Shape::Capsule(Capsule::new(radius, half_height).unwrap())),
                position: anchor - DVec3::Z * (link_length / 2.0),
                ..Default::default()
            })
            .unwrap();
        link_mass = world.body(link).unwrap().mass();
        joints.push(
            world
                .add_joint(JointDef::new(previous, link, anchor, JointKind::Ball(BallJoint::new())))
                .unwrap(),
        );
        previous = link;
    }
    let bottom = top - DVec3::Z * (link_length * f64::from(links));
    let weight_radius = 0.2;
    let weight = world
        .add_body(BodyDef {
            name: "weight".into(),
            shape: Some(Shape::Sphere(Sphere::new(weight_radius).unwrap())),
            mass: Some(100.0 * link_mass),
            position: bottom - DVec3::Z * weight_radius,
            linear_velocity: DVec3::new(nudge, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap();
    joints.push(
        world.add_joint(JointDef::new(previous, weight, bottom, JointKind::Ball(BallJoint::new()))).unwrap(),
    );

    let largest = |world: &World| {
        joints
            .iter()
            .enumerate()
            .map(|(i, &j)| (world.joint_separation(j).unwrap().length(), i))
            .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
    };
    let mut late: f64 = 0.0;
    for n in 0..600 {
        world.step(1.0 / 60.0).unwrap();
        if n >= 480 {
            late = late.max(largest(&world).0);
        }
    }
    let (last, index) = largest(&world);
    (last, late, index)
}

/// J4: the heavy chain stays together to 1 mm after 10 s at dt = 1/60, at the default settings.
///
/// The chain is a tree of joints, so its rows are solved exactly in every pass (`joint_trees`):
/// the stretch is only what the position drift leaves, 3e-4 mm. For comparison the test also runs
/// it row by row (`joint_trees: false`): a soft joint is then a spring of stiffness `k = m_eff ω²`
/// (ω = 2π·joint_hertz, `m_eff = m/2` between two links), and joint 1, carrying 19 links and the
/// weight (`F = 119 m g`), stretches by `238 g/ω²` = 4.1 mm at 120 Hz however many iterations run.
#[test]
fn j4_heavy_chain_holds_together() {
    let g = 9.81;
    let predicted = |hertz: f64| 238.0 * g / (TAU * hertz).powi(2);
    let defaults = SolverSettings::default();
    let (end, late, index) = heavy_chain(defaults.clone(), 0.3);
    let row_by_row = SolverSettings { joint_trees: false, ..Default::default() };
    let (_, rows_late, _) = heavy_chain(row_by_row, 0.3);
    println!(
        "J4: largest joint separation at 10 s: {:.2e} mm at joint {index} (largest over the last 2 s: {:.2e} mm); row by row: {:.3} mm over the last 2 s (soft equilibrium 238 g/ω² = {:.3} mm)",
        1e3 * end,
        1e3 * late,
        1e3 * rows_late,
        1e3 * predicted(defaults.joint_hertz),
    );
    assert!(late < 1e-3, "separation {late} m");
    // Row by row the chain sags to the soft joints' equilibrium (within 20%), which the tree
    // solve removes.
    let sag = rows_late / predicted(defaults.joint_hertz);
    assert!((0.8..1.2).contains(&sag), "row-by-row stretch {rows_late} m");
}

/// The 100-link `chain` scene swinging down from horizontal at 2 substeps of 1/120 s: the tip
/// whips past 40 m/s, and each substep's straight-line position stage carries its joints off
/// their arcs by up to centimetres. The joint trees' position projection puts them back every
/// substep, so the largest separation over the whole run stays within √3 times its tolerance
/// (0.1 mm, which bounds each of a ball joint's three rows); with the projection off, the same drift is only fed back through the velocities
/// and the chain comes apart by decimetres.
#[test]
fn whipping_chain_stays_within_the_projection_tolerance() {
    let run = |iterations: u32| {
        let mut scene = tumble::scenes::by_name("chain", None).unwrap();
        let settings = SolverSettings {
            substeps: 2,
            joint_projection_iterations: iterations,
            ..scene.world.solver_settings().clone()
        };
        scene.world.set_solver_settings(settings).unwrap();
        for _ in 0..scene.steps {
            scene.step();
        }
        scene.quality().metrics[0].value()
    };
    let (projected, unprojected) = (run(SolverSettings::default().joint_projection_iterations), run(0));
    println!(
        "chain at 2 substeps, largest joint separation: {projected:.2e} m projected, {unprojected:.3} m not"
    );
    let tolerance = SolverSettings::default().joint_projection_tolerance;
    assert!(projected <= 3.0_f64.sqrt() * tolerance, "{projected} m");
    assert!(unprojected > 0.1, "{unprojected} m");
}

/// A chain of ten capsules on ball joints (a joint tree), thrown flat onto the ground from 0.3 m
/// with its links flung sideways at up to 1 m/s: the exact tree rows and the contacts under every
/// link must settle together — it comes to rest on the ground, still in one piece, and falls
/// asleep within 5 s.
#[test]
fn tree_jointed_chain_settles_on_the_ground_and_sleeps() {
    let mut world = World::new(WorldDef::default()).unwrap();
    world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(20.0, 20.0, 0.5)).unwrap())),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        })
        .unwrap();
    let (radius, half_height) = (0.05, 0.2);
    let link_length = 2.0 * half_height + 2.0 * radius;
    let along_x = DQuat::from_rotation_y(PI / 2.0);
    let mut previous = None;
    let mut joints = vec![];
    let mut links = vec![];
    for i in 0..10 {
        let x = link_length * f64::from(i);
        let link = world
            .add_body(BodyDef {
                shape: Some(Shape::Capsule(Capsule::new(radius, half_height).unwrap())),
                position: DVec3::new(x, 0.0, 0.3),
                orientation: along_x,
                linear_velocity: DVec3::new(0.0, f64::from(i).sin(), 0.0),
                ..Default::default()
            })
            .unwrap();
        if let Some(p) = previous {
            let anchor = DVec3::new(x - 0.5 * link_length, 0.0, 0.3);
            joints.push(
                world.add_joint(JointDef::new(p, link, anchor, JointKind::Ball(BallJoint::new()))).unwrap(),
            );
        }
        previous = Some(link);
        links.push(link);
    }
    let mut asleep_at = None;
    let mut largest_separation: f64 = 0.0;
    for n in 0..300 {
        world.step(1.0 / 60.0).unwrap();
        for &j in &joints {
            largest_separation = largest_separation.max(world.joint_separation(j).unwrap().length());
        }
        if asleep_at.is_none() && links.iter().all(|&l| !world.body(l).unwrap().is_awake()) {
            asleep_at = Some(n);
        }
    }
    let speed = links.iter().map(|&l| world.body(l).unwrap().linear_velocity().length()).fold(0.0, f64::max);
    println!("chain on the ground: asleep after {asleep_at:?} steps, largest separation {largest_separation:.6e} m, fastest link {speed:.2e} m/s");
    assert!(asleep_at.is_some_and(|n| n < 300), "still awake after 5 s");
    assert!(largest_separation < 1e-3, "{largest_separation} m");
    let lowest = links.iter().map(|&l| world.body(l).unwrap().com_world().z).fold(f64::INFINITY, f64::min);
    assert!((lowest - radius).abs() < 2e-3, "lowest link centre at {lowest} m");
}

/// A free chain of six links on ball joints and hinges, thrown spinning and whipping in zero
/// gravity: nothing outside acts on it, so its momentum and its angular momentum about its centre
/// of mass stay what they were. Momentum holds to round-off. Angular momentum drifts only by the
/// moments of the joint impulses across the errors the position projection leaves (at most its
/// tolerance, 0.1 mm): 1.3e-5 over ten seconds, 1.3e-9 with a tolerance of 1e-8 m. Regression:
/// the projection moved the links back onto their joints without touching their velocities,
/// which took `Σ m Δx × v` from the spin every substep, 0.36% of it over the ten seconds; each
/// free figure now gets it back as one rigid spin.
#[test]
fn a_free_spinning_chain_keeps_its_momenta() {
    let run = |tolerance: f64| {
        let solver = SolverSettings { joint_projection_tolerance: tolerance, ..Default::default() };
        let mut world = World::new(WorldDef { gravity: DVec3::ZERO, solver, ..Default::default() }).unwrap();
        let mut previous = None;
        for k in 0..6 {
            let x = 0.5 * k as f64;
            let link = world
                .add_body(BodyDef {
                    shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.25, 0.05, 0.05)).unwrap())),
                    position: DVec3::new(x, 0.0, 0.0),
                    linear_velocity: DVec3::new(0.0, 0.3 * k as f64, 0.1),
                    angular_velocity: DVec3::new(0.5, 1.0 + k as f64, -0.5 * k as f64),
                    ..Default::default()
                })
                .unwrap();
            if let Some(previous) = previous {
                let kind = if k % 2 == 0 {
                    JointKind::Hinge(HingeJoint::default())
                } else {
                    JointKind::Ball(BallJoint::default())
                };
                let joint = JointDef::new(previous, link, DVec3::new(x - 0.25, 0.0, 0.0), kind);
                world.add_joint(joint.with_axis(DVec3::new(0.0, 0.3, 1.0).normalize())).unwrap();
            }
            previous = Some(link);
        }
        // The joints take up the velocities that pull them apart in the first steps.
        for _ in 0..6 {
            world.step(1.0 / 60.0).unwrap();
        }
        let (p0, l0) = (world.linear_momentum(), world.angular_momentum_about_com());
        let (mut p_error, mut l_error) = (0.0_f64, 0.0_f64);
        for _ in 0..600 {
            world.step(1.0 / 60.0).unwrap();
            p_error = p_error.max((world.linear_momentum() - p0).length() / p0.length());
            l_error = l_error.max((world.angular_momentum_about_com() - l0).length() / l0.length());
        }
        (p_error, l_error)
    };
    let (p_error, l_error) = run(1e-4);
    let (_, l_error_tight) = run(1e-8);
    println!(
        "free spinning chain over 10 s: momentum {p_error:.1e}, angular momentum {l_error:.1e} \
         ({l_error_tight:.1e} at a projection tolerance of 1e-8 m)"
    );
    assert!(p_error < 1e-13, "momentum {p_error:e}");
    assert!(l_error < 1e-4, "angular momentum {l_error:e}");
    assert!(l_error_tight < 1e-8, "angular momentum at the tight tolerance {l_error_tight:e}");
}
