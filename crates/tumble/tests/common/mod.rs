//! Analytic references shared by the validation tests and examples.
#![allow(dead_code)]

use tumble::{BodyDef, DMat3, DVec3, MassProperties};

/// Complete elliptic integral of the first kind K(k) for modulus² `m = k²`, by the
/// arithmetic–geometric mean: K = π / (2 AGM(1, √(1−m))). Converges quadratically.
pub fn elliptic_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - m).sqrt());
    while (a - b).abs() > 1e-16 * a {
        let next = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = next;
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Time between successive sign changes of the intermediate-axis angular velocity of a torque-free
/// body (the Dzhanibekov flip interval): half the period of the Jacobi functions sn/cn, `2K(k)/p`.
/// `inertia` must be ascending, `w_principal` the angular velocity in the principal frame.
/// (Landau & Lifshitz, Mechanics §37.)
pub fn flip_interval(inertia: DVec3, w_principal: DVec3) -> f64 {
    let (i1, i2, i3) = (inertia.x, inertia.y, inertia.z);
    let l2 = (inertia * w_principal).length_squared();
    let two_e = (inertia * w_principal).dot(w_principal);
    // The formulas are for L² > 2E·I₂; the other case swaps the roles of axes 1 and 3.
    let (i1, i3) = if l2 > two_e * i2 { (i1, i3) } else { (i3, i1) };
    let p = ((i3 - i2) * (l2 - two_e * i1) / (i1 * i2 * i3)).sqrt();
    let m = (i2 - i1) * (two_e * i3 - l2) / ((i3 - i2) * (l2 - two_e * i1));
    2.0 * elliptic_k(m) / p
}

/// Times where `values` change sign, linearly interpolated between samples.
pub fn sign_changes(times: &[f64], values: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 1..values.len() {
        let (a, b) = (values[i - 1], values[i]);
        if a * b < 0.0 {
            out.push(times[i - 1] + (times[i] - times[i - 1]) * a / (a - b));
        }
    }
    out
}

/// Mean spacing of a sorted list of event times.
pub fn mean_interval(events: &[f64]) -> f64 {
    assert!(events.len() >= 2, "need at least two events, got {}", events.len());
    (events[events.len() - 1] - events[0]) / (events.len() - 1) as f64
}

/// Least-squares slope of `ys` against `xs`.
pub fn slope(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// A body with mass `mass` and inertia `diag(inertia)` in its own frame, centre of mass at the origin.
pub fn body_with_inertia(mass: f64, inertia: DVec3) -> BodyDef {
    BodyDef {
        name: "body".into(),
        mass_properties: Some(MassProperties {
            volume: 1.0,
            mass,
            center_of_mass: DVec3::ZERO,
            inertia: DMat3::from_diagonal(inertia),
        }),
        ..Default::default()
    }
}
