//! The broad phase: which shapes might touch, from their fat boxes alone.
//!
//! Static proxies and dynamic (every non-static: dynamic and kinematic) proxies live in two
//! separate trees, as in Box2D v3: static geometry is usually the bulk of a scene and never moves,
//! so keeping it apart means moving proxies never rebalance it, and static–static pairs — never
//! useful — are excluded by construction rather than filtered.
//!
//! Pairs come out as `(lower key, higher key)`, each once, sorted. The order is therefore a
//! function of the set of overlapping proxy keys only, not of traversal order or tree shape, which
//! is what the deterministic step needs.

use super::aabb::Aabb;
use super::dynamic_tree::{DynamicTree, ProxyId};
use super::ray::Ray;
use crate::math::DVec3;
use crate::step_threads::{for_each_chunk_of, StepThreads};

/// Which tree a proxy lives in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize)]
pub enum ProxyKind {
    /// Never moves on its own; never paired with another static proxy.
    Static = 0,
    /// Anything that can move (dynamic or kinematic bodies).
    Dynamic = 1,
}

/// A proxy handle across both trees: the tree's proxy index shifted left by one, with the kind in
/// the low bit. Ordered by that packed value, so pair order is a pure function of the keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize)]
pub struct ProxyKey(u32);

impl ProxyKey {
    pub fn new(kind: ProxyKind, id: ProxyId) -> Self {
        debug_assert!(id.0 < (1 << 31), "proxy index out of range");
        Self((id.0 << 1) | kind as u32)
    }

    pub fn kind(self) -> ProxyKind {
        if self.0 & 1 == 0 {
            ProxyKind::Static
        } else {
            ProxyKind::Dynamic
        }
    }

    /// The proxy's index in its kind's tree.
    pub fn proxy_id(self) -> ProxyId {
        ProxyId(self.0 >> 1)
    }

    /// The packed value, for storage or hashing by the caller.
    pub fn raw(self) -> u32 {
        self.0
    }
}

/// A proxy's new tight box and its predicted displacement until the next update.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProxyUpdate {
    pub key: ProxyKey,
    pub aabb: Aabb,
    pub displacement: DVec3,
}

/// Default fat-box margin (metres): the slack a proxy may move before the tree is touched.
pub const DEFAULT_AABB_MARGIN: f64 = 0.1;

/// Two trees of fat boxes plus the list of proxies re-inserted since the last pair search.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct BroadPhase {
    /// Indexed by `ProxyKind as usize`.
    trees: [DynamicTree; 2],
    /// Proxies created or re-inserted since the last `find_new_pairs` (may hold duplicates and
    /// keys destroyed since; both are filtered when the buffer is used).
    move_buffer: Vec<ProxyKey>,
    /// The threaded pair search's pairs, one list per chunk of moved proxies (kept to reuse the
    /// allocations).
    #[serde(skip)]
    chunk_pairs: Vec<Vec<(ProxyKey, ProxyKey)>>,
}

/// Moved proxies per task of the threaded pair search: fixed, so the split follows the scene.
const PAIR_SEARCH_CHUNK: usize = 16;

/// Moved proxies below which the pair search stays on the calling thread (a few queries cost
/// less than handing them out).
const PAIR_SEARCH_MIN_SHARED: usize = 2 * PAIR_SEARCH_CHUNK;

impl Default for BroadPhase {
    fn default() -> Self {
        Self::new(DEFAULT_AABB_MARGIN)
    }
}

impl BroadPhase {
    /// An empty broad phase whose fat boxes are grown by `margin`.
    pub fn new(margin: f64) -> Self {
        Self {
            trees: [DynamicTree::new(margin), DynamicTree::new(margin)],
            move_buffer: Vec::new(),
            chunk_pairs: Vec::new(),
        }
    }

    /// The fat-box margin, m.
    pub fn margin(&self) -> f64 {
        self.trees[0].margin()
    }

    /// The tree holding proxies of `kind` (for queries and diagnostics).
    pub fn tree(&self, kind: ProxyKind) -> &DynamicTree {
        &self.trees[kind as usize]
    }

    pub fn proxy_count(&self) -> usize {
        self.trees[0].proxy_count() + self.trees[1].proxy_count()
    }

    /// Adds a proxy with tight box `aabb` and a caller payload (the world stores body and shape
    /// child there).
    pub fn create_proxy(&mut self, aabb: Aabb, kind: ProxyKind, user_data: u64) -> ProxyKey {
        let key = ProxyKey::new(kind, self.trees[kind as usize].create_proxy(aabb, user_data));
        self.move_buffer.push(key);
        key
    }

