//! `World::step`: the phases of one time step, in order. This file reads as the table of contents
//! of the pipeline in DESIGN.md; each phase lives in its own module.
//!
//! Today the pipeline is: the soft-step solve (forces, gravity, joints, exact rotation update, in
//! substeps), then accumulators are cleared. Collision joins as its modules land.

use crate::math::DVec3;
use crate::world::{World, WorldError};

impl World {
    /// Advances the world by `dt` seconds.
    pub fn step(&mut self, dt: f64) -> Result<(), WorldError> {
        if !dt.is_finite() || dt <= 0.0 {
            return Err(WorldError::InvalidTimeStep(dt));
        }

        // Wake sleeping islands that awake bodies are linked to.
        self.wake_islands_touched_by_awake_bodies(&[]);

        // Constraint solve with substeps: velocities, joints, positions (dynamics/solver.rs).
        self.solve(dt);

        // Islands and sleep (dynamics/island.rs).
        self.update_sleep(dt, &[]);

        // Forces and torques act for one step only.
        for (_, body) in self.bodies.iter_mut() {
            body.force_world = DVec3::ZERO;
            body.torque_world = DVec3::ZERO;
        }

        self.time += dt;
        self.step_count += 1;
        Ok(())
    }
}
