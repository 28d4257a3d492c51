//! Validation of the exact solver on rigid-body systems whose impulses follow from statics,
//! momentum or the lecture's point inverse mass matrix, on random systems of bodies, joints and
//! frictional contacts, and on bad input. (Lemke's algorithm alone: `lcp_lemke.rs`.)
//!
//! Tolerances: the solver's answers are a linear solve on the final basis from the original data,
//! so they are exact up to round-off (measured 1e-16 – 1e-14 relative here). The tests allow 1e-10
//! relative, far above round-off and far below any modelling error.

mod lcp_support;

use lcp_support::{random_unit, random_vec, Rng};
use tumble::dynamics::lcp::{
    ball_joint_rows, contact_rows, point_row, solve_exact, Anchor, BodyVelocity, ContactPoint, LcpBody,
    LcpError, Row, RowKind, MAX_ROWS,
};
use tumble::math::hat;
use tumble::{DMat3, DVec3};

const G: f64 = 9.81;
const DT: f64 = 1.0 / 60.0;
const REL: f64 = 1e-10;

// ---------------------------------------------------------------------------------------------
// Rigid-body systems

fn box_body(mass: f64, h: DVec3) -> LcpBody {
    let i = mass / 3.0 * DVec3::new(h.y * h.y + h.z * h.z, h.x * h.x + h.z * h.z, h.x * h.x + h.y * h.y);
    LcpBody::new(1.0 / mass, DMat3::from_diagonal(i.recip()))
}

/// Four corner contacts of box `index` (half extents `h`) on `below`: the world, or box `j` with
/// half height `hz` (corners at its top face). Rows per corner: normal (z), friction x, friction y.
fn corner_contacts(index: usize, below: Option<(usize, f64)>, h: DVec3, mu: f64, rows: &mut Vec<Row>) {
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
        let a = match below {
            None => Anchor::WORLD,
            Some((j, hz)) => Anchor::new(j, DVec3::new(sx * h.x, sy * h.y, hz)),
        };
        let b = Anchor::new(index, DVec3::new(sx * h.x, sy * h.y, -h.z));
        let c = ContactPoint { a, b, normal: DVec3::Z, tangent: DVec3::X, mu, bias: 0.0 };
        let first = rows.len();
        rows.extend(contact_rows(&c, first));
    }
}

/// Sums of the impulses of contacts `first_contact..first_contact + 4`: (friction x, friction y, normal).
fn layer_sums(impulses: &[f64], first_contact: usize) -> DVec3 {
    (0..4).fold(DVec3::ZERO, |s, k| {
        let r = 3 * (first_contact + k);
        s + DVec3::new(impulses[r + 1], impulses[r + 2], impulses[r])
    })
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= REL * scale
}

#[test]
fn box_resting_on_ground() {
    // After one step of gravity the box moves down at g·dt; four corner contacts (bias 0) must
    // stop it: the normal impulses sum to m g dt, friction has nothing to do, the box is at rest.
    // Measured: relative error of the sum ~1e-16, velocities ~1e-17.
    let (mass, h, mu) = (3.0, DVec3::new(0.5, 0.3, 0.2), 0.5);
    let mut rows = Vec::new();
    corner_contacts(0, None, h, mu, &mut rows);
    let v = [BodyVelocity::new(DVec3::new(0.0, 0.0, -G * DT), DVec3::ZERO)];
    let sol = solve_exact(&[box_body(mass, h)], &v, &rows).unwrap();
    let weight = mass * G * DT;
    let sums = layer_sums(&sol.impulses, 0);
    eprintln!("resting box: sum error {:e}, pivots {}", (sums.z - weight).abs() / weight, sol.pivots);
    assert!(close(sums.z, weight, weight), "{sums}");
    for k in 0..4 {
        assert!(sol.impulses[3 * k] >= 0.0);
        assert!(
            sol.impulses[3 * k + 1].abs() <= REL * weight && sol.impulses[3 * k + 2].abs() <= REL * weight
        );
    }
    assert!(sol.velocities[0].linear.length() <= REL * G * DT);
    assert!(sol.velocities[0].angular.length() <= REL * G * DT);
    assert!(sol.residual(&rows) <= REL * weight);
}