    pub fn destroy_proxy(&mut self, key: ProxyKey) {
        self.trees[key.kind() as usize].destroy_proxy(key.proxy_id());
    }

    /// Moves one proxy (see [`DynamicTree::move_proxy`]); returns whether it was re-inserted.
    pub fn move_proxy(&mut self, key: ProxyKey, aabb: Aabb, displacement: DVec3) -> bool {
        let moved = self.trees[key.kind() as usize].move_proxy(key.proxy_id(), aabb, displacement);
        if moved {
            self.move_buffer.push(key);
        }
        moved
    }

    /// Whether [`BroadPhase::move_proxy`] would re-insert the proxy (see
    /// [`DynamicTree::needs_move`]); reads the proxy's own fat box only.
    pub fn needs_move(&self, update: &ProxyUpdate) -> bool {
        self.trees[update.key.kind() as usize].needs_move(
            update.key.proxy_id(),
            &update.aabb,
            update.displacement,
        )
    }

    /// Re-inserts a proxy that [`BroadPhase::needs_move`] with its new box: the second half of
    /// [`BroadPhase::move_proxy`].
    pub fn reinsert(&mut self, update: &ProxyUpdate) {
        self.trees[update.key.kind() as usize].reinsert(
            update.key.proxy_id(),
            &update.aabb,
            update.displacement,
        );
        self.move_buffer.push(update.key);
    }

    /// Applies a batch of moves in the given order; returns how many proxies were re-inserted.
    pub fn update(&mut self, moves: &[ProxyUpdate]) -> usize {
        moves.iter().filter(|m| self.move_proxy(m.key, m.aabb, m.displacement)).count()
    }

    pub fn fat_aabb(&self, key: ProxyKey) -> Aabb {
        self.trees[key.kind() as usize].fat_aabb(key.proxy_id())
    }

    pub fn user_data(&self, key: ProxyKey) -> u64 {
        self.trees[key.kind() as usize].user_data(key.proxy_id())
    }

    /// Every candidate pair: dynamic–dynamic and dynamic–static proxies whose fat boxes overlap.
    /// Sorted, each pair once, lower key first.
    pub fn find_pairs(&self) -> Vec<(ProxyKey, ProxyKey)> {
        let mut pairs = Vec::new();
        let dynamic = &self.trees[ProxyKind::Dynamic as usize];
        for id in dynamic.proxies() {
            let key = ProxyKey::new(ProxyKind::Dynamic, id);
            let fat = dynamic.fat_aabb(id);
            // Each dynamic–dynamic pair is found from both ends; keep it from its lower end only.
            self.collect_overlaps(key, &fat, ProxyKind::Dynamic, |other| other > key, &mut pairs);
            self.collect_overlaps(key, &fat, ProxyKind::Static, |_| true, &mut pairs);
        }
        pairs.sort_unstable();
        pairs
    }

    /// The candidate pairs that involve at least one proxy created or re-inserted since the last
    /// call (the pairs that may be new), then clears that record. Sorted, each pair once, lower
    /// key first. Pairs of proxies that both stayed inside their fat boxes are not reported: they
    /// were reported before, and their overlap has not changed.
    pub fn find_new_pairs(&mut self) -> Vec<(ProxyKey, ProxyKey)> {
        let mut pairs = Vec::new();
        self.find_new_pairs_into(&mut pairs);
        pairs
    }

    /// [`BroadPhase::find_new_pairs`] into a caller's buffer (cleared first), so a caller that
    /// keeps the buffer allocates nothing once it is large enough.
    pub fn find_new_pairs_into(&mut self, pairs: &mut Vec<(ProxyKey, ProxyKey)>) {
        self.find_new_pairs_on(pairs, None, |_| false);
    }

