//! The contact manager: keeps the broad phase's proxies in step with the bodies, turns candidate
//! pairs into persistent contacts, and updates every contact's manifold (pipeline steps 2–3).
//!
//! Each leaf shape of a body (the shape itself, or each child of a compound) has one proxy. A
//! proxy's payload packs the body slot and the leaf index. Contacts are kept in a
//! `ContactStore` (contact_store.rs), in the order they were made, so they are visited in the
//! same order on every run.

use super::aabb::{shape_aabb, Aabb};
use super::broad_phase::{BroadPhase, ProxyKey, ProxyKind, ProxyUpdate};
use super::contact_store::{prefetch_ahead, prefetch_start, ContactStore, Reach};
use super::manifold_reuse::{is_flat_sided, ManifoldOrigin};
use super::narrow_phase::collide;
use super::support::Rounded;
use crate::body::{Body, BodyKind};
use crate::dynamics::contact::Contact;
use crate::dynamics::contact_solver::ContactMaterial;
use crate::dynamics::material::Material;
use crate::events::EventRecorder;
use crate::id::{BodyId, SlotPool};
use crate::math::{DVec3, Transform};
use crate::shape::Shape;
use crate::step_threads::{for_each_chunk_of, StepThreads};

/// The base speculative distance, m: contacts are made this far before touching (plus the
/// distance the pair closes within the step).
pub const SPECULATIVE_DISTANCE: f64 = 0.02;

/// The leaf shapes of a body's shape with their poses in the body frame.
pub(crate) fn leaves(shape: &Shape) -> Vec<(&Shape, Transform)> {
    match shape {
        Shape::Compound(c) => c.children().iter().map(|child| (&child.shape, child.pose)).collect(),
        other => vec![(other, Transform::IDENTITY)],
    }
}

/// The leaf `child` of a body's shape, with its pose in the body frame.
pub(crate) fn leaf(shape: &Shape, child: u32) -> (&Shape, Transform) {
    match shape {
        Shape::Compound(c) => {
            let child = &c.children()[child as usize];
            (&child.shape, child.pose)
        }
        other => (other, Transform::IDENTITY),
    }
}

/// The pose of a leaf whose pose in the body is `local` ([`leaf`]), for the body at `body_pose`:
/// a leaf at the identity (the body's own shape) sits at the body's pose itself. (The product
/// with the identity would only renormalise the rotation, changing its last bits: in the narrow
/// phase a rain of 2,000 balls ran 1.12x without it, with the same bits, as a ball's contacts do
/// not read its rotation.) The narrow phase, the proxies' boxes and the queries all place leaves
/// by this one rule.
pub(crate) fn leaf_pose(body_pose: Transform, local: &Transform) -> Transform {
    if *local == Transform::IDENTITY {
        body_pose
    } else {
        body_pose.mul_transform(local)
    }
}

/// The leaf `child` of a body's shape and its pose for the body at `body_pose`: [`leaf`] and
/// [`leaf_pose`] in one, with the body's own shape (not a compound) placed at `body_pose` without
/// comparing its identity pose with the identity, float by float (the same pose either way; the
/// comparison was a percent or two of the rain's instructions, in the step's two hottest loops
/// over leaves).
#[inline]
pub(crate) fn placed_leaf(shape: &Shape, child: u32, body_pose: Transform) -> (&Shape, Transform) {
    match shape {
        Shape::Compound(_) => {
            let (leaf_shape, local) = leaf(shape, child);
            (leaf_shape, leaf_pose(body_pose, &local))
        }
        other => (other, body_pose),
    }
}

fn pack(body_slot: usize, child: usize) -> u64 {
    ((body_slot as u64) << 32) | child as u64
}

/// A proxy's payload as (body slot, leaf index).
pub(crate) fn unpack(data: u64) -> (usize, u32) {
    ((data >> 32) as usize, data as u32)
}