#[test]
fn box_sliding_on_ground_gets_full_friction() {
    // Sliding at 2 m/s ≫ μ g dt: every x-friction row saturates at −μ λ_n, so the box loses
    // μ g dt of speed; the friction's tipping moment is carried by a front-heavy normal split
    // (Σ x_i λ_i = h_z μ m g dt), the box does not rotate. Measured errors ~1e-16 relative.
    let (mass, h, mu, speed) = (3.0, DVec3::new(0.5, 0.3, 0.2), 0.5, 2.0);
    let mut rows = Vec::new();
    corner_contacts(0, None, h, mu, &mut rows);
    let v = [BodyVelocity::new(DVec3::new(speed, 0.0, -G * DT), DVec3::ZERO)];
    let sol = solve_exact(&[box_body(mass, h)], &v, &rows).unwrap();
    let weight = mass * G * DT;
    let sums = layer_sums(&sol.impulses, 0);
    assert!(close(sums.z, weight, weight), "{sums}");
    assert!(close(sums.x, -mu * weight, weight), "{sums}");
    assert!(sums.y.abs() <= REL * weight, "{sums}");
    for k in 0..4 {
        assert!(close(sol.impulses[3 * k + 1], -mu * sol.impulses[3 * k], weight), "contact {k}");
    }
    let moment: f64 = (0..4).map(|k| [h.x, -h.x, -h.x, h.x][k] * sol.impulses[3 * k]).sum();
    assert!(close(moment, h.z * mu * weight, weight * h.x), "moment {moment}");
    let expected = DVec3::new(speed - mu * G * DT, 0.0, 0.0);
    assert!((sol.velocities[0].linear - expected).length() <= REL * speed, "{:?}", sol.velocities[0]);
    assert!(sol.velocities[0].angular.length() <= REL * speed);
}

#[test]
fn box_slow_on_ground_sticks() {
    // Sliding at 0.05 m/s < μ g dt ≈ 0.082 m/s: friction stops it within the step. The total
    // friction impulse is −m v, below μ times the total normal impulse.
    let (mass, h, mu, speed) = (3.0, DVec3::new(0.5, 0.3, 0.2), 0.5, 0.05);
    let mut rows = Vec::new();
    corner_contacts(0, None, h, mu, &mut rows);
    let v = [BodyVelocity::new(DVec3::new(speed, 0.0, -G * DT), DVec3::ZERO)];
    let sol = solve_exact(&[box_body(mass, h)], &v, &rows).unwrap();
    let weight = mass * G * DT;
    let sums = layer_sums(&sol.impulses, 0);
    assert!(close(sums.z, weight, weight), "{sums}");
    assert!(close(sums.x, -mass * speed, weight), "{sums}");
    assert!(sums.x.abs() < mu * sums.z);
    for k in 0..4 {
        let (n, t) = (sol.impulses[3 * k], sol.impulses[3 * k + 1]);
        assert!(t.abs() <= mu * n * (1.0 + REL), "contact {k}: |{t}| > {mu}·{n}");
    }
    assert!(sol.velocities[0].linear.length() <= REL * speed);
    assert!(sol.velocities[0].angular.length() <= REL * speed);
}

#[test]
fn three_box_stack_layers_carry_the_weight_above() {
    // Three boxes of different mass stacked on the ground, all moving down at g dt after
    // gravity. Each layer of four contacts must stop everything above it: layer k carries
    // (Σ masses above) g dt. 36 rows, an LCP of 84 unknowns. Measured errors ~1e-15 relative.
    let h = DVec3::new(0.4, 0.4, 0.25);
    let masses = [2.0, 1.0, 0.5];
    let mut rows = Vec::new();
    corner_contacts(0, None, h, 0.6, &mut rows);
    corner_contacts(1, Some((0, h.z)), h, 0.6, &mut rows);
    corner_contacts(2, Some((1, h.z)), h, 0.6, &mut rows);
    let bodies: Vec<LcpBody> = masses.iter().map(|&m| box_body(m, h)).collect();
    let v = [BodyVelocity::new(DVec3::new(0.0, 0.0, -G * DT), DVec3::ZERO); 3];
    let sol = solve_exact(&bodies, &v, &rows).unwrap();
    assert_eq!(sol.lcp_size, 12 + 3 * 24);
    let mut worst = 0.0_f64;
    for layer in 0..3 {
        let above: f64 = masses[layer..].iter().sum::<f64>() * G * DT;
        let sums = layer_sums(&sol.impulses, 4 * layer);
        worst = worst.max((sums.z - above).abs() / above);
        assert!(close(sums.z, above, above), "layer {layer}: {sums} vs {above}");
        assert!(sums.x.abs() <= REL * above && sums.y.abs() <= REL * above, "layer {layer}: {sums}");
    }
    for body in &sol.velocities {
        assert!(body.linear.length() <= REL * G * DT && body.angular.length() <= REL * G * DT, "{body:?}");
    }
    eprintln!("stack: worst layer error {worst:e}, pivots {}", sol.pivots);
}

