//! Tests of the joint trees: exact solves, the position projection, and trees kept between steps.

use super::*;
use crate::dynamics::joint::{BallJoint, FixedJoint, HingeJoint, JointDef, JointKind, SliderJoint};
use crate::dynamics::solver::StepContext;
use crate::math::{DQuat, DVec3};
use crate::shape::{Cuboid, Shape};
use crate::{BodyDef, BodyKind, World};

/// The solver bodies of a world's bodies, its joints prepared for a step of 1/60 s, and the
/// trees built from them.
fn prepared(world: &mut World) -> (StepContext, Vec<SolverBody>, JointTrees) {
    let ctx = StepContext::new(1.0 / 60.0, world.gravity, &world.solver_settings);
    let mut bodies = vec![SolverBody::FIXED; world.bodies.capacity_index()];
    for (id, b) in world.bodies.iter() {
        bodies[id.index()] = SolverBody::from_body(b);
    }
    for (_, j) in world.joints.iter_mut() {
        j.solving = true;
        let (a, b) = (world.bodies.get(j.body_a.into()).unwrap(), world.bodies.get(j.body_b.into()).unwrap());
        j.prepare(a, b, &ctx);
    }
    let mut trees = JointTrees::default();
    trees.build(&mut world.joints, &bodies, true);
    (ctx, bodies, trees)
}

/// Every joint's warm start: its accumulated impulses applied to the bodies, as each substep
/// begins.
fn warm_start(world: &mut World, bodies: &mut [SolverBody]) {
    for (_, j) in world.joints.iter_mut() {
        let (ia, ib) = (j.body_a.index(), j.body_b.index());
        let (mut a, mut b) = (bodies[ia], bodies[ib]);
        j.warm_start(&mut a, &mut b);
        (bodies[ia], bodies[ib]) = (a, b);
    }
}

/// Three boxes of half extents `half` in a row along X, 0.5 m apart, the k-th turned by `k·turn`
/// about Z, joined in turn by joints of `kinds` at the midpoints.
fn three_boxes(half: DVec3, turn: f64, kinds: [JointKind; 2]) -> (World, Vec<crate::BodyId>) {
    let mut world = World::new(Default::default()).unwrap();
    let ids: Vec<_> = (0..3)
        .map(|k| {
            world
                .add_body(BodyDef {
                    shape: Some(Shape::Cuboid(Cuboid::new(half).unwrap())),
                    position: DVec3::new(0.5 * k as f64, 0.0, 1.0),
                    orientation: DQuat::from_rotation_z(turn * k as f64),
                    ..Default::default()
                })
                .unwrap()
        })
        .collect();
    for (k, kind) in kinds.into_iter().enumerate() {
        let anchor = DVec3::new(0.5 * k as f64 + 0.25, 0.0, 1.0);
        world.add_joint(JointDef::new(ids[k], ids[k + 1], anchor, kind)).unwrap();
    }
    (world, ids)
}

/// The trees are kept from step to step while the same joints join the same moving bodies,
/// and rebuilt when that changes: here the middle body stops moving (asleep, say), which
/// cuts the chain into two figures grounded on it.
#[test]
fn trees_are_rebuilt_only_when_their_joints_or_moving_bodies_change() {
    let ball = || JointKind::Ball(BallJoint::new());
    let (mut world, ids) = three_boxes(DVec3::splat(0.1), 0.0, [ball(), ball()]);
    let (_, mut bodies, mut trees) = prepared(&mut world);
    // Three bodies and two joints, one figure: five nodes.
    assert_eq!(trees.nodes.len(), 5);
    let marker = 1234.5;
    trees.nodes[0].x[0] = marker;
    trees.build(&mut world.joints, &bodies, true);
    assert_eq!(trees.nodes[0].x[0], marker, "the same joints and bodies keep the nodes");

    bodies[ids[1].index()] = SolverBody::FIXED;
    trees.build(&mut world.joints, &bodies, true);
    // Two figures, each a joint hung from the (now fixed) middle body and its outer body.
    assert_eq!(trees.nodes.len(), 4);
    assert!(trees.nodes.iter().all(|node| node.x[0] != marker));
    assert!(world.joints.iter().all(|(_, j)| j.in_tree));
}

