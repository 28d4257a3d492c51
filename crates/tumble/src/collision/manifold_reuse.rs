//! Manifold reuse: a pair of flat-sided shapes whose relative pose has barely changed since its
//! manifold was made keeps that manifold's points and only measures them again.
//!
//! A manifold's points are fixed on each shape (`local_point_a`, `local_point_b`) and its normal is
//! fixed on A. While no point of either shape has moved more than the limit (2 mm, [`MAX_MOTION`],
//! or 1% of the smaller shape's reach if that is less) relative to the other shape since the
//! manifold was made, the same features still touch, so the points are
//! carried along with their shapes and each separation is measured again along the normal. For a
//! vertex of one shape on a face of the other — the points of face contacts between boxes and
//! hulls, and of boxes and hulls on terrain — that measure is exact; a point clipped at the edge
//! of a face or an edge–edge point is off by at most the motion. A vertex that was left out (beyond
//! the speculative margin, or by the reduction to four points) has come at most the limit
//! closer. The motion is measured from the pose at which the manifold was made, never step to
//! step, so it cannot add up: once past the limit, the pair runs the full query again.
//!
//! The motion bound: seen from A, B's pose changed by a shift `Δt` and a turn by θ about B's
//! origin, which moves a point of B at distance `r` from that origin by at most
//! `|Δt| + 2 sin(θ/2) r`; with `r` the farthest any point of B lies (its *reach*), that bounds every
//! point of B. The same holds seen from B with A's reach; the smaller bound is taken (a box on a
//! terrain mesh: the box's).
//!
//! Only flat-sided shapes are reused (boxes, hulls, and the static plane, mesh and height field
//! they lie on): on a round surface the touching point moves across the surface as the shape
//! rolls, so a point fixed on it would rise off the ground. Their queries are closed forms anyway.
//! A stack at rest moves micrometres per step: its pairs run the separating-axis test once and
//! then only every few hundred steps.

use super::manifold::Manifold;
use crate::math::{DVec3, Transform};
use crate::shape::Shape;

/// The most any point of one shape may have moved relative to the other, m, for a manifold to be
/// reused: 2 mm, or less for small shapes (`REACH_FRACTION`).
pub const MAX_MOTION: f64 = 2e-3;
/// For shapes smaller than 20 cm, the limit is this fraction of the smaller reach (a 1 cm die:
/// 87 um), so what reuse gets wrong stays small against the shapes themselves.
pub const REACH_FRACTION: f64 = 0.01;

/// Where a manifold was made: B's pose in A's frame, the normal in A's frame, and each shape's
/// reach (the farthest its points lie from its origin).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ManifoldOrigin {
    b_in_a: Transform,
    normal_local_a: DVec3,
    reach_a: f64,
    reach_b: f64,
}

/// Whether manifolds of this shape may be reused (its surface is made of flat faces).
pub fn is_flat_sided(shape: &Shape) -> bool {
    matches!(
        shape,
        Shape::Cuboid(_) | Shape::ConvexHull(_) | Shape::Plane(_) | Shape::TriMesh(_) | Shape::HeightField(_)
    )
}

/// The farthest any point of `shape` lies from its origin; infinite for static geometry (planes,
/// meshes and height fields: their partner's reach bounds the motion instead).
fn reach(shape: &Shape) -> f64 {
    match shape {
        Shape::Cuboid(c) => c.half_extents.length(),
        Shape::ConvexHull(h) => h.bounding_radius(),
        _ => f64::INFINITY,
    }
}

impl ManifoldOrigin {
    /// Records the poses at which `manifold` was made between `shape_a` and `shape_b`.
    pub fn new(
        shape_a: &Shape,
        pose_a: &Transform,
        shape_b: &Shape,
        pose_b: &Transform,
        manifold: &Manifold,
    ) -> ManifoldOrigin {
        ManifoldOrigin {
            b_in_a: pose_a.inverse().mul_transform(pose_b),
            normal_local_a: pose_a.rotation.inverse() * manifold.normal_world,
            reach_a: reach(shape_a),
            reach_b: reach(shape_b),
        }
    }

