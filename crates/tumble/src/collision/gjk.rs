//! GJK distance between two convex cores (Gilbert, Johnson, Keerthi 1988), with the signed-volume
//! sub-algorithm of Montanari, Petrinic and Barbieri (2017).
//!
//! GJK finds the point `v` of the Minkowski difference `A − B` closest to the origin: `|v|` is the
//! distance, and `v`'s barycentric weights over the simplex's support points give the closest
//! points on A and on B. Each iteration adds the support point `w` of `A − B` along `−v` and
//! replaces the simplex by the smallest face of it that holds the point closest to the origin.
//!
//! The sub-algorithm decides that face from signed volumes (determinants) rather than from the
//! classic Johnson's recursive determinants: it projects the origin onto the simplex's affine hull,
//! computes barycentric weights in the coordinate plane where the projection has the largest area
//! (so no division by a tiny number), and only recurses into the faces whose weight has the wrong
//! sign. That stays correct for the flat, needle-like simplices that appear near convergence.
//!
//! Everything runs in A's local frame: B's support points are mapped into it. Large world
//! coordinates then never enter the differences, which is where GJK loses precision.

use super::support::Core;
use crate::math::{DVec3, Transform};

/// A point of `A − B` with the points of A and B it came from, all in A's local frame.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SupportPoint {
    pub w: DVec3,
    pub a: DVec3,
    pub b: DVec3,
}

/// Two cores, with B's pose expressed in A's local frame.
#[derive(Clone, Copy, Debug)]
pub struct ConvexPair<'a> {
    pub a: Core<'a>,
    pub b: Core<'a>,
    pub b_in_a: Transform,
}

impl<'a> ConvexPair<'a> {
    pub fn new(a: Core<'a>, pose_a: &Transform, b: Core<'a>, pose_b: &Transform) -> Self {
        ConvexPair { a, b, b_in_a: pose_a.inverse().mul_transform(pose_b) }
    }

    /// Support point of `A − B` along `dir` (A's local frame).
    #[inline]
    pub fn support(&self, dir: DVec3) -> SupportPoint {
        let a = self.a.support_local(dir);
        let dir_b = self.b_in_a.rotation.inverse() * -dir;
        let b = self.b_in_a.transform_point(self.b.support_local(dir_b));
        SupportPoint { w: a - b, a, b }
    }

    /// A length scale for tolerances: the larger bounding radius.
    pub fn scale(&self) -> f64 {
        self.a.bounding_radius().max(self.b.bounding_radius()).max(f64::MIN_POSITIVE)
    }
}

/// Up to four support points.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Simplex {
    pub points: [SupportPoint; 4],
    pub len: usize,
}

impl Default for SupportPoint {
    fn default() -> Self {
        SupportPoint { w: DVec3::ZERO, a: DVec3::ZERO, b: DVec3::ZERO }
    }
}

impl Simplex {
    pub fn as_slice(&self) -> &[SupportPoint] {
        &self.points[..self.len]
    }
}

/// What GJK found, in A's local frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub struct GjkResult {
    /// Distance between the cores; 0 when they overlap or touch.
    pub distance: f64,
    /// Closest point on A and on B (equal-ish when overlapping).
    pub point_a: DVec3,
    pub point_b: DVec3,
    /// True when the origin is inside (or within round-off of) the simplex: the cores overlap.
    pub overlapping: bool,
    /// The final simplex: the seed for EPA when overlapping.
    pub simplex: Simplex,
    pub iterations: u32,
}

/// Maximum GJK iterations; polytopes converge in a handful, curved cores in a few dozen.
const MAX_ITERATIONS: u32 = 64;
/// Relative accuracy of the distance: stop when the duality gap is below `REL_GAP · |v|²`.
const REL_GAP: f64 = 1e-10;
/// `|v|² ≤ TOUCH · max|wᵢ|²` counts as the origin lying on the simplex.
const TOUCH: f64 = 1e-20;

/// Closest points of the two cores, starting the search along `initial_dir`: a guess of the
/// direction from A towards B in A's local frame (the centre offset is a good one, last step's
/// contact normal a better one).
pub fn gjk(pair: &ConvexPair, initial_dir: DVec3) -> GjkResult {
    gjk_within(pair, initial_dir, f64::INFINITY)
}

