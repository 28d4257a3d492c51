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
use crate::id::{BodyId, RawId};
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
/// root of a set is always its lowest slot).
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub fn new(n: usize) -> UnionFind {
        UnionFind { parent: (0..n as u32).collect() }
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

    /// Wakes the sleeping side of every link between an awake dynamic body and a sleeping one.
    /// `links` are pairs of body slots (joints are added here).
    pub(crate) fn wake_islands_touched_by_awake_bodies(&mut self, links: &[(u32, u32)]) {
        let mut to_wake = Vec::new();
        let joint_links: Vec<(u32, u32)> = self.joint_links();
        for &(a, b) in links.iter().chain(&joint_links) {
            let state =
                |i: u32| self.bodies.iter_slot(i as usize).map(|body| (body.kind, body.sleeping_island));
            if let (Some((ka, ia)), Some((kb, ib))) = (state(a), state(b)) {
                match (ia, ib) {
                    (None, Some(island)) if ka != BodyKind::Static => to_wake.push(island),
                    (Some(island), None) if kb != BodyKind::Static => to_wake.push(island),
                    _ => {}
                }
            }
        }
        to_wake.sort_unstable();
        to_wake.dedup();
        for island in to_wake {
            self.wake_island(island);
        }
    }

    fn joint_links(&self) -> Vec<(u32, u32)> {
        self.joints
            .iter()
            .filter(|(_, j)| !j.broken)
            .map(|(_, j)| (j.body_a.index() as u32, j.body_b.index() as u32))
            .collect()
    }

    /// After a step of `dt`: advance sleep timers, build islands over joints and the touching
    /// `contact_links`, and put to sleep the islands that have rested long enough.
    pub(crate) fn update_sleep(&mut self, dt: f64, contact_links: &[(u32, u32)]) {
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
        let mut sets = UnionFind::new(n);
        let is_linkable = |world: &World, i: u32| {
            world
                .bodies
                .iter_slot(i as usize)
                .is_some_and(|b| b.kind == BodyKind::Dynamic && b.sleeping_island.is_none() && !b.isolated)
        };
        for &(a, b) in contact_links.iter().chain(&self.joint_links()) {
            if is_linkable(self, a) && is_linkable(self, b) {
                sets.union(a, b);
            }
        }
        // The shortest rest in each island decides.
        let mut min_sleep = vec![f64::INFINITY; n];
        for (id, body) in self.bodies.iter() {
            if body.kind == BodyKind::Dynamic && body.sleeping_island.is_none() && !body.isolated {
                let root = sets.find(id.index() as u32) as usize;
                min_sleep[root] = min_sleep[root].min(body.sleep_time);
            }
        }
        let ids: Vec<RawId> = self.bodies.iter().map(|(id, _)| id).collect();
        for id in ids {
            let root = sets.find(id.index() as u32);
            let body = self.bodies.get_mut(id).expect("listed just above");
            if body.kind == BodyKind::Dynamic
                && body.sleeping_island.is_none()
                && !body.isolated
                && min_sleep[root as usize] >= settings.time_to_sleep
            {
                body.sleeping_island = Some(root);
                body.state.linear_velocity = crate::math::DVec3::ZERO;
                body.state.angular_velocity = crate::math::DVec3::ZERO;
            }
        }
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
        let mut uf = UnionFind::new(6);
        uf.union(4, 2);
        uf.union(5, 4);
        uf.union(1, 3);
        assert_eq!(uf.find(5), 2);
        assert_eq!(uf.find(3), 1);
        assert_eq!(uf.find(0), 0);
    }
}
