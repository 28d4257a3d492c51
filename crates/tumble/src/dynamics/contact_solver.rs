//! Contact constraints in the soft step: per manifold point a non-penetration row and two friction
//! rows, plus per manifold a torsional row (spin about the normal) and two rolling rows.
//!
//! - **Normal**: `Ċ = n·(v_b + ω_b×r_b − v_a − ω_a×r_a)`, `λ ≥ 0`. The separation now is the
//!   separation the narrow phase measured, advanced by the bodies' motion since the step began
//!   (`s = s₀ + n·(Δp_b + r_b − Δp_a − r_a) − n·(r_b⁰ − r_a⁰)`). Where `s > 0` the row is
//!   *speculative*: it only removes the approach speed that would close the gap within the substep
//!   (`bias = s/h`), so fast bodies stop at the surface instead of tunnelling. Where `s ≤ 0` the
//!   row is soft (contact hertz, damping ratio), with the push-out speed capped.
//! - **Friction**: Coulomb's cone. The two tangent rows are solved together and the tangent
//!   impulse vector is clamped to the disc `|λ_t| ≤ μ λ_n` (a cone, not a pyramid, so friction has
//!   no preferred directions).
//! - **Rolling and torsional friction**: angular rows on the relative angular velocity, clamped by
//!   `μ_roll·Σλ_n` and `μ_torsion·Σλ_n` (coefficients in metres: lever arms of the resistance).
//! - **Restitution**: after the substeps, points whose approach speed when their row engaged
//!   exceeded the threshold get the normal impulse that makes `v_n = −e·v_n⁰` (the speed at
//!   engagement, not at the start of the step: gravity speeds a falling body up in between).
//! - **Anchors**: on corners, edges and faces the contact point is a material point that turns
//!   with the body; on round surfaces (spheres, capsules) it keeps its step-start offset, so a
//!   rolling ball's contact stays under it.
//!
//! Accumulated impulses are kept per point (matched by feature id across steps) and applied again
//! at every substep's warm start.

use crate::collision::ProxyKey;
use crate::dynamics::joint::parts::invert_or_zero;
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{DMat3, DVec3};

/// Impulses remembered for one manifold point between steps (for warm starting).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactImpulse {
    /// Accumulated normal impulse per substep, N·s.
    pub normal: f64,
    /// Accumulated friction impulse per substep, world frame (kept as a vector so a slightly
    /// turned normal does not scramble it).
    pub tangent_world: DVec3,
    /// The largest normal impulse applied during the last step (for restitution and events).
    pub max_normal: f64,
}

/// The friction and restitution of a contact, after combining the two shapes' materials.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactMaterial {
    pub friction: f64,
    pub restitution: f64,
    pub rolling_friction: f64,
    pub torsional_friction: f64,
}

/// One point of a contact, as the narrow phase measured it.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct ContactPointInput {
    pub point_world: DVec3,
    pub separation: f64,
    pub impulse: ContactImpulse,
}

#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
struct PointConstraint {
    softness: Softness,
    /// The contact's surface point on each body relative to its centre of mass at the start of
    /// the step, world frame (the two lie on one normal line, `separation` apart).
    r_a0: DVec3,
    r_b0: DVec3,
    /// The same surface points in the body frames (material points), for the separation.
    r_a_local: DVec3,
    r_b_local: DVec3,
    /// Separation measured by the narrow phase at the start of the step.
    base_separation: f64,
    normal_mass: f64,
    /// Inverse of the 2×2 tangent effective mass, embedded in 3×3 over the tangent plane.
    tangent_mass: DMat3,
    /// Isotropic tangent effective mass, `2 / trace(K_t)`: steers sliding friction (see `solve`).
    sliding_mass: f64,
    normal_impulse: f64,
    tangent_impulse: DVec3,
    max_normal_impulse: f64,
    /// Normal velocity at the start of the step (negative = approaching).
    relative_velocity: f64,
}

