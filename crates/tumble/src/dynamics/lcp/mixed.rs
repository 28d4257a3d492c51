//! From the mixed problem (equality, normal and friction rows) to one standard LCP.
//!
//! The rows ask, with `w = A λ + b` the row velocities after the impulses:
//!
//! ```text
//!   equality  E:  w_E = 0,                              λ_E free
//!   normal    N:  w_N ≥ 0,  λ_N ≥ 0,  w_N λ_N = 0
//!   friction  F:  |λ_f| ≤ μ_f λ_n(f);  |λ_f| < μ_f λ_n(f) ⇒ w_f = 0;  w_f ≠ 0 ⇒ λ_f = −μ_f λ_n(f) sign(w_f)
//! ```
//!
//! **Equality rows: Schur complement.** `w_E = 0` is solved for `λ_E`,
//! `λ_E = −A_EE⁻¹ (b_E + A_EC λ_C)` (C = the other rows), which leaves
//! `w_C = S λ_C + s` with `S = A_CC − A_CE A_EE⁻¹ A_EC` and `s = b_C − A_CE A_EE⁻¹ b_E`. `S` is the
//! effective inverse mass seen by the contacts once the joints hold, still symmetric positive
//! semidefinite. This needs `A_EE` nonsingular, i.e. independent joint rows that each touch a
//! dynamic body; otherwise [`LcpError::SingularEquality`].
//!
//! **Friction: the Stewart–Trinkle construction, one pair of directions per row.** Each friction
//! row is split into `λ_f = λ_f⁺ − λ_f⁻` with `λ_f^± ≥ 0` (the directions `+t` and `−t`) and gets a
//! slack `β_f ≥ 0` (at the solution, the sliding speed `|w_f|`):
//!
//! ```text
//!    w_f + β_f ≥ 0           ⟂  λ_f⁺ ≥ 0
//!   −w_f + β_f ≥ 0           ⟂  λ_f⁻ ≥ 0
//!    μ_f λ_n − λ_f⁺ − λ_f⁻ ≥ 0 ⟂  β_f ≥ 0
//! ```
//!
//! If the row slides (`w_f ≠ 0`, say `w_f > 0`), the second line forces `β_f ≥ w_f > 0`, so the
//! third saturates (`λ_f⁺ + λ_f⁻ = μ λ_n`), and the first, now strictly positive, zeroes `λ_f⁺`:
//! `λ_f = −μ λ_n`, the friction opposes the slip at full strength. If `β_f = 0`, the first two lines
//! give `w_f = 0` (sticking) with `|λ_f| ≤ μ λ_n`. This is Stewart & Trinkle's formulation with one
//! slack per friction row instead of one per contact: their single slack bounds the sum over all
//! directions of a contact (a polygonal cone); here each tangent row is bounded by itself, which
//! gives the four-sided pyramid aligned with the tangents that per-row clamping in an iterative
//! solver converges to.
//!
//! With `z = (λ_N, λ_F⁺, λ_F⁻, β_F)` the LCP `w = M z + q` is
//!
//! ```text
//!        ⎡ S_NN    S_NF   −S_NF   0 ⎤        ⎡  s_N ⎤
//!   M =  ⎢ S_FN    S_FF   −S_FF   I ⎥,  q =  ⎢  s_F ⎥
//!        ⎢−S_FN   −S_FF    S_FF   I ⎥        ⎢ −s_F ⎥
//!        ⎣ μE     −I      −I      0 ⎦        ⎣   0  ⎦
//! ```
//!
//! where `E` picks each friction row's normal. `M` is copositive (`zᵀMz = λ_Cᵀ S λ_C + Σ μ λ_n β ≥ 0`
//! on `z ≥ 0`, after the `±I` terms cancel). Anitescu & Potra (1997) showed for this structure
//! (with one slack per contact, and with joints) that Lemke's algorithm does not end on a ray when
//! the constraints admit a motion; their argument uses the copositivity and the block sign pattern,
//! which the per-row variant shares. So with a consistent bias the problem is solvable by
//! [`super::lemke::solve_lcp`]. The `λ` it returns need
//! not be unique (four contacts under a box are statically indeterminate), but every solution has the
//! same free-body answer wherever the physics fixes it (sums of normal impulses, post velocities).

use super::dense::{DenseMatrix, Lu};
use super::error::LcpError;
use super::lemke::solve_lcp;
use super::system::RowKind;

