//! The rows of *still* manifolds (a still pair, no round side: `linear_pair`), written once
//! over a lane type (`lanes.rs`) and run on one manifold (`f64`) or on four of one colour side by
//! side (`f64x4`).
//!
//! A resting pile is mostly still manifolds, and their rows are the solver's main work. One
//! manifold's pass is a long chain of dependent operations (the rows' velocities, the block of
//! normal rows, the impulses, then friction on the velocities those left), which a processor
//! cannot overlap with the next manifold's. The four manifolds of a group share no moving body
//! (they are of one colour), so their chains run in the four lanes of one register.
//!
//! Each lane gets the bits its manifold gets alone: the arithmetic is the same for `f64` and for
//! `f64x4` (`lanes.rs`), branches are selections, and what lanes do not do well — the pivoting of
//! a block whose first try (every row free) fails — each such lane does on its own with the
//! scalar `NormalBlock::solve`, which makes the same first try. So which manifolds share a group
//! (and so the thread count) never changes a result, and a manifold that stops being still goes
//! on with its own rows (contact_solver.rs) from the same state.
//!
//! The order of operations is the scalar rows' (`ContactConstraint::solve_normals`,
//! `PatchFriction::solve`), step by step: the one-manifold path and the old scalar code give the
//! same state hashes.

use super::{ContactConstraint, SOFT_BAND};
use crate::dynamics::contact_block::{
    row_set, try_rows, violations, NormalBlock, RowSet, ALL_ROWS, COUPLING_ENTRIES, MAX_POINTS,
};
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::SolverBody;
use crate::lanes::{Lane, M3, V3};
use crate::math::DVec3;
use wide::f64x4;

/// Manifolds side by side in a group.
pub(crate) const GROUP: usize = 4;

/// Whether groups pay on the processor the crate is built for. `f64x4` is one AVX register;
/// without AVX (`x86-64` baseline SSE2) `wide` runs it as two halves, and the gathers and
/// scatters then cost more than the overlap gains (matched pyramid: 0.91x the one-by-one rows
/// with SSE2, 1.14x with AVX2; docs/solver.md). The results are the same bits either way.
pub(crate) const GROUPS_PAY: bool = cfg!(target_feature = "avx");

/// What a manifold's rows read of a body, and the velocities they change.
#[derive(Clone, Copy)]
struct BodyLanes<L: Lane> {
    v: V3<L>,
    w: V3<L>,
    dp: V3<L>,
    turn: V3<L>,
    inv_mass: L,
    inv_inertia: M3<L>,
}

impl<L: Lane> BodyLanes<L> {
    #[inline(always)]
    fn gather<'a>(body: impl Fn(usize) -> &'a SolverBody) -> Self {
        BodyLanes {
            v: V3::from_fn(|k| body(k).v),
            w: V3::from_fn(|k| body(k).w),
            dp: V3::from_fn(|k| body(k).dp),
            turn: V3::from_fn(|k| body(k).turn),
            inv_mass: L::from_fn(|k| body(k).inv_mass),
            inv_inertia: M3::from_fn(|k| body(k).inv_inertia),
        }
    }
}

/// What a still manifold's rows read and a step does not change, a manifold per lane (four of
/// them: `StillBlock`). Rows past a manifold's point count hold zeros and are masked out
/// (`live`).
#[derive(Clone, Copy)]
struct StillRows<L: Lane> {
    live: [L::Mask; MAX_POINTS],
    /// The point count, at least 1 (the steady load's divisor).
    count: L,
    n: V3<L>,
    /// The normal rows' angular Jacobians at the step start, `r⁰ × n`.
    arm_a: [V3<L>; MAX_POINTS],
    arm_b: [V3<L>; MAX_POINTS],
    base_separation: [L; MAX_POINTS],
    /// The step-start `K`, packed (`pack_symmetric`).
    coupling: [L; COUPLING_ENTRIES],
    bias_rate: L,
    mass_scale: L,
    impulse_scale: L,
    lever_a: V3<L>,
    lever_b: V3<L>,
    patch: PatchLanes<L>,
}

/// What friction at a manifold's centre reads besides its levers (`PatchFriction`), per lane.
#[derive(Clone, Copy)]
struct PatchLanes<L: Lane> {
    twist_arms: [L; MAX_POINTS],
    tangent_mass: M3<L>,
    sliding_mass: L,
    friction: L,
}

