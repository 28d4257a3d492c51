//! Contact constraints in the soft step: per manifold point a non-penetration row, per manifold
//! Coulomb friction at its centre, plus a torsional row (spin about the normal) and two rolling
//! rows for the materials that ask for them.
//!
//! - **Normal**: `Ċ = n·(v_b + ω_b×r_b − v_a − ω_a×r_a)`, `λ ≥ 0`. The separation now is the
//!   separation the narrow phase measured, advanced by the bodies' motion since the step began
//!   (`s = s₀ + n·(Δp_b + r_b − Δp_a − r_a) − n·(r_b⁰ − r_a⁰)`). Where `s > 0` the row is
//!   *speculative*: it only removes the approach speed that would close the gap within the substep
//!   (`bias = s/h`), so fast bodies stop at the surface instead of tunnelling. Where `s ≤ 0` the
//!   row is soft (contact hertz, damping ratio), with the push-out speed capped. A manifold's
//!   normal rows are solved together as one small LCP (contact_block.rs), so a symmetric load
//!   gives symmetric impulses whatever the order of the points.
//! - **Steady load**: a soft row is a spring, and a spring carrying a load `L` is compressed by
//!   `L/k` — summed up a stack of ten boxes that is 2.6 cm. Each manifold learns the load it
//!   carries at rest (a low-pass of its impulse, time constant `steady_load_time`) and the spring
//!   gives way only to the impulse above it: a slow integral term on the spring–damper, which
//!   holds resting loads at zero penetration while impacts still meet the soft spring.
//! - **Friction**: Coulomb's cone for the whole manifold at its centre (contact_friction.rs).
//! - **Rolling and torsional friction**: angular rows on the relative angular velocity, clamped by
//!   `μ_roll·Σλ_n` and `μ_torsion·Σλ_n` (coefficients in metres: lever arms of the resistance).
//! - **Restitution**: points whose approach speed when their row engaged exceeded the threshold
//!   get the normal impulses (solved together) that make `v_n = −e·v_n⁰`, with `v_n⁰` the speed at
//!   engagement (not at the start of the step: gravity speeds a falling body up in between, and a
//!   spinning corner's normal speed changes). They bounce after the relax pass of the substep in
//!   which the approach stops, or at the end of the step (docs/solver.md, "Restitution").
//! - **Anchors**: on corners, edges and faces the contact point is a material point that turns
//!   with the body; on round surfaces (spheres, capsules) it keeps its step-start offset, so a
//!   rolling ball's contact stays under it. Impulses act at one world point shared by both bodies
//!   (`shared_levers`), so collisions keep the total angular momentum.
//!
//! Accumulated impulses are kept per point (matched by feature id across steps) and applied again
//! at every substep's warm start.

use crate::dynamics::contact_block::{
    coupling_entry, normal_coupling, pack_symmetric, FreeFactor, NormalBlock, RowSet, ALL_ROWS,
    COUPLING_ENTRIES, MAX_POINTS,
};
use crate::dynamics::contact_friction::PatchFriction;
use crate::dynamics::softness::Softness;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::{still_pair, SolverBody};
use crate::math::{DMat3, DVec3};

/// Separation, m, up to which a row stays soft rather than speculative. A resting contact that
/// carries its load without sagging (the steady load, `solve_normals`) sits at zero separation;
/// switching there between the rigid speculative row and the soft one on round-off would make the
/// row's stiffness jump from substep to substep. Within this band the soft row lets the surfaces
/// close at no more than `bias_rate·s`.
const SOFT_BAND: f64 = 1e-4;

/// Impulses remembered for one manifold point between steps (for warm starting).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactImpulse {
    /// Accumulated normal impulse per substep, N·s.
    pub normal: f64,
    /// This point's share of the manifold's accumulated friction impulse per substep, world
    /// frame (kept as a vector so a slightly turned normal does not scramble it).
    pub tangent_world: DVec3,
    /// This point's share of the manifold's accumulated twist-friction impulse per substep.
    #[serde(default)]
    pub twist: f64,
    /// The largest normal impulse applied during the last step (for restitution and events).
    pub max_normal: f64,
    /// The steady part of the normal impulse per substep (a low-pass of `normal`): the load the
    /// point carries at rest, which the soft row holds without compressing (see `solve`).
    #[serde(default)]
    pub steady_normal: f64,
    /// How long the point has been learning its steady load, s (see `update_steady_load`).
    #[serde(default)]
    pub steady_age: f64,
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

/// The points a manifold is prepared from (`ContactConstraint::prepare_in_place`), read one at
/// a time: the solver's set-up reads them from the contact's manifold and impulses in place
/// rather than copying them into an array first.
pub(crate) trait PointInputs {
    fn len(&self) -> usize;
    fn get(&self, i: usize) -> ContactPointInput;
}