/// A body turned non-finite mid-solve leaves NaN in the kept trees' blocks (`0 × ∞` in the
/// products over whole rows). Once the body is finite again and the same trees are kept,
/// the next solve must be clean: nothing of the failure carries over.
#[test]
fn kept_trees_do_not_carry_a_non_finite_solve_over() {
    let kinds = [JointKind::Ball(BallJoint::new()), JointKind::Fixed(FixedJoint::new())];
    let (mut world, ids) = three_boxes(DVec3::new(0.2, 0.1, 0.1), 0.3, kinds);
    let (_, mut bodies, mut trees) = prepared(&mut world);
    let clean = bodies.clone();
    bodies[ids[2].index()].w = DVec3::new(f64::INFINITY, 0.0, f64::NAN);
    bodies[ids[2].index()].q = DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0);
    trees.solve(world.joints.slots_mut(), &mut bodies, 10.0, 60.0);
    assert!(bodies.iter().any(|b| !b.v.is_finite()), "the failure reached the figure");

    let mut bodies = clean;
    bodies[ids[0].index()].w = DVec3::new(0.5, -1.0, 2.0);
    trees.build(&mut world.joints, &bodies, true);
    assert_eq!(trees.nodes.len(), 5, "the same trees are kept");
    trees.solve(world.joints.slots_mut(), &mut bodies, 10.0, 60.0);
    assert!(bodies.iter().all(|b| b.v.is_finite() && b.w.is_finite()));
    for (_, j) in world.joints.iter() {
        let rows = j.equality_rows(&bodies[j.body_a.index()], &bodies[j.body_b.index()]).unwrap();
        for k in 0..rows.len {
            let residual = rows.rows[k].velocity(&bodies[j.body_a.index()], &bodies[j.body_b.index()])
                + 10.0 * rows.error[k];
            assert!(residual.abs() < 1e-10, "row {k}: {residual:e}");
        }
    }
}

