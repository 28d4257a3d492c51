//! Lemke's complementary pivoting algorithm for the standard LCP
//!
//! ```text
//!     w = M z + q,    w ≥ 0,    z ≥ 0,    wᵀ z = 0.
//! ```
//!
//! An artificial variable `z₀` with covering vector `d = (1, …, 1)` makes the start feasible:
//! `w = M z + q + d z₀`. With `z = 0` and `z₀ = −min qᵢ` every `w` is nonnegative and one of
//! them, `w_r`, is zero; that is the first pivot (`z₀` enters, `w_r` leaves). From then on the
//! *complementary pivot rule* runs: the variable that just left is replaced by its complement
//! (`w_i ↔ z_i`), and a minimum-ratio test picks which basic variable leaves. Every basis along the
//! way is *almost complementary* (only the pair of the last leaving variable is missing); when `z₀`
//! itself leaves, the basis is complementary and `z₀ = 0`, so it solves the LCP. If the entering
//! column has no positive entry the path runs off to infinity along a *secondary ray*: for
//! copositive-plus `M` (positive semidefinite matrices among them) that proves the LCP infeasible
//! (Cottle, Pang & Stone, *The Linear Complementarity Problem*, 1992, §4.4).
//!
//! **Degeneracy.** When several rows tie in the ratio test, a careless choice can cycle. The rule
//! here is the lexicographic one: among tied rows pick the one whose row of `[B⁻¹q | B⁻¹]` divided
//! by the pivot entry is lexicographically smallest. The rows of `B⁻¹` are distinct, so the choice
//! is unique and no basis repeats. `B⁻¹` is free: it sits in the tableau columns of `w`, which
//! started as the identity. Ties are judged with tolerances taken from an estimate of round-off in
//! each entry (`ε · |B⁻¹ row| · |original column|`), so exact ties computed with round-off still
//! count as ties. A tie that includes `z₀`'s row lets `z₀` leave at once.
//!
//! **Accuracy.** The path is followed on a dense tableau updated by Gauss–Jordan pivots, whose
//! round-off grows with the number of pivots. The final basis is what matters: once known, the
//! solution is recomputed from the original data, `M_αα z_α = −q_α` over the basic `z`'s, by LU with
//! partial pivoting and one refinement step, which brings it back to round-off level.

use super::dense::{DenseMatrix, Lu};
use super::error::LcpError;

/// A solution of `w = M z + q, w ≥ 0, z ≥ 0, wᵀz = 0`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LcpSolution {
    pub z: Vec<f64>,
    /// `M z + q`, recomputed from the final `z`.
    pub w: Vec<f64>,
    /// Pivots Lemke's algorithm took (0 when `q ≥ 0`, where `z = 0` solves at once).
    pub pivots: usize,
}

/// The limit on pivots is `BASE + PER_ROW · n`. Lemke's path usually takes about `n` pivots on
/// contact problems; the worst case is exponential, and the limit turns it into an error.
const MAX_PIVOTS_BASE: usize = 1000;
const MAX_PIVOTS_PER_ROW: usize = 100;
/// An entering-column entry must exceed this fraction of the column's largest entry to pivot on.
const PIVOT_RELATIVE: f64 = 1e-12;
/// Multiples of `ε`-level round-off estimates used as zero thresholds and tie widths. Round-off in
/// one tableau entry is about `n ε |B⁻¹ row| |column|`; 1e-11 ≈ 50 ε covers n up to about 50 at
/// face value and far more in practice, since errors rarely add up in one direction.
const NOISE: f64 = 1e-11;

