//! Prints energy drift and flip interval of the lecture's explicit rotation update and the engine's
//! splitting update on the Dzhanibekov handle (I = (1, 2, 3), ω₀ = (0.01, 5, 0.01), 240 Hz).
//! Run: `cargo run --release -p tumble --example compare_rotation_updates`.

use tumble::integrate::{explicit_rotation_step, free_rotation_step};
use tumble::{DQuat, DVec3};

fn main() {
    let inertia = DVec3::new(1.0, 2.0, 3.0);
    let w0 = DVec3::new(0.01, 5.0, 0.01);
    let l_world = inertia * w0;
    let e0 = 0.5 * l_world.dot(w0);
    let h = 1.0 / 240.0;
    println!(
        "{:>8} {:>14} {:>14} {:>10} {:>10}",
        "t (s)", "ΔE/E engine", "ΔE/E lecture", "ωy engine", "ωy lecture"
    );
    let (mut q_engine, mut q_lecture) = (DQuat::IDENTITY, DQuat::IDENTITY);
    for n in 1..=24_000 {
        q_engine = free_rotation_step(q_engine, l_world, inertia, h);
        q_lecture = explicit_rotation_step(q_lecture, l_world, inertia, h);
        if n % 1200 == 0 {
            let stats = |q: DQuat| {
                let l_body = q.inverse() * l_world;
                let w = l_body / inertia;
                ((0.5 * l_body.dot(w) - e0) / e0, w.y)
            };
            let (de_e, wy_e) = stats(q_engine);
            let (de_l, wy_l) = stats(q_lecture);
            println!("{:>8.1} {de_e:>+14.3e} {de_l:>+14.3e} {wy_e:>10.4} {wy_l:>10.4}", f64::from(n) * h);
        }
    }
}