/// Contacts handed to one task of the threaded narrow phase: the store split into about
/// [`NARROW_PHASE_TASKS`] chunks of at least [`NARROW_PHASE_CHUNK`] and at most
/// [`NARROW_PHASE_CHUNK_MAX`] contacts. The split follows the scene (its number of contacts),
/// never the thread count. Chunks of 32 whatever the store cost the rain's 12,600 contacts a
/// sixth of the threaded walk's time over chunks of 512 (a task per chunk, and each starting its
/// own run of memory); tasks of a pile of hulls, whose pairs differ in cost by microseconds,
/// balance between the threads better when there are a few dozen of them.
fn narrow_phase_chunk(places: usize) -> usize {
    (places / NARROW_PHASE_TASKS).clamp(NARROW_PHASE_CHUNK, NARROW_PHASE_CHUNK_MAX)
}
const NARROW_PHASE_CHUNK: usize = 32;
const NARROW_PHASE_CHUNK_MAX: usize = 512;
const NARROW_PHASE_TASKS: usize = 32;

/// Chunks of work below which a phase runs on the calling thread.
const MIN_SHARED_CHUNKS: usize = 4;

#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct ContactManager {
    pub broad_phase: BroadPhase,
    pub contacts: ContactStore,
    /// Begin/end transitions of contacts and sensor overlaps (`events.rs`).
    pub events: EventRecorder,
    /// The broad phase's new pairs, refilled each step (kept to reuse the allocation).
    #[serde(skip)]
    new_pairs: Vec<(ProxyKey, ProxyKey)>,
    /// The contacts to make for the new pairs that may collide, refilled each step.
    #[serde(skip)]
    new_contacts: Vec<NewContact>,
    /// What the threaded narrow phase found in each chunk of contacts, in contact order.
    #[serde(skip)]
    chunk_outcomes: Vec<ChunkOutcome>,
    /// The island links of the contacts, found by the narrow phase (`touching_links`).
    #[serde(skip)]
    links: Vec<(u32, u32)>,
}

/// What a new contact is made from (`Contact::new`'s arguments).
#[derive(Clone, Debug)]
struct NewContact {
    proxies: (ProxyKey, ProxyKey),
    bodies: (BodyId, BodyId),
    children: (u32, u32),
    material: ContactMaterial,
    sensor: bool,
    only_one_of_pair: bool,
}

/// What one chunk of the threaded narrow phase found: its contacts' island links and the few
/// contacts that parted or changed their event state, each in contact order. The step's thread
/// then reads these short lists, not an outcome per contact: a walk over 12,600 per-contact
/// outcomes written on the other threads was 90 µs of the rain's serial narrow phase.
#[derive(Clone, Debug, Default)]
struct ChunkOutcome {
    links: Vec<(u32, u32)>,
    changes: Vec<Change>,
}

/// A contact of a chunk that parted (`kept` false) or changed its event state from `before`.
#[derive(Clone, Copy, Debug)]
struct Change {
    place: usize,
    kept: bool,
    before: bool,
}

/// The link a contact makes between the islands of its bodies, as their slots: touching, not a
/// sensor, between two dynamic bodies.
fn island_link(contact: &Contact, a: &Body, b: &Body) -> Option<(u32, u32)> {
    let linked =
        contact.touching && !contact.sensor && a.kind == BodyKind::Dynamic && b.kind == BodyKind::Dynamic;
    linked.then(|| (contact.body_a.index() as u32, contact.body_b.index() as u32))
}

impl ContactManager {
    /// Creates the proxies of a body's leaf shapes.
    pub fn add_body(&mut self, slot: usize, body: &mut Body) {
        let Some(shape) = &body.shape else { return };
        let kind = if body.kind == BodyKind::Static { ProxyKind::Static } else { ProxyKind::Dynamic };
        let pose = body.transform();
        body.proxies = leaves(shape)
            .into_iter()
            .enumerate()
            .map(|(i, (leaf, local))| {
                self.broad_phase.create_proxy(shape_aabb(leaf, &leaf_pose(pose, &local)), kind, pack(slot, i))
            })
            .collect();
    }

