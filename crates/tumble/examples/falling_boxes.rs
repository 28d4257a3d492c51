//! 1,000 boxes (10 × 10 × 10, half size 0.2 m, 0.5 m apart) falling onto a static ground: the
//! scene of `bench/python_overhead.py`, built identically to its Python side. Prints the
//! seconds per step and the final state hash (equal to Python's `World.state_hash()` when the
//! scenes match). `STEPS` (120) sets the number of 1/60 s steps.
//!
//! Run: `cargo run --release -p tumble --example falling_boxes`.

use std::time::Instant;

use tumble::{BodyDef, BodyKind, Cuboid, DVec3, Shape, World, WorldDef};

fn main() {
    let steps: usize = std::env::var("STEPS").ok().and_then(|s| s.parse().ok()).unwrap_or(120);
    let mut world = World::new(WorldDef::default()).expect("valid settings");
    let cube = |h: DVec3| Some(Shape::Cuboid(Cuboid::new(h).expect("positive size")));
    world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: cube(DVec3::new(20.0, 20.0, 0.5)),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        })
        .expect("valid ground");
    for k in 0..10 {
        for j in 0..10 {
            for i in 0..10 {
                let position =
                    DVec3::new((i as f64 - 4.5) * 0.5, (j as f64 - 4.5) * 0.5, 0.5 + k as f64 * 0.5);
                let def = BodyDef { shape: cube(DVec3::splat(0.2)), position, ..Default::default() };
                world.add_body(def).expect("valid box");
            }
        }
    }
    let dt = 1.0 / 60.0;
    let start = Instant::now();
    for _ in 0..steps {
        world.step(dt).expect("valid step");
    }
    let seconds = start.elapsed().as_secs_f64();
    println!("bodies {}", world.body_count());
    println!("steps {steps}");
    println!("seconds_per_step {:.9}", seconds / steps as f64);
    println!("state_hash {:#018x}", world.state_hash());
}
