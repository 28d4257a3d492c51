//! `World::step`: the phases of one time step, in order. This file reads as the table of contents
//! of the pipeline in DESIGN.md; each phase lives in its own module.
//!
//! Today the pipeline is free motion only: forces, gravity and the exact rotation update for every
//! body, then accumulators are cleared. Collision and the constraint solver join as their modules
//! land.

use crate::integrate::integrate_body;
use crate::math::DVec3;
use crate::world::{World, WorldError};

impl World {
    /// Advances the world by `dt` seconds.
    pub fn step(&mut self, dt: f64) -> Result<(), WorldError> {
        if !dt.is_finite() || dt <= 0.0 {
            return Err(WorldError::InvalidTimeStep(dt));
        }
        let gravity = self.gravity;

        // Free motion: velocities from forces and gravity, then positions and rotations.
        for (_, body) in self.bodies.iter_mut() {
            integrate_body(body, gravity, dt);
        }

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
