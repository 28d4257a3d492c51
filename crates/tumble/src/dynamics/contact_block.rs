//! The normal rows of one manifold solved together, as one small mixed LCP (Box2D v2's two-point
//! block solver, grown to four points).
//!
//! Solving a manifold's points one after the other favours the first: on a box resting on its
//! face, the first corner takes more of the load than the last, the box is tipped by the
//! difference, and in a stack the tips add up and walk the tower sideways. Solved together, a
//! symmetric load gives symmetric impulses.
//!
//! Each soft row `i` has the update (softness.rs) `Δλᵢ = −(sᵢ/kᵢᵢ)(vᵢ + bᵢ) − cᵢ λ'ᵢ` with
//! `sᵢ` the mass scale, `cᵢ` the impulse scale and `λ'ᵢ` the part of the accumulated impulse the
//! spring gives way to. Multiplying by `kᵢᵢ/sᵢ`, with `γᵢ = kᵢᵢ cᵢ/sᵢ`:
//!
//! `(kᵢᵢ + γᵢ) Δλᵢ = −(vᵢ + bᵢ) − γᵢ λ'ᵢ`,
//!
//! which is the one-row case of the block system `(K + Γ) Δλ = −(v + b) − Γ λ'`, where
//! `K = J M⁻¹ Jᵀ` couples the rows through the two bodies and `Γ = diag(γ)` is each row's
//! compliance. Rigid rows (speculative, relax) have `γ = 0`; four coplanar points of a face make
//! `K` singular (a body has only three ways to move against a plane), so a tiny regularisation
//! picks the least-norm split, which is the symmetric one.
//!
//! The accumulated impulses must stay non-negative, and a row left without impulse must not be
//! left approaching: with `w = (K + Γ)Δλ − rhs` (the row's velocity error after the impulses),
//! `λ + Δλ ≥ 0`, `w ≥ 0` and `(λ + Δλ)·w = 0` — a linear complementarity problem. Its matrix is
//! positive definite, so it has one solution, found by Murty's least-index principal pivoting:
//! solve with the rows of a guessed set free, then move the first row that breaks a condition
//! (a free row that would pull, a released row that would approach) to the other set, and repeat.
//! It ends within `2ⁿ` pivots in exact arithmetic, from any first guess; should round-off make it
//! cycle on a nearly singular block, projected Gauss–Seidel sweeps give a bounded answer instead.
//! (Releasing every pulling row at once and never taking one back, as this did before, is not the
//! solution when rows are coupled: a row pulled below zero only by a coupled row's large pull was
//! dropped with it; the contact let a corner pass 4 cm into a wall in one substep, and in the
//! relax pass took back more impulse than the target allowed, which added energy —
//! docs/solver.md, "Fast spinning bodies".)
//!
//! The first try has every row free; when that fails, the second is the set of free rows the
//! manifold ended its last pass with (`RowSet`), and pivoting goes on from there. Pass after
//! pass, a box rocking on one edge releases the same rows: pivoting from all free alone, half of
//! a resting pyramid's blocks were factored twice or more (8.4 million factorisations for 4.2
//! million blocks in 1,000 steps at 4 substeps; 5.8 million with the guess, and 6% more steps
//! per second). The guess is not tried first: on a face, whose `K` is singular, releasing any one
//! row leaves the other three carrying the load with the released row's velocity error zero — a
//! valid answer within round-off, but a lopsided one, which the first try's least-norm split
//! (the symmetric one) avoids; tried first, it let a pyramid drift by 1.87 cm instead of 1.39.
//!
//! `normal_coupling` builds `K`; a still manifold keeps its step-start `K` as the upper triangle
//! (`pack_symmetric`: `K` is built exactly symmetric, so nothing is lost).

use crate::dynamics::solver_body::SolverBody;
use crate::lanes::Lane;
use crate::math::DVec3;

/// At most four points per manifold.
pub(crate) const MAX_POINTS: usize = 4;

/// A set of a block's rows, a bit each (bit `i`: row `i`).
pub(crate) type RowSet = u8;

/// Every row of a block.
pub(crate) const ALL_ROWS: RowSet = (1 << MAX_POINTS) - 1;