impl<L: Lane> PatchLanes<L> {
    #[inline(always)]
    fn gather<'a>(live: &[L::Mask; MAX_POINTS], c: impl Fn(usize) -> &'a ContactConstraint) -> Self {
        PatchLanes {
            twist_arms: std::array::from_fn(|i| {
                live_or_zero(live, i, L::from_fn(|k| c(k).friction.twist_arms[i]))
            }),
            tangent_mass: M3::from_fn(|k| c(k).friction.tangent_masses.0),
            sliding_mass: L::from_fn(|k| c(k).friction.tangent_masses.1),
            friction: L::from_fn(|k| c(k).material.friction),
        }
    }
}

/// What the passes change of a still manifold (and the steady loads, which change between
/// substeps), a manifold per lane.
#[derive(Clone, Copy)]
struct StillState<L: Lane> {
    normal_impulse: [L; MAX_POINTS],
    steady_normal: [L; MAX_POINTS],
    steady_age: [L; MAX_POINTS],
    relative_velocity: [L; MAX_POINTS],
    max_normal: [L; MAX_POINTS],
    tangent_impulse: V3<L>,
    twist_impulse: L,
    /// A torsional or rolling impulse is accumulated (only on the one-manifold path: groups take
    /// no manifold with those frictions).
    other_impulse: L::Mask,
}

/// `x` on live rows, zero past the point count.
#[inline(always)]
fn live_or_zero<L: Lane>(live: &[L::Mask; MAX_POINTS], i: usize, x: L) -> L {
    L::select(live[i], x, L::splat(0.0))
}

/// The rows of the manifolds `c(k)`, one per lane.
#[inline(always)]
fn gather_rows<'a, L: Lane>(c: impl Fn(usize) -> &'a ContactConstraint) -> StillRows<L> {
    // The places past a manifold's point count hold stale numbers (prepare writes only its own
    // points): read without a branch, then masked to zero.
    let live: [L::Mask; MAX_POINTS] = std::array::from_fn(|i| L::mask_from_fn(|k| i < c(k).point_count));
    let point = |i: usize, x: L| live_or_zero(&live, i, x);
    let point_vec = |i: usize, v: V3<L>| V3::select(live[i], v, V3::zero());
    let n = V3::from_fn(|k| c(k).normal);
    StillRows {
        live,
        count: L::from_fn(|k| c(k).point_count.max(1) as f64),
        n,
        arm_a: std::array::from_fn(|i| point_vec(i, V3::from_fn(|k| c(k).points[i].r_a0).cross(n))),
        arm_b: std::array::from_fn(|i| point_vec(i, V3::from_fn(|k| c(k).points[i].r_b0).cross(n))),
        base_separation: std::array::from_fn(|i| point(i, L::from_fn(|k| c(k).points[i].base_separation))),
        coupling: std::array::from_fn(|e| L::from_fn(|k| c(k).coupling_start[e])),
        bias_rate: L::from_fn(|k| c(k).softness.bias_rate),
        mass_scale: L::from_fn(|k| c(k).softness.mass_scale),
        impulse_scale: L::from_fn(|k| c(k).softness.impulse_scale),
        lever_a: V3::from_fn(|k| c(k).friction.levers_start.0),
        lever_b: V3::from_fn(|k| c(k).friction.levers_start.1),
        patch: PatchLanes::gather(&live, &c),
    }
}

/// The state of the manifolds `c(k)`, one per lane (`live`: their rows').
#[inline(always)]
fn gather_state<'a, L: Lane>(
    live: &[L::Mask; MAX_POINTS],
    c: impl Fn(usize) -> &'a ContactConstraint,
) -> StillState<L> {
    let point = |i: usize, x: L| live_or_zero(live, i, x);
    StillState {
        normal_impulse: std::array::from_fn(|i| point(i, L::from_fn(|k| c(k).points[i].normal_impulse))),
        steady_normal: std::array::from_fn(|i| {
            point(i, L::from_fn(|k| c(k).points[i].steady_normal_impulse))
        }),
        steady_age: std::array::from_fn(|i| point(i, L::from_fn(|k| c(k).points[i].steady_age))),
        relative_velocity: std::array::from_fn(|i| {
            point(i, L::from_fn(|k| c(k).points[i].relative_velocity))
        }),
        max_normal: std::array::from_fn(|i| point(i, L::from_fn(|k| c(k).points[i].max_normal_impulse))),
        tangent_impulse: V3::from_fn(|k| c(k).friction.tangent_impulse),
        twist_impulse: L::from_fn(|k| c(k).friction.twist_impulse),
        other_impulse: L::mask_from_fn(|k| {
            c(k).torsional_impulse != 0.0 || c(k).rolling_impulse != DVec3::ZERO
        }),
    }
}

