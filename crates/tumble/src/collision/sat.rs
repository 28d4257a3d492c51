//! Box–box and hull–hull contact by the separating-axis test (Gregorius, "The Separating Axis Test
//! between Convex Polyhedra", GDC 2013).
//!
//! Two convex polyhedra are disjoint exactly when some face normal of either, or the cross product
//! of an edge of each, separates them. The signed separation along each candidate axis is cheap;
//! the largest one is the distance bound when positive and the (negated) penetration depth when
//! negative. Edge pairs are pruned on the Gauss map: an edge of A and an edge of B span a face of
//! the Minkowski difference only if their Gauss-map arcs (between the normals of the edge's two
//! faces, B's negated) cross — everything else cannot realise the separation and is skipped, which
//! turns the O(E_A·E_B·V) test into O(E_A·E_B).
//!
//! The winning axis decides the contact: a face axis clips the other shape's most anti-parallel
//! face against the reference face (see `clip`), an edge axis gives the closest points of the two
//! edges. Face axes get a relative bias so that resting contacts stay faces, and a [`SatCache`]
//! keeps last step's reference face unless another axis is clearly better, so a resting box keeps
//! its reference face, and its feature ids, from step to step.

use super::clip::clip_to_face;
use super::manifold::{ContactPoint, Manifold};
use super::polytope::Polytope;
use super::sat_apart::{self, Apart};
use super::segment::closest_segment_segment;
use smallvec::SmallVec;
use std::cell::Cell;
use wide::f64x4;

use crate::lanes::V3;
use crate::math::{DVec3, Transform};
use crate::shape::HullEdge;

/// Which axis separated (or least penetrated) last time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum SatFeature {
    #[default]
    None,
    FaceA(u32),
    FaceB(u32),
    EdgePair(u32, u32),
}

/// What the test found last step for this pair; pass it back next step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SatCache {
    pub feature: SatFeature,
    pub separation: f64,
}

/// The best axis of each kind, in A's local frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub struct SatQuery {
    pub face_a: (usize, f64),
    pub face_b: (usize, f64),
    /// Edge of A, edge of B, separation, axis (A → B). Separation −∞ when no pair qualifies.
    pub edges: (usize, usize, f64, DVec3),
}

impl SatQuery {
    /// The largest separation over all axes: the penetration depth when negative.
    pub fn max_separation(&self) -> f64 {
        self.face_a.1.max(self.face_b.1).max(self.edges.2)
    }
}

/// An edge pair must beat the best face by this fraction of |separation| (plus an absolute slop).
const EDGE_REL_TOLERANCE: f64 = 0.1;
/// Face axes within this fraction of |separation| (plus slop) count as equally good: the larger
/// face is then the reference, and a cached face is kept.
const KEEP_REL_TOLERANCE: f64 = 0.05;
/// The edge-pair part of a [`SatQuery`] when no pair qualifies.
const NO_EDGE_PAIR: (usize, usize, f64, DVec3) = (0, 0, f64::NEG_INFINITY, DVec3::ZERO);
/// Edges closer than this sine of an angle to parallel give no axis (their faces' normals do).
const PARALLEL_SINE: f64 = 0.005;

/// B seen from A's frame: B's vertices, face normals and face offsets mapped once (`map_all`),
/// with A's own read out of the polytope once, then reused by every query. Before that, each is
/// mapped when asked for: the early outs of `collide_polytopes` (last step's axis still
/// separates) read one face and a vertex or two, and most pairs end there.
struct Frames<'p, 'h> {
    a: &'p Polytope<'h>,
    b: &'p Polytope<'h>,
    b_in_a: Transform,
    /// Empty until `map_all`.
    lists: Lists,
}

/// The flat lists of a pair. Kept per thread and reused by the next pair (`SCRATCH`): held
/// inline on the stack instead, a dozen lists of a few dozen entries made a frame of kilobytes
/// that was copied for every pair, the early outs included.
#[derive(Default)]
struct Lists {
    verts_b: Vec<DVec3>,
    normals_b: Vec<DVec3>,
    offsets_b: Vec<f64>,
    /// A's vertices, face normals and offsets: the queries' inner loops then read arrays rather
    /// than asking the polytope (a box scales the shared unit cube's corner on every read).
    verts_a: Vec<DVec3>,
    normals_a: Vec<DVec3>,
    offsets_a: Vec<f64>,
    /// `normals_b`, `verts_b` and `verts_a` again by coordinate (x, y, z): a product with all of
    /// them is then a loop the compiler runs in vector lanes (`normals_dot`, `lowest_along`).
    normals_b_by_axis: [Vec<f64>; 3],
    verts_b_by_axis: [Vec<f64>; 3],
    verts_a_by_axis: [Vec<f64>; 3],
}