/// Solves the LCP `w = M z + q, w ≥ 0, z ≥ 0, wᵀz = 0` by Lemke's algorithm with lexicographic
/// tie-breaking (see the module documentation).
///
/// Lemke's algorithm is guaranteed to end in a solution when `M` is positive semidefinite (or more
/// generally copositive-plus) and the LCP is feasible, and when `M` is a P-matrix (then the
/// solution is unique). Otherwise it may stop on a ray, reported as
/// [`LcpError::RayTermination`].
pub fn solve_lcp(m: &DenseMatrix, q: &[f64]) -> Result<LcpSolution, LcpError> {
    let n = q.len();
    if m.rows() != n || m.cols() != n {
        return Err(LcpError::Dimension { rows: m.rows(), cols: m.cols(), len: n });
    }
    if !m.is_finite() {
        return Err(LcpError::NonFinite { what: "LCP matrix M".into() });
    }
    if let Some(i) = q.iter().position(|x| !x.is_finite()) {
        return Err(LcpError::NonFinite { what: format!("LCP vector q[{i}] = {}", q[i]) });
    }
    if q.iter().all(|&x| x >= 0.0) {
        return Ok(LcpSolution { z: vec![0.0; n], w: q.to_vec(), pivots: 0 });
    }

    let mut tab = Tableau::new(m, q);
    let z0 = 2 * n;
    let max_pivots = MAX_PIVOTS_BASE + MAX_PIVOTS_PER_ROW * n;
    let mut leaving = tab.pivot(first_row(q), z0);
    let mut pivots = 1;
    while leaving != z0 {
        if pivots >= max_pivots {
            return Err(LcpError::MaxPivots { max_pivots });
        }
        let entering = complement(leaving, n);
        let Some(r) = tab.ratio_test(entering) else {
            return Err(LcpError::RayTermination { pivots, entering: variable_name(entering, n) });
        };
        leaving = tab.pivot(r, entering);
        pivots += 1;
    }

    let z = polish(m, q, &tab.z(), &tab.basic_z());
    let w = residual_w(m, q, &z);
    Ok(LcpSolution { z, w, pivots })
}

/// The natural residual `max_i |min(z_i, (Mz+q)_i)|`: zero exactly when `z` solves the LCP, and
/// about the size of the largest violation (negative `z` or `w`, or a pair that are both positive).
pub fn natural_residual(m: &DenseMatrix, q: &[f64], z: &[f64]) -> f64 {
    let w = m.mul_vec(z);
    z.iter().zip(w.iter().zip(q)).fold(0.0_f64, |acc, (&zi, (&mzi, &qi))| acc.max(zi.min(mzi + qi).abs()))
}

fn residual_w(m: &DenseMatrix, q: &[f64], z: &[f64]) -> Vec<f64> {
    m.mul_vec(z).iter().zip(q).map(|(a, b)| a + b).collect()
}

/// Recomputes the solution from the original data on the final complementary basis (`basic`: the
/// `i` with `z_i` basic) and keeps whichever of the two candidates violates the conditions less.
/// Negative round-off in `z` is then clamped to zero.
fn polish(m: &DenseMatrix, q: &[f64], z_tableau: &[f64], basic: &[usize]) -> Vec<f64> {
    let mut best = z_tableau.to_vec();
    if !basic.is_empty() {
        let sub = m.principal_submatrix(basic);
        if let Ok(lu) = Lu::factor(&sub) {
            let rhs: Vec<f64> = basic.iter().map(|&i| -q[i]).collect();
            let zb = lu.solve_refined(&sub, &rhs);
            let mut z = vec![0.0; q.len()];
            for (&i, v) in basic.iter().zip(zb) {
                z[i] = v;
            }
            if natural_residual(m, q, &z) <= natural_residual(m, q, &best) {
                best = z;
            }
        }
    }
    for v in &mut best {
        *v = v.max(0.0);
    }
    best
}

/// The row that leaves when `z₀` first enters: the most negative `q_i`. Among exact ties the last
/// row, which is the lexicographic rule for the first pivot (it keeps every row of `[B⁻¹q | B⁻¹]`
/// lexicographically positive afterwards).
fn first_row(q: &[f64]) -> usize {
    let q_min = q.iter().copied().fold(f64::INFINITY, f64::min);
    let tie = NOISE * q_min.abs();
    (0..q.len()).rev().find(|&i| q[i] <= q_min + tie).unwrap_or(0)
}

/// Variables are numbered `w_0..w_{n-1}`, then `z_0..z_{n-1}` (`n..2n`), then `z₀` (`2n`).
fn complement(var: usize, n: usize) -> usize {
    if var < n {
        var + n
    } else {
        var - n
    }
}