/// Impulses of the mixed problem and what the LCP took.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct MixedSolution {
    pub lambda: Vec<f64>,
    pub pivots: usize,
    pub lcp_size: usize,
}

/// Solves the mixed problem on `w = A λ + b` with row kinds `kinds` (see the module documentation).
/// Assumes validated kinds (friction rows point at normal rows).
pub(crate) fn solve_mixed(a: &DenseMatrix, b: &[f64], kinds: &[RowKind]) -> Result<MixedSolution, LcpError> {
    let eq: Vec<usize> = (0..kinds.len()).filter(|&i| kinds[i] == RowKind::Equality).collect();
    let normals: Vec<usize> = (0..kinds.len()).filter(|&i| kinds[i] == RowKind::Normal).collect();
    let friction: Vec<usize> =
        (0..kinds.len()).filter(|&i| matches!(kinds[i], RowKind::Friction { .. })).collect();
    let c: Vec<usize> = normals.iter().chain(&friction).copied().collect();

    // Schur complement of the equality block.
    let (s, s_rhs, eq_solve) = if eq.is_empty() {
        (a.principal_submatrix(&c), c.iter().map(|&i| b[i]).collect(), None)
    } else {
        let a_ee = a.principal_submatrix(&eq);
        let lu = Lu::factor(&a_ee)
            .map_err(|e| LcpError::SingularEquality { row: eq[e.step.min(eq.len() - 1)], pivot: e.pivot })?;
        let solve = |rhs: &[f64]| lu.solve_refined(&a_ee, rhs);
        // X = A_EE⁻¹ A_EC column by column, y = A_EE⁻¹ b_E.
        let x: Vec<Vec<f64>> =
            c.iter().map(|&j| solve(&eq.iter().map(|&e| a[(e, j)]).collect::<Vec<_>>())).collect();
        let y = solve(&eq.iter().map(|&e| b[e]).collect::<Vec<_>>());
        let mut s = a.principal_submatrix(&c);
        let mut s_rhs: Vec<f64> = c.iter().map(|&i| b[i]).collect();
        for (p, &i) in c.iter().enumerate() {
            let a_ie: Vec<f64> = eq.iter().map(|&e| a[(i, e)]).collect();
            for (r, xr) in x.iter().enumerate() {
                s[(p, r)] -= dot(&a_ie, xr);
            }
            s_rhs[p] -= dot(&a_ie, &y);
        }
        (s, s_rhs, Some((a_ee, lu)))
    };

    let (nn, nf) = (normals.len(), friction.len());
    let size = nn + 3 * nf;
    let mut m = DenseMatrix::zeros(size, size);
    let mut q = vec![0.0; size];
    // Position of each normal row (by original index) inside the LCP.
    let normal_pos = |row: usize| normals.iter().position(|&n| n == row).expect("validated normal row");
    let (plus, minus, slack) = (nn, nn + nf, nn + 2 * nf);
    for p in 0..nn + nf {
        // Rows of S: normal p < nn, friction p − nn. The LCP row of λ_C[p] is p for normals and
        // plus + f for friction; the λ⁻ row is its negative.
        let (row_plus, row_minus) = if p < nn { (p, None) } else { (p, Some(minus + p - nn)) };
        for r in 0..nn + nf {
            let v = s[(p, r)];
            let (col_plus, col_minus) = if r < nn { (r, None) } else { (r, Some(minus + r - nn)) };
            m[(row_plus, col_plus)] = v;
            if let Some(cm) = col_minus {
                m[(row_plus, cm)] = -v;
            }
            if let Some(rm) = row_minus {
                m[(rm, col_plus)] = -v;
                if let Some(cm) = col_minus {
                    m[(rm, cm)] = v;
                }
            }
        }
        q[row_plus] = s_rhs[p];
        if let Some(rm) = row_minus {
            q[rm] = -s_rhs[p];
        }
    }
    for (f, &row) in friction.iter().enumerate() {
        let RowKind::Friction { normal_row, mu } = kinds[row] else { unreachable!() };
        m[(plus + f, slack + f)] = 1.0;
        m[(minus + f, slack + f)] = 1.0;
        m[(slack + f, normal_pos(normal_row))] = mu;
        m[(slack + f, plus + f)] = -1.0;
        m[(slack + f, minus + f)] = -1.0;
    }

    let sol = solve_lcp(&m, &q)?;
    let mut lambda = vec![0.0; kinds.len()];
    let mut lambda_c = vec![0.0; c.len()];
    for (p, &row) in c.iter().enumerate() {
        let v = if p < nn { sol.z[p] } else { sol.z[plus + p - nn] - sol.z[minus + p - nn] };
        lambda_c[p] = v;
        lambda[row] = v;
    }
    if let Some((a_ee, lu)) = eq_solve {
        let rhs: Vec<f64> = eq
            .iter()
            .map(|&e| -(b[e] + c.iter().zip(&lambda_c).map(|(&j, l)| a[(e, j)] * l).sum::<f64>()))
            .collect();
        for (&e, v) in eq.iter().zip(lu.solve_refined(&a_ee, &rhs)) {
            lambda[e] = v;
        }
    }
    Ok(MixedSolution { lambda, pivots: sol.pivots, lcp_size: size })
}

