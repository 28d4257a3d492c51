//! The soft-step solver: the stages of one step, in order (Catto's Solver2D "soft step", as in
//! Box2D v3):
//!
//! | stage | what it does |
//! |---|---|
//! | prepare | anchors, effective masses, step-start separations for every joint (and contact) |
//! | per substep: integrate velocities | gravity, forces, half the torque kick, damping |
//! | per substep: warm start | apply last substep's accumulated impulses |
//! | per substep: solve | soft constraints with position bias (push apart / pull together) |
//! | per substep: integrate positions | `x += h v`; rotation by the exact free-body flow |
//! | per substep: project joint trees | move tree-jointed bodies back onto their joints (Newton on the positions; velocities untouched) |
//! | per substep: relax | the same constraints, rigid and without bias, to remove the bias energy; each contact's steady load then learns from its impulse |
//! | per substep: restitution | bounce where the approach was faster than the threshold and has stopped (at the last substep: wherever it was) |
//! | store impulses | keep impulses for the next step's warm start; joint breaking |
//!
//! Substepping with soft constraints gives the stiffness of many iterations at the price of one
//! iteration per substep; the relax pass removes the velocity the position bias added, so stacks
//! rest without jitter or energy gain.

use crate::body::{Body, BodyKind};
use crate::collision::contact_manager::{leaf, plan_proxies, ProxyPlan};
use crate::collision::contact_store::{prefetch_ahead, prefetch_start, Reach, PREFETCH_AHEAD};
use crate::collision::manifold::ContactPoint;
use crate::dynamics::contact::Contact;
use crate::dynamics::contact_solver::{
    solve_group, warm_start_group, ContactConstraint, ContactImpulse, ContactPointInput, PointInputs,
    StillBlock, GROUP, GROUPS_PAY,
};
use crate::dynamics::joint::Joint;
use crate::dynamics::softness::Softness;
use crate::dynamics::solver_body::SolverBody;
use crate::dynamics::solver_threads::{run_on_threads, ColouredContacts, SolveData};
use crate::id::{Slot, SlotPool};
use crate::math::DVec3;
use crate::profile::Phase;
use crate::shape::Shape;
use crate::step_threads::{for_each_chunk_of, resize_on_threads, StepThreads};
use crate::world::World;
use std::time::Instant;