/// Points made by hand (the tests').
#[cfg(test)]
impl PointInputs for &[ContactPointInput] {
    fn len(&self) -> usize {
        <[ContactPointInput]>::len(self)
    }

    fn get(&self, i: usize) -> ContactPointInput {
        self[i]
    }
}

#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
struct PointConstraint {
    /// The contact's surface point on each body relative to its centre of mass at the start of
    /// the step, world frame (the two lie on one normal line, `separation` apart).
    r_a0: DVec3,
    r_b0: DVec3,
    /// The same surface points in the body frames (material points), for the separation.
    r_a_local: DVec3,
    r_b_local: DVec3,
    /// Separation measured by the narrow phase at the start of the step.
    base_separation: f64,
    normal_impulse: f64,
    /// Low-pass of `normal_impulse` over substeps: the steady load (see `ContactConstraint::solve`).
    steady_normal_impulse: f64,
    /// How long the steady load has been learned, s (`update_steady_load`).
    steady_age: f64,
    max_normal_impulse: f64,
    /// Normal velocity when the row engaged this step, before its impulse acted (negative =
    /// approaching; 0 until it engages).
    relative_velocity: f64,
    /// The restitution impulse given this step (one-off, not part of the per-substep impulse).
    restitution_impulse: f64,
    /// The point has bounced this step.
    bounced: bool,
}

impl PointConstraint {
    /// The contact's surface points relative to each body's centre of mass now, world frame.
    ///
    /// On a corner, edge or face the contact point is a material point: it turns with the body
    /// (that is what makes a tumbling box's corner stop dead on impact). On a round surface
    /// (sphere, capsule of radius `R`) it is not: as a ball rolls, its contact stays at the
    /// bottom, and a material point would roll away from the ground and let the ball sink. There
    /// the material point is the centre of curvature (the ball's centre, a point of the capsule's
    /// axis), and the contact is `R` from it along the normal: it stays on the line through the
    /// centre (no spurious torque, even from the large impulse that stops a fast ball) and moves
    /// with the body as a whole. (Holding the whole step-start offset fixed instead lets a capsule
    /// end rolling round a pivot push with a lever that lags its turning; that fed the rolling
    /// energy, exponentially.) `radii` are 0 for corners, edges and faces.
    #[inline]
    fn anchors(&self, radii: (f64, f64), n: DVec3, a: &SolverBody, b: &SolverBody) -> (DVec3, DVec3) {
        round_anchors((self.r_a_local, self.r_b_local), radii, n, a, b)
    }

    /// The separation now: the measured separation advanced by how far each body's contact point
    /// moved since the step began.
    #[inline]
    fn separation(&self, (r_a, r_b): (DVec3, DVec3), a: &SolverBody, b: &SolverBody, n: DVec3) -> f64 {
        let moved_b = b.dp + (r_b - self.r_b0);
        let moved_a = a.dp + (r_a - self.r_a0);
        self.base_separation + n.dot(moved_b - moved_a)
    }

    /// The normal row's right-hand side and compliance `γ` at separation `s` and normal velocity
    /// `vn` now, with `k_ii` its diagonal of `K` and `steady` the manifold's steady load per
    /// point; notes the approach speed when the row engages (for restitution).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn row_target(
        &mut self,
        s: f64,
        vn: f64,
        k_ii: f64,
        steady: f64,
        softness: Softness,
        ctx: &StepContext,
        use_bias: bool,
    ) -> (f64, f64) {
        let (bias, mass_scale, impulse_scale) = if s > SOFT_BAND {
            // Speculative: allow closing the gap, no more.
            (s * ctx.inv_h, 1.0, 0.0)
        } else if use_bias {
            (
                (softness.bias_rate * s).max(-ctx.max_contact_push_velocity),
                softness.mass_scale,
                softness.impulse_scale,
            )
        } else {
            (0.0, 1.0, 0.0)
        };
        if vn + bias < 0.0 {
            // The approach speed at impact (for restitution) is the fastest seen when the row
            // engages, before its impulse acts: gravity keeps speeding a falling body up after
            // the step began, and a speculative row engages before the surfaces touch.
            self.relative_velocity = self.relative_velocity.min(vn);
        }
        // The soft row's compliance `γ = k·impulse_scale/mass_scale` (contact_block.rs). It
        // leaks the accumulated impulse: that is the spring's give, and under a steady load L
        // it settles compressed by L/k. Leaking only the part above the steady load lets the
        // spring carry L at zero compression while shocks still meet the soft spring (a slow
        // integral term on top of the spring–damper).
        let gamma = if mass_scale > 0.0 { k_ii * impulse_scale / mass_scale } else { 0.0 };
        (-(vn + bias) - gamma * (self.normal_impulse - steady), gamma)
    }

    const EMPTY: PointConstraint = PointConstraint {
        r_a0: DVec3::ZERO,
        r_b0: DVec3::ZERO,
        r_a_local: DVec3::ZERO,
        r_b_local: DVec3::ZERO,
        base_separation: 0.0,
        normal_impulse: 0.0,
        steady_normal_impulse: 0.0,
        steady_age: 0.0,
        max_normal_impulse: 0.0,
        relative_velocity: 0.0,
        restitution_impulse: 0.0,
        bounced: false,
    };
}

