//! The shared benchmark scenes (BENCHMARKS.md): one builder per scene, used alike by the CLI's
//! `tumble bench`, the criterion benches and the tests, and rebuilt with the same numbers by the
//! peer scripts under `bench/`.
//!
//! A [`Scene`] is a world plus its time step, its step count and a probe that watches the run
//! and reports the scene's quality result ([`Quality`]). Call [`Scene::observe`] after each step
//! for the metrics taken over the run (joint separation); it is kept out of `World::step` so the
//! time spent watching is not counted as stepping.
//!
//! Every scene uses Z up, g = 9.81 m/s² (zero in `tumbling`) and dt = 1/60 s. Sleep is off except
//! in `ragdolls` (whose quality result asks whether they all fell asleep), so the steps measured
//! are the steps of a moving world, not of one that has gone to sleep.

mod chain;
mod convex_pile;
mod pyramid;
mod quality;
mod ragdolls;
mod rain;
pub(crate) mod rng;
mod tumbling;

pub use chain::chain;
pub use convex_pile::convex_pile;
#[cfg(test)]
pub(crate) use pyramid::box_centers;
pub use pyramid::{large_pyramid, pyramid};
pub use quality::{Metric, Quality};
pub use ragdolls::{ragdoll_parts, ragdolls, RagdollPart};
pub use rain::rain;
pub use tumbling::tumbling;

use crate::body::{BodyDef, BodyKind};
use crate::shape::{Plane, Shape};
use crate::world::{World, WorldDef};

/// The time step of every scene, s.
pub const DT: f64 = 1.0 / 60.0;

/// Every scene's name, in the order the tables list them.
pub const NAMES: [&str; 7] =
    ["pyramid", "large_pyramid", "rain", "chain", "ragdolls", "convex_pile", "tumbling"];

/// Watches a scene's run and reports its quality result.
pub trait Probe: Send {
    /// Called after each step (for the metrics taken over the run).
    fn observe(&mut self, world: &World);
    /// The quality result for the world as it is now and the run observed so far.
    fn quality(&self, world: &World) -> Quality;
}

/// A benchmark scene ready to run.
pub struct Scene {
    /// The scene's name (one of [`NAMES`]).
    pub name: &'static str,
    /// The scene's size: base row of a pyramid, number of bodies, links or ragdolls.
    pub size: usize,
    pub world: World,
    /// Time step, s.
    pub dt: f64,
    /// The number of steps the benchmark runs.
    pub steps: u32,
    probe: Box<dyn Probe>,
}

impl Scene {
    pub(crate) fn new(
        name: &'static str,
        size: usize,
        world: World,
        steps: u32,
        probe: impl Probe + 'static,
    ) -> Scene {
        Scene { name, size, world, dt: DT, steps, probe: Box::new(probe) }
    }

    /// One step of the world followed by [`Scene::observe`].
    pub fn step(&mut self) {
        self.world.step(self.dt).expect("the scene's time step is valid");
        self.observe();
    }

    /// Lets the probe look at the world after a step.
    pub fn observe(&mut self) {
        self.probe.observe(&self.world);
    }

    /// The quality result so far.
    pub fn quality(&self) -> Quality {
        self.probe.quality(&self.world)
    }
}

/// Builds a scene by name with its default size, or with `size` (base row, or body, link or
/// ragdoll count) when given. `None` for an unknown name.
pub fn by_name(name: &str, size: Option<usize>) -> Option<Scene> {
    Some(match name {
        "pyramid" => pyramid(size.unwrap_or(20)),
        "large_pyramid" => large_pyramid(size.unwrap_or(100)),
        "rain" => rain(size.unwrap_or(2_000)),
        "chain" => chain(size.unwrap_or(100)),
        "ragdolls" => ragdolls(size.unwrap_or(100)),
        "convex_pile" => convex_pile(size.unwrap_or(1_000)),
        "tumbling" => tumbling(size.unwrap_or(10_000)),
        _ => return None,
    })
}

/// A world with the default solver, gravity `g` along −Z and sleep on or off.
fn world(gravity: f64, sleep: bool) -> World {
    let mut def = WorldDef { gravity: crate::math::DVec3::new(0.0, 0.0, -gravity), ..WorldDef::default() };
    def.sleep.enabled = sleep;
    World::new(def).expect("default settings are valid")
}

/// Adds the static ground plane z = 0.
fn add_ground(world: &mut World) {
    world
        .add_body(BodyDef {
            name: "ground".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::Plane(Plane::new(crate::math::DVec3::Z, 0.0).expect("unit normal"))),
            ..Default::default()
        })
        .expect("a static plane is a valid body");
}

/// Standard gravity, m/s².
const G: f64 = 9.81;
