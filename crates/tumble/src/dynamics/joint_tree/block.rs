//! Small dense blocks (at most 6×6) and their `LDLᵀ` factorisation: the pieces of the joint
//! tree's block elimination. A body's block is its 6×6 mass matrix; a joint's block has one row
//! per constraint row (3 for a ball joint, up to 6 for a fixed joint).
//!
//! The symmetric blocks the tree factors are definite — positive for bodies, negative for
//! joints — so `LDLᵀ` needs no pivoting. A pivot that vanishes (a degenerate joint, such as a
//! hinge whose two axes are at right angles) gets a zero inverse: that direction takes no
//! impulse in this pass, instead of an infinite one.

// Dense kernels index rows and columns by number: clearer here than zipped iterators.
#![allow(clippy::needless_range_loop)]

/// Largest block dimension: six rows (a fixed joint) or six velocities (a body).
pub(crate) const MAX_DIM: usize = 6;

/// A `rows × cols` block, row-major in a fixed 6×6 array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Block {
    pub rows: usize,
    pub cols: usize,
    pub m: [[f64; MAX_DIM]; MAX_DIM],
}

/// A vector of up to six entries (a block's right-hand side or solution).
pub(crate) type BlockVector = [f64; MAX_DIM];

impl Block {
    pub const fn zero(rows: usize, cols: usize) -> Block {
        Block { rows, cols, m: [[0.0; MAX_DIM]; MAX_DIM] }
    }

    /// Makes the block a zero `rows × cols` block, in place: its first `rows` rows are cleared
    /// whole. (The products below write only a block's own rows, but all six columns of them —
    /// where a non-finite neighbour's `0 × ∞` can leave NaN beyond its size; clearing whole rows
    /// keeps that from reaching the next step's solve of a kept tree.)
    pub fn set_zero(&mut self, rows: usize, cols: usize) {
        (self.rows, self.cols) = (rows, cols);
        for row in self.m.iter_mut().take(rows) {
            *row = [0.0; MAX_DIM];
        }
    }

    // The products below run their column loops over all six columns, and their other loops
    // with constant bounds for the sizes that occur (a match on the sizes, then an inlined body): blocks are zero outside
    // their size, so the extra terms add exact zeros, and loops of a fixed length unroll and
    // vectorise where loops to `cols` did not.

    /// `self −= aᵀ b` (`a` is `k × rows`, `b` is `k × cols`).
    pub fn sub_transpose_mul(&mut self, a: &Block, b: &Block) {
        debug_assert!(a.rows == b.rows && a.cols == self.rows && b.cols == self.cols);
        match (a.rows, self.rows) {
            (3, 6) => self.sub_transpose_mul_sized(a, b, 3, 6),
            (6, 3) => self.sub_transpose_mul_sized(a, b, 6, 3),
            (5, 6) => self.sub_transpose_mul_sized(a, b, 5, 6),
            (6, 5) => self.sub_transpose_mul_sized(a, b, 6, 5),
            (6, 6) => self.sub_transpose_mul_sized(a, b, 6, 6),
            (k, r) => self.sub_transpose_mul_sized(a, b, k, r),
        }
    }

    #[inline(always)]
    fn sub_transpose_mul_sized(&mut self, a: &Block, b: &Block, depth: usize, rows: usize) {
        for k in 0..depth {
            let (a_row, b_row) = (&a.m[k], &b.m[k]);
            for i in 0..rows {
                let aki = a_row[i];
                if aki == 0.0 {
                    continue;
                }
                for j in 0..MAX_DIM {
                    self.m[i][j] -= aki * b_row[j];
                }
            }
        }
    }

    /// `y −= selfᵀ x` (`x` has `rows` entries, `y` has `cols`).
    pub fn sub_transpose_mul_vector(&self, x: &BlockVector, y: &mut BlockVector) {
        for (k, xk) in x.iter().enumerate().take(self.rows) {
            for j in 0..MAX_DIM {
                y[j] -= self.m[k][j] * xk;
            }
        }
    }

    /// `y −= self x` (`x` has `cols` entries, `y` has `rows`).
    pub fn sub_mul_vector(&self, x: &BlockVector, y: &mut BlockVector) {
        for (i, yi) in y.iter_mut().enumerate().take(self.rows) {
            let row = &self.m[i];
            let mut sum = 0.0;
            for j in 0..MAX_DIM {
                sum += row[j] * x[j];
            }
            *yi -= sum;
        }
    }
}

/// A square symmetric block factored as `L D Lᵀ` (unit lower `L`, diagonal `D`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ldlt {
    pub dim: usize,
    /// `L` below the diagonal; the diagonal and above are unused.
    l: [[f64; MAX_DIM]; MAX_DIM],
    /// `1/Dᵢ`, or 0 for a pivot that vanished.
    inv_d: BlockVector,
}

impl Ldlt {
    /// The factor of an empty block.
    pub const EMPTY: Ldlt = Ldlt { dim: 0, l: [[0.0; MAX_DIM]; MAX_DIM], inv_d: [0.0; MAX_DIM] };

    /// Factors the symmetric block `a` (only its lower triangle is read). A pivot smaller than
    /// `1e-12` of the largest diagonal entry counts as zero.
    #[cfg(test)]
    pub fn factor(a: &Block) -> Ldlt {
        let mut f = Ldlt::EMPTY;
        f.factor_from(a);
        f
    }

