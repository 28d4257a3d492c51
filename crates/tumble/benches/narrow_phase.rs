//! Narrow-phase cost per pair: a box resting on a box (SAT + clipping, 4 points, warm cache), and
//! two 20-point random hulls overlapping by 5 mm in up to 64 poses (SAT over hull faces and
//! Gauss-map edge pairs), and two 10-point hulls like the convex pile's, likewise.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use tumble::collision::{collide, PairCache};
use tumble::{ConvexHull, Cuboid, DQuat, DVec3, Shape, Transform};

fn random_hull(seed: u64) -> ConvexHull {
    random_hull_of(seed, 20, DVec3::splat(0.5))
}

/// `count` random points on the ellipsoid of radii `radii`, and their hull.
fn random_hull_of(seed: u64, count: usize, radii: DVec3) -> ConvexHull {
    let mut s = seed | 1;
    let mut rnd = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let pts: Vec<DVec3> = (0..count).map(|_| DVec3::new(rnd(), rnd(), rnd()).normalize() * radii).collect();
    ConvexHull::new(&pts).expect("random points on a sphere have a hull")
}

fn bench(c: &mut Criterion) {
    let ground = Shape::Cuboid(Cuboid::new(DVec3::new(5.0, 5.0, 0.5)).unwrap());
    let cube = Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).unwrap());
    let pose_cube = Transform::new(DVec3::new(0.1, 0.2, 0.995), DQuat::from_rotation_z(0.3));
    let mut cache = PairCache::default();
    c.bench_function("box_box_resting", |b| {
        b.iter(|| {
            collide(black_box(&ground), &Transform::IDENTITY, black_box(&cube), &pose_cube, 0.02, &mut cache)
        })
    });

    let (ha, hb) = (Shape::ConvexHull(random_hull(7)), Shape::ConvexHull(random_hull(11)));
    bench_overlapping(c, "hull_hull_overlapping", &ha, &hb);
    // The convex pile's hulls: ten points on an ellipsoid of radii 0.25-0.45 m.
    let (ha, hb) = (
        Shape::ConvexHull(random_hull_of(3, 10, DVec3::new(0.3, 0.4, 0.35))),
        Shape::ConvexHull(random_hull_of(5, 10, DVec3::new(0.42, 0.27, 0.33))),
    );
    bench_overlapping(c, "hull10_hull10_overlapping", &ha, &hb);
}

/// B overlapping A by 5 mm from up to 64 directions, each turned its own way: one pose asked
/// again and again would let the processor learn every branch of the test by heart, which a
/// scene's thousands of different pairs never allow.
fn bench_overlapping(c: &mut Criterion, name: &str, ha: &Shape, hb: &Shape) {
    let mut poses: Vec<(Transform, PairCache)> = (0..64)
        .map(|k| {
            let t = k as f64;
            let dir = DVec3::new((0.7 * t).cos(), (0.7 * t).sin(), (1.3 * t).sin()).normalize();
            let q = DQuat::from_axis_angle(DVec3::new(t.sin(), 1.0, (2.0 * t).cos()).normalize(), 0.4 * t);
            // Close the gap until the deepest point is 5 mm in. One move along the first query's
            // normal is not enough: apart, the axis's separation is only a lower bound of the
            // distance (a corner nearest a corner), and most poses stayed apart after it.
            let mut pose_b = Transform::new(2.0 * dir, q);
            for _ in 0..100 {
                let m = collide(ha, &Transform::IDENTITY, hb, &pose_b, 10.0, &mut PairCache::default())
                    .expect("within 10 m");
                let gap = m.min_separation() + 0.005;
                if gap.abs() < 1e-5 {
                    break;
                }
                pose_b.translation -= m.normal_world * gap;
            }
            (pose_b, PairCache::default())
        })
        .collect();
    // Only the poses that overlap (the closing can cycle between two features, rarely).
    poses.retain(|(pose_b, _)| {
        collide(ha, &Transform::IDENTITY, hb, pose_b, 0.02, &mut PairCache::default())
            .is_some_and(|m| m.min_separation() < 0.0)
    });
    assert!(poses.len() >= 56, "{} of 64 poses overlap", poses.len());
    // The pose count is in the name: the time is for all of them.
    c.bench_function(&format!("{name}_{}_poses", poses.len()), |b| {
        b.iter(|| {
            poses
                .iter_mut()
                .map(|(pose_b, cache)| {
                    let m = collide(black_box(ha), &Transform::IDENTITY, black_box(hb), pose_b, 0.02, cache);
                    m.map_or(0, |m| m.len())
                })
                .sum::<usize>()
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