impl Lists {
    fn clear(&mut self) {
        for list in [&mut self.verts_b, &mut self.normals_b, &mut self.verts_a, &mut self.normals_a] {
            list.clear();
        }
        self.offsets_b.clear();
        self.offsets_a.clear();
        for list in self
            .normals_b_by_axis
            .iter_mut()
            .chain(&mut self.verts_b_by_axis)
            .chain(&mut self.verts_a_by_axis)
        {
            list.clear();
        }
    }
}

thread_local! {
    /// The lists of the last full query on this thread, taken by the next (`Frames::map_all`)
    /// and given back when its frames drop: once grown, they allocate nothing.
    static SCRATCH: Cell<Lists> = Cell::new(Lists::default());
}

impl Drop for Frames<'_, '_> {
    fn drop(&mut self) {
        if self.lists.verts_b.capacity() > 0 {
            SCRATCH.set(std::mem::take(&mut self.lists));
        }
    }
}

impl<'p, 'h> Frames<'p, 'h> {
    fn new(a: &'p Polytope<'h>, pose_a: &Transform, b: &'p Polytope<'h>, pose_b: &Transform) -> Self {
        let mut frames = Frames::unmapped(a, pose_a, b, pose_b);
        frames.map_all();
        frames
    }

    /// The frames with nothing of B mapped yet.
    fn unmapped(a: &'p Polytope<'h>, pose_a: &Transform, b: &'p Polytope<'h>, pose_b: &Transform) -> Self {
        let b_in_a = pose_a.inverse().mul_transform(pose_b);
        Frames { a, b, b_in_a, lists: Lists::default() }
    }

    /// Maps all of B's vertices and face normals (once; the queries read them from the lists),
    /// each as `vertex_b` and `normal_b` map one: mapped alone or in the lists, the same bits.
    /// Fills A's lists and the lists by coordinate too.
    fn map_all(&mut self) {
        if !self.lists.verts_b.is_empty() {
            return;
        }
        let mut lists = SCRATCH.take();
        lists.clear();
        let (a, b, b_in_a) = (self.a, self.b, self.b_in_a);
        lists.verts_b.extend((0..b.vertex_count()).map(|i| b_in_a.transform_point(b.vertex(i))));
        lists.normals_b.extend((0..b.face_count()).map(|f| b_in_a.rotation * b.face_normal(f)));
        // n_A · (R p + t) = n_B · p + n_A · t for p on B's face.
        let normals_b = &lists.normals_b;
        lists
            .offsets_b
            .extend(normals_b.iter().enumerate().map(|(f, n)| b.face_offset(f) + n.dot(b_in_a.translation)));
        lists.verts_a.extend((0..a.vertex_count()).map(|i| a.vertex(i)));
        lists.normals_a.extend((0..a.face_count()).map(|f| a.face_normal(f)));
        lists.offsets_a.extend((0..a.face_count()).map(|f| a.face_offset(f)));
        for axis in 0..3 {
            lists.normals_b_by_axis[axis].extend(lists.normals_b.iter().map(|n| n[axis]));
            lists.verts_b_by_axis[axis].extend(lists.verts_b.iter().map(|v| v[axis]));
            lists.verts_a_by_axis[axis].extend(lists.verts_a.iter().map(|v| v[axis]));
        }
        self.lists = lists;
    }

    /// B's vertex `i` in A's frame: from the list once mapped, else mapped now (the same bits).
    #[inline]
    fn vertex_b(&self, i: usize) -> DVec3 {
        match self.lists.verts_b.get(i) {
            Some(&v) => v,
            None => self.b_in_a.transform_point(self.b.vertex(i)),
        }
    }

    /// B's face normal `f` in A's frame, as `vertex_b`.
    #[inline]
    fn normal_b(&self, f: usize) -> DVec3 {
        match self.lists.normals_b.get(f) {
            Some(&n) => n,
            None => self.b_in_a.rotation * self.b.face_normal(f),
        }
    }

    fn support_b(&self, dir: DVec3) -> DVec3 {
        self.vertex_b(self.b.support_index(self.b_in_a.rotation.inverse() * dir))
    }

