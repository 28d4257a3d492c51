//! The contact store: every contact in one contiguous array, in the order the contacts were made
//! (new pairs in the broad phase's sorted order, appended), with a hash set of their proxy pairs
//! for the broad phase's "is this pair new?" question.
//!
//! Why an array: each step walks all contacts several times (manifold updates, events, island
//! links, the solver's gather and store), and a contact is about a kilobyte. A `BTreeMap` keyed by
//! the pair — the first store — walked its nodes, and inserting or dropping a contact shifted up to
//! ten neighbours within a node (a tenth of a pile of 2,000 falling balls' step went to those
//! walks and shifts). The array walks in memory order and splits into chunks for the threads
//! without collecting references first.
//!
//! Dropping a contact leaves it in its place, marked `dropped` and emptied (no manifold, not
//! touching), and the places are compacted away — the survivors keep their order — only once they
//! are more than [`DROPPED_SHARE`] of the array: by the walk of the next one-thread narrow phase as
//! it goes (`retain`), or after the walk of a threaded one (`compact_if_sparse`). Compacting at
//! every drop moved most of the array for a few contacts: the pile of falling balls drops about 35
//! of its 12,500 contacts a step, and the compaction moved some 8,900 kilobyte contacts, 340 µs of
//! a step on the step's own thread while the others waited. Now it moves them once in 7 to 20 steps
//! (7 while most of the balls land); the walks skip the dropped places, which they read anyway.
//! (Filling each dropped contact's place with the last contact instead also moves little, but
//! scatters the order: contacts next to each other no longer touch bodies next to each other, and a
//! new order changes how the solver's colours fall, hence every result.) The compaction runs on the
//! step's thread, in place, even in a step with threads: copying the live contacts in chunks on the
//! threads into a second array took twice as long as moving them in place on one (the 2,000 balls'
//! 13,000 contacts: 1.5–2.1 ms against 1.0–1.2 ms, measured 2026-12-07) — writing a second array of
//! 11 MB costs more than the shift within the first.
//!
//! The order of the live contacts is a pure function of the history of the world — the pairs made
//! in each step, in the broad phase's order — so it is the same on every run and for any thread
//! count, and a snapshot keeps it (it holds the live contacts only: when the dropped places are
//! compacted away never changes a result).

use rustc_hash::FxHashSet;

use super::broad_phase::ProxyKey;
use crate::dynamics::contact::Contact;
use crate::step_threads::{extend_on_threads, StepThreads};

/// The pair of proxies of a contact, lower key first.
pub(crate) type ProxyPair = (ProxyKey, ProxyKey);

/// The share of the array's places that may hold dropped contacts before they are compacted
/// away, as the divisor of the array's length: a sixteenth.
const DROPPED_SHARE: usize = 16;

/// How many places ahead a walk over the contacts asks for the next ones' memory (`prefetch.rs`):
/// about one miss's time of work on a rain's contacts.
pub(crate) const PREFETCH_AHEAD: usize = 4;

/// How much of a contact a walk asks for ahead of reading it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Reach {
    /// The whole contact (the narrow phase, which updates its manifold and cache).
    Whole,
    /// Its head (`Contact::prefetch_head`): a walk that reads the rest only of the few contacts
    /// it takes.
    Head,
}

#[inline(always)]
fn prefetch_reach(contact: &Contact, reach: Reach) {
    match reach {
        Reach::Whole => contact.prefetch(),
        Reach::Head => contact.prefetch_head(),
    }
}

/// The prefetch of a walk over `contacts` in order, at `place`: the contact [`PREFETCH_AHEAD`]
/// places ahead. (Asking also for the bodies and boxes of the contact half as far ahead, in
/// cache by then, gained nothing measurable.)
#[inline(always)]
pub(crate) fn prefetch_ahead(contacts: &[Contact], place: usize, reach: Reach) {
    if let Some(far) = contacts.get(place + PREFETCH_AHEAD) {
        prefetch_reach(far, reach);
    }
}

/// The prefetch of a walk's start: the first [`PREFETCH_AHEAD`] contacts, which
/// [`prefetch_ahead`] never asks for. A threaded walk starts anew at each chunk it takes; without
/// this, the first few contacts of every chunk (an eighth of a chunk of 32) each waited for
/// memory.
#[inline(always)]
pub(crate) fn prefetch_start(contacts: &[Contact], reach: Reach) {
    for contact in contacts.iter().take(PREFETCH_AHEAD) {
        prefetch_reach(contact, reach);
    }
}

#[derive(Clone, Debug, Default, serde::Deserialize)]
#[serde(from = "Vec<Contact>")]
pub(crate) struct ContactStore {
    /// The contacts in their order, dropped ones included (marked, until compacted away).
    contacts: Vec<Contact>,
    /// The proxy pair of every live contact.
    pairs: FxHashSet<ProxyPair>,
    /// How many places of `contacts` hold dropped contacts.
    dropped: usize,
}