/// `K = J M⁻¹ Jᵀ` of normal rows along `n` acting at the shared `levers` (body a's and b's
/// offsets): row `i` against row `j` through the two bodies, with the inverse inertias as they are
/// now.
pub(crate) fn normal_coupling(
    levers: &[(DVec3, DVec3)],
    n: DVec3,
    a: &SolverBody,
    b: &SolverBody,
) -> [[f64; MAX_POINTS]; MAX_POINTS] {
    let mut k = [[0.0; MAX_POINTS]; MAX_POINTS];
    let mut arms = [(DVec3::ZERO, DVec3::ZERO); MAX_POINTS];
    for (arm, (r_a, r_b)) in arms.iter_mut().zip(levers) {
        *arm = (r_a.cross(n), r_b.cross(n));
    }
    let count = levers.len().min(MAX_POINTS);
    for i in 0..count {
        let (ai, bi) = arms[i];
        let (wa, wb) = (a.inv_inertia * ai, b.inv_inertia * bi);
        for j in i..count {
            k[i][j] = coupling_entry(arms[j], (wa, wb), a, b);
            k[j][i] = k[i][j];
        }
    }
    k
}

/// One entry `K_ij` of `normal_coupling`, from row j's arms `(r_a × n, r_b × n)` and row i's
/// arms through the inverse inertias, `(I_a⁻¹ (r_a × n), I_b⁻¹ (r_b × n))`.
#[inline(always)]
pub(crate) fn coupling_entry(
    (arm_a, arm_b): (DVec3, DVec3),
    (inertia_arm_a, inertia_arm_b): (DVec3, DVec3),
    a: &SolverBody,
    b: &SolverBody,
) -> f64 {
    a.inv_mass + b.inv_mass + arm_a.dot(inertia_arm_a) + arm_b.dot(inertia_arm_b)
}

/// Entries in the upper triangle of a `MAX_POINTS`² symmetric matrix.
pub(crate) const COUPLING_ENTRIES: usize = MAX_POINTS * (MAX_POINTS + 1) / 2;

/// The upper triangle of the symmetric `k`, row by row.
pub(crate) fn pack_symmetric(k: &[[f64; MAX_POINTS]; MAX_POINTS]) -> [f64; COUPLING_ENTRIES] {
    let mut packed = [0.0; COUPLING_ENTRIES];
    let mut next = 0;
    for (i, row) in k.iter().enumerate() {
        for &entry in &row[i..] {
            packed[next] = entry;
            next += 1;
        }
    }
    packed
}

/// A dense system `(K + Γ) Δλ = rhs` for up to four rows.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NormalBlock {
    /// `K + Γ`, symmetric.
    pub matrix: [[f64; MAX_POINTS]; MAX_POINTS],
    pub rhs: [f64; MAX_POINTS],
    pub count: usize,
}

impl NormalBlock {
    /// The impulse increments that solve the complementarity problem of the module docs (rows
    /// that would pull are released, released rows that would approach are taken back), starting
    /// from the guess that the rows in `free` are free, and the rows free in the answer; or `None`
    /// when the system cannot be factored (the caller then solves the rows one by one).
    pub fn solve(
        &self,
        accumulated: &[f64; MAX_POINTS],
        free: RowSet,
        kept: Option<(&mut FreeFactor, RowSet)>,
    ) -> Option<([f64; MAX_POINTS], RowSet)> {
        let n = self.count;
        if n == 1 {
            // One row: the scalar soft update, clamped.
            let k = self.matrix[0][0];
            let delta = if k > 0.0 { (self.rhs[0] / k).max(-accumulated[0]) } else { return None };
            return Some(([delta, 0.0, 0.0, 0.0], ALL_ROWS));
        }
        let live: [bool; MAX_POINTS] = std::array::from_fn(|i| i < n);
        let mut active = [true; MAX_POINTS];
        let mut guess = (free & ALL_ROWS != ALL_ROWS).then_some(free);
        let mut kept = kept;
        // Murty's method needs at most 2ⁿ pivots in exact arithmetic (one more for the guess).
        for _ in 0..=(1usize << n) + 1 {
            let delta = match kept.take() {
                // The first try, every row free, with the factors kept from an earlier pass.
                Some((factor, key)) => self.solve_all_free(factor, key)?,
                None => match try_rows(&self.matrix, &self.rhs, accumulated, &live, &active) {
                    (delta, true) => delta,
                    (_, false) => return None,
                },
            };
            let violated = violations(&self.matrix, &self.rhs, accumulated, &live, &active, &delta);
            match violated.iter().position(|&v| v) {
                Some(i) => match guess.take() {
                    Some(free) => active = std::array::from_fn(|i| free & (1 << i) != 0),
                    None => active[i] = !active[i],
                },
                None => return Some((delta, row_set::<f64>(&active, 0))),
            }
        }
        // Pivoting did not settle: on a nearly singular block (two points almost on top of each
        // other) round-off can flip a row's sign test back and forth. The last pivot's solution
        // is then no answer — clamping it once let a 1.25e6 N·s impulse through, which blew up a
        // pile of hulls. Projected Gauss–Seidel sweeps are bounded instead: each row update is
        // the exact minimiser of the block's quadratic along that row, so the solution can only
        // come closer.
        Some((self.projected_gauss_seidel(accumulated), ALL_ROWS))
    }