    fn face_a(&self, f: usize) -> f64 {
        let n = self.a.face_normal(f);
        n.dot(self.support_b(-n)) - self.a.face_offset(f)
    }

    /// The gap between the shapes along the unit axis `n` (A's frame, pointing from A to B):
    /// B's lowest point along it minus A's highest.
    fn separation_along(&self, n: DVec3) -> f64 {
        n.dot(self.support_b(-n)) - n.dot(self.a.vertex(self.a.support_index(n)))
    }

    fn face_b(&self, f: usize) -> f64 {
        let n = self.normal_b(f);
        let on_face = self.vertex_b(self.b.face_vertices(f)[0] as usize);
        n.dot(self.a.vertex(self.a.support_index(-n)) - on_face)
    }

    /// `face_a` once mapped: B's lowest mapped vertex along the face normal, less the offset.
    /// (Over the mapped vertices, the lowest is found without turning the normal into B's frame
    /// first; it may differ from `face_a`'s in the last bits.)
    #[inline]
    fn face_a_mapped(&self, f: usize) -> f64 {
        lowest_along(&self.lists.verts_b_by_axis, self.lists.normals_a[f]) - self.lists.offsets_a[f]
    }

    /// `face_b` once mapped: A's lowest vertex along B's face normal, less that face's offset.
    #[inline]
    fn face_b_mapped(&self, f: usize) -> f64 {
        lowest_along(&self.lists.verts_a_by_axis, self.lists.normals_b[f]) - self.lists.offsets_b[f]
    }

    /// A's vertex `i`: from the list once mapped, else from the polytope (the same bits).
    #[inline]
    fn vertex_a(&self, i: usize) -> DVec3 {
        match self.lists.verts_a.get(i) {
            Some(&v) => v,
            None => self.a.vertex(i),
        }
    }

    /// An edge of A: its start and its direction (end − start), in A's frame.
    fn edge_a(&self, e: &HullEdge) -> (DVec3, DVec3) {
        let start = self.vertex_a(e.vertices[0] as usize);
        (start, self.vertex_a(e.vertices[1] as usize) - start)
    }

    /// An edge of B: its start and its direction, in A's frame.
    fn edge_b(&self, e: &HullEdge) -> (DVec3, DVec3) {
        let start = self.vertex_b(e.vertices[0] as usize);
        (start, self.vertex_b(e.vertices[1] as usize) - start)
    }

    fn query(&self) -> SatQuery {
        match self.query_within(f64::INFINITY) {
            Ok(q) => q,
            Err(_) => unreachable!("no axis separates by more than infinity"),
        }
    }

    /// The query, or — as soon as one face axis separates the shapes by more than `margin` —
    /// that axis and its separation: the pair is then apart, and the other axes need not be
    /// measured (most pairs whose fat boxes overlap are apart, and the edge pairs are the
    /// expensive part).
    fn query_within(&self, margin: f64) -> Result<SatQuery, (SatFeature, f64)> {
        self.query_with_sets(margin, self.b.edges().len() <= 128)
    }

    /// `query_within`, listing the edge pairs that pass the first sign test from bit sets of B's
    /// edges (`sets`, at most 128 edges) or testing every pair: the same result either way.
    fn query_with_sets(&self, margin: f64, sets: bool) -> Result<SatQuery, (SatFeature, f64)> {
        let (face_a, face_b) = self.face_axes(margin)?;
        Ok(SatQuery { face_a, face_b, edges: self.edge_axes(sets) })
    }

    /// The best face axis of A and of B (index, separation), or — as soon as one separates the
    /// shapes by more than `margin` — that axis and its separation.
    #[allow(clippy::type_complexity)]
    fn face_axes(&self, margin: f64) -> Result<((usize, f64), (usize, f64)), (SatFeature, f64)> {
        debug_assert_eq!(self.lists.normals_b.len(), self.b.face_count(), "B is mapped (`map_all`)");
        let best = |count: usize, f: &dyn Fn(usize) -> f64| {
            let mut best = (0, f64::NEG_INFINITY);
            for i in 0..count {
                let s = f(i);
                if s > best.1 {
                    best = (i, s);
                    if s > margin {
                        break;
                    }
                }
            }
            best
        };
        let face_a = best(self.lists.normals_a.len(), &|f| self.face_a_mapped(f));
        if face_a.1 > margin {
            return Err((SatFeature::FaceA(face_a.0 as u32), face_a.1));
        }
        let face_b = best(self.lists.normals_b.len(), &|f| self.face_b_mapped(f));
        if face_b.1 > margin {
            return Err((SatFeature::FaceB(face_b.0 as u32), face_b.1));
        }
        Ok((face_a, face_b))
    }

