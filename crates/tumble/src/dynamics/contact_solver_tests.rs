//! Tests of the contact rows (contact_solver.rs).

use super::*;
use crate::dynamics::solver::SolverSettings;
use crate::math::DQuat;

/// A box's face (four corners, 0.5 m from its centre) resting on another box, prepared at the
/// step start: the constraint, the two bodies and the points.
fn box_on_box(ctx: &StepContext) -> (ContactConstraint, SolverBody, SolverBody, Vec<ContactPointInput>) {
    let q_a = DQuat::from_rotation_z(0.3);
    let q_b = DQuat::from_rotation_x(0.2) * DQuat::from_rotation_y(-0.1);
    let a = SolverBody::dynamic_for_test(1.0, DVec3::new(2.0, 3.0, 4.0), q_a);
    let b = SolverBody::dynamic_for_test(0.5, DVec3::new(1.5, 1.0, 2.5), q_b);
    let (com_a, com_b) = (DVec3::new(0.1, -0.2, 0.0), DVec3::new(0.15, -0.1, 1.0));
    let points: Vec<ContactPointInput> = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
        .iter()
        .enumerate()
        .map(|(i, &(x, y))| ContactPointInput {
            point_world: DVec3::new(0.1 + x, -0.2 + y, 0.5),
            separation: -1e-3 + 2e-4 * i as f64,
            impulse: ContactImpulse::default(),
        })
        .collect();
    let material =
        ContactMaterial { friction: 0.5, restitution: 0.0, rolling_friction: 0.0, torsional_friction: 0.0 };
    let mut constraint = ContactConstraint::EMPTY;
    constraint.prepare_in_place(
        (0, 1),
        (&a, &b),
        (com_a, com_b),
        (0.0, 0.0),
        DVec3::Z,
        points.as_slice(),
        material,
        ctx,
    );
    (constraint, a, b, points)
}

/// The box pair of `box_on_box` within the step, both moved by `common` on top of their own
/// motion: a slides and turns about a tilted axis, b sinks and rocks.
fn box_on_box_moved(
    ctx: &StepContext,
    common: DVec3,
) -> (ContactConstraint, SolverBody, SolverBody, Vec<ContactPointInput>) {
    let (constraint, mut a, mut b, points) = box_on_box(ctx);
    let turn_a = DVec3::new(0.3e-3, -0.5e-3, 0.6e-3);
    let turn_b = DVec3::new(-0.7e-3, 0.4e-3, 0.2e-3);
    a.move_for_test(common + DVec3::new(2e-4, -1e-4, 3e-4), DQuat::from_scaled_axis(turn_a) * a.q);
    b.move_for_test(common + DVec3::new(-1e-4, 3e-4, -4e-4), DQuat::from_scaled_axis(turn_b) * b.q);
    (a.v, a.w) = (DVec3::new(0.01, 0.02, -0.03), DVec3::new(0.5, -0.2, 0.4));
    (b.v, b.w) = (DVec3::new(-0.02, 0.01, -0.05), DVec3::new(-0.3, 0.5, 0.1));
    (constraint, a, b, points)
}

/// The rows linear in the step-start levers agree with the exact rows to second order while the
/// pair is still, and the turn enters with the right sign (a turn of 0.9 mrad moves the corners
/// by up to 0.45 mm, 500 times the tolerance).
#[test]
fn still_rows_match_the_exact_rows_to_second_order() {
    let ctx = StepContext::new(1.0 / 60.0, DVec3::new(0.0, 0.0, -9.81), &SolverSettings::default());
    let (constraint, a, b, points) = box_on_box_moved(&ctx, DVec3::ZERO);
    assert!(still_pair(&a, &b));
    let (mut s_exact, mut v_exact, mut anchors) = ([0.0; 4], [0.0; 4], [(DVec3::ZERO, DVec3::ZERO); 4]);
    constraint.rows_now(&a, &b, (&mut s_exact, &mut v_exact, &mut anchors));
    let (s_linear, v_linear) = constraint.rows_still(&a, &b);
    for i in 0..4 {
        // Left out: |r| θ²/2 per body (levers under 0.8 m, turns under 0.9 mrad).
        assert!((s_linear[i] - s_exact[i]).abs() < 1e-6, "row {i}: {} vs {}", s_linear[i], s_exact[i]);
        // The levers' change: |ω| |θ × r| per body (|ω| ≤ 0.7 rad/s), under 1e-3 m/s together;
        // `ω × r` itself is ~0.3 m/s.
        assert!((v_linear[i] - v_exact[i]).abs() < 1e-3, "row {i}: {} vs {}", v_linear[i], v_exact[i]);
    }
    // The turn matters: leaving it out would be off by far more than the tolerance.
    let moved = DVec3::Z.dot(b.dp - a.dp);
    let worst = (0..4).map(|i| (s_exact[i] - (points[i].separation + moved)).abs()).fold(0.0, f64::max);
    assert!(worst > 1e-4, "{worst}");
}

/// A translation common to both bodies changes none of the exact rows (separations, normal
/// velocities, shared levers) beyond round-off, so a pair that moved 5 cm together is still
/// (`still_pair`) and its step-start rows agree with the exact ones as closely as without the
/// translation. Moved 1.2 mm against each other, on top, the pair is not still.
#[test]
fn a_common_translation_leaves_the_rows_and_the_still_pair() {
    let ctx = StepContext::new(1.0 / 60.0, DVec3::new(0.0, 0.0, -9.81), &SolverSettings::default());
    let rows = |common: DVec3| {
        let (constraint, a, b, _) = box_on_box_moved(&ctx, common);
        let (mut s, mut v, mut anchors) = ([0.0; 4], [0.0; 4], [(DVec3::ZERO, DVec3::ZERO); 4]);
        constraint.rows_now(&a, &b, (&mut s, &mut v, &mut anchors));
        (s, v, anchors, constraint.rows_still(&a, &b), still_pair(&a, &b))
    };
    let common = DVec3::new(0.03, -0.02, -0.035);
    let (s_0, v_0, anchors_0, _, _) = rows(DVec3::ZERO);
    let (s, v, anchors, (s_linear, v_linear), still) = rows(common);
    assert!(still, "moved together by {} m", common.length());
    for i in 0..4 {
        // Round-off of the 5 cm added to and taken from each body's displacement.
        assert!((s[i] - s_0[i]).abs() < 1e-15, "row {i}: {} vs {}", s[i], s_0[i]);
        assert!((v[i] - v_0[i]).abs() < 1e-15, "row {i}: {} vs {}", v[i], v_0[i]);
        let lever_change =
            (anchors[i].0 - anchors_0[i].0).length() + (anchors[i].1 - anchors_0[i].1).length();
        assert!(lever_change < 1e-15, "row {i}: levers moved by {lever_change}");
        // The tolerances of the still rows without the translation.
        assert!((s_linear[i] - s[i]).abs() < 1e-6, "row {i}: {} vs {}", s_linear[i], s[i]);
        assert!((v_linear[i] - v[i]).abs() < 1e-3, "row {i}: {} vs {}", v_linear[i], v[i]);
    }
    // Against each other, the pair's relative displacement counts.
    let (_, mut a, b, _) = box_on_box_moved(&ctx, common);
    assert!(still_pair(&a, &b));
    let q = a.q;
    a.move_for_test(a.dp + DVec3::new(1.2e-3, 0.0, 0.0), q);
    assert!(!still_pair(&a, &b), "relative displacement {} m", (b.dp - a.dp).length());
}
