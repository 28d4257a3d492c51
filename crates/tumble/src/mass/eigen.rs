//! Eigen-decomposition of symmetric 3×3 matrices (for principal axes of inertia).
//!
//! Method: cyclic Jacobi. Each step applies a plane rotation that zeroes one off-diagonal entry;
//! a sweep visits the three pairs (0,1), (0,2), (1,2). Convergence is quadratic once the
//! off-diagonal part is small, so a handful of sweeps reaches round-off. Jacobi is chosen over the
//! closed-form (trigonometric) cubic solution because it stays accurate for repeated and nearly
//! repeated eigenvalues (spheres, cubes, symmetric tops), where the closed form loses half the
//! digits of the eigenvectors. The accumulated product of rotations is the eigenvector matrix;
//! it is orthonormal by construction, and a final Gram–Schmidt pass with `z = x × y` makes it a
//! proper rotation to the last bit.

use crate::math::{DMat3, DVec3};

/// Sweeps after which we stop even if the off-diagonal part has not reached round-off. Jacobi on
/// a 3×3 matrix converges in 4–6 sweeps; the cap only guards against non-finite input.
const MAX_SWEEPS: usize = 32;

/// Eigenvalues (ascending) and eigenvectors (columns of a rotation, det +1) of a symmetric matrix.
/// Repeated eigenvalues give some orthonormal right-handed frame, never NaN.
///
/// Only the symmetric part `(m + mᵀ)/2` is used. Non-finite input gives the diagonal as the
/// "eigenvalues" and the identity as the axes (there is nothing meaningful to return).
pub fn symmetric_eigen(m: DMat3) -> (DVec3, DMat3) {
    // a[r][c]: row r, column c of the symmetric part.
    let mut a = [[0.0_f64; 3]; 3];
    for (r, row) in a.iter_mut().enumerate() {
        for (c, entry) in row.iter_mut().enumerate() {
            *entry = 0.5 * (m.col(c)[r] + m.col(r)[c]);
        }
    }
    if a.iter().flatten().any(|x| !x.is_finite()) {
        return (DVec3::new(a[0][0], a[1][1], a[2][2]), DMat3::IDENTITY);
    }

    // v[r][c]: accumulated rotations; column c is the c-th eigenvector.
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    // Stop when the off-diagonal part is below round-off of the whole matrix (absolute error
    // ~ε‖A‖ is what any backward-stable method achieves).
    let norm2: f64 = a.iter().flatten().map(|x| x * x).sum();
    let tiny2 = norm2 * (f64::EPSILON * f64::EPSILON * 1e-4);

    for _ in 0..MAX_SWEEPS {
        let off2 = 2.0 * (a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2]);
        if off2 <= tiny2 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            jacobi_rotate(&mut a, &mut v, p, q);
        }
    }

    // Sort eigenpairs ascending (stable, so equal eigenvalues keep their order).
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    let values = DVec3::new(a[order[0]][order[0]], a[order[1]][order[1]], a[order[2]][order[2]]);
    let column = |c: usize| DVec3::new(v[0][c], v[1][c], v[2][c]);

    // Re-orthonormalise and make right-handed. The third column is an eigenvector either way:
    // it is ± the accumulated one, and the sign of an eigenvector is free.
    let x = column(order[0]).normalize();
    let y0 = column(order[1]);
    let y = (y0 - x * x.dot(y0)).normalize();
    let z = x.cross(y);
    (values, DMat3::from_cols(x, y, z))
}

/// One Jacobi rotation in the (p, q) plane that zeroes `a[p][q]`: `A ← Jᵀ A J`, `V ← V J`.
fn jacobi_rotate(a: &mut [[f64; 3]; 3], v: &mut [[f64; 3]; 3], p: usize, q: usize) {
    let apq = a[p][q];
    if apq == 0.0 {
        return;
    }
    // θ = cot 2φ; t = tan φ is the smaller root of t² + 2θt − 1 = 0, so |φ| ≤ π/4.
    let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
    let t = if theta.abs() > 1e150 {
        // θ² would overflow; the root is then 1/(2θ) to full precision.
        0.5 / theta
    } else {
        let sign = if theta >= 0.0 { 1.0 } else { -1.0 };
        sign / (theta.abs() + (theta * theta + 1.0).sqrt())
    };
    let c = 1.0 / (t * t + 1.0).sqrt();
    let s = t * c;

    // Updating the diagonal through t·a_pq (rather than from c, s) keeps it accurate.
    a[p][p] -= t * apq;
    a[q][q] += t * apq;
    a[p][q] = 0.0;
    a[q][p] = 0.0;
    let r = 3 - p - q; // the remaining index
    let arp = a[r][p];
    let arq = a[r][q];
    a[r][p] = c * arp - s * arq;
    a[p][r] = a[r][p];
    a[r][q] = s * arp + c * arq;
    a[q][r] = a[r][q];

    for row in v.iter_mut() {
        let vp = row[p];
        let vq = row[q];
        row[p] = c * vp - s * vq;
        row[q] = s * vp + c * vq;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{mat3_max_abs, DQuat};

    fn check(m: DMat3, tol: f64) -> (DVec3, DMat3) {
        let (vals, axes) = symmetric_eigen(m);
        assert!(vals.x <= vals.y && vals.y <= vals.z, "not ascending: {vals}");
        let ortho = mat3_max_abs(axes.transpose() * axes - DMat3::IDENTITY);
        assert!(ortho < 1e-15, "not orthonormal: {ortho:e}");
        assert!((axes.determinant() - 1.0).abs() < 1e-15);
        let back = axes * DMat3::from_diagonal(vals) * axes.transpose();
        let err = mat3_max_abs(back - m);
        assert!(err <= tol * mat3_max_abs(m).max(f64::MIN_POSITIVE), "reconstruction {err:e}");
        (vals, axes)
    }

    #[test]
    fn zero_and_identity() {
        let (vals, axes) = check(DMat3::ZERO, 0.0);
        assert_eq!(vals, DVec3::ZERO);
        assert_eq!(axes, DMat3::IDENTITY);
        let (vals, _) = check(DMat3::IDENTITY, 0.0);
        assert_eq!(vals, DVec3::ONE);
    }

    #[test]
    fn diagonal_is_sorted() {
        let (vals, axes) = check(DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0)), 0.0);
        assert_eq!(vals, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(axes.col(0).abs(), DVec3::Y);
        assert_eq!(axes.col(1).abs(), DVec3::Z);
        assert_eq!(axes.col(2).abs(), DVec3::X);
    }

    #[test]
    fn rotated_symmetric_top() {
        let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::ZYX, 0.3, -1.1, 2.0));
        let m = r * DMat3::from_diagonal(DVec3::new(2.0, 2.0, 5.0)) * r.transpose();
        let (vals, axes) = check(m, 1e-14);
        assert!((vals - DVec3::new(2.0, 2.0, 5.0)).abs().max_element() < 1e-14);
        assert!(axes.col(2).dot(r.col(2)).abs() > 1.0 - 1e-14);
    }

    #[test]
    fn huge_ratio_of_entries() {
        let m = DMat3::from_cols(
            DVec3::new(1e10, 1e-20, 0.0),
            DVec3::new(1e-20, -3.0, 1e-300),
            DVec3::new(0.0, 1e-300, 7.0),
        );
        check(m, 1e-15);
    }

    #[test]
    fn non_finite_input_gives_identity() {
        let m = DMat3::from_diagonal(DVec3::new(f64::NAN, 1.0, 2.0));
        let (_, axes) = symmetric_eigen(m);
        assert_eq!(axes, DMat3::IDENTITY);
    }
}