/// Whether a manifold's rows may be taken linear in the step-start levers (see
/// `ContactConstraint::rows_now`): a still pair (`still_pair`), and no round side.
#[inline]
pub(crate) fn linear_pair(radii: (f64, f64), a: &SolverBody, b: &SolverBody) -> bool {
    radii == (0.0, 0.0) && still_pair(a, b)
}

/// Material offsets `(r_a_local, r_b_local)` from the step-start surface points `r_a`, `r_b`: the
/// points themselves, or on a round side (radius > 0) its centre of curvature, `R` behind the
/// surface along the normal `n` (from a to b). See `PointConstraint::anchors`. (Turned into the
/// body frames by the transposed rotation matrix, which `round_anchors` turns back with: half the
/// arithmetic of the quaternion's inverse rotation, and the matched pyramid's set-up 1.04x.)
#[inline]
pub(crate) fn round_locals(
    (r_a, r_b): (DVec3, DVec3),
    radii: (f64, f64),
    n: DVec3,
    a: &SolverBody,
    b: &SolverBody,
) -> (DVec3, DVec3) {
    (a.rotation.transpose() * (r_a - radii.0 * n), b.rotation.transpose() * (r_b + radii.1 * n))
}

/// The surface points now from the material offsets of `round_locals`.
#[inline]
pub(crate) fn round_anchors(
    (r_a_local, r_b_local): (DVec3, DVec3),
    radii: (f64, f64),
    n: DVec3,
    a: &SolverBody,
    b: &SolverBody,
) -> (DVec3, DVec3) {
    (a.rotation * r_a_local + radii.0 * n, b.rotation * r_b_local - radii.1 * n)
}

/// The inverse of `k`'s block on the plane perpendicular to the unit `normal`, as a 3×3 that maps
/// the plane to itself (and the normal to 0): the tangent effective mass of rolling rows.
pub(crate) fn tangent_block_inverse(k: DMat3, normal: DVec3) -> DMat3 {
    let (t1, t2) = normal.any_orthonormal_pair();
    let (k_t1, k_t2) = (k * t1, k * t2);
    tangent_inverse((t1, t2), [t1.dot(k_t1), t1.dot(k_t2), t2.dot(k_t2)])
}

/// `T B⁻¹ Tᵀ` for the symmetric block `B = [[b₁₁, b₁₂], [b₁₂, b₂₂]]` of a matrix on the orthonormal
/// basis `T = (t₁, t₂)` of a tangent plane: the block's inverse on the plane, embedded in 3×3 and
/// zero along the normal, the same whichever basis of the plane. Zero when the block is singular
/// to round-off (nothing moves along the plane).
pub(crate) fn tangent_inverse((t1, t2): (DVec3, DVec3), [b11, b12, b22]: [f64; 3]) -> DMat3 {
    let det = b11 * b22 - b12 * b12;
    let scale = b11.abs().max(b22.abs());
    // A NaN entry makes `det` NaN.
    if det.is_nan() || det <= 1e-12 * scale * scale {
        return DMat3::ZERO;
    }
    let inv_det = 1.0 / det;
    let (i11, i12, i22) = (b22 * inv_det, -b12 * inv_det, b11 * inv_det);
    // Column c of Σⱼₖ iⱼₖ tⱼ tₖᵀ is u t₁[c] + w t₂[c].
    let u = i11 * t1 + i12 * t2;
    let w = i12 * t1 + i22 * t2;
    DMat3::from_cols(u * t1.x + w * t2.x, u * t1.y + w * t2.y, u * t1.z + w * t2.z)
}

/// The lever arms at which a contact's impulse acts: one shared world point for both bodies.
///
/// The two anchors (`r_a`, `r_b`, material or round, see `PointConstraint::anchors`) start on one
/// normal line, but once the bodies move within the step they drift apart sideways; equal and
/// opposite impulses at two different points then exert a net moment `(P_b − P_a) × p`, and a
/// collision in free space would change the total angular momentum (by 3–6% in a glancing hit).
/// Acting at one point `M` on the segment between them conserves it exactly. `M` is weighted
/// towards the lighter body's anchor (`t = m_b⁻¹/(m_a⁻¹ + m_b⁻¹)`; at its own anchor when the other is fixed), so
/// a body against the ground is pushed exactly where it was before.
#[inline]
pub(crate) fn shared_levers(
    (r_a, r_b): (DVec3, DVec3),
    com_offset: DVec3,
    a: &SolverBody,
    b: &SolverBody,
) -> (DVec3, DVec3) {
    let total = a.inv_mass + b.inv_mass;
    if a.inv_mass == 0.0 || b.inv_mass == 0.0 || total == 0.0 {
        return (r_a, r_b);
    }
    // P_b − P_a, with the centres of mass where they are now.
    let d = com_offset + b.dp + r_b - a.dp - r_a;
    let t = b.inv_mass / total;
    (r_a + t * d, r_b - (1.0 - t) * d)
}