impl PointConstraint {
    /// The contact's surface points relative to each body's centre of mass now, world frame.
    ///
    /// On a corner, edge or face the contact point is a material point: it turns with the body
    /// (that is what makes a tumbling box's corner stop dead on impact). On a round surface
    /// (sphere, capsule) it is not: as a ball rolls, its contact stays at the bottom, and a
    /// material point would roll away from the ground and let the ball sink; so there the
    /// step-start offset is kept, which also keeps the contact on the line through the ball's
    /// centre (no spurious torque, even from the large impulse that stops a fast ball).
    #[inline]
    fn anchors(&self, round: (bool, bool), a: &SolverBody, b: &SolverBody) -> (DVec3, DVec3) {
        let r_a = if round.0 { self.r_a0 } else { a.q * self.r_a_local };
        let r_b = if round.1 { self.r_b0 } else { b.q * self.r_b_local };
        (r_a, r_b)
    }

    /// The separation now: the measured separation advanced by how far each body's contact point
    /// moved since the step began.
    #[inline]
    fn separation(&self, (r_a, r_b): (DVec3, DVec3), a: &SolverBody, b: &SolverBody, n: DVec3) -> f64 {
        let moved_b = b.dp + (r_b - self.r_b0);
        let moved_a = a.dp + (r_a - self.r_a0);
        self.base_separation + n.dot(moved_b - moved_a)
    }

    const EMPTY: PointConstraint = PointConstraint {
        softness: Softness::RIGID_VELOCITY,
        r_a0: DVec3::ZERO,
        r_b0: DVec3::ZERO,
        r_a_local: DVec3::ZERO,
        r_b_local: DVec3::ZERO,
        base_separation: 0.0,
        normal_mass: 0.0,
        tangent_mass: DMat3::ZERO,
        sliding_mass: 0.0,
        normal_impulse: 0.0,
        tangent_impulse: DVec3::ZERO,
        max_normal_impulse: 0.0,
        relative_velocity: 0.0,
    };
}

/// A manifold prepared for the solver.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct ContactConstraint {
    /// The contact this came from (its proxy pair).
    pub key: (ProxyKey, ProxyKey),
    /// Whether each side is a round surface (sphere, capsule) whose contact point stays put as the
    /// body turns, rather than a corner or face that carries it along (see `anchors`).
    round: (bool, bool),
    pub body_a: usize,
    pub body_b: usize,
    normal: DVec3,
    material: ContactMaterial,
    points: [PointConstraint; 4],
    point_count: usize,
    /// Angular effective mass of the pair, `(I_a⁻¹ + I_b⁻¹)⁻¹`, for rolling and torsion.
    angular_mass: DMat3,
    rolling_impulse: DVec3,
    torsional_impulse: f64,
}