/// Solver settings. The defaults suit 60 Hz steps of everyday objects.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolverSettings {
    /// Substeps per step. Default 8. More substeps allow stiffer joints (`joint_hertz` is capped
    /// at a quarter of the substep rate).
    pub substeps: u32,
    /// Stiffness of joint position correction, Hz (capped at a quarter of the substep rate).
    /// Default 120, the cap at 8 substeps and dt = 1/60 (`ωh = π/2`).
    pub joint_hertz: f64,
    /// Damping ratio of joint position correction.
    pub joint_damping_ratio: f64,
    /// Stiffness of contact position correction, Hz (capped at an eighth of the substep rate;
    /// doubled against static bodies, capped there at a quarter). Default 60: the cap at 8
    /// substeps, stiff enough and well enough resolved that a pyramid of 210 boxes settles
    /// within 1.6 mm.
    pub contact_hertz: f64,
    /// Damping ratio of contact position correction.
    pub contact_damping_ratio: f64,
    /// Largest speed at which overlapping bodies are pushed apart, m/s.
    pub max_contact_push_velocity: f64,
    /// Approach speed below which contacts do not bounce, m/s.
    pub restitution_threshold: f64,
    /// Reuse last step's impulses as the starting guess.
    pub warm_starting: bool,
    /// Biased (position-correcting) sweeps over the constraints per substep. Default 1. Extra
    /// sweeps converge coupled rows further (they steady stiff, high-mass-ratio systems) but do not
    /// make soft joints stiffer: a joint's stretch under load is set by `joint_hertz`.
    pub solve_iterations: u32,
    /// Relax sweeps per substep (0 allowed). Default 1.
    pub relax_iterations: u32,
    /// Time constant, s, over which a settled contact learns the steady load it carries, so that
    /// it holds that load without sagging (0 = plain soft contacts, which sag by load/stiffness:
    /// 2.6 cm over a stack of ten boxes at 4 substeps). A new contact learns faster, over its age,
    /// down to a fifth of this (`ContactConstraint::update_steady_load`). Joints do not use it:
    /// their loads turn with the bodies, and a learned load that lags a swinging pendulum pulls
    /// it apart. Default 0.5 s.
    #[serde(default)]
    pub steady_load_time: f64,
    /// Solve the rows holding tree-shaped groups of joints together (chains, robot arms)
    /// exactly in each pass, all at once (`dynamics/joint_tree/`), rather than row by row. Exact
    /// rows do not stretch under load, whatever the mass ratios; `joint_hertz` then sets only how
    /// fast drift is corrected. Loops, distance joints, motors, springs and friction are solved
    /// row by row either way, and so are joints that have any of those (`docs/joint-tree.md`).
    /// Default true.
    #[serde(default = "default_true")]
    pub joint_trees: bool,
    /// Let joints with limits into the joint trees, whose solve then takes each limit row in
    /// while it pushes (`docs/joint-tree.md`, "Limits in the tree"): a ragdoll's joints hold to
    /// a tenth of a millimetre instead of stretching by centimetres, at the cost of solving the
    /// figure exactly. False keeps such joints, and the figures they act on, row by row.
    /// Default true.
    #[serde(default = "default_true")]
    pub joint_tree_limits: bool,
    /// Most Newton steps per substep of the joint trees' position projection, which moves each
    /// tree's bodies after the position stage until its rows' position errors are at most
    /// `joint_projection_tolerance` (`docs/joint-tree.md`, "Holding the positions"). Most
    /// substeps need one or none; a 100-link chain whipping round at one substep of 1/60 s
    /// needed up to five. 0 turns the projection off: drift is then corrected only through the
    /// velocities, at `joint_hertz`. Default 8.
    #[serde(default = "default_joint_projection_iterations")]
    pub joint_projection_iterations: u32,
    /// The position error, m (rad for angular rows), up to which the projection leaves a joint
    /// tree alone. Default 1e-4 (a tenth of a millimetre).
    #[serde(default = "default_joint_projection_tolerance")]
    pub joint_projection_tolerance: f64,
}

fn default_true() -> bool {
    true
}

fn default_joint_projection_iterations() -> u32 {
    8
}

fn default_joint_projection_tolerance() -> f64 {
    1e-4
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            substeps: 8,
            joint_hertz: 120.0,
            joint_damping_ratio: 2.0,
            contact_hertz: 60.0,
            contact_damping_ratio: 10.0,
            max_contact_push_velocity: 3.0,
            restitution_threshold: 1.0,
            warm_starting: true,
            solve_iterations: 1,
            relax_iterations: 1,
            steady_load_time: 0.5,
            joint_trees: true,
            joint_tree_limits: true,
            joint_projection_iterations: default_joint_projection_iterations(),
            joint_projection_tolerance: default_joint_projection_tolerance(),
        }
    }
}

/// Per-step constants every stage reads.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct StepContext {
    /// Substep length.
    pub h: f64,
    pub inv_h: f64,
    pub substeps: u32,
    pub gravity: DVec3,
    pub joint_softness: Softness,
    /// The soft normal rows of contacts between two moving bodies (contact hertz, capped).
    pub contact_softness: Softness,
    /// Contacts against static (or kinematic) bodies: twice as stiff, since only one body moves.
    pub static_contact_softness: Softness,
    pub max_contact_push_velocity: f64,
    pub restitution_threshold: f64,
    pub warm_starting: bool,
    pub solve_iterations: u32,
    pub relax_iterations: u32,
    /// Time constant of settled contacts' steady loads, s (0 = off).
    pub steady_load_time: f64,
    /// Joint trees are projected onto their joints after each position stage
    /// (`joint_projection_iterations > 0`).
    #[serde(default)]
    pub project_joint_trees: bool,
}

