//! A small dense matrix and an LU factorisation with partial pivoting: all the linear algebra the
//! exact solver needs. Sizes here are tens to a few hundred, so plain row-major storage and
//! O(n³) elimination are the right tools.

use std::ops::{Index, IndexMut};

/// A dense, row-major matrix of `f64`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DenseMatrix {
    rows: usize,
    cols: usize,
    data: Vec<f64>,
}

impl DenseMatrix {
    /// A `rows × cols` matrix of zeros.
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Self { rows, cols, data: vec![0.0; rows * cols] }
    }

    /// The `n × n` identity.
    pub fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m[(i, i)] = 1.0;
        }
        m
    }

    /// A matrix from its rows; every row must have the same length.
    ///
    /// # Panics
    /// If the rows have different lengths.
    pub fn from_rows<R: AsRef<[f64]>>(rows: &[R]) -> Self {
        let cols = rows.first().map_or(0, |r| r.as_ref().len());
        let mut data = Vec::with_capacity(rows.len() * cols);
        for (i, r) in rows.iter().enumerate() {
            assert_eq!(r.as_ref().len(), cols, "row {i} has {} entries, expected {cols}", r.as_ref().len());
            data.extend_from_slice(r.as_ref());
        }
        Self { rows: rows.len(), cols, data }
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Row `i` as a slice.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.cols..(i + 1) * self.cols]
    }

    /// `self · x`.
    ///
    /// # Panics
    /// If `x.len() != self.cols()`.
    pub fn mul_vec(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.cols);
        (0..self.rows).map(|i| dot(self.row(i), x)).collect()
    }

    /// The largest absolute entry (0 for an empty matrix).
    pub fn max_abs(&self) -> f64 {
        self.data.iter().fold(0.0_f64, |a, &b| a.max(b.abs()))
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.data.iter().all(|x| x.is_finite())
    }

    /// The square submatrix on the index set `idx` (rows and columns).
    pub fn principal_submatrix(&self, idx: &[usize]) -> DenseMatrix {
        let mut s = DenseMatrix::zeros(idx.len(), idx.len());
        for (a, &i) in idx.iter().enumerate() {
            for (b, &j) in idx.iter().enumerate() {
                s[(a, b)] = self[(i, j)];
            }
        }
        s
    }

    /// Solves `self · x = rhs` for square `self` by LU with partial pivoting and one step of
    /// iterative refinement. `None` if the matrix is not square or is singular to working precision.
    pub fn solve(&self, rhs: &[f64]) -> Option<Vec<f64>> {
        let lu = Lu::factor(self).ok()?;
        Some(lu.solve_refined(self, rhs))
    }
}

impl Index<(usize, usize)> for DenseMatrix {
    type Output = f64;
    #[inline]
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        debug_assert!(i < self.rows && j < self.cols);
        &self.data[i * self.cols + j]
    }
}

impl IndexMut<(usize, usize)> for DenseMatrix {
    #[inline]
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        debug_assert!(i < self.rows && j < self.cols);
        &mut self.data[i * self.cols + j]
    }
}

#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `P A = L U` with unit lower-triangular `L` and upper-triangular `U` stored in one matrix.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Lu {
    lu: DenseMatrix,
    /// `perm[k]` is the original row now in position `k`.
    perm: Vec<usize>,
}

/// Where elimination broke down: the step and the (tiny) pivot it found there.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Singular {
    pub step: usize,
    pub pivot: f64,
}

/// A pivot smaller than this times the largest entry of the matrix counts as zero. The systems here
/// are small (n ≤ a few hundred) so round-off in a pivot is a few n·ε relative; 1e-12 leaves a wide
/// margin above that while still flagging genuinely dependent rows.
const SINGULAR_RELATIVE: f64 = 1e-12;

impl Lu {
    pub fn factor(a: &DenseMatrix) -> Result<Self, Singular> {
        let n = a.rows;
        if a.cols != n {
            return Err(Singular { step: 0, pivot: 0.0 });
        }
        let threshold = SINGULAR_RELATIVE * a.max_abs();
        let mut lu = a.clone();
        let mut perm: Vec<usize> = (0..n).collect();
        for k in 0..n {
            // Partial pivoting: the largest entry in column k at or below the diagonal.
            let p = (k..n).max_by(|&i, &j| lu[(i, k)].abs().total_cmp(&lu[(j, k)].abs())).unwrap_or(k);
            let pivot = lu[(p, k)];
            if pivot.abs() <= threshold || pivot == 0.0 {
                return Err(Singular { step: k, pivot });
            }
            if p != k {
                for j in 0..n {
                    lu.data.swap(p * n + j, k * n + j);
                }
                perm.swap(p, k);
            }
            for i in k + 1..n {
                let f = lu[(i, k)] / pivot;
                lu[(i, k)] = f;
                if f != 0.0 {
                    for j in k + 1..n {
                        let u = lu[(k, j)];
                        lu[(i, j)] -= f * u;
                    }
                }
            }
        }
        Ok(Self { lu, perm })
    }

    /// Solves `A x = rhs` with the factors.
    pub fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        let n = self.perm.len();
        let mut x: Vec<f64> = self.perm.iter().map(|&p| rhs[p]).collect();
        for i in 0..n {
            let s = dot(&self.lu.row(i)[..i], &x[..i]);
            x[i] -= s;
        }
        for i in (0..n).rev() {
            let s = dot(&self.lu.row(i)[i + 1..], &x[i + 1..]);
            x[i] = (x[i] - s) / self.lu[(i, i)];
        }
        x
    }

    /// Solves `A x = rhs`, then applies one step of iterative refinement with the residual
    /// `rhs − A x` (computed from the original `a`), which removes most of the growth in round-off.
    pub fn solve_refined(&self, a: &DenseMatrix, rhs: &[f64]) -> Vec<f64> {
        let mut x = self.solve(rhs);
        let ax = a.mul_vec(&x);
        let r: Vec<f64> = rhs.iter().zip(&ax).map(|(b, y)| b - y).collect();
        let dx = self.solve(&r);
        for (xi, d) in x.iter_mut().zip(dx) {
            *xi += d;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // The (0,0) entry is zero: without row exchanges elimination would divide by it.
        let a = DenseMatrix::from_rows(&[[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]]);
        let x_true = [1.0, -2.0, 0.5];
        let b = a.mul_vec(&x_true);
        let x = a.solve(&b).unwrap();
        for (u, v) in x.iter().zip(x_true) {
            assert!((u - v).abs() < 1e-15, "{x:?}");
        }
    }

    #[test]
    fn singular_matrix_is_reported() {
        let a = DenseMatrix::from_rows(&[[1.0, 2.0], [2.0, 4.0]]);
        assert!(a.solve(&[1.0, 2.0]).is_none());
        let err = Lu::factor(&a).unwrap_err();
        assert_eq!(err.step, 1);
    }

    #[test]
    fn identity_and_submatrix() {
        let i3 = DenseMatrix::identity(3);
        assert_eq!(i3.mul_vec(&[1.0, 2.0, 3.0]), vec![1.0, 2.0, 3.0]);
        let a = DenseMatrix::from_rows(&[[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]);
        let s = a.principal_submatrix(&[0, 2]);
        assert_eq!(s, DenseMatrix::from_rows(&[[1.0, 3.0], [7.0, 9.0]]));
        assert_eq!(a.max_abs(), 9.0);
    }
}