#[test]
fn single_contact_matches_the_lecture_impulse() {
    // A body hits the ground at one corner, no friction: λ = −u_n / (nᵀ K n) with the lecture's
    // K = m⁻¹ 1 − r̂ I⁻¹ r̂, and the corner's normal velocity is zero afterwards.
    let (mass, h) = (2.0, DVec3::new(0.5, 0.4, 0.3));
    let body = box_body(mass, h);
    let r = DVec3::new(0.5, -0.4, -0.3);
    let v = BodyVelocity::new(DVec3::new(0.3, 0.0, -1.5), DVec3::new(0.2, -0.7, 0.1));
    let row = point_row(Anchor::WORLD, Anchor::new(0, r), DVec3::Z, RowKind::Normal);
    let sol = solve_exact(&[body], &[v], &[row]).unwrap();
    let k = DMat3::from_diagonal(DVec3::splat(1.0 / mass)) - hat(r) * body.inverse_inertia_world * hat(r);
    let u = v.linear + v.angular.cross(r);
    let expected = -u.z / DVec3::Z.dot(k * DVec3::Z);
    assert!(close(sol.impulses[0], expected, expected), "{} vs {expected}", sol.impulses[0]);
    assert!(sol.row_velocities[0].abs() <= REL * u.z.abs());
}

#[test]
fn two_dynamic_bodies_collide_plastically() {
    // Two spheres meet head-on at their centres' line (frictionless): after a plastic impulse
    // they share the momentum-weighted velocity; the impulse is the reduced mass times the
    // closing speed.
    let (m1, m2) = (1.0, 3.0);
    let sphere = |m: f64| LcpBody::new(1.0 / m, DMat3::from_diagonal(DVec3::splat(1.0 / (0.4 * m * 0.01))));
    let (u1, u2) = (2.0, -1.0);
    let v = [
        BodyVelocity::new(DVec3::new(u1, 0.0, 0.0), DVec3::ZERO),
        BodyVelocity::new(DVec3::new(u2, 0.0, 0.0), DVec3::ZERO),
    ];
    let row = point_row(
        Anchor::new(0, DVec3::new(0.1, 0.0, 0.0)),
        Anchor::new(1, DVec3::new(-0.1, 0.0, 0.0)),
        DVec3::X,
        RowKind::Normal,
    );
    let sol = solve_exact(&[sphere(m1), sphere(m2)], &v, &[row]).unwrap();
    let common = (m1 * u1 + m2 * u2) / (m1 + m2);
    let reduced = m1 * m2 / (m1 + m2);
    assert!(close(sol.impulses[0], reduced * (u1 - u2), 1.0));
    for body in &sol.velocities {
        assert!((body.linear - DVec3::new(common, 0.0, 0.0)).length() <= REL);
    }
}

#[test]
fn pendulum_ball_joint_gives_centripetal_plus_gravity_impulse() {
    // A solid ball (mass m, radius ρ) on a ball joint at distance L below a fixed pivot, swinging
    // rigidly about the pivot at rate Ω. Its velocities are those of the previous step (a swing
    // angle θ = Ω dt earlier) plus gravity; the configuration is the current one, at the bottom.
    // The joint impulse must make the anchor velocity zero. Exactly, λ = −K⁻¹ u (lecture K); along
    // the rod this is m (V sin θ + g dt) = m (V²/L + g) dt · (1 + O(θ²)): the tension impulse.
    let (mass, radius, length, omega) = (1.5, 0.1, 0.8, 2.0);
    let inertia = 0.4 * mass * radius * radius;
    let body = LcpBody::new(1.0 / mass, DMat3::from_diagonal(DVec3::splat(1.0 / inertia)));
    let speed = omega * length;
    let theta = omega * DT;
    let w = DVec3::new(0.0, -omega, 0.0); // rotating so the ball moves toward +x at the bottom
    let v_old = speed * DVec3::new(theta.cos(), 0.0, -theta.sin());
    let v = BodyVelocity::new(v_old + DVec3::new(0.0, 0.0, -G * DT), w);
    let r = DVec3::new(0.0, 0.0, length); // pivot relative to the ball's centre
    let rows = ball_joint_rows(Anchor::WORLD, Anchor::new(0, r));
    let sol = solve_exact(&[body], &[v], &rows).unwrap();
    let lambda = DVec3::new(sol.impulses[0], sol.impulses[1], sol.impulses[2]);

    let k = DMat3::from_diagonal(DVec3::splat(1.0 / mass)) - hat(r) * body.inverse_inertia_world * hat(r);
    let u = v.linear + v.angular.cross(r);
    let exact = -(k.inverse() * u);
    assert!((lambda - exact).length() <= REL * exact.length(), "{lambda} vs {exact}");
    let after = sol.velocities[0];
    assert!((after.linear + after.angular.cross(r)).length() <= REL * speed);

    let tension = mass * (speed * speed / length + G) * DT;
    assert!(close(lambda.z, mass * (speed * theta.sin() + G * DT), tension));
    assert!((lambda.z - tension).abs() <= theta * theta * tension, "{} vs {tension}", lambda.z);
    eprintln!("pendulum: |λ − K⁻¹u| / |λ| = {:e}", (lambda - exact).length() / exact.length());
}

