//! Contact and sensor events: which pairs of bodies began or stopped touching in the last step.
//!
//! A pair of bodies is *on* while at least one of its contacts (one per pair of leaf shapes, so a
//! compound can have several with one body) is on:
//! - a **contact** (neither body a sensor) is on while it is `touching`: its manifold has points,
//!   which includes speculative points up to a few centimetres before the surfaces meet — the
//!   same test as [`World::contacts`] and [`World::contact_count`];
//! - a **sensor** pair (either body a sensor) is on while the shapes really overlap: some
//!   manifold point has separation ≤ 0. Sensors make no force, so "about to touch" means nothing
//!   for them.
//!
//! The narrow phase records every change of a contact's state (and every contact dropped because
//! the fat boxes parted or a body was removed); at the end of the narrow phase the changes are
//! summed per body pair, and a pair that went from off to on gives a *begin* event, one that went
//! from on to off an *end* event. The lists are replaced each step; a body removed between steps
//! gives its end events in the next step (naming the removed, now stale, id).
//!
//! Timing: the narrow phase runs at the start of the step, before the solve, so a step's events
//! describe the poses it started from (the poses the previous step ended with) — as in Box2D.
//!
//! Order: each list holds `(a, b)` with `a < b` (by slot index, then generation), sorted, each pair
//! once — a pure function of the world state, so the same run gives the same events.

use crate::collision::contact_store::ContactStore;
use crate::dynamics::contact::Contact;
use crate::id::BodyId;
use crate::world::World;

/// A pair of bodies, the lower id first.
pub type BodyPair = (BodyId, BodyId);

/// One recorded change of one contact: +1 turned on, −1 turned off.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
struct Transition {
    pair: BodyPair,
    sensor: bool,
    delta: i32,
    /// The contact is its pair's only one (`Contact::only_one_of_pair`).
    only_one: bool,
}

/// Records contact state changes during a step and turns them into per-pair events.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct EventRecorder {
    transitions: Vec<Transition>,
    contact_begin: Vec<BodyPair>,
    contact_end: Vec<BodyPair>,
    sensor_begin: Vec<BodyPair>,
    sensor_end: Vec<BodyPair>,
    /// Per-pair sums of the transitions, rebuilt by `finish` (kept to reuse the allocation).
    #[serde(skip)]
    net: Vec<NetChange>,
}

/// A body pair's net change of touching contacts over the step, and how many touch now.
#[derive(Clone, Copy, Debug)]
struct NetChange {
    pair: BodyPair,
    sensor: bool,
    delta: i32,
    on_now: i32,
    /// Every transition of the pair came from its only contact.
    only_one: bool,
}

fn ordered_pair(contact: &Contact) -> BodyPair {
    (contact.body_a.min(contact.body_b), contact.body_a.max(contact.body_b))
}

impl EventRecorder {
    /// Whether a contact is on (see the module docs).
    pub fn state(contact: &Contact) -> bool {
        if contact.sensor {
            contact.manifold.as_ref().is_some_and(|m| !m.is_empty() && m.min_separation() <= 0.0)
        } else {
            contact.touching
        }
    }

    /// Records the change of `contact` since its state was `before`.
    pub fn record(&mut self, contact: &Contact, before: bool) {
        let after = Self::state(contact);
        if before != after {
            let delta = if after { 1 } else { -1 };
            self.transitions.push(Transition {
                pair: ordered_pair(contact),
                sensor: contact.sensor,
                delta,
                only_one: contact.only_one_of_pair,
            });
        }
    }

    /// Records that `contact` is being dropped.
    pub fn record_removed(&mut self, contact: &Contact) {
        if Self::state(contact) {
            self.transitions.push(Transition {
                pair: ordered_pair(contact),
                sensor: contact.sensor,
                delta: -1,
                only_one: contact.only_one_of_pair,
            });
        }
    }

    /// Replaces the event lists with the changes recorded since the last call. `contacts` is the
    /// current set, from which the number of contacts still on per pair is counted.
    pub fn finish(&mut self, contacts: &ContactStore) {
        for list in
            [&mut self.contact_begin, &mut self.contact_end, &mut self.sensor_begin, &mut self.sensor_end]
        {
            list.clear();
        }
        if self.transitions.is_empty() {
            return;
        }
        // Net change per pair, and whether the pair is a sensor pair (a body-level property, so
        // every contact of a pair agrees); sorted by pair, in a buffer kept between steps.
        self.transitions.sort_unstable_by_key(|t| t.pair);
        let net = &mut self.net;
        net.clear();
        for t in self.transitions.drain(..) {
            match net.last_mut() {
                Some(last) if last.pair == t.pair => {
                    last.delta += t.delta;
                    last.only_one &= t.only_one;
                }
                _ => net.push(NetChange {
                    pair: t.pair,
                    sensor: t.sensor,
                    delta: t.delta,
                    on_now: 0,
                    only_one: t.only_one,
                }),
            }
        }
        if net.iter().all(|n| n.only_one) {
            // A pair's only contact went from off to on (+1), on to off (−1), or back (0): the
            // net change says it all, and the contacts need not be counted.
            for n in net.iter_mut() {
                n.on_now = n.delta.max(0);
            }
        } else {
            for contact in contacts.iter() {
                if Self::state(contact) {
                    if let Ok(i) = net.binary_search_by_key(&ordered_pair(contact), |n| n.pair) {
                        net[i].on_now += 1;
                    }
                }
            }
        }
        for n in net.iter() {
            let (after, before) = (n.on_now, n.on_now - n.delta);
            let (begin, end) = if n.sensor {
                (&mut self.sensor_begin, &mut self.sensor_end)
            } else {
                (&mut self.contact_begin, &mut self.contact_end)
            };
            if before <= 0 && after > 0 {
                begin.push(n.pair);
            } else if before > 0 && after <= 0 {
                end.push(n.pair);
            }
        }
    }
}

impl World {
    /// Pairs of non-sensor bodies that began touching in the last step.
    pub fn contact_begin_events(&self) -> &[BodyPair] {
        &self.contact_manager.events.contact_begin
    }

    /// Pairs of non-sensor bodies that stopped touching in the last step (or since: removed bodies).
    pub fn contact_end_events(&self) -> &[BodyPair] {
        &self.contact_manager.events.contact_end
    }

    /// Pairs (sensor, other body) whose shapes began to overlap in the last step; either member may
    /// be the sensor (the pair is ordered by id).
    pub fn sensor_begin_events(&self) -> &[BodyPair] {
        &self.contact_manager.events.sensor_begin
    }

    /// Pairs (sensor, other body) whose shapes stopped overlapping in the last step.
    pub fn sensor_end_events(&self) -> &[BodyPair] {
        &self.contact_manager.events.sensor_end
    }
}
