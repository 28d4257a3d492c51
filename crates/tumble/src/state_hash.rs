//! `World::state_hash()`: a 64-bit fingerprint of everything that decides the world's future, for
//! checking determinism (same inputs and binary → same bits, whatever the thread count) and for
//! comparing a restored world with the original.
//!
//! The hash is FNV-1a over the exact bit patterns of: time and step count; every body's slot,
//! generation, kind, sleep state and timer, isolation, centre of mass, rotation and velocities, and pending
//! force and torque; every joint's slot, generation, broken flag and last constraint force and torque; every contact's body pair,
//! manifold points and warm-start impulses. FNV-1a is written out here (not `std`'s hasher, whose
//! algorithm may change between Rust releases) so hashes stay comparable across builds.

use crate::math::{DQuat, DVec3};
use crate::world::World;

/// FNV-1a, 64-bit.
pub(crate) struct Fnv64(pub(crate) u64);

impl Fnv64 {
    pub(crate) const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    pub(crate) fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(Self::PRIME);
        }
    }

    fn u64(&mut self, v: u64) {
        self.bytes(&v.to_le_bytes());
    }

    fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }

    fn vec(&mut self, v: DVec3) {
        self.f64(v.x);
        self.f64(v.y);
        self.f64(v.z);
    }

    fn quat(&mut self, q: DQuat) {
        self.f64(q.x);
        self.f64(q.y);
        self.f64(q.z);
        self.f64(q.w);
    }
}

impl World {
    /// A fingerprint of the world's state; equal hashes mean (with overwhelming probability)
    /// bit-identical states.
    pub fn state_hash(&self) -> u64 {
        let mut h = Fnv64(Fnv64::OFFSET);
        h.f64(self.time);
        h.u64(self.step_count);
        for (id, body) in self.bodies.iter() {
            h.u64(id.index() as u64);
            h.u64(u64::from(crate::id::BodyId::from(id).generation()));
            h.u64(body.kind as u64);
            h.u64(body.sleeping_island.map_or(u64::MAX, u64::from));
            h.u64(u64::from(body.isolated));
            h.f64(body.sleep_time);
            let s = &body.state;
            h.vec(s.com_world);
            h.quat(s.rotation);
            h.vec(s.linear_velocity);
            h.vec(s.angular_velocity);
            h.vec(body.force_world);
            h.vec(body.torque_world);
        }
        for (id, joint) in self.joints.iter() {
            h.u64(id.index() as u64);
            h.u64(u64::from(crate::id::JointId::from(id).generation()));
            h.u64(u64::from(joint.broken));
            h.f64(joint.force);
            h.f64(joint.torque);
        }
        for contact in self.contact_manager.contacts.iter() {
            h.u64(contact.body_a.index() as u64);
            h.u64(contact.body_b.index() as u64);
            h.u64(u64::from(contact.touching));
            if let Some(m) = &contact.manifold {
                h.vec(m.normal_world);
                for (p, i) in m.points().iter().zip(&contact.impulses) {
                    h.u64(u64::from(p.feature_id));
                    h.f64(p.separation);
                    h.f64(i.normal);
                    h.vec(i.tangent_world);
                }
            }
        }
        h.0
    }
}

#[cfg(test)]
mod tests {
    use super::Fnv64;

    #[test]
    fn fnv1a_known_vector() {
        // FNV-1a 64 of "a" is 0xaf63dc4c8601ec8c (the published test vector).
        let mut h = Fnv64(Fnv64::OFFSET);
        h.bytes(b"a");
        assert_eq!(h.0, 0xaf63_dc4c_8601_ec8c);
    }
}