/// The natural residual of the mixed conditions: `max |λ_i − mid(lo_i, hi_i, λ_i − w_i)|` with the
/// bounds `(−∞, ∞)` for equality rows, `[0, ∞)` for normal rows and `[−μλ_n, μλ_n]` for friction
/// rows. It is zero exactly at a solution and is about the size of the largest violation.
pub(crate) fn mixed_residual(kinds: &[RowKind], lambda: &[f64], w: &[f64]) -> f64 {
    let mut worst = 0.0_f64;
    for (i, kind) in kinds.iter().enumerate() {
        let (l, wi) = (lambda[i], w[i]);
        let r = match *kind {
            RowKind::Equality => wi,
            RowKind::Normal => l.min(wi),
            RowKind::Friction { normal_row, mu } => {
                let h = (mu * lambda[normal_row]).max(0.0);
                l - (l - wi).clamp(-h, h)
            }
        };
        worst = worst.max(r.abs());
    }
    worst
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_sliding_particle_gets_full_friction() {
        // A unit-mass particle on the ground moving down at 1 and sideways at 3: rows are the
        // normal (A = 1) and one tangent (A = 1), decoupled. λ_n = 1 stops the fall; friction
        // μ = 0.5 can take at most 0.5 of the 3 units of sideways speed: λ_t = −0.5, w_t = 2.5.
        let a = DenseMatrix::identity(2);
        let kinds = [RowKind::Normal, RowKind::Friction { normal_row: 0, mu: 0.5 }];
        let sol = solve_mixed(&a, &[-1.0, 3.0], &kinds).unwrap();
        assert!((sol.lambda[0] - 1.0).abs() < 1e-15 && (sol.lambda[1] + 0.5).abs() < 1e-15, "{sol:?}");
        assert_eq!(sol.lcp_size, 4);
        // Slow enough to stick: λ_t = −0.2, w_t = 0.
        let sol = solve_mixed(&a, &[-1.0, 0.2], &kinds).unwrap();
        assert!((sol.lambda[1] + 0.2).abs() < 1e-15, "{sol:?}");
    }

    #[test]
    fn equality_rows_are_eliminated() {
        // Two coupled rows, one equality: w0 = 2λ0 + λ1 + 1 = 0, w1 = λ0 + 2λ1 − 3 ≥ 0 ⟂ λ1 ≥ 0.
        // λ1 = 0 gives λ0 = −½, w1 = −3.5 < 0, so λ1 > 0: solve both as equalities → λ0 = −5/3,
        // λ1 = 7/3.
        let a = DenseMatrix::from_rows(&[[2.0, 1.0], [1.0, 2.0]]);
        let kinds = [RowKind::Equality, RowKind::Normal];
        let sol = solve_mixed(&a, &[1.0, -3.0], &kinds).unwrap();
        assert!((sol.lambda[0] + 5.0 / 3.0).abs() < 1e-14 && (sol.lambda[1] - 7.0 / 3.0).abs() < 1e-14);
        let w: Vec<f64> = a.mul_vec(&sol.lambda).iter().zip([1.0, -3.0]).map(|(x, y)| x + y).collect();
        assert!(mixed_residual(&kinds, &sol.lambda, &w) < 1e-14);
    }

    #[test]
    fn dependent_equality_rows_are_an_error() {
        let a = DenseMatrix::from_rows(&[[1.0, 1.0], [1.0, 1.0]]);
        let err = solve_mixed(&a, &[1.0, 1.0], &[RowKind::Equality, RowKind::Equality]).unwrap_err();
        assert!(matches!(err, LcpError::SingularEquality { row: 1, .. }), "{err}");
    }
}