impl StepContext {
    pub fn new(dt: f64, gravity: DVec3, settings: &SolverSettings) -> StepContext {
        let substeps = settings.substeps.max(1);
        let h = dt / f64::from(substeps);
        // A soft constraint stiffer than a quarter of the substep rate is no longer resolved by
        // the substeps and starts to ring; cap it there.
        let max_hertz = 0.25 / h;
        StepContext {
            h,
            inv_h: 1.0 / h,
            substeps,
            gravity,
            // Joints too: at `ωh = π` (Box2D's joint cap of twice the contact cap) a chain with a
            // 100:1 mass ratio diverges; at `ωh = π/2` it is stable (tests/joints.rs, J4).
            joint_softness: Softness::new(
                settings.joint_hertz.min(max_hertz),
                settings.joint_damping_ratio,
                h,
            ),
            // Contacts between two moving bodies: an eighth of the substep rate (`ωh = π/4`). A
            // box pyramid at 4 substeps holds at 30 Hz (`ωh = π/4`) and falls at 40 Hz and above
            // (`ωh ≥ 1.05`: 0.18 m, 60 Hz: 1.4 m); against a static body, twice that.
            contact_softness: Softness::new(
                settings.contact_hertz.min(0.5 * max_hertz),
                settings.contact_damping_ratio,
                h,
            ),
            static_contact_softness: Softness::new(
                (2.0 * settings.contact_hertz).min(max_hertz),
                settings.contact_damping_ratio,
                h,
            ),
            max_contact_push_velocity: settings.max_contact_push_velocity,
            restitution_threshold: settings.restitution_threshold,
            warm_starting: settings.warm_starting,
            solve_iterations: settings.solve_iterations.max(1),
            relax_iterations: settings.relax_iterations,
            steady_load_time: settings.steady_load_time.max(0.0),
            project_joint_trees: settings.joint_trees && settings.joint_projection_iterations > 0,
        }
    }
}

/// Contacts below which they are prepared on one thread.
pub(crate) const PARALLEL_MIN_CONTACTS: usize = 128;

/// Bodies from which the body stages alone make threads worth their stages' hand-overs.
pub(crate) const PARALLEL_MIN_BODIES: usize = 1024;

/// Bodies a thread gathers at a time.
const GATHER_CHUNK: usize = 256;

/// Contacts a thread flags or stores impulses for at a time.
const CONTACT_CHUNK: usize = 256;

/// Chunks of contacts from which flagging them and storing their impulses is shared between the
/// threads: below that, the hand-over and the cache lines crossing between cores cost more than
/// the walk (a 210-box pyramid's 420 contacts ran 2% slower on two threads when shared).
const PARALLEL_MIN_CONTACT_CHUNKS: usize = 8;