    /// The most any point of one shape has moved relative to the other since the manifold was
    /// made, bounded as in the module docs.
    pub fn motion(&self, pose_a: &Transform, pose_b: &Transform) -> f64 {
        let b_in_a = pose_a.inverse().mul_transform(pose_b);
        // |cos(θ/2)| of the turn between the two relative rotations (either sign of a quaternion).
        let cos_half_turn = b_in_a.rotation.dot(self.b_in_a.rotation).abs().min(1.0);
        let chord = 2.0 * (1.0 - cos_half_turn * cos_half_turn).sqrt();
        // Seen from A: B's origin shifted by the change of `b_in_a`'s translation. Seen from B: A's
        // origin sits at −R⁻¹t in B's frame.
        let a_in_b = |t: &Transform| -(t.rotation.inverse() * t.translation);
        let shift_seen_from_a = (b_in_a.translation - self.b_in_a.translation).length();
        let shift_seen_from_b = (a_in_b(&b_in_a) - a_in_b(&self.b_in_a)).length();
        (shift_seen_from_a + chord * self.reach_b).min(shift_seen_from_b + chord * self.reach_a)
    }

    /// The most the shapes may move relative to each other while the manifold is reused:
    /// `MAX_MOTION`, or `REACH_FRACTION` of the smaller shape's reach if that is less.
    pub fn motion_limit(&self) -> f64 {
        MAX_MOTION.min(REACH_FRACTION * self.reach_a.min(self.reach_b))
    }

    /// Whether the manifold may be reused at these poses.
    pub fn still_fits(&self, pose_a: &Transform, pose_b: &Transform) -> bool {
        self.motion(pose_a, pose_b) < self.motion_limit()
    }

