//! Triangles of static geometry (meshes and height fields): the supporting feature of a triangle,
//! ray–triangle intersection, a common view of "a set of triangles with neighbours", and the
//! internal-edge rule.
//!
//! ## The internal-edge rule
//!
//! A body sliding over a flat floor made of many triangles must feel one flat floor. Tested one
//! triangle at a time, though, a box corner that dips just below the floor next to a triangle's
//! edge is pushed out *sideways over that edge*: the shortest way out of that single triangle. The
//! edge is internal — the neighbouring triangle continues the surface — so that normal is wrong,
//! and the box catches on it.
//!
//! The fix (as in Bullet's `btAdjustInternalEdgeContacts` and Gregorius' "Robust contact creation
//! for physics simulations", GDC 2015) is to allow an edge or vertex normal only where the surface
//! really has an edge. For triangle `T` with front normal `n_T`, edge `k` with unit direction `e`
//! (counter-clockwise), outward in-plane direction `u = e × n_T`, and neighbour normal `n_N`, the
//! edge's *bend* is `φ = atan2(n_N·u, n_N·n_T)`: positive for a convex edge (the surface falls
//! away), zero for a flat one, negative for a concave one. The normals the surface can have at a
//! convex edge fill the arc from `n_T` (θ = 0) to `n_N` (θ = φ) about `e`. A contact normal `n`
//! from `T` is **allowed** when, for every edge it leans over (`n·u > 0`), that edge is a boundary
//! (no neighbour) or convex with `θ = atan2(n·u, n·n_T) ≤ φ` (plus a small tolerance). Any other
//! normal — leaning over a flat or concave edge, or past the neighbour's normal — is replaced by
//! `n_T`, and the contact is recomputed as a face contact of `T` (the body's feature facing `−n_T`
//! clipped to `T`, separations measured from `T`'s plane). If nothing of the body lies over `T`,
//! `T` gives no contact: its neighbour does. A vertex is handled through its two edges on `T`.

use smallvec::{smallvec, SmallVec};

use super::aabb::Aabb;
use super::feature::{Feature, EDGE, EDGE_SIN_TOLERANCE, FACE, FACE_COS_TOLERANCE, VERTEX};
use crate::math::DVec3;
use crate::shape::{HeightField, TriMesh};

/// An edge counts as convex when its bend exceeds this angle (rad); flatter edges are internal.
pub const CONVEX_EDGE_ANGLE: f64 = 1e-3;
/// A normal leaning over an edge by less than this (the sine of an angle) does not lean over it.
pub const LEAN_TOLERANCE: f64 = 1e-7;
/// A convex edge allows normals up to this much (rad) beyond its neighbour's normal.
pub const EDGE_ANGLE_TOLERANCE: f64 = 1e-3;

/// A set of triangles with neighbours across their edges: a mesh or a height field.
pub trait TriangleSource {
    /// Corners of triangle `t`, counter-clockwise about its front normal, local frame.
    fn triangle(&self, t: u32) -> [DVec3; 3];
    /// Unit front normal of triangle `t`.
    fn triangle_normal(&self, t: u32) -> DVec3;
    /// The triangle across edge `k` (corner `k` to corner `k + 1`) of `t`, if any.
    fn neighbor(&self, t: u32, k: usize) -> Option<u32>;
    /// Calls `visit` with (at least) every triangle whose bounds overlap `aabb_local`.
    fn query(&self, aabb_local: &Aabb, visit: &mut dyn FnMut(u32));
    /// What the internal-edge rule needs of triangle `t` (corners `v`, front normal `n_t`):
    /// worked out from the neighbours here, kept from the build by a mesh.
    fn edges(&self, t: u32, v: &[DVec3; 3], n_t: DVec3) -> TriangleEdges {
        TriangleEdges::of(self, t, v, n_t)
    }
}

/// Triangle `t`'s edges as the internal-edge rule sees them.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TriangleEdges {
    /// The bend of each edge ([`edge_bends`]), `None` for a boundary.
    pub bends: [Option<f64>; 3],
    /// Some edge is a boundary or convex ([`has_sharp_edge`]).
    pub sharp: bool,
    /// No normal but the face's is allowed ([`allows_only_face_normals`]).
    pub only_face_normals: bool,
}

impl TriangleEdges {
    /// Worked out from `source`'s neighbours of `t`.
    pub fn of<S: TriangleSource + ?Sized>(source: &S, t: u32, v: &[DVec3; 3], n_t: DVec3) -> Self {
        let bends = edge_bends(source, t, v, n_t);
        TriangleEdges {
            bends,
            sharp: has_sharp_edge(&bends),
            only_face_normals: allows_only_face_normals(v, n_t, &bends),
        }
    }
}

