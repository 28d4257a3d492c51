//! Islands and sleep.
//!
//! An island is a set of dynamic bodies linked by joints and touching contacts: they can only come
//! to rest together. After each step, bodies slower than the sleep thresholds accumulate "sleep
//! time"; an island whose every body has rested for `time_to_sleep` falls asleep as a whole: its
//! velocities are zeroed and it is no longer simulated. Islands are built anew each step by a
//! union–find over the links in slot order (deterministic); a sleeping island keeps its identity
//! (the lowest slot among its bodies) so that touching any body in it wakes all of it.
//!
//! What wakes an island: a force, torque, impulse, velocity or pose set by the user on one of its
//! bodies; a joint added to it; an awake body touching it; a body or joint linked to it removed.

use crate::body::BodyKind;
use crate::id::BodyId;
use crate::world::World;

/// When bodies fall asleep.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SleepSettings {
    pub enabled: bool,
    /// Speed of the centre of mass below which a body counts as resting, m/s.
    pub linear_threshold: f64,
    /// Angular speed below which a body counts as resting, rad/s.
    pub angular_threshold: f64,
    /// How long every body of an island must rest before it sleeps, s.
    pub time_to_sleep: f64,
}

impl Default for SleepSettings {
    fn default() -> Self {
        Self { enabled: true, linear_threshold: 0.05, angular_threshold: 0.05, time_to_sleep: 0.5 }
    }
}

/// Union–find over body slots, with path halving and union by lower root (deterministic: the
/// root of a set is always its lowest slot). Works in a caller's buffer, so a step reuses it.
pub(crate) struct UnionFind<'a> {
    parent: &'a mut Vec<u32>,
}

impl<'a> UnionFind<'a> {
    pub fn new(n: usize, parent: &'a mut Vec<u32>) -> UnionFind<'a> {
        parent.clear();
        parent.extend(0..n as u32);
        UnionFind { parent }
    }

    pub fn find(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let grand = self.parent[self.parent[i as usize] as usize];
            self.parent[i as usize] = grand;
            i = grand;
        }
        i
    }

    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[hi as usize] = lo;
        }
    }
}

/// The island and sleep pass's working buffers, refilled every step (kept by the world so a
/// steady-state step allocates nothing).
#[derive(Clone, Debug, Default)]
pub(crate) struct IslandScratch {
    /// Body-slot pairs of unbroken joints.
    pub joint_links: Vec<(u32, u32)>,
    /// Sleeping islands to wake.
    pub to_wake: Vec<u32>,
    /// Union–find parents.
    pub parent: Vec<u32>,
    /// Shortest sleep time per island root.
    pub min_sleep: Vec<f64>,
    /// Body pairs joined by a joint that keeps them from colliding, lower id first, sorted (the
    /// broad phase's filter for new pairs).
    pub jointed_pairs: Vec<(BodyId, BodyId)>,
}

impl World {
    /// Wakes the body and the island it sleeps with. Waking an awake body only resets its timer.
    pub fn wake_body(&mut self, id: BodyId) -> Result<(), crate::world::WorldError> {
        let island = {
            let body = self.body_mut(id)?;
            body.sleep_time = 0.0;
            body.sleeping_island
        };
        if let Some(island) = island {
            self.wake_island(island);
        }
        Ok(())
    }

    /// Wakes every body sleeping in `island`.
    pub(crate) fn wake_island(&mut self, island: u32) {
        for (_, body) in self.bodies.iter_mut() {
            if body.sleeping_island == Some(island) {
                body.sleeping_island = None;
                body.sleep_time = 0.0;
            }
        }
    }