    /// `solve`, or where the block cannot be factored its rows one by one, each against its own
    /// effective mass (then every row counts as free).
    pub fn solve_or_one_by_one(
        &self,
        accumulated: &[f64; MAX_POINTS],
        free: RowSet,
        kept: Option<(&mut FreeFactor, RowSet)>,
    ) -> ([f64; MAX_POINTS], RowSet) {
        self.solve(accumulated, free, kept).unwrap_or_else(|| {
            let mut deltas = [0.0; MAX_POINTS];
            for i in 0..self.count {
                let k = self.matrix[i][i];
                deltas[i] = if k > 0.0 { (self.rhs[i] / k).max(-accumulated[i]) } else { 0.0 };
            }
            (deltas, ALL_ROWS)
        })
    }

    /// Sweeps of projected Gauss–Seidel over the rows from zero increments: each row solved
    /// against the others' current increments, its total impulse kept non-negative.
    fn projected_gauss_seidel(&self, accumulated: &[f64; MAX_POINTS]) -> [f64; MAX_POINTS] {
        const SWEEPS: usize = 16;
        let n = self.count;
        let mut delta = [0.0; MAX_POINTS];
        for _ in 0..SWEEPS {
            for i in 0..n {
                let k = self.matrix[i][i];
                if !(k > 0.0) {
                    continue;
                }
                let mut residual = self.rhs[i];
                for j in 0..n {
                    residual -= self.matrix[i][j] * delta[j];
                }
                delta[i] = (delta[i] + residual / k).max(-accumulated[i]);
            }
        }
        delta
    }

    /// The increments with every row free, factoring the system only when `factor` does not hold
    /// its factors for `key` already (and keeping them there). The same numbers as `solve_with`
    /// with every row active: the same matrix, factored the same way.
    fn solve_all_free(&self, factor: &mut FreeFactor, key: RowSet) -> Option<[f64; MAX_POINTS]> {
        let n = self.count;
        if factor.key != key {
            let mut m = [[0.0; MAX_POINTS]; MAX_POINTS];
            let mut scale = 0.0_f64;
            for i in 0..MAX_POINTS {
                if i < n {
                    scale = scale.max(self.matrix[i][i]);
                    m[i][..n].copy_from_slice(&self.matrix[i][..n]);
                } else {
                    m[i][i] = 1.0;
                }
            }
            factor.ldlt = Ldlt::factor(&m, scale)?;
            factor.key = key;
        }
        let mut b = [0.0; MAX_POINTS];
        b[..n].copy_from_slice(&self.rhs[..n]);
        let x = factor.ldlt.solve(&b);
        let mut delta = [0.0; MAX_POINTS];
        delta[..n].copy_from_slice(&x[..n]);
        Some(delta)
    }
}

/// One try of the pivoting, per lane: the increments with the live rows in `active` free and the
/// others released (their accumulated impulse taken away: their increment is fixed at
/// `−accumulated`), and whether the system could be factored (where it could not, the block has
/// no answer).
///
/// Always a 4×4 system, whatever the count: a released or missing row becomes a unit row with a
/// zero right-hand side (its solution is 0, and it couples to nothing), so the factorisation has
/// fixed loop bounds the compiler unrolls.
#[inline(always)]
pub(crate) fn try_rows<L: Lane>(
    matrix: &[[L; MAX_POINTS]; MAX_POINTS],
    rhs: &[L; MAX_POINTS],
    accumulated: &[L; MAX_POINTS],
    live: &[L::Mask; MAX_POINTS],
    active: &[L::Mask; MAX_POINTS],
) -> ([L; MAX_POINTS], L::Mask) {
    let (zero, one, minus_zero) = (L::splat(0.0), L::splat(1.0), L::splat(-0.0));
    let free: [L::Mask; MAX_POINTS] = std::array::from_fn(|i| live[i] & active[i]);
    let mut m = [[zero; MAX_POINTS]; MAX_POINTS];
    let mut b = [zero; MAX_POINTS];
    let mut scale = zero;
    let mut any_free = L::mask_splat(false);
    for i in 0..MAX_POINTS {
        any_free = any_free | free[i];
        scale = L::select(free[i], Lane::max(scale, matrix[i][i]), scale);
        // A free row: its entries in the free columns, and the released rows' impulses taken
        // away on its right-hand side (adding `−0` where a column is not released: no change).
        let mut bi = rhs[i];
        for j in 0..MAX_POINTS {
            let released = !free[j] & live[j];
            bi = bi + L::select(released, matrix[i][j] * accumulated[j], minus_zero);
            let entry = L::select(free[j], matrix[i][j], zero);
            m[i][j] = if i == j { L::select(free[i], entry, one) } else { L::select(free[i], entry, zero) };
        }
        b[i] = L::select(free[i], bi, zero);
    }
    let (factors, positive) = factor_lanes(&m, scale);
    let x = factors.solve(&b);
    let delta = std::array::from_fn(|i| {
        L::select(live[i], L::select(free[i], L::select(any_free, x[i], zero), -accumulated[i]), zero)
    });
    (delta, positive | !any_free)
}