    /// [`BroadPhase::find_new_pairs_into`], with the queries on `threads` when enough proxies
    /// moved: in chunks of [`PAIR_SEARCH_CHUNK`] moved proxies, each into its own list, joined
    /// and sorted afterwards, so the pairs are the same whatever the split. (The queries only
    /// read the trees; in a rain of 2,000 balls they were most of the broad phase's 0.8 ms.)
    /// Pairs that are `known` (that have a contact already) are left out where they are found:
    /// they are most of what a moved proxy finds in a pile, and left for later, sorting them and
    /// looking each up on one thread was most of the rain's broad phase on two threads.
    pub(crate) fn find_new_pairs_on(
        &mut self,
        pairs: &mut Vec<(ProxyKey, ProxyKey)>,
        threads: Option<&StepThreads>,
        known: impl Fn((ProxyKey, ProxyKey)) -> bool + Sync,
    ) {
        pairs.clear();
        let mut moved = std::mem::take(&mut self.move_buffer);
        moved.sort_unstable();
        moved.dedup();
        match threads.filter(|_| moved.len() >= PAIR_SEARCH_MIN_SHARED) {
            None => {
                for &key in &moved {
                    self.collect_new_pairs(key, &known, pairs);
                }
            }
            Some(threads) => {
                let mut chunk_pairs = std::mem::take(&mut self.chunk_pairs);
                chunk_pairs.resize_with(moved.len().div_ceil(PAIR_SEARCH_CHUNK), Vec::new);
                let (this, moved, known) = (&*self, &moved, &known);
                for_each_chunk_of(Some(threads), &mut chunk_pairs, 1, |chunk, found| {
                    let found = &mut found[0];
                    found.clear();
                    let start = chunk * PAIR_SEARCH_CHUNK;
                    for &key in &moved[start..(start + PAIR_SEARCH_CHUNK).min(moved.len())] {
                        this.collect_new_pairs(key, known, found);
                    }
                });
                for found in &chunk_pairs {
                    pairs.extend_from_slice(found);
                }
                self.chunk_pairs = chunk_pairs;
            }
        }
        // A pair of two moved proxies is found from both ends.
        pairs.sort_unstable();
        pairs.dedup();
        moved.clear();
        self.move_buffer = moved; // keep the allocation
    }

    /// Pushes the candidate pairs of one moved proxy that are not `known` (none if it was
    /// destroyed after it moved).
    fn collect_new_pairs(
        &self,
        key: ProxyKey,
        known: &impl Fn((ProxyKey, ProxyKey)) -> bool,
        pairs: &mut Vec<(ProxyKey, ProxyKey)>,
    ) {
        let tree = &self.trees[key.kind() as usize];
        if !tree.contains_proxy(key.proxy_id()) {
            return;
        }
        let fat = tree.fat_aabb(key.proxy_id());
        // One test for both trees: a proxy of the other kind is never `key` itself.
        let fresh = |other: ProxyKey| other != key && !known((key.min(other), key.max(other)));
        self.collect_overlaps(key, &fat, ProxyKind::Dynamic, fresh, pairs);
        if key.kind() == ProxyKind::Dynamic {
            self.collect_overlaps(key, &fat, ProxyKind::Static, fresh, pairs);
        }
    }

    /// Pushes `(min, max)` of `key` and every proxy of `kind` overlapping `fat` that passes `keep`.
    fn collect_overlaps(
        &self,
        key: ProxyKey,
        fat: &Aabb,
        kind: ProxyKind,
        keep: impl Fn(ProxyKey) -> bool,
        pairs: &mut Vec<(ProxyKey, ProxyKey)>,
    ) {
        self.trees[kind as usize].query(fat, |id| {
            let other = ProxyKey::new(kind, id);
            if keep(other) {
                pairs.push((key.min(other), key.max(other)));
            }
            true
        });
    }

    /// Calls `callback` for every proxy (static tree first) whose fat box overlaps `aabb`; it
    /// returns `false` to stop.
    pub fn query(&self, aabb: &Aabb, mut callback: impl FnMut(ProxyKey) -> bool) {
        for kind in [ProxyKind::Static, ProxyKind::Dynamic] {
            let mut go_on = true;
            self.trees[kind as usize].query(aabb, |id| {
                go_on = callback(ProxyKey::new(kind, id));
                go_on
            });
            if !go_on {
                return;
            }
        }
    }