fn variable_name(var: usize, n: usize) -> String {
    match var {
        v if v < n => format!("w[{v}]"),
        v if v < 2 * n => format!("z[{}]", v - n),
        _ => "z0".into(),
    }
}

/// The dense tableau `[I | −M | −d | q]` of `w − M z − d z₀ = q`, kept in the form `B⁻¹[…]`.
struct Tableau {
    n: usize,
    width: usize,
    t: Vec<f64>,
    /// The variable basic in each row.
    basis: Vec<usize>,
    /// Largest absolute entry of each original column, for round-off estimates.
    column_scale: Vec<f64>,
}

impl Tableau {
    fn new(m: &DenseMatrix, q: &[f64]) -> Self {
        let n = q.len();
        let width = 2 * n + 2;
        let mut t = vec![0.0; n * width];
        let mut column_scale = vec![1.0; width];
        for i in 0..n {
            let row = &mut t[i * width..(i + 1) * width];
            row[i] = 1.0;
            for j in 0..n {
                row[n + j] = -m[(i, j)];
            }
            row[2 * n] = -1.0;
            row[2 * n + 1] = q[i];
        }
        for j in 0..n {
            column_scale[n + j] = (0..n).fold(0.0_f64, |a, i| a.max(m[(i, j)].abs()));
        }
        column_scale[2 * n + 1] = q.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        Self { n, width, t, basis: (0..n).collect(), column_scale }
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.t[i * self.width + j]
    }

    /// Sum of |B⁻¹| over row `i`: how much round-off row `i` has gathered, per unit of data.
    fn inverse_row_norm(&self, i: usize) -> f64 {
        self.t[i * self.width..i * self.width + self.n].iter().map(|x| x.abs()).sum()
    }

