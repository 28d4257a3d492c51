//! Scene queries: ray casts, shape overlaps and box queries against the bodies of a world.
//!
//! Every query walks the broad phase's trees (the contact manager's fat boxes) as a filter and
//! then tests the exact leaf shapes at the bodies' **current** poses. The trees never miss a
//! body: a proxy's fat box holds its shape's box at the current pose because the step moves the
//! proxies of awake bodies at its end (after the solve), `World::set_pose` moves the proxies of
//! the body it places, and bodies that do not move (static or asleep) keep theirs. So a query
//! right after a step sees the bodies where `World::body(..).position()` says they are.
//!
//! Filtering ([`QueryFilter`]): a body is considered when the query's collision filter and the
//! body's accept each other (the same group/mask rule as between two shapes,
//! [`CollisionFilter::accepts`]), and — only when `include_sensors` is set — when it is a sensor.
//! `None` means every body that is not a sensor. Bodies without a shape are never found.
//!
//! Results are deterministic: lists are sorted (by distance then body id for rays, by body id
//! otherwise) and hold each body once.

use crate::body::Body;
use crate::collision::aabb::shape_aabb;
use crate::collision::contact_manager::{leaf, leaf_pose, leaves, unpack};
use crate::collision::narrow_phase::{collide, kind_rank, PairCache};
use crate::collision::ray::{ray_cast_shape, Ray};
use crate::collision::{Aabb, CollisionFilter, ProxyKey};
use crate::id::BodyId;
use crate::math::{DVec3, Transform};
use crate::shape::Shape;
use crate::world::World;

/// The closest hit of a ray on one body.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RayCastHit {
    pub body: BodyId,
    /// Distance from the ray origin along the unit direction, m (0 when the origin is inside a
    /// solid shape).
    pub distance: f64,
    /// `origin + distance · direction`, world frame.
    pub point: DVec3,
    /// Unit surface normal at the hit, world frame (`−direction` when the origin is inside).
    pub normal: DVec3,
}

/// Which bodies a query considers.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct QueryFilter {
    /// The query's own group and mask; a body is considered when this and the body's filter
    /// accept each other.
    pub collision: CollisionFilter,
    /// Whether sensor bodies are considered. Default false: a ray passes through triggers.
    pub include_sensors: bool,
}

impl Default for QueryFilter {
    /// Every body that is not a sensor.
    fn default() -> Self {
        QueryFilter { collision: CollisionFilter { group: u32::MAX, mask: u32::MAX }, include_sensors: false }
    }
}

impl From<CollisionFilter> for QueryFilter {
    fn from(collision: CollisionFilter) -> Self {
        QueryFilter { collision, ..QueryFilter::default() }
    }
}

impl QueryFilter {
    /// Every body, sensors included.
    pub fn everything() -> Self {
        QueryFilter { include_sensors: true, ..QueryFilter::default() }
    }

    pub fn accepts(&self, body: &Body) -> bool {
        (self.include_sensors || !body.is_sensor) && self.collision.accepts(&body.filter)
    }
}

/// A query's arguments were not usable.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum QueryError {
    #[error("{what} must be finite, got {value}")]
    NotFinite { what: &'static str, value: String },
    #[error("ray direction must be a non-zero finite vector, got {0}")]
    ZeroDirection(DVec3),
    #[error("max_distance must be >= 0 (+inf for no limit), got {0}")]
    InvalidMaxDistance(f64),
    #[error("box min must be <= max on every axis, got min {min}, max {max}")]
    InvalidAabb { min: DVec3, max: DVec3 },
    #[error("orientation must be a unit quaternion (x, y, z, w), got {0}")]
    InvalidOrientation(String),
    #[error("overlap queries take convex shapes and compounds of them, not a {0}")]
    UnsupportedShape(&'static str),
}

fn check_finite(what: &'static str, v: DVec3) -> Result<(), QueryError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(QueryError::NotFinite { what, value: format!("{v}") })
    }
}

/// A checked ray: finite origin, a direction that normalises, `max_distance` in `[0, +inf]`.
fn checked_ray(origin: DVec3, direction: DVec3, max_distance: f64) -> Result<Ray, QueryError> {
    check_finite("ray origin", origin)?;
    let unit = direction.try_normalize().ok_or(QueryError::ZeroDirection(direction))?;
    if max_distance.is_nan() || max_distance < 0.0 {
        return Err(QueryError::InvalidMaxDistance(max_distance));
    }
    Ok(Ray { origin, direction: unit, max_distance })
}

impl World {
    /// The body and leaf shape (with its world pose) behind a proxy, if the filter accepts it.
    fn proxy_leaf(&self, key: ProxyKey, filter: &QueryFilter) -> Option<(BodyId, &Shape, Transform)> {
        let (slot, child) = unpack(self.contact_manager.broad_phase.user_data(key));
        let raw = self.bodies.id_of_slot(slot)?;
        let body = self.bodies.get(raw)?;
        if !filter.accepts(body) {
            return None;
        }
        let (shape, local) = leaf(body.shape.as_ref()?, child);
        Some((raw.into(), shape, leaf_pose(body.transform(), &local)))
    }