impl World {
    /// Runs the solver stages for one step of `dt` (see the module docs for the order), on the
    /// world's threads if it has them; the set-up and the substeps are timed into the profile
    /// from `clock`.
    pub(crate) fn solve(&mut self, dt: f64, threads: Option<&StepThreads>, clock: &mut Instant) {
        let ctx = StepContext::new(dt, self.gravity, &self.solver_settings);

        // Gather: the solver's working copy of every body, indexed by slot.
        let mut bodies = std::mem::take(&mut self.solver_bodies);
        // Sleeping bodies stand still: they take part as fixed bodies, if at all. Isolated bodies
        // (non_finite.rs) have no contacts and broken joints: they take no part.
        let world_bodies = &self.bodies;
        let gather = |slot: usize| match world_bodies.iter_slot(slot) {
            Some(body) if body.is_awake() && !body.isolated => SolverBody::from_body(body),
            _ => SolverBody::FIXED,
        };
        // Assigned in place over last step's vector: collected through an iterator, each solver
        // body was built on the stack and then copied (a third of the gather's time).
        // Each slot's summary comes with it: the contacts' take-part test, their set-up and the
        // body partition then read a few bytes per body instead of two bodies of some hundred
        // bytes, scattered.
        let count = world_bodies.capacity_index();
        let mut summaries = std::mem::take(&mut self.solver_slot_summaries);
        bodies.resize(count, SolverBody::FIXED);
        summaries.resize(count, SlotSummary::default());
        let gather_chunk = |offset: usize, part: &mut [SolverBody], part_summaries: &mut [SlotSummary]| {
            for (i, (dst, summary)) in part.iter_mut().zip(part_summaries).enumerate() {
                *dst = gather(offset + i);
                *summary = SlotSummary::of(dst, world_bodies.iter_slot(offset + i));
            }
        };
        match threads.filter(|_| count >= PARALLEL_MIN_BODIES) {
            Some(threads) => {
                threads.for_each_chunk((&mut bodies, &mut summaries), GATHER_CHUNK, gather_chunk)
            }
            None => gather_chunk(0, &mut bodies, &mut summaries),
        }

        // Prepare joints.
        for (_, joint) in self.joints.iter_mut() {
            joint.solving = false;
            if joint.broken {
                continue;
            }
            let (Some(a), Some(b)) =
                (self.bodies.get(joint.body_a.into()), self.bodies.get(joint.body_b.into()))
            else {
                continue;
            };
            let movable = |body: &Body| body.kind() != BodyKind::Static && body.is_awake();
            if !movable(a) && !movable(b) {
                continue;
            }
            joint.solving = true;
            joint.prepare(a, b, &ctx);
            if !ctx.warm_starting {
                joint.reset_impulses();
            }
        }

        // Joint trees: the figures whose joints' equality rows are solved exactly.
        let mut trees = std::mem::take(&mut self.joint_trees);
        if self.solver_settings.joint_trees {
            trees.build(&mut self.joints, &bodies, self.solver_settings.joint_tree_limits);
        } else {
            trees.clear(&mut self.joints);
        }

        // Prepare contacts: every touching, non-sensor manifold with a body that can move, each
        // into its place in colour order — a colour's rows share no moving body, so a colour is
        // solved on all threads at once, with the same result for any thread count (colouring.rs).
        let mut contacts = std::mem::take(&mut self.contact_constraints);
        let mut colouring = std::mem::take(&mut self.contact_colouring);
        let mut solved = std::mem::take(&mut self.solved_contacts);
        let store = self.contact_manager.contacts.as_slice();
        // The contacts that take part, in store order: each place tested (on the threads: each test
        // reads a contact, a cache miss apiece), then those left out dropped. What the serial
        // stages below need of a contact is copied out in the same read: walking the kilobyte-long
        // contacts again for their bodies, on one thread, cost the rain a miss per contact.
        solved.clear();
        solved.resize(store.len(), SolvedContact::LEFT_OUT);
        let contact_threads = threads.filter(|_| store.len() >= PARALLEL_MIN_CONTACT_CHUNKS * CONTACT_CHUNK);
        for_each_chunk_of(contact_threads, &mut solved, CONTACT_CHUNK, |offset, places| {
            prefetch_start(&store[offset..], Reach::Head);
            for (i, place) in places.iter_mut().enumerate() {
                prefetch_ahead(store, offset + i, Reach::Head);
                let contact = &store[offset + i];
                if takes_part(contact, &summaries) {
                    *place = SolvedContact {
                        place: (offset + i) as u32,
                        bodies: (contact.body_a.index() as u32, contact.body_b.index() as u32),
                        moving: (
                            summaries[contact.body_a.index()].dynamic,
                            summaries[contact.body_b.index()].dynamic,
                        ),
                        bounces: contact.material.restitution != 0.0,
                    };
                }
            }
        });
        solved.retain(|s| s.place != SolvedContact::LEFT_OUT.place);
        let restitution = solved.iter().any(|s| s.bounces);
        let count = colouring.colour(
            solved.iter().map(|s| ((s.bodies.0 as usize, s.moving.0), (s.bodies.1 as usize, s.moving.1))),
            bodies.len(),
            threads.is_some(),
        );
        resize_on_threads(&mut contacts, count, ContactConstraint::EMPTY, threads);
        {
            let coloured = ColouredContacts::new(&mut contacts, &colouring);
            // Threads only where there are enough contacts to share (the result is the same).
            run_on_threads(threads.filter(|_| count >= PARALLEL_MIN_CONTACTS), |thread| {
                for input in thread.share(0..count) {
                    if let Some(ahead) = solved.get(input + PREFETCH_AHEAD) {
                        store[ahead.place as usize].prefetch();
                        coloured.prefetch_slot(input + PREFETCH_AHEAD);
                    }
                    let contact = &store[solved[input].place as usize];
                    coloured.with_slot(thread, input, |slot| {
                        prepare_contact(slot, contact, &bodies, &summaries, world_bodies, &ctx)
                    });
                }
            });
        }
        let mut joint_components = std::mem::take(&mut self.joint_components);
        joint_components.build(&self.joints, &bodies);
        let has_joints = !joint_components.is_empty();
        let mut partition = std::mem::take(&mut self.body_partition);
        partition.split(&summaries, &solved, &self.joints);

        // The substeps, on every thread of the pool at once (solver_threads.rs) — where some stage
        // is split between them: waiting at the ends of stages that are not (a chain of joints)
        // only costs. The result is the same either way.
        let worth_threads = colouring.stages().iter().any(|&(_, split)| split)
            || partition.constrained.len() >= PARALLEL_MIN_BODIES
            || partition.unconstrained.len() >= PARALLEL_MIN_BODIES;
        let threads = threads.filter(|_| worth_threads);
        // Still manifolds in groups of four where that pays (contact_lanes.rs); the same bits
        // either way.
        let in_lanes = self.contacts_in_groups.unwrap_or(GROUPS_PAY);
        let mut blocks = std::mem::take(&mut self.still_blocks);
        // Each block is written over at the step's start (`fill_blocks`).
        let block_count = if in_lanes { contacts.len().div_ceil(GROUP) } else { 0 };
        resize_on_threads(&mut blocks, block_count, StillBlock::default(), threads);
        let lists = (&partition.constrained[..], &partition.unconstrained[..]);
        let joint_lists = (self.joints.slots_mut(), &joint_components);
        let data = SolveData::new(
            &mut bodies,
            lists,
            &mut contacts,
            &mut blocks,
            &colouring,
            joint_lists,
            &mut trees,
        );
        let ctx = &ctx;
        self.profile.lap(Phase::SolveSetUp, clock);
        let projection_iterations = self.solver_settings.joint_projection_iterations;
        let projection_tolerance = self.solver_settings.joint_projection_tolerance;
        // Projected trees are held at the position level: their velocity rows are rigid without
        // bias (`JointTrees::project_positions`).
        let tree_bias_rate = if ctx.project_joint_trees { 0.0 } else { ctx.joint_softness.bias_rate };
        run_on_threads(threads, |thread| {
            // The rows of the still manifolds' groups, for the step (contact_lanes.rs).
            data.fill_blocks(thread);
            // A body no constraint acts on goes through all its substeps at once.
            data.unconstrained_bodies(thread, |bodies| {
                SolverBody::integrate_unconstrained(bodies, ctx.gravity, ctx.h, ctx.substeps)
            });
            // Joints component by component, the components shared between the threads
            // (joint_components.rs).
            let joint_stage = |f: &dyn Fn(&mut Joint, &mut SolverBody, &mut SolverBody)| {
                if has_joints {
                    data.joints_with_bodies(thread, f);
                }
            };
            for substep in 0..ctx.substeps {
                data.bodies(thread, |body| body.integrate_velocity(ctx.gravity, ctx.h));
                joint_stage(&|joint, a, b| joint.warm_start(a, b));
                // Still manifolds of a colour go four at a time in SIMD lanes (contact_lanes.rs):
                // the same numbers as one at a time.
                data.contacts_in_groups(
                    thread,
                    |c, a, b| c.warm_start(a, b),
                    |cs, block, bodies| warm_start_group(cs, block, bodies),
                );
                for _ in 0..ctx.solve_iterations {
                    joint_stage(&|joint, a, b| joint.solve(a, b, ctx, true));
                    // The trees before the contacts, which keep the last word as they do in the
                    // relax pass (`docs/joint-tree.md`, "Where it runs in the step").
                    if has_joints {
                        data.serial(thread, |trees, joints, bodies| {
                            trees.solve(joints, bodies, tree_bias_rate, ctx.inv_h)
                        });
                    }
                    data.contacts_in_groups(
                        thread,
                        |c, a, b| c.solve(a, b, ctx, true),
                        |cs, block, bodies| solve_group(cs, block, bodies, ctx, true),
                    );
                }
                data.bodies(thread, |body| body.integrate_position(ctx.h));
                // Joint trees back onto their constraints (before the relax pass reads the poses).
                if has_joints && ctx.project_joint_trees {
                    data.serial(thread, |trees, joints, bodies| {
                        trees.project_positions(
                            joints,
                            bodies,
                            world_bodies,
                            projection_tolerance,
                            projection_iterations,
                            ctx.h,
                        )
                    });
                }
                // The steady loads learn from each contact's final impulse of the substep: in the
                // last relax sweep, right after the contact's row is solved (nothing else touches
                // that contact before the next substep; a separate sweep over the contacts cost
                // another pass through their memory and a stage end).
                let learn = ctx.steady_load_time > 0.0;
                for sweep in 0..ctx.relax_iterations {
                    let last_sweep = sweep + 1 == ctx.relax_iterations;
                    joint_stage(&|joint, a, b| joint.solve(a, b, ctx, false));
                    data.contacts_in_groups(
                        thread,
                        |c, a, b| {
                            c.solve(a, b, ctx, false);
                            if learn && last_sweep {
                                c.update_steady_load(ctx.steady_load_time, ctx.h);
                            }
                        },
                        |cs, block, bodies| {
                            let velocities = solve_group(cs, block, bodies, ctx, false)?;
                            if learn && last_sweep {
                                block.update_steady_loads(ctx.steady_load_time, ctx.h);
                            }
                            Some(velocities)
                        },
                    );
                }
                // Without a relax pass the steady loads learn here, each group's in its block
                // (the state stays there for the next substep's passes: given back to the
                // contacts and taken again each substep, it was 7% of the matched pyramid).
                if learn && ctx.relax_iterations == 0 {
                    data.update_steady_loads(thread, ctx.steady_load_time, ctx.h);
                }
                // Restitution reads the contacts themselves, which the groups' state then goes
                // back to.
                if restitution {
                    data.give_back_block_states(thread);
                    let last = substep + 1 == ctx.substeps;
                    data.contacts_with_bodies(thread, |c, a, b| c.apply_restitution(a, b, ctx, last));
                }
            }
            // The impulses are kept from the contacts below.
            data.give_back_block_states(thread);
        });
        self.profile.lap(Phase::Substeps, clock);

        // Keep the impulses for the next step's warm start (the same contacts in the same order),
        // on the threads in chunks of the store: each contact's from its constraint, wherever the
        // colouring put that.
        let store = self.contact_manager.contacts.as_mut_slice();
        let store_impulses = |offset: usize, part: &mut [Contact]| {
            let first = solved.partition_point(|s| (s.place as usize) < offset);
            for (input, s) in solved.iter().enumerate().skip(first) {
                let Some(contact) = part.get_mut(s.place as usize - offset) else { break };
                let impulses = contacts[colouring.slot(input)].impulses();
                for (slot, impulse) in contact.impulses.iter_mut().zip(impulses) {
                    *slot = impulse;
                }
            }
        };
        for_each_chunk_of(contact_threads, store, CONTACT_CHUNK, store_impulses);
        self.solved_contacts = solved;
        self.contact_colouring = colouring;
        self.contact_constraints = contacts;
        self.still_blocks = blocks;
        self.body_partition = partition;
        self.joint_trees = trees;
        self.joint_components = joint_components;

        // Store: constraint forces and joint breaking, then write the bodies back.
        for (_, joint) in self.joints.iter_mut() {
            if joint.solving {
                joint.store(ctx);
            }
        }
        // On the threads in chunks of slots, each body on its own; the bodies left non-finite are
        // marked, and listed after in slot order. Beside each body's write-back, while it is in
        // cache, the plan for its proxies at the step's end (collision/contact_manager.rs): the
        // boxes and fat-box tests of a rain of 2,000 balls, done in the finalize stage, missed
        // the cache on each body there, 0.3–0.7 ms a step on one thread.
        let broad_phase = &self.contact_manager.broad_phase;
        let write_back = |offset: usize, slots: &mut [Slot<Body>], written: &mut [WrittenBack]| {
            for (i, (slot, written)) in slots.iter_mut().zip(written).enumerate() {
                *written = WrittenBack::default();
                if let Some(body) = slot.value_mut().filter(|body| body.is_awake() && !body.isolated) {
                    let start = body.state;
                    bodies[offset + i].write_back(body);
                    written.non_finite = crate::non_finite::left_non_finite(body);
                    written.proxies = if written.non_finite {
                        // Back where it was, for check 2 to isolate it there (non_finite.rs).
                        body.state = start;
                        ProxyPlan::Later
                    } else {
                        plan_proxies(broad_phase, body, dt)
                    };
                }
            }
        };
        let slots = self.bodies.slots_mut();
        let mut written = std::mem::take(&mut self.written_back);
        written.resize(slots.len(), WrittenBack::default());
        match threads.filter(|_| slots.len() >= PARALLEL_MIN_BODIES) {
            Some(threads) => threads.for_each_chunk((slots, &mut written), GATHER_CHUNK, write_back),
            None => write_back(0, slots, &mut written),
        }
        self.non_finite_after_solve.clear();
        self.non_finite_after_solve
            .extend(written.iter().enumerate().filter(|(_, w)| w.non_finite).map(|(slot, _)| slot));
        self.written_back = written;
        self.solver_bodies = bodies;
        self.solver_slot_summaries = summaries;
    }
}

