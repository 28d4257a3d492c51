//! The world: owns every body and the settings, and is the public API for changing them.
//! `step.rs` holds `World::step`.

use crate::body::{Body, BodyDef, BodyKind};
use crate::collision::contact_manager::ContactManager;
use crate::dynamics::contact::{ContactPointView, ContactView};
use crate::dynamics::contact_solver::ContactConstraint;
use crate::dynamics::island::SleepSettings;
use crate::dynamics::joint::{Joint, JointDef};
use crate::dynamics::solver::SolverSettings;
use crate::dynamics::solver_body::SolverBody;
use crate::id::{BodyId, JointId, SlotPool};
use crate::mass::{MassError, MassProperties};
use crate::math::{is_finite_vec, mat3_max_abs, DMat3, DVec3};

/// Settings a world starts with.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WorldDef {
    /// Gravity, m/s². Default (0, 0, −9.81): Z is up.
    pub gravity: DVec3,
    /// Substeps, constraint stiffness and the other solver settings.
    pub solver: SolverSettings,
    /// When resting bodies fall asleep.
    pub sleep: SleepSettings,
}

impl Default for WorldDef {
    fn default() -> Self {
        Self {
            gravity: DVec3::new(0.0, 0.0, -9.81),
            solver: SolverSettings::default(),
            sleep: SleepSettings::default(),
        }
    }
}

/// Errors from the world's API. Each says what was wrong and with which body.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum WorldError {
    #[error("{0} does not name a body in this world (removed, or from another world)")]
    StaleBody(BodyId),
    #[error("body \"{body}\": {source}")]
    Mass {
        body: String,
        #[source]
        source: MassError,
    },
    #[error("body \"{body}\": {message}")]
    InvalidBody { body: String, message: String },
    #[error("{what} must be finite, got {value}")]
    NotFinite { what: &'static str, value: String },
    #[error("time step must be finite and > 0, got {0}")]
    InvalidTimeStep(f64),
    #[error("{0} does not name a joint in this world (removed, or from another world)")]
    StaleJoint(JointId),
    #[error("joint \"{joint}\": {message}")]
    InvalidJoint { joint: String, message: String },
    #[error("solver settings: {0}")]
    InvalidSolverSettings(String),
    #[error("{0}")]
    InvalidSettings(String),
}