    /// Destroys a body's proxies and every contact that involves them.
    pub fn remove_body(&mut self, body: &Body) {
        for &key in &body.proxies {
            self.broad_phase.destroy_proxy(key);
        }
        let events = &mut self.events;
        self.contacts.retain(|contact| {
            let keep = !body.proxies.contains(&contact.proxy_a) && !body.proxies.contains(&contact.proxy_b);
            if !keep {
                events.record_removed(contact);
            }
            keep
        });
    }

    /// Moves the proxies of awake, non-static bodies to their current poses; the fat boxes are
    /// stretched by the distance the body will travel in the next step. On the calling thread:
    /// the tree updates, which must run one after the other, are most of the work (computing the
    /// 2,000 balls' boxes on two threads and then moving them in the tree took 227 µs a step, all
    /// on one thread 173 µs).
    pub fn update_proxies(&mut self, bodies: &SlotPool<Body>, dt: f64) {
        for (_, body) in bodies.iter() {
            if body.kind != BodyKind::Static && body.is_awake() {
                self.move_body_proxies(body, dt);
            }
        }
    }

    /// Moves the proxies of awake, non-static bodies as the solver's write-back planned them
    /// (`plans` in slot order, one per slot, see [`ProxyPlan`]): the same tree operations in the
    /// same order as [`ContactManager::update_proxies`], hence the same tree, but the boxes and
    /// the fat-box tests were worked out beside each body's write-back, on the threads and while
    /// the body was in cache. Here, on one thread, only the re-insertions are left, and the
    /// bodies planned for later. (Without plans for every slot, as after a body was added, it
    /// is `update_proxies`.)
    pub fn move_proxies_as_planned(
        &mut self,
        bodies: &SlotPool<Body>,
        plans: impl ExactSizeIterator<Item = ProxyPlan>,
        dt: f64,
    ) {
        if plans.len() != bodies.capacity_index() {
            self.update_proxies(bodies, dt);
            return;
        }
        for (slot, plan) in plans.enumerate() {
            match plan {
                ProxyPlan::Stay => {}
                ProxyPlan::Move(update) => self.broad_phase.reinsert(&update),
                ProxyPlan::Later => {
                    if let Some(body) = bodies.iter_slot(slot) {
                        if body.kind != BodyKind::Static && body.is_awake() {
                            self.move_body_proxies(body, dt);
                        }
                    }
                }
            }
        }
    }

    /// Moves one body's proxies to its current pose (any kind: a static body moved by the user
    /// too), fat boxes stretched by its velocity times `dt`.
    pub fn move_body_proxies(&mut self, body: &Body, dt: f64) {
        for m in proxy_updates(body, dt, self.broad_phase.margin()) {
            self.broad_phase.move_proxy(m.key, m.aabb, m.displacement);
        }
    }

    /// Creates contacts for new candidate pairs that may collide.
    /// The broad phase's queries run on `threads` when many proxies moved.
    pub fn find_new_contacts(
        &mut self,
        bodies: &SlotPool<Body>,
        joined: impl Fn(BodyId, BodyId) -> bool,
        threads: Option<&StepThreads>,
    ) {
        let mut new_pairs = std::mem::take(&mut self.new_pairs);
        // Only the pairs without a contact yet, and room for them at once (a first step that
        // makes thousands of contacts then moves them once, not at every doubling).
        let contacts = &self.contacts;
        self.broad_phase.find_new_pairs_on(&mut new_pairs, threads, |pair| contacts.contains(pair));
        let mut new_contacts = std::mem::take(&mut self.new_contacts);
        new_contacts.clear();
        for &(key_a, key_b) in &new_pairs {
            let (slot_a, child_a) = unpack(self.broad_phase.user_data(key_a));
            let (slot_b, child_b) = unpack(self.broad_phase.user_data(key_b));
            if slot_a == slot_b {
                continue;
            }
            let (Some((id_a, a)), Some((id_b, b))) = (slot_body(bodies, slot_a), slot_body(bodies, slot_b))
            else {
                continue;
            };
            if a.kind != BodyKind::Dynamic && b.kind != BodyKind::Dynamic {
                continue;
            }
            if !a.filter.accepts(&b.filter) || joined(id_a, id_b) {
                continue;
            }
            new_contacts.push(NewContact {
                proxies: (key_a, key_b),
                bodies: (id_a, id_b),
                children: (child_a, child_b),
                material: Material::combine(&a.material, &b.material),
                sensor: a.is_sensor || b.is_sensor,
                only_one_of_pair: a.proxies.len() == 1 && b.proxies.len() == 1,
            });
        }
        // The contacts themselves (a kilobyte each) written on the threads: a pile's first step
        // makes thousands (`extend_on_threads`).
        self.contacts.extend_on_threads(
            &new_contacts,
            |n| n.proxies,
            |n| Contact::new(n.proxies, n.bodies, n.children, n.material, n.sensor, n.only_one_of_pair),
            threads,
        );
        self.new_pairs = new_pairs;
        self.new_contacts = new_contacts;
    }

