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
//! touching), and the places are compacted away — the survivors keep their order — only once
//! they are more than [`DROPPED_SHARE`] of the array. Compacting at every drop moved most of the
//! array for a few contacts: the pile of falling balls drops about 35 of its 12,500 contacts a
//! step, and the compaction moved some 8,900 kilobyte contacts, 340 µs of a step on the step's
//! own thread while the others waited. Now it moves them about once in 20 steps; the walks skip
//! the dropped places, which they read anyway. (Filling each dropped contact's place with the
//! last contact instead also moves little, but scatters the order: contacts next to each other
//! no longer touch bodies next to each other, and a new order changes how the solver's colours
//! fall, hence every result.) With threads, the compaction copies the live contacts in chunks
//! into a second array (the one the last compaction left) and swaps the two: about 1 ms for the
//! pile's contacts on two threads, against some 3 ms in place on one.
//!
//! The order of the live contacts is a pure function of the history of the world — the pairs made
//! in each step, in the broad phase's order — so it is the same on every run and for any thread
//! count, and a snapshot keeps it (it holds the live contacts only: when the dropped places are
//! compacted away never changes a result).

use rustc_hash::FxHashSet;

use super::broad_phase::ProxyKey;
use crate::dynamics::contact::Contact;
use crate::step_threads::{for_each_chunk_of, StepThreads};

/// The pair of proxies of a contact, lower key first.
pub(crate) type ProxyPair = (ProxyKey, ProxyKey);

/// The share of the array's places that may hold dropped contacts before they are compacted
/// away, as the divisor of the array's length: a sixteenth.
const DROPPED_SHARE: usize = 16;

/// Places handed to one task of the threaded compaction ([`ContactStore::compact_if_sparse`]).
const COMPACT_CHUNK: usize = 256;

#[derive(Clone, Debug, Default, serde::Deserialize)]
#[serde(from = "Vec<Contact>")]
pub(crate) struct ContactStore {
    /// The contacts in their order, dropped ones included (marked, until compacted away).
    contacts: Vec<Contact>,
    /// The proxy pair of every live contact.
    pairs: FxHashSet<ProxyPair>,
    /// The places of `contacts` that hold dropped contacts, in the order they were dropped.
    dropped_places: Vec<usize>,
    /// The array the threaded compaction copies the live contacts into, then swaps with
    /// `contacts`.
    spare: Spare,
}

/// The last array compaction left behind, with its stale contacts: its places are overwritten
/// by the next compaction (no array of placeholders is written first). Not part of the store's
/// value: a clone starts without one.
#[derive(Default)]
struct Spare(Vec<Contact>);

impl Clone for Spare {
    fn clone(&self) -> Spare {
        Spare::default()
    }
}

impl std::fmt::Debug for Spare {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Spare({} places)", self.0.len())
    }
}

/// One task of the threaded compaction: the live contacts of `source`, in order, into `target`.
struct CompactJob<'a> {
    source: &'a [Contact],
    target: &'a mut [Contact],
    /// The live contacts found in `source`: `target.len()` when the dropped places were right.
    live_found: usize,
}

