//! Contact validation, resting contact under load: VALIDATION.md C7 and C8, and the iterative
//! solver's resting impulses against the exact LCP solution (`dynamics::lcp::solve_exact`).
//! Each test prints its measurement next to the bound.
//!
//! A plain soft contact sags under load: carrying `L` it settles where its spring `k = m_eff ω²`
//! balances it, `L/(m_eff ω²)` (ω = 2π·contact hertz, doubled against static bodies). The
//! contacts learn their steady load and hold it without sagging (`steady_load_time`), which is
//! what these tests check at the defaults; `measure_stacking_across_settings` prints the sag
//! with and without it.

use tumble::dynamics::lcp::{contact_rows, solve_exact, Anchor, BodyVelocity, ContactPoint, LcpBody, Row};
use tumble::{BodyId, DVec3, SleepSettings, SolverSettings, World, WorldDef};

mod contact_support;
use contact_support::*;

/// A stack of `n` unit boxes run for 10 s at dt = 1/60: (largest drift from the start, index of
/// that box, all asleep at the end, steps/s).
fn stack(settings: SolverSettings, n: usize) -> (f64, usize, bool, f64) {
    let mut world = world(settings);
    ground(&mut world, material(0.6, 0.0));
    let ids = box_stack(&mut world, n);
    let starts: Vec<DVec3> = ids.iter().map(|&id| world.body(id).unwrap().position()).collect();
    let rate = timed_steps(&mut world, 600);
    let (drift, index) = largest_drift(&world, &ids, &starts);
    (drift, index, world.awake_body_count() == 0, rate)
}

/// C7: a vertical stack of 10 unit boxes, dt = 1/60: after 10 s every box is within 1 mm of its
/// start, and the stack is asleep.
#[test]
fn c7_box_stack_holds_and_sleeps() {
    let (drift, index, asleep, rate) = stack(SolverSettings::default(), 10);
    println!(
        "C7 (defaults): largest drift {:.3} mm (box {index}), asleep {asleep}, {rate:.0} steps/s",
        1e3 * drift
    );
    assert!(asleep, "the stack falls asleep");
    assert!(drift < 1e-3, "drift {drift} m");
}

/// A pyramid with `base` unit boxes in its bottom row run for 10 s at dt = 1/60: (largest drift,
/// box count, steps/s).
fn pyramid(settings: SolverSettings, base: usize) -> (f64, usize, f64) {
    let mut world = world(settings);
    ground(&mut world, material(0.6, 0.0));
    let ids = box_pyramid(&mut world, base);
    let starts: Vec<DVec3> = ids.iter().map(|&id| world.body(id).unwrap().position()).collect();
    let rate = timed_steps(&mut world, 600);
    (largest_drift(&world, &ids, &starts).0, ids.len(), rate)
}

/// C8: a pyramid of 210 unit boxes (base 20), dt = 1/60: after 10 s no box moved more than 1 cm.
#[test]
fn c8_pyramid_holds() {
    let (drift, count, rate) = pyramid(SolverSettings::default(), 20);
    println!("C8 (defaults): {count} boxes, largest drift {:.3} mm, {rate:.1} steps/s", 1e3 * drift);
    assert_eq!(count, 210);
    assert!(drift < 1e-2, "drift {drift} m");
}

/// C8 without sleep, for a minute: a pyramid that never falls asleep must stay put too, not just
/// for the first 10 s. The steady loads are a slow integral term on the soft contacts; learned too
/// fast (0.1 s), they fed the boxes' rocking between their two supports, which grew from 1e-5 J
/// of kinetic energy to 0.5 J between 30 and 50 s and moved the pyramid by 2 cm after 50 s and
/// 26 cm after 100 s (docs/solver.md, "Contacts that hold their load").
#[test]
fn c8_pyramid_holds_for_a_minute_awake() {
    let mut world = world(SolverSettings::default());
    world.set_sleep_settings(SleepSettings { enabled: false, ..Default::default() });
    ground(&mut world, material(0.6, 0.0));
    let ids = box_pyramid(&mut world, 20);
    let starts: Vec<DVec3> = ids.iter().map(|&id| world.body(id).unwrap().position()).collect();
    let mut worst: f64 = 0.0;
    for second in 1..=60 {
        timed_steps(&mut world, 60);
        let kinetic: f64 = ids.iter().map(|&id| world.body(id).unwrap().kinetic_energy()).sum();
        if second >= 10 {
            worst = worst.max(kinetic);
        }
    }
    let (drift, index) = largest_drift(&world, &ids, &starts);
    println!("C8 awake for 60 s: largest drift {:.3} mm (box {index}), largest kinetic energy after 10 s {worst:.2e} J", 1e3 * drift);
    assert!(drift < 1e-2, "drift {drift} m");
    // 210 boxes of 1 kg at rest; 1e-3 J is every box moving at 3 mm/s.
    assert!(worst < 1e-3, "kinetic energy {worst} J");
}

