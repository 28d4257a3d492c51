//! `tumbling`: free boxes of three different half extents spinning in zero gravity, torque-free,
//! 3 m apart on a cubic grid (they never touch); 1,000 steps. Quality: the relative error of the
//! total kinetic energy, and the largest relative error of any body's angular momentum.

use super::quality::{Metric, Quality};
use super::rng::SplitMix64;
use super::{world, Probe, Scene};
use crate::body::BodyDef;
use crate::id::BodyId;
use crate::math::DVec3;
use crate::shape::{Cuboid, Shape};
use crate::world::World;

/// Grid spacing, m.
pub const SPACING: f64 = 3.0;
/// Seed of the sizes and spins.
pub const SEED: u64 = 11;

/// Body `k`'s half extents, position and angular velocity.
pub fn bodies(count: usize) -> Vec<(DVec3, DVec3, DVec3)> {
    let mut rng = SplitMix64::new(SEED);
    let side = (count as f64).cbrt().ceil() as usize;
    (0..count)
        .map(|k| {
            let half_extents = DVec3::new(rng.range(0.3, 0.5), rng.range(0.15, 0.25), rng.range(0.05, 0.1));
            let (i, j, l) = (k % side, (k / side) % side, k / (side * side));
            let position = DVec3::new(i as f64, j as f64, l as f64) * SPACING;
            let spin = DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
            (half_extents, position, spin)
        })
        .collect()
}

/// `count` tumbling bodies (10,000 by default).
pub fn tumbling(count: usize) -> Scene {
    let mut w = world(0.0, false);
    let ids = bodies(count)
        .into_iter()
        .map(|(half_extents, position, angular_velocity)| {
            let shape = Shape::Cuboid(Cuboid::new(half_extents).expect("positive half extents"));
            w.add_body(BodyDef { shape: Some(shape), position, angular_velocity, ..Default::default() })
                .expect("a box is a valid body")
        })
        .collect::<Vec<_>>();
    let start =
        ids.iter().map(|&id| (id, w.body(id).expect("just added").angular_momentum_about_com())).collect();
    let energy = w.kinetic_energy();
    Scene::new("tumbling", count, w, 1_000, Conservation { start, energy })
}

/// Energy and angular momentum at the start.
struct Conservation {
    start: Vec<(BodyId, DVec3)>,
    energy: f64,
}

impl Probe for Conservation {
    fn observe(&mut self, _world: &World) {}

    fn quality(&self, world: &World) -> Quality {
        let energy_error = (world.kinetic_energy() - self.energy).abs() / self.energy.max(f64::MIN_POSITIVE);
        let momentum_error = self
            .start
            .iter()
            .filter_map(|&(id, l0)| {
                let l = world.body(id).ok()?.angular_momentum_about_com();
                Some((l - l0).length() / l0.length().max(f64::MIN_POSITIVE))
            })
            .fold(0.0, f64::max);
        Quality {
            metrics: vec![
                Metric::Relative("energy error", energy_error),
                Metric::Relative("angular momentum error", momentum_error),
            ],
        }
    }
}