impl TriangleSource for TriMesh {
    fn triangle(&self, t: u32) -> [DVec3; 3] {
        self.triangle_points(t)
    }
    fn triangle_normal(&self, t: u32) -> DVec3 {
        self.normal(t)
    }
    fn neighbor(&self, t: u32, k: usize) -> Option<u32> {
        TriMesh::neighbor(self, t, k)
    }
    fn query(&self, aabb_local: &Aabb, visit: &mut dyn FnMut(u32)) {
        self.bvh().query(aabb_local, visit);
    }
    fn edges(&self, t: u32, _: &[DVec3; 3], _: DVec3) -> TriangleEdges {
        self.triangle_edges(t)
    }
}

impl TriangleSource for HeightField {
    fn triangle(&self, t: u32) -> [DVec3; 3] {
        self.triangle_points(t)
    }
    fn triangle_normal(&self, t: u32) -> DVec3 {
        let [a, b, c] = self.triangle_points(t);
        (b - a).cross(c - a).normalize_or_zero()
    }
    fn neighbor(&self, t: u32, k: usize) -> Option<u32> {
        HeightField::neighbor(self, t, k)
    }
    fn query(&self, aabb_local: &Aabb, visit: &mut dyn FnMut(u32)) {
        HeightField::query(self, aabb_local.min, aabb_local.max, visit);
    }
}

/// The bend of each edge of triangle `t` (see the module docs), `None` for a boundary edge. Flat
/// and concave edges get a value ≤ 0 (not necessarily their angle: only convex bends are used).
pub fn edge_bends<S: TriangleSource + ?Sized>(
    source: &S,
    t: u32,
    v: &[DVec3; 3],
    n_t: DVec3,
) -> [Option<f64>; 3] {
    let mut out = [None; 3];
    for (k, bend) in out.iter_mut().enumerate() {
        if let Some(nb) = source.neighbor(t, k) {
            let n_n = source.triangle_normal(nb);
            let u = (v[(k + 1) % 3] - v[k]).normalize_or_zero().cross(n_t);
            let y = n_n.dot(u);
            *bend = Some(if y <= 0.0 { y } else { y.atan2(n_n.dot(n_t)) });
        }
    }
    out
}

/// True when some edge is a boundary or convex: only then can a contact normal differ from the
/// face normal.
pub fn has_sharp_edge(bends: &[Option<f64>; 3]) -> bool {
    bends.iter().any(|b| b.is_none_or(|phi| phi > CONVEX_EDGE_ANGLE))
}

/// The internal-edge rule: may a contact on triangle `v` (front normal `n_t`, edge bends `bends`)
/// have the normal `n`? See the module docs.
pub fn normal_allowed(v: &[DVec3; 3], n_t: DVec3, bends: &[Option<f64>; 3], n: DVec3) -> bool {
    let mut leans = false;
    for k in 0..3 {
        let u = (v[(k + 1) % 3] - v[k]).normalize_or_zero().cross(n_t);
        let lean = n.dot(u);
        if lean <= LEAN_TOLERANCE {
            continue;
        }
        leans = true;
        match bends[k] {
            // A boundary allows any normal leaning over it.
            None => {}
            // A convex edge: up to its neighbour's normal.
            Some(phi) if phi > CONVEX_EDGE_ANGLE && lean.atan2(n.dot(n_t)) <= phi + EDGE_ANGLE_TOLERANCE => {}
            // Flat, concave, or past the neighbour.
            Some(_) => return false,
        }
    }
    // Not leaning over any edge: the face normal itself (or its back, which is never allowed).
    leans || n.dot(n_t) > 0.0
}