/// Per touching contact (in `world.contacts()` order): the total normal impulse of the step and its
/// moment `Σ λᵢ (pᵢ − c_b) × n` about body b's centre of mass, from the iterative solver and from
/// the exact LCP for the same bodies, contact points and step (velocities now plus a step of
/// gravity, no bias).
struct LayerComparison {
    iterative: Vec<(f64, DVec3)>,
    exact: Vec<(f64, DVec3)>,
    /// Index in `bodies` of the upper body of each contact.
    upper: Vec<usize>,
}

/// Takes one step of `world` and compares its contact impulses with the exact LCP of the same step:
/// the bodies as they were at the step's start (centres of mass, inverse inertias, velocities plus
/// the step's gravity) and the contact points the step's narrow phase found.
fn step_and_compare_with_lcp(world: &mut World, bodies: &[BodyId]) -> LayerComparison {
    let index = |id: BodyId| bodies.iter().position(|&b| b == id);
    let lcp_bodies: Vec<LcpBody> = bodies
        .iter()
        .map(|&id| {
            let b = world.body(id).unwrap();
            LcpBody::new(b.inverse_mass(), b.inverse_inertia_world())
        })
        .collect();
    let velocities: Vec<BodyVelocity> = bodies
        .iter()
        .map(|&id| {
            let b = world.body(id).unwrap();
            BodyVelocity::new(b.linear_velocity() + world.gravity() * DT, b.angular_velocity())
        })
        .collect();
    let coms: Vec<DVec3> = bodies.iter().map(|&id| world.body(id).unwrap().com_world()).collect();
    let com = |id: BodyId| index(id).map(|i| coms[i]);
    world.step(DT).unwrap();
    let world = &*world;
    let contacts = world.contacts();
    let mut rows: Vec<Row> = Vec::new();
    let mut iterative = Vec::new();
    let mut layers = Vec::new();
    let mut upper = Vec::new();
    for c in &contacts {
        let z = |id: BodyId| world.body(id).unwrap().com_world().z;
        upper.push(index(if z(c.body_b) > z(c.body_a) { c.body_b } else { c.body_a }).unwrap());
        let anchor = |id: BodyId, p: DVec3| match index(id) {
            Some(i) => Anchor::new(i, p - coms[i]),
            None => Anchor::WORLD,
        };
        let com_b = com(c.body_b).unwrap_or_else(|| world.body(c.body_b).unwrap().com_world());
        let friction = world.body(c.body_a).unwrap().material().friction
            * world.body(c.body_b).unwrap().material().friction;
        let mut first_row = Vec::new();
        let (mut total, mut moment) = (0.0, DVec3::ZERO);
        for p in &c.points {
            first_row.push(rows.len());
            let point = ContactPoint {
                a: anchor(c.body_a, p.point),
                b: anchor(c.body_b, p.point),
                normal: c.normal,
                tangent: c.normal.any_orthonormal_vector(),
                mu: friction.sqrt(),
                bias: 0.0,
            };
            rows.extend(contact_rows(&point, rows.len()));
            total += p.normal_impulse;
            moment += p.normal_impulse * (p.point - com_b).cross(c.normal);
        }
        iterative.push((total, moment));
        layers.push((first_row, com_b));
    }
    let solution = solve_exact(&lcp_bodies, &velocities, &rows).expect("the LCP solves");
    let exact = contacts
        .iter()
        .zip(&layers)
        .map(|(c, (first_rows, com_b))| {
            let (mut total, mut moment) = (0.0, DVec3::ZERO);
            for (p, &row) in c.points.iter().zip(first_rows) {
                let lambda = solution.impulses[row];
                total += lambda;
                moment += lambda * (p.point - *com_b).cross(c.normal);
            }
            (total, moment)
        })
        .collect();
    LayerComparison { iterative, exact, upper }
}