/// Per row, whether the increments `delta` break a condition of the complementarity problem: a
/// free row (in `active`) that would pull, a released row that would approach (round-off may
/// leave its velocity error a hair below zero).
#[inline(always)]
pub(crate) fn violations<L: Lane>(
    matrix: &[[L; MAX_POINTS]; MAX_POINTS],
    rhs: &[L; MAX_POINTS],
    accumulated: &[L; MAX_POINTS],
    live: &[L::Mask; MAX_POINTS],
    active: &[L::Mask; MAX_POINTS],
    delta: &[L; MAX_POINTS],
) -> [L::Mask; MAX_POINTS] {
    let (zero, minus_zero) = (L::splat(0.0), L::splat(-0.0));
    std::array::from_fn(|i| {
        let pulls = (accumulated[i] + delta[i]).lt(zero);
        let (mut w, mut scale) = (-rhs[i], rhs[i].abs());
        for j in 0..MAX_POINTS {
            let term = matrix[i][j] * delta[j];
            w = w + L::select(live[j], term, minus_zero);
            scale = scale + L::select(live[j], term.abs(), minus_zero);
        }
        let approaches = w.lt(L::splat(-1e-9) * scale);
        live[i] & L::select_mask(active[i], pulls, approaches)
    })
}

/// Lane `k` of the rows in `rows` as a row set.
#[inline(always)]
pub(crate) fn row_set<L: Lane>(rows: &[L::Mask; MAX_POINTS], k: usize) -> RowSet {
    rows.iter().enumerate().fold(0, |set, (i, &row)| set | (RowSet::from(L::mask_lane(row, k)) << i))
}

/// The factors `L D Lᵀ = m + εI` of a symmetric positive (semi-)definite 4×4 system, with a
/// regularisation `ε` of `1e-9` of `scale` (the largest diagonal entry of the rows that matter) so
/// that the singular systems of coplanar points give their least-norm solution. No square roots:
/// `L` has a unit diagonal. Over a lane type, one block per lane (contact_lanes.rs factors four
/// manifolds' blocks at once, with the bits each gets alone).
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Ldlt<L = f64> {
    /// `L` below its unit diagonal, row by row (`lower_index`).
    l: [L; LOWER_ENTRIES],
    inv_d: [L; MAX_POINTS],
}

/// Entries of a `MAX_POINTS`² matrix strictly below the diagonal.
const LOWER_ENTRIES: usize = MAX_POINTS * (MAX_POINTS - 1) / 2;

/// Where entry `(i, k)`, `k < i`, of a strictly lower triangle is kept.
#[inline(always)]
const fn lower_index(i: usize, k: usize) -> usize {
    i * (i - 1) / 2 + k
}

/// The factors of a block with every row free, kept between passes for as long as its matrix
/// stays the same. A still manifold's `K` is its step-start one for the whole step
/// (contact_solver.rs), and its matrix `K + Γ` then changes only with which rows are soft (`key`,
/// a bit per row): a resting manifold factors its block once per step for the solve passes and
/// once for the relax passes instead of once per pass. Only the first try of `NormalBlock::solve`
/// uses it; the pivots that may follow factor their own systems.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct FreeFactor {
    /// The soft rows the factors are for, or `FreeFactor::NO_KEY`.
    key: RowSet,
    ldlt: Ldlt,
}

impl FreeFactor {
    /// No key of a block: no factors kept.
    const NO_KEY: RowSet = RowSet::MAX;