/// A rigid-body world.
#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub struct World {
    pub(crate) bodies: SlotPool<Body>,
    pub(crate) joints: SlotPool<Joint>,
    pub(crate) solver_settings: SolverSettings,
    pub(crate) sleep_settings: SleepSettings,
    /// The solver's per-body working copies, kept between steps to reuse the allocation.
    #[serde(skip)]
    pub(crate) solver_bodies: Vec<SolverBody>,
    /// Per body slot, what the solver's serial stages ask of the body (kept with `solver_bodies`).
    #[serde(skip)]
    pub(crate) solver_slot_summaries: Vec<crate::dynamics::solver::SlotSummary>,
    /// Per body slot, what the solver's write-back found (non-finite state, the plan for the
    /// body's proxies), read by the step's finalize stage.
    #[serde(skip)]
    pub(crate) written_back: Vec<crate::dynamics::solver::WrittenBack>,
    /// Tests only: the finalize stage moves the proxies by its own walk over the bodies, not
    /// by the write-back's plans (what the plans are checked against).
    #[cfg(test)]
    #[serde(skip)]
    pub(crate) plain_proxy_update: bool,
    /// Broad phase, contacts and their manifolds.
    pub(crate) contact_manager: ContactManager,
    /// The solver's contact rows, kept between steps to reuse the allocation.
    #[serde(skip)]
    pub(crate) contact_constraints: Vec<ContactConstraint>,
    /// Whether still contact manifolds are solved four side by side in SIMD lanes or one at a
    /// time (contact_lanes.rs); `None` takes lanes where they pay (`GROUPS_PAY`). The same
    /// numbers either way, which the tests check with it.
    #[serde(skip)]
    pub(crate) contacts_in_groups: Option<bool>,
    /// The rows of the contacts four at a time for the still manifolds' groups, written each
    /// step (kept to reuse the allocation).
    #[serde(skip)]
    pub(crate) still_blocks: Vec<crate::dynamics::contact_solver::StillBlock>,
    /// The contacts the solver takes this step (their places in the contact store, and bodies), in
    /// store order (kept to reuse the allocation).
    #[serde(skip)]
    pub(crate) solved_contacts: Vec<crate::dynamics::solver::SolvedContact>,
    /// The step length for which the last step's finalize stage moved every moving body's
    /// proxies to its pose and velocity, if no body has changed since: a next step of the same
    /// length need not move them again. Any change through `body_mut` clears it; a loaded world
    /// starts without.
    #[serde(skip)]
    pub(crate) proxies_in_place_for: Option<f64>,
    /// The solver's constrained and unconstrained bodies, kept to reuse the allocation.
    #[serde(skip)]
    pub(crate) body_partition: crate::dynamics::solver::BodyPartition,
    /// The step's joint trees (`dynamics/joint_tree/`), kept to reuse their allocations.
    #[serde(skip)]
    pub(crate) joint_trees: crate::dynamics::joint_tree::JointTrees,
    /// The solved joints by component, for the joint stages on the threads (kept to reuse its
    /// allocations).
    #[serde(skip)]
    pub(crate) joint_components: crate::dynamics::joint_components::JointComponents,
    /// The colouring of the contact rows (`dynamics/colouring.rs`), kept to reuse its allocations.
    #[serde(skip)]
    pub(crate) contact_colouring: crate::dynamics::colouring::ContactColouring,
    pub(crate) gravity: DVec3,
    pub(crate) time: f64,
    /// The low-order bits lost from `time` by the last addition (Kahan summation).
    pub(crate) time_compensation: f64,
    pub(crate) step_count: u64,
    /// Wall time per phase of `step` (never part of the state: not saved, not hashed).
    #[serde(skip)]
    pub(crate) profile: crate::profile::StepProfile,
    /// The threads the collision pipeline and the solver may use; `None` runs it on the calling thread. Not
    /// saved: a restored world runs on one thread until told otherwise.
    #[serde(skip)]
    pub(crate) pool: Option<std::sync::Arc<rayon::ThreadPool>>,
    /// Buffers the step refills each time, kept to reuse their allocations.
    #[serde(skip)]
    pub(crate) scratch: crate::dynamics::island::IslandScratch,
    /// Bodies the last step isolated for non-finite state (`non_finite.rs`).
    pub(crate) non_finite_events: Vec<crate::non_finite::NonFiniteBody>,
    /// Static proxies under a bullet's sweep, refilled for each bullet (`continuous.rs`).
    #[serde(skip)]
    pub(crate) continuous_candidates: Vec<crate::collision::ProxyId>,
    /// Each simulated bullet's slot and state at the start of the step, for the continuous stage
    /// (`non_finite.rs` keeps them).
    #[serde(skip)]
    pub(crate) bullet_starts: Vec<(usize, crate::body::BodyState)>,
    /// The slots of the bodies whose state the solve left non-finite (`non_finite.rs`).
    #[serde(skip)]
    pub(crate) non_finite_after_solve: Vec<usize>,
    /// Whether a force or torque may have been applied since the last step cleared them (the
    /// step then clears every body's; otherwise there is nothing to clear). A loaded world
    /// starts with it set.
    #[serde(skip, default = "crate::world::yes")]
    pub(crate) forces_pending: bool,
}

pub(crate) fn yes() -> bool {
    true
}

impl Default for World {
    fn default() -> Self {
        Self::new(WorldDef::default()).expect("the default world settings are valid")
    }
}

fn check_vec(what: &'static str, v: DVec3) -> Result<DVec3, WorldError> {
    if is_finite_vec(v) {
        Ok(v)
    } else {
        Err(WorldError::NotFinite { what, value: format!("{v}") })
    }
}

