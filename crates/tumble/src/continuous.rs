//! Continuous collision for bullets: after the solve, each dynamic body flagged `bullet` has its
//! motion over the step swept against static geometry, and is moved back to the time of impact if
//! it went through something (as Box2D v3's `b2SolveContinuous`).
//!
//! ## Why speculative contacts are not enough
//!
//! Speculative contacts (`contact_manager.rs`) are made at the start of the step between shapes
//! within reach of the step's motion, and stop the points of each manifold from crossing the
//! surface. They see the motion as a straight line of each point at its start velocity. A body
//! that spins fast breaks that picture: the end of a thrown stick moves on an arc, the point that
//! will hit is not the one closest at the start, and it can pass clean through a thin wall within
//! one step, leaving the stick straddling the wall, or beyond it. Nothing in the next step can then
//! tell which side it came from.
//!
//! ## What this stage does
//!
//! For each awake dynamic bullet, in body order (one body at a time: the result does not depend on
//! the thread count), and each convex leaf of its shape:
//! 1. the sweep from the leaf's pose at the start of the step to its pose now
//!    (`time_of_impact::Sweep`: the centre of mass on a line, the rotation at a constant rate);
//! 2. candidates: the static proxies whose boxes overlap the swept box (the box of the leaf's
//!    bounding ball about the centre of mass at both ends, when it turns), and for a mesh or a
//!    height field the triangles whose boxes do, facing the leaf's start position (triangles are
//!    one-sided, as in contacts); sensors, filtered-out pairs and bodies joined to the bullet by a
//!    joint that does not let them collide are skipped, as the broad phase skips them;
//! 3. for each candidate, the time of impact with a target separation `s` of a few millimetres
//!    (at most a quarter of the leaf's smallest half extent), by conservative advancement;
//! 4. a hit at `t < 1` only counts if the contacts failed to stop the body: at the end of the step
//!    the leaf is deeper than `s` into the shape, or touches it from the other side, or is clear
//!    of it although the sweep reached it (it passed through). A body that the contacts stopped at
//!    the surface, or that only grazed an edge, is left alone.
//!
//! The bullet is then moved back to its pose at the earliest counted hit, `s` short of the
//! surface, and keeps its velocity: the next step's contact makes the bounce, from the right side.
//!
//! A leaf already within `s` of a shape at the start of the step (resting on it, sliding along it,
//! or just moved back here) would hit at once and never move again. Instead, one that is apart is
//! swept to half its present gap; one touching or overlapping is swept as a small ball at its
//! centre (a quarter of its smallest half extent), so that a body resting on the ground can slide
//! yet its centre cannot pass through (Box2D's fallback), and it may not end the step deeper than
//! `s` inside the shape (or deeper than it started, if it started deeper): when it would, it goes
//! back to the last fraction within that depth (`depth_limit`).
//!
//! Bodies that are not bullets cost one flag test per step and allocate nothing.

use crate::body::{Body, BodyKind, BodyState};
use crate::collision::aabb::{points_aabb, shape_aabb, Aabb};
use crate::collision::broad_phase::ProxyKind;
use crate::collision::contact_manager::{leaf, unpack};
use crate::collision::dynamic_tree::ProxyId;
use crate::collision::narrow_phase::{collide, PairCache};
use crate::collision::support::{Core, Rounded};
use crate::collision::time_of_impact::{time_of_impact, Moving, Sweep, Target, ToiState};
use crate::collision::triangle::TriangleSource;
use crate::collision::Manifold;
use crate::id::BodyId;
use crate::math::{is_finite_vec, DQuat, DVec3, Transform};
use crate::shape::Shape;
use crate::world::World;

/// The largest target separation of a time of impact, m: the gap left between a bullet moved back
/// and the surface it would have hit.
pub const LINEAR_SLOP: f64 = 0.005;

/// A bullet leaf's sizes and the tolerances that follow from them.
struct LeafScale {
    /// Target separation of the time of impact, m.
    target: f64,
    /// Accuracy of the time of impact's separation, m.
    tolerance: f64,
    /// Centre of the leaf, leaf frame (inside it: the fallback ball sits there).
    centre_local: DVec3,
    /// Radius of the fallback ball, m.
    core_radius: f64,
}

impl LeafScale {
    fn of(shape: &Shape) -> LeafScale {
        let min_half = shape_aabb(shape, &Transform::IDENTITY).half_extents().min_element();
        let target = LINEAR_SLOP.min(0.25 * min_half);
        let centre_local = match shape {
            // The mean of a convex hull's vertices lies inside it; the primitives are centred.
            Shape::ConvexHull(h) => {
                h.vertices().iter().fold(DVec3::ZERO, |s, &v| s + v) / h.vertices().len().max(1) as f64
            }
            _ => DVec3::ZERO,
        };
        LeafScale { target, tolerance: 0.25 * target, centre_local, core_radius: 0.25 * min_half }
    }
}

