//! `rain`: spheres (r = 0.5) dropped into a 20 × 20 m walled bin, 600 steps. They start on a
//! jittered grid of layers above the bin (17 × 17 per layer, 1.5 m apart in height), all at once.
//! Quality: how many escaped the bin, and the largest overlap among the touching contacts.

use super::quality::{max_penetration, Metric, Quality};
use super::rng::SplitMix64;
use super::{add_ground, world, Probe, Scene, G};
use crate::body::{BodyDef, BodyKind};
use crate::id::BodyId;
use crate::math::DVec3;
use crate::shape::{Cuboid, Shape, Sphere};
use crate::world::World;

/// Sphere radius, m.
pub const RADIUS: f64 = 0.5;
/// Half the inside width of the bin, m.
pub const BIN_HALF_WIDTH: f64 = 10.0;
/// Half thickness of the bin's walls, m.
pub const WALL_HALF_THICKNESS: f64 = 0.5;
/// Spheres per row of a layer (so per layer, this squared), 1.1 m apart.
pub const PER_ROW: usize = 17;
/// Horizontal spacing of the grid, m.
pub const SPACING: f64 = 1.1;
/// Height between layers, m.
pub const LAYER_HEIGHT: f64 = 1.5;
/// Height of the lowest layer, m.
pub const FIRST_LAYER: f64 = 1.0;
/// Seed of the jitter.
pub const SEED: u64 = 2;

/// The walls' height: twice the depth the spheres would fill at a loose packing of 0.5, and at
/// least 10 m.
pub fn wall_height(count: usize) -> f64 {
    let volume = count as f64 * 4.0 / 3.0 * std::f64::consts::PI * RADIUS.powi(3);
    let depth = volume / 0.5 / (2.0 * BIN_HALF_WIDTH).powi(2);
    (2.0 * depth).max(10.0)
}

/// The sphere centres: layer by layer, row by row, each jittered by up to ±0.05 m in x and y.
pub fn sphere_centers(count: usize) -> Vec<DVec3> {
    let mut rng = SplitMix64::new(SEED);
    let per_layer = PER_ROW * PER_ROW;
    let offset = 0.5 * (PER_ROW as f64 - 1.0) * SPACING;
    (0..count)
        .map(|k| {
            let (layer, rest) = (k / per_layer, k % per_layer);
            let (j, i) = (rest / PER_ROW, rest % PER_ROW);
            let jx = rng.range(-0.05, 0.05);
            let jy = rng.range(-0.05, 0.05);
            DVec3::new(
                i as f64 * SPACING - offset + jx,
                j as f64 * SPACING - offset + jy,
                FIRST_LAYER + layer as f64 * LAYER_HEIGHT,
            )
        })
        .collect()
}

/// `count` spheres (2,000 by default) into the bin.
pub fn rain(count: usize) -> Scene {
    let mut w = world(G, false);
    add_ground(&mut w);
    let height = wall_height(count);
    let (half, t) = (BIN_HALF_WIDTH, WALL_HALF_THICKNESS);
    for (center, half_extents) in [
        (DVec3::new(-half - t, 0.0, 0.5 * height), DVec3::new(t, half + 2.0 * t, 0.5 * height)),
        (DVec3::new(half + t, 0.0, 0.5 * height), DVec3::new(t, half + 2.0 * t, 0.5 * height)),
        (DVec3::new(0.0, -half - t, 0.5 * height), DVec3::new(half, t, 0.5 * height)),
        (DVec3::new(0.0, half + t, 0.5 * height), DVec3::new(half, t, 0.5 * height)),
    ] {
        w.add_body(BodyDef {
            name: "wall".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(half_extents).expect("positive half extents"))),
            position: center,
            ..Default::default()
        })
        .expect("a wall is a valid body");
    }
    let shape = Shape::Sphere(Sphere::new(RADIUS).expect("positive radius"));
    let spheres = sphere_centers(count)
        .into_iter()
        .map(|position| {
            let def = BodyDef { shape: Some(shape.clone()), position, ..Default::default() };
            w.add_body(def).expect("a sphere is a valid body")
        })
        .collect();
    Scene::new("rain", count, w, 600, Bin { spheres })
}

/// Counts the spheres outside the bin and reads the deepest contact.
struct Bin {
    spheres: Vec<BodyId>,
}

impl Probe for Bin {
    fn observe(&mut self, _world: &World) {}

    fn quality(&self, world: &World) -> Quality {
        let escaped = self
            .spheres
            .iter()
            .filter(|&&id| {
                world.body(id).map_or(true, |b| {
                    let p = b.position();
                    p.x.abs() > BIN_HALF_WIDTH || p.y.abs() > BIN_HALF_WIDTH || p.z < 0.0
                })
            })
            .count();
        Quality {
            metrics: vec![
                Metric::Count("escaped", escaped),
                Metric::Length("max penetration", max_penetration(world)),
            ],
        }
    }
}