/// A manifold prepared for the solver.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct ContactConstraint {
    /// Each side's radius of curvature: a sphere's or capsule's radius, whose contact point stays
    /// at the bottom as the body rolls, or 0 for a corner or face that carries it along (see
    /// `anchors`).
    radii: (f64, f64),
    pub body_a: usize,
    pub body_b: usize,
    normal: DVec3,
    /// `c_b − c_a` at the step start: places the two anchors relative to each other.
    com_offset: DVec3,
    material: ContactMaterial,
    points: [PointConstraint; 4],
    point_count: usize,
    /// Coulomb friction at the manifold's centre (contact_friction.rs).
    friction: PatchFriction,
    rolling_impulse: DVec3,
    torsional_impulse: f64,
    /// The soft normal rows' stiffness and damping (the same for every point).
    softness: Softness,
    /// The normal rows' `K` at the step start, used while the pair is still (see `solve`):
    /// the upper triangle, row by row (`K` is symmetric).
    coupling_start: [f64; COUPLING_ENTRIES],
    /// The normal rows left free (not released) by the last block solve: the next one's first
    /// guess (contact_block.rs).
    free_rows: RowSet,
    /// The factors of the block with every row free while the pair is still, kept for the solve
    /// passes (`[1]`) and the relax passes (`[0]`): its `K` is then the step-start one, and the
    /// factors are the same from pass to pass (contact_block.rs, `FreeFactor`).
    free_factors: [FreeFactor; 2],
}

/// Applies the impulses `pᵢ` at levers `(r_aᵢ, r_bᵢ)` (`−pᵢ` to a, `+pᵢ` to b) at once: one
/// inverse-inertia product per body instead of one per point.
#[inline]
fn apply_point_impulses(
    a: &mut SolverBody,
    b: &mut SolverBody,
    levers: &[(DVec3, DVec3)],
    impulses: &[DVec3],
) {
    let (mut p, mut torque_a, mut torque_b) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for (&(r_a, r_b), &pi) in levers.iter().zip(impulses) {
        p += pi;
        torque_a += r_a.cross(pi);
        torque_b += r_b.cross(pi);
    }
    apply_impulse_and_moments(a, b, p, torque_a, torque_b);
}

/// Applies the impulse `p` (`−p` to a, `+p` to b) and the moments it exerts about each centre of
/// mass (`−torque_a` to a, `+torque_b` to b).
#[inline]
fn apply_impulse_and_moments(
    a: &mut SolverBody,
    b: &mut SolverBody,
    p: DVec3,
    torque_a: DVec3,
    torque_b: DVec3,
) {
    a.v -= a.inv_mass * p;
    a.w -= a.inv_inertia * torque_a;
    b.v += b.inv_mass * p;
    b.w += b.inv_inertia * torque_b;
}

impl ContactConstraint {
    /// A placeholder, before `prepare`.
    pub const EMPTY: ContactConstraint = ContactConstraint {
        radii: (0.0, 0.0),
        body_a: 0,
        body_b: 0,
        normal: DVec3::Z,
        com_offset: DVec3::ZERO,
        material: ContactMaterial {
            friction: 0.0,
            restitution: 0.0,
            rolling_friction: 0.0,
            torsional_friction: 0.0,
        },
        points: [PointConstraint::EMPTY; 4],
        point_count: 0,
        friction: PatchFriction::EMPTY,
        rolling_impulse: DVec3::ZERO,
        torsional_impulse: 0.0,
        softness: Softness::RIGID_VELOCITY,
        coupling_start: [0.0; COUPLING_ENTRIES],
        free_rows: ALL_ROWS,
        free_factors: [FreeFactor::EMPTY; 2],
    };