/// `gjk`, stopping early once the cores are known to be more than `max_distance` apart: each
/// support point `w` along `−v` bounds the distance from below by `v·w / |v|` (no point of
/// `A − B` lies nearer the origin along `v`). The result then reports that bound as its
/// distance (above `max_distance`, below the true one) and the closest points found so far.
/// Within `max_distance`, the same result as `gjk`.
pub fn gjk_within(pair: &ConvexPair, initial_dir: DVec3, max_distance: f64) -> GjkResult {
    let d0 = if initial_dir.length_squared() > 0.0 { initial_dir } else { DVec3::X };
    let mut simplex = Simplex::default();
    // The point of A − B nearest the origin lies on the side facing from A towards B.
    simplex.points[0] = pair.support(d0);
    simplex.len = 1;
    // No point of A − B lies farther along `d0` than this support point, so the cores are at
    // least `−d0·w₀ / |d0|` apart. Warm-started from last step's normal, that bound already puts
    // most pairs that stay apart beyond `max_distance`, before any iteration.
    if max_distance.is_finite() {
        let bound = -d0.dot(simplex.points[0].w) / d0.length();
        if bound > max_distance {
            let SupportPoint { a: point_a, b: point_b, .. } = simplex.points[0];
            return GjkResult {
                distance: bound,
                point_a,
                point_b,
                overlapping: false,
                simplex,
                iterations: 0,
            };
        }
    }
    let mut v = simplex.points[0].w;
    let mut lambda = [1.0, 0.0, 0.0, 0.0];
    let mut iterations = 0;
    let mut overlapping = false;
    loop {
        let vv = v.length_squared();
        let max_w2 = simplex.as_slice().iter().fold(0.0_f64, |m, p| m.max(p.w.length_squared()));
        if simplex.len == 4 || vv <= TOUCH * max_w2.max(pair.scale() * pair.scale()) {
            overlapping = true;
            break;
        }
        if iterations >= MAX_ITERATIONS {
            break;
        }
        iterations += 1;
        let w = pair.support(-v);
        // v·w ≤ |v|·distance: a lower bound of the distance, and the duality gap below.
        let v_dot_w = v.dot(w.w);
        if v_dot_w > max_distance * vv.sqrt() {
            let (point_a, point_b) = closest_points(&simplex, &lambda);
            let distance = v_dot_w / vv.sqrt();
            return GjkResult { distance, point_a, point_b, overlapping: false, simplex, iterations };
        }
        // Duality gap: |v|² − v·w bounds |v|·(|v| − distance) from above.
        if vv - v_dot_w <= REL_GAP * vv {
            break;
        }
        if simplex.as_slice().iter().any(|p| p.w == w.w) {
            break;
        }
        let mut candidate = simplex;
        candidate.points[candidate.len] = w;
        candidate.len += 1;
        let ws: [DVec3; 4] = candidate.points.map(|p| p.w);
        let (mask, lam) = closest_on_simplex(&ws, candidate.len);
        let mut reduced = Simplex::default();
        let mut new_lambda = [0.0; 4];
        let mut new_v = DVec3::ZERO;
        for (i, (point, weight)) in candidate.as_slice().iter().zip(lam).enumerate() {
            if mask & (1 << i) != 0 {
                reduced.points[reduced.len] = *point;
                new_lambda[reduced.len] = weight;
                reduced.len += 1;
                new_v += point.w * weight;
            }
        }
        // Round-off can stall progress near convergence; keep the better of the two.
        if new_v.length_squared() >= vv && reduced.len < 4 {
            break;
        }
        simplex = reduced;
        lambda = new_lambda;
        v = new_v;
    }
    let (point_a, point_b) = closest_points(&simplex, &lambda);
    let distance = if overlapping { 0.0 } else { v.length() };
    GjkResult { distance, point_a, point_b, overlapping, simplex, iterations }
}

/// The points of A and of B that the simplex's weights `lambda` give.
fn closest_points(simplex: &Simplex, lambda: &[f64; 4]) -> (DVec3, DVec3) {
    let (mut point_a, mut point_b) = (DVec3::ZERO, DVec3::ZERO);
    for (p, l) in simplex.as_slice().iter().zip(lambda) {
        point_a += p.a * *l;
        point_b += p.b * *l;
    }
    (point_a, point_b)
}

/// Barycentric weights of the point of the simplex `w[..n]` closest to the origin: returns the
/// bit mask of the vertices with positive weight and the weights (indexed like `w`).
pub fn closest_on_simplex(w: &[DVec3; 4], n: usize) -> (u8, [f64; 4]) {
    match n {
        1 => (1, [1.0, 0.0, 0.0, 0.0]),
        2 => s1d(w, [0, 1]),
        3 => s2d(w, [0, 1, 2]),
        _ => s3d(w),
    }
}

#[inline]
fn same_sign(a: f64, b: f64) -> bool {
    (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0)
}