    /// Gauss–Jordan pivot on `(r, c)`; returns the variable that left the basis.
    fn pivot(&mut self, r: usize, c: usize) -> usize {
        let w = self.width;
        let p = self.t[r * w + c];
        for x in &mut self.t[r * w..(r + 1) * w] {
            *x /= p;
        }
        self.t[r * w + c] = 1.0;
        let pivot_row = self.t[r * w..(r + 1) * w].to_vec();
        for i in (0..self.n).filter(|&i| i != r) {
            let row = &mut self.t[i * w..(i + 1) * w];
            let f = row[c];
            if f != 0.0 {
                for (x, &pr) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * pr;
                }
                row[c] = 0.0;
            }
        }
        std::mem::replace(&mut self.basis[r], c)
    }

    /// The lexicographic minimum-ratio test for entering column `c`; `None` on a ray.
    fn ratio_test(&self, c: usize) -> Option<usize> {
        let n = self.n;
        let rhs = 2 * n + 1;
        let col_max = (0..n).fold(0.0_f64, |a, i| a.max(self.at(i, c).abs()));
        // (row, pivot entry, ratio, round-off width of the ratio)
        let mut cand: Vec<(usize, f64, f64, f64)> = Vec::new();
        for i in 0..n {
            let a = self.at(i, c);
            let inv_norm = self.inverse_row_norm(i);
            let zero = (PIVOT_RELATIVE * col_max).max(NOISE * inv_norm * self.column_scale[c]);
            if a > zero {
                let ratio = self.at(i, rhs).max(0.0) / a;
                let width = NOISE * inv_norm * self.column_scale[rhs] / a;
                cand.push((i, a, ratio, width));
            }
        }
        let &(_, _, theta, theta_width) = cand.iter().min_by(|x, y| x.2.total_cmp(&y.2))?;
        let ties: Vec<(usize, f64)> = cand
            .iter()
            .filter(|&&(_, _, ratio, width)| ratio - theta <= 1e-10 * theta + width + theta_width)
            .map(|&(i, a, _, _)| (i, a))
            .collect();
        if ties.len() == 1 {
            return Some(ties[0].0);
        }
        if let Some(&(i, _)) = ties.iter().find(|&&(i, _)| self.basis[i] == 2 * n) {
            return Some(i); // z₀ can leave: the next basis is a solution.
        }
        Some(self.lexicographic_min(ties))
    }

    /// Among tied rows, the one whose `B⁻¹` row divided by its pivot entry is lexicographically
    /// smallest, comparing column by column with a round-off tolerance.
    fn lexicographic_min(&self, mut ties: Vec<(usize, f64)>) -> usize {
        for k in 0..self.n {
            let values: Vec<f64> = ties.iter().map(|&(i, a)| self.at(i, k) / a).collect();
            let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
            let spread = values.iter().fold(0.0_f64, |acc, v| acc.max(v.abs()));
            let keep = ties.iter().zip(&values).filter(|(_, &v)| v - lo <= NOISE * spread).map(|(t, _)| *t);
            ties = keep.collect();
            if ties.len() == 1 {
                break;
            }
        }
        ties[0].0
    }

    /// The indices `i` whose `z_i` is basic, ascending.
    fn basic_z(&self) -> Vec<usize> {
        let n = self.n;
        let mut idx: Vec<usize> =
            self.basis.iter().filter(|&&v| (n..2 * n).contains(&v)).map(|&v| v - n).collect();
        idx.sort_unstable();
        idx
    }

    /// The `z` part of the current basic solution.
    fn z(&self) -> Vec<f64> {
        let n = self.n;
        let mut z = vec![0.0; n];
        for (i, &var) in self.basis.iter().enumerate() {
            if (n..2 * n).contains(&var) {
                z[var - n] = self.at(i, 2 * n + 1);
            }
        }
        z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(m: &DenseMatrix, q: &[f64], z_expected: &[f64]) -> LcpSolution {
        let s = solve_lcp(m, q).unwrap();
        for (i, (a, b)) in s.z.iter().zip(z_expected).enumerate() {
            assert!((a - b).abs() < 1e-13 * (1.0 + b.abs()), "z[{i}] = {a}, expected {b}; z = {:?}", s.z);
        }
        assert!(natural_residual(m, q, &s.z) < 1e-13);
        s
    }

    #[test]
    fn trivial_when_q_is_nonnegative() {
        let m = DenseMatrix::from_rows(&[[1.0, 2.0], [3.0, 4.0]]);
        let s = check(&m, &[0.0, 1.0], &[0.0, 0.0]);
        assert_eq!(s.pivots, 0);
    }

    #[test]
    fn two_by_two_interior_solution() {
        // 2 z1 + z2 = 5, z1 + 2 z2 = 6: both z positive, w = 0.
        let m = DenseMatrix::from_rows(&[[2.0, 1.0], [1.0, 2.0]]);
        check(&m, &[-5.0, -6.0], &[4.0 / 3.0, 7.0 / 3.0]);
    }

    #[test]
    fn quadratic_program_with_active_bound() {
        // min ½xᵀQx + cᵀx, x ≥ 0 with Q = 2I, c = (−2, 4): x = (1, 0), w = (0, 4).
        let m = DenseMatrix::from_rows(&[[2.0, 0.0], [0.0, 2.0]]);
        let s = check(&m, &[-2.0, 4.0], &[1.0, 0.0]);
        assert!((s.w[1] - 4.0).abs() < 1e-15);
    }

    #[test]
    fn murty_triangular_p_matrix() {
        // Lower-triangular with unit diagonal and 2's below (Murty's matrix): z = (1, 0, 0),
        // w = (0, 1, 1) by forward substitution.
        let m = DenseMatrix::from_rows(&[[1.0, 0.0, 0.0], [2.0, 1.0, 0.0], [2.0, 2.0, 1.0]]);
        let s = check(&m, &[-1.0, -1.0, -1.0], &[1.0, 0.0, 0.0]);
        assert!((s.w[1] - 1.0).abs() < 1e-15 && (s.w[2] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn degenerate_ties_in_the_first_ratio_test() {
        // M = I, q = −1: every row ties for the first pivot.
        let m = DenseMatrix::identity(4);
        check(&m, &[-1.0; 4], &[1.0; 4]);
    }

    #[test]
    fn degenerate_zero_entries_in_q() {
        // w₂ = 0 and z₂ = 0 at the solution (a degenerate solution), and a zero in q makes the
        // start degenerate too. M is positive definite, so each solution is unique.
        let m = DenseMatrix::from_rows(&[[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]]);
        check(&m, &[-1.0, 1.0, -1.0], &[0.5, 0.0, 0.5]);
        check(&m, &[-1.0, 0.0, -1.0], &[1.0, 1.0, 1.0]);
    }

    #[test]
    fn singular_psd_matrix_with_repeated_rows() {
        // M = [[1,1],[1,1]], q = (−1, −1): every z ≥ 0 with z1 + z2 = 1 solves; any answer must
        // satisfy the conditions.
        let m = DenseMatrix::from_rows(&[[1.0, 1.0], [1.0, 1.0]]);
        let s = solve_lcp(&m, &[-1.0, -1.0]).unwrap();
        assert!((s.z[0] + s.z[1] - 1.0).abs() < 1e-15);
        assert!(natural_residual(&m, &[-1.0, -1.0], &s.z) < 1e-15);
    }

    #[test]
    fn linear_program_duality_zero_diagonal() {
        // min x1 + x2 s.t. x1 + 2 x2 ≥ 2, 2 x1 + x2 ≥ 2, x ≥ 0, as the LCP of its optimality
        // conditions: M = [[0, −Aᵀ], [A, 0]] (skew-symmetric, so positive semidefinite with a zero
        // diagonal), q = (c, −b). Primal x = (⅔, ⅔), dual y = (⅓, ⅓).
        let m = DenseMatrix::from_rows(&[
            [0.0, 0.0, -1.0, -2.0],
            [0.0, 0.0, -2.0, -1.0],
            [1.0, 2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0, 0.0],
        ]);
        check(&m, &[1.0, 1.0, -2.0, -2.0], &[2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0]);
    }

    #[test]
    fn bimatrix_game_is_outside_the_guarantee() {
        // A bimatrix-game LCP, M = [[0, A], [Bᵀ, 0]] with A, B > 0, is copositive but not
        // copositive-plus. It has a solution (x = y = (⅓, ⅓)), yet Lemke's algorithm with the
        // covering vector (1, …, 1) meets a ray at once: that is why Lemke–Howson starts
        // differently. The contact LCPs built here never have this structure.
        let m = DenseMatrix::from_rows(&[
            [0.0, 0.0, 1.0, 2.0],
            [0.0, 0.0, 2.0, 1.0],
            [2.0, 1.0, 0.0, 0.0],
            [1.0, 2.0, 0.0, 0.0],
        ]);
        assert!(natural_residual(&m, &[-1.0; 4], &[1.0 / 3.0; 4]) < 1e-15);
        assert!(matches!(solve_lcp(&m, &[-1.0; 4]), Err(LcpError::RayTermination { pivots: 1, .. })));
    }

    #[test]
    fn infeasible_lcp_ends_on_a_ray() {
        // w = −z − 1 can never be ≥ 0 with z ≥ 0.
        let m = DenseMatrix::from_rows(&[[-1.0]]);
        let err = solve_lcp(&m, &[-1.0]).unwrap_err();
        assert!(matches!(err, LcpError::RayTermination { .. }), "{err}");
        // A PSD matrix with an inconsistent pair: w1 = z1 − z2 − 1, w2 = −z1 + z2 − 1.
        let m = DenseMatrix::from_rows(&[[1.0, -1.0], [-1.0, 1.0]]);
        let err = solve_lcp(&m, &[-1.0, -1.0]).unwrap_err();
        assert!(matches!(err, LcpError::RayTermination { .. }), "{err}");
    }

    #[test]
    fn bad_input_is_reported() {
        let m = DenseMatrix::from_rows(&[[1.0, 0.0], [0.0, 1.0]]);
        assert!(matches!(solve_lcp(&m, &[1.0]), Err(LcpError::Dimension { rows: 2, cols: 2, len: 1 })));
        assert!(matches!(solve_lcp(&m, &[1.0, f64::NAN]), Err(LcpError::NonFinite { .. })));
    }
}
