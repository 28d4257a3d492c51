//! Lemke's algorithm on standard LCPs: random positive definite and semidefinite problems checked
//! against brute-force enumeration of all 2ⁿ complementary bases (n ≤ 8), and a degenerate one.
//!
//! The answers are a linear solve on the final basis from the original data, so they are exact up
//! to round-off; the tolerances (1e-10 relative) sit about 10⁵ above what is measured.

mod lcp_support;

use lcp_support::Rng;
use tumble::dynamics::lcp::{natural_residual, solve_lcp, DenseMatrix};

const REL: f64 = 1e-10;

fn gram(b: &DenseMatrix) -> DenseMatrix {
    let n = b.cols();
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| (0..b.rows()).map(|k| b[(k, i)] * b[(k, j)]).sum()).collect())
        .collect();
    DenseMatrix::from_rows(&rows)
}

/// Every solution found by trying all 2ⁿ complementary bases: `z_α = −M_αα⁻¹ q_α`, zero elsewhere.
fn brute_force(m: &DenseMatrix, q: &[f64], tol: f64) -> Vec<Vec<f64>> {
    let n = q.len();
    let mut out = Vec::new();
    for mask in 0u32..(1 << n) {
        let alpha: Vec<usize> = (0..n).filter(|&i| mask & (1 << i) != 0).collect();
        let mut z = vec![0.0; n];
        if !alpha.is_empty() {
            let rhs: Vec<f64> = alpha.iter().map(|&i| -q[i]).collect();
            let Some(za) = m.principal_submatrix(&alpha).solve(&rhs) else { continue };
            for (&i, v) in alpha.iter().zip(za) {
                z[i] = v;
            }
        }
        let w: Vec<f64> = m.mul_vec(&z).iter().zip(q).map(|(a, b)| a + b).collect();
        if z.iter().chain(&w).all(|&x| x >= -tol) {
            out.push(z);
        }
    }
    out
}

/// Checks `w ≥ −tol`, `z ≥ −tol`, `|wᵀz| ≤ tol` with `tol = 1e-10 · scale`; returns the worst of
/// the three, relative to the scale.
fn check_conditions(m: &DenseMatrix, q: &[f64], z: &[f64]) -> f64 {
    let w: Vec<f64> = m.mul_vec(z).iter().zip(q).map(|(a, b)| a + b).collect();
    let scale = q.iter().chain(z).fold(1.0_f64, |a, x| a.max(x.abs())).powi(2);
    let neg = z.iter().chain(&w).fold(0.0_f64, |a, &x| a.max(-x));
    let comp = w.iter().zip(z).map(|(a, b)| a * b).sum::<f64>().abs();
    let worst = neg.max(comp) / scale;
    assert!(worst <= 1e-10, "conditions violated by {worst:e}: z = {z:?}, w = {w:?}");
    worst
}

#[test]
fn random_positive_definite_lcps_match_brute_force() {
    // M = BᵀB + 0.05 I (+ a skew part for half of them: still positive definite, so a P-matrix and
    // the solution is unique). Measured: largest |z − z_brute| / (1 + |z|) ≈ 1e-15.
    let mut rng = Rng(7);
    let (mut worst_diff, mut worst_cond) = (0.0_f64, 0.0_f64);
    for n in 1..=8 {
        for trial in 0..60 {
            let mut m = gram(&rng.matrix(n, n));
            for i in 0..n {
                m[(i, i)] += 0.05;
            }
            if trial % 2 == 1 {
                let s = rng.matrix(n, n);
                for i in 0..n {
                    for j in 0..n {
                        m[(i, j)] += s[(i, j)] - s[(j, i)];
                    }
                }
            }
            let q: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
            let sol = solve_lcp(&m, &q).unwrap();
            worst_cond = worst_cond.max(check_conditions(&m, &q, &sol.z));
            let all = brute_force(&m, &q, 1e-12);
            assert_eq!(
                all.len(),
                1,
                "n = {n}, trial {trial}: a P-matrix LCP has one solution, found {all:?}"
            );
            let zmax = sol.z.iter().fold(1.0_f64, |a, x| a.max(x.abs()));
            for (a, b) in sol.z.iter().zip(&all[0]) {
                worst_diff = worst_diff.max((a - b).abs() / zmax);
            }
        }
    }
    eprintln!(
        "positive definite: worst |z - z_brute| {worst_diff:e}, worst condition violation {worst_cond:e}"
    );
    assert!(worst_diff < REL);
}

#[test]
fn random_semidefinite_lcps_are_solved_with_the_unique_w() {
    // Singular symmetric PSD M = BᵀB with B of rank k < n, q = r − M z̄ with z̄, r ≥ 0 (so a
    // feasible point exists). Solutions may be many, but M z (hence w) is the same for all of them;
    // compare it with every solution that brute force finds.
    let mut rng = Rng(11);
    let mut worst = 0.0_f64;
    for n in 2..=8 {
        for trial in 0..40 {
            let k = 1 + trial % (n - 1);
            let m = gram(&rng.matrix(k, n));
            let zbar: Vec<f64> = (0..n).map(|_| rng.uniform().max(0.0)).collect();
            let mz = m.mul_vec(&zbar);
            let q: Vec<f64> =
                mz.iter().map(|x| 0.5 * (rng.uniform() + 1.0) * (trial % 3) as f64 - x).collect();
            let sol = solve_lcp(&m, &q).unwrap_or_else(|e| panic!("n = {n}, trial {trial}: {e}"));
            check_conditions(&m, &q, &sol.z);
            for other in brute_force(&m, &q, 1e-9) {
                let w_other = m.mul_vec(&other);
                for (a, b) in sol.w.iter().zip(w_other.iter().zip(&q)) {
                    worst = worst.max((a - (b.0 + b.1)).abs());
                }
            }
        }
    }
    eprintln!("semidefinite: worst |w - w_brute| {worst:e}");
    assert!(worst < 1e-9);
}

#[test]
fn degenerate_box_normals_lcp() {
    // Four contact normals under a box: A = J M⁻¹ Jᵀ has rank 3, and q has four equal entries.
    // Every row ties in the first ratio test, and the solution set is a segment.
    let (m_inv, i_inv, h) = (1.0, 3.0, 0.5);
    let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
    let rows: Vec<Vec<f64>> = corners
        .iter()
        .map(|&(xi, yi)| {
            corners.iter().map(|&(xj, yj)| m_inv + i_inv * h * h * (yi * yj + xi * xj)).collect()
        })
        .collect();
    let m = DenseMatrix::from_rows(&rows);
    let q = [-1.0; 4];
    let sol = solve_lcp(&m, &q).unwrap();
    check_conditions(&m, &q, &sol.z);
    assert!((sol.z.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{:?}", sol.z);
    assert!(natural_residual(&m, &q, &sol.z) < 1e-14);
}
