//! Contact between any two convex shapes by GJK (separated or touching) or EPA (overlapping),
//! followed by feature clipping to turn the single closest pair into a stable manifold.
//!
//! 1. GJK on the cores. If the cores are farther apart than the radii plus the margin, there is no
//!    contact (GJK stops as soon as it has proved that). If they are apart at all, the normal is
//!    the direction between the closest points and the separation is their distance minus the
//!    radii — exact for rounded shapes.
//! 2. If the cores overlap, EPA on the cores gives depth and normal.
//! 3. Each shape reports the feature facing the normal (vertex, edge, face). Face against edge or
//!    face: clip the incident feature to the reference face. Parallel edges: clip one to the
//!    other's extent. Anything with a vertex: the single GJK/EPA point.

use smallvec::SmallVec;

use super::clip::{clip_segment, clip_to_face, ClipVertex};
use super::epa::epa;
use super::feature::{is_round_cap, supporting_feature, Feature, CAP_MISS};
use super::gjk::{gjk_within, ConvexPair};
use super::manifold::{ContactPoint, Manifold};
use super::support::Rounded;
use crate::math::{DVec3, Transform};

/// The clip tag of a round cap's true lowest point: below 0x8000 (an original point) and above any
/// cap corner's index.
const LOWEST_TAG: u16 = 0x7FFF;

/// Contact of two convex shapes, or `None` if they are more than `margin` apart. `warm_dir` holds
/// last call's normal in A's frame (zero at first) and is updated, which lets GJK start close to
/// the answer.
pub fn collide_convex(
    a: &Rounded,
    pose_a: &Transform,
    b: &Rounded,
    pose_b: &Transform,
    margin: f64,
    warm_dir: &mut DVec3,
) -> Option<Manifold> {
    let pair = ConvexPair::new(a.core, pose_a, b.core, pose_b);
    let initial = if *warm_dir != DVec3::ZERO { *warm_dir } else { pair.b_in_a.translation };
    let radius = a.radius + b.radius;
    // Pairs whose cores are farther apart than that have no contact: the search stops as soon
    // as it knows (most of a pile's pairs, whose fat boxes overlap, stay apart).
    let g = gjk_within(&pair, initial, radius + margin);
    if !g.overlapping && g.distance > radius + margin {
        // The start direction, if it proved the gap by itself (no iteration), is the one to
        // start from again; else the direction between the closest points found.
        *warm_dir = if g.iterations == 0 { initial } else { g.point_b - g.point_a };
        return None;
    }
    let scale = pair.scale();
    let (normal, point_a, point_b, core_separation) = if !g.overlapping && g.distance > 1e-9 * scale {
        ((g.point_b - g.point_a) / g.distance, g.point_a, g.point_b, g.distance)
    } else {
        match epa(&pair, &g.simplex) {
            Some(e) => (e.normal, e.point_a, e.point_b, -e.depth),
            // Only two flat cores (points, segments) get here, and they have closed forms; the
            // centre offset is a safe stand-in.
            None => {
                let n = pair.b_in_a.translation.try_normalize().unwrap_or(DVec3::Z);
                (n, g.point_a, g.point_b, 0.0)
            }
        }
    };
    *warm_dir = normal;
    let separation = core_separation - radius;
    if separation > margin {
        return None;
    }
    let feature_a = supporting_feature(&a.core, normal);
    let mut feature_b = supporting_feature(&b.core, pair.b_in_a.rotation.inverse() * -normal);
    for p in &mut feature_b.points {
        *p = pair.b_in_a.transform_point(*p);
    }
    let ctx = Context { a, b, pose_a, pose_b, b_in_a: &pair.b_in_a, margin };
    let clipped = if feature_a.is_face() && feature_b.points.len() >= 2
        || feature_b.is_face() && feature_a.points.len() >= 2
    {
        ctx.face_contact(&feature_a, &feature_b, normal)
    } else if feature_a.is_edge() && feature_b.is_edge() {
        ctx.parallel_edges(&feature_a, &feature_b, normal)
    } else {
        None
    };
    // Clipping keeps the part of the incident feature over the reference face; when the deepest
    // part lies beyond that face (a needle cone deep inside a wide one), the points left can be
    // far shallower than the overlap GJK/EPA measured. A manifold must not hide depth from the
    // solver: keep the one exact point instead.
    let clipped = clipped.filter(|m| {
        let shallowest_allowed = separation + 0.5 * (-separation).max(0.0) + 1e-6 * scale;
        m.points().iter().map(|p| p.separation).fold(f64::INFINITY, f64::min) <= shallowest_allowed
    });
    clipped.or_else(|| {
        // One point: midway between the two surfaces.
        let on_a = point_a + normal * a.radius;
        let on_b = point_b - normal * b.radius;
        let normal_world = pose_a.rotation * normal;
        let mid = pose_a.transform_point(0.5 * (on_a + on_b));
        let id = (u32::from(feature_a.code) << 16) | u32::from(feature_b.code);
        let mut m = Manifold::new(normal_world);
        m.push(ContactPoint::new(pose_a, pose_b, normal_world, mid, separation, id));
        Some(m)
    })
}

/// Poses and radii shared by the clipping helpers. Feature points are in A's local frame.
struct Context<'t> {
    a: &'t Rounded<'t>,
    b: &'t Rounded<'t>,
    pose_a: &'t Transform,
    pose_b: &'t Transform,
    b_in_a: &'t Transform,
    margin: f64,
}

