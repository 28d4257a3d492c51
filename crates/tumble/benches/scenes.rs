//! The shared benchmark scenes (BENCHMARKS.md), one `World::step` per iteration on the world as it
//! evolves: `pyramid` (base 20), `large_pyramid` (base 100), `rain`, `chain`, `ragdolls`,
//! `convex_pile` and `tumbling` at their default sizes. After each scene's measurement its
//! quality result is printed once, with the number of steps it has then taken.
//!
//!     cargo bench -p tumble --bench scenes [-- pyramid]

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use tumble::scenes;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("scenes");
    for name in scenes::NAMES {
        let mut scene = scenes::by_name(name, None).expect("a known scene");
        let big = scene.world.body_count() > 1_000;
        group.sample_size(10);
        group.warm_up_time(Duration::from_secs(if big { 1 } else { 2 }));
        group.measurement_time(Duration::from_secs(if big { 10 } else { 5 }));
        let mut measured = false;
        group.bench_function(name, |b| {
            measured = true;
            b.iter(|| scene.step())
        });
        if measured {
            println!("{name}: after {} steps: {}", scene.world.step_count(), scene.quality());
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