/// A free figure (no joint to the ground) pulled apart by centimetres and turned: the
/// projection puts every joint back within the tolerance, keeps the figure's centre of mass
/// where it was (the joints' linear rows push its bodies equally and oppositely, so `Σ m Δx = 0`
/// in every Newton step) and its momentum, and gives it back the angular momentum the moves took
/// as one rigid spin of the whole figure: every body's `ω` changes by the same `δω`, so no
/// joint's relative velocity changes.
#[test]
fn projection_closes_the_joints_and_keeps_the_centre_of_mass() {
    let mut world = World::new(Default::default()).unwrap();
    let cuboid = |h: DVec3| Some(Shape::Cuboid(Cuboid::new(h).unwrap()));
    let mut ids = vec![];
    for (k, (half, density)) in
        [(DVec3::new(0.2, 0.1, 0.1), 1000.0), (DVec3::splat(0.1), 5000.0), (DVec3::new(0.1, 0.3, 0.1), 200.0)]
            .into_iter()
            .chain([(DVec3::splat(0.15), 1000.0)])
            .enumerate()
    {
        let id = world
            .add_body(BodyDef {
                shape: cuboid(half),
                density,
                position: DVec3::new(0.5 * k as f64, 0.0, 2.0),
                orientation: DQuat::from_rotation_z(0.2 * k as f64),
                ..Default::default()
            })
            .unwrap();
        ids.push(id);
    }
    let axis = DVec3::new(0.0, 1.0, 0.3);
    for (k, kind) in [
        JointKind::Ball(BallJoint::new()),
        JointKind::Hinge(HingeJoint::default()),
        JointKind::Fixed(FixedJoint::new()),
    ]
    .into_iter()
    .enumerate()
    {
        let anchor = DVec3::new(0.5 * k as f64 + 0.25, 0.0, 2.0);
        world.add_joint(JointDef::new(ids[k], ids[k + 1], anchor, kind).with_axis(axis)).unwrap();
    }
    for (k, &id) in ids.iter().enumerate() {
        let k = k as f64;
        world.set_linear_velocity(id, DVec3::new(k, -1.0, 0.5)).unwrap();
        world.set_angular_velocity(id, DVec3::new(0.3, k, -2.0)).unwrap();
    }

    let (ctx, mut bodies, mut trees) = prepared(&mut world);
    assert!(world.joints.iter().all(|(_, j)| j.in_tree));

    // Pull the figure apart: shifts of a few centimetres and turns of a few degrees.
    for (k, &id) in ids.iter().enumerate() {
        let k = k as f64;
        let body = &mut bodies[id.index()];
        body.displace(DVec3::new(0.02 * k, -0.03, 0.01 * k * k), DVec3::new(0.05, -0.04 * k, 0.03));
    }
    let centre = |bodies: &[SolverBody]| {
        let mass = |id: crate::BodyId| 1.0 / bodies[id.index()].inv_mass;
        let total: f64 = ids.iter().map(|&id| mass(id)).sum();
        ids.iter().map(|&id| mass(id) * bodies[id.index()].dp).sum::<DVec3>() / total
    };
    let largest_error = |bodies: &[SolverBody]| {
        world
            .joints
            .iter()
            .map(|(_, j)| {
                let rows = j.equality_rows(&bodies[j.body_a.index()], &bodies[j.body_b.index()]).unwrap();
                rows.error[..rows.len].iter().fold(0.0_f64, |m, e| m.max(e.abs()))
            })
            .fold(0.0, f64::max)
    };
    // Momentum, and angular momentum about the (kept) centre of mass.
    let momenta = |bodies: &[SolverBody]| {
        let c = centre(bodies);
        ids.iter().fold((DVec3::ZERO, DVec3::ZERO), |(p, l), &id| {
            let body = &bodies[id.index()];
            let (m, inertia) = body.mass_matrix().unwrap();
            let x = world.bodies.get(id.into()).unwrap().com_world() + body.dp;
            (p + m * body.v, l + m * (x - c).cross(body.v) + inertia * body.w)
        })
    };
    let (centre_before, error_before) = (centre(&bodies), largest_error(&bodies));
    let ((p_before, l_before), spins) = (momenta(&bodies), bodies.iter().map(|b| b.w).collect::<Vec<_>>());
    assert!(error_before > 0.02, "the figure starts apart: {error_before}");

    let tolerance = 1e-9;
    trees.project_positions(world.joints.slots(), &mut bodies, &world.bodies, tolerance, 8, ctx.h);
    let error_after = largest_error(&bodies);
    assert!(error_after <= tolerance, "largest error {error_before:e} -> {error_after:e}");
    let moved = (centre(&bodies) - centre_before).length();
    assert!(moved < 1e-14, "the centre of mass moved by {moved:e} m");
    let (p_after, l_after) = momenta(&bodies);
    assert!((p_after - p_before).length() < 1e-13 * p_before.length(), "{p_before} -> {p_after}");
    assert!((l_after - l_before).length() < 1e-12 * l_before.length(), "{l_before} -> {l_after}");
    let spin = bodies[ids[0].index()].w - spins[ids[0].index()];
    assert!(spin.length() > 1e-6, "the moves took some angular momentum: {spin}");
    for &id in &ids {
        let turned = bodies[id.index()].w - spins[id.index()];
        assert!((turned - spin).length() < 1e-12, "one rigid spin: {turned} against {spin}");
    }
}