impl Context<'_> {
    /// Clips the incident feature against the reference face (the face more aligned with the
    /// normal; A's on a tie). `None` if nothing survives.
    fn face_contact(&self, fa: &Feature, fb: &Feature, normal: DVec3) -> Option<Manifold> {
        let na = fa.is_face().then(|| polygon_normal(&fa.points));
        let nb = fb.is_face().then(|| polygon_normal(&fb.points));
        let ref_is_b = match (na, nb) {
            (Some(na), Some(nb)) => -nb.dot(normal) > na.dot(normal),
            (None, _) => true,
            _ => false,
        };
        let (reference, incident, n_ref, r_inc) = if ref_is_b {
            (fb, fa, nb.expect("b is a face"), self.a.radius)
        } else {
            (fa, fb, na.expect("a is a face"), self.b.radius)
        };
        let radius = self.a.radius + self.b.radius;
        let mut clipped = clip_to_face(&reference.points, n_ref, &incident.points, self.margin + radius);
        let incident_core = if ref_is_b { &self.a.core } else { &self.b.core };
        if is_round_cap(incident_core, incident) {
            // The incident cap polygon's corners can sit above the rim's true lowest point towards
            // the reference face (0.44 mm for a 2.2 m disc tipped 1.2° on a box): when that point
            // lies over the face and is lower than every clipped point, it is a point too. (Not
            // when a corner is as low, so a cylinder standing flat keeps its fixed corners.)
            let lowest = if ref_is_b {
                self.a.core.support_local(-n_ref)
            } else {
                let down_b = self.b_in_a.rotation.inverse() * -n_ref;
                self.b_in_a.transform_point(self.b.core.support_local(down_b))
            };
            let deepest = clipped.iter().map(|c| c.separation).fold(f64::INFINITY, f64::min);
            for mut c in clip_to_face(&reference.points, n_ref, &[lowest], self.margin + radius) {
                if c.separation < deepest - CAP_MISS {
                    c.tag = LOWEST_TAG;
                    clipped.push(c);
                }
            }
        }
        let normal_local = if ref_is_b { -n_ref } else { n_ref };
        let normal_world = self.pose_a.rotation * normal_local;
        let bits = (u32::from(ref_is_b) << 31)
            | ((u32::from(reference.code) & 0xFF) << 23)
            | ((u32::from(incident.code) & 0x7F) << 16);
        // Filled in place (a kilobyte and a half: collected and moved, it would be copied).
        let mut candidates: SmallVec<[ContactPoint; 16]> = SmallVec::new();
        candidates.extend(clipped.iter().map(|c| {
            let sep = c.separation - radius;
            let mid = c.point - n_ref * (r_inc + 0.5 * sep);
            let mid_world = self.pose_a.transform_point(mid);
            ContactPoint::new(self.pose_a, self.pose_b, normal_world, mid_world, sep, bits | u32::from(c.tag))
        }));
        Manifold::from_candidates(normal_world, &candidates)
    }

    /// Two nearly parallel edges (capsule sides, cylinder sides, box edges): B's edge clipped to
    /// the extent of A's gives up to two points. `None` if they are not parallel or do not overlap.
    fn parallel_edges(&self, fa: &Feature, fb: &Feature, normal: DVec3) -> Option<Manifold> {
        let (a0, a1) = (fa.points[0], fa.points[1]);
        let u = (a1 - a0).try_normalize()?;
        let v = (fb.points[1] - fb.points[0]).try_normalize()?;
        if u.cross(v).length() > super::feature::EDGE_SIN_TOLERANCE {
            return None;
        }
        let seg = [ClipVertex::original(fb.points[0], 0), ClipVertex::original(fb.points[1], 1)];
        let seg = clip_segment(seg, -u, -u.dot(a0), 0)?;
        let seg = clip_segment(seg, u, u.dot(a1), 1)?;
        let radius = self.a.radius + self.b.radius;
        let normal_world = self.pose_a.rotation * normal;
        let bits = 0x4000_0000 | ((u32::from(fa.code) & 0xFF) << 23) | ((u32::from(fb.code) & 0x7F) << 16);
        let mut candidates: SmallVec<[ContactPoint; 2]> = SmallVec::new();
        for c in seg {
            let sep = normal.dot(c.point - a0) - radius;
            if sep <= self.margin {
                let mid = c.point - normal * (self.b.radius + 0.5 * sep);
                let mid_world = self.pose_a.transform_point(mid);
                candidates.push(ContactPoint::new(
                    self.pose_a,
                    self.pose_b,
                    normal_world,
                    mid_world,
                    sep,
                    bits | u32::from(c.tag),
                ));
            }
        }
        // A zero-length overlap is one point, not two.
        if candidates.len() == 2 && (candidates[0].point_world - candidates[1].point_world).length() < 1e-9 {
            candidates.pop();
        }
        Manifold::from_candidates(normal_world, &candidates)
    }
}

/// Unit normal of a counter-clockwise polygon (sum of fan cross products about its first vertex).
pub(crate) fn polygon_normal(points: &[DVec3]) -> DVec3 {
    let o = points[0];
    let mut n = DVec3::ZERO;
    for k in 1..points.len() - 1 {
        n += (points[k] - o).cross(points[k + 1] - o);
    }
    n.normalize_or_zero()
}