/// True when the internal-edge rule allows no normal outside the face cone (`n·n_T ≥`
/// [`FACE_COS_TOLERANCE`]): every edge has a neighbour and the convex ones bend too little for
/// any normal they allow to lean farther. A contact on such a triangle is always its face
/// contact, whatever GJK/EPA would find. See docs/collision.md for the bound.
pub fn allows_only_face_normals(v: &[DVec3; 3], n_t: DVec3, bends: &[Option<f64>; 3]) -> bool {
    // For an allowed normal n = cos α n_T + sin α w (w a unit in-plane direction), every edge k
    // bounds sin α (w·u_k) by `limit[k]`: a flat or concave edge by the lean tolerance, a convex
    // one by tan(φ + tolerance) ≥ tan θ ≥ sin θ. So sin α ≤ min over edges with w·u_k > 0 of
    // limit[k] / (w·u_k), whose largest value over w lies where two such ratios are equal.
    let mut limit = [0.0; 3];
    let mut out = [DVec3::ZERO; 3];
    for k in 0..3 {
        limit[k] = match bends[k] {
            None => return false,
            Some(phi) if phi > CONVEX_EDGE_ANGLE => {
                let most = phi + EDGE_ANGLE_TOLERANCE;
                if most >= 0.5 {
                    return false;
                }
                most.tan().max(LEAN_TOLERANCE)
            }
            Some(_) => LEAN_TOLERANCE,
        };
        out[k] = (v[(k + 1) % 3] - v[k]).normalize_or_zero().cross(n_t);
    }
    let bound_at = |w: DVec3| {
        (0..3).fold(f64::INFINITY, |m, k| {
            let c = w.dot(out[k]);
            if c > 0.0 {
                m.min(limit[k] / c)
            } else {
                m
            }
        })
    };
    let mut sin_max: f64 = 0.0;
    for a in 0..3 {
        let b = (a + 1) % 3;
        let w = n_t.cross(out[a] * limit[b] - out[b] * limit[a]).normalize_or_zero();
        for w in [w, -w] {
            if w.dot(out[a]) > 0.0 && w.dot(out[b]) > 0.0 {
                sin_max = sin_max.max(bound_at(w));
            }
        }
    }
    // A margin for round-off in the normals the rule is later applied to.
    let face_sin = (1.0 - FACE_COS_TOLERANCE * FACE_COS_TOLERANCE).sqrt();
    sin_max.is_finite() && sin_max < 0.99 * face_sin
}

/// The feature of a triangle facing `d` (unit): its front or back face, an edge, or a corner.
/// Codes: face 0 (front) or 1 (back), edge `k` (corner `k` to `k + 1`), vertex `k`.
pub fn triangle_feature(v: &[DVec3; 3], d: DVec3) -> Feature {
    let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
    let c = n.dot(d);
    if c >= FACE_COS_TOLERANCE {
        return Feature { points: SmallVec::from_slice(v), code: FACE };
    }
    if c <= -FACE_COS_TOLERANCE {
        return Feature { points: smallvec![v[0], v[2], v[1]], code: FACE | 1 };
    }
    let dots = v.map(|p| p.dot(d));
    let i = if dots[0] >= dots[1] && dots[0] >= dots[2] {
        0
    } else if dots[1] >= dots[2] {
        1
    } else {
        2
    };
    // The two edges at corner i: edge i (i → i+1) and edge i+2 (i+2 → i).
    let mut best: Option<(usize, [DVec3; 2], f64)> = None;
    for (e, other) in [(i, (i + 1) % 3), ((i + 2) % 3, (i + 2) % 3)] {
        let sine = (v[other] - v[i]).normalize_or_zero().dot(d).abs();
        if sine <= EDGE_SIN_TOLERANCE && best.is_none_or(|b| sine < b.2) {
            let pts = if e == i { [v[i], v[other]] } else { [v[other], v[i]] };
            best = Some((e, pts, sine));
        }
    }
    match best {
        Some((e, pts, _)) => Feature { points: SmallVec::from_slice(&pts), code: EDGE | e as u16 },
        None => Feature { points: smallvec![v[i]], code: VERTEX | i as u16 },
    }
}

