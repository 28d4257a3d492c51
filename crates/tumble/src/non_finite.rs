//! Non-finite state: finding bodies whose state would become (or became) NaN or infinite, and
//! taking them out of the simulation so the rest of the world keeps stepping with finite numbers.
//!
//! The API rejects non-finite input (forces, velocities, poses), but finite input can still
//! overflow: two forces of 1e308 add up to infinity, a huge torque on a light body gives an
//! infinite angular velocity, a speed of 1e300 m/s overflows a contact's effective mass. Once one
//! number is NaN it spreads through every contact and joint the body takes part in, within a
//! single substep, and from there to the whole pile.
//!
//! So the step checks twice:
//! 1. **before the solve**, every simulated body's state, pending force and torque, and the
//!    velocity that one step of them would give, with its kinetic energy. A body that fails is
//!    isolated before it can touch any constraint: this catches the culprit itself, and nothing
//!    else is affected. The energy is in the test because a finite speed whose square overflows
//!    (above ~1e154 m/s) turns every contact it meets into NaN, and because an infinite energy is
//!    what a run calls a blow-up;
//! 2. **after the solve**, every simulated body's state. This is the safety net for what the first
//!    check cannot foresee; a body that fails here is put back where it was at the start of the
//!    step (its last finite state) and isolated. NaN that already spread to a neighbour within
//!    the step isolates the neighbour too.
//!
//! An isolated body keeps its last finite pose with zero velocity, leaves the broad phase (so it
//! has no contacts and nothing collides with it), its joints are broken (so they pass nothing on),
//! and the solver and the sleep pass skip it from then on. Each isolation is reported once, as a
//! [`NonFiniteBody`] event of the step that found it (`World::non_finite_events`), and the body
//! stays listed by `World::isolated_bodies` until it is removed.

use crate::body::{BodyKind, BodyState};
use crate::dynamics::solver_body::SolverBody;
use crate::id::BodyId;
use crate::math::{is_finite_vec, DQuat, DVec3};
use crate::world::World;

/// A body the last step took out of the simulation because its state became non-finite.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct NonFiniteBody {
    pub body: BodyId,
}

fn is_finite_state(s: &BodyState) -> bool {
    is_finite_vec(s.com_world)
        && is_finite_vec(s.linear_velocity)
        && is_finite_vec(s.angular_velocity)
        && s.rotation.is_finite()
}

/// Whether the body takes part in the solve (static bodies never move; sleeping ones stand still).
fn is_simulated(kind: BodyKind, awake: bool, isolated: bool) -> bool {
    kind != BodyKind::Static && awake && !isolated
}

/// Whether a moving body's state after the solve is non-finite; the solve's write-back asks,
/// with the body at hand, and lists the slots for check 2.
pub(crate) fn left_non_finite(body: &crate::body::Body) -> bool {
    body.kind != BodyKind::Static && !is_finite_state(&body.state)
}

/// The velocities one step of `dt` under gravity and the pending force and torque would give
/// (the solver's first kick, `SolverBody::integrate_velocity`, over the whole step). Without a
/// torque the angular velocity only shrinks by damping, so it is taken as it is.
fn velocities_after(body: &crate::body::Body, gravity: DVec3, dt: f64) -> (DVec3, DVec3) {
    if body.kind != BodyKind::Dynamic {
        return (body.state.linear_velocity, body.state.angular_velocity);
    }
    if body.torque_world == DVec3::ZERO {
        let v = (body.state.linear_velocity + dt * body.linear_acceleration(gravity))
            / (1.0 + dt * body.linear_damping);
        return (v, body.state.angular_velocity);
    }
    let mut trial = SolverBody::from_body(body);
    trial.integrate_velocity(gravity, dt);
    (trial.v, trial.w)
}

impl World {
    /// Bodies isolated in the last step because their state became non-finite.
    pub fn non_finite_events(&self) -> &[NonFiniteBody] {
        &self.non_finite_events
    }