/// The moving bodies of a step, split by whether any constraint acts on them: the substeps'
/// body stages run over the constrained ones; the unconstrained ones take all their substeps at
/// once (`SolverBody::integrate_unconstrained`).
#[derive(Clone, Debug, Default)]
pub(crate) struct BodyPartition {
    pub constrained: Vec<u32>,
    pub unconstrained: Vec<u32>,
    acted_on: Vec<bool>,
}

impl BodyPartition {
    /// Splits the moving (dynamic or kinematic) bodies by whether a contact row or a solved joint
    /// acts on them; each list in slot order.
    fn split(&mut self, bodies: &[SlotSummary], contacts: &[SolvedContact], joints: &SlotPool<Joint>) {
        self.acted_on.clear();
        self.acted_on.resize(bodies.len(), false);
        for contact in contacts {
            self.acted_on[contact.bodies.0 as usize] = true;
            self.acted_on[contact.bodies.1 as usize] = true;
        }
        for (_, joint) in joints.iter().filter(|(_, joint)| joint.solving) {
            self.acted_on[joint.body_a.index()] = true;
            self.acted_on[joint.body_b.index()] = true;
        }
        self.constrained.clear();
        self.unconstrained.clear();
        for (slot, _) in bodies.iter().enumerate().filter(|(_, body)| body.moves) {
            let list = if self.acted_on[slot] { &mut self.constrained } else { &mut self.unconstrained };
            list.push(slot as u32);
        }
    }
}