/// True when the shape is, or has a part that is, a static (possibly open) mesh.
fn has_open_mesh(shape: &crate::shape::Shape) -> bool {
    match shape {
        crate::shape::Shape::TriMesh(m) => !m.is_closed(),
        crate::shape::Shape::Compound(c) => c.children().iter().any(|child| has_open_mesh(&child.shape)),
        _ => false,
    }
}

fn check_solver_settings(s: &SolverSettings) -> Result<(), WorldError> {
    let bad = |m: String| Err(WorldError::InvalidSolverSettings(m));
    if s.substeps == 0 || s.substeps > 1000 {
        return bad(format!("substeps must be between 1 and 1000, got {}", s.substeps));
    }
    if s.solve_iterations == 0 || s.solve_iterations > 1000 {
        return bad(format!("solve_iterations must be between 1 and 1000, got {}", s.solve_iterations));
    }
    if s.relax_iterations > 1000 {
        return bad(format!("relax_iterations must be at most 1000, got {}", s.relax_iterations));
    }
    if s.joint_projection_iterations > 1000 {
        return bad(format!(
            "joint_projection_iterations must be at most 1000, got {}",
            s.joint_projection_iterations
        ));
    }
    for (what, v) in [
        ("joint_hertz", s.joint_hertz),
        ("joint_damping_ratio", s.joint_damping_ratio),
        ("contact_hertz", s.contact_hertz),
        ("contact_damping_ratio", s.contact_damping_ratio),
        ("max_contact_push_velocity", s.max_contact_push_velocity),
        ("restitution_threshold", s.restitution_threshold),
        ("steady_load_time", s.steady_load_time),
        ("joint_projection_tolerance", s.joint_projection_tolerance),
    ] {
        if !v.is_finite() || v < 0.0 {
            return bad(format!("{what} must be finite and >= 0, got {v}"));
        }
    }
    Ok(())
}

impl World {
    pub fn new(def: WorldDef) -> Result<Self, WorldError> {
        check_solver_settings(&def.solver)?;
        Ok(Self {
            bodies: SlotPool::new(),
            joints: SlotPool::new(),
            solver_settings: def.solver,
            sleep_settings: def.sleep,
            solver_bodies: Vec::new(),
            solver_slot_summaries: Vec::new(),
            written_back: Vec::new(),
            #[cfg(test)]
            plain_proxy_update: false,
            contact_manager: ContactManager::default(),
            contact_constraints: Vec::new(),
            contacts_in_groups: None,
            still_blocks: Vec::new(),
            solved_contacts: Vec::new(),
            proxies_in_place_for: None,
            body_partition: Default::default(),
            joint_trees: Default::default(),
            joint_components: Default::default(),
            contact_colouring: Default::default(),
            gravity: check_vec("gravity", def.gravity)?,
            time: 0.0,
            time_compensation: 0.0,
            step_count: 0,
            profile: Default::default(),
            pool: None,
            scratch: Default::default(),
            non_finite_events: Vec::new(),
            continuous_candidates: Vec::new(),
            bullet_starts: Vec::new(),
            non_finite_after_solve: Vec::new(),
            forces_pending: false,
        })
    }

    pub fn solver_settings(&self) -> &SolverSettings {
        &self.solver_settings
    }

    pub fn set_solver_settings(&mut self, settings: SolverSettings) -> Result<(), WorldError> {
        check_solver_settings(&settings)?;
        self.solver_settings = settings;
        Ok(())
    }

    pub fn sleep_settings(&self) -> &SleepSettings {
        &self.sleep_settings
    }

    /// Changes when bodies fall asleep (bodies asleep now stay asleep until woken).
    pub fn set_sleep_settings(&mut self, settings: SleepSettings) {
        self.sleep_settings = settings;
    }

    /// The number of threads the collision pipeline and the solver use (1: the calling thread only).
    pub fn threads(&self) -> usize {
        // The calling thread is the step's first (step_threads.rs).
        self.pool.as_ref().map_or(1, |p| p.current_num_threads() + 1)
    }

