//! `pyramid` and `large_pyramid`: a 2D pyramid of unit boxes (half extent 0.5) on the ground
//! plane, `base` boxes in the bottom row and one fewer in each row above, touching side by side
//! (Box2D v3's large_pyramid, in 3D). Quality: the largest displacement of any box from its start.

use super::quality::{Metric, Quality};
use super::{add_ground, world, Probe, Scene, G};
use crate::body::BodyDef;
use crate::id::BodyId;
use crate::math::DVec3;
use crate::shape::{Cuboid, Shape};
use crate::world::World;

/// Half extent of every box, m.
pub const HALF_EXTENT: f64 = 0.5;

/// The centres of the boxes, bottom row first, left to right.
pub fn box_centers(base: usize) -> Vec<DVec3> {
    let mut centers = Vec::with_capacity(base * (base + 1) / 2);
    for row in 0..base {
        let count = base - row;
        for i in 0..count {
            let x = (i as f64 - 0.5 * (count as f64 - 1.0)) * 2.0 * HALF_EXTENT;
            centers.push(DVec3::new(x, 0.0, HALF_EXTENT + row as f64 * 2.0 * HALF_EXTENT));
        }
    }
    centers
}

/// A pyramid with `base` boxes in its bottom row (`base (base + 1) / 2` boxes), 1,000 steps.
pub fn pyramid(base: usize) -> Scene {
    build("pyramid", base, 1_000)
}

/// The large pyramid: base 100 (5,050 boxes) by default, 500 steps.
pub fn large_pyramid(base: usize) -> Scene {
    build("large_pyramid", base, 500)
}

fn build(name: &'static str, base: usize, steps: u32) -> Scene {
    let mut w = world(G, false);
    add_ground(&mut w);
    let shape = Shape::Cuboid(Cuboid::new(DVec3::splat(HALF_EXTENT)).expect("positive half extents"));
    let start = box_centers(base)
        .into_iter()
        .map(|position| {
            let def = BodyDef { shape: Some(shape.clone()), position, ..Default::default() };
            (w.add_body(def).expect("a unit box is a valid body"), position)
        })
        .collect();
    Scene::new(name, base, w, steps, Displacement { start })
}

/// The largest distance of a body from where it started.
struct Displacement {
    start: Vec<(BodyId, DVec3)>,
}

impl Probe for Displacement {
    fn observe(&mut self, _world: &World) {}

    fn quality(&self, world: &World) -> Quality {
        let max = self
            .start
            .iter()
            .filter_map(|&(id, p0)| Some((world.body(id).ok()?.position() - p0).length()))
            .fold(0.0, f64::max);
        Quality { metrics: vec![Metric::Length("max displacement", max)] }
    }
}