impl ContactStore {
    /// The live contacts.
    pub fn len(&self) -> usize {
        self.contacts.len() - self.dropped
    }

    /// The places: live contacts and dropped ones not yet compacted away.
    pub fn places(&self) -> usize {
        self.contacts.len()
    }

    /// Whether a contact of this pair (lower key first) exists.
    pub fn contains(&self, pair: ProxyPair) -> bool {
        self.pairs.contains(&pair)
    }

    /// Appends a contact for a pair that has none.
    #[cfg(test)]
    pub fn push(&mut self, contact: Contact) {
        let fresh = self.pairs.insert((contact.proxy_a, contact.proxy_b));
        debug_assert!(fresh, "a pair has at most one contact");
        self.contacts.push(contact);
    }

    /// Appends a contact `make(n)` for each of `new`, whose pair (`pair_of(n)`) has none, in
    /// order; the contacts are written on `threads` when there are many (`extend_on_threads`).
    pub(crate) fn extend_on_threads<S: Sync>(
        &mut self,
        new: &[S],
        pair_of: impl Fn(&S) -> ProxyPair,
        make: impl Fn(&S) -> Contact + Sync,
        threads: Option<&StepThreads>,
    ) {
        self.pairs.reserve(new.len());
        for n in new {
            let fresh = self.pairs.insert(pair_of(n));
            debug_assert!(fresh, "a pair has at most one contact");
        }
        extend_on_threads(&mut self.contacts, new, make, threads);
    }

    /// Keeps the live contacts for which `keep` is true, in their order, and drops the rest
    /// (each contact asked for [`PREFETCH_AHEAD`] places ahead). When the dropped places are due
    /// to be compacted away (more than a [`DROPPED_SHARE`]th), this walk does it: each kept
    /// contact moves to its new place right after `keep`, while it is in cache, instead of in a
    /// second walk over the whole array after this one (the rain's one-thread narrow phase walks
    /// took 190 against 218 ms over its first 120 steps, medians of 16 alternating runs).
    /// Otherwise a dropped contact is marked and left in its place.
    pub fn retain(&mut self, mut keep: impl FnMut(&mut Contact) -> bool) {
        if !self.compaction_due() {
            for place in 0..self.contacts.len() {
                prefetch_ahead(&self.contacts, place, Reach::Whole);
                if !self.contacts[place].dropped && !keep(&mut self.contacts[place]) {
                    self.drop_at(place);
                }
            }
            return;
        }
        let pairs = &mut self.pairs;
        // Only an address to prefetch from (never read through): `retain_mut` holds the vector.
        let start = self.contacts.as_ptr();
        let mut place = 0;
        self.contacts.retain_mut(|contact| {
            crate::prefetch::prefetch_at(start.wrapping_add(place + PREFETCH_AHEAD));
            place += 1;
            if contact.dropped {
                return false;
            }
            let kept = keep(contact);
            if !kept {
                pairs.remove(&(contact.proxy_a, contact.proxy_b));
            }
            kept
        });
        self.dropped = 0;
    }

    /// Drops the live contact at `place` (an index into [`ContactStore::as_slice`]); its place
    /// stays until enough of them are compacted away ([`ContactStore::compact_if_sparse`], or
    /// the next [`ContactStore::retain`]).
    pub fn drop_at(&mut self, place: usize) {
        let contact = &mut self.contacts[place];
        debug_assert!(!contact.dropped, "a contact is dropped once");
        self.pairs.remove(&(contact.proxy_a, contact.proxy_b));
        contact.set_manifold(None);
        contact.manifold_origin = None;
        contact.dropped = true;
        self.dropped += 1;
    }

    /// Whether the dropped places are more than a [`DROPPED_SHARE`]th of the array.
    fn compaction_due(&self) -> bool {
        self.dropped * DROPPED_SHARE > self.contacts.len()
    }

    /// Removes the dropped contacts' places, keeping the order of the rest, once they are more
    /// than a [`DROPPED_SHARE`]th of the array.
    pub fn compact_if_sparse(&mut self) {
        if !self.compaction_due() {
            return;
        }
        self.contacts.retain(|contact| !contact.dropped);
        self.dropped = 0;
    }

    /// The live contacts, in their order.
    pub fn iter(&self) -> impl Iterator<Item = &Contact> + Clone {
        self.contacts.iter().filter(|contact| !contact.dropped)
    }

    /// Every place, in order: the live contacts and the dropped ones (`dropped`: no manifold,
    /// not touching), for walks by index.
    pub fn as_slice(&self) -> &[Contact] {
        &self.contacts
    }