    /// Nothing kept.
    pub const EMPTY: FreeFactor =
        FreeFactor { key: Self::NO_KEY, ldlt: Ldlt { l: [0.0; LOWER_ENTRIES], inv_d: [0.0; MAX_POINTS] } };

    /// Forgets the factors (a new step: the manifold's `K` is new).
    #[inline]
    pub fn forget(&mut self) {
        self.key = Self::NO_KEY;
    }
}

impl Ldlt {
    /// `None` when the matrix is not positive (a degenerate manifold).
    fn factor(m: &[[f64; MAX_POINTS]; MAX_POINTS], scale: f64) -> Option<Ldlt> {
        let (factors, positive) = factor_lanes(m, scale);
        positive.then_some(factors)
    }
}

/// The factors of `m + εI` per lane (see `Ldlt`), and the lanes where `m` is positive (where it is
/// not, that lane's factors are meaningless).
pub(crate) fn factor_lanes<L: Lane>(m: &[[L; MAX_POINTS]; MAX_POINTS], scale: L) -> (Ldlt<L>, L::Mask) {
    let zero = L::splat(0.0);
    // `scale > 0` and finite (`scale − scale` is NaN for an infinite or NaN scale).
    let mut positive = scale.gt(zero) & !(scale - scale).ne(zero);
    let epsilon = L::splat(1e-9) * scale;
    let mut l = [[zero; MAX_POINTS]; MAX_POINTS];
    let mut d = [zero; MAX_POINTS];
    let mut inv_d = [zero; MAX_POINTS];
    for j in 0..MAX_POINTS {
        let mut dj = m[j][j] + epsilon;
        for k in 0..j {
            dj = dj - l[j][k] * l[j][k] * d[k];
        }
        positive = positive & dj.gt(zero);
        d[j] = dj;
        inv_d[j] = L::splat(1.0) / dj;
        for i in j + 1..MAX_POINTS {
            let mut s = m[i][j];
            for k in 0..j {
                s = s - l[i][k] * l[j][k] * d[k];
            }
            l[i][j] = s * inv_d[j];
        }
    }
    let mut packed = [zero; LOWER_ENTRIES];
    for i in 1..MAX_POINTS {
        for k in 0..i {
            packed[lower_index(i, k)] = l[i][k];
        }
    }
    (Ldlt { l: packed, inv_d }, positive)
}

impl<L: Lane> Ldlt<L> {
    /// `x` with `L D Lᵀ x = b`.
    pub fn solve(&self, b: &[L; MAX_POINTS]) -> [L; MAX_POINTS] {
        let l = &self.l;
        let mut y = [L::splat(0.0); MAX_POINTS];
        for i in 0..MAX_POINTS {
            let mut s = b[i];
            for k in 0..i {
                s = s - l[lower_index(i, k)] * y[k];
            }
            y[i] = s;
        }
        let mut x = [L::splat(0.0); MAX_POINTS];
        for i in (0..MAX_POINTS).rev() {
            let mut s = y[i] * self.inv_d[i];
            for k in i + 1..MAX_POINTS {
                s = s - l[lower_index(k, i)] * x[k];
            }
            x[i] = s;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(matrix: &[&[f64]], rhs: &[f64]) -> NormalBlock {
        let mut b = NormalBlock { count: rhs.len(), ..Default::default() };
        for (i, row) in matrix.iter().enumerate() {
            b.rhs[i] = rhs[i];
            for (j, v) in row.iter().enumerate() {
                b.matrix[i][j] = *v;
            }
        }
        b
    }

    /// A box's face on four coplanar points, each asking for a unit push: unit mass, unit inertia
    /// about x and y, points at (±1, ±1), so `k_ij = 1 + x_i x_j + y_i y_j` (singular: rank 3).
    fn face_block() -> NormalBlock {
        let p = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
        let mut b = NormalBlock { count: 4, ..Default::default() };
        for i in 0..4 {
            b.rhs[i] = 1.0;
            for j in 0..4 {
                b.matrix[i][j] = 1.0 + p[i].0 * p[j].0 + p[i].1 * p[j].1;
            }
        }
        b
    }

    /// An unconstrained SPD system is solved exactly.
    #[test]
    fn solves_a_positive_system() {
        let b = block(&[&[4.0, 1.0, 0.5], &[1.0, 3.0, 0.2], &[0.5, 0.2, 2.0]], &[1.0, 2.0, 3.0]);
        let x = b.solve(&[10.0; 4], ALL_ROWS, None).unwrap().0;
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| b.matrix[i][j] * x[j]).sum::<f64>() - b.rhs[i];
            assert!(r.abs() < 1e-8, "residual {r}");
        }
    }