    /// The best edge pair: edge of A, edge of B, separation, axis (A → B); separation −∞ when no
    /// pair qualifies. `sets`: list the pairs that pass the first sign test from bit sets of B's
    /// edges (at most 128) rather than testing every pair — the same result either way.
    fn edge_axes(&self, sets: bool) -> (usize, usize, f64, DVec3) {
        // The Minkowski-face test of an edge pair reads four products of one edge's direction
        // with the normals of the other's two faces (faces[0].normal × faces[1].normal points
        // along the edge; B's normals are negated for the difference A − B, which flips no sign
        // that matters). Per edge of A, its products with B's face normals are taken once into
        // `dir_a_on_b` (they also give B's outline seen along it); A's face normals against B's
        // edges are taken only for the few pairs that pass the first test. (Tabulating all of
        // them up front cost more than it saved: two kilobyte-sized tables written and copied
        // for every query.)
        let (edges_a, edges_b) = (self.a.edges(), self.b.edges());
        // Each list is filled on the stack, then read through a plain slice: indexing the
        // small vector itself asks on every read whether it has moved to the heap.
        let mut dirs_a: SmallVec<[DVec3; 32]> = SmallVec::new();
        dirs_a.extend(edges_a.iter().map(|e| self.edge_a(e).1));
        let dirs_a = &dirs_a[..];
        let mut dirs_b: SmallVec<[DVec3; 32]> = SmallVec::new();
        dirs_b.extend(edges_b.iter().map(|e| self.edge_b(e).1));
        let dirs_b = &dirs_b[..];
        let mut dir_a_on_b: SmallVec<[f64; 64]> = SmallVec::new();
        dir_a_on_b.resize(self.lists.normals_b.len(), 0.0);
        let dir_a_on_b = &mut dir_a_on_b[..];
        let centre_a = self.a.interior_point();
        let mut edges = NO_EDGE_PAIR;
        // The first sign test (`cba·dba < 0`: B's edge lies on B's outline seen along A's edge)
        // passes few of B's edges, and as a branch per pair it is mispredicted often. Where B has
        // at most 128 edges, each face of B marks its edges in a bit set; the edges on the outline
        // seen along an A edge are then those with exactly one face the A edge points away from
        // (the sign bits of `dir_a_on_b`): the exclusive or of those faces' sets, a few bit
        // operations per face in place of a branch per edge. Only the edges in it take the exact
        // tests below, in the same order, so the same pairs pass and the same one wins (a product
        // below zero has factors of opposite sign bits: the set holds every edge that can pass).
        let mut face_edges_b: SmallVec<[u128; 32]> = SmallVec::new();
        // The second sign test (`adc·bdc < 0`: A's edge lies on A's outline seen along B's edge)
        // likewise: per face of A, the set of B's edges it faces away from (the sign bits of
        // `n · dir_b`, each product taken as the test takes it); an edge of A can pass with the B
        // edges where its two faces' sets differ. The candidates are then the edges in both sets,
        // about one per edge of A where the first set alone left six or seven.
        let mut away_from_a_face: SmallVec<[u128; 32]> = SmallVec::new();
        if sets {
            face_edges_b.resize(self.lists.normals_b.len(), 0);
            for (ib, eb) in edges_b.iter().enumerate() {
                for f in eb.faces {
                    face_edges_b[f as usize] |= 1 << ib;
                }
            }
            // B's edge directions in vector lanes, four at a time (zeros past the last).
            let dirs_b_by_four: SmallVec<[V3<f64x4>; 8]> = (0..edges_b.len().div_ceil(4))
                .map(|k| V3::from_fn(|j| dirs_b.get(4 * k + j).copied().unwrap_or(DVec3::ZERO)))
                .collect();
            let live = if dirs_b.len() == 128 { u128::MAX } else { (1u128 << dirs_b.len()) - 1 };
            away_from_a_face
                .extend(self.lists.normals_a.iter().map(|&n| signs_below_zero(&dirs_b_by_four, n) & live));
        }
        let face_edges_b = &face_edges_b[..];
        let away_from_a_face = &away_from_a_face[..];
        let mut passing: SmallVec<[u32; 128]> = SmallVec::new();
        passing.resize(edges_b.len(), 0);
        let passing = &mut passing[..];
        for (ia, ea) in edges_a.iter().enumerate() {
            let [f0, f1] = ea.faces.map(|f| self.lists.normals_a[f as usize]);
            normals_dot(&self.lists.normals_b_by_axis, dirs_a[ia], dir_a_on_b);
            let candidates = if sets {
                let outline_b = dir_a_on_b.iter().zip(face_edges_b).fold(0u128, |set, (d, edges)| {
                    set ^ (edges & 0u128.wrapping_sub(u128::from(d.is_sign_negative())))
                });
                let [g0, g1] = ea.faces.map(|f| away_from_a_face[f as usize]);
                EdgeCandidates::Set(outline_b & (g0 ^ g1))
            } else {
                EdgeCandidates::All(0..edges_b.len())
            };
            // The sign tests pass a pair or two per edge of A, unpredictably: as branches they
            // are mispredicted often. Each pair's outcome is written instead (the index always,
            // the count advanced only on a pass), and only the pairs that passed measure their
            // axis, in the same order.
            let mut passed = 0;
            for ib in candidates {
                let eb = &edges_b[ib];
                let cba = dir_a_on_b[eb.faces[0] as usize];
                let dba = dir_a_on_b[eb.faces[1] as usize];
                let (adc, bdc) = (f0.dot(dirs_b[ib]), f1.dot(dirs_b[ib]));
                passing[passed] = ib as u32;
                passed += usize::from((cba * dba < 0.0) & (adc * bdc < 0.0) & (cba * bdc < 0.0));
            }
            let start_a = self.lists.verts_a[ea.vertices[0] as usize];
            for &ib in &passing[..passed] {
                let ib = ib as usize;
                let start_b = self.lists.verts_b[edges_b[ib].vertices[0] as usize];
                if let Some((sep, n)) = edge_axis(start_a, dirs_a[ia], start_b, dirs_b[ib], centre_a) {
                    if sep > edges.2 {
                        edges = (ia, ib, sep, n);
                    }
                }
            }
        }
        edges
    }
}