    /// Updates every contact: drops those whose fat boxes parted, recomputes the manifolds of the
    /// rest (where a body is awake). `dt` sizes the speculative margin. With `threads`, the
    /// manifolds are computed in chunks of contacts on them (`narrow_phase_chunk`): each
    /// contact's update reads only the two bodies and writes only the contact, so the result is
    /// the same bits in any split; events are recorded afterwards in contact order.
    pub fn update_contacts(&mut self, bodies: &SlotPool<Body>, dt: f64, threads: Option<&StepThreads>) {
        let (broad_phase, events) = (&self.broad_phase, &mut self.events);
        // A contact is kept while its fat boxes overlap and both bodies exist.
        let kept = |contact: &Contact| -> Option<(&Body, &Body)> {
            let overlap =
                broad_phase.fat_aabb(contact.proxy_a).overlaps(&broad_phase.fat_aabb(contact.proxy_b));
            let a = bodies.get(contact.body_a.into())?;
            let b = bodies.get(contact.body_b.into())?;
            overlap.then_some((a, b))
        };
        // Threads only for enough contacts to share (the result is the same either way): for a
        // chain's few contacts they cost more than the work.
        let Some(threads) =
            threads.filter(|_| self.contacts.places() >= MIN_SHARED_CHUNKS * NARROW_PHASE_CHUNK)
        else {
            // On one thread: drop, update, record and link in a single walk over the contacts.
            let links = &mut self.links;
            links.clear();
            self.contacts.retain(|contact| {
                let Some((a, b)) = kept(contact) else {
                    events.record_removed(contact);
                    return false;
                };
                if a.is_awake() || b.is_awake() {
                    let before = EventRecorder::state(contact);
                    update_manifold(contact, a, b, dt);
                    events.record(contact, before);
                }
                links.extend(island_link(contact, a, b));
                true
            });
            self.events.finish(&self.contacts);
            return;
        };
        // On the threads: whether each contact is kept, and its event state before and after its
        // update; then, on this thread, drop the parted contacts and record the changes in
        // contact order (the chunks' short lists, in chunk order).
        let places = self.contacts.places();
        let chunk_outcomes = &mut self.chunk_outcomes;
        let chunk_size = narrow_phase_chunk(places);
        chunk_outcomes.resize_with(places.div_ceil(chunk_size), ChunkOutcome::default);
        let mut jobs: Vec<_> =
            self.contacts.as_mut_slice().chunks_mut(chunk_size).zip(chunk_outcomes.iter_mut()).collect();
        for_each_chunk_of(Some(threads), &mut jobs, 1, |offset, jobs| {
            for (index, (chunk, outcome)) in jobs.iter_mut().enumerate() {
                outcome.links.clear();
                outcome.changes.clear();
                let first = (offset + index) * chunk_size;
                prefetch_start(chunk, Reach::Whole);
                for place in first..first + chunk.len() {
                    prefetch_ahead(chunk, place - first, Reach::Whole);
                    let contact = &mut chunk[place - first];
                    if contact.dropped {
                        continue; // its proxies may be gone
                    }
                    let before = EventRecorder::state(contact);
                    let Some((a, b)) = kept(contact) else {
                        outcome.changes.push(Change { place, kept: false, before });
                        continue;
                    };
                    if a.is_awake() || b.is_awake() {
                        update_manifold(contact, a, b, dt);
                    }
                    if EventRecorder::state(contact) != before {
                        outcome.changes.push(Change { place, kept: true, before });
                    }
                    outcome.links.extend(island_link(contact, a, b));
                }
            }
        });
        self.links.clear();
        for outcome in &self.chunk_outcomes {
            self.links.extend_from_slice(&outcome.links);
            for change in &outcome.changes {
                let contact = &self.contacts.as_slice()[change.place];
                if change.kept {
                    events.record(contact, change.before);
                } else {
                    events.record_removed(contact);
                    self.contacts.drop_at(change.place);
                }
            }
        }
        self.contacts.compact_if_sparse();
        self.events.finish(&self.contacts);
    }