impl ContactConstraint {
    /// Stage "prepare" for one manifold. `com_a`, `com_b` are the centres of mass at the step
    /// start; `relax_static` selects the stiffer softness used against static bodies.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        key: (ProxyKey, ProxyKey),
        (body_a, body_b): (usize, usize),
        (a, b): (&SolverBody, &SolverBody),
        (com_a, com_b): (DVec3, DVec3),
        round: (bool, bool),
        normal: DVec3,
        points: &[ContactPointInput],
        material: ContactMaterial,
        ctx: &StepContext,
    ) -> ContactConstraint {
        let hertz =
            if a.inv_mass == 0.0 || b.inv_mass == 0.0 { ctx.static_contact_hertz } else { ctx.contact_hertz };
        let mut constraint = ContactConstraint {
            key,
            round,
            body_a,
            body_b,
            normal,
            material,
            points: [PointConstraint::EMPTY; 4],
            point_count: points.len().min(4),
            angular_mass: invert_or_zero(a.inv_inertia + b.inv_inertia),
            rolling_impulse: DVec3::ZERO,
            torsional_impulse: 0.0,
        };
        let tangent_projector = DMat3::IDENTITY - outer(normal, normal);
        for (pc, input) in constraint.points.iter_mut().zip(points) {
            // The narrow phase's point is midway between the surfaces. A round body is pushed at
            // its own surface point, on the line through its centre (a speculative point can lie
            // far outside it, and pushing there would spin it); others at the midpoint.
            let r_a = input.point_world
                - if round.0 { 0.5 * input.separation * normal } else { DVec3::ZERO }
                - com_a;
            let r_b = input.point_world + if round.1 { 0.5 * input.separation * normal } else { DVec3::ZERO }
                - com_b;
            let k = crate::dynamics::joint::parts::point_mass_matrix(a, r_a)
                + crate::dynamics::joint::parts::point_mass_matrix(b, r_b);
            let kn = normal.dot(k * normal);
            // The tangent block of K, inverted on the tangent plane (the normal direction gets a
            // unit entry so the 3×3 is invertible, then is projected away).
            let kt = tangent_projector * k * tangent_projector + outer(normal, normal);
            let relative_velocity = normal.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
            let normal_mass = if kn > 0.0 { 1.0 / kn } else { 0.0 };
            let softness = Softness::new(hertz, ctx.contact_damping_ratio, ctx.h);
            *pc = PointConstraint {
                softness,
                r_a0: r_a,
                r_b0: r_b,
                r_a_local: a.q.inverse() * r_a,
                r_b_local: b.q.inverse() * r_b,
                base_separation: input.separation,
                normal_mass,
                tangent_mass: tangent_projector * invert_or_zero(kt) * tangent_projector,
                sliding_mass: {
                    let trace_t = k.x_axis.x + k.y_axis.y + k.z_axis.z - kn;
                    if trace_t > 0.0 {
                        2.0 / trace_t
                    } else {
                        0.0
                    }
                },
                normal_impulse: if ctx.warm_starting { input.impulse.normal } else { 0.0 },
                tangent_impulse: if ctx.warm_starting {
                    tangent_projector * input.impulse.tangent_world
                } else {
                    DVec3::ZERO
                },
                max_normal_impulse: 0.0,
                relative_velocity,
            };
        }
        constraint
    }

    fn apply(a: &mut SolverBody, b: &mut SolverBody, r_a: DVec3, r_b: DVec3, p: DVec3) {
        crate::dynamics::joint::parts::apply_point_impulse(a, b, r_a, r_b, p);
    }

    /// Stage "warm start": apply the accumulated impulses again.
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        let round = self.round;
        for pc in &self.points[..self.point_count] {
            let (r_a, r_b) = pc.anchors(round, a, b);
            Self::apply(a, b, r_a, r_b, pc.normal_impulse * self.normal + pc.tangent_impulse);
        }
        let angular = self.rolling_impulse + self.torsional_impulse * self.normal;
        a.w -= a.inv_inertia * angular;
        b.w += b.inv_inertia * angular;
    }

    /// Stage "solve" (`use_bias`) or "relax" (`!use_bias`).
    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, ctx: &StepContext, use_bias: bool) {
        let round = self.round;
        let n = self.normal;
        let mut total_normal = 0.0;
        for pc in &mut self.points[..self.point_count] {
            let (r_a, r_b) = pc.anchors(round, a, b);
            let s = pc.separation((r_a, r_b), a, b, n);
            let (bias, mass_scale, impulse_scale) = if s > 0.0 {
                // Speculative: allow closing the gap, no more.
                (s * ctx.inv_h, 1.0, 0.0)
            } else if use_bias {
                let soft = pc.softness;
                (
                    (soft.bias_rate * s).max(-ctx.max_contact_push_velocity),
                    soft.mass_scale,
                    soft.impulse_scale,
                )
            } else {
                (0.0, 1.0, 0.0)
            };
            let vn = n.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
            if vn + bias < 0.0 {
                // The approach speed at impact (for restitution) is the fastest seen when the row
                // engages, before its impulse acts: gravity keeps speeding a falling body up after
                // the step began, and a speculative row engages before the surfaces touch.
                pc.relative_velocity = pc.relative_velocity.min(vn);
            }
            let impulse = -pc.normal_mass * mass_scale * (vn + bias) - impulse_scale * pc.normal_impulse;
            let new_impulse = (pc.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - pc.normal_impulse;
            pc.normal_impulse = new_impulse;
            pc.max_normal_impulse = pc.max_normal_impulse.max(applied);
            total_normal += new_impulse;
            Self::apply(a, b, r_a, r_b, applied * n);
        }

        // Friction: the tangent impulse vector stays inside the disc of radius μ·λ_n. Sticking
        // is solved with the full 2×2 tangent mass. Sliding friction must oppose the slip, but the
        // 2×2 mass turns the impulse away from it (by ~20° at a box corner, which cut the
        // friction of a sliding box by 6%); so a point that slides is updated with the isotropic
        // mass, whose fixed point on the rim is anti-parallel to the slip velocity.
        let mu = self.material.friction;
        for pc in &mut self.points[..self.point_count] {
            let (r_a, r_b) = pc.anchors(round, a, b);
            let dv = b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a);
            let vt = dv - n.dot(dv) * n;
            let old = pc.tangent_impulse;
            let mut new = old - pc.tangent_mass * vt;
            let max = mu * pc.normal_impulse;
            if new.length() > max {
                new = old - pc.sliding_mass * vt;
                let len = new.length();
                if len > max {
                    new *= max / len;
                }
            }
            pc.tangent_impulse = new;
            Self::apply(a, b, r_a, r_b, new - old);
        }

        // Torsional and rolling friction, bounded by the manifold's total normal impulse.
        if self.material.torsional_friction > 0.0 {
            let max = self.material.torsional_friction * total_normal;
            let w_rel = n.dot(b.w - a.w);
            let k = n.dot(self.angular_mass * n);
            let old = self.torsional_impulse;
            self.torsional_impulse = (old - k * w_rel).clamp(-max, max);
            let p = (self.torsional_impulse - old) * n;
            a.w -= a.inv_inertia * p;
            b.w += b.inv_inertia * p;
        }
        if self.material.rolling_friction > 0.0 {
            let max = self.material.rolling_friction * total_normal;
            let w = b.w - a.w;
            let w_roll = w - n.dot(w) * n;
            let old = self.rolling_impulse;
            let mut new = old - self.angular_mass * w_roll;
            new -= n.dot(new) * n;
            let len = new.length();
            if len > max {
                new *= max / len;
            }
            self.rolling_impulse = new;
            a.w -= a.inv_inertia * (new - old);
            b.w += b.inv_inertia * (new - old);
        }
    }

    /// Stage "restitution": after the substeps, make points that approached faster than the
    /// threshold separate at `e` times their approach speed.
    pub fn apply_restitution(&mut self, a: &mut SolverBody, b: &mut SolverBody, ctx: &StepContext) {
        let round = self.round;
        let e = self.material.restitution;
        if e == 0.0 {
            return;
        }
        let n = self.normal;
        for pc in &mut self.points[..self.point_count] {
            if pc.relative_velocity > -ctx.restitution_threshold || pc.max_normal_impulse == 0.0 {
                continue;
            }
            let (r_a, r_b) = pc.anchors(round, a, b);
            let vn = n.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
            let impulse = -pc.normal_mass * (vn + e * pc.relative_velocity);
            let new_impulse = (pc.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - pc.normal_impulse;
            pc.normal_impulse = new_impulse;
            pc.max_normal_impulse = pc.max_normal_impulse.max(applied);
            Self::apply(a, b, r_a, r_b, applied * n);
        }
    }

    /// Stage "store impulses": what the next step warm-starts from, per point in input order.
    pub fn impulses(&self) -> impl Iterator<Item = ContactImpulse> + '_ {
        self.points[..self.point_count].iter().map(|pc| ContactImpulse {
            normal: pc.normal_impulse,
            tangent_world: pc.tangent_impulse,
            max_normal: pc.max_normal_impulse,
        })
    }
}

fn outer(u: DVec3, v: DVec3) -> DMat3 {
    DMat3::from_cols(u * v.x, u * v.y, u * v.z)
}
