//! EPA, the expanding polytope algorithm (van den Bergen 2001): penetration depth and direction of
//! two overlapping convex cores.
//!
//! When GJK reports overlap, the origin lies inside `A − B`. The penetration depth is the distance
//! from the origin to the boundary of `A − B`, and the direction to that nearest boundary point is
//! the contact normal: translating B by `depth · normal` separates the cores. EPA starts from a
//! tetrahedron of support points around the origin and grows it: take the face nearest the
//! origin, fetch the support point along its normal; if that point is no farther than the face,
//! the face lies on the boundary and we are done; otherwise cut out every face that sees the new
//! point and re-triangulate the hole (a fan from the horizon edges to the point). Faces are kept
//! outward-wound, so face normals point away from the origin.
//!
//! GJK may stop with a point, segment or triangle when the origin lies on it (touching cores); the
//! simplex is then "blown up" to a tetrahedron with extra support points first.

use std::cell::Cell;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::gjk::{ConvexPair, Simplex, SupportPoint};
use crate::math::DVec3;

/// Penetration of two cores, in A's local frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub struct EpaResult {
    /// Penetration depth, ≥ 0.
    pub depth: f64,
    /// Unit normal from A towards B: move B by `depth · normal` to separate.
    pub normal: DVec3,
    /// Deepest point of A inside B, and of B inside A (`point_b − point_a = −depth · normal`).
    pub point_a: DVec3,
    pub point_b: DVec3,
}

#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
struct Face {
    v: [usize; 3],
    normal: DVec3,
    distance: f64,
}

const MAX_ITERATIONS: usize = 128;

// The polytope's lists, on the stack up to the sizes most calls stay within (a few dozen
// iterations); beyond, they move to the heap.
type Vertices = SmallVec<[SupportPoint; 32]>;
type Horizon = SmallVec<[(usize, usize); 16]>;
thread_local! {
    /// The edge map of the last EPA call on this thread, emptied and reused by the next: the map
    /// keeps its table, so a step allocates nothing for it once the tables have grown.
    static EDGE_OWNERS: Cell<FxHashMap<(usize, usize), usize>> = Cell::new(FxHashMap::default());
}

/// A polytope this large has stopped converging; its nearest face is as good as it gets.
const MAX_FACES: usize = 1024;
/// Converged when the support along the nearest face's normal is within this (× scale) of it.
const REL_TOLERANCE: f64 = 1e-7;

/// Penetration depth and normal from GJK's final simplex. `None` only if `A − B` is flat (both
/// cores lower-dimensional, e.g. two segments), where depth is not defined by a polytope.
pub fn epa(pair: &ConvexPair, simplex: &Simplex) -> Option<EpaResult> {
    let scale = pair.scale();
    let tol = REL_TOLERANCE * scale;
    // Filled in place: the list is two kilobytes on the stack, copied whole when returned.
    let mut verts = Vertices::new();
    if !blow_up(pair, simplex, 1e-9 * scale, &mut verts) {
        return None;
    }

    // Wind the tetrahedron so each face normal points away from the opposite vertex.
    let n012 = (verts[1].w - verts[0].w).cross(verts[2].w - verts[0].w);
    if n012.dot(verts[3].w - verts[0].w) > 0.0 {
        verts.swap(1, 2);
    }
    let mut edge_owner = EDGE_OWNERS.take();
    edge_owner.clear();
    let mut poly = Polytope::default();
    poly.edge_owner = edge_owner;
    for v in [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]] {
        poly.add_face(&verts, v);
    }
    let mut best = poly.nearest_face();
    for _ in 0..MAX_ITERATIONS {
        let face = poly.faces[best];
        let p = pair.support(face.normal);
        if face.normal.dot(p.w) - face.distance <= tol || poly.faces.len() > MAX_FACES {
            break;
        }
        let new_index = verts.len();
        verts.push(p);
        let horizon = poly.carve(&verts, best, p.w, 1e-12 * scale);
        for (a, b) in horizon {
            poly.add_face(&verts, [a, b, new_index]);
        }
        best = poly.nearest_face();
    }
    let face = poly.faces[best];
    EDGE_OWNERS.set(poly.edge_owner);
    let lam = barycentric(face.normal * face.distance, face.v.map(|i| verts[i].w));
    let mut point_a = DVec3::ZERO;
    let mut point_b = DVec3::ZERO;
    for k in 0..3 {
        point_a += verts[face.v[k]].a * lam[k];
        point_b += verts[face.v[k]].b * lam[k];
    }
    Some(EpaResult { depth: face.distance.max(0.0), normal: face.normal, point_a, point_b })
}