/// The edges of B a query tests against one edge of A, in increasing order: those in a bit set
/// (B's outline seen along the A edge), or all of them.
enum EdgeCandidates {
    Set(u128),
    All(std::ops::Range<usize>),
}

impl Iterator for EdgeCandidates {
    type Item = usize;

    #[inline]
    fn next(&mut self) -> Option<usize> {
        match self {
            EdgeCandidates::Set(set) if *set == 0 => None,
            EdgeCandidates::Set(set) => {
                let i = set.trailing_zeros() as usize;
                *set &= *set - 1;
                Some(i)
            }
            EdgeCandidates::All(range) => range.next(),
        }
    }
}

/// The set of the directions `d` (given four at a time in vector lanes, at most 128) with `n · d`
/// negative, or `−0`: its sign bit, with the product taken as `DVec3::dot` takes it (the same
/// bits). The places past the last direction hold zeros, whose bits the caller masks out.
#[inline]
fn signs_below_zero(dirs_by_four: &[V3<f64x4>], n: DVec3) -> u128 {
    let n = V3::from_fn(|_| n);
    dirs_by_four
        .iter()
        .enumerate()
        .fold(0, |set, (k, d)| set | (u128::from(d.dot(n).to_bitmask()) << (4 * k)))
}

/// `out[j] = n_j · d` for the normals given by coordinate (`[xs, ys, zs]`), in the order of
/// `DVec3::dot` (the same bits).
/// (An indexed loop: written with an iterator, or through a shared dot helper, the hull pairs'
/// bench ran 6% slower.)
#[inline]
#[allow(clippy::needless_range_loop)]
fn normals_dot(normals_by_axis: &[Vec<f64>; 3], d: DVec3, out: &mut [f64]) {
    let count = out.len();
    let (xs, ys, zs) =
        (&normals_by_axis[0][..count], &normals_by_axis[1][..count], &normals_by_axis[2][..count]);
    for j in 0..count {
        out[j] = xs[j] * d.x + ys[j] * d.y + zs[j] * d.z;
    }
}