/// The full symmetric `K` from its packed entries.
#[inline(always)]
fn unpack_coupling<L: Lane>(packed: &[L; COUPLING_ENTRIES]) -> [[L; MAX_POINTS]; MAX_POINTS] {
    let mut coupling = [[L::splat(0.0); MAX_POINTS]; MAX_POINTS];
    let mut next = 0;
    for i in 0..MAX_POINTS {
        for j in i..MAX_POINTS {
            coupling[i][j] = packed[next];
            coupling[j][i] = packed[next];
            next += 1;
        }
    }
    coupling
}

/// The block of normal rows of one pass, per lane (`NormalBlock`'s inputs).
struct BlockLanes<L: Lane> {
    matrix: [[L; MAX_POINTS]; MAX_POINTS],
    rhs: [L; MAX_POINTS],
    accumulated: [L; MAX_POINTS],
    /// The rows whose compliance is not zero (the key of the kept factors, `FreeFactor`).
    soft: [L::Mask; MAX_POINTS],
}

/// `Σ` over the live rows, from `−0.0` as `Iterator::sum` (adding `−0.0` changes nothing).
#[inline(always)]
fn sum_live<L: Lane>(live: &[L::Mask; MAX_POINTS], terms: impl Fn(usize) -> L) -> L {
    let mut sum = L::splat(-0.0);
    for (i, &is_live) in live.iter().enumerate() {
        sum = sum + L::select(is_live, terms(i), L::splat(-0.0));
    }
    sum
}

/// `apply_impulse_and_moments` (contact_solver.rs) over lanes.
#[inline(always)]
fn apply_impulse_and_moments<L: Lane>(
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
    p: V3<L>,
    torque_a: V3<L>,
    torque_b: V3<L>,
) {
    a.v = a.v - p.scale(a.inv_mass);
    a.w = a.w - a.inv_inertia.mul_vec3(torque_a);
    b.v = b.v + p.scale(b.inv_mass);
    b.w = b.w + b.inv_inertia.mul_vec3(torque_b);
}

/// `apply_point_impulse` (joint parts) over lanes.
#[inline(always)]
fn apply_point_impulse<L: Lane>(
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
    r_a: V3<L>,
    r_b: V3<L>,
    p: V3<L>,
) {
    apply_impulse_and_moments(a, b, p, r_a.cross(p), r_b.cross(p));
}

/// Normal impulses `λᵢ n` at the step-start levers (`apply_still_normal_impulses`).
#[inline(always)]
fn apply_normal_impulses<L: Lane>(
    rows: &StillRows<L>,
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
    impulses: &[L; MAX_POINTS],
) {
    // Rows past the point count add `+0` to sums that start at `+0`, which are never `−0`: no
    // change (their impulses and arms are zero).
    let (mut total, mut torque_a, mut torque_b) = (L::splat(0.0), V3::zero(), V3::zero());
    for i in 0..MAX_POINTS {
        let l = impulses[i];
        total = total + l;
        torque_a = torque_a + rows.arm_a[i].scale(l);
        torque_b = torque_b + rows.arm_b[i].scale(l);
    }
    apply_impulse_and_moments(a, b, rows.n.scale(total), torque_a, torque_b);
}

/// Stage "warm start" of still manifolds; returns the lanes that apply anything (with any
/// impulse accumulated).
#[inline(always)]
fn warm_start_pass<L: Lane>(
    rows: &StillRows<L>,
    m: &StillState<L>,
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
) -> L::Mask {
    let active = has_impulse(&rows.live, m);
    if !L::any(active) {
        return active;
    }
    let (a_before, b_before) = (*a, *b);
    apply_normal_impulses(rows, a, b, &m.normal_impulse);
    apply_point_impulse(a, b, rows.lever_a, rows.lever_b, m.tangent_impulse);
    let twist = rows.n.scale(m.twist_impulse);
    a.w = a.w - a.inv_inertia.mul_vec3(twist);
    b.w = b.w + b.inv_inertia.mul_vec3(twist);
    keep_inactive(active, a, b, &a_before, &b_before);
    active
}

