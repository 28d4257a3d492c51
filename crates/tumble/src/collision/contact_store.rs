//! The contact store: every contact in one contiguous array, in the order the contacts were made
//! (new pairs in the broad phase's sorted order, appended), with a hash set of their proxy pairs
//! for the broad phase's "is this pair new?" question.
//!
//! Why an array: each step walks all contacts several times (manifold updates, events, island
//! links, the solver's gather and store), and a contact is about a kilobyte. A `BTreeMap` keyed by
//! the pair — the first store — walked its nodes, and inserting or dropping a contact shifted up to
//! ten neighbours within a node (a tenth of a pile of 2,000 falling balls' step went to those
//! walks and shifts). The array walks in memory order, drops contacts by compacting in place (the
//! survivors keep their order), and splits into chunks for the threads without collecting
//! references first. (Filling each dropped contact's place with the last contact instead moves
//! far fewer kilobytes, but scatters the order: contacts next to each other no longer touch
//! bodies next to each other, and the pile of falling balls ran 6% slower on one thread. Measured
//! again with the step's threads: compacting in place moves about 8,900 of the rain's 12,300
//! contacts a step, 340 µs on the step's own thread while the other waits, and filling the places
//! ran the rain and the ragdolls 5–6% faster on two threads and the same on one; but the new
//! order changes how the solver's colours fall, and the rain's penetration after 120 steps at 3
//! substeps came out 1.00 cm instead of 0.65 — within that scene's spread from step to step,
//! 0.4–1.0 cm either way, yet above Rapier's 0.99 in the speed table, whose matched setting would
//! then need a fourth substep. Left as it is.)
//!
//! The order is a pure function of the history of the world — the pairs made in each step, in
//! the broad phase's order — so it is the same on every run and for any thread count, and a
//! snapshot keeps it.

use rustc_hash::FxHashSet;

use super::broad_phase::ProxyKey;
use crate::dynamics::contact::Contact;

/// The pair of proxies of a contact, lower key first.
pub(crate) type ProxyPair = (ProxyKey, ProxyKey);

#[derive(Clone, Debug, Default, serde::Deserialize)]
#[serde(from = "Vec<Contact>")]
pub(crate) struct ContactStore {
    contacts: Vec<Contact>,
    /// The proxy pair of every contact in `contacts`.
    pairs: FxHashSet<ProxyPair>,
}

impl ContactStore {
    pub fn len(&self) -> usize {
        self.contacts.len()
    }

    /// Whether a contact of this pair (lower key first) exists.
    pub fn contains(&self, pair: ProxyPair) -> bool {
        self.pairs.contains(&pair)
    }

    /// Appends a contact for a pair that has none.
    pub fn push(&mut self, contact: Contact) {
        let fresh = self.pairs.insert((contact.proxy_a, contact.proxy_b));
        debug_assert!(fresh, "a pair has at most one contact");
        self.contacts.push(contact);
    }

    /// Makes room for `additional` more contacts.
    pub fn reserve(&mut self, additional: usize) {
        self.contacts.reserve(additional);
        self.pairs.reserve(additional);
    }

    /// Keeps the contacts for which `keep` is true, in their order.
    pub fn retain(&mut self, mut keep: impl FnMut(&mut Contact) -> bool) {
        let pairs = &mut self.pairs;
        self.contacts.retain_mut(|contact| {
            let kept = keep(contact);
            if !kept {
                pairs.remove(&(contact.proxy_a, contact.proxy_b));
            }
            kept
        });
    }

    pub fn iter(&self) -> std::slice::Iter<'_, Contact> {
        self.contacts.iter()
    }

    pub fn as_slice(&self) -> &[Contact] {
        &self.contacts
    }

    /// The contacts, to update in place (a contact's pair must not change).
    pub fn as_mut_slice(&mut self) -> &mut [Contact] {
        &mut self.contacts
    }
}

impl From<Vec<Contact>> for ContactStore {
    fn from(contacts: Vec<Contact>) -> Self {
        let pairs = contacts.iter().map(|c| (c.proxy_a, c.proxy_b)).collect();
        ContactStore { contacts, pairs }
    }
}

/// Only the contacts are written: the pair set follows from them.
impl serde::Serialize for ContactStore {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.contacts.serialize(serializer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::broad_phase::ProxyKind;
    use crate::collision::ProxyId;

    fn contact(a: u32, b: u32) -> Contact {
        let key = |i| ProxyKey::new(ProxyKind::Dynamic, ProxyId(i));
        Contact::new_for_test(key(a), key(b))
    }

    #[test]
    fn dropping_contacts_keeps_the_order_of_the_rest_and_forgets_their_pairs() {
        let mut store = ContactStore::default();
        for (a, b) in [(3, 4), (0, 1), (1, 2), (0, 2)] {
            store.push(contact(a, b));
        }
        let pair = |c: &Contact| (c.proxy_a.proxy_id().0, c.proxy_b.proxy_id().0);
        store.retain(|c| pair(c) != (0, 1));
        assert_eq!(store.iter().map(pair).collect::<Vec<_>>(), [(3, 4), (1, 2), (0, 2)]);
        assert!(!store.contains((contact(0, 1).proxy_a, contact(0, 1).proxy_b)));
        assert!(store.contains((contact(1, 2).proxy_a, contact(1, 2).proxy_b)));
        assert_eq!(store.len(), 3);
    }

    #[test]
    fn a_snapshot_round_trip_keeps_the_order_and_rebuilds_the_pairs() {
        let mut store = ContactStore::default();
        for (a, b) in [(5, 6), (0, 1)] {
            store.push(contact(a, b));
        }
        let bytes = postcard::to_stdvec(&store).expect("encodes");
        let back: ContactStore = postcard::from_bytes(&bytes).expect("decodes");
        let pairs = |s: &ContactStore| s.iter().map(|c| (c.proxy_a, c.proxy_b)).collect::<Vec<_>>();
        assert_eq!(pairs(&back), pairs(&store));
        assert!(pairs(&store).into_iter().all(|p| back.contains(p)));
    }
}
