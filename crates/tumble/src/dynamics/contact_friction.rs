//! Coulomb friction of a whole manifold, applied at its centre ("patch friction", as in PhysX).
//!
//! A face resting on a face has up to four points, and friction rows solved point after point
//! favour the first: the tangent impulses come out unequal, their moments about the normal do not
//! cancel, and the body turns a little at every substep (a pyramid of boxes walked sideways by
//! centimetres). One friction anchor at the centre `c` of the points does not depend on their
//! order:
//!
//! - two tangent rows at `c`, solved together: `Ċ_t = P_t (v_b + ω_b × r_b − v_a − ω_a × r_a)`
//!   with `P_t = 1 − n nᵀ`, the impulse vector clamped to the disc `|λ_t| ≤ μ Σλ_n` (Coulomb's
//!   cone for the patch's total load);
//! - one twist row about the normal: `Ċ_τ = n·(ω_b − ω_a)`, clamped to `|λ_τ| ≤ μ Σ λ_nᵢ dᵢ`,
//!   the largest moment the points' friction can exert, `dᵢ` being each point's distance from `c`
//!   in the tangent plane.
//!
//! A single point (a ball, a tipped box's corner) is the same as per-point friction.

use crate::dynamics::contact_block::MAX_POINTS;
use crate::dynamics::contact_solver::{
    linear_pair, round_anchors, round_locals, shared_levers, tangent_inverse,
};
use crate::dynamics::joint::parts::apply_point_impulse;
use crate::dynamics::solver_body::SolverBody;
use crate::math::{DMat3, DVec3};

#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct PatchFriction {
    /// The centre as material points of each body (centres of curvature on a round side, see
    /// `PointConstraint::anchors`).
    r_a_local: DVec3,
    r_b_local: DVec3,
    /// The shared levers of the centre at the step start: used while the pair is still, as
    /// the normal rows use theirs (contact_solver.rs, `solve_normals`).
    pub levers_start: (DVec3, DVec3),
    /// Each point's distance from the centre in the tangent plane (the twist row's lever arms).
    pub twist_arms: [f64; MAX_POINTS],
    /// Inverse of the 2×2 tangent effective mass at the centre, embedded in 3×3 over the plane,
    /// and the isotropic tangent effective mass `2 / trace(K_t)` that steers sliding friction (see
    /// `solve`), both from the step start. (Built from the levers of every pass instead, as the
    /// normal rows are, a ragdoll lying on the ground no longer came to rest within 10 s (J6); the
    /// friction bound `μΣλ_n` keeps what a mismatched mass can do in check.)
    pub tangent_masses: (DMat3, f64),
    /// Accumulated friction impulse per substep, on body b, world frame.
    pub tangent_impulse: DVec3,
    /// Accumulated twist impulse about the normal, on body b.
    pub twist_impulse: f64,
}

impl PatchFriction {
    pub const EMPTY: PatchFriction = PatchFriction {
        r_a_local: DVec3::ZERO,
        r_b_local: DVec3::ZERO,
        levers_start: (DVec3::ZERO, DVec3::ZERO),
        twist_arms: [0.0; MAX_POINTS],
        tangent_masses: (DMat3::ZERO, 0.0),
        tangent_impulse: DVec3::ZERO,
        twist_impulse: 0.0,
    };

