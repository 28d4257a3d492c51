//! Scene builders shared by the contact validation tests (`contacts_*.rs`): a static ground box
//! with its top at z = 0, inclines as static boxes turned about Y, and small body helpers.
#![allow(dead_code)]

use std::time::Instant;
use tumble::{
    BodyDef, BodyId, BodyKind, Cuboid, DQuat, DVec3, Material, Shape, SolverSettings, Sphere, World, WorldDef,
};

pub const G: f64 = 9.81;
pub const DT: f64 = 1.0 / 60.0;

pub fn world(solver: SolverSettings) -> World {
    World::new(WorldDef { solver, ..Default::default() }).unwrap()
}

pub fn zero_gravity_world() -> World {
    World::new(WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap()
}

pub fn cuboid(half_extents: DVec3) -> Option<Shape> {
    Some(Shape::Cuboid(Cuboid::new(half_extents).unwrap()))
}

pub fn sphere(radius: f64) -> Option<Shape> {
    Some(Shape::Sphere(Sphere::new(radius).unwrap()))
}

pub fn material(friction: f64, restitution: f64) -> Material {
    Material { friction, restitution, ..Default::default() }
}

/// The ground: a static 40 × 40 × 1 m box whose top face is the plane z = 0.
pub fn ground(world: &mut World, material: Material) -> BodyId {
    world
        .add_body(BodyDef {
            name: "ground".into(),
            kind: BodyKind::Static,
            shape: cuboid(DVec3::new(20.0, 20.0, 0.5)),
            position: DVec3::new(0.0, 0.0, -0.5),
            material,
            ..Default::default()
        })
        .unwrap()
}

/// An incline through the origin rising towards −x at `theta`: a static 40 × 4 × 1 m box turned
/// about Y by `theta`, whose top face passes through the origin. Returns the body, its rotation,
/// the surface normal and the downhill direction.
pub struct Incline {
    pub body: BodyId,
    pub rotation: DQuat,
    pub normal: DVec3,
    pub downhill: DVec3,
}

pub fn incline(world: &mut World, theta: f64, material: Material) -> Incline {
    let rotation = DQuat::from_rotation_y(theta);
    let normal = rotation * DVec3::Z;
    let body = world
        .add_body(BodyDef {
            name: "incline".into(),
            kind: BodyKind::Static,
            shape: cuboid(DVec3::new(20.0, 2.0, 0.5)),
            position: -0.5 * normal,
            orientation: rotation,
            material,
            ..Default::default()
        })
        .unwrap();
    Incline { body, rotation, normal, downhill: rotation * DVec3::X }
}

/// A vertical stack of `n` unit boxes (1000 kg each at the default density) on the ground, touching.
pub fn box_stack(world: &mut World, n: usize) -> Vec<BodyId> {
    (0..n)
        .map(|i| {
            world
                .add_body(BodyDef {
                    name: format!("box {i}"),
                    shape: cuboid(DVec3::splat(0.5)),
                    position: DVec3::new(0.0, 0.0, 0.5 + i as f64),
                    ..Default::default()
                })
                .unwrap()
        })
        .collect()
}

/// A pyramid of unit boxes with `base` boxes in its bottom row, in the x–z plane, touching.
pub fn box_pyramid(world: &mut World, base: usize) -> Vec<BodyId> {
    let mut ids = Vec::new();
    for row in 0..base {
        let count = base - row;
        for i in 0..count {
            let x = i as f64 - 0.5 * (count as f64 - 1.0);
            ids.push(
                world
                    .add_body(BodyDef {
                        name: format!("box {row}.{i}"),
                        shape: cuboid(DVec3::splat(0.5)),
                        position: DVec3::new(x, 0.0, 0.5 + row as f64),
                        ..Default::default()
                    })
                    .unwrap(),
            );
        }
    }
    ids
}

/// Steps `world` `steps` times at `DT` and returns the wall-clock rate, steps/s.
pub fn timed_steps(world: &mut World, steps: usize) -> f64 {
    let start = Instant::now();
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    steps as f64 / start.elapsed().as_secs_f64()
}

/// Largest distance of the bodies from the given start positions.
pub fn largest_drift(world: &World, ids: &[BodyId], starts: &[DVec3]) -> (f64, usize) {
    ids.iter()
        .zip(starts)
        .enumerate()
        .map(|(i, (&id, &start))| (world.body(id).unwrap().position().distance(start), i))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}