/// A contact the solver takes: its place in the contact store, and what the serial stages need of
/// it (copied out once, on the threads; see `World::solve`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SolvedContact {
    place: u32,
    /// The slots of its bodies a and b.
    bodies: (u32, u32),
    /// Whether bodies a and b are dynamic (what the colouring needs of them).
    moving: (bool, bool),
    /// Its restitution is not zero.
    bounces: bool,
}

impl SolvedContact {
    /// A place the solver leaves out.
    const LEFT_OUT: SolvedContact =
        SolvedContact { place: u32::MAX, bodies: (0, 0), moving: (false, false), bounces: false };
}

/// What the solver's serial stages and the contacts' set-up ask of a body slot, beside its solver
/// body: a few bytes per body in slot order, where reading the world's bodies for them missed the
/// cache on two bodies of some hundred bytes per contact.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SlotSummary {
    /// The slot holds a body.
    exists: bool,
    /// It takes impulses (`inv_mass != 0`).
    movable: bool,
    /// It is dynamic and awake (`SolverBody::is_dynamic`).
    dynamic: bool,
    /// It moves in the position stage (`SolverBody::moves`).
    moves: bool,
    /// The radius of its shape's round side (`RoundSide`).
    round: RoundSide,
    /// Its centre of mass at the step start, world frame.
    com_world: DVec3,
}