/// A branching figure hung from the ground, with a loop and a second joint to the ground: the
/// loop's joints stay out of the forest, and since they act on the figure, so does the rest of
/// it. Without them the figure is one tree, and one solve makes every tree row's velocity `−β C`
/// to round-off, whatever the mass ratios.
#[test]
fn one_solve_satisfies_every_tree_row_exactly() {
    let mut world = World::new(Default::default()).unwrap();
    let cuboid = |h: f64| Some(Shape::Cuboid(Cuboid::new(DVec3::splat(h)).unwrap()));
    let ground = world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            position: DVec3::new(0.0, 0.0, 3.0),
            ..Default::default()
        })
        .unwrap();
    let mut body = |x: f64, z: f64, half: f64, density: f64| {
        world
            .add_body(BodyDef {
                shape: cuboid(half),
                density,
                position: DVec3::new(x, 0.0, z),
                orientation: DQuat::from_rotation_x(0.3 * x + z),
                ..Default::default()
            })
            .unwrap()
    };
    let b1 = body(0.0, 2.5, 0.1, 1000.0);
    let b2 = body(-0.4, 2.0, 0.1, 1000.0);
    let b3 = body(0.4, 2.0, 0.2, 1000.0);
    let b4 = body(-0.4, 1.5, 0.3, 100_000.0); // 1000 times heavier than b1
    let joint = |world: &mut World, a, b, anchor: DVec3, kind| {
        world.add_joint(JointDef::new(a, b, anchor, kind).with_axis(DVec3::new(0.3, 1.0, 0.2))).unwrap()
    };
    joint(&mut world, ground, b1, DVec3::new(0.0, 0.0, 2.8), JointKind::Ball(BallJoint::new()));
    joint(&mut world, b1, b2, DVec3::new(-0.2, 0.0, 2.25), JointKind::Hinge(HingeJoint::default()));
    joint(&mut world, b1, b3, DVec3::new(0.2, 0.0, 2.25), JointKind::Ball(BallJoint::new()));
    let loop_joint =
        joint(&mut world, b2, b3, DVec3::new(0.0, 0.0, 2.0), JointKind::Fixed(FixedJoint::new()));
    let ground_joint =
        joint(&mut world, b3, ground, DVec3::new(0.6, 0.0, 2.0), JointKind::Ball(BallJoint::new()));
    joint(&mut world, b2, b4, DVec3::new(-0.4, 0.0, 1.75), JointKind::Slider(SliderJoint::default()));
    // Velocities and a drift, so rows have both `Ċ` and `C`.
    for (k, id) in [b1, b2, b3, b4].into_iter().enumerate() {
        let k = k as f64;
        world.set_linear_velocity(id, DVec3::new(0.3 * k - 0.5, 0.2, -0.1 * k)).unwrap();
        world.set_angular_velocity(id, DVec3::new(1.0 - k, 0.5 * k, 0.3)).unwrap();
        world.bodies.get_mut(id.into()).unwrap().state.com_world += DVec3::new(0.001 * k, -0.002, 0.0005);
    }

    prepared(&mut world);
    assert!(world.joints.iter().all(|(_, j)| !j.in_tree), "the loop takes the whole figure out");
    world.remove_joint(loop_joint).unwrap();
    world.remove_joint(ground_joint).unwrap();
    let (_, mut bodies, mut trees) = prepared(&mut world);
    assert!(world.joints.iter().all(|(_, j)| j.in_tree));

    let beta = 40.0;
    trees.solve(world.joints.slots_mut(), &mut bodies, beta, 60.0);
    for (_, j) in world.joints.iter().filter(|(_, j)| j.in_tree) {
        let (a, b) = (&bodies[j.body_a.index()], &bodies[j.body_b.index()]);
        let rows = j.equality_rows(a, b).unwrap();
        for k in 0..rows.len {
            let residual = rows.rows[k].velocity(a, b) + beta * rows.error[k];
            assert!(residual.abs() < 1e-11, "{} row {k}: residual {residual:e}", j.kind.name());
        }
    }
}

