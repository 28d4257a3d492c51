//! Free-motion validation: VALIDATION.md F1–F7.

mod common;

use common::{body_with_inertia, flip_interval, mean_interval, sign_changes, slope};
use proptest::prelude::*;
use tumble::{BodyDef, Cuboid, DMat3, DQuat, DVec3, Shape, World, WorldDef};

fn zero_gravity_world() -> World {
    World::new(WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap()
}

fn rel(a: DVec3, b: DVec3) -> f64 {
    (a - b).length() / b.length().max(1e-300)
}

/// F1: a projectile follows the discrete closed form of semi-implicit Euler over the solver's
/// substeps (n substeps of length h): v_n = v₀ + n h g, x_n = x₀ + n h v₀ + h² g n(n+1)/2, to
/// round-off.
#[test]
fn f1_projectile_matches_discrete_closed_form() {
    let mut world = World::default();
    let x0 = DVec3::new(1.0, -2.0, 3.0);
    let v0 = DVec3::new(4.0, 1.5, 20.0);
    let id = world
        .add_body(BodyDef {
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.1, 0.2, 0.3)).unwrap())),
            position: x0,
            linear_velocity: v0,
            angular_velocity: DVec3::new(0.3, -2.0, 1.0),
            ..Default::default()
        })
        .unwrap();
    let g = world.gravity();
    let dt = 1.0 / 60.0;
    let substeps = world.solver_settings().substeps;
    let h = dt / f64::from(substeps);
    let mut worst: f64 = 0.0;
    for step in 1..=600_u32 {
        world.step(dt).unwrap();
        let nf = f64::from(step * substeps);
        let v_expected = v0 + nf * h * g;
        let x_expected = x0 + nf * h * v0 + h * h * g * nf * (nf + 1.0) / 2.0;
        let body = world.body(id).unwrap();
        worst = worst.max(rel(body.linear_velocity(), v_expected)).max(rel(body.com_world(), x_expected));
    }
    assert!(worst < 1e-12, "worst relative error {worst:e}");
}

/// Steps a torque-free body with I = (1, 2, 3) and ω₀ = (0.01, 5, 0.01) (body axes, body frame
/// rotated by `orientation`) for 100 s at 240 Hz, returning (times, energies, world momenta,
/// body-frame ω).
fn tumble_f2(orientation: DQuat) -> (Vec<f64>, Vec<f64>, Vec<DVec3>, Vec<DVec3>) {
    let mut world = zero_gravity_world();
    let inertia = DVec3::new(1.0, 2.0, 3.0);
    let w0_body = DVec3::new(0.01, 5.0, 0.01);
    let id = world
        .add_body(BodyDef {
            orientation,
            angular_velocity: orientation * w0_body,
            ..body_with_inertia(1.0, inertia)
        })
        .unwrap();
    let h = 1.0 / 240.0;
    let (mut t, mut e, mut l, mut w) = (vec![0.0], vec![world.kinetic_energy()], vec![], vec![w0_body]);
    l.push(world.angular_momentum(DVec3::ZERO));
    for n in 1..=24_000 {
        world.step(h).unwrap();
        let body = world.body(id).unwrap();
        t.push(f64::from(n) * h);
        e.push(world.kinetic_energy());
        l.push(world.angular_momentum(DVec3::ZERO));
        w.push(body.orientation().inverse() * body.angular_velocity());
    }
    (t, e, l, w)
}

/// F2: world angular momentum constant to 1e-10 relative; energy error below 1e-4 relative, with
/// no trend.
#[test]
fn f2_torque_free_body_conserves_momentum_and_energy() {
    for orientation in [DQuat::IDENTITY, DQuat::from_euler(glam::EulerRot::ZYX, 0.4, -1.2, 2.5)] {
        let (t, e, l, _) = tumble_f2(orientation);
        let l_drift = l.iter().map(|&li| rel(li, l[0])).fold(0.0, f64::max);
        assert!(l_drift < 1e-10, "angular momentum drift {l_drift:e}");
        let e_rel: Vec<f64> = e.iter().map(|ei| (ei - e[0]) / e[0]).collect();
        let e_max = e_rel.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
        assert!(e_max < 1e-4, "energy error {e_max:e}");
        // No trend: a secular drift would show as a slope; over 100 s it must stay far below the
        // bounded oscillation (an explicit update drifts by whole percents here).
        let drift_over_run = slope(&t, &e_rel).abs() * 100.0;
        assert!(drift_over_run < 1e-6, "energy trend over 100 s: {drift_over_run:e}");
        println!("F2: |ΔL|/|L| = {l_drift:.2e}, max |ΔE|/E = {e_max:.2e}, trend = {drift_over_run:.2e}");
    }
}

