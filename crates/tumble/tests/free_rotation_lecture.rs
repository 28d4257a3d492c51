//! The lecture's explicit rotation update against the engine's splitting update, on VALIDATION.md
//! F2/F3 (I = (1, 2, 3), ω₀ = (0.01, 5, 0.01), dt = 1/240, 100 s). The explicit update drifts in
//! energy and gets the flip interval wrong; the engine's keeps both.

mod common;

use common::{flip_interval, sign_changes};
use tumble::integrate::{explicit_rotation_step, free_rotation_step};
use tumble::{DQuat, DVec3};

struct Run {
    max_energy_error: f64,
    final_energy_error: f64,
    flips: usize,
    flip_interval: f64,
}

fn run(update: fn(DQuat, DVec3, DVec3, f64) -> DQuat) -> Run {
    let inertia = DVec3::new(1.0, 2.0, 3.0);
    let w0 = DVec3::new(0.01, 5.0, 0.01);
    let l_world = inertia * w0;
    let e0 = 0.5 * l_world.dot(w0);
    let h = 1.0 / 240.0;
    let mut q = DQuat::IDENTITY;
    let (mut times, mut wy) = (vec![0.0], vec![w0.y]);
    let (mut max_err, mut err) = (0.0_f64, 0.0);
    for n in 1..=24_000 {
        q = update(q, l_world, inertia, h);
        let w_body = (q.inverse() * l_world) / inertia;
        err = (0.5 * (q.inverse() * l_world).dot(w_body) - e0) / e0;
        max_err = max_err.max(err.abs());
        times.push(f64::from(n) * h);
        wy.push(w_body.y);
    }
    let flips = sign_changes(&times, &wy);
    let interval = if flips.len() >= 2 {
        (flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64
    } else {
        f64::NAN
    };
    Run { max_energy_error: max_err, final_energy_error: err, flips: flips.len(), flip_interval: interval }
}

#[test]
fn explicit_update_drifts_and_splitting_does_not() {
    let analytic = flip_interval(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.01, 5.0, 0.01));
    let engine = run(free_rotation_step);
    let lecture = run(explicit_rotation_step);
    for (name, r) in [("splitting (engine)", &engine), ("explicit (lecture)", &lecture)] {
        println!(
            "{name:>20}: max |ΔE|/E = {:.3e}, final ΔE/E = {:+.3e}, flips = {}, interval = {:.4} s \
             (analytic {analytic:.4} s, error {:+.2}%)",
            r.max_energy_error,
            r.final_energy_error,
            r.flips,
            r.flip_interval,
            100.0 * (r.flip_interval - analytic) / analytic
        );
    }
    // The engine: bounded energy error and the right flip interval.
    assert!(engine.max_energy_error < 1e-4);
    assert!(((engine.flip_interval - analytic) / analytic).abs() < 0.01);
    // The lecture's update: energy grows steadily (the explicit rotation by ω·h always adds energy
    // for this motion) by far more than the bound, and the flip interval is off by more than 1%.
    assert!(lecture.final_energy_error.abs() > 1e-3, "explicit update drift {}", lecture.final_energy_error);
    assert!(
        lecture.flips < 2 || ((lecture.flip_interval - analytic) / analytic).abs() > 0.01,
        "the explicit update unexpectedly got the flip interval right"
    );
}