    /// Stage "prepare" for one manifold, written over this constraint in place — every field (the
    /// solver prepares straight into the constraints' array: building each on the stack and
    /// copying it in moved another kilobyte per manifold). `com_a`, `com_b` are the centres of
    /// mass at the step start; a manifold against a static or kinematic body gets the stiffer
    /// static softness.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare_in_place(
        &mut self,
        (body_a, body_b): (usize, usize),
        (a, b): (&SolverBody, &SolverBody),
        (com_a, com_b): (DVec3, DVec3),
        radii: (f64, f64),
        normal: DVec3,
        points: impl PointInputs,
        material: ContactMaterial,
        ctx: &StepContext,
    ) {
        // The same two softnesses for every manifold of the step (solver.rs, `StepContext`).
        self.softness = if a.inv_mass == 0.0 || b.inv_mass == 0.0 {
            ctx.static_contact_softness
        } else {
            ctx.contact_softness
        };
        self.radii = radii;
        self.body_a = body_a;
        self.body_b = body_b;
        self.normal = normal;
        self.com_offset = com_b - com_a;
        self.material = material;
        self.point_count = points.len().min(4);
        let point = |i: usize| points.get(i);
        self.rolling_impulse = DVec3::ZERO;
        self.torsional_impulse = 0.0;
        // The block's first guess: the points that ended the last step carrying load, if any did;
        // a new contact's points all free.
        let loaded = (0..self.point_count)
            .fold(0, |set, i| set | (RowSet::from(ctx.warm_starting && point(i).impulse.normal > 0.0) << i));
        self.free_rows = if loaded == 0 { ALL_ROWS } else { loaded };
        self.free_factors.iter_mut().for_each(FreeFactor::forget);
        // Only the manifold's points: the places past `point_count` keep whatever they held, as
        // nothing reads them (a rain of spheres' single points wrote three empty points of 150
        // bytes each beside each one, and preparing is bound by the memory it writes).
        for (i, pc) in self.points[..self.point_count].iter_mut().enumerate() {
            let input = point(i);
            // The narrow phase's point is midway between the surfaces; each body's anchor is its
            // own surface point, half the separation either side. Not the midpoint: the anchor
            // of a corner or face is a material point that turns with its body, and a midpoint
            // `s/2` outside the body swings round on a longer arm. For a speculative point metres
            // from the wall on a stick spinning at 300 rad/s that phantom point moved at 435 m/s,
            // its separation swung by metres, and the rows pushed at it (docs/solver.md, "Fast
            // spinning bodies"). At step start both give the same lever (`r × n` ignores a shift
            // along `n`); a round body's anchor is on the line through its centre either way.
            let r_a = input.point_world - 0.5 * input.separation * normal - com_a;
            let r_b = input.point_world + 0.5 * input.separation * normal - com_b;
            let (r_a_local, r_b_local) = round_locals((r_a, r_b), radii, normal, a, b);
            *pc = PointConstraint {
                r_a0: r_a,
                r_b0: r_b,
                r_a_local,
                r_b_local,
                base_separation: input.separation,
                normal_impulse: if ctx.warm_starting { input.impulse.normal } else { 0.0 },
                steady_normal_impulse: if ctx.warm_starting { input.impulse.steady_normal } else { 0.0 },
                steady_age: if ctx.warm_starting { input.impulse.steady_age } else { 0.0 },
                max_normal_impulse: 0.0,
                relative_velocity: 0.0,
                restitution_impulse: 0.0,
                bounced: false,
            };
        }
        let count = self.point_count;
        let mut offsets = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
        let mut levers = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
        for ((offset, lever), pc) in offsets.iter_mut().zip(&mut levers).zip(&self.points[..count]) {
            *offset = (pc.r_a0, pc.r_b0);
            *lever = shared_levers(*offset, self.com_offset, a, b);
        }
        self.coupling_start = pack_symmetric(&normal_coupling(&levers[..count], normal, a, b));
        let (tangent, twist) = if ctx.warm_starting {
            (0..points.len())
                .map(point)
                .fold((DVec3::ZERO, 0.0), |(t, w), p| (t + p.impulse.tangent_world, w + p.impulse.twist))
        } else {
            (DVec3::ZERO, 0.0)
        };
        self.friction =
            PatchFriction::prepare(a, b, &offsets[..count], radii, normal, self.com_offset, tangent, twist);
    }

    fn apply(a: &mut SolverBody, b: &mut SolverBody, r_a: DVec3, r_b: DVec3, p: DVec3) {
        crate::dynamics::joint::parts::apply_point_impulse(a, b, r_a, r_b, p);
    }

    /// Stage "warm start": apply the accumulated impulses again.
    pub fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        if !self.has_impulse() {
            return;
        }
        let radii = self.radii;
        if linear_pair(radii, a, b) {
            // Still: the rows linear in the step-start levers (contact_lanes.rs).
            self.warm_start_still(a, b);
        } else if self.point_count == 1 {
            // One point: the patch's centre is the point, and so are its levers.
            let pc = &self.points[0];
            let levers = shared_levers(pc.anchors(radii, self.normal, a, b), self.com_offset, a, b);
            apply_point_impulses(a, b, &[levers], &[pc.normal_impulse * self.normal]);
            self.friction.warm_start(levers, self.normal, a, b);
        } else {
            let count = self.point_count;
            let mut levers = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
            let mut impulses = [DVec3::ZERO; MAX_POINTS];
            for (i, pc) in self.points[..count].iter().enumerate() {
                levers[i] = shared_levers(pc.anchors(radii, self.normal, a, b), self.com_offset, a, b);
                impulses[i] = pc.normal_impulse * self.normal;
            }
            apply_point_impulses(a, b, &levers[..count], &impulses[..count]);
            let patch_levers = self.friction.levers(radii, self.normal, self.com_offset, a, b);
            self.friction.warm_start(patch_levers, self.normal, a, b);
        }
        // Zero without torsional and rolling friction (and then no change to ω at all).
        if !self.fits_lanes() {
            let angular = self.rolling_impulse + self.torsional_impulse * self.normal;
            a.w -= a.inv_inertia * angular;
            b.w += b.inv_inertia * angular;
        }
    }

    /// Stage "solve" (`use_bias`) or "relax" (`!use_bias`).
    pub fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, ctx: &StepContext, use_bias: bool) {
        let radii = self.radii;
        let n = self.normal;
        let total_normal = if linear_pair(radii, a, b) {
            // Still: the rows linear in the step-start levers, with friction (contact_lanes.rs).
            let Some(total_normal) = self.solve_still(a, b, ctx, use_bias) else { return };
            total_normal
        } else if self.point_count == 1 {
            // One point: the patch's centre is the point, and so are its levers.
            let Some((total_normal, levers)) = self.solve_single_normal(a, b, ctx, use_bias) else { return };
            self.friction.solve(levers, n, self.material.friction, &[self.points[0].normal_impulse], a, b);
            total_normal
        } else {
            let Some(total_normal) = self.solve_normals(a, b, ctx, use_bias) else { return };
            let mut normal_impulses = [0.0; MAX_POINTS];
            for (l, pc) in normal_impulses.iter_mut().zip(&self.points[..self.point_count]) {
                *l = pc.normal_impulse;
            }
            let levers = self.friction.levers(radii, n, self.com_offset, a, b);
            self.friction.solve(
                levers,
                n,
                self.material.friction,
                &normal_impulses[..self.point_count],
                a,
                b,
            );
            total_normal
        };

        // Torsional and rolling friction, bounded by the manifold's total normal impulse.
        // Their effective masses from the inverse inertias as they are now, as for the normal
        // and friction rows.
        if self.material.torsional_friction > 0.0 {
            let max = self.material.torsional_friction * total_normal;
            let w_rel = n.dot(b.w - a.w);
            let k_twist = n.dot((a.inv_inertia + b.inv_inertia) * n);
            let k = if k_twist > 0.0 { 1.0 / k_twist } else { 0.0 };
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
            // The tangent block of `I_a⁻¹ + I_b⁻¹`, inverted on the tangent plane. (The tangent
            // part of the full 3×3 inverse is larger on a long body — up to the ratio of its
            // moments — and over-relaxed the rows until they fed energy into a capsule lying on
            // the ground.)
            let rolling_mass = tangent_block_inverse(a.inv_inertia + b.inv_inertia, n);
            let mut new = old - rolling_mass * w_roll;
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

    /// The normal rows of the manifold, solved together (contact_block.rs; one by one if the block
    /// cannot be factored). Returns the manifold's total normal impulse, or `None` when the whole
    /// manifold is idle (see `is_idle`): every row's update would be zero, and nothing is done.
    fn solve_normals(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) -> Option<f64> {
        let n = self.normal;
        let count = self.point_count;
        // The load the manifold carries at rest, shared evenly: the soft rows give way only to the
        // impulse above it (see the module docs). Shared evenly, not per point, so the load
        // memory cannot hold the load shifts of a body rocking between its supports.
        let steady =
            self.points[..count].iter().map(|pc| pc.steady_normal_impulse).sum::<f64>() / count.max(1) as f64;
        let mut block = NormalBlock { count, ..Default::default() };
        let mut accumulated = [0.0; MAX_POINTS];
        let mut anchors = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
        let mut separations = [0.0; MAX_POINTS];
        let mut normal_velocities = [0.0; MAX_POINTS];
        self.rows_now(a, b, (&mut separations, &mut normal_velocities, &mut anchors));
        if self.is_idle(&normal_velocities[..count], &separations[..count], ctx) {
            return None;
        }
        // `K` of the levers the impulses act at now. The step-start `K` no longer matches them once
        // a body has turned within the step, and a row whose `K` is too small by a factor `f`
        // overshoots its target by `f`: beyond `f = 2` every such impulse adds energy. A stick
        // spinning at 300 rad/s turns 1.25 rad per substep, its corner's `K` changes by up to
        // 4×, and the phantom levers of far speculative points (see `prepare`) by 60×.
        // (Still pairs, where the step-start `K` serves, take the rows of contact_lanes.rs.)
        let coupling = normal_coupling(&anchors[..count], n, a, b);
        let softness = self.softness;
        for (i, pc) in self.points[..count].iter_mut().enumerate() {
            let (rhs, gamma) = pc.row_target(
                separations[i],
                normal_velocities[i],
                coupling[i][i],
                steady,
                softness,
                ctx,
                use_bias,
            );
            block.rhs[i] = rhs;
            block.matrix[i] = coupling[i];
            block.matrix[i][i] += gamma;
            accumulated[i] = pc.normal_impulse;
        }
        let (deltas, free_rows) = block.solve_or_one_by_one(&accumulated, self.free_rows, None);
        self.free_rows = free_rows;
        let mut total_normal = 0.0;
        for (i, pc) in self.points[..count].iter_mut().enumerate() {
            let applied = deltas[i];
            pc.normal_impulse = (pc.normal_impulse + applied).max(0.0);
            pc.max_normal_impulse = pc.max_normal_impulse.max(applied);
            total_normal += pc.normal_impulse;
        }
        let impulses: [DVec3; MAX_POINTS] = std::array::from_fn(|i| deltas[i] * n);
        apply_point_impulses(a, b, &anchors[..count], &impulses[..count]);
        Some(total_normal)
    }

    /// `solve_normals` for a manifold of one point (a ball's, mostly): the same numbers, without
    /// the block's arrays of four rows — a rain of spheres spent a fifth of its contact solves
    /// setting up and walking them. Also returns the levers the row's impulse acted at.
    fn solve_single_normal(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) -> Option<(f64, (DVec3, DVec3))> {
        let n = self.normal;
        let pc = &self.points[0];
        // As `solve_normals` shares the steady load, over one point.
        let steady = [pc.steady_normal_impulse].iter().sum::<f64>() / 1.0;
        let material = pc.anchors(self.radii, n, a, b);
        let s = pc.separation(material, a, b, n);
        let (r_a, r_b) = shared_levers(material, self.com_offset, a, b);
        let vn = n.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
        if self.is_idle(&[vn], &[s], ctx) {
            return None;
        }
        let arms = (r_a.cross(n), r_b.cross(n));
        let k = coupling_entry(arms, (a.inv_inertia * arms.0, b.inv_inertia * arms.1), a, b);
        let softness = self.softness;
        let pc = &mut self.points[0];
        let (rhs, gamma) = pc.row_target(s, vn, k, steady, softness, ctx, use_bias);
        // `NormalBlock::solve` of one row, or its fallback when the row cannot be solved.
        let k = k + gamma;
        let applied = if k > 0.0 { (rhs / k).max(-pc.normal_impulse) } else { 0.0 };
        self.free_rows = ALL_ROWS;
        pc.normal_impulse = (pc.normal_impulse + applied).max(0.0);
        pc.max_normal_impulse = pc.max_normal_impulse.max(applied);
        let total_normal = 0.0 + pc.normal_impulse;
        apply_point_impulses(a, b, &[(r_a, r_b)], &[applied * n]);
        Some((total_normal, (r_a, r_b)))
    }

    /// Writes each normal row's separation and normal velocity now, and the shared levers its
    /// impulse acts at. (Out-parameters: returned as a tuple of arrays, the rain and large-pyramid
    /// scenes ran 10% slower.) A still pair's rows, linear in the step-start levers, are in
    /// contact_lanes.rs.
    #[allow(clippy::type_complexity)]
    #[inline(always)]
    fn rows_now(
        &self,
        a: &SolverBody,
        b: &SolverBody,
        (separations, normal_velocities, anchors): (
            &mut [f64; MAX_POINTS],
            &mut [f64; MAX_POINTS],
            &mut [(DVec3, DVec3); MAX_POINTS],
        ),
    ) {
        let n = self.normal;
        for (i, pc) in self.points[..self.point_count].iter().enumerate() {
            let material = pc.anchors(self.radii, n, a, b);
            separations[i] = pc.separation(material, a, b, n);
            let (r_a, r_b) = shared_levers(material, self.com_offset, a, b);
            anchors[i] = (r_a, r_b);
            normal_velocities[i] = n.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
        }
    }

    /// Whether a pass over this manifold would change nothing: every point is speculative (apart
    /// by more than the soft band) and not closing its gap within the substep, `vₙ + s/h ≥ 0`, and
    /// no impulse has been accumulated — no normal, friction, twist, torsional or rolling impulse.
    /// Then every normal row's right-hand side is ≤ 0 with nothing to release, so the block's
    /// answer is zero (its matrix is positive definite), and friction bounded by a zero load has
    /// nothing to take back. The gaps between the boxes of a pile, and spheres about to land, are
    /// mostly such manifolds.
    fn is_idle(&self, normal_velocities: &[f64], separations: &[f64], ctx: &StepContext) -> bool {
        !self.has_impulse()
            && normal_velocities
                .iter()
                .zip(separations)
                .all(|(&vn, &s)| s > SOFT_BAND && vn + s * ctx.inv_h >= 0.0)
    }

    /// Whether any impulse is accumulated: normal, friction, twist, torsional or rolling.
    fn has_impulse(&self) -> bool {
        self.points[..self.point_count].iter().any(|pc| pc.normal_impulse != 0.0)
            || self.friction.tangent_impulse != DVec3::ZERO
            || self.friction.twist_impulse != 0.0
            || self.torsional_impulse != 0.0
            || self.rolling_impulse != DVec3::ZERO
    }

    /// End of a substep of length `h`: the steady load learns from this substep's normal impulse,
    /// with a time constant of the point's age, at least a fifth of `steady_load_time` and at most
    /// all of it (`rate = h / time constant`).
    ///
    /// A new contact learns fast: the load it is taking on is what it will carry. Once settled,
    /// the load of a resting body changes mostly as it rocks between its supports, and a memory
    /// that follows that rocking closely feeds it, as an integral term with too short a time
    /// feeds a controlled mode: learned at 0.1 s throughout, a 210-box pyramid that never sleeps
    /// began rocking after 30 s and had moved 26 cm after 100 s (docs/solver.md, "Contacts that
    /// hold their load"). Between the two the time constant is the age, so the steady load is the
    /// running mean of the impulses since the contact began.
    pub fn update_steady_load(&mut self, steady_load_time: f64, h: f64) {
        for pc in &mut self.points[..self.point_count] {
            let time = pc.steady_age.clamp(0.2 * steady_load_time, steady_load_time);
            let rate = (h / time).min(1.0);
            pc.steady_normal_impulse += rate * (pc.normal_impulse - pc.steady_normal_impulse);
            pc.steady_age += h;
        }
    }

    /// Stage "restitution", after every substep's relax pass: points that approached faster than
    /// the threshold separate at `e` times their approach speed, as soon as the approach is
    /// stopped (`last`: at the end of the step in any case). See docs/solver.md, "Restitution".
    pub fn apply_restitution(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        last: bool,
    ) {
        let radii = self.radii;
        let e = self.material.restitution;
        if e == 0.0 {
            return;
        }
        let n = self.normal;
        // The bouncing points, solved together (contact_block.rs) so that a face or edge hitting
        // with several points gets the impulses that give each its target speed at once; one
        // after the other, each point's impulse disturbs the others' and energy is not kept.
        let mut rows = [0usize; MAX_POINTS];
        let mut block = NormalBlock::default();
        let mut accumulated = [0.0; MAX_POINTS];
        let mut levers = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
        let mut closed = last;
        for (i, pc) in self.points[..self.point_count].iter().enumerate() {
            if pc.bounced || pc.relative_velocity > -ctx.restitution_threshold || pc.max_normal_impulse == 0.0
            {
                continue;
            }
            let material = pc.anchors(radii, self.normal, a, b);
            let (r_a, r_b) = shared_levers(material, self.com_offset, a, b);
            let vn = n.dot(b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a));
            // The impact is over once the surfaces touch or the row has stopped the approach.
            closed |= vn >= 0.0 || pc.separation(material, a, b, n) <= SOFT_BAND;
            let row = block.count;
            rows[row] = i;
            levers[row] = (r_a, r_b);
            block.rhs[row] = -(vn + e * pc.relative_velocity);
            accumulated[row] = pc.normal_impulse + pc.restitution_impulse;
            block.count += 1;
        }
        if block.count == 0 || !closed {
            return;
        }
        // `K` of the levers the impulses act at now, not of the step-start anchors: with the latter
        // a spinning box's corner missed its target speed by 3% (docs/solver.md).
        let count = block.count;
        let coupling = normal_coupling(&levers[..count], n, a, b);
        for row in 0..count {
            block.matrix[row] = coupling[row];
        }
        let Some((deltas, _)) = block.solve(&accumulated, ALL_ROWS, None) else { return };
        for row in 0..block.count {
            let pc = &mut self.points[rows[row]];
            let applied = deltas[row];
            pc.restitution_impulse += applied;
            pc.max_normal_impulse = pc.max_normal_impulse.max(applied);
            pc.bounced = true;
            let (r_a, r_b) = levers[row];
            Self::apply(a, b, r_a, r_b, applied * n);
        }
    }

    /// Stage "store impulses": what the next step warm-starts from, per point in input order.
    pub fn impulses(&self) -> impl Iterator<Item = ContactImpulse> + '_ {
        self.points[..self.point_count].iter().map(|pc| ContactImpulse {
            normal: (pc.normal_impulse + pc.restitution_impulse).max(0.0),
            tangent_world: self.friction.tangent_impulse / self.point_count as f64,
            twist: self.friction.twist_impulse / self.point_count as f64,
            max_normal: pc.max_normal_impulse,
            steady_normal: pc.steady_normal_impulse,
            steady_age: pc.steady_age,
        })
    }
}

#[path = "contact_lanes.rs"]
mod lanes;
pub(crate) use lanes::{solve_group, warm_start_group, GroupVelocities, StillBlock, GROUP, GROUPS_PAY};

#[cfg(test)]
#[path = "contact_solver_tests.rs"]
mod tests;