/// Whether any impulse is accumulated (`ContactConstraint::has_impulse`).
#[inline(always)]
fn has_impulse<L: Lane>(live: &[L::Mask; MAX_POINTS], m: &StillState<L>) -> L::Mask {
    let zero = L::splat(0.0);
    let mut any = m.tangent_impulse.ne_zero() | m.twist_impulse.ne(zero) | m.other_impulse;
    for i in 0..MAX_POINTS {
        any = any | (live[i] & m.normal_impulse[i].ne(zero));
    }
    any
}

/// The velocities of the lanes not in `active` as they were.
#[inline(always)]
fn keep_inactive<L: Lane>(
    active: L::Mask,
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
    a_before: &BodyLanes<L>,
    b_before: &BodyLanes<L>,
) {
    a.v = V3::select(active, a.v, a_before.v);
    a.w = V3::select(active, a.w, a_before.w);
    b.v = V3::select(active, b.v, b_before.v);
    b.w = V3::select(active, b.w, b_before.w);
}

/// Each normal row's separation and normal velocity now, linear in the step-start levers `r⁰`:
/// a point moved by `Δp + θ × r⁰` and moves at `v + ω × r⁰` (`θ` the body's turn since the step
/// began), so `n·` of either is `n·Δp + θ·(r⁰ × n)`. What that leaves out is second order,
/// `|r| θ²/2` ≤ 0.5 µm on a lever of a metre, and the levers' own change, which the step-start `K`
/// leaves out as well. The step-start levers of a point lie on one normal line, so the pair's
/// angular momentum is kept exactly, as with the shared levers of the exact rows. A resting
/// pile's rows then cost dot products instead of turning every point with both bodies. (Not on a
/// round side: there the lever is the radius from a centre of curvature that turns with the body,
/// and held at its step-start offset it lags the turning and feeds a rolling body's energy,
/// docs/solver.md, "Still pairs".)
#[inline(always)]
fn rows_now<L: Lane>(
    m: &StillRows<L>,
    a: &BodyLanes<L>,
    b: &BodyLanes<L>,
) -> ([L; MAX_POINTS], [L; MAX_POINTS]) {
    let n = m.n;
    let moved = n.dot(b.dp - a.dp);
    let approach = n.dot(b.v - a.v);
    let separations = std::array::from_fn(|i| {
        m.base_separation[i] + moved + b.turn.dot(m.arm_b[i]) - a.turn.dot(m.arm_a[i])
    });
    let normal_velocities = std::array::from_fn(|i| approach + b.w.dot(m.arm_b[i]) - a.w.dot(m.arm_a[i]));
    (separations, normal_velocities)
}

/// Stage "solve" (`use_bias`) or "relax" of still manifolds: the normal rows as one block (solved
/// by `block`, given the lanes that take part), then friction. Returns the lanes that take part:
/// the others are idle (`ContactConstraint::is_idle`), and nothing of theirs changes.
#[inline(always)]
fn solve_pass<L: Lane>(
    rows: &StillRows<L>,
    m: &mut StillState<L>,
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
    ctx: &StepContext,
    use_bias: bool,
    block: impl FnOnce(&BlockLanes<L>, L::Mask) -> [L; MAX_POINTS],
) -> L::Mask {
    let (separations, normal_velocities) = rows_now(rows, a, b);
    let normal = NormalRowsNow { separations, normal_velocities };
    let softness = (rows.bias_rate, rows.mass_scale, rows.impulse_scale);
    let coupling = || unpack_coupling(&rows.coupling);
    let (a_before, b_before) = (*a, *b);
    let Some((active, deltas)) =
        solve_normal_rows(&rows.live, rows.count, softness, &normal, coupling, m, ctx, use_bias, block)
    else {
        return L::mask_splat(false);
    };
    apply_normal_impulses(rows, a, b, &deltas);
    friction_pass(&rows.live, rows.n, &rows.patch, (rows.lever_a, rows.lever_b), m, a, b);
    keep_inactive(active, a, b, &a_before, &b_before);
    active
}

/// The normal rows' separations and normal velocities now, per lane.
struct NormalRowsNow<L: Lane> {
    separations: [L; MAX_POINTS],
    normal_velocities: [L; MAX_POINTS],
}