/// Reference-solver check: a unit box resting on the ground, and a stack of three, after 2 s of
/// settling (sleep off, so the solver keeps running): per contact layer the iterative solver's
/// normal impulse over a step is within 1% of the exact LCP's, and the moment of the layer's
/// normal impulses about the upper body's centre of mass agrees to 1% of (total impulse × half
/// width 0.5 m). Only these sums are compared: four coplanar contacts are statically
/// indeterminate, so the split among the points is not unique (docs/lcp.md).
#[test]
fn resting_impulses_match_the_exact_lcp() {
    for n in [1, 3] {
        let mut world = World::new(WorldDef {
            sleep: SleepSettings { enabled: false, ..Default::default() },
            ..Default::default()
        })
        .unwrap();
        ground(&mut world, material(0.6, 0.0));
        let ids = box_stack(&mut world, n);
        for _ in 0..119 {
            world.step(DT).unwrap();
        }
        let cmp = step_and_compare_with_lcp(&mut world, &ids);
        assert_eq!(cmp.exact.len(), n, "one contact layer per box");
        for ((it, ex), &layer) in cmp.iterative.iter().zip(&cmp.exact).zip(&cmp.upper) {
            let total_error = (it.0 - ex.0) / ex.0;
            let moment_error = (it.1 - ex.1).length() / (ex.0 * 0.5);
            let m = world.body(ids[0]).unwrap().mass();
            println!(
                "LCP ({n} boxes), under box {layer}: normal impulse iterative {:.6} N·s, exact {:.6} N·s ({:+.3e} relative; statics {:.6}), moment iterative {:.3e}, exact {:.3e} N·m·s (difference {:.2e} of Λ·0.5 m)",
                it.0,
                ex.0,
                total_error,
                (n - layer) as f64 * m * G * DT,
                it.1.length(),
                ex.1.length(),
                moment_error
            );
            assert!(total_error.abs() < 0.01, "layer {layer}: total normal impulse off by {total_error}");
            assert!(moment_error < 0.01, "layer {layer}: moment off by {moment_error}");
        }
    }
}

/// The solver settings tried for C7–C9 (and their names in the printout).
fn candidate_settings() -> Vec<(&'static str, SolverSettings)> {
    let s = |substeps, contact_hertz, steady_load_time| SolverSettings {
        substeps,
        contact_hertz,
        steady_load_time,
        ..Default::default()
    };
    vec![
        ("defaults (8 substeps, 60 Hz, steady load 0.5 s)", SolverSettings::default()),
        ("8 substeps, 60 Hz, no steady load", s(8, 60.0, 0.0)),
        ("4 substeps, 30 Hz, steady load 0.5 s", s(4, 30.0, 0.5)),
        ("4 substeps, 30 Hz, no steady load", s(4, 30.0, 0.0)),
    ]
}

/// Measurement, not a check: C7 and C8 across solver settings, with the cost in steps/s.
/// Run: `cargo test -p tumble --test contacts_stacking -- --ignored --nocapture`.
#[test]
#[ignore = "measurement: prints C7 and C8 across solver settings"]
fn measure_stacking_across_settings() {
    for (name, settings) in candidate_settings() {
        let (drift, index, asleep, rate) = stack(settings.clone(), 10);
        println!(
            "C7 [{name}]: largest drift {:.3} mm (box {index}), asleep {asleep}, {rate:.0} steps/s",
            1e3 * drift
        );
        let (drift, _, rate) = pyramid(settings.clone(), 20);
        println!("C8 [{name}]: largest drift {:.3} mm, {rate:.1} steps/s", 1e3 * drift);
    }
}