/// F3: the intermediate-axis flip happens, at the interval 2K(k)/p of the analytic solution, to 1%.
#[test]
fn f3_intermediate_axis_flip_period() {
    let (t, _, _, w) = tumble_f2(DQuat::IDENTITY);
    let wy: Vec<f64> = w.iter().map(|w| w.y).collect();
    let flips = sign_changes(&t, &wy);
    assert!(flips.len() >= 10, "expected repeated flips in 100 s, got {}", flips.len());
    let measured = mean_interval(&flips);
    let analytic = flip_interval(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.01, 5.0, 0.01));
    let error = (measured - analytic).abs() / analytic;
    println!(
        "F3: {} flips, interval {measured:.6} s, analytic {analytic:.6} s, error {error:.2e}",
        flips.len()
    );
    assert!(error < 0.01, "flip interval {measured} vs analytic {analytic}");
}

/// F4: torque-free symmetric top: in the body frame ω precesses about the symmetry axis at
/// Ω = (I₃ − I₁)/I₁ · ω₃, to 0.1%.
#[test]
fn f4_symmetric_top_precession_rate() {
    for (i1, i3) in [(2.0, 1.0), (1.0, 3.0)] {
        let mut world = zero_gravity_world();
        let w0 = DVec3::new(0.7, 0.0, 5.0);
        let id = world
            .add_body(BodyDef { angular_velocity: w0, ..body_with_inertia(1.0, DVec3::new(i1, i1, i3)) })
            .unwrap();
        let h = 1.0 / 240.0;
        let (mut times, mut phases) = (vec![0.0], vec![0.0]);
        let mut phase = 0.0_f64;
        let mut last = w0.y.atan2(w0.x);
        for n in 1..=2400 {
            world.step(h).unwrap();
            let b = world.body(id).unwrap();
            let w_body = b.orientation().inverse() * b.angular_velocity();
            let angle = w_body.y.atan2(w_body.x);
            let mut d = angle - last;
            d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            phase += d;
            last = angle;
            times.push(f64::from(n) * h);
            phases.push(phase);
        }
        let measured = slope(&times, &phases);
        let expected = (i3 - i1) / i1 * w0.z;
        let error = ((measured - expected) / expected).abs();
        println!("F4: I1 = {i1}, I3 = {i3}: Ω = {measured:.6}, analytic {expected:.6}, error {error:.2e}");
        assert!(error < 1e-3, "precession rate {measured} vs {expected}");
    }
}

/// F5: a force f at offset r for one step dt changes momentum by f·dt and angular momentum (about
/// the centre of mass) by (r × f)·dt, to round-off.
#[test]
fn f5_offset_force_gives_exact_momentum_change() {
    let mut world = zero_gravity_world();
    let id = world
        .add_body(BodyDef {
            orientation: DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.2, -0.9),
            linear_velocity: DVec3::new(0.5, -1.0, 2.0),
            angular_velocity: DVec3::new(1.0, 3.0, -2.0),
            ..body_with_inertia(2.5, DVec3::new(0.4, 0.9, 1.3))
        })
        .unwrap();
    let dt = 0.01;
    let f = DVec3::new(3.0, -7.0, 2.0);
    let r = DVec3::new(0.2, 0.5, -0.3);
    let (p0, l0) = {
        let b = world.body(id).unwrap();
        (b.linear_momentum(), b.angular_momentum_about_com())
    };
    let point = world.body(id).unwrap().com_world() + r;
    world.apply_force_at_point(id, f, point).unwrap();
    world.step(dt).unwrap();
    let b = world.body(id).unwrap();
    let dp = b.linear_momentum() - p0;
    let dl = b.angular_momentum_about_com() - l0;
    assert!(rel(dp, f * dt) < 1e-12, "Δp = {dp}, expected {}", f * dt);
    // ΔL is small next to L itself, so compare against the scale of L for round-off.
    assert!((dl - r.cross(f) * dt).length() < 1e-13 * l0.length(), "ΔL = {dl}, expected {}", r.cross(f) * dt);
    assert_eq!(b.force(), DVec3::ZERO, "accumulators clear after the step");
    assert_eq!(b.torque(), DVec3::ZERO);
}