fn weighted(w: &[DVec3; 4], lam: &[f64; 4]) -> DVec3 {
    w[0] * lam[0] + w[1] * lam[1] + w[2] * lam[2] + w[3] * lam[3]
}

fn argmax_abs(v: DVec3) -> usize {
    let a = v.abs();
    if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    }
}

/// Segment `w[i0] w[i1]`.
fn s1d(w: &[DVec3; 4], [i0, i1]: [usize; 2]) -> (u8, [f64; 4]) {
    let (s1, s2) = (w[i0], w[i1]);
    let t = s2 - s1;
    let mut lam = [0.0; 4];
    let tt = t.length_squared();
    if tt == 0.0 {
        lam[i0] = 1.0;
        return (1 << i0, lam);
    }
    // Origin projected on the line, then 1-D barycentrics along the longest axis of the segment.
    let p0 = s1 - t * (s1.dot(t) / tt);
    let k = argmax_abs(t);
    let mu = s1[k] - s2[k];
    let c1 = p0[k] - s2[k];
    let c2 = s1[k] - p0[k];
    if same_sign(mu, c1) && same_sign(mu, c2) {
        lam[i0] = c1 / mu;
        lam[i1] = c2 / mu;
        ((1 << i0) | (1 << i1), lam)
    } else if same_sign(mu, c1) {
        lam[i0] = 1.0;
        (1 << i0, lam)
    } else {
        lam[i1] = 1.0;
        (1 << i1, lam)
    }
}

/// Triangle `w[i0] w[i1] w[i2]`.
fn s2d(w: &[DVec3; 4], idx: [usize; 3]) -> (u8, [f64; 4]) {
    let [s1, s2, s3] = idx.map(|i| w[i]);
    let n = (s2 - s1).cross(s3 - s1);
    let nn = n.length_squared();
    let edges = [[idx[1], idx[2]], [idx[0], idx[2]], [idx[0], idx[1]]];
    if nn > 0.0 {
        let p0 = n * (s1.dot(n) / nn);
        // Drop the coordinate in which the triangle's projection is largest; the 2-D areas in the
        // remaining (cyclic) pair share their sign convention with n[k].
        let k = argmax_abs(n);
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let area =
            |p: DVec3, q: DVec3, r: DVec3| (q[a] - p[a]) * (r[b] - p[b]) - (q[b] - p[b]) * (r[a] - p[a]);
        let mu = n[k];
        let c = [area(p0, s2, s3), area(s1, p0, s3), area(s1, s2, p0)];
        if c.iter().all(|&cj| same_sign(mu, cj)) {
            let mut lam = [0.0; 4];
            for j in 0..3 {
                lam[idx[j]] = c[j] / mu;
            }
            return ((1 << idx[0]) | (1 << idx[1]) | (1 << idx[2]), lam);
        }
        return best_of(w, (0..3).filter(|&j| !same_sign(mu, c[j])).map(|j| s1d(w, edges[j])));
    }
    best_of(w, edges.iter().map(|&e| s1d(w, e)))
}

/// Tetrahedron `w[0..4]`.
fn s3d(w: &[DVec3; 4]) -> (u8, [f64; 4]) {
    // Six times the signed volume; replacing vertex j by the origin gives j's weight numerator.
    let vol = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| (b - a).dot((c - a).cross(d - a));
    let o = DVec3::ZERO;
    let det = vol(w[0], w[1], w[2], w[3]);
    let c = [
        vol(o, w[1], w[2], w[3]),
        vol(w[0], o, w[2], w[3]),
        vol(w[0], w[1], o, w[3]),
        vol(w[0], w[1], w[2], o),
    ];
    let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    if det != 0.0 && c.iter().all(|&cj| same_sign(det, cj)) {
        return (0b1111, c.map(|cj| cj / det));
    }
    if det == 0.0 {
        return best_of(w, faces.iter().map(|&f| s2d(w, f)));
    }
    best_of(w, (0..4).filter(|&j| !same_sign(det, c[j])).map(|j| s2d(w, faces[j])))
}

