//! C4 of VALIDATION.md: rolling without slipping.

use tumble::BodyDef;

mod common;
mod contact_support;
use common::slope;
use contact_support::*;

/// C4: a solid ball rolling down a 20° incline with μ = 0.8 accelerates at 5/7·g·sinθ within 1%,
/// and its contact point does not slip: the centre's speed equals ω r within 1%.
#[test]
fn c4_sphere_rolls_down_incline() {
    let theta = 20.0_f64.to_radians();
    let radius = 0.1;
    let mut world = world(Default::default());
    let slope_ = incline(&mut world, theta, material(0.8, 0.0));
    let start = slope_.downhill * -15.0 + slope_.normal * radius;
    let ball = world
        .add_body(BodyDef {
            name: "ball".into(),
            shape: sphere(radius),
            position: start,
            material: material(0.8, 0.0),
            ..Default::default()
        })
        .unwrap();
    let axis = slope_.normal.cross(slope_.downhill);
    let (mut times, mut speeds) = (vec![], vec![]);
    let mut worst_slip: f64 = 0.0;
    for n in 1..=150 {
        world.step(DT).unwrap();
        let t = f64::from(n) * DT;
        let b = world.body(ball).unwrap();
        let v = b.linear_velocity().dot(slope_.downhill);
        let w_r = b.angular_velocity().dot(axis) * radius;
        if t >= 0.25 {
            times.push(t);
            speeds.push(v);
            worst_slip = worst_slip.max(((v - w_r) / v).abs());
        }
    }
    let a = slope(&times, &speeds);
    let exact = 5.0 / 7.0 * G * theta.sin();
    let error = (a - exact) / exact;
    println!(
        "C4: acceleration {a:.5} m/s², 5/7 g sinθ = {exact:.5} m/s² ({:+.3}%); largest slip |v − ωr|/v = {:.2e} after 0.25 s",
        100.0 * error,
        worst_slip
    );
    assert!(error.abs() < 0.01, "acceleration error {:.3}%", 100.0 * error);
    assert!(worst_slip < 0.01, "slip {worst_slip}");
}