    /// Every body isolated so far (see the module docs), in slot order.
    pub fn isolated_bodies(&self) -> impl Iterator<Item = BodyId> + '_ {
        self.bodies().filter(|(_, b)| b.isolated).map(|(id, _)| id)
    }

    /// Check 1 (module docs): isolates every simulated body whose state, pending force or torque,
    /// or velocity after one step of `dt` under them is non-finite. Also keeps each simulated
    /// bullet's state at the start of the step, for the continuous stage. (Check 2 needs no copy
    /// of every body's start state, a megabyte a step for 10,000 bodies: the solve's write-back
    /// puts a body it left non-finite back itself.)
    pub(crate) fn isolate_bodies_about_to_overflow(&mut self, dt: f64) {
        self.non_finite_events.clear();
        self.bullet_starts.clear();
        let mut failing = Vec::new();
        for (id, body) in self.bodies.iter() {
            if !is_simulated(body.kind, body.is_awake(), body.isolated) {
                continue;
            }
            if body.bullet {
                self.bullet_starts.push((id.index(), body.state));
            }
            let (v, w) = velocities_after(body, self.gravity, dt);
            // The rotational energy in the principal frame, `½ Σ Iᵢ ωᵢ²`: the same number as
            // `½ ω·I_world ω` without building the world inertia of every body every step.
            let w_principal = body.principal_rotation_world().inverse() * w;
            let energy = 0.5 * body.mass() * v.length_squared()
                + 0.5 * (body.inertia_principal() * w_principal * w_principal).element_sum();
            let ok = is_finite_state(&body.state)
                && is_finite_vec(body.force_world)
                && is_finite_vec(body.torque_world)
                && energy.is_finite()
                && is_finite_vec(body.state.com_world + dt * v);
            if !ok {
                failing.push((id, body.state));
            }
        }
        for (id, state) in failing {
            self.isolate_body(id.into(), state);
        }
    }

    /// Check 2 (module docs): isolates every simulated body the solve left non-finite, back at
    /// its state from the start of the step. The solve's write-back found them
    /// (`left_non_finite`), while each body's state was at hand, and put that state back.
    pub(crate) fn isolate_non_finite_bodies(&mut self) {
        let failing = std::mem::take(&mut self.non_finite_after_solve);
        for &slot in &failing {
            let Some(id) = self.bodies.id_of_slot(slot) else { continue };
            if let Some(start) = self.bodies.get(id).map(|body| body.state) {
                self.isolate_body(id.into(), start);
            }
        }
        self.non_finite_after_solve = failing;
        self.non_finite_after_solve.clear();
    }

    /// Takes the body out of the simulation at `last_state` (its last finite one), at rest.
    fn isolate_body(&mut self, id: BodyId, last_state: BodyState) {
        let Some(body) = self.bodies.get_mut(id.into()) else { return };
        let finite_or = |v: DVec3, fallback: DVec3| if is_finite_vec(v) { v } else { fallback };
        body.state = BodyState {
            // A state that was never finite (only a damaged snapshot can hold one) has no last
            // finite pose to go back to: fall back to the origin and identity.
            com_world: finite_or(last_state.com_world, DVec3::ZERO),
            rotation: if last_state.rotation.is_finite() { last_state.rotation } else { DQuat::IDENTITY },
            linear_velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
        };
        body.force_world = DVec3::ZERO;
        body.torque_world = DVec3::ZERO;
        body.isolated = true;
        body.sleep_time = 0.0;
        body.sleeping_island = None;
        let body = self.bodies.get(id.into()).expect("looked up above");
        self.contact_manager.remove_body(body);
        self.bodies.get_mut(id.into()).expect("looked up above").proxies.clear();
        for (_, joint) in self.joints.iter_mut() {
            if joint.body_a == id || joint.body_b == id {
                joint.broken = true;
                joint.reset_impulses();
            }
        }
        self.non_finite_events.push(NonFiniteBody { body: id });
    }
}