#[test]
fn random_mixed_systems_satisfy_every_row_condition() {
    // Random bodies (masses 0.5–2, rotated anisotropic inertia), random velocities, a chain of
    // ball joints (at most one per body, so the equality rows are independent) and random
    // frictional contacts between bodies or with the world. With bias 0 the problem is always
    // solvable (v⁺ = 0 satisfies every row kinematically). Checks each condition directly:
    // equality w = 0, normal λ ≥ 0 ⟂ w ≥ 0, friction |λ| ≤ μλ_n with stick/slip.
    let mut rng = Rng(2024);
    let (mut worst, mut max_pivots, mut max_size) = (0.0_f64, 0, 0);
    for trial in 0..300 {
        let nb = 1 + trial % 4;
        let bodies: Vec<LcpBody> = (0..nb)
            .map(|_| {
                let m = 1.25 + 0.75 * rng.uniform();
                let rot = DMat3::from_quat(tumble::DQuat::from_scaled_axis(random_vec(&mut rng, 3.0)));
                let i = m * (0.2 + 0.15 * DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()));
                LcpBody::new(1.0 / m, rot * DMat3::from_diagonal(i.recip()) * rot.transpose())
            })
            .collect();
        let v: Vec<BodyVelocity> = (0..nb)
            .map(|_| BodyVelocity::new(random_vec(&mut rng, 2.0), random_vec(&mut rng, 2.0)))
            .collect();
        let mut rows = Vec::new();
        for b in 0..nb {
            if rng.uniform() < -0.3 {
                let a = if b == 0 { Anchor::WORLD } else { Anchor::new(b - 1, random_vec(&mut rng, 0.5)) };
                rows.extend(ball_joint_rows(a, Anchor::new(b, random_vec(&mut rng, 0.5))));
            }
        }
        for _ in 0..(1 + trial % 7) {
            let b = (rng.next_u64() % nb as u64) as usize;
            let other = (rng.next_u64() % (nb as u64 + 1)) as usize;
            let a = if other == b || other == nb {
                Anchor::WORLD
            } else {
                Anchor::new(other, random_vec(&mut rng, 0.5))
            };
            let normal = random_unit(&mut rng);
            let tangent = normal.any_orthonormal_vector();
            let mu = 0.8 * (rng.uniform() + 1.0) * 0.5;
            let c = ContactPoint {
                a,
                b: Anchor::new(b, random_vec(&mut rng, 0.5)),
                normal,
                tangent,
                mu,
                bias: 0.0,
            };
            let first = rows.len();
            rows.extend(contact_rows(&c, first));
        }
        let sol = solve_exact(&bodies, &v, &rows).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
        max_pivots = max_pivots.max(sol.pivots);
        max_size = max_size.max(sol.lcp_size);
        let scale = 1.0 + sol.impulses.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let tol = 1e-10 * scale;
        for (i, row) in rows.iter().enumerate() {
            let (l, w) = (sol.impulses[i], sol.row_velocities[i]);
            match row.kind {
                RowKind::Equality => assert!(w.abs() <= tol, "trial {trial} row {i}: w = {w}"),
                RowKind::Normal => {
                    assert!(
                        l >= 0.0 && w >= -tol && (l * w).abs() <= tol * scale,
                        "trial {trial} row {i}: {l} {w}"
                    )
                }
                RowKind::Friction { normal_row, mu } => {
                    let bound = mu * sol.impulses[normal_row];
                    assert!(l.abs() <= bound + tol, "trial {trial} row {i}: |{l}| > {bound}");
                    if w.abs() > tol {
                        assert!(
                            (l + bound * w.signum()).abs() <= tol,
                            "trial {trial} row {i}: slips but {l} vs {bound}"
                        );
                    }
                }
            }
        }
        worst = worst.max(sol.residual(&rows) / scale);
    }
    eprintln!("random mixed: worst residual {worst:e}, max pivots {max_pivots}, max LCP size {max_size}");
    assert!(worst <= 1e-10);
}