/// Möller–Trumbore: the distance `t ∈ [0, max_t]` at which the ray `o + t·d` crosses the triangle
/// (from either side), or `None`.
#[inline]
pub fn ray_triangle(o: DVec3, d: DVec3, [p0, p1, p2]: [DVec3; 3], max_t: f64) -> Option<f64> {
    let (e1, e2) = (p1 - p0, p2 - p0);
    let pvec = d.cross(e2);
    let det = e1.dot(pvec);
    // A ray in the triangle's plane cannot cross it transversally.
    if det.abs() <= f64::EPSILON * e1.length() * e2.length() {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = o - p0;
    let u = s.dot(pvec) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qvec = s.cross(e1);
    let v = d.dot(qvec) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(qvec) * inv_det;
    (t >= 0.0 && t <= max_t).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn features_of_a_triangle() {
        assert_eq!(triangle_feature(&TRI, DVec3::Z).code, FACE);
        assert_eq!(triangle_feature(&TRI, -DVec3::Z).points.to_vec(), vec![TRI[0], TRI[2], TRI[1]]);
        // Along −Y the edge from corner 0 to corner 1 faces the direction.
        let f = triangle_feature(&TRI, -DVec3::Y);
        assert_eq!((f.code, f.points.len()), (EDGE, 2));
        let f = triangle_feature(&TRI, DVec3::new(1.0, -0.5, 0.2).normalize());
        assert_eq!((f.code, f.points.to_vec()), (VERTEX | 1, vec![DVec3::X]));
    }

    #[test]
    fn internal_edge_rule() {
        let n_t = DVec3::Z;
        let tilted = DVec3::new(0.0, -0.1, 1.0).normalize(); // leans over edge 0 (along −Y)
                                                             // Flat neighbour: only the face normal is allowed.
        assert!(!normal_allowed(&TRI, n_t, &[Some(0.0), Some(0.0), Some(0.0)], tilted));
        assert!(normal_allowed(&TRI, n_t, &[Some(0.0), Some(0.0), Some(0.0)], n_t));
        // Boundary: allowed. Convex by 0.2 rad: allowed up to 0.2 rad, not beyond.
        assert!(normal_allowed(&TRI, n_t, &[None, Some(0.0), Some(0.0)], tilted));
        assert!(normal_allowed(&TRI, n_t, &[Some(0.2), Some(0.0), Some(0.0)], tilted));
        let steep = DVec3::new(0.0, -1.0, 1.0).normalize();
        assert!(!normal_allowed(&TRI, n_t, &[Some(0.2), Some(0.0), Some(0.0)], steep));
        assert!(!normal_allowed(&TRI, n_t, &[None, None, None], -n_t));
    }

    /// Where `allows_only_face_normals` says so, no normal the internal-edge rule allows leaves the
    /// face cone: random triangles and bends, and many normals within 10° of the face normal
    /// (denser near the cone's rim). Where it says no, a normal just over a convex edge's bend is
    /// allowed and outside the cone in most cases, so the bound is not loose by much.
    #[test]
    fn only_face_normals_bound_holds() {
        let mut rng = crate::scenes::rng::SplitMix64::new(0x6a09_e667_f3bc_c908);
        let (mut yes, mut no, mut no_with_witness) = (0, 0, 0);
        for _ in 0..400 {
            let v = [0, 1, 2]
                .map(|_| DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-0.2, 0.2)));
            let n_t = (v[1] - v[0]).cross(v[2] - v[0]);
            if n_t.length() < 0.2 {
                continue; // too thin to be a sensible mesh triangle
            }
            let n_t = n_t.normalize();
            let bends = [0, 1, 2].map(|_| Some(rng.range(-0.01, 0.03)));
            let frame = n_t.any_orthonormal_pair();
            let only_face = allows_only_face_normals(&v, n_t, &bends);
            let mut witness = false;
            for _ in 0..4000 {
                let alpha = rng.range(0.0, 10f64.to_radians()).max(rng.range(0.0, 10f64.to_radians()));
                let phi = rng.range(0.0, std::f64::consts::TAU);
                let w = frame.0 * phi.cos() + frame.1 * phi.sin();
                let n = n_t * alpha.cos() + w * alpha.sin();
                if normal_allowed(&v, n_t, &bends, n) && n.dot(n_t) < FACE_COS_TOLERANCE {
                    assert!(
                        !only_face,
                        "{v:?} {bends:?}: {n} is allowed, {} from the face",
                        alpha.to_degrees()
                    );
                    witness = true;
                }
            }
            if only_face {
                yes += 1;
            } else {
                no += 1;
                no_with_witness += usize::from(witness);
            }
        }
        assert!(yes > 50 && no > 50, "only face {yes}, not {no}");
        assert!(
            no_with_witness * 10 >= no * 7,
            "{no_with_witness} of {no} with an allowed normal off the face"
        );
        // A boundary edge allows any normal leaning over it.
        assert!(!allows_only_face_normals(&TRI, DVec3::Z, &[None, Some(0.0), Some(0.0)]));
        assert!(allows_only_face_normals(&TRI, DVec3::Z, &[Some(0.0), Some(-0.3), Some(0.002)]));
    }

    #[test]
    fn ray_hits_either_side() {
        let o = DVec3::new(0.2, 0.2, 1.0);
        assert_eq!(ray_triangle(o, -DVec3::Z, TRI, 10.0), Some(1.0));
        assert_eq!(ray_triangle(-o, DVec3::Z, TRI, 10.0), None);
        assert_eq!(ray_triangle(o * DVec3::new(1.0, 1.0, -1.0), DVec3::Z, TRI, 10.0), Some(1.0));
        assert_eq!(ray_triangle(o, -DVec3::Z, TRI, 0.5), None);
    }
}