/// The normal rows of a pass as one block (`ContactConstraint::solve_normals`): `None` when
/// every lane is idle, else the lanes that take part and the impulses to apply (the accumulated
/// ones already updated). `coupling` gives `K` of the levers.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn solve_normal_rows<L: Lane>(
    live: &[L::Mask; MAX_POINTS],
    count: L,
    (bias_rate, soft_mass_scale, soft_impulse_scale): (L, L, L),
    rows: &NormalRowsNow<L>,
    coupling: impl FnOnce() -> [[L; MAX_POINTS]; MAX_POINTS],
    m: &mut StillState<L>,
    ctx: &StepContext,
    use_bias: bool,
    block: impl FnOnce(&BlockLanes<L>, L::Mask) -> [L; MAX_POINTS],
) -> Option<(L::Mask, [L; MAX_POINTS])> {
    let zero = L::splat(0.0);
    let (separations, normal_velocities) = (&rows.separations, &rows.normal_velocities);
    let steady = sum_live(live, |i| m.steady_normal[i]) / count;
    let (soft_band, inv_h) = (L::splat(SOFT_BAND), L::splat(ctx.inv_h));
    let mut apart = L::mask_splat(true);
    for i in 0..MAX_POINTS {
        let (s, vn) = (separations[i], normal_velocities[i]);
        apart = apart & (!live[i] | (s.gt(soft_band) & (vn + s * inv_h).ge(zero)));
    }
    let active = !(apart & !has_impulse(live, m));
    if !L::any(active) {
        return None;
    }

    let coupling = coupling();
    let mut inputs = BlockLanes {
        matrix: coupling,
        rhs: [zero; MAX_POINTS],
        accumulated: m.normal_impulse,
        soft: [L::mask_splat(false); MAX_POINTS],
    };
    let one = L::splat(1.0);
    for i in 0..MAX_POINTS {
        let s = separations[i];
        let speculative = s.gt(soft_band);
        let (bias, mass_scale, impulse_scale) = if use_bias {
            let soft_bias = Lane::max(bias_rate * s, L::splat(-ctx.max_contact_push_velocity));
            (
                L::select(speculative, s * inv_h, soft_bias),
                L::select(speculative, one, soft_mass_scale),
                L::select(speculative, zero, soft_impulse_scale),
            )
        } else {
            (L::select(speculative, s * inv_h, zero), one, zero)
        };
        let vn = normal_velocities[i];
        let engaged = live[i] & (vn + bias).lt(zero);
        // `opaque`: a blend and a store, not a masked store (lanes.rs).
        let seen = m.relative_velocity[i].opaque();
        m.relative_velocity[i] = L::select(engaged, Lane::min(seen, vn), seen);
        let k_ii = coupling[i][i];
        let gamma = L::select(mass_scale.gt(zero), k_ii * impulse_scale / mass_scale, zero);
        inputs.soft[i] = live[i] & gamma.ne(zero);
        inputs.rhs[i] = -(vn + bias) - gamma * (m.normal_impulse[i] - steady);
        inputs.matrix[i][i] = inputs.matrix[i][i] + gamma;
    }
    let deltas = block(&inputs, active);
    for i in 0..MAX_POINTS {
        let applied = deltas[i];
        let impulse = Lane::max(m.normal_impulse[i] + applied, zero);
        let (old_impulse, old_max) = (m.normal_impulse[i].opaque(), m.max_normal[i].opaque());
        m.normal_impulse[i] = L::select(live[i], impulse, old_impulse);
        m.max_normal[i] = L::select(live[i], Lane::max(old_max, applied), old_max);
    }
    Some((active, deltas))
}