impl ContactStore {
    /// The live contacts.
    pub fn len(&self) -> usize {
        self.contacts.len() - self.dropped_places.len()
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

    /// Keeps the live contacts for which `keep` is true, in their order, and drops the rest.
    pub fn retain(&mut self, mut keep: impl FnMut(&mut Contact) -> bool) {
        for place in 0..self.contacts.len() {
            if !self.contacts[place].dropped && !keep(&mut self.contacts[place]) {
                self.drop_at(place);
            }
        }
        self.compact_if_sparse(None);
    }

    /// Drops the live contact at `place` (an index into [`ContactStore::as_slice`]); its place
    /// stays until [`ContactStore::compact_if_sparse`] finds enough of them.
    pub fn drop_at(&mut self, place: usize) {
        let contact = &mut self.contacts[place];
        debug_assert!(!contact.dropped, "a contact is dropped once");
        self.pairs.remove(&(contact.proxy_a, contact.proxy_b));
        contact.set_manifold(None);
        contact.manifold_origin = None;
        contact.dropped = true;
        self.dropped_places.push(place);
    }

    /// Removes the dropped contacts' places, keeping the order of the rest, once they are more
    /// than a [`DROPPED_SHARE`]th of the array. With `threads`, the live contacts are copied into
    /// the spare array in chunks on them: moving the rain's 12,600 kilobyte contacts on the
    /// step's thread took some 3 ms once in 20 steps, while the other threads waited.
    pub fn compact_if_sparse(&mut self, threads: Option<&StepThreads>) {
        if self.dropped_places.len() * DROPPED_SHARE <= self.contacts.len() {
            return;
        }
        let copied = match threads {
            Some(threads) if self.contacts.len() >= 2 * COMPACT_CHUNK => self.compact_on(threads),
            _ => false,
        };
        if !copied {
            self.contacts.retain(|contact| !contact.dropped);
        }
        self.dropped_places.clear();
    }

    /// Copies the live contacts into the spare array on `threads` and swaps it in; false (and
    /// nothing changed) if the dropped places did not match the contacts' marks.
    fn compact_on(&mut self, threads: &StepThreads) -> bool {
        let dropped = &mut self.dropped_places;
        dropped.sort_unstable();
        let live = self.contacts.len() - dropped.len();
        // As many places as there are live contacts: the last compaction's array cut short, or
        // grown by copies of the first contacts (overwritten below) when the contacts grew.
        let spare = &mut self.spare.0;
        spare.truncate(live);
        let grow = live - spare.len();
        spare.extend_from_slice(&self.contacts[..grow]);
        // Each chunk of places goes to the next places of the spare array, as many as it has
        // live contacts (its places less the dropped ones among them).
        let mut free = &mut spare[..];
        let mut jobs = Vec::with_capacity(self.contacts.len().div_ceil(COMPACT_CHUNK));
        let mut dropped_before = 0;
        for (index, source) in self.contacts.chunks(COMPACT_CHUNK).enumerate() {
            let dropped_to_end =
                dropped.partition_point(|&place| place < index * COMPACT_CHUNK + source.len());
            let live_in_source = source.len() - (dropped_to_end - dropped_before);
            let (target, rest) = std::mem::take(&mut free).split_at_mut(live_in_source);
            free = rest;
            dropped_before = dropped_to_end;
            jobs.push(CompactJob { source, target, live_found: 0 });
        }
        for_each_chunk_of(Some(threads), &mut jobs, 1, |_, jobs| {
            for job in jobs {
                let mut targets = job.target.iter_mut();
                for contact in job.source.iter().filter(|contact| !contact.dropped) {
                    if let Some(target) = targets.next() {
                        target.clone_from(contact);
                    }
                    job.live_found += 1;
                }
            }
        });
        let complete = jobs.iter().all(|job| job.live_found == job.target.len());
        if complete {
            std::mem::swap(&mut self.contacts, spare);
        }
        complete
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
        ContactStore { contacts, pairs, dropped_places: Vec::new(), spare: Spare::default() }
    }
}

/// Only the live contacts are written: the pair set follows from them.
impl serde::Serialize for ContactStore {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        if self.dropped_places.is_empty() {
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
        // A third drop makes them more than a sixteenth: compacted, the order kept.
        let order = |s: &ContactStore| s.iter().map(first).collect::<Vec<_>>();
        let before: Vec<u32> = order(&store).into_iter().filter(|&a| a != 20).collect();
        store.retain(|c| first(c) != 20);
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

    /// The threaded compaction keeps the live contacts in their order, as the compaction on one
    /// thread does: over rounds that drop scattered places, grow the store past the last
    /// compaction's array and shrink it again (the spare array cut short, grown, reused).
    #[test]
    fn compaction_on_threads_keeps_what_the_compaction_on_one_thread_keeps() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
        let threads = StepThreads::begin(&pool);
        let (mut threaded, mut plain) = (ContactStore::default(), ContactStore::default());
        let first = |c: &Contact| c.proxy_a.proxy_id().0;
        let mut next = 0;
        for (round, (added, every)) in [(1500, 7), (2000, 3), (100, 2), (3000, 11)].into_iter().enumerate() {
            for _ in 0..added {
                threaded.push(contact(2 * next, 2 * next + 1));
                plain.push(contact(2 * next, 2 * next + 1));
                next += 1;
            }
            let doomed: Vec<usize> = (0..threaded.places())
                .filter(|&place| !threaded.as_slice()[place].dropped && (place * 31 + round) % every == 0)
                .collect();
            for &place in doomed.iter().rev() {
                threaded.drop_at(place);
                plain.drop_at(place);
            }
            assert!(threaded.dropped_places.len() * DROPPED_SHARE > threaded.places(), "round {round}");
            // Copied on the threads into the other array (compacting on one thread stays put).
            let array = threaded.as_slice().as_ptr();
            threaded.compact_if_sparse(Some(&threads));
            assert_ne!(threaded.as_slice().as_ptr(), array, "round {round}");
            plain.compact_if_sparse(None);
            let order = |s: &ContactStore| s.as_slice().iter().map(first).collect::<Vec<_>>();
            assert_eq!(order(&threaded), order(&plain), "round {round}");
            assert_eq!((threaded.len(), threaded.places()), (plain.len(), plain.len()), "round {round}");
            assert!(threaded
                .as_slice()
                .iter()
                .all(|c| !c.dropped && threaded.contains((c.proxy_a, c.proxy_b))));
        }
    }
}
