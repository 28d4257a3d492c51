//! A vertical stack of unit boxes on a static ground: prints, once a second, the top box's height,
//! the largest tilt, contacts and awake bodies, then each box's drift from its start. Settings come
//! from the environment so the solver can be explored without recompiling:
//! `N` (boxes, 10), `SUBSTEPS` (8), `CONTACT_HERTZ` (60), `STEADY_LOAD_TIME` (0.1), `FRICTION` (0.6), `SECONDS` (10).
//!
//! Run: `cargo run --release -p tumble --example box_stack`.

use tumble::{BodyDef, BodyKind, Cuboid, DQuat, DVec3, Material, Shape, SolverSettings, World, WorldDef};

fn setting(key: &str, default: f64) -> f64 {
    std::env::var(key).ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

fn main() {
    let solver = SolverSettings {
        substeps: setting("SUBSTEPS", 8.0) as u32,
        contact_hertz: setting("CONTACT_HERTZ", 60.0),
        steady_load_time: setting("STEADY_LOAD_TIME", 0.1),
        solve_iterations: setting("SOLVE_ITERATIONS", 1.0) as u32,
        relax_iterations: setting("RELAX_ITERATIONS", 1.0) as u32,
        ..Default::default()
    };
    let mut world = World::new(WorldDef { solver, ..Default::default() }).expect("valid settings");
    let cube = |h: DVec3| Some(Shape::Cuboid(Cuboid::new(h).expect("positive size")));
    world
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: cube(DVec3::new(10.0, 10.0, 0.5)),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        })
        .expect("valid ground");
    let count = setting("N", 10.0) as usize;
    let material = Material { friction: setting("FRICTION", 0.6), ..Default::default() };
    let boxes: Vec<_> = (0..count)
        .map(|i| {
            let def = BodyDef {
                shape: cube(DVec3::splat(0.5)),
                position: DVec3::new(0.0, 0.0, 0.5 + i as f64),
                material,
                ..Default::default()
            };
            world.add_body(def).expect("valid box")
        })
        .collect();
    let dt = 1.0 / 60.0;
    let steps = (setting("SECONDS", 10.0) / dt).round() as usize;
    for step in 1..=steps {
        world.step(dt).expect("valid step");
        if step % 60 == 0 {
            let tilt = boxes
                .iter()
                .map(|&id| world.body(id).unwrap().orientation().angle_between(DQuat::IDENTITY))
                .fold(0.0, f64::max);
            let top = world.body(*boxes.last().unwrap()).unwrap().position();
            println!(
                "t = {:5.2} s  top z = {:.5}  max tilt = {tilt:.2e} rad  contacts = {}  awake = {}",
                step as f64 * dt,
                top.z,
                world.contact_count(),
                world.awake_body_count()
            );
        }
    }
    println!("drift of each box from its start (m):");
    for (i, &id) in boxes.iter().enumerate() {
        let drift = world.body(id).unwrap().position() - DVec3::new(0.0, 0.0, 0.5 + i as f64);
        println!("{i:3}: {:+.5} {:+.5} {:+.5}", drift.x, drift.y, drift.z);
    }
}