    /// Body-slot pairs of touching, non-sensor contacts between two dynamic bodies (island links),
    /// in contact order, as the last [`ContactManager::update_contacts`] found them: its walk has
    /// both bodies at hand (a second walk over the contacts and their bodies for the links was
    /// most of the rain's wake phase).
    pub fn touching_links(&self) -> &[(u32, u32)] {
        &self.links
    }
}

/// What a body's proxies need at the end of the step, as the solver's write-back found it
/// ([`plan_proxies`]); carried out by [`ContactManager::move_proxies_as_planned`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) enum ProxyPlan {
    /// Nothing: no proxy, a static or sleeping body, or a fat box that still holds.
    #[default]
    Stay,
    /// Its one proxy left its fat box: re-insert it with this box.
    Move(ProxyUpdate),
    /// Left to the finalize stage: a body of several leaves (compound), a bullet (the continuous
    /// stage may still move it back), or one whose state came back non-finite.
    Later,
}

/// The plan for an awake body's proxies at its pose just written back by the solver. Reads the
/// body and its own fat box only, so bodies are planned on any thread in any order.
pub(crate) fn plan_proxies(broad_phase: &BroadPhase, body: &Body, dt: f64) -> ProxyPlan {
    if body.kind == BodyKind::Static || body.proxies.is_empty() {
        return ProxyPlan::Stay;
    }
    if body.bullet || body.proxies.len() != 1 {
        return ProxyPlan::Later;
    }
    match proxy_updates(body, dt, broad_phase.margin()).next() {
        Some(update) if broad_phase.needs_move(&update) => ProxyPlan::Move(update),
        Some(_) => ProxyPlan::Stay,
        None => ProxyPlan::Later,
    }
}

/// A body's proxies with their boxes at its current pose and its displacement over `dt`.
///
/// The box is the tight one, except for a body spinning fast enough that its tight box would
/// outgrow the fat box's `margin` within a few steps (a far corner moving more than a quarter of
/// the margin per step): that proxy gets the box of the ball about the centre of mass that the
/// shape turns in. It does not change as the body turns, so the proxy stays in the tree; with the
/// tight box, a tumbling box was re-inserted every few steps.
fn proxy_updates(body: &Body, dt: f64, margin: f64) -> impl Iterator<Item = ProxyUpdate> + '_ {
    let pose = body.transform();
    let displacement = body.state.linear_velocity * dt;
    let turn = body.state.angular_velocity.length() * dt;
    let com = body.com_world();
    body.shape.iter().flat_map(move |shape| {
        body.proxies.iter().enumerate().map(move |(child, &key)| {
            let (leaf_shape, leaf_pose) = placed_leaf(shape, child as u32, pose);
            let tight = shape_aabb(leaf_shape, &leaf_pose);
            let aabb = match turning_ball(leaf_shape, &leaf_pose, com) {
                Some(radius) if turn * radius > 0.25 * margin => {
                    tight.union(&Aabb::from_center_half_extents(com, DVec3::splat(radius)))
                }
                _ => tight,
            };
            ProxyUpdate { key, aabb, displacement }
        })
    })
}