/// Friction at the manifold's centre, bounded by its normal impulses (`PatchFriction::solve`),
/// acting at `levers` (a still pair's step-start ones, or a moving pair's now).
#[inline(always)]
fn friction_pass<L: Lane>(
    live: &[L::Mask; MAX_POINTS],
    n: V3<L>,
    patch: &PatchLanes<L>,
    (r_a, r_b): (V3<L>, V3<L>),
    m: &mut StillState<L>,
    a: &mut BodyLanes<L>,
    b: &mut BodyLanes<L>,
) {
    let zero = L::splat(0.0);
    let total = sum_live(live, |i| m.normal_impulse[i]);
    let twist_limit = patch.friction * sum_live(live, |i| m.normal_impulse[i] * patch.twist_arms[i]);
    let loaded = twist_limit.gt(zero);
    let old = m.twist_impulse;
    let unloaded = !loaded & old.ne(zero);
    let (mut w_a, mut w_b, mut twist) = (a.w, b.w, old);
    if L::any(loaded) {
        let k_twist = n.dot((a.inv_inertia + b.inv_inertia).mul_vec3(n));
        let twist_mass = L::select(k_twist.gt(zero), L::splat(1.0) / k_twist, zero);
        let w_rel = n.dot(b.w - a.w);
        let new = (old - twist_mass * w_rel).clamp(-twist_limit, twist_limit);
        let delta = n.scale(new - old);
        w_a = V3::select(loaded, a.w - a.inv_inertia.mul_vec3(delta), w_a);
        w_b = V3::select(loaded, b.w + b.inv_inertia.mul_vec3(delta), w_b);
        twist = L::select(loaded, new, twist);
    }
    if L::any(unloaded) {
        // No load, no twist friction: take back what the warm start applied.
        let back = n.scale(old);
        w_a = V3::select(unloaded, a.w + a.inv_inertia.mul_vec3(back), w_a);
        w_b = V3::select(unloaded, b.w - b.inv_inertia.mul_vec3(back), w_b);
        twist = L::select(unloaded, zero, twist);
    }
    a.w = w_a;
    b.w = w_b;
    m.twist_impulse = twist;

    let dv = b.v + b.w.cross(r_b) - a.v - a.w.cross(r_a);
    let vt = dv - n.scale(n.dot(dv));
    let old = m.tangent_impulse;
    let sticking = old - patch.tangent_mass.mul_vec3(vt);
    let max = patch.friction * total;
    let sliding = sticking.length().gt(max);
    let mut new = sticking;
    if L::any(sliding) {
        // Sliding: the isotropic mass, whose fixed point on the rim opposes the slip.
        let slide = old - vt.scale(patch.sliding_mass);
        let len = slide.length();
        let slide = V3::select(len.gt(max), slide.scale(max / len), slide);
        new = V3::select(sliding, slide, sticking);
    }
    m.tangent_impulse = new;
    apply_point_impulse(a, b, r_a, r_b, new - old);
}

/// The scalar block solve of one manifold (`NormalBlock::solve`, from its kept factors and its
/// last free rows), or its rows one by one when the block cannot be factored; sets the
/// manifold's free rows. `soft` is the key of the kept factors.
fn block_alone(
    c: &mut ContactConstraint,
    free_rows: &mut RowSet,
    matrix: &[[f64; MAX_POINTS]; MAX_POINTS],
    rhs: &[f64; MAX_POINTS],
    accumulated: &[f64; MAX_POINTS],
    soft: RowSet,
    use_bias: bool,
) -> [f64; MAX_POINTS] {
    let count = c.point_count;
    let mut block = NormalBlock { count, ..Default::default() };
    for i in 0..count {
        block.rhs[i] = rhs[i];
        block.matrix[i] = matrix[i];
    }
    let kept = Some((&mut c.free_factors[usize::from(use_bias)], soft));
    let deltas;
    (deltas, *free_rows) = block.solve_or_one_by_one(accumulated, *free_rows, kept);
    deltas
}

/// Writes what a pass changes of lane `k`'s state back into its manifold (`steady`: the steady
/// loads too).
#[inline(always)]
fn scatter_state<L: Lane>(m: &StillState<L>, k: usize, c: &mut ContactConstraint, steady: bool) {
    for (i, pc) in c.points[..c.point_count].iter_mut().enumerate() {
        pc.normal_impulse = m.normal_impulse[i].lane(k);
        pc.relative_velocity = m.relative_velocity[i].lane(k);
        pc.max_normal_impulse = m.max_normal[i].lane(k);
        if steady {
            pc.steady_normal_impulse = m.steady_normal[i].lane(k);
            pc.steady_age = m.steady_age[i].lane(k);
        }
    }
    c.friction.tangent_impulse = m.tangent_impulse.lane(k);
    c.friction.twist_impulse = m.twist_impulse.lane(k);
}