/// Three figures of two welded boxes each; the first also hangs from the ground on a hinge with
/// a motor, which the row-by-row solve keeps. Only the second is a tree: the first figure's weld
/// goes row by row with the hinge (`leave_out_held_figures`), and so does a figure a distance
/// joint reaches.
#[test]
fn figures_other_joints_act_on_are_not_trees() {
    let mut world = World::new(Default::default()).unwrap();
    let ground = world.add_body(BodyDef { kind: BodyKind::Static, ..Default::default() }).unwrap();
    let boxes: Vec<_> = (0..6)
        .map(|k| {
            world
                .add_body(BodyDef {
                    shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.1)).unwrap())),
                    position: DVec3::new(0.3 * k as f64, 0.0, 1.0),
                    ..Default::default()
                })
                .unwrap()
        })
        .collect();
    let weld = |world: &mut World, k: usize| {
        let anchor = DVec3::new(0.3 * k as f64 + 0.15, 0.0, 1.0);
        world
            .add_joint(JointDef::new(boxes[k], boxes[k + 1], anchor, JointKind::Fixed(FixedJoint::new())))
            .unwrap();
    };
    weld(&mut world, 0);
    weld(&mut world, 2);
    weld(&mut world, 4);
    let motor = crate::Motor { target_speed: 1.0, max_force: 10.0 };
    let driven = HingeJoint { motor: Some(motor), ..Default::default() };
    let hinge = JointDef::new(ground, boxes[0], DVec3::new(-0.15, 0.0, 1.0), JointKind::Hinge(driven));
    world.add_joint(hinge.with_axis(DVec3::Y)).unwrap();
    let rope = JointKind::Distance(crate::DistanceJoint::default());
    world.add_joint(JointDef::new(ground, boxes[5], DVec3::new(1.5, 0.0, 2.0), rope)).unwrap();

    let (_, _, trees) = prepared(&mut world);
    let in_tree: Vec<bool> = world.joints.iter().map(|(_, j)| j.in_tree).collect();
    assert_eq!(in_tree, [false, true, false, false, false]);
    assert_eq!(trees.nodes.len(), 3, "one figure: two bodies and their weld");
}

/// Limit rows in the tree (an active set): after one solve every eligible limit row moves at
/// least at its target velocity, pushes (impulse ≥ 0), and pushes only where it moves exactly at
/// its target; a row that is not eligible (the farther side of a range) is let go of, its
/// impulse back at zero. The boxes spin hard about the joints' axis, the first two apart
/// towards the hinge's upper limit, the last two towards the ball joint's lower twist limit, each
/// fast enough to reach it within the substep (1/480 s).
#[test]
fn limit_rows_in_the_tree_push_only_and_hold_their_targets() {
    let hinge = HingeJoint { limits: Some(crate::Limits::new(-0.5, 0.2)), ..Default::default() };
    let ball = BallJoint {
        swing_limit: Some(0.3),
        twist_limits: Some(crate::Limits::new(-0.1, 0.4)),
        ..Default::default()
    };
    let (mut world, ids) =
        three_boxes(DVec3::new(0.2, 0.1, 0.1), 0.0, [JointKind::Hinge(hinge), JointKind::Ball(ball)]);
    let (ctx, mut bodies, mut trees) = prepared(&mut world);
    assert!(world.joints.iter().all(|(_, j)| j.in_tree), "limited joints are tree joints");
    // The joint axis is Z (`JointDef`'s default): spin the boxes about it, apart.
    bodies[ids[0].index()].w = DVec3::new(0.0, 0.0, -200.0);
    bodies[ids[1].index()].w = DVec3::new(0.0, 0.0, 100.0);
    bodies[ids[2].index()].w = DVec3::new(5.0, 0.0, -100.0);
    // A warm-started impulse on the hinge's lower side, which is not eligible (0.5 rad away,
    // heading off): the solve must let go of it.
    let hinge_slot = world.joints.iter().next().unwrap().0;
    world.joints.get_mut(hinge_slot).unwrap().add_limit_impulse(0, 2.0);
    warm_start(&mut world, &mut bodies);
    let bias_rate = 10.0;
    trees.solve(world.joints.slots_mut(), &mut bodies, bias_rate, ctx.inv_h);

    let mut pushing = 0;
    for (_, j) in world.joints.iter() {
        let (a, b) = (&bodies[j.body_a.index()], &bodies[j.body_b.index()]);
        let (mut rows, mut limits) = (EqualityRows::default(), LimitRows::default());
        assert!(j.tree_rows_into(a, b, &mut rows, &mut limits));
        for k in 0..rows.len {
            let residual = rows.rows[k].velocity(a, b) + bias_rate * rows.error[k];
            assert!(residual.abs() < 1e-9, "equality row {k}: {residual:e}");
        }
        for row in &limits.rows[..limits.len] {
            if !row.eligible {
                assert_eq!(row.impulse, 0.0, "a row not eligible keeps no impulse");
                continue;
            }
            let target = if row.error > 0.0 { -row.error * ctx.inv_h } else { -bias_rate * row.error };
            let velocity = row.jacobian.velocity(a, b);
            assert!(row.impulse >= 0.0, "a limit only pushes: {}", row.impulse);
            assert!(velocity >= target - 1e-9, "velocity {velocity} below its target {target}");
            if row.impulse > 0.0 {
                pushing += 1;
                assert!((velocity - target).abs() < 1e-9, "a pushing row moves at its target");
            }
        }
    }
    assert!(pushing >= 2, "both joints' limits are reached ({pushing} rows push)");
}