/// One bullet leaf's sweep against the static shapes, with the earliest counted hit so far.
struct LeafSweep<'a> {
    sweep: &'a Sweep,
    moving: Moving<'a>,
    /// The leaf shape itself, for the end-of-step contact check.
    shape: &'a Shape,
    scale: LeafScale,
    /// Earliest counted hit (1: none).
    fraction: f64,
}

impl LeafSweep<'_> {
    /// Sweeps against one target; `end_contact` gives the contact at the end of the step between
    /// the static shape the target belongs to and the leaf. Returns true when the leaf was already
    /// within the target separation of it at the start of the step.
    fn against(&mut self, target: &Target, end_contact: &mut impl FnMut() -> Option<Manifold>) -> bool {
        let (s, tol) = (self.scale.target, self.scale.tolerance);
        let out = time_of_impact(target, &self.moving, self.sweep, 0.0, s, tol);
        let hit = match out.state {
            ToiState::Separated => return false,
            ToiState::Hit | ToiState::Failed => out,
            ToiState::Overlapping => {
                match out.separation {
                    // Within the target but apart: keep at least half the present gap.
                    Some(sep) if sep.distance > tol => {
                        let half = 0.5 * sep.distance;
                        let out = time_of_impact(target, &self.moving, self.sweep, 0.0, half, 0.25 * half);
                        if matches!(out.state, ToiState::Hit | ToiState::Failed) {
                            self.count_unless_stopped(target, out.fraction, out.separation, end_contact);
                        }
                    }
                    // Touching or overlapping: only the centre is swept, and its hit always
                    // counts (how deep the whole leaf may go is `depth_limit`'s business).
                    _ => {
                        let ball = Moving {
                            shape: Rounded { core: Core::Point, radius: self.scale.core_radius },
                            pose_local: self
                                .moving
                                .pose_local
                                .mul_transform(&Transform::new(self.scale.centre_local, DQuat::IDENTITY)),
                        };
                        let out = time_of_impact(target, &ball, self.sweep, 0.0, s, tol);
                        if matches!(out.state, ToiState::Hit | ToiState::Failed) {
                            self.fraction = self.fraction.min(out.fraction);
                        }
                    }
                }
                return true;
            }
        };
        self.count_unless_stopped(target, hit.fraction, hit.separation, end_contact);
        false
    }

    /// Counts a hit at `fraction` unless the contacts handled it.
    fn count_unless_stopped(
        &mut self,
        target: &Target,
        fraction: f64,
        separation: Option<crate::collision::time_of_impact::Separation>,
        end_contact: &mut impl FnMut() -> Option<Manifold>,
    ) {
        if fraction >= self.fraction {
            return;
        }
        let stopped = separation
            .is_some_and(|sep| self.stopped_by_contacts(target, sep.normal_world, fraction, end_contact));
        if !stopped {
            self.fraction = fraction;
        }
    }

    /// Whether the contacts handled the hit at `fraction` (normal `normal_hit`, from the static
    /// shape to the leaf): at the end of the step the leaf touches the shape from the same side no
    /// deeper than the target separation, or it is clear of the shape and the sweep never
    /// actually reached it (it grazed past within the target).
    fn stopped_by_contacts(
        &self,
        target: &Target,
        normal_hit: DVec3,
        fraction: f64,
        end_contact: &mut impl FnMut() -> Option<Manifold>,
    ) -> bool {
        match end_contact() {
            Some(m) => m.min_separation() >= -self.scale.target && m.normal_world.dot(normal_hit) > 0.0,
            None => {
                let touch =
                    time_of_impact(target, &self.moving, self.sweep, fraction, 0.0, self.scale.tolerance);
                touch.state == ToiState::Separated
            }
        }
    }
}

/// Whether the step's start and end states can be swept at all.
fn is_finite_state(s: &BodyState) -> bool {
    is_finite_vec(s.com_world) && s.rotation.is_finite()
}

/// The number of leaves of a shape (compound children, or the shape itself).
fn leaf_count(shape: &Shape) -> usize {
    match shape {
        Shape::Compound(c) => c.children().len(),
        _ => 1,
    }
}