/// `if_true` in the lanes of `mask`, else `if_false`.
#[inline(always)]
fn select_state<L: Lane>(mask: L::Mask, if_true: &StillState<L>, if_false: &StillState<L>) -> StillState<L> {
    let each = |t: &[L; MAX_POINTS], f: &[L; MAX_POINTS]| -> [L; MAX_POINTS] {
        std::array::from_fn(|i| L::select(mask, t[i], f[i]))
    };
    StillState {
        normal_impulse: each(&if_true.normal_impulse, &if_false.normal_impulse),
        steady_normal: each(&if_true.steady_normal, &if_false.steady_normal),
        steady_age: each(&if_true.steady_age, &if_false.steady_age),
        relative_velocity: each(&if_true.relative_velocity, &if_false.relative_velocity),
        max_normal: each(&if_true.max_normal, &if_false.max_normal),
        tangent_impulse: V3::select(mask, if_true.tangent_impulse, if_false.tangent_impulse),
        twist_impulse: L::select(mask, if_true.twist_impulse, if_false.twist_impulse),
        other_impulse: L::select_mask(mask, if_true.other_impulse, if_false.other_impulse),
    }
}

impl ContactConstraint {
    /// Whether a group may take this manifold: no round side, and no torsional or rolling
    /// friction (whose rows the one-manifold path adds after its friction).
    #[inline]
    pub(crate) fn fits_lanes(&self) -> bool {
        self.radii == (0.0, 0.0)
            && self.material.torsional_friction == 0.0
            && self.material.rolling_friction == 0.0
    }

    /// The separations and normal velocities of a still pair's rows now (`rows_now`).
    #[cfg(test)]
    pub(super) fn rows_still(
        &self,
        a: &SolverBody,
        b: &SolverBody,
    ) -> ([f64; MAX_POINTS], [f64; MAX_POINTS]) {
        let rows = gather_rows::<f64>(|_| self);
        rows_now(&rows, &BodyLanes::gather(|_| a), &BodyLanes::gather(|_| b))
    }

    /// Stage "warm start" of a still manifold alone (see the module docs).
    pub(super) fn warm_start_still(&self, a: &mut SolverBody, b: &mut SolverBody) {
        let rows = gather_rows::<f64>(|_| self);
        let m = gather_state::<f64>(&rows.live, |_| self);
        let (mut la, mut lb) = (BodyLanes::<f64>::gather(|_| &*a), BodyLanes::gather(|_| &*b));
        if warm_start_pass(&rows, &m, &mut la, &mut lb) {
            (a.v, a.w, b.v, b.w) = (la.v.lane(0), la.w.lane(0), lb.v.lane(0), lb.w.lane(0));
        }
    }

    /// Stage "solve"/"relax" of the normal rows and friction of a still manifold alone; the total
    /// normal impulse, or `None` when the manifold is idle.
    pub(super) fn solve_still(
        &mut self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
        use_bias: bool,
    ) -> Option<f64> {
        let rows = gather_rows::<f64>(|_| self);
        let mut m = gather_state::<f64>(&rows.live, |_| self);
        let (mut la, mut lb) = (BodyLanes::<f64>::gather(|_| &*a), BodyLanes::gather(|_| &*b));
        let active = solve_pass(&rows, &mut m, &mut la, &mut lb, ctx, use_bias, |inputs, _| {
            let mut free_rows = self.free_rows;
            let deltas = block_alone(
                self,
                &mut free_rows,
                &inputs.matrix,
                &inputs.rhs,
                &inputs.accumulated,
                row_set::<f64>(&inputs.soft, 0),
                use_bias,
            );
            self.free_rows = free_rows;
            deltas
        });
        if !active {
            return None;
        }
        scatter_state(&m, 0, self, false);
        (a.v, a.w, b.v, b.w) = (la.v.lane(0), la.w.lane(0), lb.v.lane(0), lb.w.lane(0));
        Some(self.points[..self.point_count].iter().fold(0.0, |t, pc| t + pc.normal_impulse))
    }
}

/// The new velocities `(v, ω)` of a group's bodies, `[a₀, b₀, a₁, b₁, …]`.
pub(crate) type GroupVelocities = [(DVec3, DVec3); 2 * GROUP];

/// The velocities the lanes leave.
#[inline(always)]
fn velocities(a: &BodyLanes<f64x4>, b: &BodyLanes<f64x4>) -> GroupVelocities {
    std::array::from_fn(|j| {
        let body = if j % 2 == 0 { a } else { b };
        (body.v.lane(j / 2), body.w.lane(j / 2))
    })
}