/// F6: offset-point kinematics. The velocity v_cm + ω × r and acceleration
/// a_cm + ω̇ × r + ω × (ω × r) equal central differences of the material point's path, with an
/// error that falls as O(H²) (the difference step halves → the error quarters).
#[test]
fn f6_offset_point_kinematics_match_finite_differences() {
    let r_local = DVec3::new(0.3, -0.4, 0.5);
    let force = DVec3::new(0.0, 0.0, 0.0);
    let torque = DVec3::new(0.4, -0.2, 0.3);
    let start = |world: &mut World| {
        world
            .add_body(BodyDef {
                orientation: DQuat::from_euler(glam::EulerRot::XYZ, 0.5, -0.3, 1.1),
                linear_velocity: DVec3::new(0.5, 0.2, -0.1),
                angular_velocity: DVec3::new(1.5, -2.0, 2.5),
                ..body_with_inertia(2.0, DVec3::new(0.5, 1.0, 1.7))
            })
            .unwrap()
    };
    // Fine integration step: the integrator's own error must sit far below the differences'.
    let h = 1e-6;
    let errors = |big_h: f64| -> (f64, f64) {
        let mut world = World::default();
        let id = start(&mut world);
        let steps = (big_h / h).round() as usize;
        let mut samples = Vec::new();
        let (mut v_formula, mut a_formula) = (DVec3::ZERO, DVec3::ZERO);
        for i in 0..=2 * steps {
            let b = world.body(id).unwrap();
            let p = b.com_world() + b.orientation() * r_local;
            if i % steps == 0 {
                samples.push(p);
            }
            world.apply_force(id, force).unwrap();
            world.apply_torque(id, torque).unwrap();
            if i == steps {
                v_formula = world.point_velocity(id, p).unwrap();
                a_formula = world.point_acceleration(id, p).unwrap();
            }
            world.step(h).unwrap();
        }
        let v_fd = (samples[2] - samples[0]) / (2.0 * big_h);
        let a_fd = (samples[2] - 2.0 * samples[1] + samples[0]) / (big_h * big_h);
        ((v_fd - v_formula).length(), (a_fd - a_formula).length())
    };
    let (ev1, ea1) = errors(4e-3);
    let (ev2, ea2) = errors(2e-3);
    println!(
        "F6: H = 4 ms: |Δv| = {ev1:.2e}, |Δa| = {ea1:.2e}; H = 2 ms: |Δv| = {ev2:.2e}, |Δa| = {ea2:.2e}"
    );
    // Central differences err by about H²·|x‴|/6 (velocity) and H²·|x⁗|/12 (acceleration); with
    // |ω| ≈ 3.5 rad/s and |r| ≈ 0.7 m that is well below 1e-3 m/s and 1e-3 m/s² at H = 4 ms.
    assert!(ev1 < 1e-3 && ea1 < 1e-3, "differences too far from the formulas");
    // O(H²): halving H divides the error by about 4.
    assert!((3.0..5.0).contains(&(ev1 / ev2)), "velocity error ratio {}", ev1 / ev2);
    assert!((3.0..5.0).contains(&(ea1 / ea2)), "acceleration error ratio {}", ea1 / ea2);
}

fn tumbling_body(world: &mut World, orientation: DQuat) -> tumble::BodyId {
    world.add_body(BodyDef { orientation, ..body_with_inertia(3.0, DVec3::new(0.2, 0.7, 1.1)) }).unwrap()
}

proptest! {
    /// F7: an impulse j at r₁ changes the velocity of the point at r₂ by exactly K(r₁, r₂)·j, and
    /// K(r, r) is symmetric positive definite.
    #[test]
    fn f7_point_inverse_mass_matrix(
        r1 in prop::array::uniform3(-1.0..1.0f64),
        r2 in prop::array::uniform3(-1.0..1.0f64),
        j in prop::array::uniform3(-5.0..5.0f64),
        angles in prop::array::uniform3(-3.0..3.0f64),
    ) {
        let (r1, r2, j) = (DVec3::from(r1), DVec3::from(r2), DVec3::from(j));
        let mut world = zero_gravity_world();
        let q = DQuat::from_euler(glam::EulerRot::ZYX, angles[0], angles[1], angles[2]);
        let id = tumbling_body(&mut world, q);
        world.set_angular_velocity(id, DVec3::new(0.3, -1.0, 0.7)).unwrap();
        let com = world.body(id).unwrap().com_world();
        let v_before = world.point_velocity(id, com + r2).unwrap();
        let k12 = world.inverse_mass_matrix(id, r1, r2).unwrap();
        world.apply_impulse_at_point(id, j, com + r1).unwrap();
        let dv = world.point_velocity(id, com + r2).unwrap() - v_before;
        prop_assert!((dv - k12 * j).length() <= 1e-12 * (k12 * j).length().max(1e-12), "{dv} vs {}", k12 * j);

        let k = world.inverse_mass_matrix(id, r1, r1).unwrap();
        let asym = (k - k.transpose()).to_cols_array().iter().fold(0.0_f64, |a, b| a.max(b.abs()));
        prop_assert!(asym < 1e-14);
        let (eigenvalues, _) = tumble::mass::symmetric_eigen(k);
        prop_assert!(eigenvalues.min_element() > 0.0, "eigenvalues {eigenvalues}");
    }
}

#[test]
fn f7_inverse_mass_matrix_of_static_body_is_zero() {
    let mut world = zero_gravity_world();
    let id = world
        .add_body(BodyDef { kind: tumble::BodyKind::Static, ..body_with_inertia(1.0, DVec3::ONE) })
        .unwrap();
    assert_eq!(world.inverse_mass_matrix(id, DVec3::X, DVec3::Y).unwrap(), DMat3::ZERO);
}