    /// Factors `a` into `self` (see `factor`), writing only the entries of its size: a tree
    /// refactors every block every substep, and building whole 6×6 arrays and copying them out
    /// was a fifth of a chain's step.
    pub fn factor_from(&mut self, a: &Block) {
        debug_assert_eq!(a.rows, a.cols);
        // The sizes that occur (ball joints 3, hinges and sliders 5, fixed joints and bodies 6)
        // each get a copy with constant loop bounds, which the compiler unrolls.
        match a.rows {
            3 => self.factor_sized(a, 3),
            5 => self.factor_sized(a, 5),
            6 => self.factor_sized(a, 6),
            n => self.factor_sized(a, n),
        }
    }

    #[inline(always)]
    fn factor_sized(&mut self, a: &Block, n: usize) {
        let scale = (0..n).map(|i| a.m[i][i].abs()).fold(0.0, f64::max);
        let tolerance = 1e-12 * scale;
        let mut d = [0.0; MAX_DIM];
        self.dim = n;
        let (l, inv_d) = (&mut self.l, &mut self.inv_d);
        for j in 0..n {
            let dj = a.m[j][j] - (0..j).map(|k| l[j][k] * l[j][k] * d[k]).sum::<f64>();
            if dj.abs() <= tolerance || !dj.is_finite() {
                // Degenerate direction: no impulse along it, and no coupling through it.
                d[j] = 0.0;
                inv_d[j] = 0.0;
                for row in l.iter_mut().take(n).skip(j + 1) {
                    row[j] = 0.0;
                }
                continue;
            }
            d[j] = dj;
            inv_d[j] = 1.0 / dj;
            for i in j + 1..n {
                let s = a.m[i][j] - (0..j).map(|k| l[i][k] * l[j][k] * d[k]).sum::<f64>();
                l[i][j] = s * inv_d[j];
            }
        }
    }

    /// Solves `A x = b` in place.
    #[inline]
    pub fn solve_in_place(&self, x: &mut BlockVector) {
        let n = self.dim;
        for i in 1..n {
            let mut s = x[i];
            for k in 0..i {
                s -= self.l[i][k] * x[k];
            }
            x[i] = s;
        }
        for i in 0..n {
            x[i] *= self.inv_d[i];
        }
        for i in (0..n.saturating_sub(1)).rev() {
            let mut s = x[i];
            for k in i + 1..n {
                s -= self.l[k][i] * x[k];
            }
            x[i] = s;
        }
    }

    /// `x = A⁻¹ b`, written over `x` (only the entries of `b`'s size).
    pub fn solve_block_into(&self, b: &Block, x: &mut Block) {
        match self.dim {
            3 => self.solve_block_sized(b, x, 3),
            5 => self.solve_block_sized(b, x, 5),
            6 => self.solve_block_sized(b, x, 6),
            n => self.solve_block_sized(b, x, n),
        }
    }

    #[inline(always)]
    fn solve_block_sized(&self, b: &Block, x: &mut Block, n: usize) {
        debug_assert_eq!(b.rows, self.dim);
        let cols = b.cols;
        x.rows = b.rows;
        x.cols = cols;
        // All six columns (see the products above): `b` is zero beyond `cols`, so `x` is too.
        for (row_x, row_b) in x.m.iter_mut().zip(&b.m).take(n) {
            *row_x = *row_b;
        }
        for i in 1..n {
            for k in 0..i {
                let lik = self.l[i][k];
                if lik != 0.0 {
                    let (head, tail) = x.m.split_at_mut(i);
                    for j in 0..MAX_DIM {
                        tail[0][j] -= lik * head[k][j];
                    }
                }
            }
        }
        for i in 0..n {
            for j in 0..MAX_DIM {
                x.m[i][j] *= self.inv_d[i];
            }
        }
        for i in (0..n.saturating_sub(1)).rev() {
            for k in i + 1..n {
                let lki = self.l[k][i];
                if lki != 0.0 {
                    let (head, tail) = x.m.split_at_mut(k);
                    for j in 0..MAX_DIM {
                        head[i][j] -= lki * tail[0][j];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(rows: &[&[f64]]) -> Block {
        let mut b = Block::zero(rows.len(), rows[0].len());
        for (i, row) in rows.iter().enumerate() {
            b.m[i][..row.len()].copy_from_slice(row);
        }
        b
    }

    fn mul(a: &Block, x: &BlockVector) -> BlockVector {
        let mut y = [0.0; MAX_DIM];
        for i in 0..a.rows {
            y[i] = (0..a.cols).map(|j| a.m[i][j] * x[j]).sum();
        }
        y
    }

    #[test]
    fn solves_positive_and_negative_definite_blocks() {
        let spd = block(&[&[4.0, 1.0, 0.5], &[1.0, 3.0, 0.2], &[0.5, 0.2, 2.0]]);
        let mut nd = spd;
        for row in nd.m.iter_mut() {
            for v in row.iter_mut() {
                *v = -*v;
            }
        }
        for a in [spd, nd] {
            let f = Ldlt::factor(&a);
            let b = [1.0, -2.0, 0.5, 0.0, 0.0, 0.0];
            let mut x = b;
            f.solve_in_place(&mut x);
            let r = mul(&a, &x);
            for i in 0..3 {
                assert!((r[i] - b[i]).abs() < 1e-14, "residual {i}: {}", r[i] - b[i]);
            }
        }
    }

    #[test]
    fn a_vanishing_pivot_takes_no_impulse() {
        // Rank 1: the second direction is degenerate and must come out zero, not infinite.
        let a = block(&[&[1.0, 1.0], &[1.0, 1.0]]);
        let mut x = [2.0, 2.0, 0.0, 0.0, 0.0, 0.0];
        Ldlt::factor(&a).solve_in_place(&mut x);
        assert!(x.iter().all(|v| v.is_finite()));
        assert_eq!(x[1], 0.0);
        assert!((x[0] - 2.0).abs() < 1e-15);
    }
}