    /// Casts a ray through both trees (static first) with the clipping protocol of
    /// [`DynamicTree::ray_cast`]; a clip found in one tree carries over to the other.
    pub fn ray_cast(&self, ray: &Ray, mut callback: impl FnMut(&Ray, ProxyKey) -> f64) {
        let mut max_distance = ray.max_distance;
        for kind in [ProxyKind::Static, ProxyKind::Dynamic] {
            let mut stopped = false;
            let clipped = Ray { max_distance, ..*ray };
            self.trees[kind as usize].ray_cast(&clipped, |r, id| {
                let v = callback(r, ProxyKey::new(kind, id));
                if v == 0.0 {
                    stopped = true;
                } else if v > 0.0 {
                    max_distance = max_distance.min(v);
                }
                v
            });
            if stopped {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(center: DVec3) -> Aabb {
        Aabb::from_center_half_extents(center, DVec3::splat(0.5))
    }

    #[test]
    fn key_packs_kind_and_index() {
        let k = ProxyKey::new(ProxyKind::Dynamic, ProxyId(5));
        assert_eq!((k.kind(), k.proxy_id(), k.raw()), (ProxyKind::Dynamic, ProxyId(5), 11));
        assert_eq!(ProxyKey::new(ProxyKind::Static, ProxyId(5)).kind(), ProxyKind::Static);
    }

    /// The threaded pair search finds the pairs the search on one thread finds, in the same
    /// order: 2,000 boxes in a loose cloud over a few static ones, all moved at once, then a
    /// few hundred moved again.
    #[test]
    fn pairs_found_on_threads_are_the_pairs_found_on_one() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("pool");
        let threads = StepThreads::begin(&pool);
        let mut bp = BroadPhase::new(0.1);
        let at = |k: usize, shift: f64| {
            let (i, j, l) = ((k % 20) as f64, ((k / 20) % 10) as f64, (k / 200) as f64);
            cube(DVec3::new(0.9 * i + shift, 0.9 * j, 0.9 * l + 0.3 * (k % 3) as f64))
        };
        for k in 0..5 {
            bp.create_proxy(cube(DVec3::new(4.0 * k as f64, 4.0, 0.0)), ProxyKind::Static, k as u64);
        }
        let keys: Vec<ProxyKey> =
            (0..2000).map(|k| bp.create_proxy(at(k, 0.0), ProxyKind::Dynamic, k as u64)).collect();
        let mut twin = bp.clone();
        for round in 0..2 {
            let (mut alone, mut shared) = (Vec::new(), Vec::new());
            bp.find_new_pairs_on(&mut alone, None, |_| false);
            twin.find_new_pairs_on(&mut shared, Some(&threads), |_| false);
            assert!(alone.len() > 2000, "round {round}: only {} pairs", alone.len());
            assert_eq!(alone, shared, "round {round}");
            for (k, &key) in keys.iter().enumerate().filter(|(k, _)| k % 7 == round) {
                let update = ProxyUpdate { key, aabb: at(k, 0.45), displacement: DVec3::ZERO };
                assert_eq!(
                    bp.move_proxy(key, update.aabb, update.displacement),
                    twin.move_proxy(key, update.aabb, update.displacement)
                );
            }
        }
    }

    #[test]
    fn no_static_static_pairs() {
        let mut bp = BroadPhase::new(0.0);
        let s1 = bp.create_proxy(cube(DVec3::ZERO), ProxyKind::Static, 1);
        let _s2 = bp.create_proxy(cube(DVec3::ZERO), ProxyKind::Static, 2);
        assert!(bp.find_pairs().is_empty());
        let d = bp.create_proxy(cube(DVec3::new(0.9, 0.0, 0.0)), ProxyKind::Dynamic, 3);
        let pairs = bp.find_pairs();
        assert_eq!(pairs.len(), 2);
        assert!(pairs.contains(&(s1.min(d), s1.max(d))));
    }

    #[test]
    fn new_pairs_only_for_moved_proxies() {
        let mut bp = BroadPhase::new(0.1);
        let a = bp.create_proxy(cube(DVec3::ZERO), ProxyKind::Dynamic, 0);
        let b = bp.create_proxy(cube(DVec3::new(0.5, 0.0, 0.0)), ProxyKind::Dynamic, 1);
        let c = bp.create_proxy(cube(DVec3::new(5.0, 0.0, 0.0)), ProxyKind::Dynamic, 2);
        assert_eq!(bp.find_new_pairs(), vec![(a, b)]);
        assert!(bp.find_new_pairs().is_empty(), "nothing moved");
        let moved = bp.update(&[ProxyUpdate {
            key: c,
            aabb: cube(DVec3::new(1.3, 0.0, 0.0)),
            displacement: DVec3::ZERO,
        }]);
        assert_eq!(moved, 1);
        assert_eq!(bp.find_new_pairs(), vec![(b, c)]);
        bp.destroy_proxy(b);
        assert_eq!(bp.find_pairs(), Vec::new());
    }
}