impl World {
    /// The continuous stage (module docs): moves back every bullet that went through static
    /// geometry in this step. Runs after the solve, before the proxies are moved.
    pub(crate) fn solve_continuous(&mut self) {
        let mut candidates = std::mem::take(&mut self.continuous_candidates);
        for k in 0..self.bullet_starts.len() {
            let (slot, start) = self.bullet_starts[k];
            let Some(body) = self.bodies.iter_slot(slot) else { continue };
            if !body.bullet || body.kind != BodyKind::Dynamic || body.isolated || !body.is_awake() {
                continue;
            }
            let Some(id) = self.bodies.id_of_slot(slot) else { continue };
            let Some((com_world, rotation)) =
                self.bullet_time_of_impact(id.into(), body, &start, &mut candidates)
            else {
                continue;
            };
            let body = self.bodies.get_mut(id).expect("looked up above");
            body.state.com_world = com_world;
            body.state.rotation = rotation;
        }
        self.continuous_candidates = candidates;
    }

    /// The pose a bullet goes back to, if it went through static geometry since `start`.
    /// `candidates` is scratch space for the static proxies under the sweep.
    fn bullet_time_of_impact(
        &self,
        id: BodyId,
        body: &Body,
        start: &BodyState,
        candidates: &mut Vec<ProxyId>,
    ) -> Option<(DVec3, DQuat)> {
        let shape = body.shape.as_ref()?;
        let end = &body.state;
        if !is_finite_state(start) || !is_finite_state(end) {
            return None;
        }
        let sweep =
            Sweep::new(body.com_local, (start.com_world, start.rotation), (end.com_world, end.rotation));
        if sweep.displacement() == DVec3::ZERO && sweep.angle() == 0.0 {
            return None;
        }
        let mut fraction = 1.0_f64;
        for child in 0..leaf_count(shape) {
            let (leaf_shape, leaf_local) = leaf(shape, child as u32);
            let leaf_shape = leaf_shape.moving_collision_shape();
            let Some(rounded) = Rounded::of(leaf_shape) else { continue };
            let moving = Moving { shape: rounded, pose_local: leaf_local };
            let scale = LeafScale::of(leaf_shape);
            let swept = swept_box(&sweep, &moving, leaf_shape).fattened(scale.target);
            candidates.clear();
            self.contact_manager.broad_phase.tree(ProxyKind::Static).query(&swept, |proxy| {
                candidates.push(proxy);
                true
            });
            // Tree order is a function of the tree's history; proxy order is not.
            candidates.sort_unstable();
            let mut leaf_sweep = LeafSweep { sweep: &sweep, moving, shape: leaf_shape, scale, fraction };
            for &proxy in candidates.iter() {
                let user_data = self.contact_manager.broad_phase.tree(ProxyKind::Static).user_data(proxy);
                let (static_slot, static_child) = unpack(user_data);
                let (Some(static_id), Some(other)) =
                    (self.bodies.id_of_slot(static_slot), self.bodies.iter_slot(static_slot))
                else {
                    continue;
                };
                if !self.may_collide(id, body, static_id.into(), other) {
                    continue;
                }
                let Some(other_shape) = &other.shape else { continue };
                let (static_leaf, static_local) = leaf(other_shape, static_child);
                let pose_static = other.transform().mul_transform(&static_local);
                sweep_against_static(&mut leaf_sweep, static_leaf, &pose_static, &swept);
            }
            fraction = leaf_sweep.fraction;
        }
        (fraction < 1.0).then(|| (sweep.com_at(fraction), sweep.rotation_at(fraction)))
    }

    /// The broad phase's and contact manager's rules for a bullet and a static body.
    fn may_collide(&self, bullet_id: BodyId, bullet: &Body, other_id: BodyId, other: &Body) -> bool {
        if other.is_sensor || bullet.is_sensor || other.isolated || !bullet.filter.accepts(&other.filter) {
            return false;
        }
        !self.joints.iter().any(|(_, j)| {
            !j.collide_connected
                && ((j.body_a == bullet_id && j.body_b == other_id)
                    || (j.body_a == other_id && j.body_b == bullet_id))
        })
    }
}

/// Bounds of everything the leaf covers during the sweep: the union of its boxes at both ends when
/// it does not turn, else the box of its bounding ball about the centre of mass at both ends
/// (which holds every rotation).
fn swept_box(sweep: &Sweep, moving: &Moving, leaf_shape: &Shape) -> Aabb {
    if sweep.angle() == 0.0 {
        let at = |t: f64| shape_aabb(leaf_shape, &sweep.transform_at(t).mul_transform(&moving.pose_local));
        return at(0.0).union(&at(1.0));
    }
    let r = DVec3::splat(moving.max_radius(sweep.com_local));
    Aabb::from_center_half_extents(sweep.com_start_world, r)
        .union(&Aabb::from_center_half_extents(sweep.com_end_world, r))
}

