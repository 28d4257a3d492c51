//! Contacts: one per pair of shapes whose fat bounding boxes overlap, kept from step to step.
//! A contact holds the current manifold, the impulses of its points (matched across steps by
//! feature id, for warm starting) and the narrow phase's cache for the pair.

use crate::collision::manifold::Manifold;
use crate::collision::manifold_reuse::ManifoldOrigin;
use crate::collision::narrow_phase::PairCache;
use crate::collision::ProxyKey;
use crate::dynamics::contact_solver::{ContactImpulse, ContactMaterial};
use crate::id::BodyId;
use crate::math::DVec3;

/// The cache lines of a contact's head (`Contact::prefetch_head`).
const HEAD_LINES: usize = 2;

/// Laid out head first (`repr(C)`, one contact per run of whole cache lines): the fields the
/// solver's take-part scan reads of every contact — bodies, leaves, flags, material — fill the
/// first line, and the proxies and the manifold's start the second. That scan asks for those
/// two lines instead of the contact's fourteen (`prefetch_head`); most of a rain's contacts are
/// apart and the scan reads nothing else of them.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[repr(C, align(64))]
pub(crate) struct Contact {
    pub body_a: BodyId,
    pub body_b: BodyId,
    /// Leaf shape index within each body's shape (compound child, or 0).
    pub child_a: u32,
    pub child_b: u32,
    /// One of the shapes is a sensor: overlap is reported, no contact force acts.
    pub sensor: bool,
    /// The manifold has points (within the speculative margin) — the pair links islands.
    pub touching: bool,
    /// Neither body is a compound: this is the only contact of its pair of bodies (events.rs
    /// then needs no count of the pair's contacts).
    #[serde(default)]
    pub only_one_of_pair: bool,
    /// The contact was dropped and waits in its place to be compacted away
    /// (`collision/contact_store.rs`): it has no manifold and touches nothing.
    #[serde(skip)]
    pub dropped: bool,
    pub material: ContactMaterial,
    pub proxy_a: ProxyKey,
    pub proxy_b: ProxyKey,
    pub manifold: Option<Manifold>,
    /// Impulses of the manifold's points, in the manifold's point order.
    pub impulses: [ContactImpulse; 4],
    pub cache: PairCache,
    /// Where the manifold was made, while it may be reused (`collision/manifold_reuse.rs`).
    #[serde(default)]
    pub manifold_origin: Option<ManifoldOrigin>,
}

// The layout the take-part scan relies on: the head's fields within the first line, the
// manifold's start (where its `Option` tag is) within the second.
const _: () = assert!(std::mem::offset_of!(Contact, material) + std::mem::size_of::<ContactMaterial>() <= 64);
const _: () = assert!(std::mem::offset_of!(Contact, manifold) + 8 <= HEAD_LINES * 64);

impl Contact {
    /// A new contact between two leaf shapes' proxies (lower key first), not yet touching.
    pub fn new(
        (proxy_a, proxy_b): (ProxyKey, ProxyKey),
        (body_a, body_b): (BodyId, BodyId),
        (child_a, child_b): (u32, u32),
        material: ContactMaterial,
        sensor: bool,
        only_one_of_pair: bool,
    ) -> Contact {
        Contact {
            proxy_a,
            proxy_b,
            body_a,
            body_b,
            child_a,
            child_b,
            manifold: None,
            impulses: [ContactImpulse::default(); 4],
            cache: PairCache::default(),
            manifold_origin: None,
            material,
            sensor,
            touching: false,
            only_one_of_pair,
            dropped: false,
        }
    }

    /// Asks for the whole contact ahead of a walk's reading it (`prefetch.rs`).
    #[inline(always)]
    pub fn prefetch(&self) {
        crate::prefetch::prefetch(self);
    }

    /// Asks for the contact's first two cache lines only: its bodies, leaves, flags and
    /// material, its proxies and whether it has a manifold (the struct's layout).
    #[inline(always)]
    pub fn prefetch_head(&self) {
        crate::prefetch::prefetch_lines(self, HEAD_LINES);
    }

    /// A contact between two proxies of bodies 0 and 1, for tests of the store.
    #[cfg(test)]
    pub fn new_for_test(proxy_a: ProxyKey, proxy_b: ProxyKey) -> Contact {
        let body = |i| BodyId::from_parts(i, 0);
        let material = crate::dynamics::material::Material::combine(&Default::default(), &Default::default());
        Contact::new((proxy_a, proxy_b), (body(0), body(1)), (0, 0), material, false, true)
    }

    /// Replaces the manifold, carrying impulses over to points with the same feature id.
    pub fn set_manifold(&mut self, manifold: Option<Manifold>) {
        if manifold.is_none() && self.manifold.is_none() {
            // Still apart (most of a falling pile's pairs, whose fat boxes overlap): nothing
            // changes, and nothing is written — the impulses are already zero, and moving the
            // manifold and impulses in regardless cost the rain 3% of its steps per second.
            debug_assert!(!self.touching && self.impulses == [ContactImpulse::default(); 4]);
            return;
        }
        let mut impulses = [ContactImpulse::default(); 4];
        if let (Some(old), Some(new)) = (&self.manifold, &manifold) {
            for (slot, point) in impulses.iter_mut().zip(new.points()) {
                if let Some(i) = old.points().iter().position(|p| p.feature_id == point.feature_id) {
                    *slot = self.impulses[i];
                }
            }
        }
        self.touching = manifold.as_ref().is_some_and(|m| !m.is_empty());
        self.manifold = manifold;
        self.impulses = impulses;
    }
}

/// A read-only view of one contact point, for users.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactPointView {
    /// Midpoint between the surfaces, world frame.
    pub point: DVec3,
    /// Signed distance along the normal (negative = penetration), m.
    pub separation: f64,
    /// Normal impulse of the last step (summed over substeps is `impulse × substeps`), N·s.
    pub normal_impulse: f64,
    /// Friction impulse of the last substep, world frame, N·s.
    pub tangent_impulse: DVec3,
    pub feature_id: u32,
}

/// A read-only view of a touching contact, for users.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactView {
    pub body_a: BodyId,
    pub body_b: BodyId,
    /// Unit normal from a towards b, world frame.
    pub normal: DVec3,
    pub points: Vec<ContactPointView>,
    pub sensor: bool,
}
