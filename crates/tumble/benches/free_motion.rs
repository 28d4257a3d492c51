//! Free motion of 10,000 tumbling bodies under gravity: the cost of one body-step of the
//! integrator (translation + splitting rotation update), reported per body.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use tumble::{BodyDef, DMat3, DQuat, DVec3, MassProperties, World};

const BODIES: usize = 10_000;

fn world_of_tumbling_bodies() -> World {
    let mut world = World::default();
    for i in 0..BODIES {
        let f = i as f64;
        world
            .add_body(BodyDef {
                mass_properties: Some(MassProperties {
                    volume: 1.0,
                    mass: 1.0 + (f * 0.37).sin().abs(),
                    center_of_mass: DVec3::ZERO,
                    inertia: DMat3::from_diagonal(DVec3::new(1.0, 2.0 + (f * 0.1).cos(), 3.5)),
                }),
                position: DVec3::new(f, 0.0, 0.0),
                orientation: DQuat::from_rotation_z(f * 0.01),
                angular_velocity: DVec3::new(0.1, 5.0, (f * 0.3).sin()),
                ..Default::default()
            })
            .expect("valid body");
    }
    world
}

fn free_motion(c: &mut Criterion) {
    let mut group = c.benchmark_group("free_motion");
    // Throughput in elements = bodies, so criterion reports body-steps per second.
    group.throughput(Throughput::Elements(BODIES as u64));
    group.bench_function("step_10000_bodies", |b| {
        b.iter_batched_ref(
            world_of_tumbling_bodies,
            |world| world.step(1.0 / 240.0).expect("valid step"),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, free_motion);
criterion_main!(benches);