/// The polytope's surface: triangles (dead ones kept so indices stay valid) and a map from each
/// directed edge to the face that owns it, for walking to neighbours. (Keyed by a pair of small
/// indices, the map hashes with Fx: the default SipHash, made to resist chosen keys, cost a
/// sizeable part of each EPA call.)
#[derive(Default, serde::Serialize, serde::Deserialize)]
struct Polytope {
    faces: SmallVec<[Face; 64]>,
    alive: SmallVec<[bool; 64]>,
    edge_owner: FxHashMap<(usize, usize), usize>,
}

impl Polytope {
    fn add_face(&mut self, verts: &[SupportPoint], v: [usize; 3]) {
        let [a, b, c] = v.map(|i| verts[i].w);
        let face = match (b - a).cross(c - a).try_normalize() {
            Some(normal) => Face { v, normal, distance: normal.dot(a) },
            // A sliver face has no direction; never pick it as the nearest.
            None => Face { v, normal: DVec3::ZERO, distance: f64::INFINITY },
        };
        for k in 0..3 {
            self.edge_owner.insert((v[k], v[(k + 1) % 3]), self.faces.len());
        }
        self.faces.push(face);
        self.alive.push(true);
    }

    fn nearest_face(&self) -> usize {
        let mut best = usize::MAX;
        for (i, f) in self.faces.iter().enumerate() {
            if self.alive[i] && (best == usize::MAX || f.distance < self.faces[best].distance) {
                best = i;
            }
        }
        best
    }

    /// Removes the faces that see `p` — flooding out from `start`, so the hole is connected —
    /// and returns the hole's boundary edges, wound like the removed faces. Faces that `p` is
    /// within `eps` of count as not seeing it: on flat patches (a cylinder's cap) support points
    /// are coplanar, and letting round-off decide would scatter the hole and ruin the polytope.
    fn carve(&mut self, verts: &[SupportPoint], start: usize, p: DVec3, eps: f64) -> Horizon {
        let sees = |f: &Face| f.normal.dot(p - verts[f.v[0]].w) > eps;
        let mut visible: SmallVec<[usize; 16]> = SmallVec::from_elem(start, 1);
        self.alive[start] = false;
        let mut k = 0;
        let mut horizon = Horizon::new();
        while k < visible.len() {
            let f = self.faces[visible[k]];
            k += 1;
            for e in 0..3 {
                let (a, b) = (f.v[e], f.v[(e + 1) % 3]);
                match self.edge_owner.get(&(b, a)) {
                    Some(&g) if self.alive[g] && sees(&self.faces[g]) => {
                        self.alive[g] = false;
                        visible.push(g);
                    }
                    Some(&g) if self.alive[g] => horizon.push((a, b)),
                    _ => {}
                }
            }
        }
        for &f in &visible {
            let v = self.faces[f].v;
            for e in 0..3 {
                if self.edge_owner.get(&(v[e], v[(e + 1) % 3])) == Some(&f) {
                    self.edge_owner.remove(&(v[e], v[(e + 1) % 3]));
                }
            }
        }
        horizon
    }
}