    /// The closest body hit by the ray `origin + t·direction`, `0 ≤ t ≤ max_distance`
    /// (`direction` is normalised; `max_distance` may be `+inf`). Equal distances go to the lower
    /// body id. A ray starting inside a solid shape hits it at distance 0.
    pub fn ray_cast(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_distance: f64,
        filter: Option<&QueryFilter>,
    ) -> Result<Option<RayCastHit>, QueryError> {
        let ray = checked_ray(origin, direction, max_distance)?;
        let filter = filter.copied().unwrap_or_default();
        let mut best: Option<RayCastHit> = None;
        self.contact_manager.broad_phase.ray_cast(&ray, |clipped, key| {
            let Some((body, shape, pose)) = self.proxy_leaf(key, &filter) else { return -1.0 };
            let Some(hit) = ray_cast_shape(shape, &pose, clipped) else { return -1.0 };
            let hit = RayCastHit { body, distance: hit.distance, point: hit.point, normal: hit.normal };
            if best.is_none_or(|b| (hit.distance, hit.body) < (b.distance, b.body)) {
                best = Some(hit);
            }
            // Clip the ray to the hit (0 would stop the walk and could skip an equal hit of a
            // lower body id, so clip to the smallest positive number instead).
            hit.distance.max(f64::MIN_POSITIVE)
        });
        Ok(best)
    }

    /// Every body hit by the ray, each once with its closest hit, sorted by distance and then
    /// body id.
    pub fn ray_cast_all(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_distance: f64,
        filter: Option<&QueryFilter>,
    ) -> Result<Vec<RayCastHit>, QueryError> {
        let ray = checked_ray(origin, direction, max_distance)?;
        let filter = filter.copied().unwrap_or_default();
        let mut hits: Vec<RayCastHit> = Vec::new();
        self.contact_manager.broad_phase.ray_cast(&ray, |_, key| {
            if let Some((body, shape, pose)) = self.proxy_leaf(key, &filter) {
                if let Some(hit) = ray_cast_shape(shape, &pose, &ray) {
                    hits.push(RayCastHit {
                        body,
                        distance: hit.distance,
                        point: hit.point,
                        normal: hit.normal,
                    });
                }
            }
            -1.0 // never clip: every hit is wanted
        });
        // Closest leaf of each body first, then keep one hit per body.
        hits.sort_by(|a, b| a.body.cmp(&b.body).then(a.distance.total_cmp(&b.distance)));
        hits.dedup_by_key(|h| h.body);
        hits.sort_by(|a, b| a.distance.total_cmp(&b.distance).then(a.body.cmp(&b.body)));
        Ok(hits)
    }

    /// The bodies whose shapes overlap `shape` placed at `pose` (touching counts), sorted by id.
    /// `shape` must be convex or a compound of convex shapes. The test is exact: the narrow
    /// phase with no speculative margin, overlap when its deepest point has separation ≤ 0.
    /// Triangle-mesh bodies are never reported (the narrow phase has no mesh routine yet).
    pub fn overlap_shape(
        &self,
        shape: &Shape,
        pose: &Transform,
        filter: Option<&QueryFilter>,
    ) -> Result<Vec<BodyId>, QueryError> {
        check_finite("pose translation", pose.translation)?;
        let q = pose.rotation;
        let len = q.length();
        if !len.is_finite() || (len - 1.0).abs() > 1e-6 {
            return Err(QueryError::InvalidOrientation(format!("({}, {}, {}, {})", q.x, q.y, q.z, q.w)));
        }
        let pose = Transform::new(pose.translation, q.normalize());
        let query_leaves = leaves(shape);
        if let Some((bad, _)) = query_leaves.iter().find(|(s, _)| kind_rank(s).is_none()) {
            return Err(QueryError::UnsupportedShape(bad.kind_name()));
        }
        let filter = filter.copied().unwrap_or_default();
        let mut found = Vec::new();
        for (query_leaf, local) in query_leaves {
            let query_pose = leaf_pose(pose, &local);
            let query_box = shape_aabb(query_leaf, &query_pose);
            for key in self.proxies_overlapping(&query_box) {
                let Some((body, shape, pose)) = self.proxy_leaf(key, &filter) else { continue };
                if !shape_aabb(shape, &pose).overlaps(&query_box) {
                    continue;
                }
                let manifold = collide(query_leaf, &query_pose, shape, &pose, 0.0, &mut PairCache::default());
                if manifold.is_some_and(|m| !m.is_empty() && m.min_separation() <= 0.0) {
                    found.push(body);
                }
            }
        }
        found.sort_unstable();
        found.dedup();
        Ok(found)
    }

    /// The bodies with a leaf shape whose tight bounding box at the current pose overlaps `aabb`
    /// (closed boxes: touching counts), sorted by id.
    pub fn query_aabb(&self, aabb: &Aabb, filter: Option<&QueryFilter>) -> Result<Vec<BodyId>, QueryError> {
        check_finite("box min", aabb.min)?;
        check_finite("box max", aabb.max)?;
        if !aabb.min.cmple(aabb.max).all() {
            return Err(QueryError::InvalidAabb { min: aabb.min, max: aabb.max });
        }
        let filter = filter.copied().unwrap_or_default();
        let mut found: Vec<BodyId> = self
            .proxies_overlapping(aabb)
            .into_iter()
            .filter_map(|key| self.proxy_leaf(key, &filter))
            .filter(|(_, shape, pose)| shape_aabb(shape, pose).overlaps(aabb))
            .map(|(body, _, _)| body)
            .collect();
        found.sort_unstable();
        found.dedup();
        Ok(found)
    }

    /// Proxies whose fat boxes overlap `aabb`.
    fn proxies_overlapping(&self, aabb: &Aabb) -> Vec<ProxyKey> {
        let mut keys = Vec::new();
        self.contact_manager.broad_phase.query(aabb, |key| {
            keys.push(key);
            true
        });
        keys
    }
}