/// Sweeps the leaf against one static leaf shape at `pose_static`.
fn sweep_against_static(
    leaf_sweep: &mut LeafSweep,
    static_leaf: &Shape,
    pose_static: &Transform,
    swept: &Aabb,
) {
    let end_pose = leaf_sweep.sweep.transform_at(1.0).mul_transform(&leaf_sweep.moving.pose_local);
    let (moving_shape, margin) = (leaf_sweep.shape, leaf_sweep.scale.target);
    // The contact at the end of the step is the same for every triangle of a mesh: find it once.
    let mut end_manifold: Option<Option<Manifold>> = None;
    let mut end_contact = || {
        *end_manifold.get_or_insert_with(|| {
            collide(static_leaf, pose_static, moving_shape, &end_pose, margin, &mut PairCache::default())
        })
    };
    let close_at_start = match static_leaf {
        Shape::Plane(plane) => {
            let normal_world = pose_static.rotation * plane.normal;
            let offset = plane.offset + normal_world.dot(pose_static.translation);
            leaf_sweep.against(&Target::HalfSpace { normal_world, offset }, &mut end_contact)
        }
        Shape::TriMesh(mesh) => {
            sweep_against_triangles(leaf_sweep, mesh, pose_static, swept, &mut end_contact)
        }
        Shape::HeightField(field) => {
            sweep_against_triangles(leaf_sweep, field, pose_static, swept, &mut end_contact)
        }
        convex => Rounded::of(convex).is_some_and(|shape| {
            leaf_sweep.against(&Target::Convex { shape, pose: *pose_static }, &mut end_contact)
        }),
    };
    if close_at_start {
        let end_separation = end_contact().map_or(f64::INFINITY, |m| m.min_separation());
        if let Some(fraction) = depth_limit(leaf_sweep, static_leaf, pose_static, end_separation) {
            leaf_sweep.fraction = leaf_sweep.fraction.min(fraction);
        }
    }
}

/// Bisection steps of [`depth_limit`]: the fraction to within 2⁻²⁰ of the step.
const DEPTH_BISECTIONS: u32 = 20;

/// For a leaf already touching a static shape at the start of the step: the last fraction at
/// which it is no deeper inside the shape than the target separation (or than it was at the
/// start, if deeper then), when it ends deeper than that. The contacts should hold a touching
/// body at the surface; when they let it sink (a thin box turning edge-first into a thin wall),
/// this is what keeps it from working its way through. Depths are the contact manifold's, found
/// by bisection on the sweep.
fn depth_limit(
    leaf_sweep: &LeafSweep,
    static_leaf: &Shape,
    pose_static: &Transform,
    end_separation: f64,
) -> Option<f64> {
    let margin = leaf_sweep.scale.target;
    let separation_at = |t: f64| {
        let pose = leaf_sweep.sweep.transform_at(t).mul_transform(&leaf_sweep.moving.pose_local);
        collide(static_leaf, pose_static, leaf_sweep.shape, &pose, margin, &mut PairCache::default())
            .map_or(f64::INFINITY, |m| m.min_separation())
    };
    if end_separation >= -margin {
        return None;
    }
    let limit = separation_at(0.0).min(-margin);
    if end_separation >= limit {
        return None;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..DEPTH_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if separation_at(mid) >= limit {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// Sweeps the leaf against the triangles of a mesh or height field under the swept box that face
/// the leaf's centre at the start of the step. Returns true when it was already within the target
/// separation of one of them at the start.
fn sweep_against_triangles<S: TriangleSource + ?Sized>(
    leaf_sweep: &mut LeafSweep,
    source: &S,
    pose_static: &Transform,
    swept: &Aabb,
    end_contact: &mut impl FnMut() -> Option<Manifold>,
) -> bool {
    let box_local = points_aabb(&swept.corners(), &pose_static.inverse());
    let start_local = pose_static.inverse_transform_point(
        leaf_sweep.sweep.transform_at(0.0).mul_transform(&leaf_sweep.moving.pose_local).translation,
    );
    let mut triangles = Vec::new();
    source.query(&box_local, &mut |t| triangles.push(t));
    triangles.sort_unstable();
    let mut close_at_start = false;
    for t in triangles {
        let v = source.triangle(t);
        let n_t = source.triangle_normal(t);
        if n_t == DVec3::ZERO || n_t.dot(start_local - v[0]) < 0.0 {
            continue;
        }
        let target =
            Target::Convex { shape: Rounded { core: Core::Triangle(v), radius: 0.0 }, pose: *pose_static };
        close_at_start |= leaf_sweep.against(&target, end_contact);
    }
    close_at_start
}