/// The blocks of a group, in the lanes as far as `NormalBlock::solve` goes in two tries: every row
/// free, then the rows the manifold last left free (or, with no such guess, the first row that
/// broke a condition turned over). Each active lane that needs more pivots solves its block
/// alone, from the start. A single row is its scalar soft update, clamped.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn block_group(
    contacts: &mut [ContactConstraint],
    free_rows: &mut [RowSet; GROUP],
    counts: &[usize; GROUP],
    live: &[f64x4; MAX_POINTS],
    inputs: &BlockLanes<f64x4>,
    active: f64x4,
    use_bias: bool,
) -> [f64x4; MAX_POINTS] {
    type Mask = f64x4;
    let zero = f64x4::splat(0.0);
    let (matrix, rhs, accumulated) = (&inputs.matrix, &inputs.rhs, &inputs.accumulated);
    let all = [<f64x4 as Lane>::mask_splat(true); MAX_POINTS];
    let single = <f64x4 as Lane>::mask_from_fn(|k| counts[k] == 1);
    let several = <f64x4 as Lane>::mask_from_fn(|k| counts[k] >= 2);
    let k = matrix[0][0];
    let single_delta = k.simd_gt(zero).select(Lane::max(rhs[0] / k, -accumulated[0]), zero);

    let (first, factored) = try_rows(matrix, rhs, accumulated, live, &all);
    let broken = violations(matrix, rhs, accumulated, live, &all, &first);
    let any_broken = broken.iter().fold(<f64x4 as Lane>::mask_splat(false), |any, &b| any | b);
    let first_ok = several & factored & !any_broken;
    let mut deltas: [f64x4; MAX_POINTS] = std::array::from_fn(|i| {
        if i == 0 {
            single.select(single_delta, first_ok.select(first[0], zero))
        } else {
            first_ok.select(first[i], zero)
        }
    });
    let mut solved = first_ok | single;
    let mut second_rows: [Mask; MAX_POINTS] = all;
    let second = active & several & factored & any_broken;
    let mut second_ok = <f64x4 as Lane>::mask_splat(false);
    if second.any() {
        let first_broken: [usize; GROUP] = std::array::from_fn(|k| {
            (0..MAX_POINTS).find(|&i| <f64x4 as Lane>::mask_lane(broken[i], k)).unwrap_or(0)
        });
        let guess: [RowSet; GROUP] = *free_rows;
        second_rows = std::array::from_fn(|i| {
            <f64x4 as Lane>::mask_from_fn(|k| {
                if guess[k] & ALL_ROWS != ALL_ROWS {
                    guess[k] & (1 << i) != 0
                } else {
                    i != first_broken[k]
                }
            })
        });
        let (delta, factored) = try_rows(matrix, rhs, accumulated, live, &second_rows);
        let broken = violations(matrix, rhs, accumulated, live, &second_rows, &delta);
        let any_broken = broken.iter().fold(<f64x4 as Lane>::mask_splat(false), |any, &b| any | b);
        second_ok = second & factored & !any_broken;
        for i in 0..MAX_POINTS {
            deltas[i] = second_ok.select(delta[i], deltas[i]);
        }
        solved = solved | second_ok;
    }

    let alone = active & !solved;
    if alone.any() {
        let mut lanes = deltas.map(|d| d.to_array());
        for (k, contact) in contacts.iter_mut().enumerate().take(GROUP) {
            if !<f64x4 as Lane>::mask_lane(alone, k) {
                continue;
            }
            let matrix: [[f64; MAX_POINTS]; MAX_POINTS] =
                std::array::from_fn(|i| std::array::from_fn(|j| matrix[i][j].lane(k)));
            let rhs = rhs.map(|r| r.lane(k));
            let accumulated = accumulated.map(|r| r.lane(k));
            let soft = row_set::<f64x4>(&inputs.soft, k);
            let one = block_alone(contact, &mut free_rows[k], &matrix, &rhs, &accumulated, soft, use_bias);
            for i in 0..MAX_POINTS {
                lanes[i][k] = one[i];
            }
        }
        deltas = lanes.map(f64x4::new);
    }
    for (k, free_rows) in free_rows.iter_mut().enumerate() {
        if !<f64x4 as Lane>::mask_lane(active & solved, k) {
            continue;
        }
        *free_rows = if <f64x4 as Lane>::mask_lane(second_ok, k) {
            row_set::<f64x4>(&second_rows, k)
        } else {
            ALL_ROWS
        };
    }
    deltas
}

#[path = "contact_still_blocks.rs"]
mod blocks;
pub(crate) use blocks::{solve_group, warm_start_group, StillBlock};

#[cfg(test)]
#[path = "contact_lanes_tests.rs"]
mod tests;