/// The candidate sub-simplex whose closest point is nearest the origin.
fn best_of(w: &[DVec3; 4], candidates: impl Iterator<Item = (u8, [f64; 4])>) -> (u8, [f64; 4]) {
    let mut best = (0u8, [0.0; 4]);
    let mut best_d = f64::INFINITY;
    for (mask, lam) in candidates {
        let d = weighted(w, &lam).length_squared();
        if d < best_d {
            best_d = d;
            best = (mask, lam);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;

    #[test]
    fn subalgorithm_matches_known_projections() {
        let w =
            [DVec3::new(1.0, -1.0, 1.0), DVec3::new(1.0, 1.0, 1.0), DVec3::new(1.0, 0.0, -1.0), DVec3::ZERO];
        // Triangle in the plane x = 1 containing (1, 0, 0).
        let (mask, lam) = closest_on_simplex(&w, 3);
        assert_eq!(mask, 0b111);
        assert!((weighted(&w, &lam) - DVec3::X).length() < 1e-15);
        // Segment whose closest point is an end.
        let w2 = [DVec3::new(2.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0), DVec3::ZERO, DVec3::ZERO];
        let (mask, lam) = closest_on_simplex(&w2, 2);
        assert_eq!((mask, lam[0]), (0b01, 1.0));
        // Tetrahedron around the origin.
        let t = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, -1.0, -1.0),
        ];
        let (mask, lam) = closest_on_simplex(&t, 4);
        assert_eq!(mask, 0b1111);
        assert!(lam.iter().all(|&l| (l - 0.25).abs() < 1e-15));
    }

    #[test]
    fn box_box_distance() {
        let a = Core::Cuboid { half_extents: DVec3::ONE };
        let pose_a = Transform::new(DVec3::new(10.0, 0.0, 0.0), DQuat::from_rotation_z(0.3));
        let pose_b = Transform::new(pose_a.transform_point(DVec3::new(0.0, 0.0, 3.5)), pose_a.rotation);
        let pair = ConvexPair::new(a, &pose_a, a, &pose_b);
        let r = gjk(&pair, pair.b_in_a.translation);
        assert!(!r.overlapping);
        assert!((r.distance - 1.5).abs() < 1e-12, "{}", r.distance);
        assert!((r.point_a.z - 1.0).abs() < 1e-12 && (r.point_b.z - 2.5).abs() < 1e-12);
    }

    /// Within `max_distance`, `gjk_within` is `gjk` bit for bit; beyond it, it may stop early,
    /// with a distance that is above `max_distance` and at most the true one. Boxes and a triangle
    /// against a box, at random poses and gaps, searched from a fixed direction and from the
    /// true one (last step's normal, for a pair that has not moved): from that, a gap beyond
    /// `max_distance` is known before any iteration.
    #[test]
    fn early_out_beyond_max_distance_is_a_lower_bound() {
        let mut rng = crate::scenes::rng::SplitMix64::new(0x5_eed0_f9e3);
        let mut unit = || rng.range(-1.0, 1.0);
        let box_core = Core::Cuboid { half_extents: DVec3::new(0.5, 0.3, 0.2) };
        let triangle = Core::Triangle([
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -0.5, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ]);
        let (mut stopped_early, mut within, mut known_at_start) = (0, 0, 0);
        for k in 0..2000 {
            let a = if k % 2 == 0 { box_core } else { triangle };
            let axis = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::Z);
            let pose_b = Transform::new(
                DVec3::new(unit(), unit(), unit()) * 1.2,
                DQuat::from_axis_angle(axis, 3.2 * unit()),
            );
            let pair = ConvexPair::new(a, &Transform::IDENTITY, box_core, &pose_b);
            let max_distance = 0.5 * unit().abs();
            let from_z = gjk(&pair, DVec3::Z);
            let true_direction = from_z.point_b - from_z.point_a;
            for start in [DVec3::Z, true_direction] {
                let full = gjk(&pair, start);
                let early = gjk_within(&pair, start, max_distance);
                if full.overlapping || full.distance <= max_distance {
                    within += 1;
                    assert_eq!(early.distance.to_bits(), full.distance.to_bits(), "k {k}");
                    assert_eq!(early.overlapping, full.overlapping, "k {k}");
                    assert_eq!((early.point_a, early.point_b), (full.point_a, full.point_b), "k {k}");
                } else {
                    stopped_early += usize::from(early.iterations < full.iterations);
                    assert!(!early.overlapping && early.distance > max_distance, "k {k}");
                    assert!(
                        early.distance <= full.distance * (1.0 + 1e-12),
                        "k {k}: {} > {}",
                        early.distance,
                        full.distance
                    );
                    if start == true_direction && full.distance > max_distance * (1.0 + 1e-9) {
                        assert_eq!(early.iterations, 0, "k {k}");
                        known_at_start += 1;
                    }
                }
            }
        }
        assert!(stopped_early > 400 && within > 400, "stopped early {stopped_early}, within {within}");
        assert!(known_at_start > 200, "known at the start {known_at_start}");
    }
}