    /// Runs the collision pipeline and the solver on `threads` threads of a pool owned by the
    /// world (1 or 0: on the calling thread, no pool). The work is split by the scene, never by
    /// the thread count (the solver's by graph colouring, `dynamics/colouring.rs`), and merged in
    /// a fixed order, so every thread count gives bit-identical results. The solver's threads spin
    /// while they wait for each other within a step, and sleep after half a millisecond
    /// (`waiting.rs`): more threads than free cores gains nothing, but costs little.
    pub fn set_threads(&mut self, threads: usize) -> Result<(), WorldError> {
        self.pool = if threads <= 1 {
            None
        } else {
            // The pool holds the threads beside the calling one, which does the first share of
            // every stage: a pool of `threads` workers left one idle, which woke when the step
            // took the others and spun looking for work — a third thread on the cores.
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads - 1)
                .thread_name(|i| format!("tumble-{i}"))
                .build()
                .map_err(|e| WorldError::InvalidSettings(format!("cannot start {threads} threads: {e}")))?;
            Some(std::sync::Arc::new(pool))
        };
        Ok(())
    }

    /// Wall time per step phase, summed since the world was made or [`World::reset_profile`].
    pub fn profile(&self) -> &crate::profile::StepProfile {
        &self.profile
    }

    /// Starts the profile afresh.
    pub fn reset_profile(&mut self) {
        self.profile = Default::default();
    }

    pub fn gravity(&self) -> DVec3 {
        self.gravity
    }

    pub fn set_gravity(&mut self, gravity: DVec3) -> Result<(), WorldError> {
        self.gravity = check_vec("gravity", gravity)?;
        Ok(())
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken so far.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// Adds a body. The definition is checked in full first; on error nothing changes.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyId, WorldError> {
        let invalid = |message: String| WorldError::InvalidBody { body: def.name.clone(), message };
        let finite = |what: &str, v: DVec3| {
            if is_finite_vec(v) {
                Ok(())
            } else {
                Err(invalid(format!("{what} must be finite, got {v}")))
            }
        };
        finite("position", def.position)?;
        finite("linear_velocity", def.linear_velocity)?;
        finite("angular_velocity", def.angular_velocity)?;
        let q = def.orientation;
        let q_len = q.length();
        if !q_len.is_finite() || (q_len - 1.0).abs() > 1e-6 {
            return Err(invalid(format!(
                "orientation must be a unit quaternion (x, y, z, w), got ({}, {}, {}, {}) of length {q_len}",
                q.x, q.y, q.z, q.w
            )));
        }
        for (what, value) in
            [("linear_damping", def.linear_damping), ("angular_damping", def.angular_damping)]
        {
            if !value.is_finite() || value < 0.0 {
                return Err(invalid(format!("{what} must be finite and >= 0, got {value}")));
            }
        }
        def.material.validate().map_err(|m| invalid(format!("material: {m}")))?;
        if !def.gravity_scale.is_finite() {
            return Err(invalid(format!("gravity_scale must be finite, got {}", def.gravity_scale)));
        }
        if let Some(shape) = &def.shape {
            if def.kind != BodyKind::Static {
                if let Some(what) = shape.static_only_part() {
                    return Err(invalid(format!(
                        "a {what} is static-only geometry: a body with one must be static, not {}",
                        def.kind.name()
                    )));
                }
            }
            if def.kind == BodyKind::Dynamic && has_open_mesh(shape) {
                return Err(invalid(
                    "a dynamic body's mesh must be closed (TriMesh::new); a TriMesh::new_static mesh is for static bodies"
                        .into(),
                ));
            }
        }
        let mass_properties = Self::resolve_mass(&def)?;
        let principal = mass_properties.principal();
        let smallest = principal.moments.min_element();
        if def.kind == BodyKind::Dynamic && (smallest.is_nan() || smallest <= 0.0) {
            return Err(invalid(format!(
                "a dynamic body needs positive principal moments of inertia, got {}",
                principal.moments
            )));
        }
        let body = Body::new(&def, mass_properties, principal);
        let id = self.bodies.insert(body);
        let body = self.bodies.get_mut(id).expect("just inserted");
        self.contact_manager.add_body(id.index(), body);
        // Its proxies are not yet stretched by its velocity: the next step moves them.
        self.proxies_in_place_for = None;
        Ok(id.into())
    }

    /// The mass properties a definition asks for, in the body frame.
    fn resolve_mass(def: &BodyDef) -> Result<MassProperties, WorldError> {
        let mass_error = |source| WorldError::Mass { body: def.name.clone(), source };
        if let Some(mp) = def.mass_properties {
            let ok = mp.mass.is_finite()
                && mp.mass > 0.0
                && is_finite_vec(mp.center_of_mass)
                && mp.inertia.is_finite()
                && mat3_max_abs(mp.inertia - mp.inertia.transpose()) <= 1e-9 * mat3_max_abs(mp.inertia);
            if !ok {
                return Err(WorldError::InvalidBody {
                    body: def.name.clone(),
                    message: "mass_properties must have finite mass > 0, a finite centre of mass and a finite symmetric inertia".into(),
                });
            }
            return Ok(mp);
        }
        match &def.shape {
            Some(shape) => {
                if !def.density.is_finite() || def.density <= 0.0 {
                    return Err(mass_error(MassError::NotPositive { what: "density", value: def.density }));
                }
                let mp = match shape.mass_properties(def.density) {
                    // Static geometry has no mass; a static body never uses one.
                    Err(MassError::StaticOnly { .. }) if def.kind != BodyKind::Dynamic => {
                        return Ok(MassProperties {
                            volume: 0.0,
                            mass: 1.0,
                            center_of_mass: DVec3::ZERO,
                            inertia: DMat3::IDENTITY,
                        })
                    }
                    other => other.map_err(mass_error)?,
                };
                match def.mass {
                    Some(m) => mp.with_mass(m).map_err(mass_error),
                    None => Ok(mp),
                }
            }
            None if def.kind == BodyKind::Dynamic => Err(WorldError::InvalidBody {
                body: def.name.clone(),
                message: "a dynamic body needs a shape or mass_properties".into(),
            }),
            // A shapeless static or kinematic body: unit placeholder mass, never used as a mass.
            None => Ok(MassProperties {
                volume: 0.0,
                mass: 1.0,
                center_of_mass: DVec3::ZERO,
                inertia: DMat3::IDENTITY,
            }),
        }
    }

    /// Removes a body and every joint attached to it; its id (and any copy of it) becomes stale.
    pub fn remove_body(&mut self, id: BodyId) -> Result<Body, WorldError> {
        let body = self.bodies.remove(id.into()).ok_or(WorldError::StaleBody(id))?;
        // Bodies it touched may now fall: wake them.
        let touching: Vec<BodyId> = self
            .contact_manager
            .contacts
            .iter()
            .filter(|c| c.touching && (c.body_a == id || c.body_b == id))
            .map(|c| if c.body_a == id { c.body_b } else { c.body_a })
            .collect();
        self.contact_manager.remove_body(&body);
        for other in touching {
            let _ = self.wake_body(other);
        }
        let attached: Vec<_> = self
            .joints
            .iter()
            .filter(|(_, j)| j.body_a == id || j.body_b == id)
            .map(|(jid, _)| jid)
            .collect();
        for jid in attached {
            if let Some(joint) = self.joints.remove(jid) {
                let other = if joint.body_a == id { joint.body_b } else { joint.body_a };
                let _ = self.wake_body(other);
            }
        }
        Ok(body)
    }

    /// Adds a joint between two bodies. Checked in full first; on error nothing changes.
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointId, WorldError> {
        let invalid = |message: String| WorldError::InvalidJoint { joint: def.name.clone(), message };
        let a = self
            .bodies
            .get(def.body_a.into())
            .ok_or_else(|| invalid(format!("body_a {} does not name a body in this world", def.body_a)))?;
        let b = self
            .bodies
            .get(def.body_b.into())
            .ok_or_else(|| invalid(format!("body_b {} does not name a body in this world", def.body_b)))?;
        if def.body_a == def.body_b {
            return Err(invalid("body_a and body_b are the same body".into()));
        }
        if !is_finite_vec(def.anchor_world) {
            return Err(invalid(format!("anchor must be finite, got {}", def.anchor_world)));
        }
        let axis_len = def.axis_world.length();
        if !axis_len.is_finite() || axis_len < 1e-9 {
            return Err(invalid(format!("axis must be a finite non-zero vector, got {}", def.axis_world)));
        }
        for (what, limit) in [("break_force", def.break_force), ("break_torque", def.break_torque)] {
            if let Some(f) = limit {
                if !f.is_finite() || f <= 0.0 {
                    return Err(invalid(format!("{what} must be finite and > 0, got {f}")));
                }
            }
        }
        if let Some(anchor_b) = def.anchor_b_world {
            if !is_finite_vec(anchor_b) {
                return Err(invalid(format!("anchor_b_world must be finite, got {anchor_b}")));
            }
            if !matches!(def.kind, crate::dynamics::joint::JointKind::Distance(_)) {
                return Err(invalid(format!(
                    "anchor_b_world is only for distance joints; a {} joint's anchors coincide",
                    def.kind.name()
                )));
            }
        }
        if a.kind != BodyKind::Dynamic && b.kind != BodyKind::Dynamic {
            return Err(invalid("at least one of the two bodies must be dynamic".into()));
        }
        def.kind.validate().map_err(invalid)?;
        let joint = Joint::new(&def, a, b);
        let id = self.joints.insert(joint).into();
        self.wake_body(def.body_a)?;
        self.wake_body(def.body_b)?;
        Ok(id)
    }

    /// Removes a joint; its id becomes stale.
    pub fn remove_joint(&mut self, id: JointId) -> Result<Joint, WorldError> {
        let joint = self.joints.remove(id.into()).ok_or(WorldError::StaleJoint(id))?;
        // The bodies it held may now move: wake them (a removed body's id is simply stale).
        let _ = self.wake_body(joint.body_a);
        let _ = self.wake_body(joint.body_b);
        Ok(joint)
    }

    pub fn joint(&self, id: JointId) -> Result<&Joint, WorldError> {
        self.joints.get(id.into()).ok_or(WorldError::StaleJoint(id))
    }

    /// All joints with their ids, in a fixed (slot) order.
    pub fn joints(&self) -> impl Iterator<Item = (JointId, &Joint)> {
        self.joints.iter().map(|(id, j)| (id.into(), j))
    }

    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The touching contacts (manifolds with points), in a fixed order.
    pub fn contacts(&self) -> Vec<ContactView> {
        let substeps = f64::from(self.solver_settings.substeps);
        self.contact_manager
            .contacts
            .iter()
            .filter_map(|c| {
                let m = c.manifold.as_ref().filter(|_| c.touching)?;
                Some(ContactView {
                    body_a: c.body_a,
                    body_b: c.body_b,
                    normal: m.normal_world,
                    sensor: c.sensor,
                    points: m
                        .points()
                        .iter()
                        .zip(&c.impulses)
                        .map(|(p, i)| ContactPointView {
                            point: p.point_world,
                            separation: p.separation,
                            normal_impulse: i.normal * substeps,
                            tangent_impulse: i.tangent_world * substeps,
                            feature_id: p.feature_id,
                        })
                        .collect(),
                })
            })
            .collect()
    }

    /// Number of touching contact manifolds.
    pub fn contact_count(&self) -> usize {
        self.contact_manager.contacts.iter().filter(|c| c.touching).count()
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    pub fn body(&self, id: BodyId) -> Result<&Body, WorldError> {
        self.bodies.get(id.into()).ok_or(WorldError::StaleBody(id))
    }

    pub(crate) fn body_mut(&mut self, id: BodyId) -> Result<&mut Body, WorldError> {
        self.proxies_in_place_for = None;
        self.bodies.get_mut(id.into()).ok_or(WorldError::StaleBody(id))
    }

    /// All bodies with their ids, in a fixed (slot) order.
    pub fn bodies(&self) -> impl Iterator<Item = (BodyId, &Body)> {
        self.bodies.iter().map(|(id, b)| (id.into(), b))
    }

    /// The first body with this name.
    pub fn find_body(&self, name: &str) -> Option<BodyId> {
        self.bodies().find(|(_, b)| b.name == name).map(|(id, _)| id)
    }

    // ---- changing state -------------------------------------------------------------------

    /// Places the body frame's origin at `position` with `orientation` (normalised; one that is
    /// already unit to rounding is kept bit for bit, so a pose read from a body and written back
    /// leaves the body exactly as it was).
    pub fn set_pose(
        &mut self,
        id: BodyId,
        position: DVec3,
        orientation: crate::math::DQuat,
    ) -> Result<(), WorldError> {
        check_vec("position", position)?;
        let len = orientation.length();
        if !len.is_finite() || len < 1e-9 {
            return Err(WorldError::NotFinite { what: "orientation", value: format!("{orientation}") });
        }
        self.wake_body(id)?;
        let body = self.body_mut(id)?;
        // Renormalising a quaternion that is unit to rounding would still change its last bits.
        let rotation = if (orientation.length_squared() - 1.0).abs() <= 4.0 * f64::EPSILON {
            orientation
        } else {
            orientation.normalize()
        };
        body.state.rotation = rotation;
        body.state.com_world = position + rotation * body.com_local;
        // Keep the broad phase in step with the pose, so queries see the body where it now is.
        let body = self.bodies.get(id.into()).expect("checked above");
        self.contact_manager.move_body_proxies(body, 0.0);
        Ok(())
    }

    /// Sets the velocity of the centre of mass. Ignored for static bodies (they never move).
    pub fn set_linear_velocity(&mut self, id: BodyId, v: DVec3) -> Result<(), WorldError> {
        check_vec("linear velocity", v)?;
        self.wake_body(id)?;
        let body = self.body_mut(id)?;
        if body.kind != BodyKind::Static {
            body.state.linear_velocity = v;
        }
        Ok(())
    }

    /// Sets the angular velocity (world frame). Ignored for static bodies.
    pub fn set_angular_velocity(&mut self, id: BodyId, w: DVec3) -> Result<(), WorldError> {
        check_vec("angular velocity", w)?;
        self.wake_body(id)?;
        let body = self.body_mut(id)?;
        if body.kind != BodyKind::Static {
            body.state.angular_velocity = w;
        }
        Ok(())
    }

    /// Makes the body a bullet or an ordinary body. After each step a dynamic bullet's motion is
    /// swept from its pose at the start of the step to its pose at the end against static
    /// geometry; if it passed through something, or ended deep inside it, it is moved back to
    /// the time of impact (`continuous.rs`). Static and kinematic bodies keep the flag but are
    /// never swept. Does not wake the body.
    pub fn set_bullet(&mut self, id: BodyId, bullet: bool) -> Result<(), WorldError> {
        self.body_mut(id)?.bullet = bullet;
        Ok(())
    }

    /// Adds force `f` acting at the world point `point_world`: the body gets `f` and the torque
    /// `(p − x) × f` about its centre of mass. Cleared after the next step.
    pub fn apply_force_at_point(
        &mut self,
        id: BodyId,
        force: DVec3,
        point_world: DVec3,
    ) -> Result<(), WorldError> {
        check_vec("force", force)?;
        check_vec("point", point_world)?;
        self.wake_body(id)?;
        self.forces_pending = true;
        let body = self.body_mut(id)?;
        body.force_world += force;
        body.torque_world += (point_world - body.state.com_world).cross(force);
        Ok(())
    }

    /// Adds force `f` at the centre of mass (no torque).
    pub fn apply_force(&mut self, id: BodyId, force: DVec3) -> Result<(), WorldError> {
        check_vec("force", force)?;
        self.wake_body(id)?;
        self.forces_pending = true;
        self.body_mut(id)?.force_world += force;
        Ok(())
    }

    /// Adds a torque about the centre of mass (world frame).
    pub fn apply_torque(&mut self, id: BodyId, torque: DVec3) -> Result<(), WorldError> {
        check_vec("torque", torque)?;
        self.wake_body(id)?;
        self.forces_pending = true;
        self.body_mut(id)?.torque_world += torque;
        Ok(())
    }

    /// Applies impulse `j` at `point_world` now: `Δv = j/m`, `ΔL = (p − x) × j`. No effect on
    /// static or kinematic bodies.
    pub fn apply_impulse_at_point(
        &mut self,
        id: BodyId,
        impulse: DVec3,
        point_world: DVec3,
    ) -> Result<(), WorldError> {
        check_vec("impulse", impulse)?;
        check_vec("point", point_world)?;
        self.wake_body(id)?;
        let body = self.body_mut(id)?;
        if body.kind != BodyKind::Dynamic {
            return Ok(());
        }
        let r = point_world - body.state.com_world;
        body.state.linear_velocity += impulse * body.inverse_mass;
        body.state.angular_velocity += body.inverse_inertia_world() * r.cross(impulse);
        Ok(())
    }

    /// Applies an angular impulse (world frame) now: `ΔL = j`.
    pub fn apply_angular_impulse(&mut self, id: BodyId, angular_impulse: DVec3) -> Result<(), WorldError> {
        check_vec("angular impulse", angular_impulse)?;
        self.wake_body(id)?;
        let body = self.body_mut(id)?;
        if body.kind == BodyKind::Dynamic {
            body.state.angular_velocity += body.inverse_inertia_world() * angular_impulse;
        }
        Ok(())
    }

    // ---- reading derived quantities ------------------------------------------------------------

    /// Velocity of the body's material point now at `point_world`.
    pub fn point_velocity(&self, id: BodyId, point_world: DVec3) -> Result<DVec3, WorldError> {
        Ok(self.body(id)?.point_velocity(point_world))
    }

    /// Acceleration of the body's material point now at `point_world`, from gravity and the
    /// forces and torques accumulated so far.
    pub fn point_acceleration(&self, id: BodyId, point_world: DVec3) -> Result<DVec3, WorldError> {
        Ok(self.body(id)?.point_acceleration(point_world, self.gravity))
    }

    /// The point inverse mass matrix `K(r₁, r₂)`; offsets from the centre of mass, world frame.
    pub fn inverse_mass_matrix(&self, id: BodyId, r1: DVec3, r2: DVec3) -> Result<DMat3, WorldError> {
        Ok(self.body(id)?.inverse_mass_matrix(r1, r2))
    }

    /// Total kinetic energy of the dynamic bodies.
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies.iter().map(|(_, b)| b.kinetic_energy()).sum()
    }

    /// Total gravitational potential energy of the dynamic bodies, `−m g·x`, zero at the origin.
    pub fn potential_energy(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|(_, b)| b.kind == BodyKind::Dynamic)
            .map(|(_, b)| -b.mass() * b.gravity_scale * self.gravity.dot(b.state.com_world))
            .sum()
    }

    /// Total linear momentum of the dynamic bodies.
    pub fn linear_momentum(&self) -> DVec3 {
        self.bodies.iter().map(|(_, b)| b.linear_momentum()).sum()
    }

    /// Total angular momentum of the dynamic bodies about the fixed world point `origin_world`.
    pub fn angular_momentum(&self, origin_world: DVec3) -> DVec3 {
        self.bodies.iter().map(|(_, b)| b.angular_momentum_about(origin_world)).sum()
    }

    /// Total angular momentum about the system's centre of mass (the dynamic bodies').
    pub fn angular_momentum_about_com(&self) -> DVec3 {
        let (m, mx) = self
            .bodies
            .iter()
            .filter(|(_, b)| b.kind == BodyKind::Dynamic)
            .fold((0.0, DVec3::ZERO), |(m, mx), (_, b)| (m + b.mass(), mx + b.mass() * b.state.com_world));
        if m == 0.0 {
            return DVec3::ZERO;
        }
        self.angular_momentum(mx / m)
    }
}