/// Barycentric weights of `p` (on the triangle's plane) in triangle `t`, clamped to the triangle.
fn barycentric(p: DVec3, t: [DVec3; 3]) -> [f64; 3] {
    let (e0, e1, ep) = (t[1] - t[0], t[2] - t[0], p - t[0]);
    let (d00, d01, d11) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (d20, d21) = (ep.dot(e0), ep.dot(e1));
    let denom = d00 * d11 - d01 * d01;
    if denom <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let v = ((d11 * d20 - d01 * d21) / denom).clamp(0.0, 1.0);
    let w = ((d00 * d21 - d01 * d20) / denom).clamp(0.0, 1.0 - v);
    [1.0 - v - w, v, w]
}

/// Grows GJK's simplex to a tetrahedron of non-zero volume that still contains the origin (on its
/// boundary at worst), using extra support points, into `verts`; false when `A − B` is flat.
fn blow_up(pair: &ConvexPair, simplex: &Simplex, tol: f64, verts: &mut Vertices) -> bool {
    verts.clear();
    for p in simplex.as_slice() {
        if verts.iter().all(|q| (q.w - p.w).length() > tol) {
            verts.push(*p);
        }
    }
    if verts.len() == 4 {
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| verts[i].w);
        if (b - a).dot((c - a).cross(d - a)).abs() <= tol * tol * tol {
            verts.truncate(3);
        }
    }
    if verts.is_empty() {
        verts.push(pair.support(DVec3::X));
    }
    if verts.len() == 1 {
        for dir in [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z] {
            let p = pair.support(dir);
            if (p.w - verts[0].w).length() > tol {
                verts.push(p);
                break;
            }
        }
    }
    if verts.len() == 2 {
        let d = (verts[1].w - verts[0].w).normalize_or_zero();
        let axis = [DVec3::X, DVec3::Y, DVec3::Z][d.abs().min_position()];
        let u = d.cross(axis).normalize();
        let v = d.cross(u);
        for k in 0..6 {
            let angle = k as f64 * std::f64::consts::FRAC_PI_3;
            let p = pair.support(u * angle.cos() + v * angle.sin());
            if (p.w - verts[0].w).cross(d).length() > tol {
                verts.push(p);
                break;
            }
        }
    }
    if verts.len() == 3 {
        let n = (verts[1].w - verts[0].w).cross(verts[2].w - verts[0].w).normalize_or_zero();
        for dir in [n, -n] {
            let p = pair.support(dir);
            if n.dot(p.w - verts[0].w).abs() > tol {
                verts.push(p);
                break;
            }
        }
    }
    verts.len() == 4
}

#[cfg(test)]
mod tests {
    use super::super::gjk::gjk;
    use super::super::support::Core;
    use super::*;
    use crate::math::{DQuat, Transform};

    #[test]
    fn box_box_face_depth() {
        let a = Core::Cuboid { half_extents: DVec3::new(2.0, 2.0, 0.5) };
        let b = Core::Cuboid { half_extents: DVec3::splat(0.5) };
        let pose_a = Transform::new(DVec3::new(3.0, -1.0, 0.0), DQuat::IDENTITY);
        let pose_b = Transform::new(DVec3::new(3.2, -0.9, 0.9), DQuat::from_rotation_z(0.4));
        let pair = ConvexPair::new(a, &pose_a, b, &pose_b);
        let g = gjk(&pair, pair.b_in_a.translation);
        assert!(g.overlapping);
        let e = epa(&pair, &g.simplex).unwrap();
        assert!((e.depth - 0.1).abs() < 1e-9, "{}", e.depth);
        assert!((e.normal - DVec3::Z).length() < 1e-9);
    }

    #[test]
    fn touching_point_core_blows_up() {
        // A point core exactly on the face of a box: GJK stops on a lower-dimensional simplex.
        let a = Core::Cuboid { half_extents: DVec3::ONE };
        let pair = ConvexPair::new(
            a,
            &Transform::IDENTITY,
            Core::Point,
            &Transform::new(DVec3::new(0.3, 0.2, 1.0), DQuat::IDENTITY),
        );
        let g = gjk(&pair, DVec3::Z);
        assert!(g.overlapping);
        let e = epa(&pair, &g.simplex).unwrap();
        assert!(e.depth.abs() < 1e-9);
        assert!((e.normal - DVec3::Z).length() < 1e-6);
    }
}