    /// Four coplanar points under a box centred on them: the singular K has many solutions; the
    /// block picks the equal split.
    #[test]
    fn coplanar_points_share_the_load_equally() {
        let x = face_block().solve(&[0.0; 4], ALL_ROWS, None).unwrap().0;
        for v in &x[..4] {
            assert!((v - 0.25).abs() < 1e-6, "{x:?}");
        }
    }

    /// A row pulled below zero only by a coupled row's pull is taken back once that row is
    /// released: the answer is the complementarity solution, not both rows released.
    #[test]
    fn a_row_pulled_negative_by_its_neighbour_is_taken_back() {
        // Points on either side of a long body's centre couple negatively. Alone, row 0 needs
        // +0.5; solved together with row 1, which wants to pull hard, both come out negative.
        let b = block(&[&[2.0, -1.9], &[-1.9, 2.0]], &[1.0, -20.0]);
        let x = b.solve(&[0.0; 4], ALL_ROWS, None).unwrap().0;
        assert_eq!(x[1], 0.0);
        assert!((x[0] - 0.5).abs() < 1e-8, "{x:?}");
        // Both conditions hold: row 1 is released and does not approach.
        let w1 = b.matrix[1][0] * x[0] - b.rhs[1];
        assert!(w1 >= 0.0, "{w1}");
    }

    /// A block that makes the pivoting cycle (two nearly coincident points, from a pile of hulls)
    /// still gets a bounded answer that satisfies the conditions: the rows ask for no push at
    /// all (all approach slower than their gaps close), so the answer releases what they carry.
    #[test]
    fn a_nearly_singular_block_gets_a_bounded_answer() {
        let b = block(
            &[
                &[0.11982903760955603, 0.10488287531728666, 0.02974670488515954, 0.029741139970138036],
                &[0.10488287531728666, 0.09365605053296351, 0.031136079356871314, 0.031126554534182865],
                &[0.02974670488515954, 0.031136079356871314, 0.05022741117478222, 0.05023856877545073],
                &[0.029741139970138036, 0.031126554534182865, 0.05023856877545073, 0.050249760574528075],
            ],
            &[-9.077163161259174, -0.000646214267500958, -10.168401354419347, -10.214360235440127],
        );
        let accumulated = [0.0, 0.6605284165810472, 0.0, 0.0];
        let x = b.solve(&accumulated, ALL_ROWS, None).unwrap().0;
        for i in 0..4 {
            let total = accumulated[i] + x[i];
            assert!(total >= 0.0 && total < 1.0, "{x:?}");
            let w: f64 = (0..4).map(|j| b.matrix[i][j] * x[j]).sum::<f64>() - b.rhs[i];
            assert!(w > -1e-6, "row {i} approaches: {w}, {x:?}");
        }
    }

    /// The first guess changes how the answer is found, not the answer: a guess that releases a
    /// row of a symmetric face is not kept (all rows free is tried first, and the least-norm
    /// split holds), and the released set the answer ends with is returned as the next guess.
    #[test]
    fn the_guess_of_free_rows_does_not_change_the_answer() {
        let (x, free) = face_block().solve(&[0.0; 4], 0b0111, None).unwrap();
        assert_eq!(free, ALL_ROWS);
        for v in &x[..4] {
            assert!((v - 0.25).abs() < 1e-6, "{x:?}");
        }

        let pulled = block(&[&[2.0, -1.9], &[-1.9, 2.0]], &[1.0, -20.0]);
        for guess in [ALL_ROWS, 0b01, 0b10, 0b00] {
            let (x, free) = pulled.solve(&[0.0; 4], guess, None).unwrap();
            assert_eq!(free & 0b11, 0b01, "guess {guess:b}");
            assert_eq!(x[1], 0.0);
            assert!((x[0] - 0.5).abs() < 1e-8, "guess {guess:b}: {x:?}");
        }
    }

    /// A row that would pull is released and the others carry the load.
    #[test]
    fn pulling_rows_are_released() {
        let b = block(&[&[2.0, 1.0], &[1.0, 2.0]], &[3.0, -3.0]);
        let x = b.solve(&[0.0; 4], ALL_ROWS, None).unwrap().0;
        assert_eq!(x[1], 0.0);
        assert!((x[0] - 1.5).abs() < 1e-8, "{x:?}");
    }
}