    /// Stage "prepare": the centre of the points (offsets `arms` from each centre of mass at the
    /// step start) and the warm-start impulses.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        a: &SolverBody,
        b: &SolverBody,
        arms: &[(DVec3, DVec3)],
        radii: (f64, f64),
        normal: DVec3,
        com_offset: DVec3,
        tangent_impulse: DVec3,
        twist_impulse: f64,
    ) -> PatchFriction {
        let count = arms.len().max(1) as f64;
        let r_a = arms.iter().map(|r| r.0).sum::<DVec3>() / count;
        let r_b = arms.iter().map(|r| r.1).sum::<DVec3>() / count;
        // The part of `v` in the tangent plane.
        let tangent = |v: DVec3| v - normal.dot(v) * normal;
        let mut twist_arms = [0.0; MAX_POINTS];
        for (arm, r) in twist_arms.iter_mut().zip(arms) {
            *arm = tangent(r.1 - r_b).length();
        }
        let (r_a_local, r_b_local) = round_locals((r_a, r_b), radii, normal, a, b);
        PatchFriction {
            r_a_local,
            r_b_local,
            levers_start: shared_levers((r_a, r_b), com_offset, a, b),
            twist_arms,
            tangent_masses: tangent_masses(a, b, (r_a, r_b), normal),
            tangent_impulse: tangent(tangent_impulse),
            twist_impulse,
        }
    }

    /// The levers the friction impulse acts at now: the centre's offsets turned with the bodies
    /// (see `PointConstraint::anchors`) and shared, or the step-start ones while the pair is still.
    #[inline]
    pub fn levers(
        &self,
        radii: (f64, f64),
        normal: DVec3,
        com_offset: DVec3,
        a: &SolverBody,
        b: &SolverBody,
    ) -> (DVec3, DVec3) {
        if linear_pair(radii, a, b) {
            return self.levers_start;
        }
        let anchors = round_anchors((self.r_a_local, self.r_b_local), radii, normal, a, b);
        shared_levers(anchors, com_offset, a, b)
    }

    /// Stage "warm start", at the levers of `levers` (or, on a one-point manifold, the point's,
    /// which are the same).
    pub fn warm_start(
        &self,
        (r_a, r_b): (DVec3, DVec3),
        normal: DVec3,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        apply_point_impulse(a, b, r_a, r_b, self.tangent_impulse);
        let twist = self.twist_impulse * normal;
        a.w -= a.inv_inertia * twist;
        b.w += b.inv_inertia * twist;
    }

    /// Stage "solve"/"relax" (friction has no position error, so both are the same): the
    /// tangent rows bounded by `μ Σλ_n`, the twist row by `μ Σ λ_nᵢ dᵢ`.
    /// `levers` as for `warm_start` (the bodies' velocities change within, their poses do not).
    pub fn solve(
        &mut self,
        (r_a, r_b): (DVec3, DVec3),
        normal: DVec3,
        friction: f64,
        normal_impulses: &[f64],
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let total: f64 = normal_impulses.iter().sum();
        let twist_limit: f64 =
            friction * normal_impulses.iter().zip(&self.twist_arms).map(|(l, d)| l * d).sum::<f64>();
        if twist_limit > 0.0 {
            // The effective mass with the inverse inertias as they are now: with the step-start
            // ones, a body that turns far within the step (a stick at 300 rad/s turns 1.25 rad
            // per substep) gets impulses too large for it, and an impulse more than twice the
            // right one adds energy. The normal rows do the same (contact_solver.rs).
            let k_twist = normal.dot((a.inv_inertia + b.inv_inertia) * normal);
            let twist_mass = if k_twist > 0.0 { 1.0 / k_twist } else { 0.0 };
            let w_rel = normal.dot(b.w - a.w);
            let old = self.twist_impulse;
            self.twist_impulse = (old - twist_mass * w_rel).clamp(-twist_limit, twist_limit);
            let twist = (self.twist_impulse - old) * normal;
            a.w -= a.inv_inertia * twist;
            b.w += b.inv_inertia * twist;
        } else if self.twist_impulse != 0.0 {
            // No load, no twist friction: take back what the warm start applied. (Only zeroing
            // the accumulator left the warm start's twist in the bodies: a stick whose long axis
            // turned along the normal, where its inertia is 200 times smaller, was spun up by
            // hundreds of rad/s by a contact carrying no load.)
            let twist = self.twist_impulse * normal;
            a.w += a.inv_inertia * twist;
            b.w -= b.inv_inertia * twist;
            self.twist_impulse = 0.0;
        }

        // Sticking is solved with the full 2×2 tangent mass. Sliding friction must oppose the
        // slip, but the 2×2 mass turns the impulse away from it (by ~20° at a box corner, which
        // cut the friction of a sliding box by 6%); so a sliding patch is updated with the
        // isotropic mass, whose fixed point on the rim is anti-parallel to the slip velocity.
        let (tangent_mass, sliding_mass) = self.tangent_masses;
        let dv = b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a);
        let vt = dv - normal.dot(dv) * normal;
        let old = self.tangent_impulse;
        let mut new = old - tangent_mass * vt;
        let max = friction * total;
        if new.length() > max {
            new = old - sliding_mass * vt;
            let len = new.length();
            if len > max {
                new *= max / len;
            }
        }
        self.tangent_impulse = new;
        apply_point_impulse(a, b, r_a, r_b, new - old);
    }
}

/// The tangent effective masses at the levers `(r_a, r_b)`: the inverse of the 2×2 tangent block
/// of `K`, embedded in 3×3 over the plane, and the isotropic `2 / trace(K_t)` that steers sliding
/// friction (see `solve`). On an orthonormal basis `t₁, t₂` of the plane the block's entries are
/// `tᵢ·K tⱼ` with `K = (1/m_a + 1/m_b)·1 − r̂_a I_a⁻¹ r̂_a − r̂_b I_b⁻¹ r̂_b`, and each body adds
/// `(r × tᵢ)·I⁻¹ (r × tⱼ)` (as `r̂ᵀ = −r̂`): four inertia products instead of the two 3×3
/// matrix products per body of `K` itself.
fn tangent_masses(a: &SolverBody, b: &SolverBody, (r_a, r_b): (DVec3, DVec3), normal: DVec3) -> (DMat3, f64) {
    let (t1, t2) = normal.any_orthonormal_pair();
    let (a1, a2, b1, b2) = (r_a.cross(t1), r_a.cross(t2), r_b.cross(t1), r_b.cross(t2));
    let (ia1, ia2) = (a.inv_inertia * a1, a.inv_inertia * a2);
    let (ib1, ib2) = (b.inv_inertia * b1, b.inv_inertia * b2);
    let linear = a.inv_mass + b.inv_mass;
    let k11 = linear + a1.dot(ia1) + b1.dot(ib1);
    let k12 = a1.dot(ia2) + b1.dot(ib2);
    let k22 = linear + a2.dot(ia2) + b2.dot(ib2);
    // The trace over the plane: `trace(K) − n·K n`.
    let trace_t = k11 + k22;
    (tangent_inverse((t1, t2), [k11, k12, k22]), if trace_t > 0.0 { 2.0 / trace_t } else { 0.0 })
}
