//! Narrow phase against static geometry, per pair: one iteration = one `collide` call for a shape
//! resting on a floor, as the contact manager makes it every step.
//!
//! - `capsule_mesh`: a capsule (r = 0.1 m, half height 0.3 m) lying across a 20 × 20 grid mesh of
//!   0.25 m cells (800 triangles), slightly sunk; turned 0.3 rad so it crosses several triangles.
//! - `box_mesh`, `sphere_heightfield`, `box_plane`: the same floor with other shapes, for scale.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use tumble::collision::narrow_phase::{collide, PairCache};
use tumble::{Capsule, Cuboid, DQuat, DVec3, HeightField, Plane, Shape, Sphere, Transform, TriMesh};

const MARGIN: f64 = 0.02;

/// An `n × n` grid of square cells of side `cell` on z = 0, centred, two triangles per cell.
fn grid_floor(n: usize, cell: f64) -> TriMesh {
    let half = 0.5 * n as f64 * cell;
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            vertices.push(DVec3::new(i as f64 * cell - half, j as f64 * cell - half, 0.0));
        }
    }
    let idx = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    TriMesh::new_static(vertices, triangles).expect("valid grid")
}

fn bench(c: &mut Criterion) {
    let mesh = Shape::TriMesh(grid_floor(20, 0.25));
    let heightfield = Shape::HeightField(
        HeightField::new(vec![0.0; 21 * 21], 21, 21, DVec3::new(0.25, 0.25, 1.0))
            .expect("valid height field"),
    );
    let plane = Shape::Plane(Plane::new(DVec3::Z, 0.0).expect("valid plane"));
    let capsule = Shape::Capsule(Capsule::new(0.1, 0.3).expect("valid capsule"));
    let lying = DQuat::from_rotation_z(0.3) * DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    let capsule_pose = Transform::new(DVec3::new(0.07, 0.11, 0.099), lying);
    let cube = Shape::Cuboid(Cuboid::new(DVec3::new(0.3, 0.2, 0.1)).expect("valid box"));
    let box_pose = Transform::new(DVec3::new(0.07, 0.11, 0.099), DQuat::from_rotation_z(0.3));
    let sphere = Shape::Sphere(Sphere::new(0.2).expect("valid sphere"));
    let sphere_pose = Transform::new(DVec3::new(0.07, 0.11, 0.199), DQuat::IDENTITY);
    let floor_pose = Transform::IDENTITY;

    let m = collide(&mesh, &floor_pose, &capsule, &capsule_pose, MARGIN, &mut PairCache::default());
    assert_eq!(m.map(|m| m.len()), Some(2), "the lying capsule has two contact points");

    let mut group = c.benchmark_group("static_contact");
    for (name, floor, shape, pose) in [
        ("capsule_mesh", &mesh, &capsule, &capsule_pose),
        ("box_mesh", &mesh, &cube, &box_pose),
        ("sphere_heightfield", &heightfield, &sphere, &sphere_pose),
        ("box_plane", &plane, &cube, &box_pose),
    ] {
        let mut cache = PairCache::default();
        group.bench_function(name, |b| {
            b.iter(|| {
                collide(black_box(floor), &floor_pose, black_box(shape), black_box(pose), MARGIN, &mut cache)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