    /// Carries `manifold`'s points to these poses and measures them again, in place: the normal
    /// turns with A, each point's separation is the gap between its two surface points along it,
    /// its world point their midpoint. Feature ids, and with them the warm-start impulses, stay.
    /// (In place: building a new manifold and copying it over the contact's moved some 800 bytes
    /// a contact for the few numbers that change.)
    pub fn remeasure(&self, manifold: &mut Manifold, pose_a: &Transform, pose_b: &Transform) {
        let normal_world = pose_a.rotation * self.normal_local_a;
        manifold.normal_world = normal_world;
        for point in manifold.points_mut() {
            let on_a = pose_a.transform_point(point.local_point_a);
            let on_b = pose_b.transform_point(point.local_point_b);
            point.separation = (on_b - on_a).dot(normal_world);
            point.point_world = 0.5 * (on_a + on_b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::narrow_phase::{collide, PairCache};
    use crate::math::DQuat;
    use crate::shape::Cuboid;

    fn unit_box() -> Shape {
        Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).unwrap())
    }

    /// A box resting face down on another, tilted by `tilt` about x and slid by `slide` along x.
    fn top_pose(tilt: f64, slide: f64) -> Transform {
        Transform::new(DVec3::new(0.3 + slide, 0.1, 0.995), DQuat::from_rotation_x(tilt))
    }

    #[test]
    fn a_remeasured_face_contact_matches_the_full_query() {
        // A smaller box face down on a unit box: the contact points are the corners of its bottom
        // face, which the carried manifold follows exactly.
        let (a, b) = (unit_box(), Shape::Cuboid(Cuboid::new(DVec3::new(0.3, 0.2, 0.25)).unwrap()));
        let pose_a = Transform::IDENTITY;
        let pose = |tilt: f64, slide: f64| {
            Transform::new(DVec3::new(0.1 + slide, -0.05, 0.749), DQuat::from_rotation_x(tilt))
        };
        let made_at = pose(0.0, 0.0);
        let manifold = collide(&a, &pose_a, &b, &made_at, 0.02, &mut PairCache::default()).unwrap();
        let origin = ManifoldOrigin::new(&a, &pose_a, &b, &made_at, &manifold);
        let now = pose(4e-4, 2e-4);
        assert!(origin.still_fits(&pose_a, &now), "motion {}", origin.motion(&pose_a, &now));
        let mut carried = manifold;
        origin.remeasure(&mut carried, &pose_a, &now);
        let fresh = collide(&a, &pose_a, &b, &now, 0.02, &mut PairCache::default()).unwrap();
        assert!((carried.normal_world - fresh.normal_world).length() < 1e-12);
        assert_eq!((carried.len(), fresh.len()), (4, 4));
        for p in carried.points() {
            let q = fresh.points().iter().find(|q| q.feature_id == p.feature_id).expect("same features");
            assert!((p.separation - q.separation).abs() < 1e-12, "{} vs {}", p.separation, q.separation);
            // The point on A stays where it was made, so the midpoint lags B's corner by half
            // its motion (here 1.1e-4 m).
            let lag = (p.point_world - q.point_world).length();
            assert!(lag > 1e-4 && lag <= 0.5 * origin.motion(&pose_a, &now), "lag {lag}");
        }
        // The tilt lifts one edge of the 0.4 m wide face by 0.4 sin θ: the carried points see it.
        let (lo, hi) = carried.points().iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.separation), hi.max(p.separation))
        });
        assert!((hi - lo - 0.4 * 4e-4f64.sin()).abs() < 1e-12, "spread {}", hi - lo);
    }

    #[test]
    fn the_limits_are_measured_from_where_the_manifold_was_made() {
        let (a, b) = (unit_box(), unit_box());
        let pose_a = Transform::new(DVec3::new(5.0, -2.0, 1.0), DQuat::from_rotation_z(0.7));
        let made_at = pose_a.mul_transform(&top_pose(0.0, 0.0));
        let manifold = collide(&a, &pose_a, &b, &made_at, 0.02, &mut PairCache::default()).unwrap();
        let origin = ManifoldOrigin::new(&a, &pose_a, &b, &made_at, &manifold);
        let moved = |tilt: f64, slide: f64| pose_a.mul_transform(&top_pose(tilt, slide));
        assert!(origin.still_fits(&pose_a, &moved(0.0, 0.9 * MAX_MOTION)));
        assert!(!origin.still_fits(&pose_a, &moved(0.0, 1.1 * MAX_MOTION)));
        // A turn about B's centre moves B's corners (reach √3/2 m) by 2 sin(θ/2) √3/2: the limit
        // on θ follows; seen from B, A's corners move farther (its centre is off B's axis too).
        let reach = 0.75f64.sqrt();
        let turn_limit = 2.0 * (MAX_MOTION / (2.0 * reach)).asin();
        assert!((origin.motion(&pose_a, &moved(turn_limit, 0.0)) - MAX_MOTION).abs() < 1e-12);
        assert!(origin.still_fits(&pose_a, &moved(0.9 * turn_limit, 0.0)));
        assert!(!origin.still_fits(&pose_a, &moved(1.1 * turn_limit, 0.0)));
        // Moving both bodies together changes nothing.
        let carry = Transform::new(DVec3::new(100.0, 3.0, -7.0), DQuat::from_rotation_y(2.0));
        let (a2, b2) = (carry.mul_transform(&pose_a), carry.mul_transform(&made_at));
        assert!(origin.still_fits(&a2, &b2));
        let mut carried = manifold;
        origin.remeasure(&mut carried, &a2, &b2);
        for (p, q) in carried.points().iter().zip(manifold.points()) {
            assert!((p.separation - q.separation).abs() < 1e-12);
            assert!((p.point_world - carry.transform_point(q.point_world)).length() < 1e-12);
        }
        assert!((carried.normal_world - carry.rotation * manifold.normal_world).length() < 1e-14);
    }

    /// A small shape's limit is a hundredth of its reach: a 1 cm die on a unit box may move
    /// 87 um, not 2 mm.
    #[test]
    fn small_shapes_have_a_smaller_limit() {
        let (a, die) = (unit_box(), Shape::Cuboid(Cuboid::new(DVec3::splat(0.005)).unwrap()));
        let on_top = |slide: f64| Transform::new(DVec3::new(slide, 0.0, 0.5049), DQuat::IDENTITY);
        let manifold =
            collide(&a, &Transform::IDENTITY, &die, &on_top(0.0), 0.02, &mut PairCache::default()).unwrap();
        let origin = ManifoldOrigin::new(&a, &Transform::IDENTITY, &die, &on_top(0.0), &manifold);
        let limit = REACH_FRACTION * 0.005 * 3f64.sqrt();
        assert!((origin.motion_limit() - limit).abs() < 1e-15 && limit < 1e-4);
        assert!(origin.still_fits(&Transform::IDENTITY, &on_top(0.9 * limit)));
        assert!(!origin.still_fits(&Transform::IDENTITY, &on_top(1.1 * limit)));
    }

    #[test]
    fn round_shapes_are_not_reused() {
        assert!(is_flat_sided(&unit_box()));
        assert!(!is_flat_sided(&Shape::Sphere(crate::shape::Sphere::new(0.5).unwrap())));
    }
}