/// The radius of the round side a body's contacts lie on (a sphere's, a capsule's; 0 on corners,
/// edges and faces: `PointConstraint::anchors` in contact_solver.rs), by body where its shape is
/// one leaf; a compound's depends on the contact's child.
#[derive(Clone, Copy, Debug, PartialEq)]
enum RoundSide {
    Radius(f64),
    ByChild,
}

impl Default for RoundSide {
    fn default() -> Self {
        RoundSide::Radius(0.0)
    }
}

/// What the write-back found for a body slot.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct WrittenBack {
    /// The body was written back with a non-finite state.
    non_finite: bool,
    /// What its proxies need at the step's end.
    pub proxies: ProxyPlan,
}

impl SlotSummary {
    /// The summary of a slot that holds `body` (if any), whose solver body is `solver_body`.
    fn of(solver_body: &SolverBody, body: Option<&Body>) -> SlotSummary {
        let round = match body.and_then(Body::shape) {
            Some(Shape::Compound(_)) => RoundSide::ByChild,
            Some(shape) => RoundSide::Radius(round_radius(shape)),
            None => RoundSide::Radius(0.0),
        };
        SlotSummary {
            exists: body.is_some(),
            movable: solver_body.inv_mass != 0.0,
            dynamic: solver_body.is_dynamic(),
            moves: solver_body.moves(),
            round,
            com_world: body.map_or(DVec3::ZERO, Body::com_world),
        }
    }