/// The least of `n · p` over the points (given by coordinate, `[xs, ys, zs]`). Four running
/// minima, one per vector lane, then the least of them: a minimum does not depend on the order.
#[inline]
fn lowest_along(points_by_axis: &[Vec<f64>; 3], n: DVec3) -> f64 {
    let count = points_by_axis[0].len();
    let (xs, ys, zs) =
        (&points_by_axis[0][..count], &points_by_axis[1][..count], &points_by_axis[2][..count]);
    let dot = |j: usize| xs[j] * n.x + ys[j] * n.y + zs[j] * n.z;
    let mut low = [f64::INFINITY; 4];
    let whole = count - count % 4;
    for start in (0..whole).step_by(4) {
        for (lane, low) in low.iter_mut().enumerate() {
            let d = dot(start + lane);
            *low = if d < *low { d } else { *low };
        }
    }
    for (j, low) in (whole..count).zip(&mut low) {
        let d = dot(j);
        *low = if d < *low { d } else { *low };
    }
    low[0].min(low[1]).min(low[2].min(low[3]))
}

/// The cross product of two edge directions and its length; `None` when the edges are within
/// [`PARALLEL_SINE`] of parallel and so give no axis of their own (their faces' normals do).
pub(crate) fn edge_cross(da: DVec3, db: DVec3) -> Option<(DVec3, f64)> {
    let axis = da.cross(db);
    let len = axis.length();
    if len < PARALLEL_SINE * (da.length_squared() * db.length_squared()).sqrt() {
        return None;
    }
    Some((axis, len))
}

/// Separation of two edges along their common normal, oriented out of A (away from A's
/// interior point `centre_a`); `None` for nearly parallel edges, whose axis a face normal covers.
fn edge_axis(pa: DVec3, da: DVec3, pb: DVec3, db: DVec3, centre_a: DVec3) -> Option<(f64, DVec3)> {
    let (axis, len) = edge_cross(da, db)?;
    let mut n = axis / len;
    if n.dot(pa - centre_a) < 0.0 {
        n = -n;
    }
    Some((n.dot(pb - pa), n))
}

/// The separating-axis queries alone (for tests and diagnostics).
pub fn sat_query(a: &Polytope, pose_a: &Transform, b: &Polytope, pose_b: &Transform) -> SatQuery {
    Frames::new(a, pose_a, b, pose_b).query()
}