/// The radius of the ball about `com` (the body's centre of mass) that a convex leaf at
/// `leaf_pose` stays in however the body turns; `None` for shapes without one (planes, height
/// fields, static meshes).
fn turning_ball(shape: &Shape, leaf_pose: &Transform, com: DVec3) -> Option<f64> {
    let convex = Rounded::of(shape.moving_collision_shape())?;
    Some((leaf_pose.translation - com).length() + convex.bounding_radius())
}

fn slot_body(bodies: &SlotPool<Body>, slot: usize) -> Option<(BodyId, &Body)> {
    let id = bodies.id_of_slot(slot)?;
    Some((BodyId::from(id), bodies.get(id)?))
}

/// Runs the narrow phase for one contact at the bodies' current poses.
fn update_manifold(contact: &mut Contact, a: &Body, b: &Body, dt: f64) {
    let (Some(shape_a), Some(shape_b)) = (&a.shape, &b.shape) else {
        contact.set_manifold(None);
        return;
    };
    let (leaf_a, pose_a) = placed_leaf(shape_a, contact.child_a, a.transform());
    let (leaf_b, pose_b) = placed_leaf(shape_b, contact.child_b, b.transform());
    // A dynamic body's closed mesh collides through its convex hull.
    let moving = |body: &Body, shape| {
        if body.kind == BodyKind::Dynamic {
            Shape::moving_collision_shape(shape)
        } else {
            shape
        }
    };
    let (leaf_a, leaf_b) = (moving(a, leaf_a), moving(b, leaf_b));
    // A pair that has barely moved since its manifold was made keeps the manifold's points.
    if let (Some(origin), Some(manifold)) = (&contact.manifold_origin, &mut contact.manifold) {
        if origin.still_fits(&pose_a, &pose_b) {
            origin.remeasure(manifold, &pose_a, &pose_b);
            return;
        }
    }
    // Contacts within reach of this step's relative motion are made now, so the solver can stop
    // the bodies at the surface (speculative contact).
    // A point of the shape moves by at most |ω| times its distance from the centre of mass.
    let spin = |body: &Body, pose: &Transform, shape: &Shape| {
        let w = body.state.angular_velocity.length();
        if w == 0.0 {
            return 0.0;
        }
        let reach = turning_ball(shape, pose, body.com_world())
            .unwrap_or_else(|| shape_aabb(shape, pose).half_extents().length());
        w * reach
    };
    let closing = ((a.state.linear_velocity - b.state.linear_velocity).length()
        + spin(a, &pose_a, leaf_a)
        + spin(b, &pose_b, leaf_b))
        * dt;
    let margin = SPECULATIVE_DISTANCE + closing;
    let manifold = collide(leaf_a, &pose_a, leaf_b, &pose_b, margin, &mut contact.cache);
    contact.manifold_origin = match &manifold {
        Some(m) if !m.is_empty() && is_flat_sided(leaf_a) && is_flat_sided(leaf_b) => {
            Some(ManifoldOrigin::new(leaf_a, &pose_a, leaf_b, &pose_b, m))
        }
        _ => None,
    };
    contact.set_manifold(manifold);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodyDef;
    use crate::math::DQuat;
    use crate::shape::{Compound, CompoundChild, Cuboid, Plane, Sphere};
    use crate::world::World;

    /// Balls falling fast onto a floor (re-inserted most steps), tumbling compounds (several
    /// leaves: planned for later), bullets (the continuous stage moves them back after the
    /// write-back) and a kinematic box sweeping through.
    fn mixed_world(threads: usize) -> World {
        let mut world = World::new(Default::default()).expect("default settings");
        world.set_threads(threads).expect("threads");
        world
            .add_body(BodyDef {
                kind: BodyKind::Static,
                shape: Some(Shape::Plane(Plane::new(DVec3::Z, 0.0).expect("plane"))),
                ..Default::default()
            })
            .expect("floor");
        let ball = || Some(Shape::Sphere(Sphere::new(0.1).expect("ball")));
        for k in 0..300 {
            let (i, j, l) = ((k % 10) as f64, ((k / 10) % 10) as f64, (k / 100) as f64);
            world
                .add_body(BodyDef {
                    shape: ball(),
                    position: DVec3::new(0.3 * i, 0.3 * j, 1.0 + 0.3 * l),
                    linear_velocity: DVec3::new(0.0, 0.0, -8.0),
                    ..Default::default()
                })
                .expect("ball");
        }
        let child = |x: f64| CompoundChild {
            pose: Transform::new(DVec3::new(x, 0.0, 0.0), DQuat::IDENTITY),
            shape: Shape::Cuboid(Cuboid::new(DVec3::splat(0.1)).expect("cube")),
        };
        for k in 0..4 {
            world
                .add_body(BodyDef {
                    shape: Some(Shape::Compound(
                        Compound::new(vec![child(-0.2), child(0.2)]).expect("compound"),
                    )),
                    position: DVec3::new(-1.0, 0.6 * k as f64, 0.5),
                    angular_velocity: DVec3::new(3.0, 20.0, 1.0),
                    ..Default::default()
                })
                .expect("compound");
        }
        // Bullets: spinning sticks thrown at a 1 cm wall, whose ends sweep past it within a
        // step (tests/continuous.rs), so the continuous stage moves them back.
        world
            .add_body(BodyDef {
                kind: BodyKind::Static,
                shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.005, 5.0, 5.0)).expect("wall"))),
                position: DVec3::new(8.0, 0.0, 5.0),
                ..Default::default()
            })
            .expect("wall");
        for k in 0..10 {
            let phase = 0.07 * k as f64;
            world
                .add_body(BodyDef {
                    shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 0.01, 0.01)).expect("stick"))),
                    position: DVec3::new(4.0 - phase, -4.0 + 0.8 * k as f64, 6.0),
                    orientation: DQuat::from_rotation_z(3.0 * phase),
                    linear_velocity: DVec3::new(50.0, 0.0, 0.0),
                    angular_velocity: DVec3::new(0.0, 0.0, 90.0),
                    bullet: true,
                    ..Default::default()
                })
                .expect("bullet");
        }
        world
            .add_body(BodyDef {
                kind: BodyKind::Kinematic,
                shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.3)).expect("box"))),
                position: DVec3::new(-2.0, 1.5, 0.4),
                linear_velocity: DVec3::new(5.0, 0.0, 0.0),
                ..Default::default()
            })
            .expect("kinematic");
        world
    }

    /// The plans made beside the write-back move the proxies as the plain walk of the finalize
    /// stage ([`ContactManager::update_proxies`]) does: the same tree, node for node, after every
    /// step, on one thread and on two. And every awake body's fat boxes hold its shape where it
    /// ended the step.
    #[test]
    fn planned_proxy_moves_build_the_tree_the_plain_update_builds() {
        let dt = 1.0 / 60.0;
        for threads in [1, 2] {
            let mut world = mixed_world(threads);
            let mut plain = mixed_world(threads);
            plain.plain_proxy_update = true;
            let mut reinserted = 0;
            for step in 0..40 {
                world.step(dt).expect("step");
                plain.step(dt).expect("step");
                let tree = |w: &World| format!("{:?}", w.contact_manager.broad_phase);
                assert_eq!(tree(&world), tree(&plain), "{threads} threads, step {step}");
                reinserted +=
                    world.written_back.iter().filter(|w| matches!(w.proxies, ProxyPlan::Move(_))).count();
                for (_, body) in
                    world.bodies.iter().filter(|(_, b)| b.kind != BodyKind::Static && b.is_awake())
                {
                    for update in proxy_updates(body, dt, world.contact_manager.broad_phase.margin()) {
                        let fat = world.contact_manager.broad_phase.fat_aabb(update.key);
                        assert!(
                            fat.contains(&update.aabb),
                            "{threads} threads, step {step}: a fat box lost its shape"
                        );
                    }
                }
            }
            assert!(reinserted > 300, "{threads} threads: only {reinserted} planned re-insertions");
        }
    }
}