    /// The radius of the round side of the body's leaf `child`.
    #[inline]
    fn round_radius(&self, body: usize, child: u32, world_bodies: &SlotPool<Body>) -> f64 {
        match self.round {
            RoundSide::Radius(radius) => radius,
            RoundSide::ByChild => world_bodies
                .iter_slot(body)
                .and_then(Body::shape)
                .map_or(0.0, |shape| round_radius(leaf(shape, child).0)),
        }
    }
}

/// A leaf shape's round radius: a sphere's or capsule's, 0 for the others.
fn round_radius(leaf: &Shape) -> f64 {
    match leaf {
        Shape::Sphere(s) => s.radius,
        Shape::Capsule(c) => c.radius,
        _ => 0.0,
    }
}

/// Whether the solver takes a contact: touching, not a sensor, with a body that can move.
fn takes_part(contact: &Contact, summaries: &[SlotSummary]) -> bool {
    let (a, b) = (&summaries[contact.body_a.index()], &summaries[contact.body_b.index()]);
    // The manifold last: of a contact apart, only its head (`Contact::prefetch_head`) is read.
    contact.touching
        && !contact.sensor
        && (a.movable || b.movable)
        && a.exists
        && b.exists
        && contact.manifold.is_some()
}

/// A contact's manifold points with their impulses, as the solver's rows are prepared from them.
struct ManifoldInputs<'a> {
    points: &'a [ContactPoint],
    impulses: &'a [ContactImpulse; 4],
}

impl PointInputs for ManifoldInputs<'_> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.points.len()
    }

    #[inline(always)]
    fn get(&self, i: usize) -> ContactPointInput {
        let point = &self.points[i];
        ContactPointInput {
            point_world: point.point_world,
            separation: point.separation,
            impulse: self.impulses[i],
        }
    }
}

/// The solver's rows of one contact that `takes_part`, written over `constraint`.
fn prepare_contact(
    constraint: &mut ContactConstraint,
    contact: &Contact,
    bodies: &[SolverBody],
    summaries: &[SlotSummary],
    world_bodies: &SlotPool<Body>,
    ctx: &StepContext,
) {
    let (ia, ib) = (contact.body_a.index(), contact.body_b.index());
    let Some(manifold) = contact.manifold.as_ref() else { unreachable!("takes_part checked the manifold") };
    let (a, b) = (&summaries[ia], &summaries[ib]);
    // Round sides (spheres, capsules) keep their contact at the bottom as they roll.
    let radii = (
        a.round_radius(ia, contact.child_a, world_bodies),
        b.round_radius(ib, contact.child_b, world_bodies),
    );
    constraint.prepare_in_place(
        (ia, ib),
        (&bodies[ia], &bodies[ib]),
        (a.com_world, b.com_world),
        radii,
        manifold.normal_world,
        ManifoldInputs { points: manifold.points(), impulses: &contact.impulses },
        contact.material,
        ctx,
    );
}