/// Contact manifold of two polyhedra, or `None` when they are more than `margin` apart.
pub fn collide_polytopes(
    a: &Polytope,
    pose_a: &Transform,
    b: &Polytope,
    pose_b: &Transform,
    margin: f64,
    cache: &mut SatCache,
) -> Option<Manifold> {
    let mut frames = Frames::unmapped(a, pose_a, b, pose_b);
    // Last step's axis, re-measured: if it still separates, nothing else needs testing.
    let cached = match cache.feature {
        SatFeature::FaceA(f) if (f as usize) < a.face_count() => Some(frames.face_a(f as usize)),
        SatFeature::FaceB(f) if (f as usize) < b.face_count() => Some(frames.face_b(f as usize)),
        _ => None,
    };
    if let Some(s) = cached {
        if s > margin {
            cache.separation = s;
            return None;
        }
    }
    // An edge pair that separated last step: its axis now, with the separation measured by the
    // support points (the edges themselves need no longer be the closest features along it, so
    // their distance would not do). Only for the early out: a face is what the hysteresis below
    // keeps.
    if let SatFeature::EdgePair(ia, ib) = cache.feature {
        if let (Some(ea), Some(eb)) = (a.edges().get(ia as usize), b.edges().get(ib as usize)) {
            let ((start_a, dir_a), (start_b, dir_b)) = (frames.edge_a(ea), frames.edge_b(eb));
            if let Some((_, n)) = edge_axis(start_a, dir_a, start_b, dir_b, a.interior_point()) {
                let s = frames.separation_along(n);
                if s > margin {
                    cache.separation = s;
                    return None;
                }
            }
        }
    }
    frames.map_all();
    let (face_a, face_b) = match frames.face_axes(margin) {
        Ok(faces) => faces,
        Err((feature, separation)) => {
            *cache = SatCache { feature, separation };
            return None;
        }
    };
    // A face axis shows the shapes apart: GJK's closest features stand in for the edge pairs
    // (`sat_apart`). Overlapping or touching, every edge pair is tested.
    let apart = if face_a.1.max(face_b.1) > 0.0 {
        let lists = &frames.lists;
        let start = if face_a.1 >= face_b.1 { lists.normals_a[face_a.0] } else { -lists.normals_b[face_b.0] };
        sat_apart::apart(a, b, &frames.b_in_a, start, margin, &lists.verts_a, &lists.verts_b)
    } else {
        None
    };
    let edges = match &apart {
        Some(Apart { edges: Some((ea, eb)), distance, normal, .. }) => (*ea, *eb, *distance, *normal),
        Some(_) => NO_EDGE_PAIR,
        None => frames.edge_axes(b.edges().len() <= 128),
    };
    let q = SatQuery { face_a, face_b, edges };
    let best = q.max_separation();
    let distance = apart.as_ref().map_or(best, |found| found.distance);
    if distance > margin {
        cache.feature = if q.edges.2 == best {
            SatFeature::EdgePair(q.edges.0 as u32, q.edges.1 as u32)
        } else if q.face_a.1 == best {
            SatFeature::FaceA(q.face_a.0 as u32)
        } else {
            SatFeature::FaceB(q.face_b.0 as u32)
        };
        cache.separation = distance;
        return None;
    }
    let slop = 0.0025_f64.min(0.01 * a.bounding_radius().min(b.bounding_radius()));
    let face_sep = q.face_a.1.max(q.face_b.1);
    // Between two faces that separate about equally well, the larger one makes the better
    // reference (a box on the ground clips against the ground, whichever way it is tilted). The
    // rule looks at both shapes alike, so swapping A and B picks the same physical face.
    let face_tol = KEEP_REL_TOLERANCE * face_sep.abs() + slop;
    let (area_a, area_b) = (a.face_area(q.face_a.0), b.face_area(q.face_b.0));
    let b_wins = if (q.face_a.1 - q.face_b.1).abs() <= face_tol
        && (area_a - area_b).abs() > 0.01 * area_a.max(area_b)
    {
        area_b > area_a
    } else {
        q.face_b.1 > q.face_a.1
    };
    let mut feature =
        if b_wins { SatFeature::FaceB(q.face_b.0 as u32) } else { SatFeature::FaceA(q.face_a.0 as u32) };
    // Apart, with neither a face nor an edge pair near the distance (a corner nearest a corner
    // or an edge): the contact is the closest points themselves. Clipped to a face, the corner's
    // points would be measured along that face's normal, not the way the shapes approach.
    if let Some(found) = apart.filter(|found| {
        found.edges.is_none() && face_sep < found.distance - (KEEP_REL_TOLERANCE * found.distance + slop)
    }) {
        *cache = SatCache { feature, separation: face_sep };
        return Some(closest_point_contact(pose_a, pose_b, &found));
    }
    if q.edges.2 > face_sep + EDGE_REL_TOLERANCE * face_sep.abs() + slop {
        feature = SatFeature::EdgePair(q.edges.0 as u32, q.edges.1 as u32);
    }
    // Hysteresis: keep last step's face while it stays within tolerance of the best axis (of
    // the distance, apart).
    if let (Some(s), SatFeature::FaceA(_) | SatFeature::FaceB(_)) = (cached, cache.feature) {
        if s >= distance - (KEEP_REL_TOLERANCE * distance.abs() + slop) {
            feature = cache.feature;
        }
    }
    let manifold = match feature {
        SatFeature::FaceA(f) => face_contact(a, pose_a, b, pose_b, f as usize, false, margin),
        SatFeature::FaceB(f) => face_contact(b, pose_b, a, pose_a, f as usize, true, margin),
        _ => None,
    };
    // Apart, the face's clipped points may all lie well above the distance (the nearest corner
    // cut away past the face's rim): they would let the shapes close by more than the gap in
    // one step. The closest points are the contact then.
    if let Some(found) = &apart {
        if manifold
            .as_ref()
            .is_some_and(|m| m.min_separation() > found.distance + KEEP_REL_TOLERANCE * found.distance + slop)
        {
            cache.feature = feature;
            cache.separation = face_sep;
            return Some(closest_point_contact(pose_a, pose_b, found));
        }
    }
    let manifold = match manifold {
        Some(m) => Some(m),
        // No face points survived clipping (a corner just past the rim): use the edge axis.
        None if q.edges.2 > f64::NEG_INFINITY => {
            feature = SatFeature::EdgePair(q.edges.0 as u32, q.edges.1 as u32);
            Some(edge_contact(&frames, pose_a, pose_b, q.edges.0, q.edges.1, q.edges.3))
        }
        // Apart, with no edge pair closest: the closest points themselves.
        None => apart.map(|found| closest_point_contact(pose_a, pose_b, &found)),
    };
    cache.feature = feature;
    cache.separation = match feature {
        SatFeature::FaceA(_) => q.face_a.1,
        SatFeature::FaceB(_) => q.face_b.1,
        _ => q.edges.2,
    };
    manifold.filter(|m| m.min_separation() <= margin)
}

