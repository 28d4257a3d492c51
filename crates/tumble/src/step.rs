//! `World::step`: the phases of one time step, in order. This file reads as the table of contents
//! of the pipeline in DESIGN.md; each phase lives in its own module. Each phase's wall time is
//! added to the world's profile (`profile.rs`).
//!
//! The pipeline: broad and narrow phase, waking, the non-finite check, the soft-step solve
//! (forces, gravity, contacts, joints, exact rotation update, in substeps), the check again, the
//! continuous sweep of bullets against static geometry, sleep, then accumulators are cleared.

use std::time::Instant;

use crate::dynamics::solver::{PARALLEL_MIN_BODIES, PARALLEL_MIN_CONTACTS};
use crate::id::BodyId;
use crate::math::DVec3;
use crate::profile::Phase;
use crate::step_threads::StepThreads;
use crate::world::{World, WorldError};

impl World {
    /// Advances the world by `dt` seconds.
    pub fn step(&mut self, dt: f64) -> Result<(), WorldError> {
        if !dt.is_finite() || dt <= 0.0 {
            return Err(WorldError::InvalidTimeStep(dt));
        }
        let start = Instant::now();
        let mut clock = start;
        // The pool's threads, for the stages up to the solve (step_threads.rs): they wake while
        // the serial stages below run. Not for a step none of whose stages would be shared (too
        // few contacts and bodies, as in a lone chain): taking them only cost (a 100-link chain
        // ran 5–9% slower on two threads than on one).
        let pool = self.pool.clone();
        let step_threads = pool.as_deref().filter(|_| self.worth_step_threads()).map(StepThreads::begin);
        let threads = step_threads.as_ref();

        // Broad phase: move proxies (unless the last step's finalize left them in place for this
        // step length and no body has changed since), find new pairs; narrow phase: update
        // manifolds (collision/contact_manager.rs).
        if self.proxies_in_place_for != Some(dt) {
            self.contact_manager.update_proxies(&self.bodies, dt);
        }
        self.profile.lap(Phase::Proxies, &mut clock);
        // Jointed pairs that may not collide, sorted once: each new pair is looked up in them
        // (walking every joint for every new pair was a twentieth of a pile of ragdolls' step).
        let mut jointed = std::mem::take(&mut self.scratch.jointed_pairs);
        jointed.clear();
        jointed.extend(
            self.joints
                .iter()
                .filter(|(_, j)| !j.collide_connected)
                .map(|(_, j)| (j.body_a.min(j.body_b), j.body_a.max(j.body_b))),
        );
        jointed.sort_unstable();
        let joined = |a: BodyId, b: BodyId| jointed.binary_search(&(a.min(b), a.max(b))).is_ok();
        self.contact_manager.find_new_contacts(&self.bodies, joined, threads);
        self.scratch.jointed_pairs = jointed;
        self.profile.lap(Phase::BroadPhase, &mut clock);
        self.contact_manager.update_contacts(&self.bodies, dt, threads);
        self.profile.lap(Phase::NarrowPhase, &mut clock);

        // Wake sleeping islands that awake bodies touch or are jointed to.
        self.wake_islands_touched_by_awake_bodies();
        self.profile.lap(Phase::Wake, &mut clock);

        // Bodies whose numbers would overflow leave the simulation before they can spread NaN
        // through contacts and joints; after the solve, anything non-finite that got through
        // goes back to its last finite state and leaves too (non_finite.rs).
        self.isolate_bodies_about_to_overflow(dt);

        // Constraint solve with substeps: velocities, joints, positions (dynamics/solver.rs).
        self.solve(dt, threads, &mut clock);
        drop(step_threads);
        self.isolate_non_finite_bodies();
        self.profile.lap(Phase::SolveStore, &mut clock);

        // Bullets that went through static geometry despite their contacts go back to the time
        // of impact (continuous.rs).
        self.solve_continuous();
        self.profile.lap(Phase::Continuous, &mut clock);

        // Move the proxies of the bodies that moved, so queries between steps see the current
        // poses (query.rs); the next step's broad phase then finds them already in place. The
        // solver's write-back planned the moves (collision/contact_manager.rs).
        let plans = self.written_back.iter().map(|written| written.proxies);
        #[cfg(test)]
        let plans = plans.take(if self.plain_proxy_update { 0 } else { usize::MAX });
        self.contact_manager.move_proxies_as_planned(&self.bodies, plans, dt);
        self.proxies_in_place_for = Some(dt);
        self.profile.lap(Phase::Finalize, &mut clock);

        // Islands and sleep (dynamics/island.rs), over the links found before the solve.
        self.update_sleep(dt);
        self.profile.lap(Phase::Sleep, &mut clock);

        // Forces and torques act for one step only.
        if std::mem::take(&mut self.forces_pending) {
            for (_, body) in self.bodies.iter_mut() {
                body.force_world = DVec3::ZERO;
                body.torque_world = DVec3::ZERO;
            }
        }

        // Compensated (Kahan) summation: 720,000 steps of 1/240 s still add up to 3000 s exactly,
        // instead of drifting by the round-off of each addition.
        let y = dt - self.time_compensation;
        let t = self.time + y;
        self.time_compensation = (t - self.time) - y;
        self.time = t;
        self.step_count += 1;
        self.profile.steps += 1;
        self.profile.total += start.elapsed();
        Ok(())
    }

    /// Whether some stage of this step is likely to be shared between threads: enough contacts
    /// for the solver to prepare them on threads (the narrow phase shares from as many), or
    /// enough bodies for its body stages. (Counted before the step's new contacts are made: only
    /// a guess, which changes the speed alone.)
    fn worth_step_threads(&self) -> bool {
        self.contact_manager.contacts.len() >= PARALLEL_MIN_CONTACTS
            || self.bodies.capacity_index() >= PARALLEL_MIN_BODIES
    }
}