/// A limit row that pushed at the end of the last pass starts the next one in the active set;
/// when its joint is now moving away from the limit the solve would have it pull, so it leaves
/// the set and its impulse goes back to zero, taken off the bodies' velocities.
#[test]
fn a_limit_row_that_would_pull_is_let_go() {
    let hinge = HingeJoint { limits: Some(crate::Limits::new(-0.5, 0.2)), ..Default::default() };
    let kinds = [JointKind::Hinge(hinge), JointKind::Ball(BallJoint::new())];
    let (mut world, ids) = three_boxes(DVec3::new(0.2, 0.1, 0.1), 0.0, kinds);
    let (ctx, mut bodies, mut trees) = prepared(&mut world);
    // Turning slowly away from the upper limit (the nearer side), which pushed last pass.
    bodies[ids[0].index()].w = DVec3::new(0.0, 0.0, 2.0);
    bodies[ids[1].index()].w = DVec3::new(0.0, 0.0, -2.0);
    // The same figure without the impulse, solved alike, for comparison.
    let (mut clean_world, mut clean_bodies, mut clean_trees) = (world.clone(), bodies.clone(), trees.clone());
    clean_trees.solve(clean_world.joints.slots_mut(), &mut clean_bodies, 10.0, ctx.inv_h);
    let hinge_slot = world.joints.iter().next().unwrap().0;
    world.joints.get_mut(hinge_slot).unwrap().add_limit_impulse(1, 3.0);
    warm_start(&mut world, &mut bodies);
    trees.solve(world.joints.slots_mut(), &mut bodies, 10.0, ctx.inv_h);

    let joint = world.joints.get(hinge_slot).unwrap();
    let (a, b) = (&bodies[joint.body_a.index()], &bodies[joint.body_b.index()]);
    let (mut rows, mut limits) = (EqualityRows::default(), LimitRows::default());
    assert!(joint.tree_rows_into(a, b, &mut rows, &mut limits));
    let upper = &limits.rows[1];
    assert!(upper.eligible, "the upper side is the nearer");
    assert_eq!(upper.impulse, 0.0, "let go of, not pulling");
    assert!(upper.jacobian.velocity(a, b) > 0.0, "moving away");
    // The let-go impulse took back exactly what the warm start gave: every body moves as in the
    // figure that never had the impulse.
    for (body, clean) in bodies.iter().zip(&clean_bodies) {
        assert!((body.v - clean.v).length() < 1e-9 && (body.w - clean.w).length() < 1e-9);
    }
}