/// Face contact with `reference`'s face `ref_face` as the reference face. `reference_is_b` says the
/// roles are swapped, so the manifold normal must be flipped to point from A to B.
fn face_contact(
    reference: &Polytope,
    ref_pose: &Transform,
    incident: &Polytope,
    inc_pose: &Transform,
    ref_face: usize,
    reference_is_b: bool,
    margin: f64,
) -> Option<Manifold> {
    let inc_in_ref = ref_pose.inverse().mul_transform(inc_pose);
    let n_ref = reference.face_normal(ref_face);
    // The incident face is the one most anti-parallel to the reference normal.
    let inc_face = incident.best_face(-(inc_in_ref.rotation.inverse() * n_ref));
    // The lists are filled in place: collected and moved, each would be copied whole.
    let mut ref_loop: SmallVec<[DVec3; 16]> = SmallVec::new();
    ref_loop.extend(reference.face_vertices(ref_face).iter().map(|&v| reference.vertex(v as usize)));
    let mut inc_poly: SmallVec<[DVec3; 16]> = SmallVec::new();
    inc_poly.extend(
        incident
            .face_vertices(inc_face)
            .iter()
            .map(|&v| inc_in_ref.transform_point(incident.vertex(v as usize))),
    );
    let clipped = clip_to_face(&ref_loop, n_ref, &inc_poly, margin);
    if clipped.is_empty() {
        return None;
    }
    let normal_ref_world = ref_pose.rotation * n_ref;
    let normal_world = if reference_is_b { -normal_ref_world } else { normal_ref_world };
    let (pose_a, pose_b) = if reference_is_b { (inc_pose, ref_pose) } else { (ref_pose, inc_pose) };
    let face_bits = (u32::from(reference_is_b) << 30)
        | ((ref_face as u32 & 0x7F) << 23)
        | ((inc_face as u32 & 0x7F) << 16);
    let mut candidates: SmallVec<[ContactPoint; 16]> = SmallVec::new();
    candidates.extend(clipped.iter().map(|c| {
        let mid = ref_pose.transform_point(c.point - n_ref * (0.5 * c.separation));
        ContactPoint::new(pose_a, pose_b, normal_world, mid, c.separation, face_bits | u32::from(c.tag))
    }));
    Manifold::from_candidates(normal_world, &candidates)
}

/// Contact of two shapes apart at their closest points (a corner against a corner or an edge,
/// past the rims of the faces): one point midway, along the line between them.
fn closest_point_contact(pose_a: &Transform, pose_b: &Transform, found: &Apart) -> Manifold {
    let normal_world = pose_a.rotation * found.normal;
    let mid = pose_a.transform_point(0.5 * (found.point_a + found.point_b));
    let mut m = Manifold::new(normal_world);
    m.push(ContactPoint::new(pose_a, pose_b, normal_world, mid, found.distance, CLOSEST_POINTS_ID));
    m
}

/// The feature id of a closest-points contact: apart from face ids (bit 31 clear) and edge ids
/// (bit 31 set, below 2^30).
const CLOSEST_POINTS_ID: u32 = 0xC000_0000;

/// Edge–edge contact: one point midway between the closest points of the two edges.
fn edge_contact(
    frames: &Frames,
    pose_a: &Transform,
    pose_b: &Transform,
    ea: usize,
    eb: usize,
    n_in_a: DVec3,
) -> Manifold {
    let edge_a = frames.a.edges()[ea];
    let edge_b = frames.b.edges()[eb];
    let (pa, qa) =
        (frames.a.vertex(edge_a.vertices[0] as usize), frames.a.vertex(edge_a.vertices[1] as usize));
    let (pb, qb) = (
        frames.lists.verts_b[edge_b.vertices[0] as usize],
        frames.lists.verts_b[edge_b.vertices[1] as usize],
    );
    let (s, t) = closest_segment_segment(pa, qa, pb, qb);
    let ca = pa + (qa - pa) * s;
    let cb = pb + (qb - pb) * t;
    let normal_world = pose_a.rotation * n_in_a;
    let mid = pose_a.transform_point(0.5 * (ca + cb));
    let id = 0x8000_0000 | ((ea as u32 & 0x7FFF) << 15) | (eb as u32 & 0x7FFF);
    let mut m = Manifold::new(normal_world);
    m.push(ContactPoint::new(pose_a, pose_b, normal_world, mid, n_in_a.dot(cb - ca), id));
    m
}

#[cfg(test)]
#[path = "sat_tests.rs"]
mod tests;