    /// Every place, to update the live contacts in place (a contact's pair must not change, and
    /// a dropped one must stay as it is).
    pub fn as_mut_slice(&mut self) -> &mut [Contact] {
        &mut self.contacts
    }
}

impl From<Vec<Contact>> for ContactStore {
    fn from(contacts: Vec<Contact>) -> Self {
        let pairs = contacts.iter().map(|c| (c.proxy_a, c.proxy_b)).collect();
        ContactStore { contacts, pairs, dropped: 0 }
    }
}

/// Only the live contacts are written: the pair set follows from them.
impl serde::Serialize for ContactStore {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        if self.dropped == 0 {
            self.contacts.serialize(serializer)
        } else {
            self.iter().collect::<Vec<_>>().serialize(serializer)
        }
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

    /// Contacts made on threads are the contacts made one by one, in the same order, and their
    /// pairs are known.
    #[test]
    fn contacts_made_on_threads_are_those_made_one_by_one() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("pool");
        let threads = StepThreads::begin(&pool);
        let pairs: Vec<(u32, u32)> = (0..3000).map(|i| (2 * i, 2 * i + 1)).collect();
        let (mut alone, mut shared) = (ContactStore::default(), ContactStore::default());
        alone.push(contact(1, 7));
        shared.push(contact(1, 7));
        for &(a, b) in &pairs {
            alone.push(contact(a, b));
        }
        let pair_of = |&(a, b): &(u32, u32)| (contact(a, b).proxy_a, contact(a, b).proxy_b);
        shared.extend_on_threads(&pairs, pair_of, |&(a, b)| contact(a, b), Some(&threads));
        let pair = |c: &Contact| (c.proxy_a.proxy_id().0, c.proxy_b.proxy_id().0);
        assert_eq!(shared.len(), pairs.len() + 1);
        assert_eq!(alone.iter().map(pair).collect::<Vec<_>>(), shared.iter().map(pair).collect::<Vec<_>>());
        assert!(pairs.iter().all(|p| shared.contains(pair_of(p))));
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
    fn dropped_places_stay_until_they_are_a_sixteenth_and_the_walks_skip_them() {
        let mut store = ContactStore::default();
        for i in 0..32 {
            store.push(contact(2 * i, 2 * i + 1));
        }
        let first = |c: &Contact| c.proxy_a.proxy_id().0;
        // Two of 32 places dropped: not more than a sixteenth, so they stay, invisible to `iter`.
        store.retain(|c| first(c) != 4 && first(c) != 10);
        assert_eq!((store.len(), store.places()), (30, 32));
        assert!(store.as_slice()[2].dropped && store.as_slice()[5].dropped);
        assert!(store.as_slice()[2].manifold.is_none() && !store.as_slice()[2].touching);
        assert!(store.iter().all(|c| !c.dropped) && store.iter().count() == 30);
        assert!(!store.contains((contact(4, 5).proxy_a, contact(4, 5).proxy_b)));
        // The same pair may be made again while its old place waits: the new one is live.
        store.push(contact(4, 5));
        assert_eq!((store.len(), store.places()), (31, 33));
        // A third drop makes them more than a sixteenth: the next walk compacts them away as it
        // goes (a compaction on its own, `compact_if_sparse`, would now too), the order kept.
        let order = |s: &ContactStore| s.iter().map(first).collect::<Vec<_>>();
        let before: Vec<u32> = order(&store).into_iter().filter(|&a| a != 20).collect();
        store.retain(|c| first(c) != 20);
        assert_eq!((store.len(), store.places()), (30, 33));
        let mut visited = 0;
        store.retain(|_| {
            visited += 1;
            true
        });
        assert_eq!(visited, 30, "the walk visits the live contacts only");
        assert_eq!((store.len(), store.places()), (30, 30));
        assert_eq!(order(&store), before);
        assert_eq!(store.as_slice().iter().map(first).collect::<Vec<_>>(), before);
    }

    #[test]
    fn a_snapshot_round_trip_keeps_the_order_and_rebuilds_the_pairs() {
        let mut store = ContactStore::default();
        for (a, b) in [(5, 6), (0, 1), (2, 3), (7, 8)] {
            store.push(contact(a, b));
        }
        // A dropped place is not written.
        store.drop_at(2);
        assert_eq!(store.places(), 4);
        let bytes = postcard::to_stdvec(&store).expect("encodes");
        let back: ContactStore = postcard::from_bytes(&bytes).expect("decodes");
        let pairs = |s: &ContactStore| s.iter().map(|c| (c.proxy_a, c.proxy_b)).collect::<Vec<_>>();
        assert_eq!(pairs(&back), pairs(&store));
        assert_eq!((back.len(), back.places()), (3, 3));
        assert!(pairs(&store).into_iter().all(|p| back.contains(p)));
    }
}