// ---------------------------------------------------------------------------------------------
// Errors

fn one_body() -> (Vec<LcpBody>, Vec<BodyVelocity>) {
    (vec![box_body(1.0, DVec3::splat(0.5))], vec![BodyVelocity::default()])
}

#[test]
fn errors_name_what_is_wrong() {
    let (bodies, v) = one_body();
    let normal = point_row(Anchor::WORLD, Anchor::new(0, DVec3::ZERO), DVec3::Z, RowKind::Normal);

    let err = solve_exact(&bodies, &[], &[normal]).unwrap_err();
    assert!(matches!(err, LcpError::VelocityCount { bodies: 1, velocities: 0 }), "{err}");

    let err = solve_exact(&bodies, &v, &vec![normal; MAX_ROWS + 1]).unwrap_err();
    assert!(matches!(err, LcpError::TooManyRows { .. }), "{err}");
    assert!(err.to_string().contains("at most 128"), "{err}");

    let bad = Row { body_b: Some(3), ..normal };
    let err = solve_exact(&bodies, &v, &[bad]).unwrap_err();
    assert!(matches!(err, LcpError::BodyIndex { row: 0, index: 3, bodies: 1 }), "{err}");

    let bad = Row { body_a: Some(0), ..normal };
    assert!(matches!(solve_exact(&bodies, &v, &[bad]), Err(LcpError::SameBody { row: 0, body: 0 })));

    let friction = Row { kind: RowKind::Friction { normal_row: 5, mu: 0.5 }, ..normal };
    let err = solve_exact(&bodies, &v, &[normal, friction]).unwrap_err();
    assert!(matches!(err, LcpError::NormalRow { row: 1, normal_row: 5, .. }), "{err}");
    let friction = Row { kind: RowKind::Friction { normal_row: 1, mu: 0.5 }, ..normal };
    let err = solve_exact(&bodies, &v, &[normal, friction]).unwrap_err();
    assert!(err.to_string().contains("not a normal row"), "{err}");
    let friction = Row { kind: RowKind::Friction { normal_row: 0, mu: -0.1 }, ..normal };
    let err = solve_exact(&bodies, &v, &[normal, friction]).unwrap_err();
    assert!(matches!(err, LcpError::FrictionCoefficient { row: 1, .. }), "{err}");

    let bad = Row { bias: f64::NAN, ..normal };
    assert!(matches!(solve_exact(&bodies, &v, &[bad]), Err(LcpError::NonFinite { .. })));
    let v_bad = [BodyVelocity::new(DVec3::new(f64::INFINITY, 0.0, 0.0), DVec3::ZERO)];
    assert!(matches!(solve_exact(&bodies, &v_bad, &[normal]), Err(LcpError::NonFinite { .. })));
    let heavy = [LcpBody::new(-1.0, DMat3::IDENTITY)];
    assert!(matches!(solve_exact(&heavy, &v, &[normal]), Err(LcpError::InvalidBody { body: 0, .. })));
}

#[test]
fn impossible_and_redundant_systems_are_errors() {
    let (bodies, v) = one_body();
    // A normal row on the world alone that asks for separation it cannot get: no solution.
    let world_only = Row {
        body_a: None,
        body_b: None,
        bias: -1.0,
        ..point_row(Anchor::WORLD, Anchor::WORLD, DVec3::Z, RowKind::Normal)
    };
    let err = solve_exact(&bodies, &v, &[world_only]).unwrap_err();
    assert!(matches!(err, LcpError::RayTermination { .. }), "{err}");

    // The same ball joint twice: six equality rows of rank three.
    let mut rows = ball_joint_rows(Anchor::WORLD, Anchor::new(0, DVec3::Z)).to_vec();
    rows.extend(ball_joint_rows(Anchor::WORLD, Anchor::new(0, DVec3::Z)));
    let err = solve_exact(&bodies, &v, &rows).unwrap_err();
    assert!(matches!(err, LcpError::SingularEquality { .. }), "{err}");
}