    /// Wakes the sleeping side of every link between an awake dynamic body and a sleeping one:
    /// the touching contacts' links (as the narrow phase listed them,
    /// `ContactManager::touching_links`) and the joints' (gathered here into `scratch.joint_links`).
    pub(crate) fn wake_islands_touched_by_awake_bodies(&mut self) {
        let mut scratch = std::mem::take(&mut self.scratch);
        self.gather_joint_links(&mut scratch.joint_links);
        scratch.to_wake.clear();
        for &(a, b) in self.contact_manager.touching_links().iter().chain(&scratch.joint_links) {
            let state =
                |i: u32| self.bodies.iter_slot(i as usize).map(|body| (body.kind, body.sleeping_island));
            if let (Some((ka, ia)), Some((kb, ib))) = (state(a), state(b)) {
                match (ia, ib) {
                    (None, Some(island)) if ka != BodyKind::Static => scratch.to_wake.push(island),
                    (Some(island), None) if kb != BodyKind::Static => scratch.to_wake.push(island),
                    _ => {}
                }
            }
        }
        scratch.to_wake.sort_unstable();
        scratch.to_wake.dedup();
        for &island in &scratch.to_wake {
            self.wake_island(island);
        }
        self.scratch = scratch;
    }

    fn gather_joint_links(&self, links: &mut Vec<(u32, u32)>) {
        links.clear();
        links.extend(
            self.joints
                .iter()
                .filter(|(_, j)| !j.broken)
                .map(|(_, j)| (j.body_a.index() as u32, j.body_b.index() as u32)),
        );
    }

    /// After a step of `dt`: advance sleep timers, build islands over joints and the touching
    /// contacts (`ContactManager::touching_links`), and put to sleep the islands that have rested long
    /// enough.
    pub(crate) fn update_sleep(&mut self, dt: f64) {
        let settings = self.sleep_settings.clone();
        let n = self.bodies.capacity_index();
        // Bodies that can never sleep keep their island awake: their timer stays at zero.
        for (_, body) in self.bodies.iter_mut() {
            if body.kind != BodyKind::Dynamic || body.sleeping_island.is_some() || body.isolated {
                continue;
            }
            let resting = body.state.linear_velocity.length() < settings.linear_threshold
                && body.state.angular_velocity.length() < settings.angular_threshold;
            body.sleep_time =
                if resting && body.allow_sleep && settings.enabled { body.sleep_time + dt } else { 0.0 };
        }
        if !settings.enabled {
            return;
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        // The joints may have changed (broken) in the solve since the wake pass gathered them.
        self.gather_joint_links(&mut scratch.joint_links);
        let mut sets = UnionFind::new(n, &mut scratch.parent);
        let is_linkable = |world: &World, i: u32| {
            world
                .bodies
                .iter_slot(i as usize)
                .is_some_and(|b| b.kind == BodyKind::Dynamic && b.sleeping_island.is_none() && !b.isolated)
        };
        for &(a, b) in self.contact_manager.touching_links().iter().chain(&scratch.joint_links) {
            if is_linkable(self, a) && is_linkable(self, b) {
                sets.union(a, b);
            }
        }
        // The shortest rest in each island decides.
        let min_sleep = &mut scratch.min_sleep;
        min_sleep.clear();
        min_sleep.resize(n, f64::INFINITY);
        for (id, body) in self.bodies.iter() {
            if body.kind == BodyKind::Dynamic && body.sleeping_island.is_none() && !body.isolated {
                let root = sets.find(id.index() as u32) as usize;
                min_sleep[root] = min_sleep[root].min(body.sleep_time);
            }
        }
        for (id, body) in self.bodies.iter_mut() {
            if body.kind == BodyKind::Dynamic && body.sleeping_island.is_none() && !body.isolated {
                let root = sets.find(id.index() as u32);
                if min_sleep[root as usize] >= settings.time_to_sleep {
                    body.sleeping_island = Some(root);
                    body.state.linear_velocity = crate::math::DVec3::ZERO;
                    body.state.angular_velocity = crate::math::DVec3::ZERO;
                }
            }
        }
        self.scratch = scratch;
    }

    /// Number of dynamic bodies awake (isolated ones, `non_finite.rs`, are not simulated at all).
    pub fn awake_body_count(&self) -> usize {
        self.bodies
            .iter()
            .filter(|(_, b)| b.kind == BodyKind::Dynamic && b.sleeping_island.is_none() && !b.isolated)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_find_roots_are_lowest_slots() {
        let mut parent = Vec::new();
        let mut uf = UnionFind::new(6, &mut parent);
        uf.union(4, 2);
        uf.union(5, 4);
        uf.union(1, 3);
        assert_eq!(uf.find(5), 2);
        assert_eq!(uf.find(3), 1);
        assert_eq!(uf.find(0), 0);
    }
}
